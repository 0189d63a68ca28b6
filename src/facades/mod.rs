//! Facades stage: a [`FacadeSource`] (CMP-layout files) + floor height → [`FacadeSet`]
//! (paper 3.2).
//!
//! Per facade: decode the photo and its CMP XML boxes; crop below the first (topmost)
//! molding, or keep the whole photo when it has no molding; take the floors from the side
//! file, else estimate them from the rows of window boxes (see `window_rows`); size the
//! building `floors × floor_height` tall and `cw / ch` times that wide (cw × ch the cropped
//! pixels); match a roof by the molding's mean colour (see `roof_set`).
//!
//! Bad facade data (missing XML, unreadable photo, bad XML, no window boxes and no floors
//! entry, a crop that leaves nothing) stops the stage with an error naming the file, or with
//! [`OnError::Skip`] leaves the facade out with a warning ([`Diagnostic`]). A bad floors-file line is
//! always an error. So is an empty result.
//!
//! Facades are processed in parallel into index-addressed slots; errors and warnings are
//! reported in file order, so the result is the same for any number of threads.
//!
//! [`builtin`] is cityspec's own set, generated in the same CMP layout and loaded by the
//! same code.

/// Bump when the builtin set's bytes change: part of the facades stage's cache key.
pub const BUILTIN_VERSION: u32 = 4;
/// Bump when [`process`]'s output changes for the same input.
pub const VERSION: u32 = 3;

mod builtin;
mod cmp_box;
mod cmp_label;
mod crop;
mod facade_error;
mod facade_source;
mod floors_file;
mod roof_set;
mod window_rows;

#[cfg(test)]
mod tests;

use rayon::prelude::*;

use crate::model::{Facade, FacadeSet, Roof};
use crate::spec::OnError;

pub use builtin::builtin;
pub use cmp_box::{CmpBox, parse_cmp_xml, write_cmp_xml};
pub use cmp_label::CmpLabel;
pub use facade_error::FacadeError;

use crate::diagnostic::Diagnostic;
pub use facade_source::{FacadeFile, FacadeSource, Photo};
pub use floors_file::FloorsFile;
pub use roof_set::{builtin_roofs, nearest_roof};

/// The facades stage. See the module docs for the steps and the error policy.
pub fn process(
    source: &FacadeSource,
    floor_height: f64,
    on_error: OnError,
) -> Result<(FacadeSet, Vec<Diagnostic>), FacadeError> {
    let side = match &source.floors {
        Some(text) => FloorsFile::parse(text, &source.origin)?,
        None => FloorsFile::default(),
    };
    let roofs = builtin_roofs();
    let results: Vec<_> = source
        .files
        .par_iter()
        .map(|file| {
            let floors = side.floors.get(&file.name).copied();
            let facade = crop::crop_facade(source, file, floors, floor_height, &roofs);
            (file.name.clone(), facade)
        })
        .collect();

    let mut warnings = Vec::new();
    for name in side.floors.keys() {
        if !source.files.iter().any(|f| &f.name == name) {
            let message = format!(
                "{}: floors file (facades.floors) lists `{name}`, which has no photo",
                source.origin
            );
            warnings
                .push(Diagnostic::warning("facade-floors-unmatched", message).at("facades.floors"));
        }
    }
    gather(&source.origin, results, roofs, on_error, warnings)
}

/// [`process`] of [`builtin`], each facade painted and processed in one task: no wait
/// for the whole set to be painted before the first is cropped and encoded.
pub fn process_builtin(
    floor_height: f64,
    on_error: OnError,
) -> Result<(FacadeSet, Vec<Diagnostic>), FacadeError> {
    let source = builtin::source_without_files();
    let roofs = builtin_roofs();
    let results: Vec<_> = (0..builtin::COUNT)
        .into_par_iter()
        .map(|i| {
            let file = builtin::facade_file(i);
            let facade = crop::crop_facade(&source, &file, None, floor_height, &roofs);
            (file.name, facade)
        })
        .collect();
    gather(&source.origin, results, roofs, on_error, Vec::new())
}

/// The set from each file's result, in file order, as `on_error` says; `warnings` are the
/// source's own so far.
fn gather(
    origin: &str,
    results: Vec<(String, Result<Facade, FacadeError>)>,
    roofs: Vec<Roof>,
    on_error: OnError,
    mut warnings: Vec<Diagnostic>,
) -> Result<(FacadeSet, Vec<Diagnostic>), FacadeError> {
    let found = results.len();
    let mut facades = Vec::new();
    let mut skipped = 0;
    for (name, result) in results {
        match (result, on_error) {
            (Ok(facade), _) => facades.push(facade),
            (Err(error), OnError::Error) => return Err(error),
            (Err(error), OnError::Skip) => {
                skipped += 1;
                let message = format!("skipped facade {name}: {error}");
                warnings
                    .push(Diagnostic::warning("facade-skipped", message).at("facades.on_error"));
            }
        }
    }
    if facades.is_empty() {
        return Err(FacadeError::Empty {
            origin: origin.to_owned(),
            found,
            skipped,
        });
    }
    Ok((FacadeSet { facades, roofs }, warnings))
}

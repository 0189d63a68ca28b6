//! FacadeError: why a facade set, or one facade of it, could not be used.

use thiserror::Error;

/// Why the facades stage failed. Every message names the file (`origin/name.ext`) and says
/// what is wrong with it.
#[derive(Debug, Error)]
pub enum FacadeError {
    /// The photo has no `<name>.xml` beside it.
    #[error("{file}: missing; every facade photo needs its CMP XML boxes beside it")]
    MissingXml { file: String },
    /// The XML is not CMP XML.
    #[error("{file}: {message}")]
    BadXml { file: String, message: String },
    /// The photo could not be decoded.
    #[error("{file}: not a readable image: {source}")]
    BadImage {
        file: String,
        #[source]
        source: image::ImageError,
    },
    /// The photo file is cut short.
    #[error("{file}: not a whole image: found {why}")]
    Truncated { file: String, why: String },
    /// The photo is empty or too large to decode safely.
    #[error("{file}: the photo is {width}×{height} px; 8 to {max_side} px a side are accepted")]
    BadSize {
        file: String,
        width: u32,
        height: u32,
        max_side: u32,
    },
    /// The first molding lies at the very bottom, so cropping below it leaves nothing.
    #[error("{file}: the first molding ends at row {row} of {height}; nothing is left below it")]
    EmptyCrop { file: String, row: u32, height: u32 },
    /// Floors cannot be estimated and the floors file does not give them.
    #[error(
        "{file}: no window boxes below the first molding, so the floors cannot be estimated; \
         give them in the floors file (facades.floors) or annotate the windows"
    )]
    NoWindows { file: String },
    /// A line of the floors side file is not `name floors`.
    #[error("{origin}: floors file (facades.floors), line {line}: {message}")]
    BadFloorsLine {
        origin: String,
        line: usize,
        message: String,
    },
    /// No facade is left to build with.
    #[error("{origin}: no usable facades ({found} found, {skipped} skipped for bad data)")]
    Empty {
        origin: String,
        found: usize,
        skipped: usize,
    },
}

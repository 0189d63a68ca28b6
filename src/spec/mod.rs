//! Spec stage: TOML text (+ the world's image headers) → validated [`Spec`], or every
//! problem of the file at once as [`SpecErrors`].
//!
//! [`load`] runs four passes, each pointing its findings at source text with a key path:
//!
//! | pass | checks | stops the pipeline? |
//! |---|---|---|
//! | syntax | the file is TOML (one diagnostic) | yes |
//! | version | `version` is one this cityspec reads | yes: other versions mean other keys |
//! | schema | the committed `schemas/cityspec.schema.json`, via a JSON-schema validator | yes, after reporting all |
//! | semantic | rules between values: one layout source, roads that fit, the image and models exist, one of a camera's `frames` and `spacing`, … | no |
//!
//! Then serde builds the [`Spec`] (defaults filled in). The only I/O is through
//! [`SpecWorld`], so the stage stays pure; [`FsWorld`] is the file-system world, which the
//! build driver wraps with the parse stage's reading of a layout image (a layout image
//! nothing can be read off is refused here, with the spec's other errors). Relative paths
//! in a spec resolve against the spec's own folder.

mod camera_checks;
mod camera_path_checks;
mod camera_spec;
mod class_checks;
mod closest;
mod cost_checks;
mod diagnostic;
mod findings;
mod fs_world;
mod input_file;
mod key_path;
mod layout_checks;
mod lighting_spec;
mod limits_spec;
mod locator;
mod object_checks;
mod object_spec;
mod output_spec;
mod report;
mod schema_check;
mod sensor_ranges;
mod sensor_spec;
#[allow(clippy::module_inception)]
mod spec;
mod spec_errors;
mod splits_spec;
mod toml_json;
mod value_checks;
mod value_range;
mod weather_spec;

use std::path::{Path, PathBuf};

use toml::de::{DeTable, DeValue};

pub use camera_spec::{
    AnnotationsSpec, CameraPath, CameraSpec, DEFAULT_FRAMES, DepthFormat, FrameRule, MAX_FRAMES,
};
pub use class_checks::produced_classes;
pub use cost_checks::{CostEstimate, MAX_INSTANCE_ID};
pub use diagnostic::Diagnostic;
pub use fs_world::FsWorld;
pub use input_file::{
    InputFileError, MAX_FLOORS_BYTES, MAX_IMAGE_BYTES, MAX_MODEL_BYTES, MAX_MTL_BYTES,
    MAX_SPEC_BYTES, MAX_TEXTURE_BYTES, check_file, open_capped, read_capped, read_text_capped,
};
pub use layout_checks::{MAX_LAYOUT_PIXELS, MAX_LAYOUT_SIDE};
pub use lighting_spec::{LightingSpec, Span, TimeOfDay, TimePreset, Vary};
pub use limits_spec::LimitsSpec;
pub use object_spec::{
    CarBody, Ground, KIND_KEYS, ObjectKind, ObjectSpec, RIDER_CLASS, SignKind, TextCase,
    TreeSpecies, kinds_of_key,
};
pub use output_spec::{OutputLayout, OutputSpec};
pub use report::report;
pub use sensor_spec::{ExposureMode, SensorSpec};
pub use spec::{
    BUILTIN_FACADES, BuildingsSpec, Color, FacadesSpec, GenerateSpec, LampsSpec, LayoutSpec,
    OnError, Palette, SPEC_VERSION, Spec,
};
pub use spec_errors::SpecErrors;
pub use splits_spec::{SPLIT_NAMES, SplitBy, SplitsSpec};
pub use value_range::ValueRange;
pub use weather_spec::{Weather, WeatherKinds, WeatherSpec};

use findings::Findings;
use key_path::KeyPath;
use locator::Locator;

/// A spec file: its path as the user gave it, and its text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpecSource {
    pub path: PathBuf,
    pub text: String,
}

/// What the spec stage may ask of the outside world.
pub trait SpecWorld {
    /// Width and height of the image at `path` (already resolved against the spec's
    /// folder), read from its header only; Err(message) if missing/unreadable/not an image.
    /// The message completes "expected a PNG or JPEG layout image at …, found {message}".
    fn image_dimensions(&self, path: &Path) -> Result<(u32, u32), String>;
    /// Whether `path` (already resolved) is a folder; Err(message) when it is not.
    fn folder(&self, path: &Path) -> Result<(), String>;
    /// Whether `path` (already resolved) is a readable file; Err(message) when it is not.
    fn file(&self, path: &Path) -> Result<(), String>;
    /// The layout image at `path` (already resolved) decoded, for the checks that need its
    /// pixels: a whole file, drawn in the palette, its block area and road length. None
    /// when this world does not decode images (the checks then use the header's size).
    /// Err(message) completes "expected a whole PNG or JPEG layout image at …, found …".
    fn layout_pixels(&self, _path: &Path) -> Option<Result<image::RgbImage, String>> {
        None
    }
    /// What the parse stage reads off a layout image drawn with `palette`: how many roads
    /// and how many blocks, as `(roads, blocks)`. None when this world does not parse
    /// layouts: the spec stage may not run another stage, so the build driver's world
    /// (`driver::BuildWorld`) answers this, and [`FsWorld`] does not.
    fn parsed_layout(
        &self,
        _pixels: &image::RgbImage,
        _palette: &Palette,
    ) -> Option<(usize, usize)> {
        None
    }
}

/// Syntax → version → schema → serde → semantic; every error of the file at once.
pub fn load(source: &SpecSource, world: &dyn SpecWorld) -> Result<Spec, SpecErrors> {
    let fail = |mut diagnostics: Vec<Diagnostic>| {
        diagnostics.sort_by(|a, b| {
            (a.span.start, a.span.end, &a.key).cmp(&(b.span.start, b.span.end, &b.key))
        });
        diagnostics.dedup();
        SpecErrors {
            path: source.path.clone(),
            text: source.text.clone(),
            diagnostics,
        }
    };
    let text = source.text.as_str();
    let table = match DeTable::parse(text) {
        Ok(table) => table.into_inner(),
        Err(error) => return Err(fail(vec![syntax_diagnostic(text, &error)])),
    };
    let locator = Locator::new(table);
    if let Some(diagnostic) = check_version(&locator, text) {
        return Err(fail(vec![diagnostic]));
    }

    let (json, problems) = toml_json::to_json(locator.root());
    let mut diagnostics: Vec<Diagnostic> = problems
        .iter()
        .map(|(path, message)| Diagnostic::new(text, locator.span(path), path, message.clone()))
        .collect();
    let skip: Vec<KeyPath> = problems.into_iter().map(|(path, _)| path).collect();
    diagnostics.extend(schema_check::check(&json, &locator, text, &skip));
    if !diagnostics.is_empty() {
        return Err(fail(diagnostics));
    }

    let mut spec: Spec = match toml::from_str(text) {
        Ok(spec) => spec,
        Err(error) => return Err(fail(vec![serde_diagnostic(text, &locator, &error)])),
    };
    object_spec::fill_default_labels(&mut spec.objects);

    let mut findings = Findings::new(&locator, text);
    let extent = layout_checks::check_layout(&spec.layout, &source.path, world, &mut findings);
    value_checks::check_palette(&spec.layout.palette, &mut findings);
    value_checks::check_buildings(&spec.buildings, &mut findings);
    value_checks::check_facades(&spec.facades, &source.path, world, &mut findings);
    value_checks::check_lamps(&spec.lamps, &mut findings);
    object_checks::check_objects(&spec.objects, &source.path, world, &mut findings);
    camera_checks::check_cameras(&spec.cameras, &mut findings);
    camera_path_checks::check_camera_paths(&spec.cameras, &spec.objects, &mut findings);
    class_checks::check_classes(&spec, &mut findings);
    if let Some(extent) = extent {
        cost_checks::check_costs(&spec, extent, &mut findings);
    }
    lighting_spec::check_lighting(&spec.lighting, &mut findings);
    splits_spec::check_splits(
        spec.splits.as_ref(),
        spec.cameras.len(),
        spec.output.layout == OutputLayout::Webdataset,
        &mut findings,
    );
    let diagnostics = findings.into_diagnostics();
    if diagnostics.is_empty() {
        Ok(spec)
    } else {
        Err(fail(diagnostics))
    }
}

/// `spec_path`'s folder joined with `relative` (relative paths resolve against the spec's
/// folder; absolute ones stay as they are).
pub fn resolve(spec_path: &Path, relative: &str) -> PathBuf {
    match spec_path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder.join(relative),
        _ => PathBuf::from(relative),
    }
}

/// The 1-based line and column of the key `key` (a dotted path such as
/// `objects[2].count`) in the spec text, or of its nearest written ancestor; `None` when the
/// text does not parse. The CLI places a build's diagnostics with it.
pub fn key_position(text: &str, key: &str) -> Option<(usize, usize)> {
    let table = DeTable::parse(text).ok()?;
    let locator = Locator::new(table.into_inner());
    let span = locator.key_span(&key_path::KeyPath::parse(key));
    let at = Diagnostic::new(text, span, key, "");
    Some((at.line, at.column))
}

/// The schema generated from the types (pretty JSON text, trailing newline) — what
/// `cityspec schema` prints and what is committed at schemas/cityspec.schema.json.
pub fn schema_json() -> String {
    let generator = schemars::generate::SchemaSettings::draft2020_12().into_generator();
    let schema = generator.into_root_schema_for::<Spec>();
    let mut text = serde_json::to_string_pretty(&schema)
        .unwrap_or_else(|e| format!("{{\"error\": {:?}}}", e.to_string()));
    text.push('\n');
    text
}

/// A TOML syntax error, keyed by the innermost key written before it on its line, or by
/// the key it repeats.
fn syntax_diagnostic(text: &str, error: &toml::de::Error) -> Diagnostic {
    let span = error.span().unwrap_or(0..0);
    let (partial, _) = DeTable::parse_recoverable(text);
    let partial = Locator::new(partial.into_inner());
    // The error often sits just past the value it breaks (an unclosed string ends at the
    // line's end), so look back along its line for the key being written.
    let start = span.start.min(text.len());
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let key = (line_start..=start)
        .rev()
        .map(|offset| partial.path_at(offset))
        .find(|path| {
            !path.0.is_empty() && (line_start..=start).contains(&partial.key_span(path).start)
        })
        // A duplicate key's span is the repeated key itself; name it by its first use.
        .or_else(|| {
            let repeated = text.get(span.clone()).unwrap_or_default();
            partial.last_key_before(repeated, span.start)
        })
        .map_or_else(|| "(toml)".to_string(), |path| path.to_string());
    Diagnostic::new(
        text,
        span,
        key,
        format!("invalid TOML: {}", error.message().trim_end()),
    )
}

/// `version` must be one this cityspec reads; anything else is checked by the schema.
fn check_version(locator: &Locator<'_>, text: &str) -> Option<Diagnostic> {
    let path = KeyPath::root().key("version");
    let value = locator.value(&path)?;
    let DeValue::Integer(found) = value.get_ref() else {
        return None;
    };
    if i64::from_str_radix(found.as_str(), found.radix()) == Ok(i64::from(SPEC_VERSION)) {
        return None;
    }
    Some(Diagnostic::new(
        text,
        value.span(),
        path,
        format!(
            "unsupported spec version: this cityspec reads version {SPEC_VERSION}, found \
             {found}; use a cityspec that reads version {found}, or rewrite the spec for \
             version {SPEC_VERSION}"
        ),
    ))
}

/// A serde error after the schema passed (a float where an integer belongs, or a schema
/// out of step with the types): never a panic, always a pointed diagnostic.
fn serde_diagnostic(text: &str, locator: &Locator<'_>, error: &toml::de::Error) -> Diagnostic {
    let span = error.span().unwrap_or(0..0);
    let path = locator.path_at(span.start);
    let message = match locator.value(&path).map(|v| v.get_ref()) {
        Some(DeValue::Float(f)) if error.message().contains("expected u") => {
            format!("expected an integer, found a float {f}")
        }
        _ => format!(
            "expected a valid value, found: {}",
            error.message().trim_end()
        ),
    };
    Diagnostic::new(text, span, path, message)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::FakeWorld;

    fn report(text: &str) -> String {
        let source = SpecSource {
            path: PathBuf::from("c.toml"),
            text: text.to_string(),
        };
        match load(&source, &FakeWorld::empty()) {
            Ok(_) => String::new(),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn each_pass_stops_the_later_ones() {
        let cases = [
            // Syntax: one diagnostic, nothing else looked at.
            (
                "version = 3\nsede = 1\nname = 'a\n",
                "c.toml:3:10: error: name: invalid TOML: invalid literal string, expected `'`",
            ),
            // Version: other versions have other keys, so nothing else is reported.
            (
                "version = 0\nsede = 1\n",
                "c.toml:1:11: error: version: unsupported spec version: this cityspec reads \
                 version 1, found 0; use a cityspec that reads version 0, or rewrite the spec \
                 for version 1",
            ),
            // Schema: the road width is out of range; the duplicate widths wait.
            (
                "version = 1\nname = 'a'\n[layout.generate]\nroad_width = 300\n\
                 [buildings]\nwidths = [5, 5]\n",
                "c.toml:4:14: error: layout.generate.road_width: expected an integer at most \
                 256, found 300",
            ),
        ];
        for (text, want) in cases {
            assert_eq!(report(text), want, "{text}");
        }
    }

    #[test]
    fn diagnostics_come_in_source_order() {
        let got = report(
            "version = 1\nname = 'a'\n[lamps]\nspacing = 0\n[layout]\nmirror = [9]\n\
             [layout.generate]\nwidth = 1\n",
        );
        let lines: Vec<&str> = got
            .lines()
            .map(|l| l.split(": error").next().unwrap())
            .collect();
        assert_eq!(lines, ["c.toml:4:11", "c.toml:6:11", "c.toml:8:9"], "{got}");
    }

    #[test]
    fn serde_errors_become_pointed_diagnostics() {
        let text = "version = 1\nname = 'a'\n[layout.generate]\nwidth = 512.0\n";
        let table = DeTable::parse(text).unwrap().into_inner();
        let locator = Locator::new(table);
        let error = toml::from_str::<Spec>(text).unwrap_err();
        let d = serde_diagnostic(text, &locator, &error);
        assert_eq!((d.line, d.column), (4, 9));
        assert_eq!(d.key, "layout.generate.width");
        assert_eq!(d.message, "expected an integer, found a float 512.0");
    }

    #[test]
    fn schema_json_is_pretty_and_ends_with_a_newline() {
        let text = schema_json();
        assert!(
            text.starts_with("{\n  \"$schema\": \"https://json-schema.org/draft/2020-12/schema\"")
        );
        assert!(text.ends_with("}\n"));
        let schema: serde_json::Value = serde_json::from_str(&text).unwrap();
        // Optional sources are plain references, not `anyOf [T, null]`: TOML has no null,
        // and a plain reference gives plain error messages.
        assert_eq!(
            schema["$defs"]["LayoutSpec"]["properties"]["generate"]["$ref"],
            "#/$defs/GenerateSpec"
        );
        assert_eq!(
            schema["$defs"]["LayoutSpec"]["properties"]["image"]["type"],
            "string"
        );
    }
}

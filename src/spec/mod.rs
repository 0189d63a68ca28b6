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
mod lidar_spec;
mod lighting_spec;
mod limits_spec;
mod locator;
mod map_checks;
mod merge;
mod object_checks;
mod object_spec;
mod output_spec;
mod report;
mod schema_check;
mod sensor_ranges;
mod sensor_spec;
mod sources;
#[allow(clippy::module_inception)]
mod spec;
mod spec_errors;
mod splits_spec;
mod toml_json;
mod traffic_spec;
mod value_checks;
mod value_range;
mod weather_spec;

use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;
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
pub use lidar_spec::LidarSpec;
pub use lighting_spec::{LightingSpec, Span, TimeOfDay, TimePreset, Vary};
pub use limits_spec::LimitsSpec;
pub use object_spec::{
    CarBody, EntryKind, Ground, KIND_KEYS, ObjectSpec, RIDER_CLASS, SignGroup, SignKind, TextCase,
    TreeSpecies, kinds_of_key,
};
pub use output_spec::{OutputLayout, OutputSpec};
pub use report::report;
pub use sensor_spec::{ExposureMode, SensorSpec};
pub use spec::{
    BUILTIN_FACADES, BuildingsSpec, Color, FacadesSpec, GenerateSpec, LampsSpec, LayoutSpec,
    OnError, OsmLayoutSpec, Palette, SPEC_VERSION, Spec,
};
pub use spec_errors::SpecErrors;
pub use splits_spec::{SPLIT_NAMES, SplitBy, SplitsSpec};
pub use traffic_spec::TrafficSpec;
pub use value_range::ValueRange;
pub use weather_spec::{Weather, WeatherKinds, WeatherSpec};

use findings::Findings;
use key_path::KeyPath;
use locator::Locator;
pub use sources::SET_FILE;
use sources::Sources;

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
    /// The text of the spec file at `path` (already resolved) that a spec `extends`;
    /// Err(message) completes "expected a spec file to extend at …, found {message}".
    fn spec_text(&self, path: &Path) -> Result<String, String>;
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
    load_with(source, &[], world)
}

/// [`load`], with `sets` (TOML documents, one per `--set`) merged last, in order.
/// A spec that `extends` a base is merged onto it first (see `spec/merge.rs` for the rules), so
/// every pass sees the merged document, and each diagnostic names the file that wrote it.
pub fn load_with(
    source: &SpecSource,
    sets: &[String],
    world: &dyn SpecWorld,
) -> Result<Spec, SpecErrors> {
    let errors = |sources: &Sources, diagnostics: Vec<Diagnostic>| SpecErrors {
        path: source.path.clone(),
        text: source.text.clone(),
        files: sources.texts(),
        diagnostics,
    };
    let sources = match Sources::read(source, sets, world) {
        Ok(sources) => sources,
        Err((sources, diagnostics)) => return Err(errors(&sources, diagnostics)),
    };
    let fail = |mut diagnostics: Vec<Diagnostic>| {
        diagnostics.sort_by(|a, b| {
            (a.span.start, a.span.end, &a.key).cmp(&(b.span.start, b.span.end, &b.key))
        });
        diagnostics.dedup();
        let diagnostics = diagnostics
            .into_iter()
            .map(|d| sources.localize(d))
            .collect();
        errors(&sources, diagnostics)
    };
    let text = sources.combined.as_str();
    let (table, merge_problems) = sources.tree();
    if !merge_problems.is_empty() {
        return Err(fail(
            merge_problems
                .into_iter()
                .map(|(span, key, message)| Diagnostic::new(text, span, key, message))
                .collect(),
        ));
    }
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

    let whole = Spanned::new(0..text.len(), locator.root().clone());
    let mut spec: Spec = match Spec::deserialize(toml::de::Deserializer::from(whole)) {
        Ok(spec) => spec,
        Err(error) => return Err(fail(vec![serde_diagnostic(text, &locator, &error)])),
    };
    object_spec::fill_default_labels(&mut spec.objects);

    let mut findings = Findings::new(&locator, text);
    check_values(&spec, &source.path, world, &mut findings);
    let diagnostics = findings.into_diagnostics();
    if diagnostics.is_empty() {
        Ok(spec)
    } else {
        Err(fail(diagnostics))
    }
}

/// The checks of a deserialized spec's values, each finding placed at its key.
fn check_values(spec: &Spec, path: &Path, world: &dyn SpecWorld, findings: &mut Findings) {
    let extent = layout_checks::check_layout(&spec.layout, path, world, findings);
    map_checks::check_map(spec, path, world, findings);
    value_checks::check_palette(&spec.layout.palette, findings);
    value_checks::check_buildings(&spec.buildings, findings);
    value_checks::check_facades(&spec.facades, path, world, findings);
    value_checks::check_lamps(&spec.lamps, findings);
    object_checks::check_objects(&spec.objects, path, world, findings);
    camera_checks::check_cameras(&spec.cameras, findings);
    camera_path_checks::check_camera_paths(&spec.cameras, &spec.objects, findings);
    class_checks::check_classes(spec, findings);
    if let Some(extent) = extent {
        cost_checks::check_costs(spec, extent, findings);
    }
    lighting_spec::check_lighting(&spec.lighting, "lighting", findings);
    for (i, camera) in spec.cameras.iter().enumerate() {
        if let Some(lighting) = &camera.lighting {
            lighting_spec::check_lighting(lighting, &format!("cameras[{i}].lighting"), findings);
        }
    }
    splits_spec::check_splits(spec.splits.as_ref(), spec.cameras.len(), findings);
    traffic_spec::check_traffic(spec.traffic.as_ref(), findings);
}

/// `spec_path`'s folder joined with `relative` (relative paths resolve against the spec's
/// folder; absolute ones stay as they are).
pub fn resolve(spec_path: &Path, relative: &str) -> PathBuf {
    match spec_path.parent() {
        Some(folder) if !folder.as_os_str().is_empty() => folder.join(relative),
        _ => PathBuf::from(relative),
    }
}

/// Where each of `keys` (dotted paths such as `objects[2].count`) was written, or its
/// nearest written ancestor: `(file, line, column)`, 1-based, in the spec at `path` or in
/// a base it extends (read through `world`); `None` when the spec does not load that far.
/// The CLI places a build's warnings with it.
pub fn key_places(
    path: &Path,
    keys: &[&str],
    world: &dyn SpecWorld,
) -> Option<Vec<(PathBuf, usize, usize)>> {
    let source = SpecSource {
        path: path.to_path_buf(),
        text: world.spec_text(path).ok()?,
    };
    let sources = Sources::read(&source, &[], world).ok()?;
    let (table, _) = sources.tree();
    let locator = Locator::new(table);
    let places = keys
        .iter()
        .map(|key| {
            let span = locator.key_span(&KeyPath::parse(key));
            let at = sources.localize(Diagnostic::new(&sources.combined, span, key, ""));
            (
                at.file.unwrap_or_else(|| path.to_path_buf()),
                at.line,
                at.column,
            )
        })
        .collect();
    Some(places)
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
pub(crate) fn syntax_diagnostic(text: &str, error: &toml::de::Error) -> Diagnostic {
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

    const BASE: &str = "version = 1\nname = 'base'\nseed = 3\n[layout.generate]\nwidth = 512\n\
                        [[cameras]]\nname = 'a'\nframes = 2\n[[cameras]]\nname = 'b'\nframes = 3\n";

    fn load_child(child: &str) -> Result<Spec, SpecErrors> {
        let world = FakeWorld::empty().with_spec("specs/base.toml", BASE);
        let source = SpecSource {
            path: PathBuf::from("specs/child.toml"),
            text: child.to_string(),
        };
        load(&source, &world)
    }

    #[test]
    fn a_child_is_merged_onto_its_base_before_it_is_checked() {
        let child = "extends = 'base.toml'\nname = 'child'\n[[cameras]]\nname = 'b'\n\
                     frames = 5\n[[cameras]]\nname = 'a'\nremove = true\n";
        let spec = load_child(child).unwrap();
        let base = FakeWorld::empty()
            .load("specs/base.toml", BASE.to_string())
            .unwrap();
        assert_eq!((spec.name.as_str(), spec.seed), ("child", base.seed));
        assert_eq!(spec.layout, base.layout);
        let cameras: Vec<(&str, u32)> = spec
            .cameras
            .iter()
            .map(|c| (c.name.as_str(), c.frames.unwrap_or_default()))
            .collect();
        assert_eq!(cameras, [("b", 5)]);
    }

    #[test]
    fn errors_name_the_file_and_line_that_wrote_the_value() {
        // The bad value in the child: the child's line.
        let got = load_child("extends = 'base.toml'\n[layout.generate]\nroad_width = 300\n")
            .unwrap_err()
            .to_string();
        assert_eq!(
            got,
            "specs/child.toml:3:14: error: layout.generate.road_width: expected an integer at \
             most 256, found 300"
        );
        // The bad value in the base, overriding nothing: the base's line.
        let world = FakeWorld::empty().with_spec(
            "specs/base.toml",
            &BASE.replace("width = 512", "width = 512\nroad_width = 300"),
        );
        let source = SpecSource {
            path: PathBuf::from("specs/child.toml"),
            text: "extends = 'base.toml'\nseed = 4\n".to_string(),
        };
        let errors = load(&source, &world).unwrap_err();
        assert_eq!(
            errors.to_string(),
            "specs/base.toml:6:14: error: layout.generate.road_width: expected an integer at \
             most 256, found 300"
        );
        let rendered = report::report(&errors, false);
        assert!(rendered.contains("specs/base.toml:6:14"), "{rendered}");
        assert!(rendered.contains("road_width = 300"), "{rendered}");
        // The child's value replaces the base's bad one: no error at all.
        let source = SpecSource {
            path: PathBuf::from("specs/child.toml"),
            text: "extends = 'base.toml'\n[layout.generate]\nroad_width = 30\n".to_string(),
        };
        assert!(load(&source, &world).is_ok());
    }

    #[test]
    fn bad_bases_are_refused_at_extends() {
        let cases = [
            (
                "extends = 'gone.toml'\n",
                "specs/child.toml:1:11: error: extends: expected a spec file to extend at \
                 specs/gone.toml (\"gone.toml\" from this spec's folder), found no such file",
            ),
            (
                "extends = 3\n",
                "specs/child.toml:1:11: error: extends: expected the path of a spec file to \
                 extend, found an integer 3",
            ),
            (
                "extends = './x/../child.toml'\n",
                "specs/child.toml:1:11: error: extends: expected a base that does not extend \
                 this spec again, found a cycle: specs/child.toml → specs/child.toml",
            ),
            (
                "extends = 'base.toml'\n[[cameras]]\nname = 'c'\nremove = true\n",
                "specs/child.toml:4:10: error: cameras[0].remove: expected the name of an \
                 entry of the base's `cameras` to remove, found \"c\", which the base does not \
                 have",
            ),
        ];
        for (child, want) in cases {
            assert_eq!(load_child(child).unwrap_err().to_string(), want, "{child}");
        }
    }

    #[test]
    fn a_cycle_through_bases_names_every_file() {
        let world = FakeWorld::empty()
            .with_spec("specs/a.toml", "extends = 'b.toml'\n")
            .with_spec("specs/b.toml", "version = 1\nextends = 'a.toml'\n");
        let source = SpecSource {
            path: PathBuf::from("specs/a.toml"),
            text: "extends = 'b.toml'\n".to_string(),
        };
        assert_eq!(
            load(&source, &world).unwrap_err().to_string(),
            "specs/b.toml:2:11: error: extends: expected a base that does not extend this spec \
             again, found a cycle: specs/a.toml → specs/b.toml → specs/a.toml"
        );
    }

    fn load_set(sets: &[&str]) -> Result<Spec, String> {
        let world = FakeWorld::empty().with_spec("specs/base.toml", BASE);
        let source = SpecSource {
            path: PathBuf::from("specs/child.toml"),
            text: "extends = 'base.toml'\n".to_string(),
        };
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        load_with(&source, &sets, &world).map_err(|e| e.to_string())
    }

    #[test]
    fn sets_apply_after_extends_by_key_path_and_entry_name() {
        let spec = load_set(&[
            "cameras.b.frames=7",
            "seed = 11",
            "name=plain_words",
            "layout.generate.road_width=40",
        ])
        .unwrap();
        assert_eq!(spec.cameras[1].name, "b");
        assert_eq!(spec.cameras[1].frames, Some(7));
        assert_eq!(spec.cameras[0].frames, Some(2));
        assert_eq!(spec.seed, 11);
        assert_eq!(spec.name, "plain_words");
        assert_eq!(spec.layout.generate.unwrap().road_width, 40);
        // A later --set wins over an earlier one.
        assert_eq!(load_set(&["seed=1", "seed=2"]).unwrap().seed, 2);
    }

    #[test]
    fn a_cameras_own_lighting_is_checked_at_its_own_key() {
        let got = load_set(&["cameras.b.lighting={ sun_elevation = 10 }"]).unwrap_err();
        assert!(
            got.starts_with("--set:1:") && got.contains(": cameras[1].lighting.sun_elevation: "),
            "{got}"
        );
        let spec = load_set(&["cameras.b.weather.kind=\"fog\""]).unwrap();
        assert!(spec.cameras[0].weather.is_none());
        assert_eq!(
            spec.cameras[1].weather.as_ref().map(|w| w.kind.clone()),
            Some(load_set(&["weather.kind=\"fog\""]).unwrap().weather.kind)
        );
    }

    #[test]
    fn bad_sets_are_errors_at_the_set_line() {
        let cases: [(&[&str], &str); 4] = [
            (
                &["seed=1", "cameras.b.framez=4"],
                "--set:2:1: error: cameras[1].framez: expected one of `name`, `path`, `frames`",
            ),
            (
                &["cameras.c.frames=4"],
                "--set:1:1: error: cameras: expected the name of an entry of `cameras` \
                 (`--set cameras.NAME.key=value`), found \"c\", which no entry is named",
            ),
            (
                &["seed"],
                "--set:1:1: error: : expected `--set key.path=value`, found \"seed\"",
            ),
            (
                &["seed.x=1"],
                "--set:1:1: error: seed: expected a table at `seed` to set a key in, found an \
                 integer 3",
            ),
        ];
        for (sets, want) in cases {
            let got = load_set(sets).unwrap_err();
            assert!(got.starts_with(want), "{sets:?}: {got}");
        }
        let unknown = load_set(&["cameras.b.framez=4"]).unwrap_err();
        assert!(unknown.ends_with("(did you mean `frames`?)"), "{unknown}");
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

//! Object checks: schema-valid `[[objects]]` tables → the problems between values (ranges
//! written high-to-low, a mesh class without its model, a model or word file that is not
//! there).

use std::fmt::Display;
use std::path::Path;

use super::class_checks::SCENE_CLASSES;
use super::findings::Findings;
use super::object_spec::{EntryKind, ObjectSpec};
use super::{SpecWorld, resolve};

/// Every object class's ranges run low to high; a mesh class names a readable model file.
pub(crate) fn check_objects(
    objects: &[ObjectSpec],
    spec_path: &Path,
    world: &dyn SpecWorld,
    findings: &mut Findings<'_, '_>,
) {
    for (i, object) in objects.iter().enumerate() {
        let key = |name: &str| format!("objects[{i}].{name}");
        match object.kind {
            EntryKind::Text | EntryKind::StreetName => {
                check_range(&key("letter_height"), object.letter_height, findings);
                check_range(&key("words"), object.words, findings);
                if let Some(words) = &object.words_file {
                    let file = resolve(spec_path, words);
                    if let Err(problem) = world.file(&file) {
                        findings.error(
                            &key("words_file"),
                            format!(
                                "expected a word file at {}, found {problem}",
                                file.display()
                            ),
                        );
                    }
                }
            }
            EntryKind::Sign => {}
            EntryKind::Car | EntryKind::TrafficLight => {}
            EntryKind::Tree | EntryKind::Person | EntryKind::Bicycle => {
                check_heights(object, &key("height"), findings);
            }
            EntryKind::Mesh if object.label.is_empty() => findings.error(
                &format!("objects[{i}]"),
                "expected a `label` for an object of kind \"mesh\" (its annotation \
                 category), found none",
            ),
            EntryKind::Mesh => check_mesh(object, i, spec_path, world, findings),
        }
    }
}

/// A tree's, person's or rider's height range runs low to high within its kind's bounds.
fn check_heights(object: &ObjectSpec, key: &str, findings: &mut Findings<'_, '_>) {
    let range = object.height_range();
    check_range(key, range, findings);
    if let Some([low, high]) = ObjectSpec::height_bounds(object.kind)
        && (range[0] < low || range[1] > high)
    {
        findings.error(
            key,
            format!(
                "expected heights from {low} to {high} m for a {}, found {:?}",
                match object.kind {
                    EntryKind::Tree => "tree",
                    EntryKind::Bicycle => "bicycle's rider",
                    _ => "person",
                },
                range
            ),
        );
    }
}

/// A labelled mesh entry (`objects[i]`): a label that is no scene class, ranges low to
/// high, a readable model file.
fn check_mesh(
    object: &ObjectSpec,
    i: usize,
    spec_path: &Path,
    world: &dyn SpecWorld,
    findings: &mut Findings<'_, '_>,
) {
    let key = |name: &str| format!("objects[{i}].{name}");
    // Mesh objects are named `<label>_NNNN`: a scene class would clash.
    if SCENE_CLASSES.contains(&object.label.as_str()) {
        findings.error(
            &key("label"),
            format!(
                "expected a label other than the scene's own classes ({}), found {:?}",
                SCENE_CLASSES.join(", "),
                object.label
            ),
        );
    }
    check_range(&key("scale"), object.scale, findings);
    check_range(&key("rotation"), object.rotation, findings);
    match &object.model {
        None => findings.error(
            &format!("objects[{i}]"),
            "expected a `model` (an OBJ file) for an object of kind \"mesh\", found none",
        ),
        Some(model) => {
            let file = resolve(spec_path, model);
            if let Err(problem) = world.file(&file) {
                findings.error(
                    &key("model"),
                    format!(
                        "expected an OBJ model file at {}, found {problem}",
                        file.display()
                    ),
                );
            }
        }
    }
}

fn check_range<T: PartialOrd + Display>(key: &str, range: [T; 2], findings: &mut Findings) {
    if range[0] > range[1] {
        findings.error(
            key,
            format!(
                "expected a range [low, high] with low ≤ high, found [{}, {}]",
                range[0], range[1]
            ),
        );
    }
}

//! Camera path checks: schema-valid `[[cameras]]` and `[[objects]]` tables → the problems
//! of a path's own keys (an objects path without classes, or with a class nothing has).

use super::camera_spec::{CameraPath, CameraSpec};
use super::findings::Findings;
use super::object_spec::ObjectSpec;

/// Scene classes an objects path may aim at besides the `[[objects]]` labels (the ground,
/// roads and sidewalks are everywhere, so "aiming" at them means nothing).
const AIMABLE_SCENE_CLASSES: [&str; 2] = ["building", "lamp"];

/// A timed drive's keys: `fps` and `speed_kmh` on a roads path only, `speed_kmh` with
/// `fps`, frames counted (not spaced), and `flow` only on a timed drive.
fn check_timed(camera: &CameraSpec, key: &dyn Fn(&str) -> String, findings: &mut Findings<'_, '_>) {
    if camera.flow && camera.fps.is_none() {
        findings.error(
            &key("flow"),
            "expected `flow` only on a timed drive (a camera with path = \"roads\" and \
             `fps`: its frames are one time step apart), found no `fps`",
        );
    }
    if camera.path != CameraPath::Roads {
        for (name, set) in [
            ("fps", camera.fps.is_some()),
            ("speed_kmh", camera.speed_kmh.is_some()),
        ] {
            if set {
                findings.error(
                    &key(name),
                    format!(
                        "expected `{name}` only on a camera with path = \"roads\" (a timed \
                         drive), found it on another path"
                    ),
                );
            }
        }
    } else if camera.speed_kmh.is_some() && camera.fps.is_none() {
        findings.error(
            &key("speed_kmh"),
            "expected `fps` beside `speed_kmh` (the speed of a timed drive), found no `fps`",
        );
    } else if camera.fps.is_some() && camera.spacing.is_some() {
        findings.error(
            &key("spacing"),
            "expected `frames` for a timed drive (`fps`): its frames are one time step \
             apart, not spaced along the tour; found `spacing`",
        );
    }
}

/// An objects path names at least one class, each one something in the scene, and counts
/// its frames (it has no length for `spacing` to divide); other paths name no classes.
pub(crate) fn check_camera_paths(
    cameras: &[CameraSpec],
    objects: &[ObjectSpec],
    findings: &mut Findings<'_, '_>,
) {
    for (i, camera) in cameras.iter().enumerate() {
        let key = |name: &str| format!("cameras[{i}].{name}");
        check_timed(camera, &key, findings);
        if camera.path != CameraPath::Objects {
            if !camera.classes.is_empty() {
                findings.error(
                    &key("classes"),
                    "expected `classes` only on a camera with path = \"objects\", found it \
                     on another path",
                );
            }
            continue;
        }
        if camera.classes.is_empty() {
            findings.error(
                &format!("cameras[{i}]"),
                "expected `classes` (the classes to aim at) for a camera with path = \
                 \"objects\", found none",
            );
        }
        if camera.spacing.is_some() {
            findings.error(
                &key("spacing"),
                "expected `frames` for a camera with path = \"objects\" (it has no length \
                 to space frames along), found `spacing`",
            );
        }
        for (j, class) in camera.classes.iter().enumerate() {
            let known = AIMABLE_SCENE_CLASSES.contains(&class.as_str())
                || objects.iter().any(|o| &o.label == class);
            if !known {
                let mut labels: Vec<&str> = AIMABLE_SCENE_CLASSES.to_vec();
                labels.extend(objects.iter().map(|o| o.label.as_str()));
                labels.dedup();
                findings.error(
                    &format!("cameras[{i}].classes[{j}]"),
                    format!(
                        "expected a class in the scene ({}), found {class:?}",
                        labels.join(", ")
                    ),
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::test_support::FakeWorld;

    /// The spec's problems as `key: message` (empty when it loads).
    fn problems(body: &str) -> Vec<String> {
        let text = format!(
            "version = 1\nname = \"c\"\n[layout.generate]\n[[objects]]\nkind = \"text\"\n\
             label = \"text\"\n{body}"
        );
        FakeWorld::empty()
            .load("city.toml", text)
            .err()
            .unwrap_or_default()
    }

    #[test]
    fn a_timed_drive_is_a_roads_camera_with_fps_and_frames() {
        let ok = problems("[[cameras]]\nname = \"d\"\nfps = 10\nspeed_kmh = 40\n");
        assert!(ok.is_empty(), "{ok:?}");
        let walk = problems("[[cameras]]\nname = \"w\"\npath = \"sidewalks\"\nfps = 10\n");
        assert!(
            walk.iter()
                .any(|p| p.contains("cameras[0].fps") && p.contains("roads")),
            "{walk:?}"
        );
        assert!(problems("[[cameras]]\nname = \"d\"\nfps = 10\nflow = true\n").is_empty());
        let flow = problems("[[cameras]]\nname = \"d\"\nflow = true\n");
        assert!(
            flow.iter()
                .any(|p| p.contains("cameras[0].flow") && p.contains("fps")),
            "{flow:?}"
        );
        let bare = problems("[[cameras]]\nname = \"d\"\nspeed_kmh = 40\n");
        assert!(
            bare.iter()
                .any(|p| p.contains("cameras[0].speed_kmh") && p.contains("fps")),
            "{bare:?}"
        );
        let spaced = problems("[[cameras]]\nname = \"d\"\nfps = 10\nspacing = 5\n");
        assert!(
            spaced.iter().any(|p| p.contains("cameras[0].spacing")),
            "{spaced:?}"
        );
        let fast = problems("[[cameras]]\nname = \"d\"\nfps = 1000\n");
        assert!(
            fast.iter().any(|p| p.contains("cameras[0].fps")),
            "{fast:?}"
        );
    }

    #[test]
    fn objects_paths_name_classes_in_the_scene() {
        let cases: &[(&str, &[&str])] = &[
            (
                "[[cameras]]\nname = \"a\"\npath = \"objects\"\nclasses = [\"text\", \"lamp\"]\n",
                &[],
            ),
            (
                "[[cameras]]\nname = \"a\"\npath = \"objects\"\n",
                &[
                    "cameras[0]: expected `classes` (the classes to aim at) for a camera with \
                   path = \"objects\", found none",
                ],
            ),
            (
                "[[cameras]]\nname = \"a\"\npath = \"objects\"\nclasses = [\"car\"]\n",
                &[
                    "cameras[0].classes[0]: expected a class in the scene (building, lamp, \
                   text), found \"car\"",
                ],
            ),
            (
                "[[cameras]]\nname = \"a\"\npath = \"objects\"\nclasses = [\"text\"]\n\
                 spacing = 5\n",
                &[
                    "cameras[0].spacing: expected `frames` for a camera with path = \
                   \"objects\" (it has no length to space frames along), found `spacing`",
                ],
            ),
            (
                "[[cameras]]\nname = \"a\"\nclasses = [\"text\"]\n",
                &[
                    "cameras[0].classes: expected `classes` only on a camera with path = \
                   \"objects\", found it on another path",
                ],
            ),
        ];
        for (body, expected) in cases {
            assert_eq!(problems(body), *expected, "{body}");
        }
    }

    #[test]
    fn ranges_are_bounded_by_the_schema() {
        assert!(problems("[[cameras]]\nname = \"a\"\nheading = [-60, 60]\nroll = 3\n").is_empty());
        for bad in [
            "heading = [-200, 0]",
            "pitch = 95",
            "height = [0.1, 2]",
            "roll = [1, 2, 3]",
            "distance = \"far\"",
        ] {
            let found = problems(&format!("[[cameras]]\nname = \"a\"\n{bad}\n"));
            assert_eq!(found.len(), 1, "{bad}: {found:?}");
            let key = bad.split(' ').next().unwrap();
            assert!(
                found[0].starts_with(&format!("cameras[0].{key}")),
                "{found:?}"
            );
        }
    }
}

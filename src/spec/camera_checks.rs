//! Camera checks: schema-valid `[[cameras]]` tables → the problems between values (a path
//! given both a frame count and a frame spacing, two paths with one name).

use super::camera_spec::CameraSpec;
use super::findings::Findings;

/// Each camera gives at most one of `frames` and `spacing`, and has a name of its own: a
/// path writes `frames/<name>/`, so two paths of one name would write the same files.
pub(crate) fn check_cameras(cameras: &[CameraSpec], findings: &mut Findings<'_, '_>) {
    for (i, camera) in cameras.iter().enumerate() {
        if let Some(first) = cameras[..i].iter().position(|c| c.name == camera.name) {
            findings.error(
                &format!("cameras[{i}].name"),
                format!(
                    "expected distinct camera names, found {:?} again (it is also \
                     cameras[{first}].name)",
                    camera.name
                ),
            );
        }
        if let Some(lidar) = &camera.lidar
            && lidar.beams > 1
            && lidar.bottom >= lidar.top
        {
            findings.error(
                &format!("cameras[{i}].lidar.bottom"),
                format!(
                    "expected the bottom beam below the top one (`top` = {}), found \
                     bottom = {}",
                    lidar.top, lidar.bottom
                ),
            );
        }
        if camera.frames.is_some() && camera.spacing.is_some() {
            let line = findings.line_of(&format!("cameras[{i}].frames"));
            findings.error(
                &format!("cameras[{i}].spacing"),
                format!(
                    "expected either `frames` or `spacing`, found both (`frames` is on line \
                     {line})"
                ),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::spec::FrameRule;
    use crate::test_support::FakeWorld;

    /// The spec's first camera's frame rule, or its problems as `key: message`.
    fn rule(cameras: &str) -> Result<FrameRule, Vec<String>> {
        let text = format!("version = 1\nname = \"c\"\n[layout.generate]\n{cameras}");
        FakeWorld::empty()
            .load("city.toml", text)
            .map(|spec| spec.cameras[0].frame_rule())
    }

    #[test]
    fn frames_or_spacing_or_the_default() {
        let cases: &[(&str, Result<FrameRule, &[&str]>)] = &[
            ("[[cameras]]\nname = \"a\"\n", Ok(FrameRule::Count(100))),
            (
                "[[cameras]]\nname = \"a\"\nframes = 7\n",
                Ok(FrameRule::Count(7)),
            ),
            (
                "[[cameras]]\nname = \"a\"\nspacing = 12.5\n",
                Ok(FrameRule::Spacing(12.5)),
            ),
            (
                "[[cameras]]\nname = \"a\"\npath = \"orbit\"\nspacing = 3\n",
                Ok(FrameRule::Spacing(3.0)),
            ),
            (
                "[[cameras]]\nname = \"a\"\nframes = 7\nspacing = 12.5\n",
                Err(&[
                    "cameras[0].spacing: expected either `frames` or `spacing`, found both \
                     (`frames` is on line 6)",
                ]),
            ),
            (
                "[[cameras]]\nname = \"a\"\n[[cameras]]\nname = \"b\"\nspacing = 1\n\
                 frames = 2\n",
                Err(&[
                    "cameras[1].spacing: expected either `frames` or `spacing`, found both \
                     (`frames` is on line 9)",
                ]),
            ),
            (
                "[[cameras]]\nname = \"a\"\n[[cameras]]\nname = \"b\"\n[[cameras]]\n\
                 name = \"a\"\n",
                Err(&[
                    "cameras[2].name: expected distinct camera names, found \"a\" again (it is \
                     also cameras[0].name)",
                ]),
            ),
        ];
        for (cameras, expected) in cases {
            let expected = (*expected)
                .map_err(|problems| problems.iter().map(|p| p.to_string()).collect::<Vec<_>>());
            assert_eq!(rule(cameras), expected, "{cameras}");
        }
    }

    #[test]
    fn a_lidar_has_its_bottom_beam_below_its_top_and_known_keys() {
        let lidar = |body: &str| {
            rule(&format!(
                "[[cameras]]\nname = \"a\"\n[cameras.lidar]\n{body}"
            ))
        };
        assert_eq!(lidar(""), Ok(FrameRule::Count(100)));
        assert_eq!(
            lidar("beams = 1\ntop = -5\nbottom = -5\n"),
            Ok(FrameRule::Count(100))
        );
        assert_eq!(
            lidar("top = -10\nbottom = 5\n"),
            Err(vec![
                "cameras[0].lidar.bottom: expected the bottom beam below the top one \
                 (`top` = -10), found bottom = 5"
                    .to_string()
            ])
        );
        for bad in [
            "beams = 0",
            "columns = 100000",
            "dropout = 1",
            "range = 0",
            "lasers = 3",
        ] {
            let problems = lidar(&format!("{bad}\n")).expect_err(bad);
            assert_eq!(problems.len(), 1, "{bad}: {problems:?}");
            assert!(problems[0].starts_with("cameras[0].lidar"), "{problems:?}");
        }
    }

    #[test]
    fn the_schema_bounds_spacing() {
        for spacing in ["0", "-5", "0.001", "1e9"] {
            let problems = rule(&format!("[[cameras]]\nname = \"a\"\nspacing = {spacing}\n"))
                .expect_err(spacing);
            assert_eq!(problems.len(), 1, "{spacing}: {problems:?}");
            assert!(
                problems[0].starts_with("cameras[0].spacing: "),
                "{problems:?}"
            );
        }
    }
}

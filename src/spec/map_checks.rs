//! Map checks: a spec whose layout is an OpenStreetMap extract (`[layout.osm]`) → the
//! problems the schema cannot see: the file and the box, and what a map layout does not
//! take yet (mirroring, moving traffic).

use std::path::Path;

use super::findings::Findings;
use super::spec::Spec;
use super::{SpecWorld, resolve};

/// Checks `spec`'s map layout, if it has one.
pub(crate) fn check_map(
    spec: &Spec,
    spec_path: &Path,
    world: &dyn SpecWorld,
    findings: &mut Findings,
) {
    let Some(osm) = &spec.layout.osm else {
        for (i, object) in spec.objects.iter().enumerate() {
            if object.at.is_some() {
                findings.error(
                    &format!("objects[{i}].at"),
                    "`at` names the map's nodes a model stands at: expected it only with \
                     `[layout.osm]`",
                );
            }
        }
        return;
    };
    let file = resolve(spec_path, &osm.file);
    if let Err(problem) = world.file(&file) {
        findings.error(
            "layout.osm.file",
            format!(
                "expected an OpenStreetMap extract (.osm.pbf or .osm) at {}, found {problem}",
                file.display()
            ),
        );
    }
    if let Some(problem) = osm.geo_box().and_then(|b| b.problem()) {
        findings.error("layout.osm.bbox", format!("the box {problem}"));
    }
    if !spec.layout.mirror.is_empty() {
        findings.error(
            "layout.mirror",
            "a map is not mirrored: expected no `mirror` with `[layout.osm]`",
        );
    }
    if spec.traffic.is_some() {
        findings.error(
            "traffic",
            "traffic does not move on a map layout yet: expected no `[traffic]` with \
             `[layout.osm]`",
        );
    }
}

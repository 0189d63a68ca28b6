//! `instances.json`: every camera path lists each instance id with the kind the stage that
//! made the object gave it, and `cityspec stats` counts pixels by those kinds.

use std::collections::BTreeSet;
use std::fs;

use crate::common::{self, Workspace};
use cityspec::driver;
use cityspec::model::{Instances, ObjectKind};

#[test]
fn every_id_is_listed_with_the_kind_its_stage_gave_it_and_stats_reads_them() {
    let ws = Workspace::with_spec("day");
    ws.shrink_day();
    driver::build(&ws.spec("day"), &ws.options()).unwrap();
    let out = ws.out().join("day");
    let obj = fs::read_to_string(out.join("city.obj")).unwrap();
    let names: Vec<&str> = obj.lines().filter_map(|l| l.strip_prefix("o ")).collect();
    let street = out.join("frames/street");
    let listed: Instances =
        serde_json::from_slice(&fs::read(street.join("instances.json")).unwrap()).unwrap();

    // One instance per scene object, ids 1, 2, 3, … in scene order, named as city.obj.
    assert_eq!(listed.instances.len(), names.len());
    for (instance, (id, name)) in listed.instances.iter().zip((1u32..).zip(&names)) {
        assert_eq!((instance.id, instance.name.as_str()), (id, *name));
    }
    // Kinds come from the stages, not the names: a user's model is a mesh whatever its
    // label (day.toml's is named after it), and every kind the day city makes is there.
    let kinds: BTreeSet<ObjectKind> = listed.instances.iter().map(|i| i.kind).collect();
    for kind in [
        ObjectKind::Ground,
        ObjectKind::Road,
        ObjectKind::Building,
        ObjectKind::Lamp,
        ObjectKind::Text,
        ObjectKind::Sign,
        ObjectKind::Car,
        ObjectKind::Tree,
        ObjectKind::Person,
        ObjectKind::Bicycle,
        ObjectKind::Rider,
        ObjectKind::Mesh,
    ] {
        assert!(kinds.contains(&kind), "no {kind:?} in {kinds:?}");
    }
    let mesh = listed
        .instances
        .iter()
        .find(|i| i.kind == ObjectKind::Mesh)
        .unwrap();
    assert!(mesh.name.starts_with(&mesh.class), "{mesh:?}");
    assert_ne!(mesh.class, "mesh");
    // A category only where this path labels the class: the ground never, cars always.
    for instance in &listed.instances {
        match instance.kind {
            ObjectKind::Ground => assert_eq!(instance.category, None),
            ObjectKind::Car => assert!(instance.category.is_some(), "{instance:?}"),
            _ => {}
        }
    }
    // Every id the instance images hold is listed.
    for entry in fs::read_dir(street.join("ids")).unwrap() {
        let image = image::open(entry.unwrap().path()).unwrap().to_rgb8();
        for p in image.pixels() {
            let id = u32::from(p[0]) + 256 * u32::from(p[1]) + 65536 * u32::from(p[2]);
            assert!(id as usize <= listed.instances.len(), "id {id} not listed");
        }
    }

    let run = common::cityspec(&ws, &["stats", "--json", out.to_str().unwrap()]);
    assert!(run.status.success(), "{}", common::stderr(&run));
    let stats: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let street_kinds: Vec<&str> = stats["paths"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "street")
        .unwrap()["kinds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k["kind"].as_str().unwrap())
        .collect();
    for kind in ["sky", "road", "building", "car"] {
        assert!(street_kinds.contains(&kind), "{street_kinds:?}");
    }

    // A folder an older cityspec built, without instances.json, is told to be rebuilt.
    fs::remove_file(street.join("instances.json")).unwrap();
    let run = common::cityspec(&ws, &["stats", out.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2), "{}", common::stderr(&run));
    assert!(
        common::stderr(&run).contains("instances.json"),
        "{}",
        common::stderr(&run)
    );
}

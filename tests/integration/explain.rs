//! `cityspec explain`: each stage's key inputs and what the cache holds, without running
//! or writing anything.

use crate::common;

use std::fs;

use common::{Workspace, cityspec, stderr};

#[test]
fn explain_shows_what_each_key_reads_and_which_stages_an_edit_reruns() {
    let ws = Workspace::with_spec("day");
    let spec = ws.path().join("specs/small.toml");
    let mut table: toml::Table = include_str!("../fixtures/shards.toml").parse().unwrap();
    fs::write(&spec, toml::to_string(&table).unwrap()).unwrap();
    let explain = |json: bool| {
        let mut args = vec!["explain", "--cache", "cache"];
        if json {
            args.push("--json");
        }
        args.push("specs/small.toml");
        let out = cityspec(&ws, &args);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        String::from_utf8(out.stdout).unwrap()
    };
    let states = || -> Vec<(String, String)> {
        let value: serde_json::Value = serde_json::from_str(&explain(true)).unwrap();
        value[0]["stages"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| {
                let stage = s["stage"].as_str().unwrap().to_owned();
                let name = match s["camera"].as_str() {
                    Some(camera) => format!("{stage} {camera}"),
                    None => stage,
                };
                (name, s["state"]["state"].as_str().unwrap().to_owned())
            })
            .collect()
    };
    // Before any build: every stage missing, and nothing written, not even the cache.
    let before = states();
    assert_eq!(before.len(), 12, "{before:?}");
    assert!(
        before.iter().all(|(_, state)| state == "missing"),
        "{before:?}"
    );
    assert!(!ws.path().join("cache").exists());
    let text = explain(false);
    assert!(
        text.contains("reads version 1; spec generate, palette, seed"),
        "{text}"
    );

    let built = cityspec(
        &ws,
        &["build", "-q", "--cache", "cache", "specs/small.toml"],
    );
    assert_eq!(built.status.code(), Some(0), "{}", stderr(&built));
    assert!(states().iter().all(|(_, state)| state == "cached"));

    // A new seed moves every key that reads it and what follows from them; the facades
    // read no seed and stay cached.
    table["seed"] = toml::Value::Integer(12);
    fs::write(&spec, toml::to_string(&table).unwrap()).unwrap();
    let after = states();
    let state = |name: &str| &after.iter().find(|(n, _)| n == name).unwrap().1;
    assert_eq!(state("facades"), "cached", "{after:?}");
    for moved in [
        "layout",
        "place",
        "export",
        "frames street",
        "frames aerial",
    ] {
        assert_eq!(state(moved), "missing", "{moved}: {after:?}");
    }
}

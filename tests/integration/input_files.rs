//! The files a spec names, as the binary meets them: a FIFO never hangs a command and is
//! refused with the file and key; OBJ and MTL problems point into the model's own files.

use crate::common;

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{Workspace, stderr};

/// Runs the binary in `ws` with `args`, killing it (and failing the test) if it has not
/// ended within 60 s: a command blocked on a FIFO must fail the test, not hang the suite.
fn bounded(ws: &Workspace, args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(ws.path())
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            let out = child.wait_with_output().unwrap();
            panic!(
                "cityspec {args:?} hung (killed after 60 s): {}",
                stderr(&out)
            );
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

#[cfg(target_os = "linux")]
fn make_fifo(path: &Path) {
    if path.exists() {
        std::fs::remove_file(path).unwrap();
    }
    rustix::fs::mkfifoat(rustix::fs::CWD, path, rustix::fs::Mode::RUSR).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn a_fifo_as_spec_layout_image_model_or_word_file_exits_2_at_once() {
    let ws = Workspace::with_spec("day");
    ws.edit_spec("text", |spec| {
        spec.remove("objects[0].case")
            .insert("objects[0].words_file", "words.fifo");
    });
    make_fifo(&ws.path().join("specs/fifo.toml"));
    make_fifo(&ws.path().join("specs/words.fifo"));
    make_fifo(&ws.path().join("assets/layouts/drawn.png"));
    make_fifo(&ws.path().join("assets/models/bench.obj"));
    let cases: [(&str, &[&str]); 4] = [
        ("specs/fifo.toml", &["cannot read spec specs/fifo.toml"]),
        (
            "specs/drawn.toml",
            &["layout.image", "assets/layouts/drawn.png"],
        ),
        (
            "specs/day.toml",
            &["objects[4].model", "assets/models/bench.obj"],
        ),
        ("specs/text.toml", &["objects[0].words_file", "words.fifo"]),
    ];
    for (spec, wants) in cases {
        for command in ["validate", "build"] {
            let out = bounded(&ws, &["-q", command, spec]);
            let text = stderr(&out);
            assert_eq!(out.status.code(), Some(2), "{command} {spec}: {text}");
            assert!(
                text.contains("a FIFO, not a regular file"),
                "{command} {spec}: {text}"
            );
            for want in wants {
                assert!(text.contains(want), "{command} {spec}: {want}: {text}");
            }
        }
    }
}

#[test]
fn a_photo_as_the_layout_image_is_refused_by_validate_and_build() {
    let ws = Workspace::with_spec("drawn");
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(
        repo.join("tests/fixtures/bad/street_photo.png"),
        ws.path().join("assets/layouts/drawn.png"),
    )
    .unwrap();
    for command in ["validate", "build"] {
        let out = bounded(&ws, &["-q", command, "specs/drawn.toml"]);
        let text = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{command}: {text}");
        for want in [
            "invalid `layout.image`",
            "specs/drawn.toml:10:9",
            "found 0 roads and 1 block in specs/../assets/layouts/drawn.png",
            "3036 road, 107 line, 1383 block and 0 strip pixels",
        ] {
            assert!(text.contains(want), "{command}: {want}: {text}");
        }
    }
    assert!(!ws.out().exists(), "nothing is built");
}

/// The bench model's OBJ with line `number` replaced by `text`.
fn bench_with_line(number: usize, text: &str) -> String {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR"));
    let obj = std::fs::read_to_string(repo.join("assets/models/bench.obj")).unwrap();
    let mut lines: Vec<&str> = obj.lines().collect();
    lines[number - 1] = text;
    lines.join("\n") + "\n"
}

#[test]
fn obj_and_mtl_errors_point_into_the_model_s_own_files() {
    let ws = Workspace::with_spec("day");
    let models = ws.path().join("assets/models");
    let obj = models.join("bench.obj");
    let mtl = std::fs::read_to_string(models.join("bench.mtl")).unwrap();
    assert_eq!(
        std::fs::read_to_string(&obj).unwrap().lines().nth(2),
        Some("mtllib bench.mtl"),
        "the cases below rely on line 3 naming the MTL"
    );
    // (what to write, the MTL to write, what the report must hold)
    let cases: [(String, Option<&str>, &[&str]); 4] = [
        (
            bench_with_line(4, "v -0.800 oops -0.220"),
            None,
            &[
                "error: specs/day.toml: objects[4].model: specs/../assets/models/bench.obj:4:1: not a valid OBJ model",
                "┌─ specs/../assets/models/bench.obj:4:1",
                "4 │ v -0.800 oops -0.220",
                "^^^^^^^^^^^^^^^^^^^^ not a valid OBJ line",
            ],
        ),
        (
            bench_with_line(3, "mtllib gone.mtl"),
            None,
            &[
                "objects[4].model: specs/../assets/models/bench.obj:3:8: the file its `mtllib` names, specs/../assets/models/gone.mtl: expected an MTL file, found no such file",
                "3 │ mtllib gone.mtl",
                "^^^^^^^^ found no such file",
            ],
        ),
        (
            bench_with_line(3, "mtllib bench.mtl"),
            Some("newmtl wood\nKd 0.45 brown 0.14\n"),
            &[
                "objects[4].model: specs/../assets/models/bench.mtl:2:1: not a valid MTL file",
                "2 │ Kd 0.45 brown 0.14",
                "^^^^^^^^^^^^^^^^^^ not a valid MTL line",
            ],
        ),
        (
            bench_with_line(3, "mtllib bench.mtl"),
            Some("newmtl wood\nKd 0.45 0.28 0.14\nmap_Kd wood.png\n"),
            &[
                "specs/../assets/models/bench.mtl:3:8: the file its `map_Kd` names, specs/../assets/models/wood.png: expected a texture image, found no such file",
                "3 │ map_Kd wood.png",
            ],
        ),
    ];
    for (obj_text, mtl_text, wants) in cases {
        std::fs::write(&obj, &obj_text).unwrap();
        std::fs::write(models.join("bench.mtl"), mtl_text.unwrap_or(&mtl)).unwrap();
        for command in ["validate", "build"] {
            let out = bounded(&ws, &["-q", command, "specs/day.toml"]);
            let text = stderr(&out);
            assert_eq!(out.status.code(), Some(2), "{command}: {text}");
            for want in wants {
                assert!(text.contains(want), "{command}: {want}\n{text}");
            }
        }
    }
}

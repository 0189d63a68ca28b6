//! Issue 12: `--cache s3://…` against a real S3-compatible server on localhost (moto in
//! server mode, from PyPI): the same bytes as a local-cache build for one machine and for
//! 2, 4 and 7 shards merged; a damaged remote object is found and replaced; `cache gc`
//! prunes the bucket. And, with no server at all, the errors a bad or unreachable cache
//! gives.
//!
//! The moto test is `#[ignore]`d: `.ci/run` installs moto and runs it explicitly with
//! `MOTO_SERVER=<venv>/bin/moto_server cargo test --test s3_cache -- --ignored`; it fails
//! when the server does not start, it never skips.

mod common;

use std::collections::BTreeMap;
use std::fs;
use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::tree;
use object_store::aws::{AmazonS3, AmazonS3Builder};
use object_store::path::Path as Key;
use object_store::{ObjectStore, ObjectStoreExt, PutPayload};

const SPEC: &str = include_str!("fixtures/shards.toml");
const BUCKET: &str = "cityspec";

/// moto_server on a free localhost port, killed when dropped.
struct Moto {
    child: Child,
    endpoint: String,
}

impl Moto {
    /// Starts the server, its log (one line per request) in `log`: a pipe nobody reads
    /// would fill and stall it.
    fn start(log: &Path) -> Moto {
        let program = std::env::var("MOTO_SERVER").unwrap_or_else(|_| "moto_server".into());
        let port = TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let mut child = Command::new(&program)
            .args(["-H", "127.0.0.1", "-p", &port.to_string()])
            .stdout(Stdio::null())
            .stderr(fs::File::create(log).unwrap())
            .spawn()
            .unwrap_or_else(|e| {
                panic!("cannot start {program} (set MOTO_SERVER, pip install 'moto[server]'): {e}")
            });
        let start = Instant::now();
        loop {
            if let Some(status) = child.try_wait().unwrap() {
                let err = fs::read_to_string(log).unwrap_or_default();
                panic!("{program} exited ({status}) before it answered:\n{err}");
            }
            if http(port, "GET", "/").is_some() {
                break;
            }
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "{program} did not answer on port {port} within 60 s"
            );
            std::thread::sleep(Duration::from_millis(200));
        }
        // moto accepts unsigned requests: make the bucket with a bare PUT.
        let created = http(port, "PUT", &format!("/{BUCKET}")).expect("moto answers");
        assert!(created.starts_with("HTTP/1.1 200"), "{created}");
        Moto {
            child,
            endpoint: format!("http://127.0.0.1:{port}"),
        }
    }

    /// The environment a cityspec process needs to reach it.
    fn env(&self) -> Vec<(&'static str, String)> {
        vec![
            ("AWS_ENDPOINT_URL", self.endpoint.clone()),
            ("AWS_ALLOW_HTTP", "true".into()),
            ("AWS_ACCESS_KEY_ID", "testing".into()),
            ("AWS_SECRET_ACCESS_KEY", "testing".into()),
            ("AWS_REGION", "us-east-1".into()),
        ]
    }

    /// A client of our own, to damage and list objects behind cityspec's back.
    fn client(&self) -> AmazonS3 {
        // cityspec's reqwest has no crypto provider of its own; it installs ring's.
        let _ = rustls::crypto::ring::default_provider().install_default();
        AmazonS3Builder::new()
            .with_endpoint(&self.endpoint)
            .with_allow_http(true)
            .with_bucket_name(BUCKET)
            .with_access_key_id("testing")
            .with_secret_access_key("testing")
            .with_region("us-east-1")
            .build()
            .unwrap()
    }
}

impl Drop for Moto {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// One bare HTTP/1.1 request; the response head, or `None` when nothing answers.
fn http(port: u16, method: &str, path: &str) -> Option<String> {
    let mut stream = TcpStream::connect(("127.0.0.1", port)).ok()?;
    stream
        .set_read_timeout(Some(Duration::from_secs(10)))
        .ok()?;
    write!(
        stream,
        "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Length: 0\r\nConnection: close\r\n\r\n"
    )
    .ok()?;
    let mut response = String::new();
    stream.read_to_string(&mut response).ok()?;
    (!response.is_empty()).then_some(response)
}

/// `cityspec ARGS` in `dir` with `env`; its output, after checking it succeeded.
fn cityspec(dir: &Path, env: &[(&str, String)], args: &[&str]) -> Output {
    let output = run(dir, env, args);
    assert!(
        output.status.success(),
        "cityspec {args:?}: {}\n{}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

fn run(dir: &Path, env: &[(&str, String)], args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_cityspec"))
        .current_dir(dir)
        .envs(env.iter().map(|(k, v)| (k, v)))
        .args(args)
        .output()
        .unwrap()
}

fn workspace() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("small.toml"), SPEC).unwrap();
    let path = dir.path().to_path_buf();
    (dir, path)
}

fn assert_same(one: &BTreeMap<String, Vec<u8>>, other: &Path, what: &str) {
    let other = tree(other);
    let names = |t: &BTreeMap<String, Vec<u8>>| t.keys().cloned().collect::<Vec<_>>();
    assert_eq!(names(one), names(&other), "{what}: other files");
    for (path, bytes) in one {
        assert!(bytes == &other[path], "{what}: {path} differs");
    }
}

/// The SHA-256 `manifest.json` records for `file`.
fn manifest_sha(out: &Path, file: &str) -> String {
    let manifest: serde_json::Value =
        serde_json::from_slice(&fs::read(out.join("manifest.json")).unwrap()).unwrap();
    manifest["artifacts"]
        .as_array()
        .unwrap()
        .iter()
        .find(|a| a["path"] == file)
        .unwrap_or_else(|| panic!("{file} not in the manifest"))["sha256"]
        .as_str()
        .unwrap()
        .to_owned()
}

#[test]
#[ignore = "needs moto_server (pip install 'moto[server]'); .ci/run runs it with MOTO_SERVER set"]
fn s3_cache_gives_local_bytes_repairs_damage_and_collects_garbage() {
    let (_guard, dir) = workspace();
    let moto = Moto::start(&dir.join("moto.log"));
    let env = moto.env();
    cityspec(
        &dir,
        &[],
        &[
            "build",
            "-q",
            "--cache",
            "local",
            "--out",
            "local-out",
            "small.toml",
        ],
    );
    let local = tree(&dir.join("local-out/small"));

    // One machine, then 2, 4 and 7 shards, each with its own prefix, merged.
    for shards in [1u32, 2, 4, 7] {
        let cache = format!("s3://{BUCKET}/run{shards}");
        let out = format!("out{shards}");
        if shards > 1 {
            let mut rendered = 0;
            for index in 0..shards {
                let shard = format!("{index}/{shards}");
                let report = cityspec(
                    &dir,
                    &env,
                    &[
                        "build",
                        "-j1",
                        "--cache",
                        &cache,
                        "--shard",
                        &shard,
                        "small.toml",
                    ],
                );
                let text = String::from_utf8_lossy(&report.stderr).into_owned()
                    + &String::from_utf8_lossy(&report.stdout);
                rendered += chunks_rendered(&text);
            }
            assert_eq!(rendered, 5 + 2, "{shards} shards: every chunk exactly once");
            assert!(!dir.join(&out).exists(), "a shard wrote the output folder");
        }
        cityspec(
            &dir,
            &env,
            &[
                "build",
                "-q",
                "--cache",
                &cache,
                "--out",
                &out,
                "small.toml",
            ],
        );
        assert_same(
            &local,
            &dir.join(&out).join("small"),
            &format!("{shards} shards"),
        );
    }

    // A damaged object, overwritten through the S3 API: found, rebuilt, replaced.
    let client = moto.client();
    let rt = tokio_runtime();
    let sha = manifest_sha(&dir.join("out1/small"), "frames/street/rgb/000007.png");
    let key = Key::from(format!("run1/objects/{}/{sha}", &sha[..2]));
    rt.block_on(client.put(&key, PutPayload::from_static(b"not a png")))
        .unwrap();
    let rebuilt = cityspec(
        &dir,
        &env,
        &[
            "build",
            "--cache",
            &format!("s3://{BUCKET}/run1"),
            "--out",
            "out1",
            "small.toml",
        ],
    );
    let stderr = String::from_utf8_lossy(&rebuilt.stderr);
    assert!(
        stderr.contains("no longer matches its hash"),
        "the damage went unnoticed:\n{stderr}"
    );
    assert_same(&local, &dir.join("out1/small"), "after the repair");
    let repaired = rt
        .block_on(async { client.get(&key).await.unwrap().bytes().await })
        .unwrap();
    assert_eq!(
        cityspec::hash::sha256_hex(&repaired),
        sha,
        "the damaged object was not replaced"
    );

    // gc: a stray entry and object (old enough: --grace-minutes 0) go, the spec's stay,
    // and so do files of names the cache never writes.
    let stray_entry = Key::from(format!("run2/entries/{}.json", "0".repeat(64)));
    let stray_object = Key::from(format!("run2/objects/ab/ab{}", "0".repeat(62)));
    let foreign = [
        Key::from("run2/objects/README-keep.txt"),
        Key::from("run2/entries/0000.json"),
    ];
    for stray in [&stray_entry, &stray_object].into_iter().chain(&foreign) {
        rt.block_on(client.put(stray, PutPayload::from_static(b"{}")))
            .unwrap();
    }
    // `cache gc` of the run2 prefix for `spec` (strays old enough: --grace-minutes 0):
    // what it says.
    let gc = |spec: &str| {
        let gc = cityspec(
            &dir,
            &env,
            &[
                "cache",
                "gc",
                "--grace-minutes",
                "0",
                "--cache",
                &format!("s3://{BUCKET}/run2"),
                spec,
            ],
        );
        String::from_utf8_lossy(&gc.stdout).into_owned() + &String::from_utf8_lossy(&gc.stderr)
    };
    let said = gc("small.toml");
    assert!(said.contains("removed 1 entries, 1 objects"), "{said}");
    assert!(
        said.contains("skipped 2 files and folders that cityspec does not write"),
        "{said}"
    );
    for kept in &foreign {
        assert!(
            rt.block_on(client.head(kept)).is_ok(),
            "gc removed {kept}, which the cache never writes"
        );
    }
    for stray in [&stray_entry, &stray_object] {
        assert!(
            matches!(
                rt.block_on(client.head(stray)),
                Err(object_store::Error::NotFound { .. })
            ),
            "gc left {stray}"
        );
    }
    // What it kept still merges to the same bytes, with nothing rebuilt.
    let again = cityspec(
        &dir,
        &env,
        &[
            "build",
            "-v",
            "--cache",
            &format!("s3://{BUCKET}/run2"),
            "--out",
            "gc-out",
            "small.toml",
        ],
    );
    assert!(
        !String::from_utf8_lossy(&again.stderr).contains("warning"),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    assert_same(&local, &dir.join("gc-out/small"), "after gc");
    // gc for another spec: everything of this one goes.
    fs::write(dir.join("other.toml"), common::set(SPEC, "seed", 12)).unwrap();
    let said = gc("other.toml");
    // It shares a stage or two (the built-in facades) with small.toml: what the bucket
    // still holds is exactly what gc says it kept.
    let left = rt.block_on(async {
        let mut names = Vec::new();
        let mut list = client.list(Some(&Key::from("run2")));
        while let Some(meta) = futures_util::StreamExt::next(&mut list).await {
            names.push(meta.unwrap().location.to_string());
        }
        names
    });
    let entries = left
        .iter()
        .filter(|n| n.starts_with("run2/entries/"))
        .count();
    let objects = left
        .iter()
        .filter(|n| n.starts_with("run2/objects/"))
        .count();
    // Besides them: the marker and the two foreign files.
    assert_eq!(left.len(), entries + objects + 1, "{left:?}");
    assert!(left.contains(&"run2/CACHEDIR.TAG".to_owned()), "{left:?}");
    let (entries, objects) = (entries - 1, objects - 1);
    let kept = format!("kept {entries} entries and {objects} objects; removed ");
    assert!(
        said.contains(&kept),
        "{said}\nbut the bucket holds {left:?}"
    );
    assert!(entries < 5, "gc for another spec kept {entries} entries");
}

/// The chunks a shard says it rendered ("rendered N chunks").
fn chunks_rendered(report: &str) -> usize {
    report
        .split(": rendered ")
        .skip(1)
        .map(|rest| {
            rest.split_whitespace()
                .next()
                .and_then(|n| n.parse::<usize>().ok())
                .unwrap_or_else(|| panic!("no chunk count in {report:?}"))
        })
        .sum()
}

fn tokio_runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .enable_all()
        .build()
        .unwrap()
}

#[test]
fn a_bad_cache_url_is_bad_input() {
    let (_guard, dir) = workspace();
    for bad in ["ftp://host/cache", "s3://", "s3://bu cket/x"] {
        let output = run(&dir, &[], &["build", "--cache", bad, "small.toml"]);
        assert_eq!(output.status.code(), Some(2), "{bad}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains("--cache"), "{bad}: {stderr}");
    }
}

#[test]
fn an_unreachable_cache_fails_clearly_and_quickly() {
    let (_guard, dir) = workspace();
    // A port nobody listens on.
    let port = TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let env = [
        ("AWS_ENDPOINT_URL", format!("http://127.0.0.1:{port}")),
        ("AWS_ALLOW_HTTP", "true".into()),
        ("AWS_ACCESS_KEY_ID", "testing".into()),
        ("AWS_SECRET_ACCESS_KEY", "testing".into()),
        ("AWS_REGION", "us-east-1".into()),
    ];
    let start = Instant::now();
    for args in [
        &[
            "build",
            "--cache",
            "s3://nowhere/cache",
            "--out",
            "out",
            "small.toml",
        ][..],
        &[
            "build",
            "--cache",
            "s3://nowhere/cache",
            "--shard",
            "0/2",
            "small.toml",
        ],
        &["cache", "gc", "--cache", "s3://nowhere/cache", "small.toml"],
        &["verify", "--cache", "s3://nowhere/cache", "small.toml"],
    ] {
        let output = run(&dir, &env, args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(
            stderr.contains("s3://nowhere/cache") && !stderr.contains("panicked"),
            "{args:?}: {stderr}"
        );
    }
    assert!(!dir.join("out").exists());
    assert!(
        start.elapsed() < Duration::from_secs(60),
        "{:?}",
        start.elapsed()
    );
}

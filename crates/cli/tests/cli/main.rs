//! The binaries run on good and bad scenes: `bwc-simulate` ([`simulate`]), `bwc-identify`
//! ([`identify`]), long studies resumed from their checkpoints ([`checkpoint`]), impact sequences and drop tests ([`sequence`]), sweeps served by interpolants
//! ([`sweep`]), chains of bodies ([`chain`]), studies written as they are computed ([`study`]).

/// Table 4's BWSHCCM for the 0.145 kg baseball as a scene's `[physical]` table (the law of
/// `bw_models::published::CROSS_BWSHCCM`, checked by `the_physical_table_is_table_4`), a
/// literal for `concat!`.
macro_rules! cross_physical {
    () => {
        "[physical]\nm = 0.145\nk = 117080063.0\nc = 5854003.0\nn = 1.1\np = 1.7\n\
         alpha = 0.1\nbeta = 981.05\ngamma = -961.4\nA = 0.925\n"
    };
}

mod chain;
mod checkpoint;
mod identify;
mod sequence;
mod simulate;
mod study;
mod sweep;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

// The closed form the examples check against, `e` of the Hunt-Crossley limit at `σ`.
#[path = "../../../../examples/support/hunt_crossley.rs"]
mod hunt_crossley;
use hunt_crossley::hunt_crossley_e;

/// Runs `bwc-simulate run SCENE --out OUT`, which must succeed; its stderr.
fn simulate_to(scene: &Path, out: &Path) -> String {
    let run = simulate(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{err}");
    err
}

fn simulate(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bwc-simulate"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// The one JSON object on stdout of a successful run, without `"command"` (the command line,
/// which differs between runs the tests compare).
fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    // Exactly one JSON object on stdout.
    let mut stream = serde_json::Deserializer::from_str(&text).into_iter::<serde_json::Value>();
    let mut v = stream.next().expect("one JSON value").expect("valid JSON");
    assert!(
        stream.next().is_none(),
        "more than one JSON value on stdout"
    );
    assert!(v["command"].is_array(), "{v}");
    v.as_object_mut().unwrap().remove("command");
    v
}

/// A fresh scratch directory, removed when the test passes (kept for inspection when it fails).
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("bwc-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

fn identify(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bwc-identify"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// Runs a bad scene: non-zero exit (not a panic), a message naming the file, line and key, and
/// nothing written to --out.
fn rejects(name: &str, text: &str, line: Option<usize>, needles: &[&str]) {
    let dir = scratch(&format!("bad-{name}"));
    let scene = dir.join(format!("{name}.toml"));
    std::fs::write(&scene, text).unwrap();
    let out_dir = dir.join("out");
    let out = simulate(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--json",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{name}: exit {:?}, stderr {err}",
        out.status.code()
    );
    assert!(out.stdout.is_empty(), "{name}: stdout not empty");
    assert!(
        err.contains(scene.to_str().unwrap()),
        "{name}: no file name in {err}"
    );
    if let Some(line) = line {
        assert!(
            err.contains(&format!(":{line}:")) || err.contains(&format!("line {line}")),
            "{name}: no line {line} in {err}"
        );
    }
    for n in needles {
        assert!(err.contains(n), "{name}: {n:?} not in {err}");
    }
    assert!(!out_dir.exists(), "{name}: output written");
}

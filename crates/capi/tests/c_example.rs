//! `examples/c/drop.c`, built with the system C compiler against `libbwc.a` and run: its
//! bounces are the Rust element's, step for step, and its first rebound is the library's
//! impact of the same law to the host's error.

use bw_models::input::Constant;
use bw_models::sequence::Policy;
use bw_models::{
    impact, Bwshccl, Bwshccm, ContactElement, ElementSettings, ModelKind, Penetration,
    PhysicalParams, Settings,
};
use std::path::{Path, PathBuf};
use std::process::Command;

const M: f64 = 0.145;
const G: f64 = 9.81;
const H0: f64 = 0.1;
const DT: f64 = 1e-6;

/// The law of the example: Table 4's BWSHCCM.
fn params() -> PhysicalParams {
    bw_models::published::cross(ModelKind::Shccm)
}

/// The example's host in Rust: `(v_in, v_out, dissipated)` per contact.
fn rust_bounces(count: usize) -> Vec<[f64; 3]> {
    let mut settings = ElementSettings::default();
    settings.policy = Policy::Carry;
    let mut element = ContactElement::new(Bwshccl::new(&params()).unwrap(), settings).unwrap();
    let (mut y, mut v, mut force, mut v_in) = (H0, 0.0, 0.0, f64::NAN);
    let at = |y: f64, v: f64| Penetration {
        depth: -y,
        rate: -v,
    };
    let mut out = Vec::new();
    while out.len() < count {
        let predicted = v + (force / M - G) * DT;
        let end = at(y + 0.5 * DT * (v + predicted), predicted);
        let trial = element
            .clone()
            .advance_penetration(DT, at(y, v), end)
            .unwrap();
        let v1 = v + trial.impulse / M - G * DT;
        let y1 = y + 0.5 * DT * (v + v1);
        let step = element
            .advance_penetration(DT, at(y, v), at(y1, v1))
            .unwrap();
        if let Some(t) = step.began_at {
            v_in = G * t - v;
        }
        if let Some(t) = step.separated_at {
            out.push([v_in, v1 + G * (DT - t), element.dissipated()]);
        }
        (y, v, force) = (y1, v1, step.force);
    }
    out
}

/// Where cargo put `libbwc.a` for this test: beside the test binary (target/PROFILE/deps).
fn static_library() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    [deps, deps.parent().unwrap()]
        .iter()
        .map(|d| d.join("libbwc.a"))
        .find(|p| p.exists())
        .expect("libbwc.a beside the test binary")
}

fn compile(root: &Path, dir: &Path) -> PathBuf {
    let exe = dir.join("drop");
    let status = Command::new(std::env::var("CC").unwrap_or_else(|_| "cc".into()))
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"])
        .arg(root.join("examples/c/drop.c"))
        .arg("-I")
        .arg(root.join("crates/capi/include"))
        .arg(static_library())
        .args(["-lm", "-lpthread", "-ldl", "-o"])
        .arg(&exe)
        .status()
        .expect("a C compiler (`cc`, or $CC) on the PATH");
    assert!(status.success(), "the C example did not compile");
    exe
}

#[test]
fn the_c_example_bounces_as_the_rust_element() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = std::env::temp_dir().join(format!("bwc-c-example-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let exe = compile(&root, &dir);
    let run = Command::new(&exe).output().unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = String::from_utf8(run.stdout).unwrap();
    let numbers = |prefix: &str| -> Vec<Vec<f64>> {
        text.lines()
            .filter_map(|l| l.strip_prefix(prefix))
            .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
            .collect()
    };
    let bounces = numbers("bounce ");
    let rust = rust_bounces(bounces.len());
    assert_eq!(bounces.len(), 3, "{text}");
    for (c, r) in bounces.iter().zip(&rust) {
        for (x, y) in c[1..].iter().zip(r) {
            assert!((x - y).abs() <= 1e-12 * y.abs(), "C {c:?} vs Rust {r:?}");
        }
    }
    // The first contact is one impact at the fall's speed under the ball's weight: the C
    // host's rebound matches the library's to the host's O(dt²) error (1e-7 at dt = 1 us).
    let v_in = (2.0 * G * H0).sqrt();
    let model = Bwshccm::new(&params(), M, v_in, Constant(-M * G)).unwrap();
    let e = impact(&model, &Settings::default()).unwrap().e;
    let (c_in, c_out) = (bounces[0][1], bounces[0][2]);
    // The fall: 1.4e5 trapezoid steps, exact but for rounding.
    assert!((c_in - v_in).abs() < 1e-9 * v_in, "{c_in} vs {v_in}");
    assert!(
        (c_out / c_in - e).abs() < 1e-6 * e,
        "{} vs {e}",
        c_out / c_in
    );
    // The C example's own one-shot impact is the library's.
    let c_impact = &numbers("impact ")[0];
    assert!((c_impact[0] - e).abs() < 1e-12, "{c_impact:?} vs {e}");
}

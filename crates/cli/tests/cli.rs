//! The binaries run on good and bad scenes.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

fn simulate(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bwc-simulate"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    // Exactly one JSON object on stdout.
    let mut stream = serde_json::Deserializer::from_str(&text).into_iter::<serde_json::Value>();
    let v = stream.next().expect("one JSON value").expect("valid JSON");
    assert!(
        stream.next().is_none(),
        "more than one JSON value on stdout"
    );
    assert!(v.is_object());
    v
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bwc-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn two_balls_fixtures_write_the_papers_columns_and_plots() {
    for model in ["shccm", "mcm"] {
        let out_dir = scratch(&format!("two-balls-{model}"));
        let scene = fixtures().join(format!("two_balls_{model}.toml"));
        let v = json(&simulate(&[
            "run",
            scene.to_str().unwrap(),
            "--json",
            "--out",
            out_dir.to_str().unwrap(),
        ]));
        let run = &v["runs"][0];
        for key in ["v0", "t_s", "e", "t_d", "separated", "rhs_evals"] {
            assert!(run.get(key).is_some(), "missing key {key}");
        }
        assert_eq!(run["v0"], 2.0);
        assert_eq!(run["separated"], true);
        let (e, ts) = (run["e"].as_f64().unwrap(), run["t_s"].as_f64().unwrap());
        assert!(
            e > 0.0 && e < 1.0 && ts > 1e-3 && ts < 5e-2,
            "{model}: e {e}, t_s {ts}"
        );
        assert_eq!(run["t_d"], run["t_s"]);
        let traj = std::fs::read_to_string(out_dir.join("trajectory.csv")).unwrap();
        assert_eq!(
            traj.lines().next().unwrap(),
            if model == "shccm" {
                "t,x_m_1,x_m_2,x_m,x,v_m_1,v_m_2,v_m,v,u_1,u_2,u,F,z"
            } else {
                "t,x_m_1,x_m_2,x_m,x,v_m_1,v_m_2,v_m,v,u_1,u_2,u,F,r,y,z"
            }
        );
        // Last row: separation, where F <= 0 <= v.
        let last: Vec<f64> = traj
            .lines()
            .last()
            .unwrap()
            .split(',')
            .map(|x| x.parse().unwrap())
            .collect();
        assert!(
            last[12] <= 1e-9 && last[8] >= 0.0,
            "{model}: F {} v {}",
            last[12],
            last[8]
        );
        for f in [
            "summary.json",
            "displacements.svg",
            "velocities.svg",
            "forces.svg",
        ] {
            let text = std::fs::read_to_string(out_dir.join(f)).unwrap();
            assert!(!text.is_empty(), "{f}");
        }
        assert!(std::fs::read_dir(&out_dir).unwrap().all(|e| !e
            .unwrap()
            .file_name()
            .to_string_lossy()
            .ends_with(".tmp")));
    }
}

#[test]
fn sweeps_are_identical_for_any_thread_count() {
    let scene = fixtures().join("kharaz_curves.toml");
    let one = simulate(&["run", scene.to_str().unwrap(), "--json", "--threads", "1"]);
    let two = simulate(&["run", scene.to_str().unwrap(), "--json", "--threads", "2"]);
    assert_eq!(json(&one), json(&two));
    let v = json(&one);
    let runs = v["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 8 * 40);
    // No T_b: durations have no time scale.
    assert!(runs
        .iter()
        .all(|r| r["t_d"].is_null() && r["time_unit"] == "nondimensional"));
}

#[test]
fn cross_fixtures_write_loops_and_sweeps() {
    for model in ["shccm", "mcm"] {
        let out_dir = scratch(&format!("cross-{model}"));
        let scene = fixtures().join(format!("cross_{model}.toml"));
        let out = simulate(&[
            "run",
            scene.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let sweep = std::fs::read_to_string(out_dir.join("sweep.csv")).unwrap();
        assert!(sweep.starts_with("v_0,e,t_d"));
        assert_eq!(sweep.lines().count(), 5);
        let loops = std::fs::read_to_string(out_dir.join("loop.csv")).unwrap();
        assert!(loops.starts_with("v_0,x,F"));
        for f in ["loops.svg", "cor.svg", "duration.svg"] {
            assert!(out_dir.join(f).exists(), "{f}");
        }
    }
}

#[test]
fn nondimensional_scene_reports_null_speed_and_duration() {
    let dir = scratch("nd");
    let scene = dir.join("hc.toml");
    std::fs::write(&scene, "model = \"shccm\"\n[nondimensional]\nB = 0\nGamma = 0\nkappa = 0.5\nsigma = 0.5\nn = 1\np = 1.5\n").unwrap();
    let v = json(&simulate(&["run", scene.to_str().unwrap(), "--json"]));
    let run = &v["runs"][0];
    assert!(run["v0"].is_null() && run["t_d"].is_null());
    // Hunt-Crossley limit: e = 0.748434931597434 (REFERENCES.md).
    assert!((run["e"].as_f64().unwrap() - 0.748434931597434).abs() < 1e-9);
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

const GOOD_PHYSICAL: &str = "model = \"shccm\"\nv0 = [1.0]\n[physical]\nm = 0.145\nk = 117080063.0\nc = 5854003.0\nn = 1.1\np = 1.7\nalpha = 0.1\nbeta = 981.05\ngamma = -961.4\nA = 0.925\n";

#[test]
fn bad_scenes_are_clear_errors() {
    rejects(
        "unknown-key",
        &GOOD_PHYSICAL.replace("A = 0.925", "A = 0.925\nstiffness = 3"),
        Some(13),
        &["stiffness"],
    );
    rejects(
        "missing-key",
        &GOOD_PHYSICAL.replace("k = 117080063.0\n", ""),
        Some(3),
        &["[physical].k", "missing"],
    );
    rejects(
        "two-systems",
        &format!("{GOOD_PHYSICAL}[nondimensional]\nB = 0\n"),
        None,
        &["two system descriptions"],
    );
    rejects(
        "wrong-type",
        &GOOD_PHYSICAL.replace("n = 1.1", "n = \"one\""),
        Some(7),
        &["n"],
    );
    rejects(
        "nan",
        &GOOD_PHYSICAL.replace("c = 5854003.0", "c = nan"),
        Some(6),
        &["[physical].c", "finite"],
    );
    rejects(
        "inf",
        &GOOD_PHYSICAL.replace("k = 117080063.0", "k = inf"),
        Some(5),
        &["[physical].k", "finite"],
    );
    rejects(
        "inadmissible",
        &GOOD_PHYSICAL.replace("alpha = 0.1", "alpha = 1.5"),
        Some(9),
        &["[physical].alpha", "1.5", "0 < alpha < 1"],
    );
    rejects(
        "gamma-range",
        &GOOD_PHYSICAL.replace("gamma = -961.4", "gamma = -2000"),
        Some(11),
        &["[physical].gamma", "-beta <= gamma <= beta"],
    );
    rejects(
        "negative-speed",
        &GOOD_PHYSICAL.replace("v0 = [1.0]", "v0 = [1.0, -2.0]"),
        Some(2),
        &["v0", "-2"],
    );
    rejects(
        "no-speeds",
        &GOOD_PHYSICAL.replace("v0 = [1.0]\n", ""),
        None,
        &["v0", "missing"],
    );
    rejects(
        "bad-model",
        &GOOD_PHYSICAL.replace("\"shccm\"", "\"maxwell\""),
        Some(1),
        &["model", "maxwell"],
    );
    rejects(
        "bad-method",
        &format!("{GOOD_PHYSICAL}[solver]\nmethod = \"euler\"\n"),
        Some(14),
        &["[solver].method", "euler"],
    );
    rejects(
        "bad-rtol",
        &format!("{GOOD_PHYSICAL}[solver]\nrtol = 0.0\n"),
        Some(14),
        &["[solver].rtol"],
    );
    rejects("not-toml", "model = \n", Some(1), &[]);
    rejects("empty", "", None, &["no system description"]);
    rejects(
        "mcm-c-zero",
        &GOOD_PHYSICAL
            .replace("\"shccm\"", "\"mcm\"")
            .replace("c = 5854003.0", "c = 0.0"),
        Some(6),
        &["[physical].c", "c > 0"],
    );
    rejects(
        "nd-kappa",
        "model = \"mcm\"\n[nondimensional]\nB = 1\nGamma = 0\nkappa = 1.0\nsigma = 0.1\nn = 1\np = 1\n",
        Some(5),
        &["[nondimensional].kappa", "0 < kappa < 1"],
    );
    rejects(
        "base-input-needs-scales",
        "model = \"shccm\"\nv0 = [1]\n[base]\nB_b = 1\nGamma_b = 0\nkappa = 0.5\nsigma_b = 0.1\nn = 1\np = 1\n[input]\nkind = \"gravity\"\nm = 1\n",
        Some(3),
        &["U_b"],
    );
    rejects(
        "input-key-for-other-kind",
        &format!("{GOOD_PHYSICAL}[input]\nkind = \"constant\"\nvalue = 1\nomega = 3\n"),
        Some(16),
        &["[input].omega", "does not apply"],
    );
    rejects(
        "bodies-apart",
        "model = \"shccm\"\n[bodies]\nm1 = 1\nm2 = \"inf\"\nv1 = 1\nv2 = 0\n[physical]\nk = 1e6\nc = 1e3\nn = 1.5\np = 1.5\nalpha = 0.5\nbeta = 1e4\ngamma = 0\nA = 1\n",
        Some(5),
        &["v0 = v2 - v1 > 0"],
    );
    rejects("missing-file", "", None, &[]);
    let out = simulate(&["run", "/nonexistent/scene.toml"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/scene.toml"));
}

#[test]
fn a_failed_run_overwrites_nothing() {
    let dir = scratch("keep");
    let out_dir = dir.join("out");
    std::fs::create_dir_all(&out_dir).unwrap();
    std::fs::write(out_dir.join("summary.json"), "previous").unwrap();
    let scene = dir.join("s.toml");
    // Valid scene whose simulation fails: a step limit of 3.
    std::fs::write(&scene, format!("{GOOD_PHYSICAL}[solver]\nmax_steps = 3\n")).unwrap();
    let out = simulate(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("more than 3 steps"));
    assert_eq!(
        std::fs::read_to_string(out_dir.join("summary.json")).unwrap(),
        "previous"
    );
}

#[test]
fn help_shows_examples() {
    let out = simulate(&["--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Examples") && text.contains("bwc-simulate run"));
}

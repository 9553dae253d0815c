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
    // Hunt-Crossley limit (B = Γ = 0): e is the root in (0, 1) of
    // σ - ln(1+σ) = -σe - ln(1-σe); at σ = 0.5, e = 0.748434931597434.
    assert!((run["e"].as_f64().unwrap() - 0.748434931597434).abs() < 1e-9);
}

/// A CoR-only nondimensional scene under a constant input takes the Taylor-series path by
/// default (`series_steps` in the JSON summary); `[solver] series = false` the Runge-Kutta path;
/// both give the Hunt-Crossley closed form.
#[test]
fn series_key_and_series_steps() {
    let dir = scratch("series");
    let hc = "model = \"shccm\"\n[nondimensional]\nB = 0\nGamma = 0\nkappa = 0.5\nsigma = 0.5\nn = 1\np = 1.5\n";
    let scene = dir.join("hc.toml");
    // The series are the default for CoR-only runs; `series = false` takes the Runge-Kutta path.
    for (extra, series) in [("", true), ("[solver]\nseries = false\n", false)] {
        std::fs::write(&scene, format!("{hc}{extra}")).unwrap();
        let v = json(&simulate(&["run", scene.to_str().unwrap(), "--json"]));
        let run = &v["runs"][0];
        assert!((run["e"].as_f64().unwrap() - 0.748434931597434).abs() < 1e-10);
        assert_eq!(run["series_steps"].as_u64().unwrap() > 0, series, "{run}");
    }
}

/// `method = "rosenbrock"` runs RODAS4 (Jacobian evaluations reported, the Hunt-Crossley answer
/// kept); a nearly rigid dashpot in the MCM makes the default explicit method switch, reported
/// as `stiff_from`; `switch_when_stiff = false` keeps the explicit method.
#[test]
fn rosenbrock_method_and_the_stiffness_switch() {
    let dir = scratch("rosenbrock");
    let hc = dir.join("hc.toml");
    std::fs::write(&hc, "model = \"shccm\"\n[nondimensional]\nB = 0\nGamma = 0\nkappa = 0.5\nsigma = 0.5\nn = 1\np = 1.5\n[solver]\nmethod = \"rosenbrock\"\n").unwrap();
    let v = json(&simulate(&["run", hc.to_str().unwrap(), "--json"]));
    let run = &v["runs"][0];
    assert!((run["e"].as_f64().unwrap() - 0.748434931597434).abs() < 1e-9);
    assert!(run["jacobians"].as_u64().unwrap() > 0 && run["stiff_from"].is_null());
    let stiff = "model = \"mcm\"\n[nondimensional]\nB = 1\nGamma = -0.5\nkappa = 0.5\nsigma = 1e5\nn = 2\np = 1.5\n";
    let scene = dir.join("stiff.toml");
    std::fs::write(&scene, stiff).unwrap();
    let v = json(&simulate(&["run", scene.to_str().unwrap(), "--json"]));
    let run = &v["runs"][0];
    assert!(run["stiff_from"].as_f64().unwrap() > 0.0, "{run}");
    assert!(run["rhs_evals"].as_u64().unwrap() < 20_000, "{run}");
    std::fs::write(
        &scene,
        format!("{stiff}[solver]\nswitch_when_stiff = false\nmax_steps = 20000\n"),
    )
    .unwrap();
    let out = simulate(&["run", scene.to_str().unwrap(), "--json"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(err.contains("20000 steps"), "{err}");
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
        &["[solver].method", "euler", "rosenbrock"],
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
fn several_mistakes_are_reported_at_once_in_file_order() {
    rejects(
        "scalar-v0",
        &GOOD_PHYSICAL.replace("v0 = [1.0]", "v0 = 1.5"),
        Some(2),
        &["`v0` expects a list of impact speeds", "range"],
    );
    let three = GOOD_PHYSICAL
        .replace("k = 117080063.0", "k = -1.0")
        .replace("n = 1.1", "n = \"one\"")
        .replace("A = 0.925", "A = 0.925\nstiffness = 3");
    rejects(
        "three",
        &format!("{three}[solver]\nrtol = -1\n"),
        Some(5),
        &[
            "4 mistakes",
            ":5: `[physical].k`: -1 is not admissible: k > 0",
            ":7:5: `[physical].n` expects a number",
            ":13:1: unknown field `stiffness`",
            ":15: `[solver].rtol`",
        ],
    );
    // A J2 weight on data without durations comes first, before what it makes required.
    let dir = scratch("many-config");
    std::fs::write(dir.join("d.csv"), "v_0,e\n1.0,0.8\n2.0,0.7\n").unwrap();
    let config = dir.join("c.toml");
    std::fs::write(
        &config,
        "[[fit]]\nname = \"x\"\nmodel = \"shccm\"\ndata = \"d.csv\"\nobjectives = { J1 = 1.0, J2 = 1.0 }\n[fit.bounds]\nB_b = [0.0, -10.0]\ng = [-1.0, 1.0]\nkappa = [0.02, 0.98]\nsigma_b = [1e-5, 1.0]\nn = [1.0, \"4\"]\np = [1.0, 4.0]\n",
    )
    .unwrap();
    let out = identify(&["run", config.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let lines: Vec<&str> = err.lines().collect();
    assert!(lines[0].contains("3 mistakes"), "{err}");
    assert!(
        lines[1].contains(":5: `objectives.J2`") && lines[1].contains("no `t_d` column"),
        "{err}"
    );
    assert!(lines[2].contains(":7: `[fit.bounds].B_b`"), "{err}");
    assert!(
        lines[3].contains(":11:") && lines[3].contains("`[fit.bounds].n` expects a number"),
        "{err}"
    );
}

#[test]
fn each_run_stands_alone_and_the_output_says_what_it_is() {
    let dir = scratch("alone");
    let out_dir = dir.join("out");
    std::fs::create_dir_all(&out_dir).unwrap();
    // Left by an earlier run that wrote a trajectory; and a file of the user's.
    std::fs::write(
        out_dir.join("summary.json"),
        r#"{"files": ["summary.json", "trajectory.csv", "../outside.txt"]}"#,
    )
    .unwrap();
    std::fs::write(out_dir.join("trajectory.csv"), "stale").unwrap();
    std::fs::write(out_dir.join("notes.txt"), "mine").unwrap();
    let scene = dir.join("s.toml");
    // Undamped, 1.5 m/s separates; 1e12 m/s needs far more than 2000 steps.
    let sweep = "model = \"shccm\"\nv0 = [1.5, 1e12]\n[physical]\nm = 0.145\nk = 117080063.0\nc = 0.0\nn = 1.5\np = 1.5\nalpha = 0.5\nbeta = 1.0e4\ngamma = -5.0e3\nA = 1.0\n";
    std::fs::write(&scene, format!("{sweep}[solver]\nmax_steps = 2000\n")).unwrap();
    let out = simulate(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.contains("failed") && err.contains("[solver].max_steps (now 2000)"),
        "{err}"
    );
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("separated") && table.contains("failed"),
        "{table}"
    );
    assert!(
        table.contains("t_s (s)") && table.contains("t_d (s)"),
        "{table}"
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
            .unwrap();
    let runs = v["runs"].as_array().unwrap();
    assert_eq!(runs[0]["outcome"], "separated");
    assert!(runs[0]["error"].is_null() && runs[0]["e"].as_f64().unwrap() > 0.5);
    assert_eq!(runs[1]["outcome"], "failed");
    assert!(runs[1]["e"].is_null());
    assert!(runs[1]["error"].as_str().unwrap().contains("max_steps"));
    // T_c = (m/k)^(1/(p+1)) D^(-1/(p+1)) v0^(-(p-1)/(p+1)) of Table 1 at 1.5 m/s.
    let (m, k, p, alpha, a): (f64, f64, f64, f64, f64) = (0.145, 117080063.0, 1.5, 0.5, 1.0);
    let d = alpha + (1.0 - alpha) * a.powf(p);
    let t_c = (m / k / d).powf(1.0 / (p + 1.0)) * 1.5f64.powf(-(p - 1.0) / (p + 1.0));
    assert!((runs[0]["T_c"].as_f64().unwrap() / t_c - 1.0).abs() < 1e-12);
    assert_eq!(
        runs[0]["nondimensional"]["kappa"].as_f64().unwrap(),
        alpha / d
    );
    // Provenance: the files written, the version, the command, the scene with its defaults.
    assert_eq!(v["files"], serde_json::json!(["summary.json", "sweep.csv"]));
    assert_eq!(v["version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(v["command"][1], "run");
    assert_eq!(v["scene"]["solver"]["max_steps"], 2000);
    assert_eq!(v["scene"]["solver"]["rtol"].as_f64(), Some(1e-11));
    assert_eq!(v["scene"]["systems"][0]["physical"]["k"].as_f64(), Some(k));
    assert_eq!(v["units"]["sweep.csv"]["t_s"], "s");
    assert_eq!(v["units"]["runs"]["T_c"], "s");
    let sweep_csv = std::fs::read_to_string(out_dir.join("sweep.csv")).unwrap();
    assert!(
        sweep_csv.starts_with("v_0,e,t_d,t_s,separated,outcome\n"),
        "{sweep_csv}"
    );
    assert!(
        sweep_csv.contains("1000000000000,,,,false,failed"),
        "{sweep_csv}"
    );
    // The earlier run's trajectory is gone; the user's file stays.
    assert!(!out_dir.join("trajectory.csv").exists());
    assert_eq!(
        std::fs::read_to_string(out_dir.join("notes.txt")).unwrap(),
        "mine"
    );
}

#[test]
fn horizons_and_settled_contacts_are_outcomes_not_results() {
    let dir = scratch("outcomes");
    let scene = dir.join("horizon.toml");
    std::fs::write(&scene, format!("{GOOD_PHYSICAL}[solver]\nt_max = 0.5\n")).unwrap();
    let out = simulate(&["run", scene.to_str().unwrap(), "--json"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("raise [solver].t_max") && err.contains("T_c"),
        "{err}"
    );
    let v = json(&out);
    assert_eq!(v["runs"][0]["outcome"], "horizon");
    assert_eq!(v["runs"][0]["separated"], false);
    // Under a constant push U = -2 the NDBWSHCCM with B = 0 comes to rest where the force
    // balances it: F = -U = 2.
    let settle = dir.join("settle.toml");
    std::fs::write(&settle, "model = \"shccm\"\n[nondimensional]\nB = 0\nGamma = 0\nkappa = 0.5\nsigma = 0.5\nn = 1\np = 1.5\nU = -2\n").unwrap();
    let v = json(&simulate(&["run", settle.to_str().unwrap(), "--json"]));
    let run = &v["runs"][0];
    assert_eq!(run["outcome"], "settled", "{run}");
    assert!(
        (run["rest"]["F"].as_f64().unwrap() - 2.0).abs() < 1e-9,
        "{run}"
    );
    assert_eq!(run["rest"]["u"].as_f64(), Some(-2.0));
    assert!(run["T_c"].is_null());
}

#[test]
fn an_unusable_out_is_refused_before_any_work() {
    let dir = scratch("badout");
    let blocker = dir.join("file");
    std::fs::write(&blocker, "x").unwrap();
    let scene = dir.join("s.toml");
    std::fs::write(&scene, GOOD_PHYSICAL).unwrap();
    let out_dir = blocker.join("sub");
    let out = simulate(&[
        "run",
        scene.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("--out") && out.stdout.is_empty(), "{err}");
}

#[test]
fn help_shows_examples() {
    let out = simulate(&["--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Examples") && text.contains("bwc-simulate run"));
}

fn identify(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bwc-identify"))
        .args(args)
        .output()
        .expect("binary runs")
}

#[test]
fn identify_eval_reports_the_json_contract() {
    let config = fixtures().join("kharaz.toml");
    let v = json(&identify(&["eval", config.to_str().unwrap(), "--json"]));
    let fits = v["fits"].as_array().unwrap();
    assert_eq!(fits.len(), 4);
    for f in fits {
        for key in [
            "name",
            "model",
            "params",
            "J1",
            "J2",
            "evaluations",
            "wall_s",
        ] {
            assert!(f.get(key).is_some(), "missing {key}");
        }
        for key in ["B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "U_b", "T_b"] {
            assert!(f["params"].get(key).is_some(), "missing params.{key}");
        }
        // u = 0 and no durations: U_b, T_b and J2 are unused.
        assert!(f["params"]["U_b"].is_null() && f["params"]["T_b"].is_null() && f["J2"].is_null());
        let j1 = f["J1"].as_f64().unwrap();
        // The published vectors fit the reconstructed data (the mean of their own curves).
        assert!(j1 > 0.0 && j1 < 1e-4, "{}: J1 = {j1}", f["name"]);
    }
    assert_eq!(fits[0]["params"]["B_b"], 2.38);
}

/// Writes a synthetic dataset of a known NDBWSHCCM and a config that frees κ and σ_b.
fn synthetic_config(dir: &Path) -> PathBuf {
    use bw_models::{impact_at, input::Zero, BaseMap, BaseParams, ModelKind, Settings};
    let truth = BaseParams {
        b_b: 1.0,
        gamma_b: -1.0,
        kappa: 0.6,
        sigma_b: 0.03,
        n: 1.5,
        p: 1.5,
        u_b: 1.0,
        t_b: 1.0,
    };
    let map = BaseMap::new(ModelKind::Shccm, truth).unwrap();
    let mut csv = String::from("# synthetic: kappa = 0.6, sigma_b = 0.03\nv_0,e\n");
    for v0 in [0.2, 0.5, 1.0, 2.0, 4.0] {
        csv += &format!(
            "{v0},{}\n",
            impact_at(&map, Zero, v0, &Settings::default()).unwrap().e
        );
    }
    std::fs::write(dir.join("synthetic.csv"), csv).unwrap();
    let config = dir.join("fit.toml");
    std::fs::write(
        &config,
        "[[fit]]\nname = \"synthetic\"\nmodel = \"shccm\"\ndata = \"synthetic.csv\"\n[fit.bounds]\nkappa = [0.1, 0.9]\nsigma_b = [0.0, 0.1]\n\
         [fit.fixed]\nB_b = 1.0\ng = -1.0\nn = 1.5\np = 1.5\n[fit.optimizer]\nparticles = 8\niterations = 10\npolish = 300\nstarts = 2\n",
    )
    .unwrap();
    config
}

#[test]
fn identify_run_recovers_synthetic_parameters_on_any_thread_count() {
    let dir = scratch("identify-synthetic");
    let config = synthetic_config(&dir);
    let out_dir = dir.join("out");
    let one = json(&identify(&[
        "run",
        config.to_str().unwrap(),
        "--json",
        "--threads",
        "1",
        "--out",
        out_dir.to_str().unwrap(),
    ]));
    let two = json(&identify(&[
        "run",
        config.to_str().unwrap(),
        "--json",
        "--threads",
        "2",
    ]));
    let strip = |mut v: serde_json::Value| {
        v["fits"][0].as_object_mut().unwrap().remove("wall_s");
        v
    };
    assert_eq!(strip(one.clone()), strip(two));
    let f = &one["fits"][0];
    assert!(
        (f["params"]["kappa"].as_f64().unwrap() - 0.6).abs() < 1e-5,
        "{f}"
    );
    assert!(
        (f["params"]["sigma_b"].as_f64().unwrap() - 0.03).abs() < 1e-5,
        "{f}"
    );
    assert!(f["J1"].as_f64().unwrap() < 1e-12);
    assert_eq!(
        f["identifiability"]["singular_values"]
            .as_array()
            .unwrap()
            .len(),
        2
    );
    let c = &f["convergence"];
    assert!(c["agreeing"].as_u64().unwrap() >= 2, "{c}");
    assert!(c["starts"].as_u64().unwrap() >= c["agreeing"].as_u64().unwrap());
    assert_eq!(
        c["costs"].as_array().unwrap().len() as u64,
        c["starts"].as_u64().unwrap()
    );
    assert_eq!(f["at_bound"], serde_json::json!([]));
    let iv = &f["intervals"];
    assert_eq!(iv["level"], 0.95);
    assert!(iv["method"].as_str().unwrap().contains("delta method"));
    let kappa = iv["params"]["kappa"].as_array().unwrap();
    let (lo, hi) = (kappa[0].as_f64().unwrap(), kappa[1].as_f64().unwrap());
    // Noise-free data: an interval around the truth, and a narrow one.
    assert!(lo <= 0.6 && 0.6 <= hi && hi - lo < 1e-3, "{iv}");
    assert!(f["predictions"]["e"]["summary"]
        .as_str()
        .unwrap()
        .starts_with("e is determined to"));
    assert_eq!(f["warnings"], serde_json::json!([]));
    let csv = std::fs::read_to_string(out_dir.join("synthetic.csv")).unwrap();
    assert!(csv.starts_with("v_0,e,e_model,t_d,t_d_model,e_lo,e_hi,t_d_lo,t_d_hi"));
    for row in csv.lines().skip(1) {
        let v: Vec<f64> = row.split(',').filter_map(|x| x.parse().ok()).collect();
        // v_0, e, e_model, e_lo, e_hi: the band holds the model.
        assert!(v[3] <= v[2] && v[2] <= v[4], "{row}");
    }
    assert!(out_dir.join("synthetic_cor.svg").exists() && out_dir.join("summary.json").exists());
}

/// A bad config: exit 1, a message naming the file (and line and key where there is one),
/// nothing written.
fn identify_rejects(name: &str, config: &str, data: Option<&str>, needles: &[&str]) {
    let dir = scratch(&format!("bad-identify-{name}"));
    if let Some(d) = data {
        std::fs::write(dir.join("d.csv"), d).unwrap();
    }
    let path = dir.join("c.toml");
    std::fs::write(&path, config).unwrap();
    let out_dir = dir.join("out");
    let out = identify(&[
        "run",
        path.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{name}: {err}");
    for n in needles {
        assert!(err.contains(n), "{name}: {n:?} not in {err}");
    }
    assert!(!out_dir.exists(), "{name}: output written");
}

#[test]
fn bad_identification_inputs_are_clear_errors() {
    let good_data = "v_0,e\n0.5,0.9\n1.0,0.8\n";
    let head = "[[fit]]\nname = \"f\"\nmodel = \"shccm\"\ndata = \"d.csv\"\n";
    let bounds = "[fit.bounds]\nB_b = [0.0, 2.0]\ng = [-1.0, 1.0]\nkappa = [0.1, 0.9]\nsigma_b = [0.0, 0.1]\nn = [1.0, 2.0]\np = [1.0, 2.0]\n";
    let good = format!("{head}{bounds}");
    identify_rejects("missing-data-file", &good, None, &["d.csv"]);
    identify_rejects(
        "malformed-row",
        &good,
        Some("v_0,e\n0.5,0.9\n1.0,abc\n"),
        &["d.csv:3", "abc"],
    );
    identify_rejects(
        "negative-speed",
        &good,
        Some("v_0,e\n-0.5,0.9\n"),
        &["d.csv:2", "v_0 > 0"],
    );
    identify_rejects(
        "nan",
        &good,
        Some("v_0,e\n0.5,nan\n"),
        &["d.csv:2", "not finite"],
    );
    identify_rejects("empty-data", &good, Some("v_0,e\n"), &["no data rows"]);
    identify_rejects(
        "swapped-bounds",
        &good.replace("kappa = [0.1, 0.9]", "kappa = [0.9, 0.1]"),
        Some(good_data),
        &[
            "c.toml:8",
            "[fit.bounds].kappa",
            "lower bound <= upper bound",
        ],
    );
    identify_rejects(
        "bound-outside-admissible",
        &good.replace("kappa = [0.1, 0.9]", "kappa = [0.1, 1.5]"),
        Some(good_data),
        &["kappa", "0 < kappa < 1"],
    );
    identify_rejects(
        "start-outside-bounds",
        &format!("{good}[fit.start]\nB_b = 3.0\nGamma_b = 0.0\nkappa = 0.5\nsigma_b = 0.01\nn = 1.0\np = 1.0\n"),
        Some(good_data),
        &["[fit.start]", "B_b"],
    );
    identify_rejects(
        "infeasible",
        &format!("{head}objectives = {{ J1 = 1.0 }}\n{bounds}U_b = [1e-4, 1e-3]\n[fit.known]\nm = 0.5\nk = 255.0\n"),
        Some(good_data),
        &["infeasible"],
    );
    identify_rejects(
        "unknown-key",
        &format!("{good}speed = 3\n"),
        Some(good_data),
        &["c.toml:", "speed"],
    );
    identify_rejects(
        "missing-bound",
        &good.replace("n = [1.0, 2.0]\n", ""),
        Some(good_data),
        &["[fit.bounds].n", "missing"],
    );
    identify_rejects(
        "duration-without-data",
        &format!(
            "{head}objectives = {{ J2 = 1.0 }}\n{bounds}U_b = [0.01, 1.0]\nT_b = [0.01, 1.0]\n"
        ),
        Some(good_data),
        &["t_d"],
    );
    identify_rejects("no-fits", "", None, &["no fits"]);
    identify_rejects(
        "duplicate-names",
        &format!("{good}{good}"),
        Some(good_data),
        &["used twice"],
    );
}

#[test]
fn identify_eval_of_loop_fits() {
    let config = fixtures().join("cross.toml");
    let v = json(&identify(&["eval", config.to_str().unwrap(), "--json"]));
    let fits = v["fits"].as_array().unwrap();
    assert_eq!(fits.len(), 2);
    assert_eq!(fits[0]["kind"], "loops");
    assert_eq!(fits[0]["params"]["k"], 117080063.0);
    assert!(fits[0]["cost"].as_f64().unwrap() < 1e-7);
    assert!(fits[1]["cost"].as_f64().unwrap() < 1e-2);
}

mod fuzz {
    //! Arbitrary and near-valid inputs: never a panic; every error names the file.
    use super::fixtures;
    use bwc_cli::config::Config;
    use bwc_cli::scene::Scene;
    use proptest::prelude::*;
    use proptest::test_runner::RngSeed;
    use std::path::Path;

    fn config(cases: u32) -> ProptestConfig {
        ProptestConfig {
            cases,
            rng_seed: RngSeed::Fixed(0x6277_6321),
            failure_persistence: None,
            ..ProptestConfig::default()
        }
    }

    const SCENES: [&str; 5] = [
        "two_balls_shccm.toml",
        "two_balls_mcm.toml",
        "cross_shccm.toml",
        "cross_mcm.toml",
        "kharaz_curves.toml",
    ];
    const CONFIGS: [&str; 4] = [
        "kharaz.toml",
        "villegas.toml",
        "cross.toml",
        "baseball_wood.toml",
    ];
    const REPLACEMENTS: [&str; 12] = [
        "nan", "inf", "-inf", "1e308", "-1", "0", "\"x\"", "[]", "1e-320", "{}", "true", "-1e308",
    ];

    /// Replaces the `which`-th number of `text` by a hostile value, deletes or duplicates a
    /// line, or truncates the text.
    fn mutate(text: &str, op: usize, which: usize, with: usize) -> String {
        let lines: Vec<&str> = text.lines().collect();
        match op % 4 {
            0 => {
                let numbers: Vec<(usize, usize)> = {
                    let bytes = text.as_bytes();
                    let mut spans = Vec::new();
                    let mut i = 0;
                    while i < bytes.len() {
                        if bytes[i].is_ascii_digit()
                            && (i == 0
                                || !bytes[i - 1].is_ascii_alphanumeric() && bytes[i - 1] != b'_')
                        {
                            let start = if i > 0 && bytes[i - 1] == b'-' {
                                i - 1
                            } else {
                                i
                            };
                            let mut j = i;
                            while j < bytes.len()
                                && (bytes[j].is_ascii_digit() || b".eE-+".contains(&bytes[j]))
                            {
                                j += 1;
                            }
                            spans.push((start, j));
                            i = j;
                        } else {
                            i += 1;
                        }
                    }
                    spans
                };
                if numbers.is_empty() {
                    return text.to_string();
                }
                let (a, b) = numbers[which % numbers.len()];
                format!(
                    "{}{}{}",
                    &text[..a],
                    REPLACEMENTS[with % REPLACEMENTS.len()],
                    &text[b..]
                )
            }
            1 => lines
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != which % lines.len().max(1))
                .map(|(_, l)| *l)
                .collect::<Vec<_>>()
                .join("\n"),
            2 => {
                let mut v = lines.clone();
                let i = which % v.len().max(1);
                v.insert(i, lines[i]);
                v.join("\n")
            }
            _ => {
                let mut cut = which % text.len().max(1);
                while !text.is_char_boundary(cut) {
                    cut -= 1;
                }
                text[..cut].to_string()
            }
        }
    }

    proptest! {
        #![proptest_config(config(256))]

        #[test]
        fn arbitrary_text_never_panics(text in ".{0,400}") {
            let p = Path::new("fuzz.toml");
            if let Err(e) = Scene::parse(p, &text) {
                prop_assert!(e.to_string().contains("fuzz.toml"), "{e}");
            }
            if let Err(e) = Config::parse(p, &text) {
                prop_assert!(e.to_string().contains("fuzz.toml"), "{e}");
            }
            let _ = bwc_identify::Dataset::parse(p, &text);
        }

        /// Mutated fixtures: parsing never panics, errors name the file, and a scene that still
        /// parses runs (with a bounded step budget) without panicking.
        #[test]
        fn mutated_fixtures_never_panic(file in 0usize..9, op in 0usize..4, which in 0usize..10_000, with in 0usize..100) {
            let (name, is_scene) = if file < 5 { (SCENES[file], true) } else { (CONFIGS[file - 5], false) };
            let path = fixtures().join(name);
            let text = std::fs::read_to_string(&path).unwrap();
            let mutated = mutate(&text, op, which, with);
            if is_scene {
                match Scene::parse(&path, &mutated) {
                    Err(e) => prop_assert!(e.to_string().contains(name), "{e}"),
                    Ok(mut scene) => {
                        scene.settings.max_steps = 20_000;
                        scene.speeds.truncate(3);
                        let _ = bwc_cli::simulate::run(&scene, None);
                    }
                }
            } else if let Err(e) = Config::parse(&path, &mutated) {
                prop_assert!(e.to_string().contains(name), "{e}");
            }
        }
    }
}

/// Suspicious data and an optimum on a bound are named on stderr and in the JSON; the fit still
/// finishes (exit 0) with its results.
#[test]
fn identify_warns_about_data_and_bounds() {
    let dir = scratch("identify-warnings");
    std::fs::write(
        dir.join("d.csv"),
        "v_0,e\n0.2,0.95\n0.5,0.93\n1.0,1.02\n2.0,0.88\n4.0,0.84\n",
    )
    .unwrap();
    let config = dir.join("fit.toml");
    std::fs::write(
        &config,
        "[[fit]]\nname = \"w\"\nmodel = \"shccm\"\ndata = \"d.csv\"\n[fit.bounds]\nkappa = [0.1, 0.9]\nsigma_b = [0.0, 0.001]\n\
         [fit.fixed]\nB_b = 0.0\ng = 0.0\nn = 1.5\np = 1.5\n[fit.optimizer]\nparticles = 8\niterations = 10\n",
    )
    .unwrap();
    let out = identify(&["run", config.to_str().unwrap(), "--json"]);
    let v = json(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("d.csv:4: e = 1.02 > 1"), "{stderr}");
    // Damping alone cannot reach e = 0.84: sigma_b ends on its upper bound.
    assert!(
        stderr.contains("sigma_b = 0.001 is on its upper bound 0.001"),
        "{stderr}"
    );
    let f = &v["fits"][0];
    assert_eq!(f["at_bound"], serde_json::json!(["sigma_b"]));
    assert_eq!(f["intervals"]["params"]["sigma_b"], serde_json::Value::Null);
    assert_eq!(f["warnings"].as_array().unwrap().len(), 2, "{f}");
}

/// A coverage study is a set of independent replicates: the same on any thread count, and a
/// study split into shards (`--first-seed`, `--replicates`) gives the same replicates.
#[test]
fn identify_coverage_shards_and_threads() {
    let dir = scratch("identify-coverage");
    let config = synthetic_config(&dir);
    let c = config.to_str().unwrap();
    let run = |args: &[&str]| {
        let mut all = vec!["coverage", c, "--json", "--noise", "0.01"];
        all.extend_from_slice(args);
        json(&identify(&all))
    };
    let whole = run(&["--replicates", "3", "--threads", "1"]);
    assert_eq!(whole, run(&["--replicates", "3", "--threads", "2"]));
    let a = run(&["--replicates", "2"]);
    let b = run(&["--replicates", "1", "--first-seed", "3"]);
    let reps = |v: &serde_json::Value| v["coverage"][0]["replicates"].as_array().unwrap().clone();
    let mut joined = reps(&a);
    joined.extend(reps(&b));
    assert_eq!(joined, reps(&whole));
    let s = &whole["coverage"][0];
    assert_eq!(s["truth_from"], "fit");
    assert_eq!(s["noise"], 0.01);
    let cov = s["coverage"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&cov));
    assert_eq!(reps(&whole).len(), 3);
    assert!(reps(&whole)
        .iter()
        .all(|r| r["points"] == 5 && r["error"].is_null()));
    // A fit with a duration objective is refused with a message naming it.
    let out = identify(&[
        "coverage",
        fixtures().join("villegas.toml").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("CoR-only"));
}

/// The Table 4 baseball contact law dropped from 1 m: `[sequence]` with the given extra keys.
fn drop_scene(extra: &str) -> String {
    format!(
        "model = \"shccm\"\n[sequence]\nh0 = 1.0\n{extra}\n[physical]\nm = 0.145\nk = 117080063.0\nc = 5854003.0\nn = 1.1\np = 1.7\nalpha = 0.1\nbeta = 981.05\ngamma = -961.4\nA = 0.925\n"
    )
}

#[test]
fn a_reset_sequence_is_single_impacts_and_ballistic_flights() {
    let dir = scratch("sequence");
    let scene = dir.join("drop.toml");
    std::fs::write(&scene, drop_scene("bounces = 4")).unwrap();
    let out_dir = dir.join("out");
    let v = json(&simulate(&[
        "run",
        scene.to_str().unwrap(),
        "--json",
        "--out",
        out_dir.to_str().unwrap(),
    ]));
    let bounces = v["runs"][0]["bounces"].as_array().unwrap();
    assert_eq!(bounces.len(), 4);
    let g: f64 = 9.81;
    let f = |b: &serde_json::Value, k: &str| b[k].as_f64().unwrap();
    // Dropped from rest: the first contact at sqrt(2 h0 / g) with speed sqrt(2 g h0).
    let (mut t, mut v_in) = ((2.0 / g).sqrt(), (2.0 * g).sqrt());
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
    for (k, b) in bounces.iter().enumerate() {
        assert_eq!(b["n"], k + 1);
        assert!(
            close(f(b, "t_contact"), t) && close(f(b, "v_in"), v_in),
            "{b}"
        );
        // The same contact alone: one impact at v_in under the input -m g.
        let single = dir.join(format!("single{k}.toml"));
        let text = drop_scene("").replace(
            "[sequence]\nh0 = 1.0\n",
            &format!("v0 = [{v_in:e}]\n[input]\nkind = \"gravity\"\nm = 0.145\ng = 9.81\n"),
        );
        std::fs::write(&single, text).unwrap();
        let one = json(&simulate(&["run", single.to_str().unwrap(), "--json"]));
        let run = &one["runs"][0];
        let (e, t_s) = (f(run, "e"), f(run, "t_s"));
        assert!(
            close(f(b, "e"), e) && close(f(b, "t_s"), t_s),
            "{b} vs {run}"
        );
        let v_out = e * v_in;
        assert!(close(f(b, "v_out"), v_out) && close(f(b, "apex"), v_out * v_out / (2.0 * g)));
        if k + 1 < bounces.len() {
            let interval = t_s + 2.0 * v_out / g;
            assert!(close(f(b, "interval"), interval), "{b}");
            t += interval;
            v_in = v_out;
        } else {
            assert!(b["interval"].is_null());
        }
    }
    let csv = std::fs::read_to_string(out_dir.join("bounces.csv")).unwrap();
    assert!(csv.starts_with("n,t_contact,v_in,v_out,e,t_s,apex,interval,x_s,outcome\n"));
    assert_eq!(csv.lines().count(), 5);
    assert!(out_dir.join("height.svg").exists());
}

#[test]
fn carried_state_changes_the_later_contacts_and_rest_ends_a_sequence() {
    let dir = scratch("carry");
    let run = |name: &str, text: String| {
        let scene = dir.join(name);
        std::fs::write(&scene, text).unwrap();
        json(&simulate(&["run", scene.to_str().unwrap(), "--json"]))["runs"][0].clone()
    };
    let reset = run("reset.toml", drop_scene("bounces = 3"));
    let carry = run("carry.toml", drop_scene("bounces = 3\npolicy = \"carry\""));
    let e = |r: &serde_json::Value, k: usize| r["bounces"][k]["e"].as_f64().unwrap();
    // The first contact starts unloaded either way; the second from the residual deformation.
    assert_eq!(e(&reset, 0), e(&carry, 0));
    assert!(
        (e(&reset, 1) - e(&carry, 1)).abs() > 1e-3,
        "{reset} {carry}"
    );
    // A stiff dashpot swallows a 1 mm drop: the body rests on the surface.
    let rest = run(
        "rest.toml",
        drop_scene("bounces = 5")
            .replace("h0 = 1.0", "h0 = 0.001")
            .replace("c = 5854003.0", "c = 5.0e9"),
    );
    assert_eq!(rest["outcome"], "settled");
    let last = rest["bounces"].as_array().unwrap().last().unwrap().clone();
    assert_eq!(last["outcome"], "settled");
    assert!(last["interval"].is_null() && last["t_s"].is_null());
}

#[test]
fn bad_sequences_are_clear_errors() {
    rejects(
        "seq-h0",
        &drop_scene("").replace("h0 = 1.0", "h0 = -1.0"),
        Some(3),
        &["[sequence].h0", "> 0 (m)"],
    );
    rejects(
        "seq-g",
        &drop_scene("g = 0.0"),
        Some(4),
        &["[sequence].g", "> 0"],
    );
    rejects(
        "seq-bounces",
        &drop_scene("bounces = 0"),
        Some(4),
        &["[sequence].bounces", "1 <= bounces"],
    );
    rejects(
        "seq-drag",
        &drop_scene("drag = nan"),
        Some(4),
        &["[sequence].drag", "finite"],
    );
    rejects(
        "seq-policy",
        &drop_scene("policy = \"keep\""),
        Some(4),
        &["[sequence].policy", "\"reset\" or \"carry\""],
    );
    let bodies = "model = \"shccm\"\n[sequence]\nh0 = 1.0\n[bodies]\nm1 = 1\nm2 = \"inf\"\nv1 = -1\nv2 = 0\n[physical]\nk = 1e6\nc = 1e3\nn = 1.5\np = 1.5\nalpha = 0.5\nbeta = 1e4\ngamma = 0\nA = 1\n";
    rejects(
        "seq-bodies",
        bodies,
        Some(4),
        &["[bodies]", "fixed surface"],
    );
    rejects(
        "seq-v0",
        &format!("v0 = [1.0]\n{}", drop_scene("")),
        Some(1),
        &["v0", "[sequence].h0"],
    );
}

#[test]
fn drop_tests_are_fitted_from_their_intervals() {
    // Intervals of a Hunt-Crossley contact (B_b = Γ_b = 0, σ = σ_b v): e(σ) is the root of
    // σ - ln(1+σ) = -σe - ln(1-σe); instantaneous contacts, so interval_n = 2 v_(n+1) / g.
    let hunt_crossley_e = |sigma: f64| {
        let g = |e: f64| sigma - sigma.ln_1p() + sigma * e + (-sigma * e).ln_1p();
        let (mut lo, mut hi) = (1e-12, 1.0 - 1e-12);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    let (g, sigma_b) = (9.81f64, 0.05);
    let mut csv = String::from("# synthetic\nh0,bounce_n,interval_s\n");
    for h0 in [0.3, 0.6] {
        let mut v = (2.0 * g * h0).sqrt();
        for n in 1..=3 {
            v *= hunt_crossley_e(sigma_b * v);
            csv.push_str(&format!("{h0},{n},{}\n", 2.0 * v / g));
        }
    }
    let dir = scratch("drops");
    std::fs::write(dir.join("drops.csv"), csv).unwrap();
    let config = dir.join("drops.toml");
    std::fs::write(
        &config,
        "[[fit]]\nname = \"hc\"\nmodel = \"shccm\"\ndata = \"drops.csv\"\n[fit.fixed]\nB_b = 0.0\ng = 0.0\nkappa = 0.5\nn = 1.5\np = 1.5\n[fit.bounds]\nsigma_b = [0.01, 0.1]\n[fit.params]\nB_b = 0.0\nGamma_b = 0.0\nkappa = 0.5\nsigma_b = 0.05\nn = 1.5\np = 1.5\n",
    )
    .unwrap();
    let out_dir = dir.join("out");
    let eval = json(&identify(&[
        "eval",
        config.to_str().unwrap(),
        "--json",
        "--out",
        out_dir.to_str().unwrap(),
    ]));
    let f = &eval["fits"][0];
    assert!(f["J_drop"].as_f64().unwrap() < 1e-18, "{f}");
    assert_eq!(f["J_drop_unit"], "s^2");
    assert_eq!(f["drops"].as_array().unwrap().len(), 6);
    assert!(f["J1"].is_null() && f["J2"].is_null());
    let written = std::fs::read_to_string(out_dir.join("hc_drops.csv")).unwrap();
    assert!(
        written.starts_with("h0,bounce_n,measured,model\n"),
        "{written}"
    );
    let run = json(&identify(&["run", config.to_str().unwrap(), "--json"]));
    let f = &run["fits"][0];
    assert!(
        (f["params"]["sigma_b"].as_f64().unwrap() - sigma_b).abs() < 1e-6,
        "{f}"
    );
    assert!(f["convergence"]["agreeing"].as_u64().unwrap() >= 2);
    // A drop-test fit has one cost: objectives on J1 or J2 are a mistake.
    let bad = dir.join("bad.toml");
    let text = std::fs::read_to_string(&config).unwrap();
    std::fs::write(
        &bad,
        text.replace(
            "data = \"drops.csv\"\n",
            "data = \"drops.csv\"\nobjectives = { J1 = 1.0 }\n",
        ),
    )
    .unwrap();
    let out = identify(&["run", bad.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.code() == Some(1) && err.contains(":5:") && err.contains("J_drop"),
        "{err}"
    );
}

#[test]
fn a_base_sequence_is_the_physical_one_in_other_units() {
    // The Table 4 law as base parameters of the 0.145 kg ball: the same bounces, reset and
    // carry (whose carried state is rescaled between the contacts' speeds).
    let law = bw_models::Physical {
        k: 117080063.0,
        c: 5854003.0,
        n: 1.1,
        p: 1.7,
        alpha: 0.1,
        beta: 981.05,
        gamma: -961.4,
        a: 0.925,
    };
    let params = bw_models::PhysicalParams::new(bw_models::ModelKind::Shccm, law).unwrap();
    let b = bw_models::base_params(&params, 0.145).unwrap();
    let dir = scratch("base-sequence");
    for policy in ["reset", "carry"] {
        let physical = drop_scene(&format!("bounces = 3\npolicy = \"{policy}\""));
        let base = format!(
            "model = \"shccm\"\n[sequence]\nh0 = 1.0\nbounces = 3\npolicy = \"{policy}\"\nm = 0.145\n[base]\nB_b = {:e}\nGamma_b = {:e}\nkappa = {:e}\nsigma_b = {:e}\nn = {:e}\np = {:e}\nU_b = {:e}\nT_b = {:e}\n",
            b.b_b, b.gamma_b, b.kappa, b.sigma_b, b.n, b.p, b.u_b, b.t_b
        );
        let run = |name: &str, text: &str| {
            let scene = dir.join(name);
            std::fs::write(&scene, text).unwrap();
            json(&simulate(&["run", scene.to_str().unwrap(), "--json"]))["runs"][0].clone()
        };
        let (si, nd) = (run("si.toml", &physical), run("nd.toml", &base));
        for k in 0..3 {
            for key in ["t_contact", "v_out", "t_s", "apex", "x_s"] {
                let (a, c) = (
                    si["bounces"][k][key].as_f64().unwrap(),
                    nd["bounces"][k][key].as_f64().unwrap(),
                );
                assert!(
                    (a - c).abs() <= 1e-7 * a.abs(),
                    "{policy} bounce {k} {key}: {a} vs {c}"
                );
            }
        }
    }
    rejects(
        "base-seq-mass",
        "model = \"shccm\"\n[sequence]\nh0 = 1.0\n[base]\nB_b = 1\nGamma_b = -1\nkappa = 0.5\nsigma_b = 0.1\nn = 1.5\np = 1.5\nU_b = 1\nT_b = 1\n",
        Some(2),
        &["[sequence].m", "mass"],
    );
}

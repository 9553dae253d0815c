//! `bwc-simulate`: the paper's fixtures, thread counts, outputs and bad scenes.

use super::*;

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

/// The Hunt-Crossley limit (`B = Γ = 0`, `σ = 0.5`, closed form `e_exact`) in a scratch folder, on
/// the Runge-Kutta path, run with extra keys in its `[solver]` table.
struct HuntCrossley {
    dir: Scratch,
}

impl HuntCrossley {
    const E_EXACT: f64 = 0.748434931597434;

    fn new(name: &str) -> Self {
        HuntCrossley { dir: scratch(name) }
    }

    /// The scene with `extra` in its `[solver]`, run with `--json` (or without, for the table).
    fn output(&self, extra: &str, json_out: bool) -> Output {
        let hc = "model = \"shccm\"\n[nondimensional]\nB = 0\nGamma = 0\nkappa = 0.5\nsigma = 0.5\nn = 1\np = 1.5\n";
        let scene = self.dir.join("hc.toml");
        std::fs::write(&scene, format!("{hc}[solver]\nseries = false\n{extra}")).unwrap();
        let path = scene.to_str().unwrap();
        simulate(&if json_out {
            vec!["run", path, "--json"]
        } else {
            vec!["run", path]
        })
    }

    /// The run of the scene with `extra`.
    fn run(&self, extra: &str) -> serde_json::Value {
        json(&self.output(extra, true))["runs"][0].clone()
    }
}

/// `[solver] e_tol`: by default a CoR is checked against a run at 100 times its rtol and
/// reports the difference (`e_error`); a loose `rtol` is tightened until the check meets
/// `e_tol`; `e_tol = 0` is one run at `rtol`. The Hunt-Crossley limit's closed form
/// (`σ - ln(1 + σ) = -σ e - ln(1 - σ e)`, σ = 0.5) is the reference.
#[test]
fn e_tol_checks_each_cor() {
    let hc = HuntCrossley::new("e-tol");
    let e_exact = HuntCrossley::E_EXACT;
    let checked = hc.run("");
    assert!(checked["e_error"].as_f64().unwrap() <= 1e-11, "{checked}");
    assert!(checked["rtol"].as_f64().unwrap() <= 1e-12, "{checked}");
    assert_eq!(checked["check"], "met", "{checked}");
    assert_eq!(checked["arithmetic"], "double", "{checked}");
    assert!(
        (checked["e"].as_f64().unwrap() - e_exact).abs() <= 1e-11,
        "{checked}"
    );
    let single = hc.run("e_tol = 0\n");
    assert!(single["e_error"].is_null(), "{single}");
    assert_eq!(single["check"], "off", "{single}");
    assert!(single["rhs_evals"].as_u64() < checked["rhs_evals"].as_u64());
    let loose = hc.run("rtol = 1e-5\n");
    assert!(loose["rtol"].as_f64().unwrap() < 1e-5, "{loose}");
    assert!(loose["e_error"].as_f64().unwrap() <= 1e-11, "{loose}");
    assert!(
        (loose["e"].as_f64().unwrap() - e_exact).abs() <= 1e-10,
        "{loose}"
    );
    let loose_single = hc.run("rtol = 1e-5\ne_tol = 0\n");
    assert!(
        (loose_single["e"].as_f64().unwrap() - e_exact).abs() > 1e-9,
        "{loose_single}"
    );
    // The table shows the estimate next to e.
    let table = hc.output("", false);
    let text = String::from_utf8_lossy(&table.stdout);
    let estimate = format!("{:.1e}", checked["e_error"].as_f64().unwrap());
    assert!(
        text.contains("e_error") && text.contains(&estimate),
        "{text}"
    );
}

#[test]
fn an_unmet_e_tol_says_why_and_which_setting_helps() {
    let hc = HuntCrossley::new("e-tol-unmet");
    // A target below rounding is not met, and the run says so.
    let out = hc.output("e_tol = 1e-18\n", true);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("warning")
            && err.contains("[solver].e_tol = 1e-18")
            && err.contains("rtol 1e-14"),
        "{err}"
    );
    assert_eq!(json(&out)["runs"][0]["rtol"].as_f64(), Some(1e-14));
    assert_eq!(json(&out)["runs"][0]["check"], "unmet");
    assert!(json(&out)["runs"][0]["tighter_failed"].is_null());
    // A tighter run that runs out of steps: the warning names the setting that lets it finish.
    let loose_single = hc.run("rtol = 1e-5\ne_tol = 0\n");
    let limit =
        loose_single["accepted"].as_u64().unwrap() + loose_single["rejected"].as_u64().unwrap();
    let out = hc.output(
        &format!("rtol = 1e-5\ne_tol = 1e-18\nmax_steps = {limit}\n"),
        true,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the run at rtol 1e-7 needed more than [solver].max_steps")
            && err.contains("a larger max_steps lets it finish"),
        "{err}"
    );
    let run = &json(&out)["runs"][0];
    assert_eq!(
        (run["rtol"].as_f64(), &run["check"]),
        (Some(1e-5), &"unmet".into())
    );
    assert_eq!(run["tighter_failed"]["out_of_steps"], true, "{run}");
    assert_eq!(run["tighter_failed"]["rtol"].as_f64(), Some(1e-7), "{run}");
}

#[test]
fn a_target_double_precision_cannot_check_is_met_in_double_double() {
    let hc = HuntCrossley::new("e-tol-dd");
    let precise = hc.run("e_tol = 1e-15\n");
    assert_eq!(
        (&precise["arithmetic"], &precise["check"]),
        (&"double-double".into(), &"met".into()),
        "{precise}"
    );
    assert_eq!(precise["rtol"].as_f64(), Some(1e-18), "{precise}");
    assert!(
        (precise["e"].as_f64().unwrap() - HuntCrossley::E_EXACT).abs() <= 1e-15,
        "{precise}"
    );
    let double = hc.run("e_tol = 1e-15\ndouble_double = false\n");
    assert_eq!(double["arithmetic"], "double", "{double}");
    assert!(double["rtol"].as_f64().unwrap() >= 1e-14, "{double}");
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

const GOOD_PHYSICAL: &str = concat!("model = \"shccm\"\nv0 = [1.0]\n", cross_physical!());

/// The scenes' `[physical]` table is Table 4's law of `bw_models::published`.
#[test]
fn the_physical_table_is_table_4() {
    let scene = bwc_app::impact::scene::Scene::parse(Path::new("t.toml"), GOOD_PHYSICAL).unwrap();
    let described = scene.describe().to_string();
    let l = bw_models::published::CROSS_BWSHCCM;
    for (key, value) in [
        ("k", l.k),
        ("c", l.c),
        ("beta", l.beta),
        ("gamma", l.gamma),
        ("A", l.a),
    ] {
        assert!(
            described.contains(&format!("\"{key}\":{value:?}")),
            "{key} in {described}"
        );
    }
}

/// How a bad scene is made: the good one with replacements or an appended table, or a whole
/// text.
enum Edit {
    Replace(&'static [(&'static str, &'static str)]),
    Append(&'static str),
    Whole(&'static str),
}

impl Edit {
    fn scene(&self) -> String {
        match self {
            Edit::Replace(pairs) => pairs
                .iter()
                .fold(GOOD_PHYSICAL.to_string(), |s, (from, to)| {
                    s.replace(from, to)
                }),
            Edit::Append(text) => format!("{GOOD_PHYSICAL}{text}"),
            Edit::Whole(text) => text.to_string(),
        }
    }
}

/// Bad scenes: name, how it is made, the line the error names (if any), and what it says.
type BadScene = (&'static str, Edit, Option<usize>, &'static [&'static str]);

const BAD_SCENES: &[BadScene] = &[
    ("unknown-key", Edit::Replace(&[("A = 0.925", "A = 0.925\nstiffness = 3")]), Some(13), &["stiffness"]),
    ("missing-key", Edit::Replace(&[("k = 117080063.0\n", "")]), Some(3), &["[physical].k", "missing"]),
    ("two-systems", Edit::Append("[nondimensional]\nB = 0\n"), None, &["two system descriptions"]),
    ("wrong-type", Edit::Replace(&[("n = 1.1", "n = \"one\"")]), Some(7), &["n"]),
    ("nan", Edit::Replace(&[("c = 5854003.0", "c = nan")]), Some(6), &["[physical].c", "finite"]),
    ("inf", Edit::Replace(&[("k = 117080063.0", "k = inf")]), Some(5), &["[physical].k", "finite"]),
    ("inadmissible", Edit::Replace(&[("alpha = 0.1", "alpha = 1.5")]), Some(9), &["[physical].alpha", "1.5", "0 < alpha < 1"]),
    ("gamma-range", Edit::Replace(&[("gamma = -961.4", "gamma = -2000")]), Some(11), &["[physical].gamma", "-beta <= gamma <= beta"]),
    ("negative-speed", Edit::Replace(&[("v0 = [1.0]", "v0 = [1.0, -2.0]")]), Some(2), &["v0", "-2"]),
    ("no-speeds", Edit::Replace(&[("v0 = [1.0]\n", "")]), None, &["v0", "missing"]),
    ("bad-model", Edit::Replace(&[("\"shccm\"", "\"maxwell\"")]), Some(1), &["model", "maxwell"]),
    ("bad-method", Edit::Append("[solver]\nmethod = \"euler\"\n"), Some(14), &["[solver].method", "euler", "rosenbrock"]),
    ("bad-rtol", Edit::Append("[solver]\nrtol = 0.0\n"), Some(14), &["[solver].rtol"]),
    ("e-tol", Edit::Append("[solver]\ne_tol = -1e-10\n"), Some(14), &["[solver].e_tol", "-0.0000000001", "> 0"]),
    ("not-toml", Edit::Whole("model = \n"), Some(1), &[]),
    ("empty", Edit::Whole(""), None, &["no system description"]),
    ("mcm-c-zero", Edit::Replace(&[("\"shccm\"", "\"mcm\""), ("c = 5854003.0", "c = 0.0")]), Some(6), &["[physical].c", "c > 0"]),
    ("nd-kappa", Edit::Whole("model = \"mcm\"\n[nondimensional]\nB = 1\nGamma = 0\nkappa = 1.0\nsigma = 0.1\nn = 1\np = 1\n"), Some(5), &["[nondimensional].kappa", "0 < kappa < 1"]),
    ("base-input-needs-scales", Edit::Whole("model = \"shccm\"\nv0 = [1]\n[base]\nB_b = 1\nGamma_b = 0\nkappa = 0.5\nsigma_b = 0.1\nn = 1\np = 1\n[input]\nkind = \"gravity\"\nm = 1\n"), Some(3), &["U_b"]),
    ("input-key-for-other-kind", Edit::Append("[input]\nkind = \"constant\"\nvalue = 1\nomega = 3\n"), Some(16), &["[input].omega", "does not apply"]),
    ("bodies-apart", Edit::Whole("model = \"shccm\"\n[bodies]\nm1 = 1\nm2 = \"inf\"\nv1 = 1\nv2 = 0\n[physical]\nk = 1e6\nc = 1e3\nn = 1.5\np = 1.5\nalpha = 0.5\nbeta = 1e4\ngamma = 0\nA = 1\n"), Some(5), &["v0 = v2 - v1 > 0"]),
    ("missing-file", Edit::Whole(""), None, &[]),
];

#[test]
fn bad_scenes_are_clear_errors() {
    for (name, edit, line, needles) in BAD_SCENES {
        rejects(name, &edit.scene(), *line, needles);
    }
    let out = simulate(&["run", "/nonexistent/scene.toml"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("/nonexistent/scene.toml"));
}

/// A table where a number belongs names its key at its header (it was serde's "invalid type:
/// map, expected f64", or "expected a borrowed string" at a column inside the table).
#[test]
fn a_table_where_a_value_belongs_is_named_at_its_header() {
    rejects(
        "table-for-k",
        &GOOD_PHYSICAL.replace("k = 117080063.0\n", "[physical.k]\nvalue = 1.0\n"),
        Some(5),
        &["`[physical].k` expects a number, not a table"],
    );
    rejects(
        "table-for-rtol",
        &format!("{GOOD_PHYSICAL}[solver.rtol]\nx = 1\n"),
        Some(13),
        &["`[solver].rtol` expects a value, not a table"],
    );
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
    // Undamped, 1.5 m/s separates; 1e12 m/s needs far more than 2000 Runge-Kutta steps.
    let sweep = "model = \"shccm\"\nv0 = [1.5, 1e12]\n[physical]\nm = 0.145\nk = 117080063.0\nc = 0.0\nn = 1.5\np = 1.5\nalpha = 0.5\nbeta = 1.0e4\ngamma = -5.0e3\nA = 1.0\n";
    std::fs::write(
        &scene,
        format!("{sweep}[solver]\nmax_steps = 2000\nseries = false\n"),
    )
    .unwrap();
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
    each_run_says_how_it_ended(&v);
    the_summary_says_where_it_came_from(&v);
    the_folder_holds_this_run_and_the_users_files(&out_dir);
}

/// The two runs of `each_run_stands_alone_and_the_output_says_what_it_is`: one separated and
/// checked, one failed, each with its scales.
fn each_run_says_how_it_ended(v: &serde_json::Value) {
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
}

/// Provenance: the files written, the version, the command, the scene with its defaults.
fn the_summary_says_where_it_came_from(v: &serde_json::Value) {
    let runs = v["runs"].as_array().unwrap();
    assert_eq!(v["files"], serde_json::json!(["summary.json", "sweep.csv"]));
    assert_eq!(v["version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(v["command"][1], "run");
    assert_eq!(v["scene"]["solver"]["max_steps"], 2000);
    assert_eq!(v["scene"]["solver"]["rtol"].as_f64(), Some(1e-12));
    assert_eq!(v["scene"]["solver"]["e_tol"].as_f64(), Some(1e-10));
    // A CoR at the defaults is checked against a run at rtol 1e-10 and says by how much.
    let estimate = runs[0]["e_error"].as_f64().unwrap();
    assert!(estimate <= 1e-11, "{estimate}");
    assert!(runs[0]["t_s_error"].as_f64().is_some());
    assert!(runs[0]["rtol"].as_f64().unwrap() <= 1e-12);
    assert!(runs[1]["e_error"].is_null() && runs[1]["rtol"].is_null());
    assert_eq!(v["units"]["runs"]["t_s_error"], "s");
    assert_eq!(
        v["scene"]["systems"][0]["physical"]["k"].as_f64(),
        Some(117080063.0)
    );
    assert_eq!(v["units"]["sweep.csv"]["t_s"], "s");
    assert_eq!(v["units"]["runs"]["T_c"], "s");
}

/// `sweep.csv` as written; the earlier run's trajectory gone, the user's file kept.
fn the_folder_holds_this_run_and_the_users_files(out_dir: &Path) {
    let sweep_csv = std::fs::read_to_string(out_dir.join("sweep.csv")).unwrap();
    assert!(
        sweep_csv.starts_with("v_0,e,t_d,t_s,separated,outcome,source\n"),
        "{sweep_csv}"
    );
    assert!(
        sweep_csv.contains("1000000000000,,,,false,failed,simulated"),
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

/// The double-double path under the paper's two-body scene (SI BWMCM, gravity plus the arctan
/// ramp): a target double precision cannot check is met there, and agrees with the
/// double-precision run.
#[test]
fn two_balls_meet_a_tight_target_in_double_double() {
    let dir = scratch("two-balls-dd");
    let fixture = std::fs::read_to_string(fixtures().join("two_balls_mcm.toml")).unwrap();
    let body = &fixture[..fixture.find("[output]").unwrap()];
    let scene = dir.join("scene.toml");
    let run_of = |extra: &str| {
        std::fs::write(&scene, format!("{body}[solver]\ne_tol = 1e-15\n{extra}")).unwrap();
        json(&simulate(&["run", scene.to_str().unwrap(), "--json"]))["runs"][0].clone()
    };
    let precise = run_of("");
    assert_eq!(
        (&precise["arithmetic"], &precise["check"]),
        (&"double-double".into(), &"met".into()),
        "{precise}"
    );
    let double = run_of("double_double = false\n");
    assert_eq!(double["arithmetic"], "double", "{double}");
    let (a, b) = (
        precise["e"].as_f64().unwrap(),
        double["e"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-12, "e {a} vs {b}"); // The table says which runs are double-double.
    std::fs::write(&scene, format!("{body}[solver]\ne_tol = 1e-15\n")).unwrap();
    let text =
        String::from_utf8_lossy(&simulate(&["run", scene.to_str().unwrap()]).stdout).into_owned();
    assert!(
        text.contains("double-double arithmetic") && text.contains("v0 = 2 m/s"),
        "{text}"
    );
}

/// Case 5523 of the stress sweep's seed 3 (STABILITY.md, "Double-double"): its double-precision
/// runs go stiff and agree to only 1.2e-10, and the double-double retry is not tried there.
/// The output says so, and `e` is within the estimate of the reference 0.127578645362
/// (Verner's 9(8), Verner's 7(6) and DOP853 at rtol 3e-15).
#[test]
fn a_stiff_unmet_cor_says_why_double_double_was_not_tried() {
    let dir = scratch("stiff-unmet");
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        "model = \"mcm\"\nv0 = [506.91324093318553]\n[base]\nB_b = 35.85524463149488\n\
         Gamma_b = -35.85524463149488\nkappa = 0.2754451940192927\n\
         sigma_b = 0.012827185718774515\nn = 10\np = 5.367702693104487\n",
    )
    .unwrap();
    let out = simulate(&["run", scene.to_str().unwrap(), "--json"]);
    let run = json(&out)["runs"][0].clone();
    assert_eq!(
        (&run["check"], &run["arithmetic"]),
        (&"unmet".into(), &"double".into()),
        "{run}"
    );
    let why = run["double_double_declined"].as_str().unwrap();
    assert!(
        why.starts_with("was not tried") && why.contains("RODAS4"),
        "{why}"
    );
    let (e, estimate) = (run["e"].as_f64().unwrap(), run["e_error"].as_f64().unwrap());
    assert!((e - 0.127578645362).abs() < estimate, "{run}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the double-double retry ([solver] double_double) was not tried"),
        "{err}"
    );
    // Where the check is met, the key is null.
    let settled = dir.join("settled.toml");
    std::fs::write(
        &settled,
        std::fs::read_to_string(&scene)
            .unwrap()
            .replace("506.91324093318553", "1"),
    )
    .unwrap();
    let run = json(&simulate(&["run", settled.to_str().unwrap(), "--json"]))["runs"][0].clone();
    assert_eq!(run["check"], "met", "{run}");
    assert!(run["double_double_declined"].is_null(), "{run}");
}

/// `[solver] phase = true`: the Hunt-Crossley scene's CoR comes from the phase path (the JSON
/// says so, with no steps), matches the closed form and the default run, and a forced scene
/// keeps the usual path.
#[test]
fn the_phase_path_where_solver_asks_for_it() {
    let dir = scratch("phase");
    let hc = "model = \"shccm\"\n[nondimensional]\nB = 0\nGamma = 0\nkappa = 0.5\nsigma = 0.5\nn = 1\np = 1.5\n";
    let scene = dir.join("hc.toml");
    let run_of = |text: &str| {
        std::fs::write(&scene, text).unwrap();
        json(&simulate(&["run", scene.to_str().unwrap(), "--json"]))["runs"][0].clone()
    };
    let phase = run_of(&format!("{hc}[solver]\nphase = true\n"));
    let usual = run_of(hc);
    assert_eq!(
        (&phase["phase"], &usual["phase"]),
        (&true.into(), &false.into())
    );
    assert_eq!(
        (&phase["check"], &phase["rhs_evals"]),
        (&"met".into(), &0.into()),
        "{phase}"
    );
    let e = phase["e"].as_f64().unwrap();
    assert!((e - 0.748434931597434).abs() < 1e-10, "{phase}");
    assert!(
        (e - usual["e"].as_f64().unwrap()).abs() < 1e-10,
        "{phase} {usual}"
    );
    assert!(phase["e_error"].as_f64().unwrap() <= 1e-10, "{phase}");
    let forced = run_of(&format!("{hc}U = 0.1\n[solver]\nphase = true\n"));
    assert_eq!(forced["phase"], false, "{forced}");
}

/// Values the models admit but whose magnitude suggests another unit: the run runs, and a
/// warning names the likely slip and the fix.
#[test]
fn unit_slips_get_a_hint_and_the_run_still_runs() {
    let dir = scratch("unit-slips");
    let law = "n = 1.5\np = 1.5\nalpha = 0.5\nbeta = 1.0e3\ngamma = -1.0e3\nA = 1.0\nc = 100.0\n";
    let scene = dir.join("slips.toml");
    let cases = [
        // mm/s meant, grams meant
        (
            "v0 = [2150, 3030]",
            "m = 145\nk = 1.0e9",
            &[
                "divide by 1000 (3.03 m/s)",
                "if grams were meant, divide by 1000 (0.145 kg)",
            ][..],
        ),
        // N/mm^p or kN/m^p meant
        (
            "v0 = [2.0]",
            "m = 0.145\nk = 50.0",
            &["`[physical].k` = 50 N/m^1.5 is softer"][..],
        ),
    ];
    for (v0, mk, needles) in cases {
        std::fs::write(
            &scene,
            format!("model = \"shccm\"\n{v0}\n[physical]\n{mk}\n{law}"),
        )
        .unwrap();
        let out = simulate(&["run", scene.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "{err}");
        for n in needles {
            assert!(err.contains(n), "{n:?} not in {err}");
        }
    }
    // Plausible values: no hint.
    std::fs::write(
        &scene,
        format!("model = \"shccm\"\nv0 = [2.0]\n[physical]\nm = 0.145\nk = 1.0e9\n{law}"),
    )
    .unwrap();
    let out = simulate(&["run", scene.to_str().unwrap()]);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("warning"));
}

/// `[output].dt` is in seconds in an SI scene: one that samples a 1.3 ms contact 3 times says
/// so, with the unit and a `dt` that samples it well; a fine `dt` draws no warning.
#[test]
fn a_dt_that_undersamples_the_contact_says_so() {
    let dir = scratch("coarse-dt");
    let scene = |dt: &str| {
        let path = dir.join(format!("dt-{dt}.toml"));
        std::fs::write(
            &path,
            format!(
                concat!(
                    "model = \"shccm\"\nv0 = [2.15]\n",
                    cross_physical!(),
                    "[output]\ntrajectory = true\ndt = {dt}\n"
                ),
                dt = dt
            ),
        )
        .unwrap();
        simulate_to(&path, &dir.join(dt))
    };
    let err = scene("0.001");
    assert!(
        err.contains("[output].dt = 1e-3 s samples the contact")
            && err.contains("dt is in seconds in an SI or [base] scene"),
        "{err}"
    );
    let csv = std::fs::read_to_string(dir.join("0.001").join("trajectory.csv")).unwrap();
    assert!(csv.starts_with("t,x,v,u,F,z\n"), "{csv}");
    assert!(!scene("1e-5").contains("samples the contact"));
}

/// `[output.figures.NAME]` gives a figure its own title, axis labels and line style; an unknown
/// figure or style is an error naming the table and what is admissible.
#[test]
fn a_scene_gives_its_figures_their_titles_labels_and_styles() {
    let dir = scratch("figure-labels");
    let law = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/src/tutorial/first-cor.toml"),
    )
    .unwrap();
    let text = format!(
        "{law}\n[output.figures.cor]\ntitle = \"Baseball on a floor\"\nx_label = \"v (m/s)\"\n\
         y_label = \"CoR\"\nstyle = \"markers\"\n"
    );
    let path = dir.join("labels.toml");
    std::fs::write(&path, &text).unwrap();
    let out_dir = dir.join("out");
    simulate_to(&path, &out_dir);
    let svg = std::fs::read_to_string(out_dir.join("cor.svg")).unwrap();
    for words in ["Baseball on a floor", ">v (m/s)<", ">CoR<"] {
        assert!(
            svg.replace(['\n', ' '], "")
                .contains(&words.replace(' ', "")),
            "{words}"
        );
    }
    assert!(!svg.contains("Coefficient of restitution"));
    // Markers only: the model's line and its legend key are gone (the mesh's lines remain).
    let plain = dir.join("plain.toml");
    std::fs::write(&plain, &law).unwrap();
    let plain_out = dir.join("plain");
    simulate_to(&plain, &plain_out);
    let default = std::fs::read_to_string(plain_out.join("cor.svg")).unwrap();
    let lines = |svg: &str| svg.matches("<polyline").count();
    assert_eq!(lines(&svg) + 2, lines(&default), "markers only");
    // The other figures keep their own titles.
    let loops = std::fs::read_to_string(out_dir.join("loops.svg")).unwrap();
    assert!(loops.contains("Force-compression loops"));
    rejects(
        "figure-name",
        &format!("{law}\n[output.figures.corr]\ntitle = \"x\"\n"),
        None,
        &[
            "[output.figures.corr]",
            "not a figure: one of cor, duration, loops",
        ],
    );
    rejects(
        "figure-style",
        &format!("{law}\n[output.figures.cor]\nstyle = \"dots\"\n"),
        None,
        &["[output.figures.cor].style", "\"dots\" is not a style"],
    );
}

/// `sweep.csv` of a scene of several systems has every column its `units` name, with `name`,
/// and no other.
#[test]
fn every_sweep_column_has_its_unit() {
    let dir = scratch("sweep-units");
    let out_dir = dir.join("out");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/kharaz_curves.toml");
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
    let header: Vec<&str> = sweep.lines().next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "v_0",
            "e",
            "t_d",
            "t_s",
            "separated",
            "name",
            "outcome",
            "source"
        ]
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("summary.json")).unwrap())
            .unwrap();
    let units = summary["units"]["sweep.csv"].as_object().unwrap();
    let mut named: Vec<&str> = units.keys().map(String::as_str).collect();
    let mut columns = header.clone();
    named.sort_unstable();
    columns.sort_unstable();
    assert_eq!(named, columns);
    assert_eq!(units["t_s"], "nondimensional");
}

//! `bwc-identify`: evaluations, fits, warnings, coverage studies and bad configs.

use super::*;

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

/// The known NDBWSHCCM of the synthetic datasets: `κ = 0.6`, `σ_b = 0.03`, the rest fixed.
fn synthetic_truth() -> bw_models::BaseMap {
    use bw_models::{BaseMap, BaseParams, ModelKind};
    // The identification tests' synthetic truth (`bwc-identify`'s tests/support/band_design.rs).
    let truth = BaseParams::unforced(1.0, -1.0, 0.6, 0.03, 1.5, 1.5);
    BaseMap::new(ModelKind::Shccm, truth).unwrap()
}

/// Writes a synthetic dataset of a known NDBWSHCCM and a config that frees κ and σ_b.
fn synthetic_config(dir: &Path) -> PathBuf {
    use bw_models::{impact_at, input::Zero, Settings};
    let map = synthetic_truth();
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

/// The mean squared difference in `e` between the synthetic truth's CoR and that of `kappa`
/// (all else as the truth) at the synthetic speeds: `J1` of a reference, computed here
/// independently of `bwc-identify`.
fn j1_against_truth(kappa: f64) -> f64 {
    use bw_models::{impact_at, input::Zero, BaseMap, BaseParams, ModelKind, Settings};
    let at = |kappa: f64, v0: f64| {
        let p = BaseParams {
            b_b: 1.0,
            gamma_b: -1.0,
            kappa,
            sigma_b: 0.03,
            n: 1.5,
            p: 1.5,
            u_b: 1.0,
            t_b: 1.0,
        };
        let map = BaseMap::new(ModelKind::Shccm, p).unwrap();
        impact_at(&map, Zero, v0, &Settings::default()).unwrap().e
    };
    let speeds = [0.2, 0.5, 1.0, 2.0, 4.0];
    speeds
        .iter()
        .map(|&v| (at(0.6, v) - at(kappa, v)).powi(2))
        .sum::<f64>()
        / speeds.len() as f64
}

/// The reference table of the synthetic fit: the truth but for `kappa`, named `label`.
fn with_reference(config: &Path, kappa: f64, label: &str) {
    let mut text = std::fs::read_to_string(config).unwrap();
    text += &format!(
        "[fit.reference]\nlabel = \"{label}\"\nB_b = 1.0\nGamma_b = -1.0\nkappa = {kappa}\n\
         sigma_b = 0.03\nn = 1.5\np = 1.5\n"
    );
    std::fs::write(config, text).unwrap();
}

#[test]
fn identify_run_reports_the_reference_beside_the_fit() {
    let dir = scratch("identify-reference");
    let config = synthetic_config(&dir);
    with_reference(&config, 0.5, "kappa off by 0.1");
    let out_dir = dir.join("out");
    let out = identify(&[
        "run",
        config.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("The reference (kappa off by 0.1) has J1 ="),
        "{text}"
    );
    assert!(
        text.contains("the fit reproduces these data better"),
        "{text}"
    );
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out_dir.join("summary.json")).unwrap()).unwrap();
    let r = &v["fits"][0]["reference"];
    assert_eq!(r["label"], "kappa off by 0.1");
    assert_eq!(r["params"]["kappa"], 0.5);
    assert_eq!(r["standing"], "fit_lower");
    // The reference's cost is the truth's distance from it, to the solver's accuracy.
    let (j1, expected) = (r["J1"].as_f64().unwrap(), j1_against_truth(0.5));
    assert!(
        (j1 - expected).abs() < 1e-6 * expected,
        "{j1} vs {expected}"
    );
    let ratio = r["cost_ratio"].as_f64().unwrap();
    assert!(
        (ratio - j1 / v["fits"][0]["J1"].as_f64().unwrap()).abs() < 1e-9 * ratio,
        "{r}"
    );
    // kappa and sigma_b are both determined by five noise-free speeds.
    assert_eq!(r["weak_directions"], 0);
    assert_eq!(r["directions"], 2);
    assert_eq!(
        v["config"]["fit"][0]["reference"]["label"],
        "kappa off by 0.1"
    );
    let svg = std::fs::read_to_string(out_dir.join("synthetic_cor.svg")).unwrap();
    assert!(svg.contains("reference: kappa off by 0.1"));
}

#[test]
fn a_reference_outside_the_bounds_that_fits_better_is_a_warning() {
    let dir = scratch("identify-reference-outside");
    let config = synthetic_config(&dir);
    // The truth itself, with kappa's bounds excluding it.
    let text = std::fs::read_to_string(&config)
        .unwrap()
        .replace("kappa = [0.1, 0.9]", "kappa = [0.1, 0.5]");
    std::fs::write(&config, text).unwrap();
    with_reference(&config, 0.6, "the truth");
    let v = json(&identify(&["run", config.to_str().unwrap(), "--json"]));
    let f = &v["fits"][0];
    assert_eq!(f["reference"]["standing"], "reference_lower", "{f}");
    assert_eq!(
        f["reference"]["outside_bounds"],
        serde_json::json!(["kappa"])
    );
    let warnings = f["warnings"].to_string();
    assert!(
        warnings.contains("outside [fit.bounds] in kappa; widen them"),
        "{warnings}"
    );
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

const GOOD_DATA: &str = "v_0,e\n0.5,0.9\n1.0,0.8\n";
const HEAD: &str = "[[fit]]\nname = \"f\"\nmodel = \"shccm\"\ndata = \"d.csv\"\n";
const BOUNDS: &str = "[fit.bounds]\nB_b = [0.0, 2.0]\ng = [-1.0, 1.0]\nkappa = [0.1, 0.9]\nsigma_b = [0.0, 0.1]\nn = [1.0, 2.0]\np = [1.0, 2.0]\n";

#[test]
fn bad_identification_data_are_clear_errors() {
    let good = format!("{HEAD}{BOUNDS}");
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
    // An empty file is the data's error, not the objectives'.
    identify_rejects(
        "empty-file",
        &good,
        Some(""),
        &["d.csv:1: no header", "`v_0`"],
    );
    // Columns under other names: the names a dataset needs, and the renames.
    identify_rejects(
        "other-names",
        &good,
        Some("v0,cor\n0.5,0.9\n1.0,0.8\n"),
        &["d.csv:1", "rename `v0` to `v_0`, `cor` to `e`"],
    );
    // CoRs in percent: one error, not a fit.
    let percent: String = (1..=24)
        .map(|i| format!("{},{}\n", 0.1 * i as f64, 90 - i))
        .collect();
    let dir_err = {
        let dir = scratch("bad-identify-percent");
        std::fs::write(dir.join("d.csv"), format!("v_0,e\n{percent}")).unwrap();
        let path = dir.join("c.toml");
        std::fs::write(&path, &good).unwrap();
        let out = identify(&["run", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(1));
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    assert!(
        dir_err.contains("d.csv:2") && dir_err.contains("look like percent"),
        "{dir_err}"
    );
    assert_eq!(dir_err.matches("above 1").count(), 1, "{dir_err}");
}

/// Missing bounds are named together, and a reversed bound is not hidden behind them.
#[test]
fn missing_and_reversed_bounds_are_reported_together() {
    let config = format!("{HEAD}[fit.bounds]\nkappa = [0.1, 0.9]\nsigma_b = [0.0, 0.1]\n");
    identify_rejects(
        "missing-bounds",
        &config,
        Some(GOOD_DATA),
        &["missing B_b, g, n, p: give each bounds"],
    );
    let config = format!("{HEAD}[fit.bounds]\nkappa = [0.9, 0.1]\nsigma_b = [0.0, 0.1]\n");
    identify_rejects(
        "reversed-bound",
        &config,
        Some(GOOD_DATA),
        &[
            "c.toml:6",
            "[fit.bounds].kappa",
            "[0.9, 0.1] is not admissible",
        ],
    );
}

#[test]
fn bad_identification_configs_are_clear_errors() {
    let (head, bounds, good_data) = (HEAD, BOUNDS, GOOD_DATA);
    let good = format!("{head}{bounds}");
    identify_rejects(
        "label-of-a-start",
        &format!(
            "{good}[fit.start]\nlabel = \"x\"\nB_b = 1.0\nGamma_b = -1.0\nkappa = 0.5\n\
             sigma_b = 0.01\nn = 1.5\np = 1.5\n"
        ),
        Some(good_data),
        &[
            "c.toml:13",
            "[fit.start].label",
            "only [fit.reference] and [fit.params]",
        ],
    );
    // An unknown model name hides neither the other mistakes nor is it reported as missing.
    let typo = good
        .replace("model = \"shccm\"", "model = \"shcm\"")
        .replace("n = [1.0, 2.0]", "n = [6.0, 1.0]");
    identify_rejects(
        "typo-and-swapped-bounds",
        &typo,
        Some(good_data),
        &[
            "2 mistakes",
            "c.toml:3: `[[fit]].model`: \"shcm\" is not a model",
            "c.toml:10: `[fit.bounds].n`",
        ],
    );
    let dir = scratch("typo-alone");
    std::fs::write(dir.join("d.csv"), good_data).unwrap();
    std::fs::write(dir.join("c.toml"), &typo).unwrap();
    let out = identify(&["run", dir.join("c.toml").to_str().unwrap()]);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("missing required key"));
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

/// A comparison law's parameter on a bound is named with its own value and bound (its slot
/// among the Bouc-Wen quantities is not `B_b`'s): the tennis data want more damping than
/// Hunt-Crossley's `alpha <= 0.01 s/m`.
#[test]
fn a_comparison_law_on_a_bound_is_reported_with_its_own_value() {
    let dir = scratch("identify-family-bound");
    let config = dir.join("fit.toml");
    let data = fixtures().join("data/real/tennis_v0_e.csv");
    std::fs::write(
        &config,
        format!(
            "[[fit]]\nname = \"HC\"\nmodel = \"hunt-crossley\"\ndata = \"{}\"\n\
             [fit.bounds]\nalpha = [0.0, 0.01]\n",
            data.display()
        ),
    )
    .unwrap();
    let out = identify(&["run", config.to_str().unwrap(), "--json"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr
            .contains("\"HC\": alpha = 0.01 is on its upper bound 0.01: widen [fit.bounds].alpha"),
        "{stderr}"
    );
    assert_eq!(
        json(&out)["fits"][0]["at_bound"],
        serde_json::json!(["alpha"])
    );
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

/// A mass in grams where kilograms are asked for: a warning naming the slip, and the fit runs.
#[test]
fn a_mass_in_grams_gets_a_hint() {
    let dir = scratch("identify-grams");
    let data = fixtures().join("data/real/golf_intervals.csv");
    let config = dir.join("c.toml");
    std::fs::write(
        &config,
        format!(
            "[[fit]]\nname = \"golf\"\nmodel = \"shccm\"\ndata = {data:?}\n[fit.bounds]\n\
             kappa = [0.1, 0.9]\n[fit.fixed]\nB_b = 1.0\ng = -1.0\nsigma_b = 0.01\nn = 1.5\n\
             p = 1.5\n[fit.sequence]\nm = 41.5\n[fit.params]\nB_b = 1.0\nGamma_b = -1.0\n\
             kappa = 0.5\nsigma_b = 0.01\nn = 1.5\np = 1.5\n"
        ),
    )
    .unwrap();
    let out = identify(&["eval", config.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        err.contains("`[fit.sequence].m` = 41.5 kg is heavier") && err.contains("(0.0415 kg)"),
        "{err}"
    );
}

#[test]
fn identify_posterior_reports_its_contract_on_any_thread_count() {
    let dir = scratch("identify-posterior");
    let config = synthetic_config(&dir);
    let out_dir = dir.join("out");
    let run = |threads: &str, out: Option<&Path>| {
        let mut args = vec![
            "posterior",
            config.to_str().unwrap(),
            "--json",
            "--particles",
            "64",
            "--runs",
            "2",
            "--threads",
            threads,
        ];
        if let Some(o) = out {
            args.extend(["--out", o.to_str().unwrap()]);
        }
        let mut v = json(&identify(&args));
        v["posteriors"][0]["wall_s"] = serde_json::Value::Null;
        v["command"] = serde_json::Value::Null;
        v
    };
    let (one, two) = (run("1", None), run("2", Some(&out_dir)));
    assert_eq!(one, two);
    let p = &one["posteriors"][0];
    for key in [
        "log_evidence",
        "log_evidence_error",
        "run_log_evidence",
        "evaluations",
        "particles",
        "runs",
        "ess",
        "noise",
        "prior",
        "marginals",
        "band",
        "stages",
    ] {
        assert!(p.get(key).is_some(), "missing {key}");
    }
    // Noise-free data: the CoR's noise scale is sampled (no e_std column) and sits at the
    // bottom of its range; κ's credible interval holds the truth, 0.6.
    let kappa = &p["marginals"]["kappa"];
    assert!(kappa["lo"].as_f64().unwrap() <= 0.6 && 0.6 <= kappa["hi"].as_f64().unwrap());
    assert!(p["marginals"]["sigma_e"]["median"].as_f64().unwrap() < 1e-2);
    assert!(p["log_evidence_error"].as_f64().unwrap().is_finite());
    let csv = std::fs::read_to_string(out_dir.join("synthetic_posterior.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "run,weight,log_likelihood,B_b,Gamma_b,kappa,sigma_b,n,p,U_b,T_b,sigma_e"
    );
    assert_eq!(csv.lines().count(), 1 + 128);
    let band = std::fs::read_to_string(out_dir.join("synthetic_posterior_band.csv")).unwrap();
    assert_eq!(
        band.lines().next().unwrap(),
        "v_0,e,e_lo,e_hi,e_new_lo,e_new_hi,t_d,t_d_lo,t_d_hi,t_d_new_lo,t_d_new_hi"
    );
    for f in [
        "synthetic_posterior_cor.svg",
        "synthetic_corner.svg",
        "summary.json",
    ] {
        assert!(out_dir.join(f).exists(), "{f}");
    }
}

#[test]
fn a_posterior_of_data_it_cannot_use_is_a_clear_error_and_writes_nothing() {
    let cases = [
        ("one point", "v_0,e\n1.0,0.8\n", "at least 2"),
        (
            "zero noise",
            "v_0,e,e_std\n0.5,0.9,0.01\n1.0,0.8,0\n",
            "d.csv:3: column `e_std`: 0 is not a noise scale",
        ),
    ];
    for (name, data, needle) in cases {
        let dir = scratch(&format!("posterior-{}", name.replace(' ', "-")));
        std::fs::write(dir.join("d.csv"), data).unwrap();
        let path = dir.join("c.toml");
        std::fs::write(&path, format!("{HEAD}{BOUNDS}")).unwrap();
        let out_dir = dir.join("out");
        let out = identify(&[
            "posterior",
            path.to_str().unwrap(),
            "--out",
            out_dir.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {err}");
        assert!(err.contains(needle), "{name}: {needle:?} not in {err}");
        let written = std::fs::read_dir(&out_dir).map_or(0, |d| d.count());
        assert_eq!(written, 0, "{name}: output written");
    }
}

#[test]
fn compare_names_the_law_that_made_the_data() {
    // Synthetic CoRs of a Hunt-Crossley law (alpha = 0.3 s/m) at eight speeds, with noise of
    // 0.005 in e_std: the Hunt-Crossley family against Kelvin-Voigt, whose CoR does not depend
    // on the speed.
    use bw_models::{family_impact, Family, FamilyParams, Settings};
    let dir = scratch("compare");
    let law = FamilyParams {
        family: Family::HuntCrossley,
        param: 0.3,
        t_b: 1.0,
    };
    let mut csv = String::from("v_0,e,e_std\n");
    let noise = [0.004, -0.003, 0.001, -0.005, 0.002, 0.0, -0.002, 0.003];
    for (i, v0) in [0.2, 0.4, 0.6, 0.9, 1.2, 1.6, 2.0, 2.5]
        .into_iter()
        .enumerate()
    {
        let e = family_impact(&law, v0, &Settings::default()).unwrap().e;
        csv += &format!("{v0},{},0.005\n", e + noise[i]);
    }
    std::fs::write(dir.join("hc.csv"), csv).unwrap();
    let config = dir.join("laws.toml");
    std::fs::write(
        &config,
        "[[fit]]\nname = \"HC\"\nmodel = \"hunt-crossley\"\ndata = \"hc.csv\"\n\
         [[fit]]\nname = \"KV\"\nmodel = \"kelvin-voigt\"\ndata = \"hc.csv\"\n",
    )
    .unwrap();
    let v = json(&identify(&[
        "compare",
        config.to_str().unwrap(),
        "--json",
        "--folds",
        "4",
        "--particles",
        "64",
        "--runs",
        "2",
    ]));
    let group = &v["comparisons"][0];
    let models = group["models"].as_array().unwrap();
    assert_eq!(models.len(), 2);
    let (hc, kv) = (&models[0], &models[1]);
    for key in [
        "cost",
        "AIC",
        "BIC",
        "log_evidence",
        "log_evidence_error",
        "cv_rmse",
    ] {
        assert!(hc[key].as_f64().is_some(), "missing {key}");
    }
    let f = |m: &serde_json::Value, k: &str| m[k].as_f64().unwrap();
    assert!(f(hc, "BIC") < f(kv, "BIC") && f(hc, "cv_rmse") < f(kv, "cv_rmse"));
    assert!(f(hc, "log_evidence") > f(kv, "log_evidence") + 5.0);
    let sentence = group["supported"].as_str().unwrap();
    assert!(
        sentence.starts_with("the evidence supports \"HC\" (hunt-crossley) decisively"),
        "{sentence}"
    );
}

#[test]
fn family_fits_recover_their_damping_and_name_wrong_keys() {
    let dir = scratch("family-keys");
    std::fs::write(dir.join("d.csv"), GOOD_DATA).unwrap();
    let bad = [
        (
            "[[fit]]\nname = \"f\"\nmodel = \"hunt-crossley\"\ndata = \"d.csv\"\n[fit.bounds]\nkappa = [0.1, 0.9]\n",
            "[fit.bounds].kappa",
        ),
        (
            "[[fit]]\nname = \"f\"\nmodel = \"shccm\"\ndata = \"d.csv\"\n[fit.bounds]\nalpha = [0.0, 1.0]\n",
            "[fit.bounds].alpha",
        ),
        (
            "[[fit]]\nname = \"f\"\nmodel = \"hooke\"\ndata = \"d.csv\"\n",
            "\"hertz-flores\"",
        ),
        (
            "[[fit]]\nname = \"f\"\nmodel = \"kelvin-voigt\"\ndata = \"d.csv\"\n[fit.input]\nkind = \"constant\"\nvalue = 1.0\n",
            "[fit.input]",
        ),
        (
            "[[fit]]\nname = \"f\"\nmodel = \"hertz-ln\"\ndata = \"d.csv\"\n[fit.bounds]\ne_r = [0.0, 1.0]\n",
            "0 < e_r <= 1",
        ),
    ];
    for (i, (text, needle)) in bad.into_iter().enumerate() {
        let path = dir.join(format!("c{i}.toml"));
        std::fs::write(&path, text).unwrap();
        let out = identify(&["run", path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{i}: {err}");
        assert!(err.contains(needle), "{i}: {needle:?} not in {err}");
    }
    // A Flores fit of data made by its own law gives its e_r back.
    use bw_models::{family_impact, Family, FamilyParams, Settings};
    let law = FamilyParams {
        family: Family::HertzFlores,
        param: 0.7,
        t_b: 1.0,
    };
    let e = family_impact(&law, 1.0, &Settings::default()).unwrap().e;
    std::fs::write(dir.join("f.csv"), format!("v_0,e\n0.5,{e}\n2.0,{e}\n")).unwrap();
    let path = dir.join("flores.toml");
    std::fs::write(
        &path,
        "[[fit]]\nname = \"f\"\nmodel = \"hertz-flores\"\ndata = \"f.csv\"\n",
    )
    .unwrap();
    let v = json(&identify(&["run", path.to_str().unwrap(), "--json"]));
    let e_r = v["fits"][0]["params"]["e_r"].as_f64().unwrap();
    assert!((e_r - 0.7).abs() < 1e-6, "e_r {e_r}");
    assert_eq!(v["fits"][0]["model"], "hertz-flores");
}

/// A Thornton fit of CoRs and durations its own law made (yield speed 0.2 m/s, `T_b` of a
/// 10 g body on 1e9 N/m^1.5) gives both back, each under its own name in the JSON, and the
/// printed report names `v_y`; its default bounds are searched on a log scale.
#[test]
fn a_thornton_fit_recovers_its_yield_speed_and_time_scale() {
    use bw_models::{family_impact, Family, FamilyParams, Settings};
    let dir = scratch("thornton");
    let law = FamilyParams {
        family: Family::Thornton,
        param: 0.2,
        t_b: (0.01f64 / 1e9).powf(0.4),
    };
    let mut csv = String::from("v_0,e,t_d\n");
    for v0 in [0.5, 1.0, 2.0, 4.0] {
        let out = family_impact(&law, v0, &Settings::default()).unwrap();
        let t_d = out.t_s.unwrap() * law.time_scale(v0);
        csv += &format!("{v0},{},{t_d}\n", out.e);
    }
    std::fs::write(dir.join("t.csv"), csv).unwrap();
    let path = dir.join("thornton.toml");
    std::fs::write(
        &path,
        "[[fit]]\nname = \"t\"\nmodel = \"thornton\"\ndata = \"t.csv\"\n\
         [fit.objectives]\nJ1 = 1.0\nJ2 = 1.0\n[fit.bounds]\nT_b = [1e-5, 1e-3]\n",
    )
    .unwrap();
    let v = json(&identify(&["run", path.to_str().unwrap(), "--json"]));
    let p = &v["fits"][0]["params"];
    let v_y = p["v_y"].as_f64().unwrap();
    let t_b = p["T_b"].as_f64().unwrap();
    assert!((v_y - 0.2).abs() < 1e-5, "v_y {v_y}");
    assert!(
        (t_b / law.t_b - 1.0).abs() < 1e-5,
        "T_b {t_b} vs {}",
        law.t_b
    );
    assert!(p.get("sigma_b").is_none(), "{p}");
    let out = identify(&["run", path.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && text.contains("v_y = 2.0000"),
        "{text}"
    );
}

/// A Thornton fit of noisy CoRs (yield speed 0.2 m/s, noise of about 0.003) reports the
/// interval of `v_y` around its estimate, in m/s (the parameter is looked up by its slot, not
/// by a name list that knew only the older families), and its coverage study's truth as `v_y`.
#[test]
fn a_family_parameters_interval_and_unit_are_its_own() {
    use bw_models::{family_impact, Family, FamilyParams, Settings};
    let dir = scratch("thornton-interval");
    let law = FamilyParams {
        family: Family::Thornton,
        param: 0.2,
        t_b: 1.0,
    };
    let noise = [0.004, -0.003, 0.002, -0.001, 0.003, -0.004];
    let mut csv = String::from("v_0,e\n");
    for (v0, z) in [0.5, 0.8, 1.2, 2.0, 3.0, 4.5].into_iter().zip(noise) {
        let e = family_impact(&law, v0, &Settings::default()).unwrap().e;
        csv += &format!("{v0},{}\n", e + z);
    }
    std::fs::write(dir.join("t.csv"), csv).unwrap();
    let path = dir.join("t.toml");
    std::fs::write(
        &path,
        "[[fit]]\nname = \"t\"\nmodel = \"thornton\"\ndata = \"t.csv\"\n",
    )
    .unwrap();
    let v = json(&identify(&["run", path.to_str().unwrap(), "--json"]));
    let f = &v["fits"][0];
    let v_y = f["params"]["v_y"].as_f64().unwrap();
    let iv = &f["intervals"]["params"]["v_y"];
    let (lo, hi) = (iv[0].as_f64().unwrap(), iv[1].as_f64().unwrap());
    assert!(
        lo < v_y && v_y < hi && lo > 0.18 && hi < 0.22,
        "{v_y} in [{lo}, {hi}]"
    );
    assert_eq!(v["units"]["params"]["v_y"], "m/s");
    // A coverage study of the fit names its truth as the family does.
    let args = [
        "coverage",
        path.to_str().unwrap(),
        "--json",
        "--replicates",
        "2",
    ];
    let c = json(&identify(&args));
    let truth = &c["coverage"][0]["truth"];
    assert_eq!(truth.as_object().unwrap().len(), 1, "{truth}");
    assert_eq!(truth["v_y"].as_f64(), Some(v_y));
}

/// A family's Pareto front names its columns as the family does (`e_r`, `T_b`), with their
/// units, not the Bouc-Wen vector whose `sigma_b` slot holds the parameter.
#[test]
fn a_family_pareto_front_has_the_familys_columns() {
    use bw_models::{family_impact, Family, FamilyParams, Settings};
    let dir = scratch("flores-pareto");
    let law = FamilyParams {
        family: Family::HertzFlores,
        param: 0.7,
        t_b: 1e-3,
    };
    let mut csv = String::from("v_0,e,t_d\n");
    for v0 in [0.5, 1.0, 2.0] {
        let out = family_impact(&law, v0, &Settings::default()).unwrap();
        csv += &format!("{v0},{},{}\n", out.e, out.t_s.unwrap() * law.time_scale(v0));
    }
    std::fs::write(dir.join("f.csv"), csv).unwrap();
    let path = dir.join("f.toml");
    std::fs::write(
        &path,
        "[[fit]]\nname = \"f\"\nmodel = \"hertz-flores\"\ndata = \"f.csv\"\n\
         [fit.objectives]\nJ1 = 1.0\nJ2 = 1.0\n[fit.bounds]\nT_b = [1e-4, 1e-2]\n\
         [fit.pareto]\ncount = 3\n",
    )
    .unwrap();
    let out_dir = dir.join("out");
    let v = json(&identify(&[
        "run",
        path.to_str().unwrap(),
        "--json",
        "--out",
        out_dir.to_str().unwrap(),
    ]));
    let front = std::fs::read_to_string(out_dir.join("f_pareto.csv")).unwrap();
    assert_eq!(front.lines().next(), Some("w,J1,J2,e_r,T_b"), "{front}");
    let row: Vec<f64> = (front.lines().nth(1).unwrap().split(','))
        .map(|x| x.parse().unwrap())
        .collect();
    assert!(
        (row[3] - 0.7).abs() < 1e-3 && (row[4] / 1e-3 - 1.0).abs() < 1e-3,
        "{row:?}"
    );
    assert_eq!(v["units"]["<fit>_pareto.csv"]["e_r"], "1");
}

/// A fit's reported noise level is the residual standard deviation of its own CSV:
/// `sqrt(Σ (e - e_model)² / dof)`, computed here from `<fit>.csv` and the JSON's `dof`, and near
/// the noise the data were drawn with.
#[test]
fn a_fits_sigma_is_the_residual_standard_deviation_of_its_csv() {
    use bw_models::{impact_at, input::Zero, Settings};
    let dir = scratch("identify-sigma");
    let map = synthetic_truth();
    // 24 speeds with fixed pseudo-random noise of standard deviation near 6e-3.
    let noise = [
        0.9, -1.2, 0.3, 1.5, -0.4, -0.8, 1.1, -1.6, 0.2, 0.7, -1.0, 1.3, -0.2, 0.5, -1.4, 0.8,
        -0.6, 1.0, -0.9, 0.1, 1.2, -1.1, 0.6, -0.3,
    ];
    let mut csv = String::from("v_0,e\n");
    for (i, z) in noise.iter().enumerate() {
        let v0 = 0.2 * 1.15f64.powi(i as i32);
        let e = impact_at(&map, Zero, v0, &Settings::default()).unwrap().e;
        csv += &format!("{v0},{}\n", e + 6e-3 * z);
    }
    std::fs::write(dir.join("noisy.csv"), csv).unwrap();
    let config = dir.join("fit.toml");
    std::fs::write(
        &config,
        "[[fit]]\nname = \"noisy\"\nmodel = \"shccm\"\ndata = \"noisy.csv\"\n[fit.bounds]\nkappa = [0.1, 0.9]\nsigma_b = [0.0, 0.1]\n\
         [fit.fixed]\nB_b = 1.0\ng = -1.0\nn = 1.5\np = 1.5\n[fit.optimizer]\nparticles = 8\niterations = 10\npolish = 300\nstarts = 2\n",
    )
    .unwrap();
    let out_dir = dir.join("out");
    let v = json(&identify(&[
        "run",
        config.to_str().unwrap(),
        "--json",
        "--out",
        out_dir.to_str().unwrap(),
    ]));
    let iv = &v["fits"][0]["intervals"];
    let dof = iv["dof"].as_u64().unwrap() as f64;
    assert_eq!(dof, 22.0, "{iv}");
    let text = std::fs::read_to_string(out_dir.join("noisy.csv")).unwrap();
    let rss: f64 = text
        .lines()
        .skip(1)
        .map(|row| {
            let v: Vec<f64> = row
                .split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect();
            (v[1] - v[2]).powi(2)
        })
        .sum();
    let expected = (rss / dof).sqrt();
    let sigma_e = iv["sigma_e"].as_f64().unwrap();
    assert!(
        (sigma_e / expected - 1.0).abs() < 1e-4,
        "{sigma_e} against {expected}"
    );
    assert_eq!(iv["sigma"], iv["sigma_e"]);
    assert!(iv["sigma_t_d"].is_null());
    // The noise drawn: 6e-3 times the pattern's root mean square (0.92).
    assert!(sigma_e > 4e-3 && sigma_e < 8e-3, "{sigma_e}");
}

/// `bwc-identify materials`: one JSON object with the derived quantities, the laws and the CoR
/// table, and a text report with units; a bad file exits non-zero naming its key.
#[test]
fn materials_prints_the_law_from_materials() {
    let file = fixtures().join("alumina_on_aluminium.toml");
    let file = file.to_str().unwrap();
    let out = identify(&["materials", file, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["derived"]["yields_first"], 2);
    assert_eq!(v["bodies"][0]["material"], "alumina");
    let thornton = &v["laws"]["thornton"];
    assert_eq!(thornton["element"]["law"], "thornton");
    let v_y = thornton["family"]["v_y"].as_f64().unwrap();
    assert!((v_y - v["derived"]["v_y"].as_f64().unwrap()).abs() == 0.0);
    let rows = v["cor"].as_array().unwrap();
    assert_eq!(rows.len(), 12);
    let e: Vec<f64> = rows.iter().map(|r| r["e"].as_f64().unwrap()).collect();
    assert!(
        e.windows(2).all(|w| w[1] < w[0]),
        "e falls with speed: {e:?}"
    );
    let text = identify(&["materials", file]);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("N/m^(3/2)") && text.contains("first in body 2"),
        "{text}"
    );

    let dir = scratch("materials-bad");
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[materials.body1]\nmaterial = \"steel\"\n").unwrap();
    let out = identify(&["materials", bad.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && out.stdout.is_empty());
    assert!(
        err.contains("bad.toml:2") && err.contains("steel-aisi-1045"),
        "{err}"
    );
}

/// `bwc-identify materials --fit`: the BWSHCCM fitted to Thornton's law from materials
/// follows its CoR and duration, and its SI law (with the pair's mass), simulated in SI
/// units, rebounds at Thornton's closed form.
#[test]
fn materials_fit_gives_a_bouc_wen_law_that_follows_the_reference() {
    use bw_models::{impact, input::Zero, Bwshccm, ModelKind, Physical, PhysicalParams, Settings};
    let dir = scratch("materials-fit");
    let file = fixtures().join("alumina_on_aluminium.toml");
    let out_dir = dir.join("out");
    let out = identify(&[
        "materials",
        file.to_str().unwrap(),
        "--fit",
        "--out",
        out_dir.to_str().unwrap(),
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(out_dir.join("reference.csv").exists() && out_dir.join("fit.toml").exists());
    let fits = v["fits"].as_array().unwrap();
    assert_eq!(fits.len(), 2);
    let shccm = &fits[0];
    assert_eq!(shccm["model"], "shccm");
    let (de, dt) = (
        shccm["e_error"].as_f64().unwrap(),
        shccm["t_d_error"].as_f64().unwrap(),
    );
    assert!(de < 0.01 && dt < 0.01, "{de} {dt}");
    let si = &shccm["SI"];
    let m = si["m"].as_f64().unwrap();
    assert!((m / v["derived"]["m_star"].as_f64().unwrap() - 1.0).abs() < 1e-12);
    let num = |k: &str| si[k].as_f64().unwrap();
    let law = Physical {
        k: num("k"),
        c: num("c"),
        n: num("n"),
        p: num("p"),
        alpha: num("alpha"),
        beta: num("beta"),
        gamma: num("gamma"),
        a: num("A"),
    };
    let params = PhysicalParams::new(ModelKind::Shccm, law).unwrap();
    let (v0, v_y) = (1.0, v["derived"]["v_y"].as_f64().unwrap());
    let model = Bwshccm::new(&params, m, v0, Zero).unwrap();
    let e = impact(&model, &Settings::default()).unwrap().cor().e;
    let r = v_y / v0;
    let thornton = (6.0 * 3f64.sqrt() / 5.0).sqrt()
        * (1.0 - r * r / 6.0).sqrt()
        * (r / (r + 2.0 * (1.2 - 0.2 * r * r).sqrt())).powf(0.25);
    assert!(
        (e - thornton).abs() < de + 1e-9,
        "SI law e {e} vs Thornton {thornton}"
    );
}

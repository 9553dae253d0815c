//! Impact sequences and drop tests.

use super::*;

/// The Table 4 baseball contact law dropped from 1 m: `[sequence]` with the given extra keys.
fn drop_scene(extra: &str) -> String {
    format!(
        concat!(
            "model = \"shccm\"\n[sequence]\nh0 = 1.0\n{extra}\n",
            cross_physical!()
        ),
        extra = extra
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
    let params = bw_models::published::cross(bw_models::ModelKind::Shccm);
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

//! `[chain]` scenes: bodies on a line with a law per pair.

use super::*;

/// The chain form of the paper's application example (`fixtures/two_balls_*.toml`): ball 2 on
/// the left with its arctan push, ball 1 on the right under gravity, touching at `t = 0`.
fn two_balls_chain(model: &str, physical: &str) -> String {
    format!(
        "model = \"{model}\"\n[chain]\nhorizon = 0.05\n\
         [[chain.body]]\nmass = 0.5235987755982988\nvelocity = 1.5\nlength = 0.1\n\
         [chain.body.input]\nkind = \"arctan\"\nD = 250.0\nomega = 1000.0\n\
         [[chain.body]]\nmass = 1.5707963267948966\nvelocity = -0.5\nlength = 0.1\ngap = 0.0\n\
         [chain.body.input]\nkind = \"gravity\"\ng = 9.81\n\
         [solver]\nrtol = 1e-12\natol = 1e-17\n{physical}"
    )
}

/// The `[physical]` table of a fixture.
fn physical_of(fixture: &str) -> String {
    let text = std::fs::read_to_string(fixtures().join(fixture)).unwrap();
    let start = text.find("[physical]").unwrap();
    let end = text[start..]
        .find("\n[output]")
        .map_or(text.len(), |e| start + e);
    text[start..end].to_string()
}

/// Two bodies as a chain are the `[bodies]` scene: its contact's rebound ratio and duration are
/// the scene's `e` and `t_s` to 1e-9, for both models.
#[test]
fn two_bodies_as_a_chain_are_the_bodies_scene() {
    let dir = scratch("chain-two");
    for (model, fixture) in [
        ("shccm", "two_balls_shccm.toml"),
        ("mcm", "two_balls_mcm.toml"),
    ] {
        let reference = json(&simulate(&[
            "run",
            fixtures().join(fixture).to_str().unwrap(),
            "--json",
        ]));
        let run = &reference["runs"][0];
        let (e, t_s) = (run["e"].as_f64().unwrap(), run["t_s"].as_f64().unwrap());
        let scene = dir.join(format!("{model}.toml"));
        std::fs::write(&scene, two_balls_chain(model, &physical_of(fixture))).unwrap();
        let v = json(&simulate(&["run", scene.to_str().unwrap(), "--json"]));
        let contact = &v["chain"]["contacts"][0];
        let rebound = contact["rebound"].as_f64().unwrap();
        let separation = contact["separation_s"].as_f64().unwrap();
        assert_eq!(contact["onset_s"].as_f64(), Some(0.0), "{model}");
        assert!((rebound - e).abs() <= 1e-9, "{model}: {rebound} vs {e}");
        assert!(
            (separation - t_s).abs() <= 1e-9 * t_s,
            "{model}: {separation} vs {t_s}"
        );
    }
}

/// A law in base parameters is the one under which its pair, alone, has the CoR and duration
/// of `P*`: two bodies (0.3 and 0.2 kg, closing at 1.5 m/s) with `[base]` rebound as the
/// `[base]` scene at `v0 = 1.5` with `U_b = T_b / m` (m the pair's effective mass), to 1e-9,
/// for both models, from `[base]` and from `[[chain.pair]]` alike.
#[test]
fn a_law_in_base_parameters_has_its_cor_in_the_chain() {
    let dir = scratch("chain-base");
    let p_star = "B_b = 0.5\nGamma_b = -0.2\nkappa = 0.5\nsigma_b = 0.1\nn = 1.5\np = 1.5\n";
    let (t_b, m) = (0.002, 0.3 * 0.2 / (0.3 + 0.2));
    for model in ["shccm", "mcm"] {
        let reference = dir.join(format!("{model}-reference.toml"));
        std::fs::write(
            &reference,
            format!(
                "model = \"{model}\"\nv0 = [1.5]\n[base]\n{p_star}U_b = {}\nT_b = {t_b}\n",
                t_b / m
            ),
        )
        .unwrap();
        let v = json(&simulate(&["run", reference.to_str().unwrap(), "--json"]));
        let run = &v["runs"][0];
        let (e, t_s) = (run["e"].as_f64().unwrap(), run["t_s"].as_f64().unwrap());
        let bodies = "[chain]\nmass = [0.3, 0.2]\nvelocity = [1.0, -0.5]\nlength = 0.1\n\
                      gap = [0.0]\nhorizon = 1.0\n[solver]\nrtol = 1e-12\natol = 1e-17\n";
        for law in [
            format!("[base]\n{p_star}T_b = {t_b}\n"),
            format!("[[chain.pair]]\nmodel = \"{model}\"\n{p_star}T_b = {t_b}\n"),
        ] {
            let scene = dir.join(format!("{model}.toml"));
            std::fs::write(&scene, format!("model = \"{model}\"\n{bodies}{law}")).unwrap();
            let v = json(&simulate(&["run", scene.to_str().unwrap(), "--json"]));
            let contact = &v["chain"]["contacts"][0];
            let rebound = contact["rebound"].as_f64().unwrap();
            let duration = contact["separation_s"].as_f64().unwrap();
            assert!((rebound - e).abs() <= 1e-9, "{model}: {rebound} vs {e}");
            assert!(
                (duration - t_s).abs() <= 1e-9 * t_s,
                "{model}: {duration} vs {t_s}"
            );
        }
    }
}

/// The fixtures run and write what they promise: the summary, `contacts.csv`, `chain.csv` with a
/// row every `dt` and a column per body and pair, and both figures; the cradle conserves its
/// momentum and its ledger closes.
#[test]
fn the_chain_fixtures_run_and_write_their_files() {
    for (name, bodies, pairs) in [
        ("newtons_cradle", 5, 4),
        ("ball_stack", 3, 3),
        ("granular_chain", 40, 39),
    ] {
        let dir = scratch(&format!("chain-{name}"));
        let out_dir = dir.join("out");
        let path = fixtures().join(format!("{name}.toml"));
        let v = json(&simulate(&[
            "run",
            path.to_str().unwrap(),
            "--json",
            "--out",
            out_dir.to_str().unwrap(),
        ]));
        let chain = &v["chain"];
        assert_eq!(chain["bodies"].as_array().unwrap().len(), bodies, "{name}");
        let ledger = &chain["ledger"];
        let f = |k: &str| ledger[k].as_f64().unwrap();
        let scale = f("initial_J") + f("work_J").abs();
        assert!(f("imbalance_J").abs() <= 1e-8 * scale, "{name}: {ledger}");
        let files: Vec<&str> = v["files"]
            .as_array()
            .map_or(vec![], |a| a.iter().filter_map(|f| f.as_str()).collect());
        let written = std::fs::read_to_string(out_dir.join("summary.json")).unwrap();
        let summary: serde_json::Value = serde_json::from_str(&written).unwrap();
        assert!(files.is_empty() || files.contains(&"chain.csv"));
        for file in [
            "contacts.csv",
            "chain.csv",
            "chain_space_time.svg",
            "chain_velocities.svg",
            "chain_ledger.svg",
        ] {
            assert!(out_dir.join(file).exists(), "{name}: {file}");
            assert!(
                summary["files"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .any(|f| f == file),
                "{name}: {file} not listed"
            );
        }
        let csv = std::fs::read_to_string(out_dir.join("chain.csv")).unwrap();
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        assert_eq!(header.len(), 1 + 2 * bodies + 2 * pairs + 4, "{name}");
        assert_eq!(header[0], "t_s");
        assert!(header.contains(&"kinetic_J") && header.contains(&"F_0_N"));
    }
    // The cradle: no inputs, no walls; its momentum is the striker's.
    let v = json(&simulate(&[
        "run",
        fixtures().join("newtons_cradle.toml").to_str().unwrap(),
        "--json",
    ]));
    let p = v["chain"]["momentum_kg_m_s"].as_f64().unwrap();
    assert!((p - 0.0642).abs() <= 1e-12 * 0.0642, "{p}");
}

/// Bad chains: an error naming the line, the key and the body or pair; nothing written.
#[test]
fn bad_chains_are_rejected_with_the_body_or_pair() {
    let law = "[physical]\nk = 1e7\nc = 0.0\nn = 1.0\np = 1.5\nalpha = 0.5\nbeta = 0.0\ngamma = 0.0\nA = 1.0\n";
    let scene = |chain: &str| format!("model = \"shccm\"\n[chain]\nhorizon = 0.01\n{chain}\n{law}");
    rejects(
        "chain-overlap",
        &scene(
            "mass = 0.1\nposition = [0.0, 0.015, 0.04]\nlength = 0.02\nvelocity = [1.0, 0.0, 0.0]",
        ),
        None,
        &["pair 0", "overlap"],
    );
    rejects(
        "chain-one",
        &scene("mass = [0.1]\nposition = [0.0]\nvelocity = [1.0]"),
        None,
        &["one body"],
    );
    rejects(
        "chain-wall-velocity",
        &scene("mass = [\"inf\", 0.1]\nposition = [0.0, 0.1]\nvelocity = [0.5, -1.0]"),
        None,
        &["body 0", "velocity", "wall"],
    );
    rejects(
        "chain-zero-mass",
        &scene("mass = [0.1, 0.0]\nposition = [0.0, 0.1]\nvelocity = [1.0, 0.0]"),
        None,
        &["body 1", "mass"],
    );
    let pairs = "model = \"shccm\"\n[chain]\nhorizon = 0.01\nmass = 0.1\n\
                 position = [0.0, 0.1, 0.2]\nvelocity = [1.0, 0.0, 0.0]\n\
                 [[chain.pair]]\nk = 1e7\nc = 0.0\nn = 1.0\np = 1.5\nalpha = 0.5\nbeta = 0.0\n\
                 gamma = 0.0\nA = 1.0\n";
    rejects(
        "chain-pairs",
        pairs,
        None,
        &["[[chain.pair]]", "1 laws for 2 pairs"],
    );
    rejects(
        "chain-list-length",
        &scene("mass = [0.1, 0.1]\nposition = [0.0, 0.1, 0.2]\nvelocity = [1.0, 0.0]"),
        Some(5),
        &["[chain].position", "3 values for 2 bodies"],
    );
    let two = "model = \"shccm\"\n[chain]\nhorizon = 0.01\nmass = 0.1\n\
               position = [0.0, 0.1]\nvelocity = [1.0, 0.0]\n";
    let p_star = "B_b = 0.5\nGamma_b = 0.0\nkappa = 0.5\nsigma_b = 0.1\nn = 1.0\np = 1.5\n";
    rejects(
        "chain-base-u",
        &format!("{two}[base]\n{p_star}U_b = 2.0\n"),
        Some(14),
        &["[base].U_b", "effective mass"],
    );
    rejects(
        "chain-pair-both-forms",
        &format!("{two}[[chain.pair]]\n{p_star}k = 1e7\n"),
        Some(7),
        &["[[chain.pair]] 0", "give one form"],
    );
    rejects(
        "chain-base-kappa",
        &format!(
            "{two}[base]\n{}",
            p_star.replace("kappa = 0.5", "kappa = 1.5")
        ),
        Some(10),
        &["[base].kappa", "0 < kappa < 1"],
    );
}

/// A chain scene's one mistake is reported once, at its key's line, with no second error made
/// by the reader's own stand-in for it (a mass of "inf" makes a wall that must not move).
#[test]
fn a_chain_mistake_is_named_once_at_its_key() {
    let law = "[physical]\nk = 1e7\nc = 0.0\nn = 1.0\np = 1.5\nalpha = 0.5\nbeta = 0.0\ngamma = 0.0\nA = 1.0\n";
    let scene = |chain: &str| format!("model = \"shccm\"\n[chain]\nhorizon = 0.01\n{chain}\n{law}");
    let once = |name: &str, text: &str, line: usize, needles: &[&str]| {
        rejects(name, text, Some(line), needles);
        let dir = scratch(&format!("once-{name}"));
        let path = dir.join("s.toml");
        std::fs::write(&path, text).unwrap();
        let err = String::from_utf8_lossy(&simulate(&["run", path.to_str().unwrap()]).stderr)
            .into_owned();
        assert_eq!(err.lines().count(), 1, "{name}: {err}");
    };
    let gaps = "velocity = [1.0, 0.0]\nlength = 0.01\n";
    once(
        "chain-heavy",
        &scene(&format!("mass = \"heavy\"\ngap = 0.001\n{gaps}")),
        4,
        &["\"heavy\"", "a mass in kg or \"inf\""],
    );
    once(
        "chain-heavy-list",
        &scene(&format!("mass = [\"heavy\", 0.1]\ngap = 0.001\n{gaps}")),
        4,
        &["\"heavy\""],
    );
    once(
        "chain-empty-mass",
        &scene("mass = []\ngap = 0.001\n"),
        4,
        &["[chain].mass", "an empty list"],
    );
    once(
        "chain-negative-gap",
        &scene(&format!("mass = 0.1\ngap = -0.001\n{gaps}")),
        5,
        &["[chain].gap", "-0.001 is not admissible", "gap >= 0"],
    );
    once(
        "chain-nan-gap",
        &scene(&format!("mass = 0.1\ngap = nan\n{gaps}")),
        5,
        &["[chain].gap", "NaN is not admissible"],
    );
    once(
        "chain-nan-in-a-list",
        &scene("mass = 0.1\ngap = 0.001\nvelocity = [1.0, nan]\n"),
        6,
        &["[chain].velocity", "body 1: NaN"],
    );
    once(
        "chain-duplicate-key",
        &scene(&format!("mass = 0.1\ngap = 0.001\n{gaps}horizon = 0.02\n")),
        8,
        &["duplicate key `horizon`"],
    );
    once(
        "chain-rtol",
        &format!(
            "{}[solver]\nrtol = 1e-20\n",
            scene(&format!("mass = 0.1\ngap = 0.001\n{gaps}"))
        ),
        19,
        &[
            "[solver].rtol",
            "1e-20 is not admissible: finite and > 2.2e-16",
        ],
    );
    let body = "[[chain.body]]\nmass = 0.1\nvelocity = 1.0\ninput = { kind = \"wobble\" }\n\
                [[chain.body]]\nmass = 0.1\ngap = 0.001\n";
    once(
        "chain-input-kind",
        &format!("model = \"shccm\"\n[chain]\nhorizon = 0.01\n{body}{law}"),
        7,
        &["input.kind", "\"wobble\" is not an input kind"],
    );
}

/// The granular chain's touching beads: a pair that begins touching at rest has no rebound
/// ratio (null, with the reason) and its contact's onset at 0 s; the summary carries the
/// units of its keys and the scene it ran (tolerances included).
#[test]
fn touching_pairs_at_rest_have_no_rebound_ratio_and_the_summary_says_its_units() {
    let v = json(&simulate(&[
        "run",
        fixtures().join("granular_chain.toml").to_str().unwrap(),
        "--json",
    ]));
    let contacts = v["chain"]["contacts"].as_array().unwrap();
    assert!(contacts.len() > 30, "{}", contacts.len());
    for c in contacts {
        let onset_v = c["onset_velocity_m_s"].as_f64().unwrap();
        if c["began_at_rest"] == true {
            assert_eq!(c["rebound"], serde_json::Value::Null, "{c}");
            assert!(
                c["rebound_note"]
                    .as_str()
                    .unwrap()
                    .contains("began at rest"),
                "{c}"
            );
            assert_eq!(c["onset_s"], 0.0, "{c}");
            assert_eq!(onset_v, 0.0, "{c}");
        } else {
            // The struck bead's pair approaches at 0.5 m/s.
            assert!(onset_v < -1e-3, "{c}");
        }
        if let Some(r) = c["rebound"].as_f64() {
            assert!((0.0..=1.0 + 1e-9).contains(&r), "{c}");
        }
    }
    let units = &v["units"]["chain"]["contacts"];
    for key in contacts[0].as_object().unwrap().keys() {
        assert!(units.get(key).is_some(), "no unit for contacts' {key}");
    }
    for key in v["chain"].as_object().unwrap().keys() {
        assert!(
            v["units"]["chain"].get(key).is_some()
                || ["outcome", "policy", "models"].contains(&key.as_str()),
            "no unit for {key}"
        );
    }
    assert_eq!(v["scene"]["solver"]["rtol"], 1e-10, "{}", v["scene"]);
    assert_eq!(v["scene"]["bodies"], 40);
}

/// An elastic cradle whose balls drift apart (and together) at the rounding level of the
/// speeds settles once the last contact ends, instead of running to the horizon.
#[test]
fn an_elastic_cradle_settles_despite_rounding_drift() {
    let dir = scratch("elastic-cradle");
    let text = std::fs::read_to_string(fixtures().join("newtons_cradle.toml"))
        .unwrap()
        .replace("beta = 2.0e5", "beta = 0.0")
        .replace("gamma = -1.0e5", "gamma = 0.0")
        .replace("until = \"horizon\"", "until = \"settled\"")
        .replace("horizon = 0.001", "horizon = 10.0");
    let path = dir.join("cradle.toml");
    std::fs::write(&path, text).unwrap();
    let v = json(&simulate(&["run", path.to_str().unwrap(), "--json"]));
    assert_eq!(v["chain"]["outcome"], "settled", "{}", v["chain"]);
    assert!(v["chain"]["t_end_s"].as_f64().unwrap() < 1e-3);
    let last = &v["chain"]["bodies"][4];
    assert!((last["velocity_m_s"].as_f64().unwrap() - 1.0).abs() < 1e-9);
}

/// A chain's law by name (`[chain.law]`, `[[chain.pair]] law = {...}`): two equal balls, one
/// at rest, the other meeting it at 1 m/s, Thornton's law between them; the rebound ratio is
/// his closed form at `r = v_y / v`, `(5/4) (m/2) v_y² = k δ_y^(5/2)`. Mistakes name the key.
#[test]
fn a_chain_law_by_name_rebounds_at_its_closed_form() {
    let (m, k, r) = (0.01f64, 1e9f64, 0.2f64);
    let delta_y = (1.25 * 0.5 * m * r * r / k).powf(0.4);
    let chain = format!(
        "[chain]\nhorizon = 1e-3\nmass = {m}\nposition = [0.0, 0.01]\nlength = 0.01\n\
         velocity = [1.0, 0.0]\n[solver]\nrtol = 1e-12\natol = 1e-17\n"
    );
    let want = (6.0 * 3f64.sqrt() / 5.0).sqrt()
        * (1.0 - r * r / 6.0).sqrt()
        * (r / (r + 2.0 * (1.2 - 0.2 * r * r).sqrt())).powf(0.25);
    let dir = scratch("chain-named");
    let law = format!("model = \"thornton\", k = {k:?}, delta_y = {delta_y:?}");
    for (name, laws) in [
        ("all", format!("[chain.law]\n{}\n", law.replace(", ", "\n"))),
        ("pair", format!("[[chain.pair]]\nlaw = {{ {law} }}\n")),
    ] {
        let scene = dir.join(format!("{name}.toml"));
        std::fs::write(&scene, format!("{chain}{laws}")).unwrap();
        let v = json(&simulate(&["run", scene.to_str().unwrap(), "--json"]));
        let rebound = v["chain"]["contacts"][0]["rebound"].as_f64().unwrap();
        assert!((rebound - want).abs() < 1e-8, "{name}: {rebound} vs {want}");
        assert_eq!(v["scene"]["models"][0], "thornton", "{name}");
    }
    rejects(
        "chain-law-unknown",
        &format!("{chain}[chain.law]\nmodel = \"hertz\"\nk = 1e9\n"),
        Some(11),
        &["[chain.law].model", "`hertz`", "thornton"],
    );
    rejects(
        "chain-law-missing",
        &format!("{chain}[chain.law]\nmodel = \"thornton\"\nk = 1e9\n"),
        Some(10),
        &["[chain.law].delta_y", "is missing", "k, delta_y"],
    );
    rejects(
        "chain-law-bad",
        &format!("{chain}[chain.law]\nmodel = \"thornton\"\nk = 1e9\ndelta_y = -1.0\n"),
        Some(13),
        &["[chain.law].delta_y", "delta_y > 0 (m)"],
    );
}

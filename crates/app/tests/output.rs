//! Summaries: the JSON written run by run is the JSON tree's text; every key of a run has its
//! unit in `"units"` and its line in the outputs reference.

use bwc_app::impact::output::{units, Summary};
use bwc_app::impact::scene::Scene;
use serde_json::Value;
use std::collections::BTreeSet;

/// Scenes whose runs fill every key of a run between them: a sequence with its bounces, a
/// settled and a separated run under an input (`rest` filled and null), a failed run (`error`,
/// null results), and a sweep served by an interpolant (`interpolation` filled).
const SCENES: [&str; 4] = [
    "model = \"shccm\"\n[sequence]\nh0 = 1.0\nbounces = 3\n[physical]\nm = 0.145\n\
     k = 117080063.0\nc = 5854003.0\nn = 1.1\np = 1.7\nalpha = 0.1\nbeta = 981.05\n\
     gamma = -961.4\nA = 0.925\n",
    "model = \"shccm\"\nv0 = [0.5, 2.0]\n[base]\nB_b = 0.966\nGamma_b = -0.966\n\
     kappa = 0.531\nsigma_b = 0.3\nn = 1.57\np = 1.75\nU_b = 1.0\nT_b = 1.0\n\
     [input]\nkind = \"constant\"\nvalue = -0.5\n",
    "model = \"shccm\"\nv0 = [1.0]\n[base]\nB_b = 2.38\nGamma_b = -2.38\nkappa = 0.677\n\
     sigma_b = 0.0348\nn = 2.93\np = 2.62\n[solver]\nmax_steps = 2\nseries = false\n",
    "model = \"shccm\"\nv0 = { from = 0.5, to = 5.0, count = 200 }\n[base]\nB_b = 0.0\n\
     Gamma_b = 0.0\nkappa = 0.5\nsigma_b = 0.3\nn = 1.0\np = 1.5\n",
];

/// The JSON text written run by run is the text of the tree, byte for byte, for each of
/// [`SCENES`].
#[test]
fn provenance_json_is_the_tree_as_text() {
    let mut outcomes = Vec::new();
    let mut interpolated = 0;
    for text in SCENES {
        let scene = Scene::parse(std::path::Path::new("test.toml"), text).unwrap();
        let runs = bwc_app::impact::simulate::run(&scene, None);
        outcomes.extend(runs.iter().map(|r| (r.outcome.name(), r.bounces.len())));
        interpolated += runs.iter().filter(|r| r.interpolation.is_some()).count();
        let summary = Summary::new(&runs, scene.sequence.is_some());
        // The tree built key by key, sorted as serde_json's maps are.
        let mut tree = bwc_app::outdir::provenance("bwc-simulate");
        tree["runs"] = serde_json::to_value(&summary.runs).unwrap();
        let unit = bwc_app::impact::simulate::Tally::of(&scene, &runs).time_unit();
        tree["units"] = units(&scene, unit);
        tree["scene"] = scene.describe();
        assert_eq!(
            summary.provenance_json(&scene, &runs),
            tree.to_string(),
            "{text}"
        );
    }
    for want in ["separated", "settled", "failed"] {
        assert!(outcomes.iter().any(|(o, _)| *o == want), "{outcomes:?}");
    }
    assert!(interpolated > 150, "{interpolated}");
    assert!(outcomes[0].1 >= 2, "{outcomes:?}");
}

/// The runs of each of [`SCENES`] as JSON, with the scene's `"units"`.
fn runs_and_units() -> Vec<(Value, Value)> {
    SCENES
        .iter()
        .map(|text| {
            let scene = Scene::parse(std::path::Path::new("test.toml"), text).unwrap();
            let runs = bwc_app::impact::simulate::run(&scene, None);
            let summary = Summary::new(&runs, scene.sequence.is_some());
            let unit = bwc_app::impact::simulate::Tally::of(&scene, &runs).time_unit();
            let json = serde_json::to_value(&summary.runs).unwrap();
            (json, units(&scene, unit))
        })
        .collect()
}

/// The key paths of `v`'s objects, `prefix` first: an array's paths are its elements'.
fn paths(v: &Value, prefix: &str, into: &mut BTreeSet<String>) {
    match v {
        Value::Object(map) => {
            for (k, x) in map {
                let path = format!("{prefix}{k}");
                into.insert(path.clone());
                paths(x, &format!("{path}."), into);
            }
        }
        Value::Array(items) => items.iter().for_each(|x| paths(x, prefix, into)),
        _ => {}
    }
}

/// Every key of every run of [`SCENES`], nested ones included, has its unit in `"units"`
/// (a unit given for an object holds for its entries), and every unit names a key a run has.
#[test]
fn every_key_of_a_run_has_its_unit_and_every_unit_its_key() {
    let (mut keys, mut unit_keys, mut covering) = (BTreeSet::new(), BTreeSet::new(), Vec::new());
    for (runs, units) in runs_and_units() {
        paths(&runs, "", &mut keys);
        let map = &units["runs"];
        paths(map, "", &mut unit_keys);
        for (k, v) in map.as_object().unwrap() {
            if v.is_string() {
                covering.push(k.clone());
            }
        }
    }
    let uncovered: Vec<&String> = keys
        .iter()
        .filter(|k| !unit_keys.contains(*k))
        .filter(|k| !covering.iter().any(|c| k.starts_with(&format!("{c}."))))
        .collect();
    assert!(uncovered.is_empty(), "keys without a unit: {uncovered:?}");
    // `tighter_failed` is filled only by a tighter run that failed, which these scenes avoid.
    let unused: Vec<&String> = unit_keys
        .iter()
        .filter(|k| !keys.contains(*k) && !k.starts_with("tighter_failed."))
        .collect();
    assert!(unused.is_empty(), "units of no key: {unused:?}");
}

/// The outputs reference's table of a run's keys names exactly the keys of the list a run's
/// JSON is made from, and the runs of [`SCENES`] have exactly those keys between them.
#[test]
fn the_reference_lists_every_key_of_a_run() {
    let page = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/src/reference/outputs.md"
    ))
    .unwrap();
    let table = page
        .split("### A run")
        .nth(1)
        .and_then(|t| t.split("\n\n").nth(1))
        .expect("outputs.md has a section \"A run\" with a table");
    let listed: BTreeSet<String> = table
        .lines()
        .skip(2)
        .filter_map(|row| row.split('|').nth(1))
        .flat_map(|cell| cell.split('`').skip(1).step_by(2).map(String::from))
        .collect();
    let mut keys = BTreeSet::new();
    for (runs, _) in runs_and_units() {
        for run in runs.as_array().unwrap() {
            keys.extend(run.as_object().unwrap().keys().cloned());
        }
    }
    let list: BTreeSet<String> = bwc_app::impact::output::RUN_KEYS
        .iter()
        .map(|k| k.to_string())
        .collect();
    assert_eq!(listed, list);
    assert_eq!(keys, list);
}

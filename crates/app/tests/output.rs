//! Summaries: the JSON written run by run is the JSON tree's text.

use bwc_app::output::{units, Summary};
use bwc_app::scene::Scene;

/// The JSON text written run by run is the text of the tree, byte for byte: a sequence with its bounces, a settled and a separated run under an input (`rest`
/// filled and null), a failed run (`error`, null results), and a sweep served by an
/// interpolant (`interpolation` filled).
#[test]
fn provenance_json_is_the_tree_as_text() {
    let scenes = [
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
    let mut outcomes = Vec::new();
    let mut interpolated = 0;
    for text in scenes {
        let scene = Scene::parse(std::path::Path::new("test.toml"), text).unwrap();
        let runs = bwc_app::simulate::run(&scene, None);
        outcomes.extend(runs.iter().map(|r| (r.outcome.name(), r.bounces.len())));
        interpolated += runs.iter().filter(|r| r.interpolation.is_some()).count();
        let summary = Summary::new(&runs, scene.sequence.is_some());
        // The tree built key by key, sorted as serde_json's maps are.
        let mut tree = bwc_app::outdir::provenance("bwc-simulate");
        tree["runs"] = serde_json::to_value(&summary.runs).unwrap();
        let unit = bwc_app::simulate::Tally::of(&scene, &runs).time_unit();
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

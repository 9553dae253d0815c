//! Scene files: speed ranges and arrays of base parameters.

use bw_models::ModelKind;
use bwc_app::impact::scene::Scene;
use std::path::Path;

const BASE: &str = "model = \"shccm\"\n[[base]]\nB_b = 1\nGamma_b = 0\nkappa = 0.5\nsigma_b = 0.1\nn = 1\np = 1\n[[base]]\nname = \"second\"\nmodel = \"mcm\"\nB_b = 1\nGamma_b = 0\nkappa = 0.5\nsigma_b = 0.1\nn = 1\np = 1\n";

#[test]
fn speed_ranges_and_base_arrays() {
    let log = Scene::parse(
        Path::new("s.toml"),
        &format!("v0 = {{ from = 0.1, to = 10.0, count = 3, spacing = \"log\" }}\n{BASE}"),
    )
    .unwrap();
    assert_eq!(log.speeds.len(), 3);
    assert!(
        (log.speeds[1] - 1.0).abs() < 1e-15
            && log.speeds[0] == 0.1
            && (log.speeds[2] - 10.0).abs() < 1e-14
    );
    let lin = Scene::parse(
        Path::new("s.toml"),
        &format!("v0 = {{ from = 1, to = 3, count = 3 }}\n{BASE}"),
    )
    .unwrap();
    assert_eq!(lin.speeds, vec![1.0, 2.0, 3.0]);
    assert_eq!(lin.systems.len(), 2);
    assert_eq!(lin.systems[0].kind, ModelKind::Shccm);
    assert_eq!(lin.systems[1].kind, ModelKind::Mcm);
    assert_eq!(lin.systems[1].name.as_deref(), Some("second"));
    let e = Scene::parse(
        Path::new("s.toml"),
        &format!("v0 = {{ from = 1, to = 3, count = 0 }}\n{BASE}"),
    )
    .unwrap_err();
    assert!(e.to_string().contains("v0.count"), "{e}");
}

/// `fixtures/cross_shccm.toml` and `fixtures/cross_mcm.toml` are the laws of
/// `bw_models::published` (Table 4), with its mass.
#[test]
fn the_cross_fixtures_are_table_4() {
    use bw_models::published::{cross_law, CROSS_MASS};
    for (file, kind) in [
        ("cross_shccm.toml", ModelKind::Shccm),
        ("cross_mcm.toml", ModelKind::Mcm),
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../fixtures")
            .join(file);
        let scene = Scene::parse(&path, &std::fs::read_to_string(&path).unwrap()).unwrap();
        let physical = &scene.describe()["systems"][0]["physical"];
        let l = cross_law(kind);
        let want = [
            ("m", CROSS_MASS),
            ("k", l.k),
            ("c", l.c),
            ("n", l.n),
            ("p", l.p),
            ("alpha", l.alpha),
            ("beta", l.beta),
            ("gamma", l.gamma),
            ("A", l.a),
        ];
        for (key, value) in want {
            assert_eq!(physical[key].as_f64(), Some(value), "{file}: {key}");
        }
    }
}

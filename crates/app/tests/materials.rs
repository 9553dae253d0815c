//! `[materials]` tables: the derived law against the contact mechanics written out here, and
//! every bad value named with its file, line and key.
//!
//! The facts used: `1/E* = (1 - ν₁²)/E₁ + (1 - ν₂²)/E₂`, `k = (4/3) E* √R*`, yield at the
//! peak Hertz pressure `p_y = 1.295 exp(0.736 ν) S_y` (Jackson & Green 2005) of the body with
//! the lower one, `δ_y = R* (π p_y / (2 E*))²`, `v_y` from `m v_y² / 2 = (2/5) k δ_y^(5/2)`;
//! Thornton's (1997) CoR at `r = v_y / v0`; and the energy balance of the loading for the
//! deepest penetration.

use bwc_app::materials::{MaterialsReport, MaterialsSpec};
use std::path::Path;

const ALUMINA_ON_ALUMINIUM: &str = r#"
[materials]
v0 = [0.01, 0.5, 3.0]

[materials.body1]
material = "alumina"
radius = 2.5e-3

[materials.body2]
material = "aluminium-6061-t6"
yield_strength = 300e6
"#;

fn parse(src: &str) -> Result<MaterialsSpec, String> {
    MaterialsSpec::parse(Path::new("m.toml"), src).map_err(|e| e.to_string())
}

#[test]
fn the_law_from_materials_is_contact_mechanics() {
    let spec = parse(ALUMINA_ON_ALUMINIUM).unwrap();
    let p = &spec.pair;
    let e_star = 1.0 / ((1.0 - 0.22f64.powi(2)) / 370e9 + (1.0 - 0.33f64.powi(2)) / 68.9e9);
    assert!((p.e_star / e_star - 1.0).abs() < 1e-14);
    assert!((p.k / (4.0 / 3.0 * e_star * 2.5e-3f64.sqrt()) - 1.0).abs() < 1e-14);
    let p_y = 1.295 * (0.736f64 * 0.33).exp() * 300e6;
    assert!((p.p_y.unwrap() / p_y - 1.0).abs() < 1e-14);
    assert_eq!(p.yields_first, Some(2));
    assert_eq!(spec.bodies[1].own, ["yield_strength"]);
    let m = 4.0 / 3.0 * std::f64::consts::PI * 2.5e-3f64.powi(3) * 3890.0;
    let delta_y = 2.5e-3 * (std::f64::consts::PI * p_y / (2.0 * e_star)).powi(2);
    let v_y = (0.8 * p.k * delta_y.powf(2.5) / m).sqrt();
    assert!((p.v_y.unwrap() / v_y - 1.0).abs() < 1e-12);

    let report = MaterialsReport::of(&spec).unwrap();
    for row in &report.rows {
        let r: f64 = v_y / row.v0;
        let e = if r >= 1.0 {
            1.0
        } else {
            (6.0 * 3f64.sqrt() / 5.0).sqrt()
                * (1.0 - r * r / 6.0).sqrt()
                * (r / (r + 2.0 * (1.2 - 0.2 * r * r).sqrt())).powf(0.25)
        };
        assert!((row.e - e).abs() < 1e-12, "v0 {}: {} vs {e}", row.v0, row.e);
        // The loading's work to the deepest penetration is the kinetic energy.
        let (k, d) = (p.k, row.delta_max);
        let work = if d <= delta_y {
            0.4 * k * d.powf(2.5)
        } else {
            let (f_y, s) = (k * delta_y.powf(1.5), 1.5 * k * delta_y.sqrt());
            0.4 * k * delta_y.powf(2.5) + f_y * (d - delta_y) + 0.5 * s * (d - delta_y).powi(2)
        };
        let energy = 0.5 * m * row.v0 * row.v0;
        assert!((work / energy - 1.0).abs() < 1e-12, "v0 {}", row.v0);
        assert!(row.t_d > 0.0 && row.t_d < 1e-3);
    }
    assert_eq!(report.rows[0].e, 1.0, "0.01 m/s is below v_y = {v_y}");
    let json = report.json(&spec);
    assert_eq!(json["laws"]["thornton"]["element"]["law"], "thornton");
    assert_eq!(json["derived"]["yields_first"], 2);
    for key in [
        "E_star", "k", "p_y", "delta_y", "v_y", "T_b", "e", "t_d", "F_max",
    ] {
        assert!(json["units"][key].is_string(), "{key}");
    }
}

#[test]
fn bad_materials_are_named_with_the_file_line_and_key() {
    let cases = [
        (
            ALUMINA_ON_ALUMINIUM.replace("\"alumina\"", "\"alumna\""),
            "m.toml:6: `materials.body1.material`: \"alumna\" is not a known material: steel-aisi-52100",
        ),
        (
            ALUMINA_ON_ALUMINIUM.replace("yield_strength = 300e6", "yield_strength = 300"),
            "m.toml:11: `materials.body2.yield_strength`: 300 is not admissible: a stress in Pa: this looks like MPa",
        ),
        (
            ALUMINA_ON_ALUMINIUM.replace("yield_strength = 300e6", "poisson = 0.5"),
            "m.toml:11: `materials.body2.poisson`: 0.5 is not admissible: -1 < nu < 0.5",
        ),
        (
            ALUMINA_ON_ALUMINIUM.replace("radius = 2.5e-3", "youngs_modulus = 370"),
            "m.toml:7: `materials.body1.youngs_modulus`: 370 is not admissible: E in Pa: this looks like GPa",
        ),
        (
            ALUMINA_ON_ALUMINIUM.replace("radius = 2.5e-3", ""),
            "`materials`: inf is not admissible: at least one curved body: two flats",
        ),
        (
            "[materials.body1]\nradius = 1e-3\n[materials.body2]\nmaterial = \"ptfe\"\n".to_string(),
            "m.toml:1: `materials.body1.youngs_modulus`: missing: give it, or a `material`",
        ),
        (
            ALUMINA_ON_ALUMINIUM.replace("[materials.body2]", "[materials.body3]"),
            "unknown field `body3`",
        ),
        ("model = \"shccm\"\n".to_string(), "m.toml:1: `materials`: missing table [materials]"),
    ];
    for (src, want) in cases {
        let e = parse(&src).unwrap_err();
        assert!(e.contains(want), "{e}\n  wants {want}");
    }
}

#[test]
fn a_flat_speed_range_defaults_around_the_yield_speed() {
    let spec = parse(&ALUMINA_ON_ALUMINIUM.replace("v0 = [0.01, 0.5, 3.0]\n", "")).unwrap();
    let v_y = spec.pair.v_y.unwrap();
    assert_eq!(spec.speeds.len(), 12);
    assert!((spec.speeds[0] / (0.5 * v_y) - 1.0).abs() < 1e-12);
    assert!((spec.speeds[11] / (100.0 * v_y) - 1.0).abs() < 1e-12);
}

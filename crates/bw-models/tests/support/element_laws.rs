//! The laws an element takes by name: each built from its named parameters and bounced by the
//! host of `element.rs` (a ball of mass `M` on a fixed floor, no gravity) against what is
//! known of it independently of the element. The facts used:
//!
//! * Kelvin-Voigt with the force criterion: `e = exp(-ζ θ / ω)`, `ω = √(1 - ζ²)`, `θ` the
//!   angle with `sin θ = 2ζω`, `cos θ = 2ζ² - 1`, `ζ = c / (2 √(k m))` (Schwager & Pöschel
//!   2007); the contact lasts `θ / (ω √(k/m))`.
//! * Hunt-Crossley: the family's nondimensional impact at `α v0` (checked against RK4 in
//!   `families.rs`).
//! * Thornton (1997): `e = (6√3/5)^(1/2) (1 - r²/6)^(1/2) (r / (r + 2 √(6/5 - r²/5)))^(1/4)`
//!   at `r = v_y / v0 < 1`, with `(5/4) m v_y² = k δ_y^(5/2)`.
//!
//! In each, the work the element absorbed is the kinetic energy lost, `m (v_in² - v_out²) / 2`.

use super::element::{host_bounce, M};
use bw_models::{
    family_impact, AnyContactElement, ElementSettings, Family, FamilyParams, HuntCrossleyLaw,
    KelvinVoigtLaw, LawSpec, ModelError, NamedLaw, Settings, ThorntonLaw, ELEMENT_LAWS,
};

const V_IN: f64 = 2.0;
const DT: f64 = 1e-6;

/// `(e, t_s, absorbed)` of the host's bounce with `law`, and how far the absorbed work is
/// from the kinetic energy lost (relative).
fn bounce<L: NamedLaw<N> + Clone, const N: usize>(law: L) -> (f64, f64, f64) {
    let (v_out, t_s, absorbed) = host_bounce(law, V_IN, 0.0, DT);
    let lost = 0.5 * M * (V_IN * V_IN - v_out * v_out);
    (v_out / V_IN, t_s, (absorbed - lost).abs() / lost)
}

#[test]
fn a_kelvin_voigt_element_rebounds_at_the_closed_form() {
    let k = 1e5;
    for zeta in [0.05, 0.3, 0.6] {
        let c = 2.0 * zeta * (k * M).sqrt();
        let (e, t_s, energy) = bounce(KelvinVoigtLaw { k, c });
        let w = (1.0 - zeta * zeta).sqrt();
        let theta = (2.0 * zeta * w).atan2(2.0 * zeta * zeta - 1.0);
        let want = (-zeta / w * theta).exp();
        let duration = theta / (w * (k / M).sqrt());
        assert!(
            (e - want).abs() < 1e-6 * want,
            "zeta {zeta}: e {e} vs {want}"
        );
        assert!(
            (t_s - duration).abs() < 1e-6 * duration,
            "zeta {zeta}: {t_s} vs {duration}"
        );
        assert!(energy < 1e-5, "zeta {zeta}: absorbed off by {energy:.1e}");
    }
}

#[test]
fn a_hunt_crossley_element_rebounds_as_the_family_impact() {
    for alpha in [0.0, 0.1, 0.4] {
        let (e, _, energy) = bounce(HuntCrossleyLaw { k: 1e7, alpha });
        let family = FamilyParams {
            family: Family::HuntCrossley,
            param: alpha,
            t_b: 1.0,
        };
        let want = family_impact(&family, V_IN, &Settings::default())
            .unwrap()
            .e;
        assert!((e - want).abs() < 1e-6, "alpha {alpha}: e {e} vs {want}");
        if alpha > 0.0 {
            assert!(energy < 1e-5, "alpha {alpha}: absorbed off by {energy:.1e}");
        }
    }
}

#[test]
fn a_thornton_element_rebounds_at_thorntons_closed_form() {
    let k = 1e7;
    for r in [0.05, 0.3, 0.8] {
        let v_y = r * V_IN;
        let delta_y = (1.25 * M * v_y * v_y / k).powf(0.4);
        let (e, _, energy) = bounce(ThorntonLaw { k, delta_y });
        let want = (6.0 * 3f64.sqrt() / 5.0).sqrt()
            * (1.0 - r * r / 6.0).sqrt()
            * (r / (r + 2.0 * (1.2 - 0.2 * r * r).sqrt())).powf(0.25);
        assert!((e - want).abs() < 1e-6, "v_y / v0 = {r}: e {e} vs {want}");
        assert!(
            energy < 1e-5,
            "v_y / v0 = {r}: absorbed off by {energy:.1e}"
        );
    }
    // Below yield the contact is Hertz's: elastic.
    let delta_y = (1.25 * M * 4.0 * V_IN * V_IN / k).powf(0.4);
    let (e, _, _) = bounce(ThorntonLaw { k, delta_y });
    assert!((e - 1.0).abs() < 1e-6, "{e}");
}

/// A Thornton contact driven in and partly out and in again deeper: the reloading retraces the
/// unloading curve elastically (no dissipation) and rejoins the plastic line at the deepest
/// point, where the force is the line's, `F_y + (3/2) k √δ_y (δ - δ_y)`.
#[test]
fn a_thornton_contact_reloads_elastically_and_rejoins_the_plastic_line() {
    let (k, delta_y) = (1e9, 1e-6);
    let params = [("k", k), ("delta_y", delta_y)];
    let mut e = AnyContactElement::of_law("thornton", &params, ElementSettings::default()).unwrap();
    let line = |d: f64| k * delta_y.powf(1.5) + 1.5 * k * delta_y.sqrt() * (d - delta_y);
    let step = |e: &mut AnyContactElement, u: f64, n: usize| {
        for _ in 0..n {
            e.advance(1e-7, u, u).unwrap();
        }
    };
    step(&mut e, -1.0, 40); // to 4 µm
    assert!(
        (e.force() - line(4e-6)).abs() < 1e-8 * line(4e-6),
        "{}",
        e.force()
    );
    let at_peak = e.dissipated();
    step(&mut e, 1.0, 10); // back to 3 µm
    step(&mut e, -1.0, 10); // in again to 4 µm, on the unloading curve
    assert!(
        (e.dissipated() - at_peak).abs() < 1e-9 * at_peak,
        "reloading dissipated"
    );
    step(&mut e, -1.0, 10); // on to 5 µm: on the line again
    assert!(
        (e.force() - line(5e-6)).abs() < 1e-6 * line(5e-6),
        "{}",
        e.force()
    );
    assert_eq!(e.state().len(), 2);
    assert_eq!(e.spec().states, ["x", "x_m"]);
}

/// Every registered law builds from its spec's start values; a wrong law, a missing or unknown
/// parameter and an inadmissible value are errors that name what is wrong and what is
/// admissible.
#[test]
fn laws_by_name_and_what_is_wrong_with_a_name() {
    let s = ElementSettings::default();
    let good = |spec: &LawSpec| -> Vec<(&str, f64)> {
        spec.params.iter().map(|p| (p.name, p.start)).collect()
    };
    for spec in ELEMENT_LAWS {
        for p in spec.params {
            assert!((p.admits)(p.start), "{}: {}", spec.name, p.name);
        }
        let e = AnyContactElement::of_law(spec.name, &good(spec), s)
            .unwrap_or_else(|e| panic!("{}: {e}", spec.name));
        assert_eq!(e.spec().name, spec.name);
        assert_eq!(e.state().len(), spec.states.len(), "{}", spec.name);
    }
    let err =
        |law: &str, params: &[(&str, f64)]| AnyContactElement::of_law(law, params, s).unwrap_err();
    let e = err("hertz", &[]).to_string();
    assert!(
        e.contains("`hertz`") && e.contains("hunt-crossley, kelvin-voigt, thornton"),
        "{e}"
    );
    let e = err("kelvin-voigt", &[("k", 1.0)]).to_string();
    assert!(e.contains("`c` is missing") && e.contains("k, c"), "{e}");
    let e = err("kelvin-voigt", &[("k", 1.0), ("c", 1.0), ("m", 1.0)]).to_string();
    assert!(e.contains("`m` is not one of its parameters"), "{e}");
    match err("thornton", &[("k", 1.0), ("delta_y", -1.0)]) {
        ModelError::InvalidParameter { name, allowed, .. } => {
            assert_eq!((name, allowed), ("delta_y", "delta_y > 0 (m)"))
        }
        other => panic!("{other}"),
    }
    // Parameters admissible one by one but not together are the law's to refuse.
    let mut bw = good(&<bw_models::Bwshccl as NamedLaw<2>>::SPEC);
    bw.iter_mut().find(|(n, _)| *n == "gamma").unwrap().1 = 1e4;
    let e = err("shccm", &bw).to_string();
    assert!(e.contains("-beta <= gamma <= beta"), "{e}");
}

/// The guide's tables of element laws (`docs/src/reference/laws.md`) list exactly the
/// registered laws, each with its title, states and force, and each parameter with its unit
/// and admissible set.
#[test]
fn the_guide_lists_every_element_law_as_registered() {
    let page = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/src/reference/laws.md"
    ))
    .unwrap();
    let table = |marker: &str| -> Vec<String> {
        let after = page
            .split(marker)
            .nth(1)
            .unwrap_or_else(|| panic!("no {marker}"));
        let rows = after.lines().skip(3).take_while(|l| l.starts_with('|'));
        rows.map(str::to_string).collect()
    };
    let quoted = |s: &str| format!("`{s}`");
    let laws: Vec<String> = ELEMENT_LAWS
        .iter()
        .map(|s| {
            let states: Vec<String> = s.states.iter().map(|n| quoted(n)).collect();
            let force = s.force.replace('|', "\\|");
            format!(
                "| `\"{}\"` | {} | {} | `{force}` |",
                s.name,
                s.title,
                states.join(", ")
            )
        })
        .collect();
    assert_eq!(table("<!-- elements:"), laws);
    let params: Vec<String> = ELEMENT_LAWS
        .iter()
        .flat_map(|s| {
            s.params.iter().map(move |p| {
                format!(
                    "| `\"{}\"` | `{}` | {} | `{}` |",
                    s.name, p.name, p.unit, p.allowed
                )
            })
        })
        .collect();
    assert_eq!(table("<!-- element parameters:"), params);
}

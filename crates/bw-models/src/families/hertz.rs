//! The Hertz families: `F = k δ^(3/2) (1 + s δ̇ / v0)` in the nondimensional impact
//! `X'' = -X^(3/2) (1 + s X')`, each with its own damping `s`: Hunt-Crossley's
//! `s = (3/2) α v0`, Lankarani-Nikravesh's `3 (1 - e_r²) / 4`, Flores' `8 (1 - e_r) / (5 e_r)`.
//! They are the NDBWSHCCM with `B = Γ = 0`, `κ = 1/2`, `n = 1`, `p = 3/2` and `σ = s`, and take
//! its impact paths.

use super::{FamilySpec, ParamSpec};
use crate::cor::impact;
use crate::error::ModelError;
use crate::input::Zero;
use crate::models::Ndbwshccm;
use crate::outcome::Cor;
use crate::params::{ModelKind, Nondim, NondimParams};
use crate::settings::Settings;

/// One impact of the Hertz law with nondimensional damping `s`.
fn hertz_impact(s: f64, settings: &Settings) -> Result<Cor, ModelError> {
    let nd = Nondim {
        b: 0.0,
        gamma: 0.0,
        kappa: 0.5,
        sigma: s,
        n: 1.0,
        p: 1.5,
    };
    let model = Ndbwshccm::new(&NondimParams::new(ModelKind::Shccm, nd)?, Zero)?;
    impact(&model, settings).map(|i| i.cor())
}

/// The restitution parameter `e_r` of the Lankarani-Nikravesh and Flores dampings.
const E_R: ParamSpec = ParamSpec {
    name: "e_r",
    unit: "-",
    allowed: "0 < e_r <= 1",
    admits: |d| d > 0.0 && d <= 1.0,
    default_bounds: (0.05, 1.0),
    default_log: false,
    neutral: 1.0,
};

pub(super) const HUNT_CROSSLEY: FamilySpec = FamilySpec {
    name: "hunt-crossley",
    title: "Hunt-Crossley",
    force: "k δ^(3/2) (1 + (3/2) α δ̇)",
    exponent: 1.5,
    param: ParamSpec {
        name: "alpha",
        unit: "s/m",
        allowed: "alpha >= 0 (s/m)",
        admits: |d| d >= 0.0 && d.is_finite(),
        // A CoR of 1 to about 0 at 0.1-2 m/s.
        default_bounds: (0.0, 5.0),
        default_log: false,
        neutral: 0.0,
    },
    impact: |alpha, v0, settings| hertz_impact(1.5 * alpha * v0, settings),
    closed_form: None,
};

pub(super) const LANKARANI_NIKRAVESH: FamilySpec = FamilySpec {
    name: "hertz-ln",
    title: "Hertz, Lankarani-Nikravesh",
    force: "k δ^(3/2) (1 + 3 (1 - e_r²) / 4 · δ̇ / v0)",
    exponent: 1.5,
    param: E_R,
    impact: |e_r, _, settings| hertz_impact(0.75 * (1.0 - e_r * e_r), settings),
    closed_form: None,
};

pub(super) const FLORES: FamilySpec = FamilySpec {
    name: "hertz-flores",
    title: "Hertz, Flores",
    force: "k δ^(3/2) (1 + 8 (1 - e_r) / (5 e_r) · δ̇ / v0)",
    exponent: 1.5,
    param: E_R,
    impact: |e_r, _, settings| hertz_impact(1.6 * (1.0 - e_r) / e_r, settings),
    closed_form: None,
};

//! The Hertz families: `F = k δ^(3/2) (1 + s δ̇ / v0)` in the nondimensional impact
//! `X'' = -X^(3/2) (1 + s X')`, each with its own damping `s`: Hunt-Crossley's
//! `s = (3/2) α v0`, Lankarani-Nikravesh's `3 (1 - e_r²) / 4`, Flores' `8 (1 - e_r) / (5 e_r)`.
//! They are the NDBWSHCCM with `B = Γ = 0`, `κ = 1/2`, `n = 1`, `p = 3/2` and `σ = s`, and take
//! its impact paths.

use super::{FamilySpec, ParamSpec};
use crate::cor::impact;
use crate::error::ModelError;
use crate::input::Zero;
use crate::law_spec::{non_negative, positive, LawParam, LawSpec, NamedLaw};
use crate::laws::ContactLaw;
use crate::models::Ndbwshccm;
use crate::outcome::Cor;
use crate::params::{ModelKind, Nondim, NondimParams};
use crate::settings::Settings;
use bwc_ode::State;

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

/// Hunt and Crossley's law as a contact element: `F = -k |x|^(1/2) x - (3/2) α k |x|^(3/2) u`,
/// which is `k δ^(3/2) (1 + (3/2) α δ̇)` in compression (`δ = -x`, `δ̇ = -u`): the BWSHCCL with
/// `B = Γ = 0`, `κ = 1/2`, `n = 1`, `p = 3/2`, `c = (3/2) α k`. State `x` (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HuntCrossleyLaw {
    /// The Hertz stiffness `k` (N/m^(3/2)).
    pub k: f64,
    /// The damping `α` (s/m).
    pub alpha: f64,
}

impl ContactLaw<1> for HuntCrossleyLaw {
    fn eval(&self, s: &State<1>, u: f64) -> (State<1>, f64) {
        let x = s[0];
        let root = x.abs().sqrt();
        let f = -self.k * root * (x + 1.5 * self.alpha * x.abs() * u);
        (State::<1>::new(u), f)
    }
    /// `(2/5) k |x|^(5/2)` (J).
    fn stored(&self, s: &State<1>) -> f64 {
        0.4 * self.k * s[0].abs().powf(2.5)
    }
    /// `(3/2) α k |x|^(3/2) u²` (W).
    fn dissipation(&self, s: &State<1>, u: f64, _rate: &State<1>, _force: f64) -> f64 {
        1.5 * self.alpha * self.k * s[0].abs().powf(1.5) * u * u
    }
    /// `x`: the force's root is not smooth there.
    fn kinks(&self, s: &State<1>, _u: f64) -> [f64; 2] {
        [s[0], s[0]]
    }
}

impl NamedLaw<1> for HuntCrossleyLaw {
    const SPEC: LawSpec = LawSpec {
        name: "hunt-crossley",
        title: "Hunt-Crossley",
        force: "-k |x|^(1/2) x - (3/2) alpha k |x|^(3/2) u",
        params: &[
            LawParam::new("k", "N m^-3/2", "k > 0 (N/m^(3/2))", positive, 1e10),
            LawParam::new("alpha", "s/m", "alpha >= 0 (s/m)", non_negative, 0.2),
        ],
        states: &["x"],
    };
    fn of_values(values: &[f64]) -> Result<Self, ModelError> {
        match *values {
            [k, alpha] => Ok(Self { k, alpha }),
            _ => Err(ModelError::NotApplicable {
                reason: "the Hunt-Crossley law takes 2 values: k, alpha",
            }),
        }
    }
}

//! A linear spring and dashpot, `F = k δ + c δ̇`: nondimensional `X'' = -X - 2 ζ X'` with the
//! damping ratio `ζ = c / (2 √(k m))`, its own model ([`Ndkv`]), ended at `F <= 0 <= v`.

use super::{FamilySpec, ParamSpec};
use crate::cor::impact;
use crate::error::ModelError;
use crate::law_spec::{non_negative, positive, LawParam, LawSpec, NamedLaw};
use crate::laws::ContactLaw;
use crate::models::{nondimensional_scales, unforced, CollisionModel};
use bwc_ode::{State, System};

pub(super) const SPEC: FamilySpec = FamilySpec {
    name: "kelvin-voigt",
    title: "Kelvin-Voigt",
    force: "k δ + c δ̇",
    exponent: 1.0,
    param: ParamSpec {
        name: "zeta",
        unit: "-",
        allowed: "0 <= zeta < 1",
        admits: |d| (0.0..1.0).contains(&d),
        default_bounds: (0.0, 0.99),
        default_log: false,
        neutral: 0.0,
    },
    impact: |zeta, _, settings| impact(&Ndkv { zeta }, settings).map(|i| i.cor()),
    closed_form: Some(|zeta, _| closed_form(zeta)),
};

/// The Kelvin-Voigt CoR with the force criterion (Schwager & Pöschel 2007):
/// `e = exp(-ζ θ / ω)`, `ω = √(1 - ζ²)`, where `θ = ω t_s` is the angle with
/// `sin θ = 2ζω`, `cos θ = 2ζ² - 1`: the first zero of `F` after the impact, where the speed
/// is `e^(-ζ t_s)`; `θ = π - atan(2ζω / (1 - 2ζ²))` for `ζ < 1/√2`. The same at every speed.
fn closed_form(zeta: f64) -> f64 {
    let w = (1.0 - zeta * zeta).sqrt();
    let theta = (2.0 * zeta * w).atan2(2.0 * zeta * zeta - 1.0);
    (-zeta / w * theta).exp()
}

/// The nondimensional Kelvin-Voigt impact, states `(X, V)`: `X' = V`, `V' = F = -X - 2 ζ V`;
/// `X < 0` in compression, `V(0) = -1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ndkv {
    /// The damping ratio `ζ`.
    pub zeta: f64,
}

impl System<2> for Ndkv {
    fn rhs(&self, _t: f64, y: &State<2>) -> State<2> {
        State::<2>::new(y[1], self.force(y))
    }
}

impl CollisionModel<2> for Ndkv {
    fn initial_state(&self) -> State<2> {
        State::<2>::new(0.0, -1.0)
    }
    fn force(&self, y: &State<2>) -> f64 {
        -y[0] - 2.0 * self.zeta * y[1]
    }
    fn displacement(&self, y: &State<2>) -> f64 {
        y[0]
    }
    fn velocity(&self, y: &State<2>) -> f64 {
        y[1]
    }
    unforced!();
    nondimensional_scales!(2);
    fn kinks(&self, _t: f64, _y: &State<2>) -> [f64; 2] {
        // Linear: no point where the right-hand side is not smooth.
        [1.0, 1.0]
    }
}

#[cfg(test)]
mod tests {
    use super::super::{family_impact, Family, FamilyParams};
    use crate::settings::Settings;

    #[test]
    fn kelvin_voigt_matches_its_closed_form_at_every_speed() {
        let s = Settings::default();
        for zeta in [0.0, 0.05, 0.2, 0.5, 0.8] {
            for v0 in [0.1, 3.0] {
                let p = FamilyParams {
                    family: Family::KelvinVoigt,
                    param: zeta,
                    t_b: 1.0,
                };
                let e = family_impact(&p, v0, &s).unwrap().e;
                let want = p.closed_form_cor(v0).unwrap();
                assert!((e - want).abs() < 1e-7, "zeta {zeta}: {e} vs {want}");
            }
        }
    }
}

/// A linear spring and dashpot as a contact element: `F = -k x - c u`, which is `k δ + c δ̇`
/// in compression. State `x` (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KelvinVoigtLaw {
    /// The stiffness `k` (N/m).
    pub k: f64,
    /// The damping `c` (N s/m).
    pub c: f64,
}

impl ContactLaw<1> for KelvinVoigtLaw {
    fn eval(&self, s: &State<1>, u: f64) -> (State<1>, f64) {
        (State::<1>::new(u), -self.k * s[0] - self.c * u)
    }
    /// `k x² / 2` (J).
    fn stored(&self, s: &State<1>) -> f64 {
        0.5 * self.k * s[0] * s[0]
    }
    /// `c u²` (W).
    fn dissipation(&self, _s: &State<1>, u: f64, _rate: &State<1>, _force: f64) -> f64 {
        self.c * u * u
    }
    /// None: the law is smooth everywhere (constants that never cross zero).
    fn kinks(&self, _s: &State<1>, _u: f64) -> [f64; 2] {
        [1.0, 1.0]
    }
}

impl NamedLaw<1> for KelvinVoigtLaw {
    const SPEC: LawSpec = LawSpec {
        name: "kelvin-voigt",
        title: "Kelvin-Voigt",
        force: "-k x - c u",
        params: &[
            LawParam::new("k", "N/m", "k > 0 (N/m)", positive, 1e7),
            LawParam::new("c", "N s/m", "c >= 0 (N s/m)", non_negative, 200.0),
        ],
        states: &["x"],
    };
    fn of_values(values: &[f64]) -> Result<Self, ModelError> {
        match *values {
            [k, c] => Ok(Self { k, c }),
            _ => Err(ModelError::NotApplicable {
                reason: "the Kelvin-Voigt law takes 2 values: k, c",
            }),
        }
    }
}

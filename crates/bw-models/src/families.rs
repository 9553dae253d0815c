//! The contact laws other simulators use, for comparison with the Bouc-Wen laws on the same
//! data: a body of mass `m` meeting a contact of stiffness `k` at speed `v0`, penetration `δ`
//! (m), its rate `δ̇` (m/s), contact force `F` (N, positive pushing apart).
//!
//! | family | force | damping parameter |
//! | --- | --- | --- |
//! | [`Family::HuntCrossley`] | `k δ^(3/2) (1 + (3/2) α δ̇)` | `α` (s/m) |
//! | [`Family::KelvinVoigt`] | `k δ + c δ̇` | `ζ = c / (2 √(k m))` (-) |
//! | [`Family::HertzLankaraniNikravesh`] | `k δ^(3/2) (1 + 3 (1 - e_r²) / 4 · δ̇ / v0)` | `e_r` (-) |
//! | [`Family::HertzFlores`] | `k δ^(3/2) (1 + 8 (1 - e_r) / (5 e_r) · δ̇ / v0)` | `e_r` (-) |
//!
//! Scaled by `δ* = (m v0² / k)^(1/(p+1))` and `t* = δ* / v0` (`p = 3/2`, or 1 for Kelvin-Voigt)
//! each is a one-parameter nondimensional impact `X'' = -X^p (1 + s X')` (Hertz families,
//! `s = (3/2) α v0`, `3 (1 - e_r²) / 4` or `8 (1 - e_r) / (5 e_r)`) or `X'' = -X - 2 ζ X'`
//! (Kelvin-Voigt). The Hertz families are the NDBWSHCCM with `B = Γ = 0` and `σ = s`, and take
//! its impact paths; Kelvin-Voigt is its own model ([`Ndkv`]). Both end at the paper's
//! separation `F <= 0 <= v`, so a Kelvin-Voigt contact ends before the penetration returns to
//! zero, when its damper would pull. Durations in seconds are `T_d T_b v0^(-(p-1)/(p+1))` with
//! `T_b = (m / k)^(1/(p+1))`, as for the Bouc-Wen models.

use crate::cor::impact;
use crate::error::ModelError;
use crate::input::Zero;
use crate::models::{CollisionModel, Ndbwshccm};
use crate::outcome::Cor;
use crate::params::{ModelKind, Nondim, NondimParams};
use crate::settings::Settings;
use bwc_ode::{State, System};

/// A contact-law family (see the module's table).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Family {
    /// Hertz stiffness with Hunt-Crossley damping.
    HuntCrossley,
    /// A linear spring and dashpot.
    KelvinVoigt,
    /// Hertz stiffness with the Lankarani-Nikravesh damping.
    HertzLankaraniNikravesh,
    /// Hertz stiffness with the Flores damping.
    HertzFlores,
}

/// Every family, in the order of the module's table.
pub const FAMILIES: [Family; 4] = [
    Family::HuntCrossley,
    Family::KelvinVoigt,
    Family::HertzLankaraniNikravesh,
    Family::HertzFlores,
];

impl Family {
    /// The name a config uses: `"hunt-crossley"`, `"kelvin-voigt"`, `"hertz-ln"`,
    /// `"hertz-flores"`.
    pub fn name(self) -> &'static str {
        match self {
            Family::HuntCrossley => "hunt-crossley",
            Family::KelvinVoigt => "kelvin-voigt",
            Family::HertzLankaraniNikravesh => "hertz-ln",
            Family::HertzFlores => "hertz-flores",
        }
    }

    /// The family of a name ([`Family::name`]).
    pub fn parse(name: &str) -> Option<Self> {
        FAMILIES.into_iter().find(|f| f.name() == name)
    }

    /// The damping parameter's name: `"alpha"` (s/m), `"zeta"` or `"e_r"`.
    pub fn damping_name(self) -> &'static str {
        match self {
            Family::HuntCrossley => "alpha",
            Family::KelvinVoigt => "zeta",
            Family::HertzLankaraniNikravesh | Family::HertzFlores => "e_r",
        }
    }

    /// The stiffness exponent `p`: 3/2 (Hertz), 1 (Kelvin-Voigt).
    pub fn exponent(self) -> f64 {
        match self {
            Family::KelvinVoigt => 1.0,
            _ => 1.5,
        }
    }

    /// What the damping parameter admits, in words, and whether `d` is admissible.
    fn admits(self, d: f64) -> (&'static str, bool) {
        match self {
            Family::HuntCrossley => ("alpha >= 0 (s/m)", d >= 0.0 && d.is_finite()),
            Family::KelvinVoigt => ("0 <= zeta < 1", (0.0..1.0).contains(&d)),
            _ => ("0 < e_r <= 1", d > 0.0 && d <= 1.0),
        }
    }
}

/// A family's law in the terms the data determine: the damping parameter and the time scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FamilyParams {
    /// The family.
    pub family: Family,
    /// Its damping parameter ([`Family::damping_name`]).
    pub damping: f64,
    /// `T_b = (m / k)^(1/(p+1))` (s, with `k` in N/m^p): only durations depend on it.
    pub t_b: f64,
}

impl FamilyParams {
    /// Checks the parameters.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] naming the parameter and what it admits.
    pub fn validate(&self) -> Result<(), ModelError> {
        let (allowed, ok) = self.family.admits(self.damping);
        if !ok {
            return Err(ModelError::InvalidParameter {
                name: self.family.damping_name(),
                value: self.damping,
                allowed,
            });
        }
        if !(self.t_b > 0.0 && self.t_b.is_finite()) {
            return Err(ModelError::InvalidParameter {
                name: "T_b",
                value: self.t_b,
                allowed: "T_b > 0 (s)",
            });
        }
        Ok(())
    }

    /// The time scale at `v0` (s): a nondimensional duration times this is in seconds.
    pub fn time_scale(&self, v0: f64) -> f64 {
        let p = self.family.exponent();
        self.t_b * v0.powf(-(p - 1.0) / (p + 1.0))
    }

    /// The nondimensional damping `s` of a Hertz family at `v0` (see the module's text).
    fn hertz_damping(&self, v0: f64) -> f64 {
        let d = self.damping;
        match self.family {
            Family::HuntCrossley => 1.5 * d * v0,
            Family::HertzLankaraniNikravesh => 0.75 * (1.0 - d * d),
            _ => 1.6 * (1.0 - d) / d,
        }
    }
}

/// One unforced impact of a family at `v0` (m/s): `e`, and `t_s` in the nondimensional time
/// (multiply by [`FamilyParams::time_scale`] for seconds).
///
/// # Errors
/// As [`FamilyParams::validate`]; `v0 <= 0`; as [`impact`].
pub fn family_impact(p: &FamilyParams, v0: f64, settings: &Settings) -> Result<Cor, ModelError> {
    p.validate()?;
    if !(v0 > 0.0 && v0.is_finite()) {
        return Err(ModelError::InvalidParameter {
            name: "v0",
            value: v0,
            allowed: "v0 > 0 (m/s)",
        });
    }
    if p.family == Family::KelvinVoigt {
        return impact(&Ndkv { zeta: p.damping }, settings).map(|i| i.cor());
    }
    let nd = Nondim {
        b: 0.0,
        gamma: 0.0,
        kappa: 0.5,
        sigma: p.hertz_damping(v0),
        n: 1.0,
        p: 1.5,
    };
    let model = Ndbwshccm::new(&NondimParams::new(ModelKind::Shccm, nd)?, Zero)?;
    impact(&model, settings).map(|i| i.cor())
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
    fn input(&self, _t: f64) -> f64 {
        0.0
    }
    fn input_constant_after(&self) -> Option<f64> {
        Some(f64::NEG_INFINITY)
    }
    fn impact_speed(&self) -> f64 {
        1.0
    }
    fn state_scale(&self) -> State<2> {
        State::<2>::repeat(1.0)
    }
    fn time_scale(&self) -> f64 {
        1.0
    }
    fn kinks(&self, _t: f64, _y: &State<2>) -> [f64; 2] {
        // Linear: no point where the right-hand side is not smooth.
        [1.0, 1.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Kelvin-Voigt CoR with the force criterion (Schwager & Pöschel 2007):
    /// `e = exp(-ζ/ω (π - atan(2ζω / (1 - 2ζ²))))`, `ω = √(1 - ζ²)`, for `ζ < 1/√2`.
    fn kv_closed_form(zeta: f64) -> f64 {
        let w = (1.0 - zeta * zeta).sqrt();
        (-zeta / w * (std::f64::consts::PI - (2.0 * zeta * w / (1.0 - 2.0 * zeta * zeta)).atan()))
            .exp()
    }

    #[test]
    fn kelvin_voigt_matches_its_closed_form_at_every_speed() {
        let s = Settings::default();
        for zeta in [0.0, 0.05, 0.2, 0.5] {
            for v0 in [0.1, 3.0] {
                let p = FamilyParams {
                    family: Family::KelvinVoigt,
                    damping: zeta,
                    t_b: 1.0,
                };
                let e = family_impact(&p, v0, &s).unwrap().e;
                assert!((e - kv_closed_form(zeta)).abs() < 1e-7, "zeta {zeta}: {e}");
            }
        }
    }

    #[test]
    fn names_round_trip_and_bad_parameters_are_named() {
        for f in FAMILIES {
            assert_eq!(Family::parse(f.name()), Some(f));
        }
        let bad = FamilyParams {
            family: Family::HertzFlores,
            damping: 0.0,
            t_b: 1.0,
        };
        let e = family_impact(&bad, 1.0, &Settings::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("e_r") && e.contains("0 < e_r <= 1"), "{e}");
    }
}

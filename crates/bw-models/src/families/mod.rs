//! The contact laws other simulators use, for comparison with the Bouc-Wen laws on the same
//! data: a body of mass `m` meeting a contact of stiffness `k` at speed `v0`, penetration `δ`
//! (m), its rate `δ̇` (m/s), contact force `F` (N, positive pushing apart).
//!
//! | family | force | parameter |
//! | --- | --- | --- |
//! | [`Family::HuntCrossley`] | `k δ^(3/2) (1 + (3/2) α δ̇)` | `alpha` (s/m) |
//! | [`Family::KelvinVoigt`] | `k δ + c δ̇` | `zeta = c / (2 √(k m))` (-) |
//! | [`Family::HertzLankaraniNikravesh`] | `k δ^(3/2) (1 + 3 (1 - e_r²) / 4 · δ̇ / v0)` | `e_r` (-) |
//! | [`Family::HertzFlores`] | `k δ^(3/2) (1 + 8 (1 - e_r) / (5 e_r) · δ̇ / v0)` | `e_r` (-) |
//! | [`Family::Thornton`] | Hertz to the yield penetration, then its tangent; Hertz unloading of a flattened sphere | `v_y` (m/s) |
//!
//! Each family is described once, by a [`FamilySpec`] in its own module ([`Family::spec`]):
//! its name, its parameter with unit, admissible set and default bounds, its nondimensional
//! impact and, where one exists, its CoR in closed form. Configs, fits, reports and the
//! Python package take every family from [`FAMILIES`]. A new family is a module with its
//! spec and its model, a variant with its arm in [`Family::spec`] and its entry in
//! [`FAMILIES`], and its row in the guide's `reference/laws.md` (a test compares the rows with
//! the specs).
//!
//! Scaled by `δ* = (m v0² / k)^(1/(p+1))` and `t* = δ* / v0` (`p = 3/2`, or 1 for Kelvin-Voigt)
//! each is a one-parameter nondimensional impact. All end at the paper's separation
//! `F <= 0 <= v`, so a Kelvin-Voigt contact ends before the penetration returns to zero, when
//! its damper would pull. Durations in seconds are `T_d T_b v0^(-(p-1)/(p+1))` with
//! `T_b = (m / k)^(1/(p+1))`, as for the Bouc-Wen models.

mod deepest;
mod hertz;
mod jackson_green;
mod kelvin_voigt;
mod thornton;

pub use hertz::HuntCrossleyLaw;
pub use jackson_green::JacksonGreenLaw;
pub use kelvin_voigt::{KelvinVoigtLaw, Ndkv};
pub use thornton::{Ndthornton, ThorntonLaw};

use crate::error::ModelError;
use crate::outcome::Cor;
use crate::settings::Settings;

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
    /// Thornton's (1997) elastic-perfectly-plastic sphere.
    Thornton,
}

/// Every family, in the order of the module's table.
pub const FAMILIES: [Family; 5] = [
    Family::HuntCrossley,
    Family::KelvinVoigt,
    Family::HertzLankaraniNikravesh,
    Family::HertzFlores,
    Family::Thornton,
];

/// The one parameter of a family besides `T_b`.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct ParamSpec {
    /// The name a config, a report and a samples file use.
    pub name: &'static str,
    /// Its unit (`"-"` for a pure number).
    pub unit: &'static str,
    /// What it admits, in words (`"0 < e_r <= 1"`).
    pub allowed: &'static str,
    /// Whether a value is admissible.
    pub admits: fn(f64) -> bool,
    /// The bounds a fit searches when the config gives none.
    pub default_bounds: (f64, f64),
    /// Whether those bounds are searched on a logarithmic scale.
    pub default_log: bool,
    /// An admissible value (for checking `T_b` alone).
    pub neutral: f64,
}

/// Everything about one family, in one place.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct FamilySpec {
    /// The name a config uses (`model = "hunt-crossley"`).
    pub name: &'static str,
    /// Its name in figures' legends (`"Hunt-Crossley"`, `"Hertz, Flores"`).
    pub title: &'static str,
    /// The force law, as in the module's table.
    pub force: &'static str,
    /// The stiffness exponent `p` of its `T_b = (m / k)^(1/(p+1))`.
    pub exponent: f64,
    /// Its parameter.
    pub param: ParamSpec,
    /// One unforced impact at `v0` (m/s) with the parameter at a validated value: `e`, and
    /// `t_s` in the nondimensional time.
    pub(crate) impact: fn(f64, f64, &Settings) -> Result<Cor, ModelError>,
    /// The CoR in closed form at (parameter, `v0`), where there is one.
    pub(crate) closed_form: Option<fn(f64, f64) -> f64>,
}

impl Family {
    /// The family's description: the one place each family is defined.
    pub fn spec(self) -> &'static FamilySpec {
        match self {
            Family::HuntCrossley => &hertz::HUNT_CROSSLEY,
            Family::KelvinVoigt => &kelvin_voigt::SPEC,
            Family::HertzLankaraniNikravesh => &hertz::LANKARANI_NIKRAVESH,
            Family::HertzFlores => &hertz::FLORES,
            Family::Thornton => &thornton::SPEC,
        }
    }

    /// The name a config uses: `"hunt-crossley"`, `"kelvin-voigt"`, `"hertz-ln"`,
    /// `"hertz-flores"`, `"thornton"`.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// The family of a name ([`Family::name`]).
    pub fn parse(name: &str) -> Option<Self> {
        FAMILIES.into_iter().find(|f| f.name() == name)
    }

    /// The parameter's name: `"alpha"` (s/m), `"zeta"`, `"e_r"` or `"v_y"` (m/s).
    pub fn param_name(self) -> &'static str {
        self.spec().param.name
    }

    /// The stiffness exponent `p`: 3/2 (Hertz), 1 (Kelvin-Voigt).
    pub fn exponent(self) -> f64 {
        self.spec().exponent
    }

    /// The names of every family's parameter, once each, in the order of [`FAMILIES`].
    pub fn param_names() -> Vec<&'static str> {
        let mut names: Vec<&'static str> = Vec::new();
        for f in FAMILIES {
            if !names.contains(&f.param_name()) {
                names.push(f.param_name());
            }
        }
        names
    }
}

/// A family's law in the terms the data determine: its parameter and the time scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FamilyParams {
    /// The family.
    pub family: Family,
    /// Its parameter ([`Family::param_name`]).
    pub param: f64,
    /// `T_b = (m / k)^(1/(p+1))` (s, with `k` in N/m^p): only durations depend on it.
    pub t_b: f64,
}

impl FamilyParams {
    /// Checks the parameters.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] naming the parameter and what it admits.
    pub fn validate(&self) -> Result<(), ModelError> {
        let spec = self.family.spec().param;
        if !(spec.admits)(self.param) {
            return Err(ModelError::InvalidParameter {
                name: spec.name,
                value: self.param,
                allowed: spec.allowed,
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

    /// The CoR at `v0` (m/s) in closed form, where the family has one (Kelvin-Voigt,
    /// Thornton); `None` otherwise.
    pub fn closed_form_cor(&self, v0: f64) -> Option<f64> {
        self.family.spec().closed_form.map(|f| f(self.param, v0))
    }
}

/// One unforced impact of a family at `v0` (m/s): `e`, and `t_s` in the nondimensional time
/// (multiply by [`FamilyParams::time_scale`] for seconds).
///
/// # Errors
/// As [`FamilyParams::validate`]; `v0 <= 0`; as [`crate::impact`].
pub fn family_impact(p: &FamilyParams, v0: f64, settings: &Settings) -> Result<Cor, ModelError> {
    p.validate()?;
    if !(v0 > 0.0 && v0.is_finite()) {
        return Err(ModelError::InvalidParameter {
            name: "v0",
            value: v0,
            allowed: "v0 > 0 (m/s)",
        });
    }
    (p.family.spec().impact)(p.param, v0, settings)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_bad_parameters_are_named() {
        for f in FAMILIES {
            assert_eq!(Family::parse(f.name()), Some(f));
            let p = f.spec().param;
            assert!((p.admits)(p.neutral), "{}", f.name());
            assert!((p.admits)(p.default_bounds.0) && (p.admits)(p.default_bounds.1));
        }
        let bad = FamilyParams {
            family: Family::HertzFlores,
            param: 0.0,
            t_b: 1.0,
        };
        let e = family_impact(&bad, 1.0, &Settings::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("e_r") && e.contains("0 < e_r <= 1"), "{e}");
    }
}

//! Model parameters: SI (dimensional) and nondimensional, validated against the paper's
//! admissible sets. The two kinds are distinct types so they cannot be mixed.

use crate::ModelError;

/// Which collision model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModelKind {
    /// Bouc-Wen-Simon-Hunt-Crossley collision model (states x, z, v).
    Shccm,
    /// Bouc-Wen-Maxwell collision model, Lipschitz form (states r, y, z, v).
    Mcm,
}

/// Both models, in the order of [`ModelKind`]'s variants.
pub const MODEL_KINDS: [ModelKind; 2] = [ModelKind::Shccm, ModelKind::Mcm];

impl ModelKind {
    /// Short name, as scenes, configs and the bindings take it: `"shccm"` or `"mcm"`.
    pub fn name(self) -> &'static str {
        match self {
            ModelKind::Shccm => "shccm",
            ModelKind::Mcm => "mcm",
        }
    }

    /// The model of a short name ([`ModelKind::name`]).
    pub fn parse(name: &str) -> Option<Self> {
        MODEL_KINDS.into_iter().find(|k| k.name() == name)
    }

    /// The model's name in the paper: `"BWSHCCM"` or `"BWMCM"`.
    pub fn title(self) -> &'static str {
        match self {
            ModelKind::Shccm => "BWSHCCM",
            ModelKind::Mcm => "BWMCM",
        }
    }

    /// The names of the law's states (m), in the order of its state vector: `x, z` (BWSHCCL)
    /// or `r, y, z` (BWMCL).
    pub fn law_states(self) -> &'static [&'static str] {
        match self {
            ModelKind::Shccm => &["x", "z"],
            ModelKind::Mcm => &["r", "y", "z"],
        }
    }
}

pub(crate) fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    allowed: &'static str,
) -> Result<(), ModelError> {
    if value.is_finite() && ok {
        Ok(())
    } else {
        Err(ModelError::InvalidParameter {
            name,
            value,
            allowed,
        })
    }
}

/// Contact-law parameters in SI units (eq:BWSHCCL, eq:BWMCL), unvalidated plain data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Physical {
    /// Stiffness `k` (kg m^(1-p) s^-2).
    pub k: f64,
    /// Damping `c`: kg m^-p s^-1 (SHCCM), kg s^-1 (MCM).
    pub c: f64,
    /// Bouc-Wen exponent `n`.
    pub n: f64,
    /// Force exponent `p`.
    pub p: f64,
    /// Share of the elastic element `α` in (0, 1).
    pub alpha: f64,
    /// Bouc-Wen `β` (m^-n).
    pub beta: f64,
    /// Bouc-Wen `γ` (m^-n).
    pub gamma: f64,
    /// Bouc-Wen `A`.
    pub a: f64,
}

impl Physical {
    /// The Hertz law with a damping `c |x|^p u` as a BWSHCCL: `β = γ = 0`, `A = 1` (the
    /// Bouc-Wen element a spring, `z = x`), `α = 1/2`, `n = 1`, `p = 3/2`, so that
    /// `F = -k |x|^(1/2) x - c |x|^(3/2) u`: Hunt-Crossley's law with `c = (3/2) α_HC k`.
    pub const fn hertz_damped(k: f64, c: f64) -> Self {
        Physical {
            k,
            c,
            n: 1.0,
            p: 1.5,
            alpha: 0.5,
            beta: 0.0,
            gamma: 0.0,
            a: 1.0,
        }
    }
}

/// Validated SI parameters of one model: the contact law plus its model kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalParams {
    kind: ModelKind,
    law: Physical,
}

impl PhysicalParams {
    /// Validates `law` for `kind`: `A, k > 0`, `α ∈ (0, 1)`, `c >= 0` (SHCCM) or `c > 0` (MCM),
    /// `β >= 0`, `γ ∈ [-β, β]`, `n, p >= 1`, all finite.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] naming the first offending parameter.
    pub fn new(kind: ModelKind, law: Physical) -> Result<Self, ModelError> {
        check("k", law.k, law.k > 0.0, "k > 0")?;
        match kind {
            ModelKind::Shccm => check("c", law.c, law.c >= 0.0, "c >= 0 for the BWSHCCM")?,
            ModelKind::Mcm => check("c", law.c, law.c > 0.0, "c > 0 for the BWMCM")?,
        }
        check("n", law.n, law.n >= 1.0, "n >= 1")?;
        check("p", law.p, law.p >= 1.0, "p >= 1")?;
        check(
            "alpha",
            law.alpha,
            law.alpha > 0.0 && law.alpha < 1.0,
            "0 < alpha < 1",
        )?;
        check("beta", law.beta, law.beta >= 0.0, "beta >= 0")?;
        check(
            "gamma",
            law.gamma,
            law.gamma.abs() <= law.beta,
            "-beta <= gamma <= beta",
        )?;
        check("A", law.a, law.a > 0.0, "A > 0")?;
        Ok(Self { kind, law })
    }

    /// The model kind.
    pub fn kind(&self) -> ModelKind {
        self.kind
    }

    /// The parameters.
    pub fn law(&self) -> &Physical {
        &self.law
    }
}

/// Nondimensional parameters `P = (B, Γ, κ, σ, n, p)`, unvalidated plain data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nondim {
    /// `B >= 0`.
    pub b: f64,
    /// `Γ ∈ [-B, B]`.
    pub gamma: f64,
    /// `κ ∈ (0, 1)`.
    pub kappa: f64,
    /// `σ >= 0` (NDBWSHCCM) or `σ > 0` (NDBWMCM).
    pub sigma: f64,
    /// `n >= 1`.
    pub n: f64,
    /// `p >= 1`.
    pub p: f64,
}

/// Validated nondimensional parameters of one model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NondimParams {
    kind: ModelKind,
    p: Nondim,
}

impl NondimParams {
    /// Validates `p` for `kind` (Sections 4, 5): `B >= 0`, `Γ ∈ [-B, B]`, `κ ∈ (0, 1)`,
    /// `σ >= 0` (SHCCM) or `σ > 0` (MCM), `n, p >= 1`, all finite.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] naming the first offending parameter.
    pub fn new(kind: ModelKind, p: Nondim) -> Result<Self, ModelError> {
        check("B", p.b, p.b >= 0.0, "B >= 0")?;
        check("Gamma", p.gamma, p.gamma.abs() <= p.b, "-B <= Gamma <= B")?;
        check(
            "kappa",
            p.kappa,
            p.kappa > 0.0 && p.kappa < 1.0,
            "0 < kappa < 1",
        )?;
        match kind {
            ModelKind::Shccm => check(
                "sigma",
                p.sigma,
                p.sigma >= 0.0,
                "sigma >= 0 for the NDBWSHCCM",
            )?,
            ModelKind::Mcm => check("sigma", p.sigma, p.sigma > 0.0, "sigma > 0 for the NDBWMCM")?,
        }
        check("n", p.n, p.n >= 1.0, "n >= 1")?;
        check("p", p.p, p.p >= 1.0, "p >= 1")?;
        Ok(Self { kind, p })
    }

    /// The model kind.
    pub fn kind(&self) -> ModelKind {
        self.kind
    }

    /// The parameters.
    pub fn get(&self) -> &Nondim {
        &self.p
    }
}

/// Base parameters `P* = (B_b, Γ_b, κ, σ_b, n, p, U_b, T_b)` (Sections 4, 5), unvalidated plain
/// data; [`crate::BaseMap::new`] validates them for a model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaseParams {
    /// `B_b >= 0`.
    pub b_b: f64,
    /// `Γ_b ∈ [-B_b, B_b]`.
    pub gamma_b: f64,
    /// `κ ∈ (0, 1)`.
    pub kappa: f64,
    /// `σ_b >= 0` (SHCCM) or `σ_b > 0` (MCM).
    pub sigma_b: f64,
    /// `n >= 1`.
    pub n: f64,
    /// `p >= 1`.
    pub p: f64,
    /// `U_b > 0` (irrelevant when `u = 0`).
    pub u_b: f64,
    /// `T_b > 0` (irrelevant when `u = 0`, except to express durations in seconds).
    pub t_b: f64,
}

impl BaseParams {
    /// Base parameters of an unforced impact in nondimensional time: `U_b = T_b = 1`, which
    /// do not matter without an input and durations in seconds.
    pub const fn unforced(
        b_b: f64,
        gamma_b: f64,
        kappa: f64,
        sigma_b: f64,
        n: f64,
        p: f64,
    ) -> Self {
        BaseParams {
            b_b,
            gamma_b,
            kappa,
            sigma_b,
            n,
            p,
            u_b: 1.0,
            t_b: 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law() -> Physical {
        Physical {
            k: 1e6,
            c: 1e3,
            n: 1.5,
            p: 1.5,
            alpha: 0.5,
            beta: 1e4,
            gamma: -5e3,
            a: 1.0,
        }
    }

    #[test]
    fn admissible_sets() {
        assert!(PhysicalParams::new(ModelKind::Shccm, law()).is_ok());
        assert!(PhysicalParams::new(ModelKind::Shccm, Physical { c: 0.0, ..law() }).is_ok());
        let e = PhysicalParams::new(ModelKind::Mcm, Physical { c: 0.0, ..law() }).unwrap_err();
        assert_eq!(
            e,
            ModelError::InvalidParameter {
                name: "c",
                value: 0.0,
                allowed: "c > 0 for the BWMCM"
            }
        );
        let e = PhysicalParams::new(
            ModelKind::Shccm,
            Physical {
                gamma: 2e4,
                ..law()
            },
        )
        .unwrap_err();
        assert!(
            e.to_string().contains("gamma") && e.to_string().contains("20000"),
            "{e}"
        );
        assert!(PhysicalParams::new(
            ModelKind::Shccm,
            Physical {
                alpha: 1.0,
                ..law()
            }
        )
        .is_err());
        assert!(PhysicalParams::new(ModelKind::Shccm, Physical { p: 0.9, ..law() }).is_err());
        assert!(PhysicalParams::new(
            ModelKind::Shccm,
            Physical {
                k: f64::NAN,
                ..law()
            }
        )
        .is_err());

        let nd = Nondim {
            b: 1.0,
            gamma: -1.0,
            kappa: 0.5,
            sigma: 0.0,
            n: 1.0,
            p: 1.0,
        };
        assert!(NondimParams::new(ModelKind::Shccm, nd).is_ok());
        assert!(NondimParams::new(ModelKind::Mcm, nd).is_err());
        assert!(NondimParams::new(
            ModelKind::Shccm,
            Nondim {
                gamma: 1.0 + 1e-12,
                ..nd
            }
        )
        .is_err());
        assert!(NondimParams::new(ModelKind::Shccm, Nondim { kappa: 0.0, ..nd }).is_err());
        assert!(NondimParams::new(
            ModelKind::Shccm,
            Nondim {
                n: f64::INFINITY,
                ..nd
            }
        )
        .is_err());
    }
}

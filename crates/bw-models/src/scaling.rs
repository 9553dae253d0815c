//! Nondimensionalization (Table 1, tab:ND), input scaling (eq:EBWSHCCM_U_nd, eq:EBWMCM_U_nd)
//! and base parameters with their map `P(P*, u, v0)` (Sections 4, 5).

use crate::params::{check, BaseParams, ModelKind, Nondim, NondimParams, Physical, PhysicalParams};
use crate::ModelError;

/// Characteristic scales of an impact (Table 1): `t = T_c T`, `x = X_c X`, `z = Z_c Z`,
/// `v = (X_c / T_c) V = v0 V`, and the input scaling `U(T) = u_factor · u(T_c T)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// Time scale `T_c` (s).
    pub t_c: f64,
    /// Displacement scale `X_c` (m).
    pub x_c: f64,
    /// Hysteretic displacement scale `Z_c = A X_c` (m).
    pub z_c: f64,
    /// Impact speed `v0 = X_c / T_c` (m/s).
    pub v0: f64,
    /// Effective mass `m` (kg).
    pub m: f64,
    /// `U = u_factor · u`: `T_c² / (m X_c)` (1/N).
    pub u_factor: f64,
}

impl Scales {
    /// Force scale `m X_c / T_c²` (N): `F = force() · F_nd`.
    pub fn force(&self) -> f64 {
        1.0 / self.u_factor
    }

    /// Time in seconds of a nondimensional time: `t = T_c T`.
    pub fn time(&self, t_nd: f64) -> f64 {
        self.t_c * t_nd
    }

    /// Displacement in m of a nondimensional displacement (`x`, `r`, `y`): `X_c X`.
    pub fn displacement(&self, x_nd: f64) -> f64 {
        self.x_c * x_nd
    }

    /// Hysteretic displacement in m: `z = Z_c Z`.
    pub fn hysteretic(&self, z_nd: f64) -> f64 {
        self.z_c * z_nd
    }

    /// Velocity in m/s: `v = (X_c / T_c) V = v0 V`.
    pub fn velocity(&self, v_nd: f64) -> f64 {
        self.v0 * v_nd
    }
}

fn check_m_v0(m: f64, v0: f64) -> Result<(), ModelError> {
    check("m", m, m > 0.0, "m > 0 (kg)")?;
    check("v0", v0, v0 > 0.0, "v0 > 0 (m/s)")
}

/// Table 1: the nondimensional parameters and scales of a physical model with effective mass
/// `m` (kg) hitting at relative speed `v0` (m/s).
///
/// With `D = α + (1-α) A^p`: `T_c = D^(-1/(p+1)) (m/k)^(1/(p+1)) v0^(-(p-1)/(p+1))`,
/// `X_c = v0 T_c`, `Z_c = A X_c`, `B = β Z_c^n / A`, `Γ = γ Z_c^n / A`, `κ = α / D`,
/// `σ = c v0 / (D k)` (SHCCM) or `σ = m / (c T_c)` (MCM).
///
/// # Errors
/// [`ModelError::InvalidParameter`] for `m` or `v0` not finite and positive, or if the result
/// leaves the admissible set (overflow).
pub fn nondimensionalize(
    params: &PhysicalParams,
    m: f64,
    v0: f64,
) -> Result<(NondimParams, Scales), ModelError> {
    check_m_v0(m, v0)?;
    let l = params.law();
    let d = l.alpha + (1.0 - l.alpha) * l.a.powf(l.p);
    let q = 1.0 / (l.p + 1.0);
    let t_c = d.powf(-q) * (m / l.k).powf(q) * v0.powf(-(l.p - 1.0) * q);
    let x_c = v0 * t_c;
    let z_c = l.a * x_c;
    let zn = z_c.powf(l.n);
    let sigma = match params.kind() {
        ModelKind::Shccm => l.c * v0 / (d * l.k),
        ModelKind::Mcm => m / (l.c * t_c),
    };
    let nd = Nondim {
        b: l.beta * zn / l.a,
        gamma: l.gamma * zn / l.a,
        kappa: l.alpha / d,
        sigma,
        n: l.n,
        p: l.p,
    };
    let scales = Scales {
        t_c,
        x_c,
        z_c,
        v0,
        m,
        u_factor: t_c * t_c / (m * x_c),
    };
    Ok((NondimParams::new(params.kind(), nd)?, scales))
}

/// The base parameters of a physical model with effective mass `m` (kg): the `P*` for which
/// `P(P*, u, v0)` reproduces Table 1 at every `v0`.
///
/// `B_b = β/A (A^(p+1)/D)^(n/(p+1)) (m/k)^(n/(p+1))`, `Γ_b` likewise with `γ`,
/// `σ_b = c / (D k)` (SHCCM) or `D^(1/(p+1)) (m^p k)^(1/(p+1)) / c` (MCM),
/// `U_b = D^(-1/(p+1)) (m^p k)^(-1/(p+1))`, `T_b = D^(-1/(p+1)) (m/k)^(1/(p+1))`.
///
/// # Errors
/// [`ModelError::InvalidParameter`] for `m` not finite and positive.
pub fn base_params(params: &PhysicalParams, m: f64) -> Result<BaseParams, ModelError> {
    check_m_v0(m, 1.0)?;
    let l = params.law();
    let d = l.alpha + (1.0 - l.alpha) * l.a.powf(l.p);
    let q = 1.0 / (l.p + 1.0);
    let zb = (l.a.powf(l.p + 1.0) / d).powf(l.n * q) * (m / l.k).powf(l.n * q);
    let mpk = (m.powf(l.p) * l.k).powf(q);
    let sigma_b = match params.kind() {
        ModelKind::Shccm => l.c / (d * l.k),
        ModelKind::Mcm => d.powf(q) * mpk / l.c,
    };
    Ok(BaseParams {
        b_b: l.beta / l.a * zb,
        gamma_b: l.gamma / l.a * zb,
        kappa: l.alpha / d,
        sigma_b,
        n: l.n,
        p: l.p,
        u_b: d.powf(-q) / mpk,
        t_b: d.powf(-q) * (m / l.k).powf(q),
    })
}

/// How a physical input `u(t)` enters a nondimensional model: `U(T) = factor · u(time_scale · T)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InputScaling {
    /// Multiplier of the force.
    pub factor: f64,
    /// Multiplier of the time argument (the time scale in seconds).
    pub time_scale: f64,
}

/// Validated base parameters of a model: the map `P(P*, u, v0)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaseMap {
    kind: ModelKind,
    base: BaseParams,
}

impl BaseMap {
    /// Validates `base` for `kind`: `B_b >= 0`, `Γ_b ∈ [-B_b, B_b]`, `κ ∈ (0, 1)`, `σ_b >= 0`
    /// (SHCCM) or `> 0` (MCM), `n, p >= 1`, `U_b, T_b > 0`.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] naming the first offending base parameter.
    pub fn new(kind: ModelKind, base: BaseParams) -> Result<Self, ModelError> {
        check("B_b", base.b_b, base.b_b >= 0.0, "B_b >= 0")?;
        check(
            "Gamma_b",
            base.gamma_b,
            base.gamma_b.abs() <= base.b_b,
            "-B_b <= Gamma_b <= B_b",
        )?;
        check(
            "kappa",
            base.kappa,
            base.kappa > 0.0 && base.kappa < 1.0,
            "0 < kappa < 1",
        )?;
        match kind {
            ModelKind::Shccm => check(
                "sigma_b",
                base.sigma_b,
                base.sigma_b >= 0.0,
                "sigma_b >= 0 for the NDBWSHCCM",
            )?,
            ModelKind::Mcm => check(
                "sigma_b",
                base.sigma_b,
                base.sigma_b > 0.0,
                "sigma_b > 0 for the NDBWMCM",
            )?,
        }
        check("n", base.n, base.n >= 1.0, "n >= 1")?;
        check("p", base.p, base.p >= 1.0, "p >= 1")?;
        check("U_b", base.u_b, base.u_b > 0.0, "U_b > 0")?;
        check("T_b", base.t_b, base.t_b > 0.0, "T_b > 0")?;
        Ok(Self { kind, base })
    }

    /// The model kind.
    pub fn kind(&self) -> ModelKind {
        self.kind
    }

    /// The base parameters.
    pub fn base(&self) -> &BaseParams {
        &self.base
    }

    /// `P(P*, u, v0)`: nondimensional parameters at impact speed `v0` (m/s),
    /// `B = B_b v0^(2n/(p+1))`, `Γ = Γ_b v0^(2n/(p+1))`, `σ = σ_b v0` (SHCCM) or
    /// `σ_b v0^((p-1)/(p+1))` (MCM), and the input scaling
    /// `U(T) = U_b v0^(-2p/(p+1)) u(T_b v0^(-(p-1)/(p+1)) T)`.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] for `v0` not finite and positive, or if the mapped
    /// parameters leave the admissible set (e.g. overflow at extreme speeds).
    pub fn at(&self, v0: f64) -> Result<(NondimParams, InputScaling), ModelError> {
        check("v0", v0, v0 > 0.0, "v0 > 0 (m/s)")?;
        let b = &self.base;
        let q = 1.0 / (b.p + 1.0);
        let s = v0.powf(2.0 * b.n * q);
        let sigma = match self.kind {
            ModelKind::Shccm => b.sigma_b * v0,
            ModelKind::Mcm => b.sigma_b * v0.powf((b.p - 1.0) * q),
        };
        let nd = Nondim {
            b: b.b_b * s,
            gamma: b.gamma_b * s,
            kappa: b.kappa,
            sigma,
            n: b.n,
            p: b.p,
        };
        let scaling = InputScaling {
            factor: b.u_b * v0.powf(-2.0 * b.p * q),
            time_scale: self.time_scale(v0),
        };
        Ok((NondimParams::new(self.kind, nd)?, scaling))
    }

    /// A contact law with these base parameters, and the mass (kg) they were taken with:
    /// `m = T_b / U_b` (Table 1 makes `U_b / T_b = 1/m` whatever the law). The Bouc-Wen
    /// element's scale is free (`z` may be scaled with `A`, `β`, `γ`); the law takes `A = 1`,
    /// so `α = κ`, `k = m / T_b^(p+1)`, `β = B_b / T_b^n`, `γ = Γ_b / T_b^n` and `c = σ_b k`
    /// (SHCCM) or `c = 1 / (U_b σ_b)` (MCM). [`base_params`] of the result gives `P*` back.
    ///
    /// # Errors
    /// [`ModelError::InvalidParameter`] where the law overflows (extreme `T_b`).
    pub fn physical(&self) -> Result<(PhysicalParams, f64), ModelError> {
        let b = &self.base;
        let m = b.t_b / b.u_b;
        let k = m / b.t_b.powf(b.p + 1.0);
        let zb = b.t_b.powf(b.n);
        let c = match self.kind {
            ModelKind::Shccm => b.sigma_b * k,
            ModelKind::Mcm => 1.0 / (b.u_b * b.sigma_b),
        };
        let law = Physical {
            k,
            c,
            n: b.n,
            p: b.p,
            alpha: b.kappa,
            beta: b.b_b / zb,
            gamma: b.gamma_b / zb,
            a: 1.0,
        };
        check("m", m, m.is_finite() && m > 0.0, "T_b / U_b finite")?;
        Ok((PhysicalParams::new(self.kind, law)?, m))
    }

    /// The time scale at `v0`, `T_b v0^(-(p-1)/(p+1))` (s): a nondimensional duration `T_d`
    /// is `T_d` times this in seconds (eq:Theta_2).
    pub fn time_scale(&self, v0: f64) -> f64 {
        let b = &self.base;
        b.t_b * v0.powf(-(b.p - 1.0) / (b.p + 1.0))
    }
}

//! The nondimensional models (eq:EBWSHCCM_nd, eq:EBWMCM_nd, and the earlier NDBWMCM form
//! eq:BWMCM_nd): Table 1's scales, `V(0) = -1`, the right-hand sides the series and
//! double-double paths expand.

use super::coefficients::NdCoefficients;
use super::collision::{input_of_field, nondimensional_scales, unforced, CollisionModel};
use super::form::NdForm;
use crate::clearance::shccm_clearance;
use crate::error::ModelError;
use crate::input::Input;
use crate::laws::hysteresis;
use crate::params::{ModelKind, NondimParams};
use crate::power::{Pow, Powers};
use bwc_ode::{Matrix, State, System};

/// NDBWSHCCM (eq:EBWSHCCM_nd), states `(X, Z, V)`:
/// `X' = V`, `Z' = V - B|Z|^(n-1) Z |V| - Γ|Z|^n V`,
/// `V' = -κ|X|^(p-1) X - (1-κ)|Z|^(p-1) Z - σ|X|^p V + U(T)`.
/// Units and signs: nondimensional (Table 1's scales); `X < 0` in compression, `V(0) = -1`,
/// `F > 0` pushes the bodies apart, `U > 0` pulls them apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ndbwshccm<I> {
    pub(crate) k: NdCoefficients,
    input: I,
}

impl<I: Input> Ndbwshccm<I> {
    /// The model with coefficients already classified (the fast paths' view of a form).
    pub(crate) fn of(k: NdCoefficients, input: I) -> Self {
        Self { k, input }
    }

    /// The model with validated parameters and input `U(T)`.
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for NDBWMCM parameters.
    pub fn new(params: &NondimParams, input: I) -> Result<Self, ModelError> {
        Ok(Self {
            k: NdCoefficients::new(params, ModelKind::Shccm)?,
            input,
        })
    }

    /// Force `F` and the powers of `|Z|` (for `|Z|^n` when the hysteresis needs it). While
    /// `|Z| = |X|` (loading with `Γ = -B`, where `Z' = X'` exactly) `|Z|^p` is `|X|^p`.
    #[inline]
    fn parts(&self, y: &State<3>) -> (f64, Powers) {
        let (x, z, v) = (y[0], y[1], y[2]);
        let xp = self.k.p.of_abs(x.abs());
        let mut zpow = Powers::of(z.abs());
        let zp = if z.abs() == x.abs() {
            xp
        } else {
            zpow.get(self.k.p)
        };
        let f = -self.k.kappa * xp.copysign(x)
            - (1.0 - self.k.kappa) * zp.copysign(z)
            - self.k.sigma * xp * v;
        (f, zpow)
    }
}

impl<I: Input> System<3> for Ndbwshccm<I> {
    #[inline]
    fn rhs(&self, t: f64, y: &State<3>) -> State<3> {
        let (f, mut zpow) = self.parts(y);
        let v = y[2];
        let n = self.k.n;
        State::<3>::new(
            v,
            hysteresis(1.0, self.k.b, self.k.gamma, y[1], v, || zpow.get(n)),
            f + self.input.at(t),
        )
    }
}

impl<I: Input> CollisionModel<3> for Ndbwshccm<I> {
    fn nondimensional_form(&self) -> Option<NdForm<'_, 3>> {
        Some(NdForm::shccm(self.k, &self.input, None))
    }
    fn initial_state(&self) -> State<3> {
        State::<3>::new(0.0, 0.0, -1.0)
    }
    fn force(&self, y: &State<3>) -> f64 {
        self.parts(y).0
    }
    fn displacement(&self, y: &State<3>) -> f64 {
        y[0]
    }
    fn velocity(&self, y: &State<3>) -> f64 {
        y[2]
    }
    input_of_field!();
    nondimensional_scales!(3);
    fn kinks(&self, _t: f64, y: &State<3>) -> [f64; 2] {
        [y[2], y[1]]
    }
    fn clearance(&self, y: &State<3>, f: &State<3>, rtol: f64) -> f64 {
        shccm_clearance(&self.k.nondim(), (*y).into(), (*f).into(), rtol)
    }
    fn jacobian(&self, _t: f64, y: &State<3>) -> Matrix<3> {
        let k = &self.k;
        let (x, z, v) = (y[0], y[1], y[2]);
        let (dz_dv, dz_dz) = k.dhysteresis(z, v);
        let sx = if x == 0.0 { 0.0 } else { x.signum() };
        let dxp = k.dpow_p(x);
        Matrix::<3>::new(
            0.0,
            0.0,
            1.0,
            0.0,
            dz_dz,
            dz_dv,
            -k.kappa * dxp - k.sigma * dxp * sx * v,
            -(1.0 - k.kappa) * k.dpow_p(z),
            -k.sigma * k.p.of_abs(x.abs()),
        )
    }
}

/// NDBWMCM in the Lipschitz form (eq:EBWMCM_nd), states `(R, Y, Z, V)`:
/// `R' = σ(κ|Y|^(p-1) Y + (1-κ)|Z|^(p-1) Z)`, `Y' = V - R'`,
/// `Z' = Y' - B|Z|^(n-1) Z |Y'| - Γ|Z|^n Y'`, `V' = -κ|Y|^(p-1) Y - (1-κ)|Z|^(p-1) Z + U(T)`;
/// `X = R + Y`, `F = -κ|Y|^(p-1) Y - (1-κ)|Z|^(p-1) Z`.
/// Units and signs: nondimensional (Table 1's scales); `X < 0` in compression, `V(0) = -1`,
/// `F > 0` pushes the bodies apart, `U > 0` pulls them apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ndbwmcm<I> {
    pub(crate) k: NdCoefficients,
    input: I,
}

impl<I: Input> Ndbwmcm<I> {
    /// The model with coefficients already classified (the fast paths' view of a form).
    pub(crate) fn of(k: NdCoefficients, input: I) -> Self {
        Self { k, input }
    }

    /// The model with validated parameters and input `U(T)`.
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for NDBWSHCCM parameters.
    pub fn new(params: &NondimParams, input: I) -> Result<Self, ModelError> {
        Ok(Self {
            k: NdCoefficients::new(params, ModelKind::Mcm)?,
            input,
        })
    }

    /// Force `F` and the powers of `|Z|` (for `|Z|^n` when the hysteresis needs it). While
    /// `|Z| = |Y|` (loading with `Γ = -B`, where `Z' = Y'` exactly) `|Z|^p` is `|Y|^p`.
    #[inline]
    fn parts(&self, y: &State<4>) -> (f64, Powers) {
        let (yy, z) = (y[1], y[2]);
        let yp = self.k.p.of_abs(yy.abs());
        let mut zpow = Powers::of(z.abs());
        let zp = if z.abs() == yy.abs() {
            yp
        } else {
            zpow.get(self.k.p)
        };
        let f = -self.k.kappa * yp.copysign(yy) - (1.0 - self.k.kappa) * zp.copysign(z);
        (f, zpow)
    }

    #[inline]
    fn force_of(&self, y: &State<4>) -> f64 {
        self.parts(y).0
    }
}

impl<I: Input> System<4> for Ndbwmcm<I> {
    #[inline]
    fn rhs(&self, t: f64, y: &State<4>) -> State<4> {
        let (f, mut zpow) = self.parts(y);
        let rdot = -self.k.sigma * f;
        let ydot = y[3] - rdot;
        let n = self.k.n;
        State::<4>::new(
            rdot,
            ydot,
            hysteresis(1.0, self.k.b, self.k.gamma, y[2], ydot, || zpow.get(n)),
            f + self.input.at(t),
        )
    }
}

impl<I: Input> CollisionModel<4> for Ndbwmcm<I> {
    fn nondimensional_form(&self) -> Option<NdForm<'_, 4>> {
        Some(NdForm::mcm(self.k, &self.input, None))
    }
    fn initial_state(&self) -> State<4> {
        State::<4>::new(0.0, 0.0, 0.0, -1.0)
    }
    fn force(&self, y: &State<4>) -> f64 {
        self.force_of(y)
    }
    fn displacement(&self, y: &State<4>) -> f64 {
        y[0] + y[1]
    }
    fn velocity(&self, y: &State<4>) -> f64 {
        y[3]
    }
    input_of_field!();
    nondimensional_scales!(4);
    fn kinks(&self, _t: f64, y: &State<4>) -> [f64; 2] {
        [y[3] + self.k.sigma * self.force_of(y), y[2]]
    }
    fn jacobian(&self, _t: f64, y: &State<4>) -> Matrix<4> {
        let k = &self.k;
        // F = -κ|Y|^(p-1)Y - (1-κ)|Z|^(p-1)Z; R' = -σF; Y' = V + σF; Z' = h(Z, Y'); V' = F + U.
        let (f_y, f_z) = (-k.kappa * k.dpow_p(y[1]), -(1.0 - k.kappa) * k.dpow_p(y[2]));
        let ydot = y[3] + k.sigma * self.force_of(y);
        let (dz_dw, dz_dz) = k.dhysteresis(y[2], ydot);
        Matrix::<4>::new(
            0.0,
            -k.sigma * f_y,
            -k.sigma * f_z,
            0.0,
            0.0,
            k.sigma * f_y,
            k.sigma * f_z,
            1.0,
            0.0,
            dz_dw * k.sigma * f_y,
            dz_dw * k.sigma * f_z + dz_dz,
            dz_dw,
            0.0,
            f_y,
            f_z,
            0.0,
        )
    }
}

/// The earlier NDBWMCM form (eq:BWMCM_nd, no input), states `(R, Y, Z, W)`:
/// `R' = κσ|Y|^(p-1) Y + (1-κ)σ|Z|^(p-1) Z`, `Y' = W`, `Z' = W - B|Z|^(n-1) Z |W| - Γ|Z|^n W`,
/// `W' = -R'/σ - κ p σ |Y|^(p-1) Y' - (1-κ) p σ |Z|^(p-1) Z'`; outputs `X = R + Y`,
/// `V = R' + Y'`. Well posed for `p = 1` or `p >= 2`; kept for the equivalence with
/// [`Ndbwmcm`] at `u = 0` that the paper states.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NdbwmcmEarlier {
    inner: Ndbwmcm<crate::input::Zero>,
    pm1: Pow,
}

impl NdbwmcmEarlier {
    /// The model with validated NDBWMCM parameters.
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for NDBWSHCCM parameters.
    pub fn new(params: &NondimParams) -> Result<Self, ModelError> {
        let inner = Ndbwmcm::new(params, crate::input::Zero)?;
        Ok(Self {
            inner,
            pm1: Pow::new(params.get().p - 1.0),
        })
    }

    fn rdot(&self, y: &State<4>) -> f64 {
        -self.inner.k.sigma * self.inner.force_of(y)
    }
}

impl System<4> for NdbwmcmEarlier {
    fn rhs(&self, _t: f64, y: &State<4>) -> State<4> {
        let m = &self.inner.k;
        let (yy, z, w) = (y[1], y[2], y[3]);
        let rdot = self.rdot(y);
        let zdot = hysteresis(1.0, m.b, m.gamma, z, w, || m.n.of_abs(z.abs()));
        let p = m.p.exponent();
        let wdot = -rdot / m.sigma
            - m.kappa * p * m.sigma * self.pm1.of_abs(yy.abs()) * w
            - (1.0 - m.kappa) * p * m.sigma * self.pm1.of_abs(z.abs()) * zdot;
        State::<4>::new(rdot, w, zdot, wdot)
    }
}

impl CollisionModel<4> for NdbwmcmEarlier {
    fn initial_state(&self) -> State<4> {
        State::<4>::new(0.0, 0.0, 0.0, -1.0)
    }
    fn force(&self, y: &State<4>) -> f64 {
        self.inner.force_of(y)
    }
    fn displacement(&self, y: &State<4>) -> f64 {
        y[0] + y[1]
    }
    fn velocity(&self, y: &State<4>) -> f64 {
        self.rdot(y) + y[3]
    }
    unforced!();
    nondimensional_scales!(4);
    fn kinks(&self, _t: f64, y: &State<4>) -> [f64; 2] {
        [y[3], y[2]]
    }
}

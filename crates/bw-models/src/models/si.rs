//! The dimensional models (eq:EBWSHCCM, eq:EBWMCM) in SI units: the laws of `crate::laws`
//! driven by the relative motion of a mass `m`, with CoRs taken through their nondimensional
//! forms (Table 1) where the input is constant.

use super::coefficients::NdCoefficients;
use super::collision::{input_of_field, unforced, CollisionModel};
use super::form::NdForm;
use crate::clearance::{in_natural_units, shccm_clearance};
use crate::error::ModelError;
use crate::input::Input;
use crate::laws::{hysteresis, Bwmcl, Bwshccl};
use crate::params::{check, ModelKind, PhysicalParams};
use crate::power::Pow;
use crate::scaling::{nondimensionalize, Scales};
use bwc_ode::{State, System};

/// BWSHCCM (eq:EBWSHCCM) in SI units, states `(x, z, v)`: the BWSHCCL driven by `v`, and
/// `m v̇ = F + u(t)`.
/// Units and signs: `x`, `r`, `y`, `z` in m with `x < 0` in compression (the bodies overlap),
/// `v` in m/s (relative velocity, `v(0) = -v0 < 0` as the bodies approach), `F` in N (positive
/// pushes the bodies apart), `u` in N (the relative input, positive pulls them apart), `m` in kg.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bwshccm<I> {
    law: Bwshccl,
    m: f64,
    v0: f64,
    scales: Scales,
    /// The nondimensional form's coefficients (Table 1), classified once.
    k: NdCoefficients,
    input: I,
}

impl<I: Input> Bwshccm<I> {
    /// The model with validated parameters, effective mass `m` (kg), impact speed `v0` (m/s)
    /// and external input `u(t)` (N).
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for MCM parameters, [`ModelError::InvalidParameter`] for `m`
    /// or `v0`.
    pub fn new(params: &PhysicalParams, m: f64, v0: f64, input: I) -> Result<Self, ModelError> {
        check_mass_speed(m, v0)?;
        let (nd, scales) = nondimensionalize(params, m, v0)?;
        let law = Bwshccl::new(params)?;
        Ok(Self {
            law,
            m,
            v0,
            scales,
            k: NdCoefficients::new(&nd, ModelKind::Shccm)?,
            input,
        })
    }
}

impl<I: Input> System<3> for Bwshccm<I> {
    #[inline]
    fn rhs(&self, t: f64, y: &State<3>) -> State<3> {
        let (d, f) = self.law.eval(&State::<2>::new(y[0], y[1]), y[2]);
        State::<3>::new(d[0], d[1], (f + self.input.at(t)) / self.m)
    }
}

impl<I: Input> CollisionModel<3> for Bwshccm<I> {
    fn nondimensional_form(&self) -> Option<NdForm<'_, 3>> {
        Some(NdForm::shccm(self.k, &self.input, Some(self.scales)))
    }
    fn initial_state(&self) -> State<3> {
        State::<3>::new(0.0, 0.0, -self.v0)
    }
    fn force(&self, y: &State<3>) -> f64 {
        self.law.eval(&State::<2>::new(y[0], y[1]), y[2]).1
    }
    fn displacement(&self, y: &State<3>) -> f64 {
        y[0]
    }
    fn velocity(&self, y: &State<3>) -> f64 {
        y[2]
    }
    input_of_field!();
    fn impact_speed(&self) -> f64 {
        self.v0
    }
    fn state_scale(&self) -> State<3> {
        State::<3>::new(self.scales.x_c, self.scales.z_c, self.v0)
    }
    fn time_scale(&self) -> f64 {
        self.scales.t_c
    }
    fn kinks(&self, _t: f64, y: &State<3>) -> [f64; 2] {
        [y[2] / self.v0, y[1] / self.scales.z_c]
    }
    fn clearance(&self, y: &State<3>, f: &State<3>, rtol: f64) -> f64 {
        let t_c = self.scales.t_c;
        let (y, f) = in_natural_units(y, f, self.state_scale(), t_c);
        t_c * shccm_clearance(&self.k.nondim(), y.into(), f.into(), rtol)
    }
}

/// BWMCM in the Lipschitz form (eq:EBWMCM) in SI units, states `(r, y, z, v)`: the BWMCL
/// driven by `v`, and `m v̇ = F + u(t)`; `x = r + y`.
/// Units and signs: `x`, `r`, `y`, `z` in m with `x < 0` in compression (the bodies overlap),
/// `v` in m/s (relative velocity, `v(0) = -v0 < 0` as the bodies approach), `F` in N (positive
/// pushes the bodies apart), `u` in N (the relative input, positive pulls them apart), `m` in kg.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bwmcm<I> {
    law: Bwmcl,
    m: f64,
    v0: f64,
    scales: Scales,
    /// The nondimensional form's coefficients (Table 1), classified once.
    k: NdCoefficients,
    input: I,
}

impl<I: Input> Bwmcm<I> {
    /// The model with validated parameters, effective mass `m` (kg), impact speed `v0` (m/s)
    /// and external input `u(t)` (N).
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for SHCCM parameters, [`ModelError::InvalidParameter`] for
    /// `m` or `v0`.
    pub fn new(params: &PhysicalParams, m: f64, v0: f64, input: I) -> Result<Self, ModelError> {
        check_mass_speed(m, v0)?;
        let (nd, scales) = nondimensionalize(params, m, v0)?;
        let law = Bwmcl::new(params)?;
        Ok(Self {
            law,
            m,
            v0,
            scales,
            k: NdCoefficients::new(&nd, ModelKind::Mcm)?,
            input,
        })
    }
}

impl<I: Input> System<4> for Bwmcm<I> {
    #[inline]
    fn rhs(&self, t: f64, y: &State<4>) -> State<4> {
        let (d, f) = self.law.eval(&State::<3>::new(y[0], y[1], y[2]), y[3]);
        State::<4>::new(d[0], d[1], d[2], (f + self.input.at(t)) / self.m)
    }
}

impl<I: Input> CollisionModel<4> for Bwmcm<I> {
    fn nondimensional_form(&self) -> Option<NdForm<'_, 4>> {
        Some(NdForm::mcm(self.k, &self.input, Some(self.scales)))
    }
    fn initial_state(&self) -> State<4> {
        State::<4>::new(0.0, 0.0, 0.0, -self.v0)
    }
    fn force(&self, y: &State<4>) -> f64 {
        self.law.eval(&State::<3>::new(y[0], y[1], y[2]), y[3]).1
    }
    fn displacement(&self, y: &State<4>) -> f64 {
        y[0] + y[1]
    }
    fn velocity(&self, y: &State<4>) -> f64 {
        y[3]
    }
    input_of_field!();
    fn impact_speed(&self) -> f64 {
        self.v0
    }
    fn state_scale(&self) -> State<4> {
        State::<4>::new(self.scales.x_c, self.scales.x_c, self.scales.z_c, self.v0)
    }
    fn time_scale(&self) -> f64 {
        self.scales.t_c
    }
    fn kinks(&self, _t: f64, y: &State<4>) -> [f64; 2] {
        let (d, _) = self.law.eval(&State::<3>::new(y[0], y[1], y[2]), y[3]);
        [d[1] / self.v0, y[2] / self.scales.z_c]
    }
}

/// The earlier BWMCM form (eq:BWMCM, no input) in SI units, states `(r, y, z, w)`:
/// `ṙ = (k/c)(α|y|^(p-1) y + (1-α)|z|^(p-1) z)`, `ẏ = w`, `ż = A w - β|z|^(n-1) z |w| - γ|z|^n w`,
/// `ẇ = -(c/m) ṙ - α p (k/c) |y|^(p-1) ẏ - (1-α) p (k/c) |z|^(p-1) ż`; outputs `x = r + y`,
/// `v = ṙ + ẏ` (eq:BWMCM_output). Well posed for `p = 1` or `p >= 2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BwmcmEarlier {
    law: Bwmcl,
    m: f64,
    v0: f64,
    scales: Scales,
    pm1: Pow,
}

impl BwmcmEarlier {
    /// The model with validated MCM parameters, effective mass `m` (kg) and impact speed `v0`.
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for SHCCM parameters, [`ModelError::InvalidParameter`] for
    /// `m` or `v0`.
    pub fn new(params: &PhysicalParams, m: f64, v0: f64) -> Result<Self, ModelError> {
        check_mass_speed(m, v0)?;
        let (_, scales) = nondimensionalize(params, m, v0)?;
        Ok(Self {
            law: Bwmcl::new(params)?,
            m,
            v0,
            scales,
            pm1: Pow::new(params.law().p - 1.0),
        })
    }

    fn rdot(&self, y: &State<4>) -> f64 {
        let l = &self.law.0;
        l.k / l.c * (l.alpha * l.p.signed(y[1]) + (1.0 - l.alpha) * l.p.signed(y[2]))
    }
}

impl System<4> for BwmcmEarlier {
    fn rhs(&self, _t: f64, y: &State<4>) -> State<4> {
        let l = &self.law.0;
        let (yy, z, w) = (y[1], y[2], y[3]);
        let rdot = self.rdot(y);
        let zdot = hysteresis(l.a, l.beta, l.gamma, z, w, || l.n.of_abs(z.abs()));
        let p = l.p.exponent();
        let wdot = -l.c / self.m * rdot
            - l.alpha * p * l.k / l.c * self.pm1.of_abs(yy.abs()) * w
            - (1.0 - l.alpha) * p * l.k / l.c * self.pm1.of_abs(z.abs()) * zdot;
        State::<4>::new(rdot, w, zdot, wdot)
    }
}

impl CollisionModel<4> for BwmcmEarlier {
    fn initial_state(&self) -> State<4> {
        State::<4>::new(0.0, 0.0, 0.0, -self.v0)
    }
    fn force(&self, y: &State<4>) -> f64 {
        -self.law.0.c * self.rdot(y)
    }
    fn displacement(&self, y: &State<4>) -> f64 {
        y[0] + y[1]
    }
    fn velocity(&self, y: &State<4>) -> f64 {
        self.rdot(y) + y[3]
    }
    unforced!();
    fn impact_speed(&self) -> f64 {
        self.v0
    }
    fn state_scale(&self) -> State<4> {
        State::<4>::new(self.scales.x_c, self.scales.x_c, self.scales.z_c, self.v0)
    }
    fn time_scale(&self) -> f64 {
        self.scales.t_c
    }
    fn kinks(&self, _t: f64, y: &State<4>) -> [f64; 2] {
        [y[3] / self.v0, y[2] / self.scales.z_c]
    }
}

fn check_mass_speed(m: f64, v0: f64) -> Result<(), ModelError> {
    check("m", m, m > 0.0, "m > 0 (kg)")?;
    check("v0", v0, v0 > 0.0, "v0 > 0 (m/s)")
}

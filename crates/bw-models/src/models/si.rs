//! The dimensional models (eq:EBWSHCCM, eq:EBWMCM) in SI units: the laws of `crate::laws`
//! driven by the relative motion of a mass `m`, with CoRs taken through their nondimensional
//! forms (Table 1) where the input is constant.

use super::{check_mass_speed, CollisionModel, Ndbwmcm, Ndbwshccm};
use crate::clearance::{in_natural_units, shccm_clearance};
use crate::input::{Constant, Input, Scaled};
use crate::laws::{hysteresis, Bwmcl, Bwshccl};
use crate::params::{ModelKind, NondimParams, PhysicalParams};
use crate::power::Pow;
use crate::series::SeriesRun;
use crate::{Impact, ModelError, Settings, State};
use bwc_ode::System;

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
    scales: crate::Scales,
    nd: NondimParams,
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
        let (nd, scales) = crate::scaling::nondimensionalize(params, m, v0)?;
        Ok(Self {
            law: Bwshccl::new(params)?,
            m,
            v0,
            scales,
            nd,
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
    fn input(&self, t: f64) -> f64 {
        self.input.at(t)
    }
    fn input_constant_after(&self) -> Option<f64> {
        self.input.constant_after()
    }
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
        t_c * shccm_clearance(self.nd.get(), y.into(), f.into(), rtol)
    }
    fn series_impact(
        &self,
        key: crate::series::Private,
        settings: &Settings,
    ) -> Option<SeriesRun<3>> {
        let u = nondimensional_input(&self.input, &self.scales)?;
        let run = Ndbwshccm::new(&self.nd, u)
            .ok()?
            .series_impact(key, settings)?;
        Some(in_si(run, self.state_scale(), self.scales.t_c))
    }
    fn phase_impact(&self, key: crate::series::Private, settings: &Settings) -> Option<Impact<3>> {
        if !self.input.is_zero() {
            return None;
        }
        let out = Ndbwshccm::new(&self.nd, crate::input::Zero)
            .ok()?
            .phase_impact(key, settings)?;
        Some(phase_in_si(out, self.state_scale(), self.scales.t_c))
    }
    fn double_double_impact(
        &self,
        _: crate::series::Private,
        ext: bwc_ode::Extrapolation,
        settings: &Settings,
    ) -> Option<Result<crate::Impact<3>, crate::precise::DdFailure>> {
        let scale = self.state_scale();
        let state_of = |y: [f64; 4]| State::<3>::new(y[1], y[2], y[3]).component_mul(&scale);
        dd_in_si(
            (ModelKind::Shccm, &self.nd, &self.input),
            &self.scales,
            ext,
            settings,
            state_of,
        )
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
    scales: crate::Scales,
    nd: NondimParams,
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
        let (nd, scales) = crate::scaling::nondimensionalize(params, m, v0)?;
        Ok(Self {
            law: Bwmcl::new(params)?,
            m,
            v0,
            scales,
            nd,
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
    fn input(&self, t: f64) -> f64 {
        self.input.at(t)
    }
    fn input_constant_after(&self) -> Option<f64> {
        self.input.constant_after()
    }
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
    fn series_impact(
        &self,
        key: crate::series::Private,
        settings: &Settings,
    ) -> Option<SeriesRun<4>> {
        let u = nondimensional_input(&self.input, &self.scales)?;
        let run = Ndbwmcm::new(&self.nd, u)
            .ok()?
            .series_impact(key, settings)?;
        Some(in_si(run, self.state_scale(), self.scales.t_c))
    }
    fn phase_impact(&self, key: crate::series::Private, settings: &Settings) -> Option<Impact<4>> {
        if !self.input.is_zero() {
            return None;
        }
        let out = Ndbwmcm::new(&self.nd, crate::input::Zero)
            .ok()?
            .phase_impact(key, settings)?;
        Some(phase_in_si(out, self.state_scale(), self.scales.t_c))
    }
    fn double_double_impact(
        &self,
        _: crate::series::Private,
        ext: bwc_ode::Extrapolation,
        settings: &Settings,
    ) -> Option<Result<crate::Impact<4>, crate::precise::DdFailure>> {
        let scale = self.state_scale();
        let state_of = |y: [f64; 4]| State::<4>::from(y).component_mul(&scale);
        dd_in_si(
            (ModelKind::Mcm, &self.nd, &self.input),
            &self.scales,
            ext,
            settings,
            state_of,
        )
    }
}

/// A constant input `u` (N) as the nondimensional models' `U = u T_c² / (m X_c)` (Table 1);
/// `None` for an input that varies (the series path takes constant inputs only).
fn nondimensional_input<I: Input>(input: &I, scales: &crate::Scales) -> Option<Constant> {
    input
        .is_constant()
        .then(|| Constant(input.at(0.0) * scales.u_factor))
}

/// The double-double run of an SI model: its nondimensional model `kind` with parameters `nd`
/// under the input `u(t)` (N) as `U(T) = u(T T_c) T_c² / (m X_c)` (Table 1), with the state
/// `state_of` the run's `(R, Y, Z, V)` and the times in seconds.
fn dd_in_si<I: Input, const N: usize>(
    (kind, nd, input): (ModelKind, &NondimParams, &I),
    scales: &crate::Scales,
    ext: bwc_ode::Extrapolation,
    settings: &Settings,
    state_of: impl Fn([f64; 4]) -> State<N>,
) -> Option<Result<crate::Impact<N>, crate::precise::DdFailure>> {
    let u = Scaled {
        inner: input,
        factor: scales.u_factor,
        time_scale: scales.t_c,
    };
    let run = crate::precise::run_model((kind, *nd.get(), &u), ext, settings, state_of)?;
    Some(run.map(|out| Impact {
        t_s: out.t_s.map(|t| t * scales.t_c),
        ..out
    }))
}

/// A phase impact of the nondimensional model in the SI model's units: times times `T_c`,
/// each state component times its scale (Table 1).
fn phase_in_si<const N: usize>(out: Impact<N>, scale: State<N>, t_c: f64) -> Impact<N> {
    Impact {
        t_s: out.t_s.map(|t| t * t_c),
        t_s_error: out.t_s_error.map(|t| t * t_c),
        state: out.state.component_mul(&scale),
        ..out
    }
}

/// A series run of the nondimensional model in the SI model's units: times times `T_c`, each
/// state component times its scale (Table 1; `e = V(T_s) = v(t_s) / v0` is the same).
fn in_si<const N: usize>(run: SeriesRun<N>, scale: State<N>, t_c: f64) -> SeriesRun<N> {
    match run {
        SeriesRun::Done(out) => SeriesRun::Done(Impact {
            t_s: out.t_s.map(|t| t * t_c),
            state: out.state.component_mul(&scale),
            settled_at: out.settled_at.map(|t| t * t_c),
            stiff_from: out.stiff_from.map(|t| t * t_c),
            ..out
        }),
        SeriesRun::HandOver {
            t,
            state,
            stats,
            series_steps,
        } => SeriesRun::HandOver {
            t: t * t_c,
            state: state.component_mul(&scale),
            stats,
            series_steps,
        },
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
    scales: crate::Scales,
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
        let (_, scales) = crate::scaling::nondimensionalize(params, m, v0)?;
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
    fn input(&self, _t: f64) -> f64 {
        0.0
    }
    fn input_constant_after(&self) -> Option<f64> {
        Some(f64::NEG_INFINITY)
    }
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

//! The collision models with external input: BWSHCCM (eq:EBWSHCCM), BWMCM in the Lipschitz form
//! (eq:EBWMCM), their nondimensional forms (eq:EBWSHCCM_nd, eq:EBWMCM_nd), and the earlier
//! NDBWMCM form (eq:BWMCM_nd) for the equivalence the paper states.

use crate::clearance::{in_natural_units, shccm_clearance};
use crate::input::{Constant, Input, Scaled};
use crate::laws::{hysteresis, Bwmcl, Bwshccl};
use crate::params::{check, ModelKind, NondimParams, PhysicalParams};
use crate::power::{Pow, Powers};
use crate::series::SeriesRun;
use crate::{ModelError, Nondim, Settings, State};
use bwc_ode::{Matrix, System};

/// A collision model: a right-hand side with the outputs the impact analysis needs.
pub trait CollisionModel<const N: usize>: System<N> {
    /// State at the instant of impact: all displacements zero, relative velocity `-v0`.
    fn initial_state(&self) -> State<N>;
    /// Contact force `F` (positive pushes the bodies apart).
    fn force(&self, y: &State<N>) -> f64;
    /// Relative displacement `x` (`x < 0` is compression).
    fn displacement(&self, y: &State<N>) -> f64;
    /// Relative velocity `v`.
    fn velocity(&self, y: &State<N>) -> f64;
    /// The external input at `t`.
    fn input(&self, t: f64) -> f64;
    /// A time from which the input is constant (model time units; `-inf` for a constant
    /// input), if any (see [`Input::constant_after`]).
    fn input_constant_after(&self) -> Option<f64>;
    /// The crate's Taylor-series fast path of the nondimensional models (a private detail:
    /// its argument cannot be named outside the crate, so other models keep the default,
    /// `None`, and the Runge-Kutta path).
    #[doc(hidden)]
    fn series_impact(
        &self,
        _: crate::series::Private,
        _settings: &Settings,
    ) -> Option<SeriesRun<N>> {
        None
    }
    /// The crate's double-double path of the nondimensional models, and of the SI models
    /// through them ([`Settings::double_double`]; private as [`Self::series_impact`]): `None`
    /// where the model has none.
    #[doc(hidden)]
    fn double_double_impact(
        &self,
        _: crate::series::Private,
        _ext: bwc_ode::Extrapolation,
        _settings: &Settings,
    ) -> Option<Result<crate::Impact<N>, crate::precise::DdFailure>> {
        None
    }
    /// Whether the input is constant at all times.
    fn input_is_constant(&self) -> bool {
        self.input_constant_after() == Some(f64::NEG_INFINITY)
    }
    /// Impact speed `v0` (1 for nondimensional models), so that `e = v(t_s) / v0`.
    fn impact_speed(&self) -> f64;
    /// Natural magnitude of each state component (ones for nondimensional models; the scales
    /// of Table 1 for SI models): absolute tolerances are multiplied by these.
    fn state_scale(&self) -> State<N>;
    /// Natural time scale (1 for nondimensional models, `T_c` in seconds for SI models).
    fn time_scale(&self) -> f64;
    /// Functions whose zeros are the non-smooth points of the right-hand side: the velocity
    /// across the hysteretic element (`|v|` or `|ẏ|`) and `z`, in natural (nondimensional)
    /// units so that they compare with the absolute tolerance.
    fn kinks(&self, t: f64, y: &State<N>) -> [f64; 2];
    /// How long (model time) the state `y`, moving with derivative `f`, stays clear of a point
    /// where the right-hand side is not analytic (the base of a term `c |s|^q` reaching 0), to
    /// first order, while that term matters at tolerance `rtol`; `+inf` where none does (the
    /// default). The Runge-Kutta path with [`Settings::stop_at_kinks`] keeps its steps to half
    /// of it: an embedded error estimate assumes the solution analytic over a few step lengths
    /// and passes steps that end close to such a point with errors of a hundred tolerances
    /// (STABILITY.md, "Session 20"). The NDBWSHCCM and the BWSHCCM say it for `X` and `Z`; the
    /// MCMs keep the default (measured: it moved a flat separation of the NDBWMCM by up to 1e-9
    /// at rtol 1e-9).
    fn clearance(&self, y: &State<N>, f: &State<N>, rtol: f64) -> f64 {
        let _ = (y, f, rtol);
        f64::INFINITY
    }
    /// The Jacobian `∂f/∂y` for implicit methods. Analytic for the nondimensional models; by
    /// default forward differences with steps `√ε max(|y_i|, scale_i)` (relative accuracy about
    /// `1e-8`, enough for the step-size control of RODAS4, which then behaves like a method
    /// of lower order on the affected steps).
    fn jacobian(&self, t: f64, y: &State<N>) -> Matrix<N> {
        let f0 = self.rhs(t, y);
        let scale = self.state_scale();
        let mut j = Matrix::<N>::zeros();
        for c in 0..N {
            let d = f64::EPSILON.sqrt() * y[c].abs().max(scale[c]);
            let mut yc = *y;
            yc[c] += d;
            j.set_column(c, &((self.rhs(t, &yc) - f0) / (yc[c] - y[c])));
        }
        j
    }
}

/// Which nondimensional model a parameter set belongs to.
fn expect_nd(p: &NondimParams, kind: ModelKind) -> Result<(), ModelError> {
    if p.kind() == kind {
        Ok(())
    } else {
        Err(ModelError::WrongModel {
            expected: kind.name(),
            found: p.kind().name(),
        })
    }
}

fn check_mass_speed(m: f64, v0: f64) -> Result<(), ModelError> {
    check("m", m, m > 0.0, "m > 0 (kg)")?;
    check("v0", v0, v0 > 0.0, "v0 > 0 (m/s)")
}

// ----------------------------------------------------------------------------------------------
// Nondimensional models

/// The nondimensional parameters both ND models use, with the exponents classified once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NdCoefficients {
    pub(crate) b: f64,
    pub(crate) gamma: f64,
    pub(crate) kappa: f64,
    pub(crate) sigma: f64,
    pub(crate) n: Pow,
    pub(crate) p: Pow,
    /// `n - 1` and `p - 1`, for the Jacobians.
    nm1: Pow,
    pm1: Pow,
}

impl NdCoefficients {
    /// The parameters as given.
    fn nondim(&self) -> Nondim {
        Nondim {
            b: self.b,
            gamma: self.gamma,
            kappa: self.kappa,
            sigma: self.sigma,
            n: self.n.exponent(),
            p: self.p.exponent(),
        }
    }

    /// `(d/ds |s|^(p-1) s, d/dz ż)` pieces: `p |s|^(p-1)`.
    #[inline]
    pub(crate) fn dpow_p(&self, s: f64) -> f64 {
        self.p.exponent() * self.pm1.of_abs(s.abs())
    }

    /// `∂ż/∂w` and `∂ż/∂z` of `ż = w - |z|^n (B sgn(z) |w| + Γ w)` for the driving rate `w`.
    #[inline]
    fn dhysteresis(&self, z: f64, w: f64) -> (f64, f64) {
        let zn = self.n.of_abs(z.abs());
        let sz = if z == 0.0 { 0.0 } else { z.signum() };
        let sw = if w == 0.0 { 0.0 } else { w.signum() };
        let d_w = 1.0 - zn * (self.gamma + self.b * sz * sw);
        let d_z = -self.n.exponent()
            * self.nm1.of_abs(z.abs())
            * (self.b * w.abs() + self.gamma * w * sz);
        (d_w, d_z)
    }

    fn new(params: &NondimParams, kind: ModelKind) -> Result<Self, ModelError> {
        expect_nd(params, kind)?;
        let p = params.get();
        Ok(Self {
            b: p.b,
            gamma: p.gamma,
            kappa: p.kappa,
            sigma: p.sigma,
            n: Pow::new(p.n),
            p: Pow::new(p.p),
            nm1: Pow::new(p.n - 1.0),
            pm1: Pow::new(p.p - 1.0),
        })
    }
}

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
    fn double_double_impact(
        &self,
        _: crate::series::Private,
        ext: bwc_ode::Extrapolation,
        settings: &Settings,
    ) -> Option<Result<crate::Impact<3>, crate::precise::DdFailure>> {
        let model = (ModelKind::Shccm, self.k.nondim(), &self.input);
        crate::precise::run_model(model, ext, settings, |y| State::<3>::new(y[1], y[2], y[3]))
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
    fn input(&self, t: f64) -> f64 {
        self.input.at(t)
    }
    fn input_constant_after(&self) -> Option<f64> {
        self.input.constant_after()
    }
    fn impact_speed(&self) -> f64 {
        1.0
    }
    fn state_scale(&self) -> State<3> {
        State::<3>::repeat(1.0)
    }
    fn time_scale(&self) -> f64 {
        1.0
    }
    fn kinks(&self, _t: f64, y: &State<3>) -> [f64; 2] {
        [y[2], y[1]]
    }
    fn clearance(&self, y: &State<3>, f: &State<3>, rtol: f64) -> f64 {
        shccm_clearance(&self.k.nondim(), (*y).into(), (*f).into(), rtol)
    }
    fn series_impact(
        &self,
        _: crate::series::Private,
        settings: &Settings,
    ) -> Option<SeriesRun<3>> {
        crate::series::impact(self, settings)
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
    fn double_double_impact(
        &self,
        _: crate::series::Private,
        ext: bwc_ode::Extrapolation,
        settings: &Settings,
    ) -> Option<Result<crate::Impact<4>, crate::precise::DdFailure>> {
        let model = (ModelKind::Mcm, self.k.nondim(), &self.input);
        crate::precise::run_model(model, ext, settings, State::<4>::from)
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
    fn input(&self, t: f64) -> f64 {
        self.input.at(t)
    }
    fn input_constant_after(&self) -> Option<f64> {
        self.input.constant_after()
    }
    fn impact_speed(&self) -> f64 {
        1.0
    }
    fn state_scale(&self) -> State<4> {
        State::<4>::repeat(1.0)
    }
    fn time_scale(&self) -> f64 {
        1.0
    }
    fn kinks(&self, _t: f64, y: &State<4>) -> [f64; 2] {
        [y[3] + self.k.sigma * self.force_of(y), y[2]]
    }
    fn series_impact(
        &self,
        _: crate::series::Private,
        settings: &Settings,
    ) -> Option<SeriesRun<4>> {
        crate::series::impact(self, settings)
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
    fn input(&self, _t: f64) -> f64 {
        0.0
    }
    fn input_constant_after(&self) -> Option<f64> {
        Some(f64::NEG_INFINITY)
    }
    fn impact_speed(&self) -> f64 {
        1.0
    }
    fn state_scale(&self) -> State<4> {
        State::<4>::repeat(1.0)
    }
    fn time_scale(&self) -> f64 {
        1.0
    }
    fn kinks(&self, _t: f64, y: &State<4>) -> [f64; 2] {
        [y[3], y[2]]
    }
}

// ----------------------------------------------------------------------------------------------
// Dimensional models

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
    Some(run.map(|out| crate::Impact {
        t_s: out.t_s.map(|t| t * scales.t_c),
        ..out
    }))
}

/// A series run of the nondimensional model in the SI model's units: times times `T_c`, each
/// state component times its scale (Table 1; `e = V(T_s) = v(t_s) / v0` is the same).
fn in_si<const N: usize>(run: SeriesRun<N>, scale: State<N>, t_c: f64) -> SeriesRun<N> {
    match run {
        SeriesRun::Done(out) => SeriesRun::Done(crate::Impact {
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

//! RODAS4: Hairer & Wanner's L-stable, stiffly accurate Rosenbrock method of order 4(3) with a
//! 3rd-order dense output (Solving ODEs II, Sec. IV.7, code RODAS), for stiff problems.
//!
//! A Rosenbrock method replaces the Newton iterations of an implicit Runge-Kutta method by one
//! linear solve per stage with the same matrix `M = I / (γ h) - J`, `J = ∂f/∂y (t, y)`:
//!
//! ```text
//! M g_i = f(t + c_i h, y + Σ_j a_ij g_j) + d_i h ∂f/∂t + Σ_j c_ij g_j / h,   i = 1..6
//! y_1 = y + Σ_j a_6j g_j + g_6,   error estimate g_6.
//! ```
//!
//! The Jacobian is the system's own ([`Jacobian`]); `∂f/∂t` is a forward difference (one RHS
//! evaluation per step) unless the system says it is autonomous. `M` is inverted by nalgebra on
//! the stack (closed forms up to 4 x 4, LU beyond, without the dimension bounds nalgebra's `lu`
//! would put on every generic caller): a step allocates nothing.

#![allow(clippy::excessive_precision)] // coefficients keep their published digits

use crate::control::Stats;
use crate::control::{aimed, inside_last_step, Limits};
use crate::integrator::{compensated, Dense, Trial};
use crate::{Error, Options, State, System};

/// An `N x N` matrix on the stack.
pub type Matrix<const N: usize> = nalgebra::SMatrix<f64, N, N>;

/// A right-hand side with its Jacobian `∂f/∂y`, as implicit methods need.
pub trait Jacobian<const N: usize>: System<N> {
    /// `∂f/∂y (t, y)`.
    fn jacobian(&self, t: f64, y: &State<N>) -> Matrix<N>;
    /// Whether `f` does not depend on `t` explicitly (then `∂f/∂t = 0` is not computed).
    fn is_autonomous(&self) -> bool {
        false
    }
}

// RODAS4 coefficients (Hairer & Wanner II, Sec. IV.7, as in rodas.f with METH = 1), with the
// published digits.
const GAMMA: f64 = 0.25;
const C: [f64; 6] = [0.0, 0.386, 0.21, 0.63, 1.0, 1.0];
const D: [f64; 4] = [0.25, -0.1043, 0.1035, -0.3620000000000023e-01];
const A: [[f64; 5]; 5] = [
    [0.1544000000000000e+01, 0.0, 0.0, 0.0, 0.0],
    [0.9466785280815826, 0.2557011698983284, 0.0, 0.0, 0.0],
    [
        0.3314825187068521e+01,
        0.2896124015972201e+01,
        0.9986419139977817,
        0.0,
        0.0,
    ],
    [
        0.1221224509226641e+01,
        0.6019134481288629e+01,
        0.1253708332932087e+02,
        -0.6878860361058950,
        0.0,
    ],
    // Row 6 = row 5 plus g_5 (stiffly accurate).
    [
        0.1221224509226641e+01,
        0.6019134481288629e+01,
        0.1253708332932087e+02,
        -0.6878860361058950,
        1.0,
    ],
];
const CC: [[f64; 5]; 5] = [
    [-0.5668800000000000e+01, 0.0, 0.0, 0.0, 0.0],
    [-0.2430093356833875e+01, -0.2063599157091915, 0.0, 0.0, 0.0],
    [
        -0.1073529058151375,
        -0.9594562251023355e+01,
        -0.2047028614809616e+02,
        0.0,
        0.0,
    ],
    [
        0.7496443313967647e+01,
        -0.1024680431464352e+02,
        -0.3399990352819905e+02,
        0.1170890893206160e+02,
        0.0,
    ],
    [
        0.8083246795921522e+01,
        -0.7981132988064893e+01,
        -0.3152159432874371e+02,
        0.1631930543123136e+02,
        -0.6058818238834054e+01,
    ],
];
/// Dense output: `y(t + θh) = y + θ (y_1 - y + (1 - θ)(Σ_j D2_j g_j + θ Σ_j D3_j g_j))`.
const DENSE: [[f64; 5]; 2] = [
    [
        0.1012623508344586e+02,
        -0.7487995877610167e+01,
        -0.3480091861555747e+02,
        -0.7992771707568823e+01,
        0.1025137723295662e+01,
    ],
    [
        -0.6762803392801253,
        0.6087714651680015e+01,
        0.1643084320892478e+02,
        0.2476722511418386e+02,
        -0.6594389125716872e+01,
    ],
];

/// An adaptive RODAS4 integration of `y' = f(t, y)` in progress; the same interface as
/// [`crate::Integrator`] (see [`crate::Stepper`]).
///
/// ```
/// use bwc_ode::{Jacobian, Matrix, Options, Rosenbrock, State, System};
/// // Prothero-Robinson, stiff: y' = -1e6 (y - cos t) - sin t, exact y = cos t.
/// struct Stiff;
/// impl System<1> for Stiff {
///     fn rhs(&self, t: f64, y: &State<1>) -> State<1> {
///         State::<1>::new(-1e6 * (y[0] - t.cos()) - t.sin())
///     }
/// }
/// impl Jacobian<1> for Stiff {
///     fn jacobian(&self, _t: f64, _y: &State<1>) -> Matrix<1> {
///         Matrix::<1>::new(-1e6)
///     }
/// }
/// let mut it = Rosenbrock::new(Stiff, 0.0, State::<1>::new(1.0), Options::new(1e-8, 1e-10))?;
/// it.integrate_to(1.0)?;
/// assert!((it.y()[0] - 1.0f64.cos()).abs() < 1e-8);
/// assert!(it.stats().accepted < 200); // an explicit method needs about 10^6 steps
/// # Ok::<(), bwc_ode::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Rosenbrock<F, const N: usize> {
    f: F,
    rtol: State<N>,
    atol: State<N>,
    limits: Limits,
    t: f64,
    y: State<N>,
    f_now: State<N>,
    h: f64,
    t_prev: f64,
    y_prev: State<N>,
    f_prev: State<N>,
    h_prev: f64,
    /// The rounding error of `y`, added to the next increment (compensated summation, as in
    /// [`crate::Integrator`]), and its value at the start of the last accepted step.
    carry: State<N>,
    carry_prev: State<N>,
    /// Stage increments `g_1 .. g_5` of the last accepted step (for the dense output).
    g: [State<N>; 5],
    last_rejected: bool,
    stats: Stats,
}

impl<F: Jacobian<N>, const N: usize> Rosenbrock<F, N> {
    /// Starts an integration at `(t0, y0)` (the controller settings of `options` are not used:
    /// RODAS's own are).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] for inadmissible options, [`Error::NonFiniteInitialValue`] for a
    /// non-finite `t0`, `y0` or `f(t0, y0)`.
    pub fn new(f: F, t0: f64, y0: State<N>, options: Options<N>) -> Result<Self, Error> {
        options.validate()?;
        let f_now = f.rhs(t0, &y0);
        if !t0.is_finite() || !y0.iter().chain(f_now.iter()).all(|v| v.is_finite()) {
            return Err(Error::NonFiniteInitialValue {
                t: t0,
                state: y0.as_slice().to_vec(),
            });
        }
        let mut it = Self {
            f,
            rtol: options.rtol,
            atol: options.atol,
            limits: Limits::of(&options),
            t: t0,
            y: y0,
            f_now,
            h: 0.0,
            t_prev: t0,
            y_prev: y0,
            f_prev: f_now,
            h_prev: 0.0,
            carry: State::zeros(),
            carry_prev: State::zeros(),
            g: [State::zeros(); 5],
            last_rejected: false,
            stats: Stats {
                rhs_evals: 1,
                ..Stats::default()
            },
        };
        it.h = options
            .h0
            .unwrap_or_else(|| it.initial_step())
            .min(it.limits.max_step());
        Ok(it)
    }

    /// Continues an integration at `(t, y)` with `f(t, y) = f_now`, a proposed step `h` and the
    /// statistics so far (used to switch to this method in the middle of a run).
    ///
    /// # Errors
    /// As [`Rosenbrock::new`].
    pub fn resume(
        f: F,
        t: f64,
        y: State<N>,
        h: f64,
        options: Options<N>,
        stats: Stats,
    ) -> Result<Self, Error> {
        let mut it = Self::new(f, t, y, options.with_h0(h.max(f64::MIN_POSITIVE)))?;
        // Carry the counts over; the new start's evaluation of f adds to them.
        it.stats = Stats {
            rhs_evals: it.stats.rhs_evals + stats.rhs_evals,
            ..stats
        };
        Ok(it)
    }

    /// Current time.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    pub fn y(&self) -> &State<N> {
        &self.y
    }

    /// `f(t, y)` at the current point.
    pub fn derivative(&self) -> &State<N> {
        &self.f_now
    }

    /// Statistics so far.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Counts one located event in the statistics.
    pub fn record_event(&mut self) {
        self.stats.events += 1;
    }

    /// Proposed size of the next step.
    pub fn next_step_size(&self) -> f64 {
        self.h
    }

    /// How many error tolerances a difference `dy` from the current state spans: the largest
    /// `|dy_i| / (atol_i + rtol_i |y_i|)`.
    pub fn tolerances(&self, dy: &State<N>) -> f64 {
        crate::control::in_tolerances(&self.atol, &self.rtol, &self.y, dy)
    }

    /// Proposes the size of the next step; clipped to the largest step.
    pub fn propose_step_size(&mut self, h: f64) {
        if h.is_finite() && h > 0.0 {
            self.h = h.min(self.limits.max_step());
        }
    }

    /// A first step from the scaled size of `y` and `f` (as Hairer's HINIT without its second
    /// evaluation, with the order of the error estimate, 3).
    fn initial_step(&self) -> f64 {
        let sk = self.atol + self.rtol.component_mul(&self.y.abs());
        let dnf = self.f_now.component_div(&sk).norm() / (N as f64).sqrt();
        let h = if dnf <= 1e-5 {
            1e-6
        } else {
            (0.01 / dnf).powf(0.25)
        };
        h.min(self.limits.max_step())
    }

    fn eval(&mut self, t: f64, y: &State<N>) -> State<N> {
        self.stats.rhs_evals += 1;
        self.f.rhs(t, y)
    }

    fn snapshot(&self) -> Vec<f64> {
        self.y.as_slice().to_vec()
    }

    /// One RODAS4 step of size `h` from the current point: the new solution, the error
    /// estimate and the new solution's rounding error (carried into the next step), or `None`
    /// when `M` is singular or a value is not finite.
    fn attempt(
        &mut self,
        h: f64,
        jac: &Matrix<N>,
        ft: &State<N>,
    ) -> Option<(State<N>, State<N>, State<N>)> {
        // N is tiny (3 or 4 here): nalgebra inverts in closed form up to 4 x 4 (by LU beyond),
        // and each stage is then one matrix-vector product.
        let m_inv = (Matrix::<N>::identity() / (GAMMA * h) - jac).try_inverse()?;
        let mut g = [State::<N>::zeros(); 6];
        for i in 0..6 {
            let rhs_f = if i == 0 {
                self.f_now
            } else {
                let mut yi = self.y;
                for (aij, gj) in A[i - 1].iter().zip(&g).take(i) {
                    yi.axpy(*aij, gj, 1.0);
                }
                self.eval(self.t + C[i] * h, &yi)
            };
            let mut b = rhs_f;
            if i < 4 {
                b.axpy(D[i] * h, ft, 1.0);
            }
            if i > 0 {
                for (cij, gj) in CC[i - 1].iter().zip(&g).take(i) {
                    b.axpy(cij / h, gj, 1.0);
                }
            }
            g[i] = m_inv * b;
        }
        let mut d = g[5] + self.carry;
        for (aj, gj) in A[4].iter().zip(&g) {
            d.axpy(*aj, gj, 1.0);
        }
        let (y1, lost) = compensated(&self.y, &d);
        self.g.copy_from_slice(&g[..5]);
        let ok = y1.iter().chain(g[5].iter()).all(|v| v.is_finite());
        ok.then_some((y1, g[5], lost))
    }

    /// As [`crate::Integrator::step_aiming`].
    ///
    /// # Errors
    /// As [`crate::Integrator::step`].
    pub fn step_aiming(
        &mut self,
        t_end: f64,
        mut aim: impl FnMut(&Trial<'_, N>) -> Option<f64>,
    ) -> Result<(), Error> {
        // One Jacobian (and ∂f/∂t) per step, reused by the rejected trials.
        let jac = self.f.jacobian(self.t, &self.y);
        self.stats.jacobians += 1;
        let ft = if self.f.is_autonomous() {
            State::zeros()
        } else {
            let dt = (f64::EPSILON * self.t.abs().max(1e-5)).sqrt();
            let y = self.y;
            let f1 = self.eval(self.t + dt, &y);
            (f1 - self.f_now) / dt
        };
        loop {
            let (h, last) =
                self.limits
                    .trial(self.t, t_end, self.h, &self.stats, self.y.as_slice())?;
            let attempt = self.attempt(h, &jac, &ft);
            let err = attempt.as_ref().map_or(f64::INFINITY, |(y1, e, _)| {
                let sk = self.atol + self.rtol.component_mul(&self.y.abs().sup(&y1.abs()));
                (e.component_div(&sk).norm_squared() / N as f64).sqrt()
            });
            if let (Some((y1, _, carry)), true) = (attempt, err <= 1.0) {
                let t1 = if last { t_end } else { self.t + h };
                let f1 = self.eval(t1, &y1);
                if !f1.iter().all(|v| v.is_finite()) {
                    return Err(Error::NonFiniteState {
                        t: self.t,
                        state: self.snapshot(),
                    });
                }
                // Hairer's RODAS controller: h_new / h in [0.2, 6], safety 0.9, exponent 1/4.
                let mut ratio = (0.9 / err.max(1e-10).powf(0.25)).clamp(0.2, 6.0);
                if self.last_rejected {
                    ratio = ratio.min(1.0);
                }
                self.t_prev = self.t;
                self.y_prev = self.y;
                self.f_prev = self.f_now;
                self.carry_prev = self.carry;
                self.carry = carry;
                self.h_prev = h;
                self.t = t1;
                self.y = y1;
                self.f_now = f1;
                self.stats.accepted += 1;
                self.last_rejected = false;
                if !last || h * ratio > self.h {
                    self.h = h * ratio;
                }
                return Ok(());
            }
            self.stats.rejected += 1;
            self.last_rejected = true;
            let y1 = attempt.map_or(self.y, |(y1, _, _)| y1);
            let trial = Trial {
                t0: self.t,
                y0: &self.y,
                f0: &self.f_now,
                t1: self.t + h,
                y1: &y1,
                error: err,
            };
            self.h = match aimed(aim(&trial), self.t, h) {
                Some(h_aim) => h_aim,
                None if err.is_finite() => h * (0.9 / err.powf(0.25)).clamp(0.2, 1.0),
                None => h * 0.1,
            };
        }
    }

    /// One accepted step ending at `t_end` at the latest.
    ///
    /// # Errors
    /// As [`crate::Integrator::step`].
    pub fn step(&mut self, t_end: f64) -> Result<(), Error> {
        self.step_aiming(t_end, |_| None)
    }

    /// Integrates until `t = t_end` (exactly).
    ///
    /// # Errors
    /// As [`crate::Integrator::step`].
    pub fn integrate_to(&mut self, t_end: f64) -> Result<(), Error> {
        while self.t < t_end {
            self.step(t_end)?;
        }
        Ok(())
    }

    /// The 3rd-order continuous extension of the last accepted step.
    pub fn dense(&mut self) -> Dense<N> {
        let mut rows = [State::<N>::zeros(); 3];
        rows[0] = self.y - self.y_prev;
        for (row, d) in rows[1..].iter_mut().zip(&DENSE) {
            for (dj, gj) in d.iter().zip(&self.g) {
                row.axpy(*dj, gj, 1.0);
            }
        }
        Dense::from_rows(self.t_prev, self.h_prev, self.y_prev, &rows)
    }

    /// As [`crate::Integrator::retake_to`].
    ///
    /// # Errors
    /// As [`crate::Integrator::retake_to`].
    pub fn retake_to(&mut self, t_stop: f64) -> Result<(), Error> {
        inside_last_step(t_stop, self.t_prev, self.t)?;
        self.t = self.t_prev;
        self.y = self.y_prev;
        self.carry = self.carry_prev;
        self.f_now = self.f_prev;
        self.stats.accepted -= 1;
        self.stats.rejected += 1;
        let proposal = self.h;
        self.h = t_stop - self.t;
        self.integrate_to(t_stop)?;
        self.h = self.h.max(proposal);
        Ok(())
    }
}

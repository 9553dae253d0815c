//! The stepping engine shared by every tableau.

use crate::control::{aimed, inside_last_step, Limits, Stats};
use crate::tableau::{ErrorEstimate, Tableau, MAX_ROWS, MAX_STAGES};
use crate::{Controller, Error, Options, State, System};

/// A step counts as limited by stability when `h |λ|` exceeds this fraction of the method's
/// real stability boundary (see [`crate::tableau::StiffnessTest`]).
const STIFF_FRACTION: f64 = 0.6;

/// A rejected trial step, shown to the `aim` hook of [`Integrator::step_aiming`].
#[derive(Debug, Clone, Copy)]
pub struct Trial<'a, const N: usize> {
    /// Start of the trial (the current point).
    pub t0: f64,
    /// State at the start.
    pub y0: &'a State<N>,
    /// `f(t0, y0)`.
    pub f0: &'a State<N>,
    /// End of the trial.
    pub t1: f64,
    /// The rejected (inaccurate) solution at the end.
    pub y1: &'a State<N>,
    /// The trial's error estimate in units of the tolerance (above 1, or not finite).
    pub error: f64,
}

/// The continuous extension of one accepted step, `y(t)` for `t` in `[t0, t0 + h]`.
///
/// A small `Copy` value (no heap): the event locator evaluates it many times.
#[derive(Debug, Clone, Copy)]
pub struct Dense<const N: usize> {
    t0: f64,
    h: f64,
    y0: State<N>,
    rows: [State<N>; MAX_ROWS],
    len: usize,
}

impl<const N: usize> Dense<N> {
    /// The interpolant `y0 + θ (F_0 + (1-θ)(F_1 + θ (F_2 + ...)))` of a step `[t0, t0 + h]` from
    /// its rows `F_r` (at most 8).
    pub(crate) fn from_rows(t0: f64, h: f64, y0: State<N>, rows: &[State<N>]) -> Self {
        let mut all = [State::zeros(); MAX_ROWS];
        all[..rows.len()].copy_from_slice(rows);
        Self {
            t0,
            h,
            y0,
            rows: all,
            len: rows.len(),
        }
    }

    /// Start of the step.
    pub fn t0(&self) -> f64 {
        self.t0
    }

    /// End of the step.
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }

    /// The interpolated state at `t` (extrapolates outside the step; callers stay inside).
    pub fn eval(&self, t: f64) -> State<N> {
        let theta = (t - self.t0) / self.h;
        let f = &self.rows[..self.len];
        let theta1 = 1.0 - theta;
        let mut acc = f[self.len - 1];
        for r in (0..self.len - 1).rev() {
            // Row r+1 is multiplied by θ when r+1 is even and by 1-θ when it is odd.
            let m = if (r + 1) % 2 == 0 { theta } else { theta1 };
            acc = f[r] + acc * m;
        }
        self.y0 + acc * theta
    }
}

/// `y + d` rounded, and what the rounding lost (Knuth's TwoSum, exact for any magnitudes): the
/// integrators add it to the next step's increment (compensated summation). Without it each
/// step's rounding of the state, about `ε |y|`, stays in it; over the tens of thousands of steps
/// of a long contact at tight tolerances these add up to more than the tolerance (STABILITY.md,
/// "Checks by other methods").
#[inline]
pub(crate) fn compensated<const N: usize>(y: &State<N>, d: &State<N>) -> (State<N>, State<N>) {
    let sum = y + d;
    let lost = State::<N>::from_fn(|i, _| {
        let (a, b, s) = (y[i], d[i], sum[i]);
        let b_virtual = s - a;
        (a - (s - b_virtual)) + (b - b_virtual)
    });
    (sum, lost)
}

/// An adaptive explicit Runge-Kutta integration of `y' = f(t, y)` in progress.
///
/// Owns its state on the stack: stepping allocates nothing. Each [`Integrator::step`] takes one
/// accepted step; [`Integrator::dense`] gives the continuous extension of that step (computing
/// the extra stages only when asked).
///
/// ```
/// use bwc_ode::{Integrator, Options, State, DOP853};
/// // y' = -y, y(0) = 1
/// let f = |_t: f64, y: &State<1>| -*y;
/// let mut it = Integrator::new(f, &DOP853, 0.0, State::<1>::new(1.0), Options::new(1e-10, 1e-12))?;
/// it.integrate_to(1.0)?;
/// assert!((it.y()[0] - (-1.0f64).exp()).abs() < 1e-10);
/// # Ok::<(), bwc_ode::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Integrator<F, const N: usize> {
    f: F,
    tab: &'static Tableau,
    rtol: State<N>,
    atol: State<N>,
    limits: Limits,
    ctrl: Controller,
    expo: f64,
    // Current point and f(t, y).
    t: f64,
    y: State<N>,
    f_now: State<N>,
    /// The rounding error of `y` (what the last update lost when it was rounded), added to the
    /// next increment: compensated summation, so that rounding errors of the state do not grow
    /// with the number of steps.
    carry: State<N>,
    /// `carry` at the start of the last accepted step.
    carry_prev: State<N>,
    /// Proposed size of the next step.
    h: f64,
    // The last accepted step: [t_prev, t], its stages and its interpolant.
    t_prev: f64,
    y_prev: State<N>,
    h_prev: f64,
    k: [State<N>; MAX_STAGES],
    dense_ready: bool,
    rows: [State<N>; MAX_ROWS],
    fac_old: f64,
    last_rejected: bool,
    stats: Stats,
    // Hairer's stiffness test: stability-limited steps so far, and non-limited ones in a row.
    stiff_steps: u32,
    nonstiff_steps: u32,
    h_lambda: f64,
    /// The point at which the stiffness test's stage was evaluated in the last step.
    y_stiff: State<N>,
}

impl<F: System<N>, const N: usize> Integrator<F, N> {
    /// Starts an integration at `(t0, y0)`.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] for inadmissible options, [`Error::InvalidTableau`] for a
    /// user-supplied tableau the engine cannot take ([`Tableau::validate`]),
    /// [`Error::NonFiniteInitialValue`] for a non-finite `t0`, `y0` or `f(t0, y0)`.
    pub fn new(
        f: F,
        tableau: &'static Tableau,
        t0: f64,
        y0: State<N>,
        options: Options<N>,
    ) -> Result<Self, Error> {
        options.validate()?;
        // The built-in methods are known to fit; a user's tableau is checked once here.
        if !crate::METHODS.iter().any(|t| std::ptr::eq(*t, tableau)) {
            tableau.validate()?;
        }
        if !t0.is_finite() || !y0.iter().all(|v| v.is_finite()) {
            return Err(Error::NonFiniteInitialValue {
                t: t0,
                state: y0.as_slice().to_vec(),
            });
        }
        let ctrl = options
            .controller
            .unwrap_or_else(|| Controller::for_method(tableau));
        let expo = 1.0 / (tableau.error_order as f64 + 1.0) - 0.75 * ctrl.beta;
        let mut it = Self {
            f,
            tab: tableau,
            rtol: options.rtol,
            atol: options.atol,
            limits: Limits::of(&options),
            ctrl,
            expo,
            t: t0,
            y: y0,
            f_now: State::zeros(),
            carry: State::zeros(),
            carry_prev: State::zeros(),
            h: 0.0,
            t_prev: t0,
            y_prev: y0,
            h_prev: 0.0,
            k: [State::zeros(); MAX_STAGES],
            dense_ready: false,
            rows: [State::zeros(); MAX_ROWS],
            fac_old: 1e-4,
            last_rejected: false,
            stats: Stats::default(),
            stiff_steps: 0,
            nonstiff_steps: 0,
            h_lambda: 0.0,
            y_stiff: State::zeros(),
        };
        it.f_now = it.eval(t0, &y0);
        if !it.f_now.iter().all(|v| v.is_finite()) {
            return Err(Error::NonFiniteInitialValue {
                t: t0,
                state: y0.as_slice().to_vec(),
            });
        }
        it.h = match options.h0 {
            Some(h0) => h0.min(it.limits.max_step()),
            None => it.initial_step(),
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

    /// The method in use.
    pub fn tableau(&self) -> &'static Tableau {
        self.tab
    }

    /// The right-hand side.
    pub fn system(&self) -> &F {
        &self.f
    }

    /// Statistics so far.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Counts one located event in the statistics.
    pub fn record_event(&mut self) {
        self.stats.events += 1;
    }

    /// Start of the last accepted step.
    pub fn t_prev(&self) -> f64 {
        self.t_prev
    }

    /// State at the start of the last accepted step.
    pub fn y_prev(&self) -> &State<N> {
        &self.y_prev
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

    /// Proposes the size of the next step (e.g. to resume after a stop at a non-smooth point
    /// with the step size that fitted before it); clipped to the largest step.
    pub fn propose_step_size(&mut self, h: f64) {
        if h.is_finite() && h > 0.0 {
            self.h = h.min(self.limits.max_step());
        }
    }

    fn eval(&mut self, t: f64, y: &State<N>) -> State<N> {
        self.stats.rhs_evals += 1;
        self.f.rhs(t, y)
    }

    fn snapshot(&self) -> Vec<f64> {
        self.y.as_slice().to_vec()
    }

    /// Hairer's initial step (HINIT in dop853.f): one extra RHS evaluation.
    fn initial_step(&mut self) -> f64 {
        let sk = self.atol + self.rtol.component_mul(&self.y.abs());
        let dnf = self.f_now.component_div(&sk).norm_squared();
        let dny = self.y.component_div(&sk).norm_squared();
        let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
            1e-6
        } else {
            (dny / dnf).sqrt() * 0.01
        };
        h = h.min(self.limits.max_step());
        let y1 = self.y + self.f_now * h;
        let f1 = self.eval(self.t + h, &y1);
        let der2 = (f1 - self.f_now).component_div(&sk).norm() / h;
        let der12 = der2.abs().max(dnf.sqrt());
        crate::control::initial_step_from(h, der12, self.tab.error_order, self.limits.max_step())
    }

    /// Evaluates stages `1..stages` of a step of size `h` from the current point and returns the
    /// new solution `y_1` with its rounding error ([`Integrator::advance`]). Stage 0 is
    /// `f(t, y)`.
    fn stages(&mut self, h: f64) -> (State<N>, State<N>) {
        let tab = self.tab;
        self.k[0] = self.f_now;
        let mut end = None;
        for i in 1..tab.stages {
            let yi = if i == tab.fsal {
                // The fsal stage is evaluated at y_1 itself.
                let (y1, carry) = self.advance(tab.a[i], h);
                end = Some((y1, carry));
                y1
            } else {
                self.combine(&self.y, &self.carry, tab.a[i], h)
            };
            if i == tab.stiffness.stage {
                self.y_stiff = yi;
            }
            self.k[i] = self.eval(self.t + tab.c[i] * h, &yi);
        }
        end.unwrap_or_else(|| self.advance(tab.b, h))
    }

    /// `h Σ_j w_j k_j`, skipping zero weights.
    #[inline]
    fn increment(&self, w: &[f64], h: f64) -> State<N> {
        let mut acc = State::<N>::zeros();
        for (wj, kj) in w.iter().zip(&self.k) {
            if *wj != 0.0 {
                acc.axpy(*wj, kj, 1.0);
            }
        }
        acc * h
    }

    /// `y + (h Σ_j w_j k_j + carry)`: a stage from the state `y` whose rounding error is
    /// `carry`. The stages take the carry as the step's end does, so that differences between
    /// them (the stiffness test's) are not differences of roundings.
    #[inline]
    fn combine(&self, y: &State<N>, carry: &State<N>, w: &[f64], h: f64) -> State<N> {
        y + (self.increment(w, h) + carry)
    }

    /// The state after a step, `y_1 = y + (h Σ_j w_j k_j + carry)` rounded, and what that
    /// rounding lost, to be carried into the next step ([`compensated`]).
    #[inline]
    fn advance(&self, w: &[f64], h: f64) -> (State<N>, State<N>) {
        compensated(&self.y, &(self.increment(w, h) + self.carry))
    }

    /// Scaled error norm of the step just computed (`<= 1`: acceptable).
    fn error_norm(&self, h: f64, y1: &State<N>) -> f64 {
        let sk = self.atol + self.rtol.component_mul(&self.y.abs().sup(&y1.abs()));
        let weighted = |w: &[f64]| {
            let mut acc = State::<N>::zeros();
            for (wj, kj) in w.iter().zip(&self.k) {
                if *wj != 0.0 {
                    acc.axpy(*wj, kj, 1.0);
                }
            }
            acc.component_div(&sk).norm_squared()
        };
        let n = N as f64;
        match self.tab.error {
            ErrorEstimate::Embedded(e) => (weighted(e) / n).sqrt() * h.abs(),
            ErrorEstimate::Hairer853 { e5, e3 } => {
                let err5 = weighted(e5);
                let err3 = weighted(e3);
                let mut deno = err5 + 0.01 * err3;
                if deno <= 0.0 {
                    deno = 1.0;
                }
                h.abs() * err5 * (1.0 / (n * deno)).sqrt()
            }
        }
    }

    /// Finishes a step of size `h` ending at `t1` with solution `y1` (rounded by `carry`):
    /// makes it the last step.
    fn accept(&mut self, h: f64, t1: f64, (y1, carry): (State<N>, State<N>)) -> Result<(), Error> {
        let tab = self.tab;
        let f1 = if tab.fsal < tab.stages {
            self.k[tab.fsal]
        } else {
            let f1 = self.eval(t1, &y1);
            self.k[tab.fsal] = f1;
            f1
        };
        if !y1.iter().chain(f1.iter()).all(|v| v.is_finite()) {
            return Err(Error::NonFiniteState {
                t: self.t,
                state: self.snapshot(),
            });
        }
        self.stiffness_test(h, &y1, &f1);
        self.t_prev = self.t;
        self.y_prev = self.y;
        self.carry_prev = self.carry;
        self.carry = carry;
        self.h_prev = h;
        self.t = t1;
        self.y = y1;
        self.f_now = f1;
        self.dense_ready = false;
        self.stats.accepted += 1;
        Ok(())
    }

    /// Hairer's stiffness test on the step just accepted (see [`crate::tableau::StiffnessTest`]).
    fn stiffness_test(&mut self, h: f64, y1: &State<N>, f1: &State<N>) {
        let test = self.tab.stiffness;
        let den = (y1 - self.y_stiff).norm_squared();
        if den <= 0.0 {
            return;
        }
        let h_lambda = h.abs() * ((f1 - self.k[test.stage]).norm_squared() / den).sqrt();
        self.h_lambda = h_lambda;
        if h_lambda > STIFF_FRACTION * test.bound {
            self.stiff_steps += 1;
            self.nonstiff_steps = 0;
        } else {
            self.nonstiff_steps += 1;
            if self.nonstiff_steps == 6 {
                self.stiff_steps = 0;
            }
        }
    }

    /// Whether Hairer's stiffness test has fired: 15 accepted steps limited by stability (`h |λ|`
    /// beyond 0.6 times the method's real stability boundary) without 6 in a row that were not.
    pub fn is_stiff(&self) -> bool {
        self.stiff_steps >= 15
    }

    /// The estimate `h |λ|` of the stiffness test on the last accepted step (0 before the
    /// first step).
    pub fn h_lambda(&self) -> f64 {
        self.h_lambda
    }

    /// Takes one accepted adaptive step, ending at `t_end` at the latest.
    ///
    /// # Errors
    /// [`Error::StepSizeTooSmall`], [`Error::TooManySteps`] or [`Error::NonFiniteState`]; the
    /// integrator stays at the last accepted point.
    pub fn step(&mut self, t_end: f64) -> Result<(), Error> {
        self.step_aiming(t_end, |_| None)
    }

    /// As [`Integrator::step`], but after each rejected trial step `aim` may name an instant
    /// inside the trial (e.g. a predicted non-smooth point that the trial straddled); the next
    /// trial then ends there instead of where the step-size controller would put it. An aim
    /// outside the trial, or closer to its start than `1e-6 h`, is ignored.
    ///
    /// # Errors
    /// As [`Integrator::step`].
    pub fn step_aiming(
        &mut self,
        t_end: f64,
        mut aim: impl FnMut(&Trial<'_, N>) -> Option<f64>,
    ) -> Result<(), Error> {
        loop {
            let (h, last) =
                self.limits
                    .trial(self.t, t_end, self.h, &self.stats, self.y.as_slice())?;
            let end = self.stages(h);
            let y1 = end.0;
            let err = self.error_norm(h, &y1);
            if err.is_finite() && err <= 1.0 {
                let t1 = if last { t_end } else { self.t + h };
                let fac11 = err.powf(self.expo);
                let fac = (fac11 / self.fac_old.powf(self.ctrl.beta) / self.ctrl.safety)
                    .clamp(1.0 / self.ctrl.max_ratio, 1.0 / self.ctrl.min_ratio);
                let mut h_new = h / fac;
                if self.last_rejected {
                    h_new = h_new.min(h);
                }
                self.accept(h, t1, end)?;
                self.fac_old = err.max(1e-4);
                self.last_rejected = false;
                // Keep the proposal from the controller even when the last step was clipped.
                if !last || h_new > self.h {
                    self.h = h_new;
                }
                return Ok(());
            }
            self.stats.rejected += 1;
            self.last_rejected = true;
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
                None if err.is_finite() => {
                    h / (1.0 / self.ctrl.min_ratio).min(err.powf(self.expo) / self.ctrl.safety)
                }
                None => h * 0.1,
            };
        }
    }

    /// Takes one step of exactly `h` without error control (for convergence studies).
    ///
    /// # Errors
    /// [`Error::NonFiniteState`] if the step produced NaN or infinity.
    pub fn step_fixed(&mut self, h: f64) -> Result<(), Error> {
        let end = self.stages(h);
        let t1 = self.t + h;
        self.accept(h, t1, end)
    }

    /// Integrates until `t = t_end` (exactly).
    ///
    /// # Errors
    /// As [`Integrator::step`].
    pub fn integrate_to(&mut self, t_end: f64) -> Result<(), Error> {
        while self.t < t_end {
            self.step(t_end)?;
        }
        Ok(())
    }

    /// The continuous extension of the last accepted step (computes the extra dense stages the
    /// first time it is asked for after a step).
    pub fn dense(&mut self) -> Dense<N> {
        if !self.dense_ready {
            let tab = self.tab;
            let (t0, h) = (self.t_prev, self.h_prev);
            for i in tab.fsal + 1..tab.total_stages() {
                let yi = self.combine(&self.y_prev, &self.carry_prev, tab.a[i], h);
                self.k[i] = self.eval(t0 + tab.c[i] * h, &yi);
            }
            // F_r = h [(Σ_j D_rj) k_0 + Σ_j D_rj (k_j - k_0)]: the stages differ from k_0 by
            // O(h), so the large, cancelling interpolant weights multiply small differences.
            let k0 = self.k[0];
            for (r, row) in tab.interpolant.rows.iter().enumerate() {
                let mut acc = k0 * row.iter().sum::<f64>();
                for (d, kj) in row.iter().zip(&self.k).skip(1) {
                    if *d != 0.0 {
                        acc += (kj - k0) * *d;
                    }
                }
                self.rows[r] = acc * h;
            }
            self.dense_ready = true;
        }
        Dense {
            t0: self.t_prev,
            h: self.h_prev,
            y0: self.y_prev,
            rows: self.rows,
            len: self.tab.interpolant.rows.len(),
        }
    }

    /// Undoes the last accepted step and integrates again from its start to exactly `t_stop`
    /// (inside that step), so that the solution stops at `t_stop` without stepping over it.
    /// Used to stop exactly at non-smooth points and restart from there.
    ///
    /// # Errors
    /// [`Error::OutsideStep`] if `t_stop` is not inside the last step; otherwise as
    /// [`Integrator::step`].
    pub fn retake_to(&mut self, t_stop: f64) -> Result<(), Error> {
        inside_last_step(t_stop, self.t_prev, self.t)?;
        self.t = self.t_prev;
        self.y = self.y_prev;
        self.carry = self.carry_prev;
        self.f_now = self.k[0];
        self.stats.accepted -= 1;
        self.stats.rejected += 1;
        // Resume after the stop with the controller's proposal for the step after the
        // original one, not with the (possibly tiny) retaken piece.
        let proposal = self.h;
        self.h = t_stop - self.t;
        self.integrate_to(t_stop)?;
        self.h = self.h.max(proposal);
        Ok(())
    }

    /// Restarts the integration from `(t, y)` (e.g. after an event changed the state): one RHS
    /// evaluation; keeps the proposed step size.
    ///
    /// # Errors
    /// [`Error::NonFiniteInitialValue`] if `t`, `y` or `f(t, y)` is not finite.
    pub fn restart(&mut self, t: f64, y: State<N>) -> Result<(), Error> {
        let f = self.eval(t, &y);
        if !t.is_finite() || !y.iter().chain(f.iter()).all(|v| v.is_finite()) {
            return Err(Error::NonFiniteInitialValue {
                t,
                state: y.as_slice().to_vec(),
            });
        }
        self.t = t;
        self.y = y;
        self.carry = State::zeros();
        self.carry_prev = State::zeros();
        self.f_now = f;
        self.t_prev = t;
        self.y_prev = y;
        self.h_prev = 0.0;
        self.dense_ready = false;
        Ok(())
    }
}

//! The explicit Runge-Kutta engine on a state whose size is fixed when the integration starts
//! (a chain of `N` bodies, its contact laws), held in flat heap buffers allocated once.
//!
//! Same tableaux, step-size controller and compensated summation as [`crate::Integrator`];
//! two differences that a large system needs:
//!
//! * the error is measured in the **maximum** norm over the components, `max_i |err_i| / sc_i`
//!   (DOP853's combined estimate taken per component), so that the error of one component
//!   among ten thousand idle ones is not averaged away;
//! * the dense output is evaluated **per component** ([`FlatIntegrator::dense_component`]), so
//!   that an event function of a few components costs a few evaluations, not `N`.

use crate::control::{Limits, Stats};
use crate::tableau::{ErrorEstimate, Tableau, MAX_ROWS};
use crate::{Controller, Error};

/// A right-hand side `y' = f(t, y)` on a state of [`FlatSystem::len`] components.
pub trait FlatSystem {
    /// The number of components.
    fn len(&self) -> usize;
    /// Whether the state is empty.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Writes `f(t, y)` into `dy` (both of [`FlatSystem::len`] components).
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);
}

/// Tolerances and limits of a [`FlatIntegrator`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct FlatOptions {
    /// Relative tolerance (all components).
    pub rtol: f64,
    /// Absolute tolerance of each component (in its unit).
    pub atol: Vec<f64>,
    /// Largest step.
    pub max_step: f64,
    /// Most steps (accepted and rejected).
    pub max_steps: u64,
}

impl FlatOptions {
    /// `rtol` and one absolute tolerance per component; no step limit but 10^7 steps.
    pub fn new(rtol: f64, atol: Vec<f64>) -> Self {
        Self {
            rtol,
            atol,
            max_step: f64::INFINITY,
            max_steps: 10_000_000,
        }
    }

    fn limits(&self) -> Limits {
        Limits::new(self.max_step, 0.0, self.max_steps)
    }
}

/// An adaptive explicit Runge-Kutta integration of a [`FlatSystem`] in progress. Stepping,
/// retaking and restarting allocate nothing.
#[derive(Debug, Clone)]
pub struct FlatIntegrator<F> {
    f: F,
    tab: &'static Tableau,
    n: usize,
    rtol: f64,
    atol: Vec<f64>,
    limits: Limits,
    ctrl: Controller,
    expo: f64,
    t: f64,
    y: Vec<f64>,
    carry: Vec<f64>,
    f_now: Vec<f64>,
    t_prev: f64,
    y_prev: Vec<f64>,
    carry_prev: Vec<f64>,
    h_prev: f64,
    h: f64,
    /// Stages, stage `i` at `k[i n..(i + 1) n]`.
    k: Vec<f64>,
    /// Scratch: a stage's argument, then the step's end.
    scratch: Vec<f64>,
    y1: Vec<f64>,
    carry1: Vec<f64>,
    /// Dense-output rows of the last step, row `r` at `rows[r n..(r + 1) n]`.
    rows: Vec<f64>,
    dense_ready: bool,
    fac_old: f64,
    last_rejected: bool,
    stats: Stats,
}

impl<F: FlatSystem> FlatIntegrator<F> {
    /// Starts an integration of `f` at `(t0, y0)`.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] for a tolerance that is not positive and finite or an `atol`
    /// of the wrong length, [`Error::InvalidTableau`] for a tableau the engine cannot take,
    /// [`Error::NonFiniteInitialValue`] for a non-finite `t0`, `y0` or `f(t0, y0)`.
    pub fn new(
        f: F,
        tableau: &'static Tableau,
        t0: f64,
        y0: &[f64],
        options: FlatOptions,
    ) -> Result<Self, Error> {
        let n = f.len();
        let invalid = |name: &'static str, value: f64, allowed: &'static str| {
            Err(Error::InvalidOption {
                name,
                value,
                allowed,
            })
        };
        if !(options.rtol > 0.0 && options.rtol.is_finite()) {
            return invalid("rtol", options.rtol, "positive and finite");
        }
        if options.atol.len() != n {
            let allowed = "one absolute tolerance per component of the state";
            return invalid("atol", options.atol.len() as f64, allowed);
        }
        if y0.len() != n {
            let allowed = "one initial value per component of the state";
            return invalid("y0", y0.len() as f64, allowed);
        }
        if let Some(a) = options.atol.iter().find(|a| !(**a > 0.0 && a.is_finite())) {
            return invalid("atol", *a, "positive and finite");
        }
        if !crate::METHODS.iter().any(|t| std::ptr::eq(*t, tableau)) {
            tableau.validate()?;
        }
        let ctrl = Controller::for_method(tableau);
        let stages = tableau.total_stages();
        let mut it = Self {
            f,
            tab: tableau,
            n,
            rtol: options.rtol,
            limits: options.limits(),
            atol: options.atol,
            ctrl,
            expo: 1.0 / (tableau.error_order as f64 + 1.0) - 0.75 * ctrl.beta,
            t: t0,
            y: y0.to_vec(),
            carry: vec![0.0; n],
            f_now: vec![0.0; n],
            t_prev: t0,
            y_prev: y0.to_vec(),
            carry_prev: vec![0.0; n],
            h_prev: 0.0,
            h: 0.0,
            k: vec![0.0; stages * n],
            scratch: vec![0.0; n],
            y1: vec![0.0; n],
            carry1: vec![0.0; n],
            rows: vec![0.0; MAX_ROWS * n],
            dense_ready: false,
            fac_old: 1e-4,
            last_rejected: false,
            stats: Stats::default(),
        };
        it.restart(t0)?;
        it.h = it.initial_step();
        Ok(it)
    }

    /// Current time.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// `f(t, y)` at the current point.
    pub fn derivative(&self) -> &[f64] {
        &self.f_now
    }

    /// Start of the last accepted step.
    pub fn t_prev(&self) -> f64 {
        self.t_prev
    }

    /// State at the start of the last accepted step.
    pub fn y_prev(&self) -> &[f64] {
        &self.y_prev
    }

    /// The right-hand side.
    pub fn system(&self) -> &F {
        &self.f
    }

    /// The right-hand side and the current state, both to change (e.g. when an event switches
    /// the system); [`FlatIntegrator::restart`] must follow.
    pub fn system_and_state_mut(&mut self) -> (&mut F, &mut [f64]) {
        (&mut self.f, &mut self.y)
    }

    /// Statistics so far.
    pub fn stats(&self) -> Stats {
        self.stats
    }

    /// Counts one located event in the statistics.
    pub fn record_event(&mut self) {
        self.stats.events += 1;
    }

    fn eval_into(&mut self, t: f64, stage: usize) {
        self.stats.rhs_evals += 1;
        let n = self.n;
        self.f
            .rhs(t, &self.scratch, &mut self.k[stage * n..(stage + 1) * n]);
    }

    /// Hairer's initial step, in the maximum norm: one extra evaluation.
    fn initial_step(&mut self) -> f64 {
        let n = self.n;
        let sk = |it: &Self, i: usize| it.atol[i] + it.rtol * it.y[i].abs();
        let (mut dnf, mut dny) = (0.0f64, 0.0f64);
        for i in 0..n {
            dnf = dnf.max((self.f_now[i] / sk(self, i)).abs());
            dny = dny.max((self.y[i] / sk(self, i)).abs());
        }
        let h = if dnf <= 1e-5 || dny <= 1e-5 {
            1e-6
        } else {
            dny / dnf * 0.01
        }
        .min(self.limits.max_step());
        for i in 0..n {
            self.scratch[i] = self.y[i] + h * self.f_now[i];
        }
        self.eval_into(self.t + h, 1);
        let mut der2 = 0.0f64;
        for i in 0..n {
            der2 = der2.max(((self.k[n + i] - self.f_now[i]) / sk(self, i)).abs() / h);
        }
        let der12 = der2.max(dnf);
        crate::control::initial_step_from(h, der12, self.tab.error_order, self.limits.max_step())
    }

    /// `Σ_j w_j k_j` of component `i`, skipping zero weights.
    #[inline]
    fn weighted(&self, w: &[f64], i: usize) -> f64 {
        let n = self.n;
        w.iter()
            .enumerate()
            .filter(|(_, wj)| **wj != 0.0)
            .map(|(j, wj)| wj * self.k[j * n + i])
            .sum()
    }

    /// `scratch = y + (h Σ_j w_j k_j + carry)`.
    fn combine(&mut self, w: &[f64], h: f64) {
        for i in 0..self.n {
            self.scratch[i] = self.y[i] + (h * self.weighted(w, i) + self.carry[i]);
        }
    }

    /// `y1 = y + (h Σ_j w_j k_j + carry)` rounded, with what the rounding lost in `carry1`
    /// (Knuth's TwoSum, as the fixed-size engine's compensated summation).
    fn advance(&mut self, w: &[f64], h: f64) {
        for i in 0..self.n {
            let (a, d) = (self.y[i], h * self.weighted(w, i) + self.carry[i]);
            let s = a + d;
            let b_virtual = s - a;
            self.y1[i] = s;
            self.carry1[i] = (a - (s - b_virtual)) + (d - b_virtual);
        }
    }

    /// Stages `1..stages` of a step of size `h`; leaves the step's end in `y1`.
    fn stages(&mut self, h: f64) {
        let tab = self.tab;
        let n = self.n;
        self.k[..n].copy_from_slice(&self.f_now);
        let mut ended = false;
        for i in 1..tab.stages {
            if i == tab.fsal {
                self.advance(tab.a[i], h);
                self.scratch.copy_from_slice(&self.y1);
                ended = true;
            } else {
                self.combine(tab.a[i], h);
            }
            self.eval_into(self.t + tab.c[i] * h, i);
        }
        if !ended {
            self.advance(tab.b, h);
        }
    }

    /// The step's error in units of the tolerance, maximum norm.
    fn error_norm(&self, h: f64) -> f64 {
        let sum = |w: &[f64], i: usize| self.weighted(w, i);
        let mut err = 0.0f64;
        for i in 0..self.n {
            if !self.y1[i].is_finite() {
                return f64::INFINITY;
            }
            let sk = self.atol[i] + self.rtol * self.y[i].abs().max(self.y1[i].abs());
            let e = match self.tab.error {
                ErrorEstimate::Embedded(e) => (sum(e, i) / sk).abs(),
                ErrorEstimate::Hairer853 { e5, e3 } => {
                    let (a5, a3) = (sum(e5, i) / sk, sum(e3, i) / sk);
                    let deno = a5 * a5 + 0.01 * a3 * a3;
                    if deno > 0.0 || deno.is_nan() {
                        a5 * a5 / deno.sqrt()
                    } else {
                        0.0
                    }
                }
            };
            if !e.is_finite() {
                return f64::INFINITY;
            }
            err = err.max(e);
        }
        h.abs() * err
    }

    /// Takes one accepted adaptive step, ending at `t_end` at the latest.
    ///
    /// # Errors
    /// [`Error::StepSizeTooSmall`], [`Error::TooManySteps`] or [`Error::NonFiniteState`]; the
    /// integrator stays at the last accepted point.
    pub fn step(&mut self, t_end: f64) -> Result<(), Error> {
        loop {
            let (h, last) = self
                .limits
                .trial(self.t, t_end, self.h, &self.stats, &self.y)?;
            self.stages(h);
            let err = self.error_norm(h);
            if err.is_finite() && err <= 1.0 {
                let t1 = if last { t_end } else { self.t + h };
                let fac =
                    (err.powf(self.expo) / self.fac_old.powf(self.ctrl.beta) / self.ctrl.safety)
                        .clamp(1.0 / self.ctrl.max_ratio, 1.0 / self.ctrl.min_ratio);
                let mut h_new = h / fac;
                if self.last_rejected {
                    h_new = h_new.min(h);
                }
                self.accept(h, t1)?;
                self.fac_old = err.max(1e-4);
                self.last_rejected = false;
                if !last || h_new > self.h {
                    self.h = h_new;
                }
                return Ok(());
            }
            self.stats.rejected += 1;
            self.last_rejected = true;
            self.h = if err.is_finite() {
                h / (1.0 / self.ctrl.min_ratio).min(err.powf(self.expo) / self.ctrl.safety)
            } else {
                h * 0.1
            };
        }
    }

    fn accept(&mut self, h: f64, t1: f64) -> Result<(), Error> {
        let tab = self.tab;
        let n = self.n;
        if tab.fsal >= tab.stages {
            self.scratch.copy_from_slice(&self.y1);
            self.eval_into(t1, tab.fsal);
        }
        let f1 = &self.k[tab.fsal * n..(tab.fsal + 1) * n];
        if !self.y1.iter().chain(f1).all(|v| v.is_finite()) {
            return Err(Error::NonFiniteState {
                t: self.t,
                state: self.y.clone(),
            });
        }
        self.t_prev = self.t;
        std::mem::swap(&mut self.y_prev, &mut self.y);
        std::mem::swap(&mut self.y, &mut self.y1);
        std::mem::swap(&mut self.carry_prev, &mut self.carry);
        std::mem::swap(&mut self.carry, &mut self.carry1);
        self.f_now.copy_from_slice(f1);
        self.h_prev = h;
        self.t = t1;
        self.dense_ready = false;
        self.stats.accepted += 1;
        Ok(())
    }

    /// Integrates until `t = t_end` (exactly).
    ///
    /// # Errors
    /// As [`FlatIntegrator::step`].
    pub fn integrate_to(&mut self, t_end: f64) -> Result<(), Error> {
        while self.t < t_end {
            self.step(t_end)?;
        }
        Ok(())
    }

    /// Computes the dense-output rows of the last accepted step (the extra stages the first
    /// time it is asked for after a step).
    fn prepare_dense(&mut self) {
        if self.dense_ready {
            return;
        }
        let tab = self.tab;
        let n = self.n;
        let (t0, h) = (self.t_prev, self.h_prev);
        for i in tab.fsal + 1..tab.total_stages() {
            for c in 0..n {
                let mut acc = 0.0;
                for (j, a) in tab.a[i].iter().enumerate() {
                    if *a != 0.0 {
                        acc += a * self.k[j * n + c];
                    }
                }
                self.scratch[c] = self.y_prev[c] + (h * acc + self.carry_prev[c]);
            }
            self.eval_into(t0 + tab.c[i] * h, i);
        }
        // As the fixed-size engine: the rows from the stages' differences to k_0.
        for (r, row) in tab.interpolant.rows.iter().enumerate() {
            let total: f64 = row.iter().sum();
            for c in 0..n {
                let k0 = self.k[c];
                let mut acc = k0 * total;
                for (j, d) in row.iter().enumerate().skip(1) {
                    if *d != 0.0 {
                        acc += (self.k[j * n + c] - k0) * d;
                    }
                }
                self.rows[r * n + c] = acc * h;
            }
        }
        self.dense_ready = true;
    }

    /// Component `c` of the last accepted step's continuous extension at `t` (inside the step).
    pub fn dense_component(&mut self, c: usize, t: f64) -> f64 {
        self.prepare_dense();
        let n = self.n;
        let len = self.tab.interpolant.rows.len();
        let theta = (t - self.t_prev) / self.h_prev;
        let theta1 = 1.0 - theta;
        let mut acc = self.rows[(len - 1) * n + c];
        for r in (0..len - 1).rev() {
            let m = if (r + 1) % 2 == 0 { theta } else { theta1 };
            acc = self.rows[r * n + c] + acc * m;
        }
        self.y_prev[c] + acc * theta
    }

    /// Undoes the last accepted step and integrates again from its start to exactly `t_stop`
    /// (inside that step).
    ///
    /// # Errors
    /// [`Error::OutsideStep`] if `t_stop` is not inside the last step; otherwise as
    /// [`FlatIntegrator::step`].
    pub fn retake_to(&mut self, t_stop: f64) -> Result<(), Error> {
        if !(t_stop > self.t_prev && t_stop <= self.t) {
            return Err(Error::OutsideStep {
                t: t_stop,
                t0: self.t_prev,
                t1: self.t,
            });
        }
        self.undo();
        let proposal = self.h;
        self.h = t_stop - self.t;
        self.integrate_to(t_stop)?;
        self.h = self.h.max(proposal);
        Ok(())
    }

    /// Undoes the last accepted step: back to its start, as if it had not been taken.
    pub fn undo(&mut self) {
        self.t = self.t_prev;
        self.y.copy_from_slice(&self.y_prev);
        self.carry.copy_from_slice(&self.carry_prev);
        self.f_now.copy_from_slice(&self.k[..self.n]);
        self.stats.accepted -= 1;
        self.stats.rejected += 1;
        self.dense_ready = false;
    }

    /// Restarts the integration at `t` from `y` with absolute tolerances `atol`, on a state
    /// whose size ([`FlatSystem::len`], after the system was changed through
    /// [`FlatIntegrator::system_and_state_mut`]) may differ from before: a system that
    /// integrates only part of a larger one (the bodies in contact). The buffers grow only past
    /// the largest size so far; keeps the proposed step size.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] if `y` or `atol` does not have the system's length or a
    /// tolerance is not positive and finite; as [`FlatIntegrator::restart`].
    pub fn restart_with(&mut self, t: f64, y: &[f64], atol: &[f64]) -> Result<(), Error> {
        let n = self.f.len();
        let invalid = |name: &'static str, value: f64, allowed: &'static str| {
            Err(Error::InvalidOption {
                name,
                value,
                allowed,
            })
        };
        if y.len() != n {
            return invalid("y", y.len() as f64, "one value per component of the system");
        }
        if atol.len() != n {
            let allowed = "one absolute tolerance per component of the system";
            return invalid("atol", atol.len() as f64, allowed);
        }
        if let Some(a) = atol.iter().find(|a| !(**a > 0.0 && a.is_finite())) {
            return invalid("atol", *a, "positive and finite");
        }
        self.n = n;
        for v in [
            &mut self.carry,
            &mut self.f_now,
            &mut self.y_prev,
            &mut self.carry_prev,
            &mut self.scratch,
            &mut self.y1,
            &mut self.carry1,
        ] {
            v.resize(n, 0.0);
        }
        self.k.resize(self.tab.total_stages() * n, 0.0);
        self.rows.resize(MAX_ROWS * n, 0.0);
        self.y.clear();
        self.y.extend_from_slice(y);
        self.atol.clear();
        self.atol.extend_from_slice(atol);
        self.restart(t)
    }

    /// Restarts the integration at `t` from the current state (after an event changed the
    /// system or the state): one evaluation; keeps the proposed step size.
    ///
    /// # Errors
    /// [`Error::NonFiniteInitialValue`] if `t`, the state or `f(t, y)` is not finite.
    pub fn restart(&mut self, t: f64) -> Result<(), Error> {
        self.scratch.copy_from_slice(&self.y);
        self.eval_into(t, 0);
        let n = self.n;
        if !t.is_finite() || !self.y.iter().chain(&self.k[..n]).all(|v| v.is_finite()) {
            return Err(Error::NonFiniteInitialValue {
                t,
                state: self.y.clone(),
            });
        }
        self.f_now.copy_from_slice(&self.k[..n]);
        self.t = t;
        self.t_prev = t;
        self.y_prev.copy_from_slice(&self.y);
        self.carry.fill(0.0);
        self.carry_prev.fill(0.0);
        self.h_prev = 0.0;
        self.dense_ready = false;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DOP853, DOPRI5, VERN7};

    /// Two uncoupled oscillators `x'' = -ω² x` of very different frequency, `ω = 1, 7`:
    /// `x = cos ω t`.
    struct Oscillators;

    impl FlatSystem for Oscillators {
        fn len(&self) -> usize {
            4
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = -y[0];
            dy[2] = y[3];
            dy[3] = -49.0 * y[2];
        }
    }

    #[test]
    fn integrates_to_the_closed_form_and_its_dense_output_follows_it() {
        for tab in [&DOPRI5, &DOP853, &VERN7] {
            let options = FlatOptions::new(1e-11, vec![1e-13; 4]);
            let mut it =
                FlatIntegrator::new(Oscillators, tab, 0.0, &[1.0, 0.0, 1.0, 0.0], options).unwrap();
            it.integrate_to(3.0).unwrap();
            let y = it.y();
            assert!((y[0] - 3.0f64.cos()).abs() < 1e-9, "{} {}", tab.name, y[0]);
            assert!((y[2] - 21.0f64.cos()).abs() < 1e-9, "{} {}", tab.name, y[2]);
            let (t0, t1) = (it.t_prev(), it.t());
            let t = 0.5 * (t0 + t1);
            let x = it.dense_component(2, t);
            assert!((x - (7.0 * t).cos()).abs() < 1e-8, "{} {x}", tab.name);
            assert_eq!(it.dense_component(2, t1), it.y()[2]);
        }
    }

    /// A retaken step stops exactly on the solution, and a restart from a changed state
    /// follows the new solution.
    #[test]
    fn retakes_stop_exactly_and_restarts_resume() {
        let options = FlatOptions::new(1e-10, vec![1e-12; 4]);
        let mut it =
            FlatIntegrator::new(Oscillators, &DOP853, 0.0, &[1.0, 0.0, 1.0, 0.0], options).unwrap();
        it.step(10.0).unwrap();
        it.step(10.0).unwrap();
        let stop = 0.5 * (it.t_prev() + it.t());
        it.retake_to(stop).unwrap();
        assert_eq!(it.t(), stop);
        assert!((it.y()[2] - (7.0 * stop).cos()).abs() < 1e-9);
        let (_, y) = it.system_and_state_mut();
        y[0] = 2.0;
        y[1] = 0.0;
        it.restart(stop).unwrap();
        it.integrate_to(stop + 1.0).unwrap();
        assert!((it.y()[0] - 2.0 * 1.0f64.cos()).abs() < 1e-8);
        assert!(FlatIntegrator::new(
            Oscillators,
            &DOP853,
            0.0,
            &[1.0; 3],
            FlatOptions::new(1e-8, vec![1e-9; 4])
        )
        .is_err());
    }
}

//! Step bookkeeping shared by the explicit and the Rosenbrock integrators.

use crate::{Error, Options, State};

/// Work done by a solve.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps (including steps retaken to stop exactly at a switching point).
    pub rejected: u64,
    /// Events located (switching points and terminal events).
    pub events: u64,
    /// Jacobian evaluations (implicit methods only).
    pub jacobians: u64,
}

impl std::ops::AddAssign for Stats {
    fn add_assign(&mut self, o: Self) {
        self.rhs_evals += o.rhs_evals;
        self.accepted += o.accepted;
        self.rejected += o.rejected;
        self.events += o.events;
        self.jacobians += o.jacobians;
    }
}

/// The step limits of a solve.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Limits {
    max_step: f64,
    min_step: f64,
    max_steps: u64,
}

impl Limits {
    pub(crate) fn of<const N: usize>(o: &Options<N>) -> Self {
        Self::new(o.max_step, o.min_step, o.max_steps)
    }

    pub(crate) fn new(max_step: f64, min_step: f64, max_steps: u64) -> Self {
        Self {
            max_step,
            min_step,
            max_steps,
        }
    }

    /// The largest step.
    pub(crate) fn max_step(&self) -> f64 {
        self.max_step
    }

    /// The next trial from `t` toward `t_end` with proposed size `h`: its size, and whether it
    /// ends exactly at `t_end`.
    ///
    /// # Errors
    /// [`Error::TooManySteps`] or [`Error::StepSizeTooSmall`], with the state `y` at `t`.
    pub(crate) fn trial(
        &self,
        t: f64,
        t_end: f64,
        h: f64,
        stats: &Stats,
        y: &[f64],
    ) -> Result<(f64, bool), Error> {
        if stats.accepted + stats.rejected >= self.max_steps {
            return Err(Error::TooManySteps {
                max_steps: self.max_steps,
                t,
                state: y.to_vec(),
            });
        }
        if t_end <= t || t_end.is_nan() {
            return Err(Error::NotAhead { t, t_end });
        }
        let remaining = t_end - t;
        let mut h = h.min(self.max_step);
        let last = remaining <= h * (1.0 + 1e-12);
        if last {
            h = remaining;
        } else {
            // A step the time can take exactly (t + h has no rounding), so that the state and
            // the time advance by the same h.
            h = (t + h) - t;
        }
        let h_floor = self.min_step.max(16.0 * f64::EPSILON * t.abs());
        if h <= h_floor && !(last && h > 0.0) {
            return Err(Error::StepSizeTooSmall {
                t,
                h,
                state: y.to_vec(),
            });
        }
        Ok((h, last))
    }
}

/// The size of the next trial after a rejected trial `[t, t + h]` when the aim hook named `aim`
/// inside it (at least `1e-6 h` from its start), else `None`.
pub(crate) fn aimed(aim: Option<f64>, t: f64, h: f64) -> Option<f64> {
    aim.filter(|a| *a > t + 1e-6 * h && *a < t + h)
        .map(|a| a - t)
}

/// Checks that `t_stop` lies inside the last step `(t0, t1]`.
///
/// # Errors
/// [`Error::OutsideStep`] otherwise.
pub(crate) fn inside_last_step(t_stop: f64, t0: f64, t1: f64) -> Result<(), Error> {
    if t_stop > t0 && t_stop <= t1 {
        Ok(())
    } else {
        Err(Error::OutsideStep { t: t_stop, t0, t1 })
    }
}

/// How many error tolerances `atol_i + rtol_i |y_i|` a difference `dy` from the state `y`
/// spans: the largest ratio over the components.
pub(crate) fn in_tolerances<const N: usize>(
    atol: &State<N>,
    rtol: &State<N>,
    y: &State<N>,
    dy: &State<N>,
) -> f64 {
    let sk = atol + rtol.component_mul(&y.abs());
    dy.abs().component_div(&sk).max()
}

/// The end of Hairer's initial step (HINIT in dop853.f): from the trial `h` and `der12`, the
/// larger of the scaled first and second derivatives' norms, the step
/// `min(100 h, (0.01 / der12)^(1 / (error_order + 1)), max_step)` (1e-6 where that is not a
/// positive number).
pub(crate) fn initial_step_from(h: f64, der12: f64, error_order: u32, max_step: f64) -> f64 {
    let iord = error_order as f64 + 1.0;
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / iord)
    };
    let h = (100.0 * h).min(h1).min(max_step);
    if h.is_finite() && h > 0.0 {
        h
    } else {
        1e-6
    }
}

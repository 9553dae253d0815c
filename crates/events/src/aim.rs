//! Aiming rejected steps at switching points.
//!
//! A step that straddles a kink of the right-hand side (a jump in the derivative of `f`) is
//! polluted to first order in the distance `δ` by which it passes the kink: the error is about
//! `h J δ` for a jump `J`, so the step-size controller, left alone, shrinks the step until
//! `h² J` is below the tolerance (about `10⁻⁶` at `10⁻¹¹`), after many rejections, and then
//! climbs back up. Instead, after a rejected trial that crossed a switching function, the next
//! trial is aimed to end *at* the predicted zero: a quadratic through the value and slope at
//! the start and the value at the end of the first trial, then through the start and the ends
//! of the last two trials (a secant-like iteration on the end of the step). Steps that end at
//! a kink are smooth, so after two or three aimed trials the step is accepted with the
//! switching function within `LANDING` noise floors of zero, and the locator stops there.

use crate::functions::{Switches, Values, LANDING, MAX_FUNCTIONS};
use crate::root::class;
use bwc_ode::Trial;

/// The aiming state of one step.
pub(crate) struct Aim {
    count: usize,
    start: Values,
    class_start: [i8; MAX_FUNCTIONS],
    floor: Values,
    /// End and switching values of the previous rejected trial of this step.
    previous: Option<(f64, Values)>,
    /// The function the last aim was at.
    target: Option<usize>,
    /// A rejected trial that ended on a switching point (within the landing tolerance) but was
    /// rejected for the smooth part of the solution: the function and the instant.
    landed: Option<(usize, f64)>,
    /// Start of the step.
    t0: f64,
    /// Aims taken in this step.
    aims: u32,
}

/// Most aimed trials per step.
const MAX_AIMS: u32 = 6;

impl Aim {
    /// Aiming for a step starting where the switching functions are `start`, with sign classes
    /// `class_start` (possibly imposed) and noise floors `floor`.
    pub(crate) fn new(
        count: usize,
        start: Values,
        class_start: [i8; MAX_FUNCTIONS],
        floor: Values,
    ) -> Self {
        Self {
            count,
            start,
            class_start,
            floor,
            previous: None,
            target: None,
            landed: None,
            t0: f64::NAN,
            aims: 0,
        }
    }

    /// After the accepted step `[t0, t1]` (switching values `end`): if a rejected trial had
    /// landed on a switching point beyond `t1`, that point; if the step was aimed at a switching
    /// point and stopped short of it, the function and the predicted instant of the point
    /// (between `t1` and the end of the last rejected trial, which had crossed).
    pub(crate) fn after_acceptance(&self, t1: f64, end: &Values) -> Option<(usize, f64)> {
        if let Some((i, t)) = self.landed {
            // The step the controller shortened ends before a point a trial had landed on.
            if t > t1 && class(end[i]) == self.class_start[i] {
                return Some((i, t));
            }
        }
        let i = self.target?;
        let (tp, gp) = self.previous?;
        let (t0, g0, g1) = (self.t0, self.start[i], end[i]);
        if class(g1) != self.class_start[i] || !(tp > t1 && t1 > t0) {
            return None;
        }
        let h = tp - t0;
        let s1 = (t1 - t0) / h;
        // Quadratic through (0, g0), (s1, g1), (1, gp): its root in (s1, 1).
        let s = through_three(g0, s1, g1, gp[i]).filter(|s| *s > s1 && *s < 1.0)?;
        Some((i, t0 + s * h))
    }

    /// The end of the next trial after `trial` was rejected, or `None` to leave it to the
    /// step-size controller (no switching function crossed inside the trial).
    pub(crate) fn after_rejection<S: Switches<N>, const N: usize>(
        &mut self,
        switches: &S,
        trial: &Trial<'_, N>,
    ) -> Option<f64> {
        // A trial can also be rejected for the smooth part of the solution: after a few aims
        // (or once a trial ends on the point) the step-size controller takes over.
        if self.count == 0 || self.aims >= MAX_AIMS {
            return None;
        }
        let (t0, h) = (trial.t0, trial.t1 - trial.t0);
        self.t0 = t0;
        let end = switches.values(trial.t1, trial.y1);
        // The slope at the start, by a forward difference along f(t0, y0) (first trial only).
        let mut slope: Option<Values> = None;
        let mut best: Option<(f64, usize)> = None;
        for i in 0..self.count {
            let (g0, g1) = (self.start[i], end[i]);
            let crossed = self.class_start[i] != 0 && class(g1) != self.class_start[i];
            let visible = g0.abs() > self.floor[i] || g1.abs() > self.floor[i];
            let landed = g1.abs() <= LANDING * self.floor[i];
            if landed && visible && self.class_start[i] != 0 {
                self.landed = Some((i, trial.t1));
            }
            if !crossed || !visible || landed || !g1.is_finite() {
                continue;
            }
            // Nodes in units of the trial: 0 (start), sp (previous trial's end), 1.
            let root = match self.previous {
                Some((tp, ref gp)) if tp > t0 && tp != trial.t1 && gp[i].is_finite() => {
                    let sp = (tp - t0) / h;
                    through_three(g0, sp, gp[i], g1)
                }
                _ => {
                    let ahead = *slope.get_or_insert_with(|| {
                        let eps = 1.5e-8 * h;
                        switches.values(t0 + eps, &(trial.y0 + trial.f0 * eps))
                    });
                    let a = (ahead[i] - g0) / 1.5e-8;
                    smallest_root(g0, a, g1 - g0 - a)
                }
            };
            let s = root.unwrap_or(g0 / (g0 - g1));
            if s.is_finite() && s > 0.0 && s < 1.0 && best.is_none_or(|(b, _)| s < b) {
                best = Some((s, i));
            }
        }
        self.previous = Some((trial.t1, end));
        self.target = best.map(|(_, i)| i);
        self.aims += 1;
        best.map(|(s, _)| t0 + s * h)
    }
}

/// The smallest root in `(0, 1]` of the quadratic through `(0, g0)`, `(sp, gp)`, `(1, g1)`.
fn through_three(g0: f64, sp: f64, gp: f64, g1: f64) -> Option<f64> {
    // q(s) = g0 + a s + b s^2 with q(sp) = gp, q(1) = g1.
    let (d1, dp) = (g1 - g0, gp - g0);
    let b = (dp - d1 * sp) / (sp * sp - sp);
    let a = d1 - b;
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    smallest_root(g0, a, b)
}

/// The smallest root in `(0, 1]` of `g0 + a s + b s²` (computed without cancellation).
fn smallest_root(g0: f64, a: f64, b: f64) -> Option<f64> {
    let in_range = |s: &f64| *s > 0.0 && *s <= 1.0;
    if b == 0.0 {
        return (a != 0.0).then(|| -g0 / a).filter(in_range);
    }
    let disc = a * a - 4.0 * b * g0;
    if disc < 0.0 {
        return None;
    }
    let q = -0.5 * (a + a.signum() * disc.sqrt());
    let roots = [q / b, if q != 0.0 { g0 / q } else { f64::NAN }];
    roots.into_iter().filter(in_range).min_by(f64::total_cmp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_roots() {
        // (s - 0.25)(s - 2) = s² - 2.25 s + 0.5
        assert!((smallest_root(0.5, -2.25, 1.0).unwrap() - 0.25).abs() < 1e-15);
        // Linear.
        assert!((smallest_root(1.0, -4.0, 0.0).unwrap() - 0.25).abs() < 1e-15);
        // No root in (0, 1].
        assert_eq!(smallest_root(1.0, 1.0, 1.0), None);
        // Through three points of (s - 0.3)(s + 1) = s² + 0.7 s - 0.3.
        let q = |s: f64| s * s + 0.7 * s - 0.3;
        assert!((through_three(q(0.0), 0.6, q(0.6), q(1.0)).unwrap() - 0.3).abs() < 1e-14);
    }
}

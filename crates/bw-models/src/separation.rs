//! The separation condition of the paper, `F <= 0 <= v`: the bodies part at
//! `t_s = inf{t > 0 : F(t) <= 0 <= v(t)}`, where the contact force `F` (N, positive pushing
//! the bodies apart) no longer pushes and the relative velocity `v` (m/s, negative while they
//! approach) has turned. Every path that tests it (the Runge-Kutta path's event location, the
//! Taylor-series path, a simulator holding a law as a force element) uses [`separated`].

use crate::State;
use bwc_events::{Condition, Values};

/// Whether contact force `force` and relative velocity `velocity` satisfy `F <= 0 <= v`.
#[inline]
pub fn separated(force: f64, velocity: f64) -> bool {
    force <= 0.0 && velocity >= 0.0
}

/// The separation condition as an event of `bwc-events`: `of(t, y)` gives `(F, v)` of the
/// state. The locator reports the infimum of the instants where it holds, never the instant of
/// contact itself (where `F = 0` and `v < 0`).
///
/// ```
/// use bw_models::{Separation, State};
/// use bwc_events::Condition;
/// // A state (x, v) of a linear spring contact, F = -k x.
/// let condition = Separation(|_t: f64, y: &State<2>| (-1e3 * y[0], y[1]));
/// let values = condition.values(0.0, &State::<2>::new(0.001, 0.2));
/// assert!(condition.holds(&values, &values));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct Separation<F>(pub F);

impl<const N: usize, F: Fn(f64, &State<N>) -> (f64, f64)> Condition<N> for Separation<F> {
    fn count(&self) -> usize {
        2
    }
    fn values(&self, t: f64, y: &State<N>) -> Values {
        let (force, velocity) = (self.0)(t, y);
        [force, velocity, 0.0, 0.0]
    }
    fn holds(&self, _start: &Values, g: &Values) -> bool {
        separated(g[0], g[1])
    }
}

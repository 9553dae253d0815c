//! The functions a locator watches: boundary conditions ([`Condition`]) that end an integration
//! and switching functions ([`Switches`]) whose zeros it stops at, with their limits.

use crate::root::class;
use bwc_ode::State;

/// A step ending within this many noise floors of a switching point stops there (no retake).
pub(crate) const LANDING: f64 = 100.0;

/// Most boundary or switching functions one condition may have.
pub const MAX_FUNCTIONS: usize = 4;

/// Values of the boundary or switching functions; entries past `count()` are ignored.
pub type Values = [f64; MAX_FUNCTIONS];

/// A terminal condition: a set of states described by the signs of `count()` boundary functions.
///
/// The condition must only change truth value where one of its functions changes sign (or
/// reaches zero); the event is the first instant after the start where it holds.
pub trait Condition<const N: usize> {
    /// Number of boundary functions (at most [`MAX_FUNCTIONS`]).
    fn count(&self) -> usize;
    /// The boundary functions at `(t, y)`.
    fn values(&self, t: f64, y: &State<N>) -> Values;
    /// Whether the condition holds, given the function values now and at the start of the step.
    fn holds(&self, start: &Values, now: &Values) -> bool;
}

/// Functions whose zeros are non-smooth points of the right-hand side.
pub trait Switches<const N: usize> {
    /// Number of switching functions (at most [`MAX_FUNCTIONS`]).
    fn count(&self) -> usize;
    /// The switching functions at `(t, y)`.
    fn values(&self, t: f64, y: &State<N>) -> Values;
    /// Noise floor of each function: a sign change inside a step where `|g|` stays below the
    /// floor at both ends is round-off around a resting point, not a kink, and is ignored
    /// (otherwise a state at rest on a switching surface would chatter). Default: 0.
    fn floor(&self) -> Values {
        [0.0; MAX_FUNCTIONS]
    }
}

/// No switching points: step over everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoSwitches;

impl<const N: usize> Switches<N> for NoSwitches {
    fn count(&self) -> usize {
        0
    }
    fn values(&self, _t: f64, _y: &State<N>) -> Values {
        [0.0; MAX_FUNCTIONS]
    }
}

/// Switching points at the zeros of a function `g(t, y) -> [f64; K]` with `K <= 4`.
#[derive(Debug, Clone, Copy)]
pub struct SwitchAt<G, const K: usize>(pub G);

impl<const N: usize, const K: usize, G: Fn(f64, &State<N>) -> [f64; K]> Switches<N>
    for SwitchAt<G, K>
{
    fn count(&self) -> usize {
        K
    }
    fn values(&self, t: f64, y: &State<N>) -> Values {
        let mut v = [0.0; MAX_FUNCTIONS];
        v[..K].copy_from_slice(&(self.0)(t, y));
        v
    }
}

/// Direction of a crossing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// From negative to zero or positive.
    Up,
    /// From positive to zero or negative.
    Down,
    /// Either way.
    Either,
}

/// The first zero crossing of one function in a given direction.
#[derive(Debug, Clone, Copy)]
pub struct Crossing<G> {
    g: G,
    direction: Direction,
}

impl<G> Crossing<G> {
    /// The event `g(t, y)` crosses zero in `direction`.
    pub fn new(g: G, direction: Direction) -> Self {
        Self { g, direction }
    }
}

impl<const N: usize, G: Fn(f64, &State<N>) -> f64> Condition<N> for Crossing<G> {
    fn count(&self) -> usize {
        1
    }
    fn values(&self, t: f64, y: &State<N>) -> Values {
        [(self.g)(t, y), 0.0, 0.0, 0.0]
    }
    fn holds(&self, start: &Values, now: &Values) -> bool {
        let (s, g) = (class(start[0]), class(now[0]));
        match self.direction {
            Direction::Up => s < 0 && g >= 0,
            Direction::Down => s > 0 && g <= 0,
            Direction::Either => s != 0 && g != s,
        }
    }
}

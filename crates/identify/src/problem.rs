//! What the searches minimise: a cost on the unit cube, with the residuals and the early exits a
//! problem may offer ([`CubeProblem`]); the CoR and duration [`Objective`] is one.

use crate::objective::{Objective, TermOrder};
use bw_models::input::Input;

/// A cost on the unit cube `[0, 1]^d`, always finite (penalised outside the cube).
pub trait CubeProblem: Sync {
    /// Dimension `d`.
    fn dim(&self) -> usize;
    /// The cost at `s`.
    fn cost_at(&self, s: &[f64]) -> f64;
    /// Cost evaluations so far.
    fn evaluations(&self) -> u64;
    /// For a least-squares cost, the residuals at `s` whose sum of squares is
    /// [`CubeProblem::cost_at`]; then the search polishes by Levenberg-Marquardt. `None` (the
    /// default) polishes by Nelder-Mead alone.
    fn residuals_at(&self, s: &[f64]) -> Option<Vec<f64>> {
        let _ = s;
        None
    }
    /// The cost at `s` where it is below `bound`; otherwise any value not below `bound`. A
    /// search that only compares a cost with a bound (a particle with its own best) asks this,
    /// and a problem may then skip work, trying first the terms that `order` ranks high and
    /// updating it (see [`Objective::scalar_below`]). The default is [`CubeProblem::cost_at`].
    fn cost_below(&self, s: &[f64], bound: f64, order: &mut TermOrder) -> f64 {
        let _ = (bound, order);
        self.cost_at(s)
    }
    /// The residuals at `s` where their cost is below `bound`, the same as
    /// [`CubeProblem::residuals_at`]; otherwise `None` or any residuals whose cost is not below
    /// `bound`. Levenberg-Marquardt takes a trial step only if it lowers the cost, so it asks
    /// this with the current cost as `bound`, and a problem may skip work as in
    /// [`CubeProblem::cost_below`]. The default is [`CubeProblem::residuals_at`].
    fn residuals_below(&self, s: &[f64], bound: f64, order: &mut TermOrder) -> Option<Vec<f64>> {
        let _ = (bound, order);
        self.residuals_at(s)
    }
}

impl<I: Input + Sync> CubeProblem for Objective<'_, I> {
    fn dim(&self) -> usize {
        self.space().dim()
    }
    fn cost_at(&self, s: &[f64]) -> f64 {
        self.scalar(s)
    }
    fn evaluations(&self) -> u64 {
        Objective::evaluations(self)
    }
    fn residuals_at(&self, s: &[f64]) -> Option<Vec<f64>> {
        Some(self.residuals(s))
    }
    fn cost_below(&self, s: &[f64], bound: f64, order: &mut TermOrder) -> f64 {
        self.scalar_below(s, bound, order)
    }
    fn residuals_below(&self, s: &[f64], bound: f64, order: &mut TermOrder) -> Option<Vec<f64>> {
        self.residuals_or_partial(s, bound, order).ok()
    }
}

//! Aggregate quantities `Θ_1` (CoR, eq:Theta_1) and `Θ_2` (duration in s, eq:Theta_2), and the
//! costs `J_j = (1/M) Σ (Θ̃_j - Θ_j(P*, u, v0))²` (eq:J) over a dataset.

use crate::data::{Dataset, Point};
use crate::error::IdentifyError;
use crate::space::FitModel;
use crate::space::Space;
use bw_models::input::Input;
use bw_models::{ModelError, Settings};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// The model's prediction at one data point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prediction {
    /// Impact speed (m/s).
    pub v0: f64,
    /// `Θ_1`: CoR (0 without separation).
    pub e: f64,
    /// `Θ_2`: duration `T_d T_b v0^(-(p-1)/(p+1))` (s); the horizon without separation.
    pub t_d: f64,
    /// Whether the bodies separated.
    pub separated: bool,
}

/// `Θ_1` and `Θ_2` of base map `map` with physical input `u` at every point of `data`
/// (each distinct speed simulated once, in parallel; the result is in data order and
/// independent of the thread count).
///
/// # Errors
/// The first [`ModelError`] of a failed simulation.
pub fn predict<I: Input + Sync>(
    map: &FitModel,
    u: &I,
    data: &Dataset,
    settings: &Settings,
) -> Result<Vec<Prediction>, ModelError> {
    let speeds = distinct_speeds(data);
    let at: Vec<Prediction> = speeds
        .par_iter()
        .map(|&v0| prediction(map, u, v0, settings))
        .collect::<Result<_, ModelError>>()?;
    Ok(in_data_order(data, &speeds, &at))
}

/// The distinct impact speeds of `data`, in increasing order.
pub(crate) fn distinct_speeds(data: &Dataset) -> Vec<f64> {
    let mut speeds: Vec<f64> = data.points.iter().map(|p| p.v0).collect();
    speeds.sort_by(f64::total_cmp);
    speeds.dedup();
    speeds
}

/// The predictions `at` the [`distinct_speeds`] `speeds`, one per point of `data`.
fn in_data_order(data: &Dataset, speeds: &[f64], at: &[Prediction]) -> Vec<Prediction> {
    data.points
        .iter()
        .map(|p| at[speeds.partition_point(|&v| v < p.v0)])
        .collect()
}

/// The prediction at one speed.
pub(crate) fn prediction<I: Input + Sync>(
    map: &FitModel,
    u: &I,
    v0: f64,
    settings: &Settings,
) -> Result<Prediction, ModelError> {
    let out = map.impact(u, v0, settings)?;
    Ok(Prediction {
        v0,
        e: out.e,
        t_d: out.t_s.unwrap_or(settings.t_max) * map.time_scale(v0),
        separated: out.separated(),
    })
}

/// The costs of predictions against data: `J1` over the points with a measured CoR, `J2` over
/// those with a measured duration (`None` where there are none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Costs {
    /// Mean squared CoR error.
    pub j1: Option<f64>,
    /// Mean squared duration error (s²).
    pub j2: Option<f64>,
}

impl Costs {
    /// Compares predictions with the data they were made for.
    pub fn of(data: &Dataset, predictions: &[Prediction]) -> Self {
        let mean = |it: &mut dyn Iterator<Item = f64>| {
            let (mut s, mut n) = (0.0, 0usize);
            for r in it {
                s += r * r;
                n += 1;
            }
            (n > 0).then(|| s / n as f64)
        };
        let pairs = || data.points.iter().zip(predictions);
        Costs {
            j1: mean(&mut pairs().filter_map(|(d, p)| d.e.map(|e| e - p.e))),
            j2: mean(&mut pairs().filter_map(|(d, p)| d.t_d.map(|t| t - p.t_d))),
        }
    }

    /// The weighted sum `w1 J1 + w2 J2` (a missing cost counts as 0).
    pub fn weighted(&self, w: Weights) -> f64 {
        w.j1 * self.j1.unwrap_or(0.0) + w.j2 * self.j2.unwrap_or(0.0)
    }
}

/// Weights of the scalarization `w1 J1 + w2 J2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weights {
    /// Weight of `J1`.
    pub j1: f64,
    /// Weight of `J2`.
    pub j2: f64,
}

/// Cost of a point whose simulation failed: worse than any feasible point.
pub const FAILED: f64 = 1e3;

/// The scalarized identification problem on the unit cube of a [`Space`].
pub struct Objective<'a, I> {
    space: &'a Space,
    data: &'a Dataset,
    input: &'a I,
    settings: Settings,
    weights: Weights,
    evaluations: AtomicU64,
    progress: Option<&'a (dyn Fn() + Sync)>,
}

impl<'a, I: Input + Sync> Objective<'a, I> {
    /// The problem of fitting `space` to `data` with input `u`, weights and solver settings.
    ///
    /// # Errors
    /// [`IdentifyError::Objectives`] for negative or non-finite weights, all weights zero, or a
    /// weight on a quantity the data do not contain; [`IdentifyError::Infeasible`] for a
    /// duration objective without `T_b` (or a known mass) to express durations in seconds.
    pub fn new(
        space: &'a Space,
        data: &'a Dataset,
        u: &'a I,
        settings: Settings,
        weights: Weights,
    ) -> Result<Self, IdentifyError> {
        let bad = |reason: &str| {
            Err(IdentifyError::Objectives {
                reason: reason.to_string(),
            })
        };
        if !(weights.j1 >= 0.0
            && weights.j2 >= 0.0
            && weights.j1.is_finite()
            && weights.j2.is_finite())
        {
            return bad("weights must be finite and >= 0");
        }
        if weights.j1 + weights.j2 == 0.0 {
            return bad("at least one weight must be positive");
        }
        if weights.j1 > 0.0 && !data.has_cor() {
            return bad("J1 has a weight but the data have no column `e`");
        }
        if weights.j2 > 0.0 && !data.has_durations() {
            return bad("J2 has a weight but the data have no column `t_d`");
        }
        settings.validate()?;
        Ok(Self {
            space,
            data,
            input: u,
            settings,
            weights,
            evaluations: AtomicU64::new(0),
            progress: None,
        })
    }

    /// Calls `progress` after every cost evaluation.
    pub fn with_progress(mut self, progress: &'a (dyn Fn() + Sync)) -> Self {
        self.progress = Some(progress);
        self
    }

    /// The search space.
    pub fn space(&self) -> &Space {
        self.space
    }

    /// The data.
    pub fn data(&self) -> &Dataset {
        self.data
    }

    /// The physical input `u(t)` (N).
    pub fn input(&self) -> &I {
        self.input
    }

    /// The solver settings of the simulations.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The weights.
    pub fn weights(&self) -> Weights {
        self.weights
    }

    /// Cost evaluations so far.
    pub fn evaluations(&self) -> u64 {
        self.evaluations.load(Ordering::Relaxed)
    }

    /// Predictions and costs at a point of the unit cube.
    ///
    /// # Errors
    /// [`IdentifyError::Model`] when a simulation fails or the point is not admissible.
    pub fn evaluate(&self, s: &[f64]) -> Result<(Vec<Prediction>, Costs), IdentifyError> {
        let p = self.space.decode(s);
        let map = self.space.map(&p)?;
        let predictions = predict(&map, self.input, self.data, &self.settings)?;
        let costs = Costs::of(self.data, &predictions);
        Ok((predictions, costs))
    }

    /// The weighted residuals of predictions: `sqrt(w1 / M1) (e_model - e)` for every point with
    /// a CoR and `sqrt(w2 / M2) (t_d,model - t_d)` for every point with a duration (where the
    /// weight is positive), in data order; their sum of squares is `w1 J1 + w2 J2`.
    pub fn weighted_residuals(&self, predictions: &[Prediction]) -> Vec<f64> {
        let scales = self.residual_scales();
        let mut r = Vec::new();
        for (d, p) in self.data.points.iter().zip(predictions) {
            let (e, t) = point_residuals(d, p, scales);
            r.extend(e);
            r.extend(t);
        }
        r
    }

    /// `sqrt(w1 / M1)` and `sqrt(w2 / M2)`, the factors of the weighted residuals, each `None`
    /// where its weight is zero.
    pub(crate) fn residual_scales(&self) -> (Option<f64>, Option<f64>) {
        let w = self.weights;
        let count = |has: fn(&Point) -> bool| {
            self.data.points.iter().filter(|p| has(p)).count().max(1) as f64
        };
        let n1 = count(|p| p.e.is_some());
        let n2 = count(|p| p.t_d.is_some());
        (
            (w.j1 > 0.0).then(|| (w.j1 / n1).sqrt()),
            (w.j2 > 0.0).then(|| (w.j2 / n2).sqrt()),
        )
    }

    /// The penalty at `s`: `(s - clamp(s))²` outside the cube, plus `1 + 10 v` for a violation
    /// `v` of the inequality constraint.
    fn penalty(&self, s: &[f64]) -> f64 {
        let outside: f64 = s.iter().map(|x| (x - x.clamp(0.0, 1.0)).powi(2)).sum();
        let v = self.space.violation(&self.space.decode(s));
        outside + if v > 0.0 { 1.0 + 10.0 * v } else { 0.0 }
    }

    /// Counts an evaluation and reports it.
    fn count(&self) {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        if let Some(p) = self.progress {
            p();
        }
    }

    /// The residual vector of predictions (`None` for a failed simulation) and the penalty.
    fn residuals_of(&self, predictions: Option<&[Prediction]>, penalty: f64) -> Vec<f64> {
        if let Some(p) = predictions {
            let mut r = self.weighted_residuals(p);
            if r.iter().all(|x| x.is_finite()) {
                r.push(penalty.sqrt());
                return r;
            }
        }
        let mut r = vec![0.0; self.weighted_residual_count()];
        r.push((FAILED + penalty).sqrt());
        r
    }

    /// The residual vector at `s`: [`Objective::weighted_residuals`] followed by one penalty
    /// entry, so that its sum of squares is [`Objective::scalar`]. A failed simulation gives
    /// zero residuals and the penalty entry `sqrt(FAILED + penalty)`.
    pub fn residuals(&self, s: &[f64]) -> Vec<f64> {
        self.count();
        let penalty = self.penalty(s);
        let predictions = self.evaluate(s).ok().map(|(p, _)| p);
        self.residuals_of(predictions.as_deref(), penalty)
    }

    fn weighted_residual_count(&self) -> usize {
        let w = self.weights;
        self.data
            .points
            .iter()
            .map(|d| {
                usize::from(d.e.is_some() && w.j1 > 0.0)
                    + usize::from(d.t_d.is_some() && w.j2 > 0.0)
            })
            .sum()
    }

    /// The scalar cost at `s`: `w1 J1 + w2 J2`, plus a penalty `1 + 10 v` for a violation `v`
    /// of the inequality constraint and `(s - clamp(s))²` outside the cube (Nelder-Mead is
    /// unbounded); [`FAILED`] when a simulation fails. Always finite.
    pub fn scalar(&self, s: &[f64]) -> f64 {
        self.residuals(s).iter().map(|x| x * x).sum()
    }

    /// [`Objective::scalar`] for a search that only asks whether it is below `bound` (a
    /// particle against its own best): the same value, bit for bit, where it is below `bound`;
    /// otherwise possibly a smaller value that is still above `bound`. The speeds are simulated
    /// one after another, largest weight in `order` first, and once the penalty plus the
    /// squared residuals of the points simulated so far exceed `bound` (by more than the
    /// rounding of the sum), the rest are skipped: every term is nonnegative, so the full cost
    /// exceeds `bound` too. Only below [`FAILED`], so that a failed simulation's cost compares
    /// with `bound` as before. Each simulated speed's weight in `order` becomes its squared
    /// residuals. Counts as one evaluation.
    pub fn scalar_below(&self, s: &[f64], bound: f64, order: &mut TermOrder) -> f64 {
        match self.residuals_or_partial(s, bound, order) {
            Ok(r) => r.iter().map(|x| x * x).sum(),
            Err(partial) => partial,
        }
    }

    /// The residuals at `s` as [`Objective::residuals`] gives them, or where the speeds
    /// simulated in `order` have passed `bound`, the partial cost (see
    /// [`Objective::scalar_below`]). Counts as one evaluation.
    pub(crate) fn residuals_or_partial(
        &self,
        s: &[f64],
        bound: f64,
        order: &mut TermOrder,
    ) -> Result<Vec<f64>, f64> {
        self.count();
        let penalty = self.penalty(s);
        let passed = passes(bound, FAILED);
        if passed(penalty) {
            return Err(penalty);
        }
        let p = self.predict_below(s, penalty, passed, order)?;
        Ok(self.residuals_of(p.as_deref(), penalty))
    }

    /// The predictions at `s` (`None` where a simulation fails), speed after speed in `order`,
    /// or the partial cost (from `penalty`) at which `passed` stopped them.
    fn predict_below(
        &self,
        s: &[f64],
        penalty: f64,
        passed: impl Fn(f64) -> bool,
        order: &mut TermOrder,
    ) -> Result<Option<Vec<Prediction>>, f64> {
        let Ok(map) = self.space.map(&self.space.decode(s)) else {
            return Ok(None);
        };
        let scales = self.residual_scales();
        let speeds = distinct_speeds(self.data);
        let at = order.accumulate(speeds.len(), penalty, passed, |k| {
            let p = prediction(&map, self.input, speeds[k], &self.settings).ok()?;
            let points = self.data.points.iter().filter(|d| d.v0 == speeds[k]);
            let squares: f64 = points
                .map(|d| {
                    let (e, t) = point_residuals(d, &p, scales);
                    e.into_iter().chain(t).map(|x| x * x).sum::<f64>()
                })
                .sum();
            Some((p, squares))
        })?;
        Ok(at.map(|at| in_data_order(self.data, &speeds, &at)))
    }
}

/// Whether a partial cost has passed `bound` for [`Objective::scalar_below`] and its kin: by
/// more than [`PASSED_MARGIN`], and only for a bound below `failed` (the cost of a failed
/// simulation, which then compares with the bound as the full evaluation would).
pub(crate) fn passes(bound: f64, failed: f64) -> impl Fn(f64) -> bool {
    move |partial| bound < failed && partial > bound * (1.0 + PASSED_MARGIN)
}

/// The order in which a cost with early stopping computes its terms (the distinct speeds of
/// [`Objective::scalar_below`], the release heights of a drop fit; index `k` in increasing
/// order of speed or height): the largest weight first, ties by index. The weights start at
/// zero and become each term's contribution where it was last computed, so that a search that
/// keeps one order per particle tries first where that particle fitted worst.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TermOrder {
    weights: Vec<f64>,
}

impl TermOrder {
    /// Computes terms `0..n` in this order: `term(k)` gives term `k`'s value and its
    /// nonnegative contribution to the cost, or `None` where it fails. Returns the values in
    /// index order (`None` if a term failed), or the partial cost from `start` once `passed`
    /// holds for it (the remaining terms skipped). Each computed term's weight becomes its
    /// contribution.
    pub(crate) fn accumulate<T>(
        &mut self,
        n: usize,
        start: f64,
        passed: impl Fn(f64) -> bool,
        mut term: impl FnMut(usize) -> Option<(T, f64)>,
    ) -> Result<Option<Vec<T>>, f64> {
        let mut values: Vec<Option<T>> = (0..n).map(|_| None).collect();
        let mut partial = start;
        for k in self.sequence(n) {
            let Some((value, contribution)) = term(k) else {
                return Ok(None);
            };
            self.weights[k] = contribution;
            partial += contribution;
            if passed(partial) {
                return Err(partial);
            }
            values[k] = Some(value);
        }
        Ok(values.into_iter().collect())
    }

    /// The indices `0..n` in this order (weights reset to zero if there were not `n`).
    fn sequence(&mut self, n: usize) -> Vec<usize> {
        if self.weights.len() != n {
            self.weights = vec![0.0; n];
        }
        let mut k: Vec<usize> = (0..n).collect();
        k.sort_by(|&a, &b| self.weights[b].total_cmp(&self.weights[a]));
        k
    }
}

/// Relative margin by which a partial cost must exceed a bound in [`Objective::scalar_below`]:
/// far above the rounding of a sum of a few hundred terms, which may make a partial sum exceed
/// the full sum (taken in another order) by that much.
const PASSED_MARGIN: f64 = 1e-12;

/// The weighted residuals of one data point against its prediction (CoR, duration), for the
/// scales of [`Objective::residual_scales`].
fn point_residuals(
    d: &Point,
    p: &Prediction,
    (s1, s2): (Option<f64>, Option<f64>),
) -> (Option<f64>, Option<f64>) {
    (
        s1.zip(d.e).map(|(w, e)| w * (p.e - e)),
        s2.zip(d.t_d).map(|(w, t)| w * (p.t_d - t)),
    )
}

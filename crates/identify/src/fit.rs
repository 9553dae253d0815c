//! Global search with argmin's particle swarm, then Levenberg-Marquardt and Nelder-Mead
//! polishing, from several seeded starts. Everything runs on the unit cube of the
//! [`crate::Space`].

use crate::error::IdentifyError;
use crate::objective::{Costs, Objective, Prediction, TermOrder};
use crate::problem::CubeProblem;
use argmin::core::{Executor, State};
use argmin::solver::neldermead::NelderMead;
use argmin::solver::particleswarm::ParticleSwarm;
use bw_models::input::Input;
use bw_models::BaseParams;
use rand::SeedableRng;
use rayon::prelude::*;
use std::sync::{Mutex, PoisonError};
use std::time::Instant;

/// Optimizer budget and stopping rule of [`minimize`].
///
/// Each *start* is a point polished by Levenberg-Marquardt where the problem has residuals, and
/// by Nelder-Mead where that does not converge or there are none, until a fresh simplex no
/// longer improves it. The starts alternate between two kinds of origin: the even ones a point
/// of a seeded Latin hypercube of the cube (unbiased: each alone in its stratum on every axis),
/// the odd ones (and a search of one start) the best point of an independent particle swarm
/// (its own seed). Each kind finds
/// basins the other misses (BENCHMARKS.md, "Identification: the global optimum on measured
/// data"). Starts run in batches until `agree` of them, from origins in distinct regions of
/// the cube (see [`Convergence::agreeing`]), end within `tolerance` (relative) of the best cost
/// found, or `max_starts` have run; the best point is then verified by Nelder-Mead from a fresh
/// simplex (and the batches go on if that moves it below the others).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    /// Particles of each swarm (the odd starts).
    pub particles: usize,
    /// Swarm iterations per swarm start.
    pub iterations: u64,
    /// Nelder-Mead iterations per polishing round (a polish runs up to [`POLISH_ROUNDS`]
    /// rounds, each from a fresh simplex).
    pub polish_iterations: u64,
    /// Independent starts run before the stopping rule is first checked.
    pub starts: usize,
    /// Most independent starts.
    pub max_starts: usize,
    /// Starts that must agree with the best for the search to count as converged.
    pub agree: usize,
    /// Relative tolerance of that agreement: a start agrees when its cost is at most
    /// `(1 + tolerance)` times the best.
    pub tolerance: f64,
}

/// The distance on the unit cube of six searched quantities between the origins of two starts
/// that makes their agreement count twice (see [`Convergence::agreeing`]); in `d` dimensions
/// it is `REGION √(d/6)`, the same fraction of the typical distance between two random points.
pub const REGION: f64 = 0.5;

/// Most Nelder-Mead rounds per polish.
pub const POLISH_ROUNDS: u64 = 4;

/// Starts added per batch once the first `starts` have run.
const BATCH: usize = 2;

impl Default for Budget {
    fn default() -> Self {
        Self {
            particles: 20,
            iterations: 15,
            polish_iterations: 60,
            starts: 10,
            max_starts: 20,
            agree: 4,
            tolerance: 0.01,
        }
    }
}

impl Budget {
    /// One start, no stopping rule: the budget of a local refinement from a known point.
    pub fn single(self) -> Self {
        Self {
            starts: 1,
            max_starts: 1,
            agree: 1,
            ..self
        }
    }

    /// About how many cost evaluations the budget allows at most (for progress bars).
    pub fn evaluations(&self, dim: usize) -> u64 {
        self.max_starts.max(self.starts) as u64 * self.per_start(dim)
    }

    /// About how many cost evaluations one start takes (the mean of a swarm start and a
    /// Latin-hypercube start).
    pub fn per_start(&self, dim: usize) -> u64 {
        self.particles as u64 * (self.iterations + 1) / 2
            + self.polish_iterations * 2
            + dim as u64
            + 1
    }

    /// Checks that the budget can run.
    ///
    /// # Errors
    /// [`IdentifyError::Optimizer`] naming the inadmissible setting.
    pub fn validate(&self) -> Result<(), IdentifyError> {
        let bad = |message: &str| {
            Err(IdentifyError::Optimizer {
                message: message.into(),
            })
        };
        if self.particles < 2 {
            return bad("need at least 2 particles");
        }
        if self.starts == 0 || self.agree == 0 {
            return bad("need at least 1 start and agree >= 1");
        }
        if self.max_starts < self.starts {
            return bad(&format!(
                "max_starts = {} must be >= starts = {}",
                self.max_starts, self.starts
            ));
        }
        if self.agree > self.max_starts {
            return bad(&format!(
                "agree = {} must be <= max_starts = {}",
                self.agree, self.max_starts
            ));
        }
        if !(self.tolerance >= 0.0 && self.tolerance.is_finite()) {
            return bad("the agreement tolerance must be finite and >= 0");
        }
        Ok(())
    }
}

/// How the search ended: the evidence that it found the optimum in its bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct Convergence {
    /// Independent starts run.
    pub starts: usize,
    /// Starts whose cost is within the tolerance of the best (the best itself included), counted
    /// once per region: a start counts only where its origin (the point its polish began from)
    /// lies at least [`REGION`] (scaled to the dimension) from the origin of every start
    /// counted before it. Swarms drawn into the same basin from the whole cube begin their polishes
    /// at nearly the same point and count once.
    pub agreeing: usize,
    /// Cost evaluations of the whole search.
    pub evaluations: u64,
    /// The final cost of every start, in start order.
    pub costs: Vec<f64>,
}

impl Convergence {
    /// Whether at least two independent starts agree.
    pub fn converged(&self) -> bool {
        self.agreeing >= 2
    }
}

/// The outcome of a fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitResult {
    /// Identified base parameters.
    pub params: BaseParams,
    /// The point on the unit cube.
    pub point: Vec<f64>,
    /// Costs at the optimum.
    pub costs: Costs,
    /// The scalarized cost at the optimum.
    pub cost: f64,
    /// Predictions at the optimum.
    pub predictions: Vec<Prediction>,
    /// Cost evaluations used.
    pub evaluations: u64,
    /// Wall-clock time (s).
    pub wall_s: f64,
    /// How the search ended.
    pub convergence: Convergence,
    /// The coordinates of [`FitResult::point`] on a bound of the search (positions in
    /// [`crate::Space::free_indices`]; see [`at_bound`]).
    pub at_bound: Vec<usize>,
}

fn optimizer_error(e: argmin::core::Error) -> IdentifyError {
    IdentifyError::Optimizer {
        message: e.to_string(),
    }
}

/// argmin's view of a [`CubeProblem`].
struct Cube<'a, P>(&'a P);

impl<P: CubeProblem> argmin::core::CostFunction for Cube<'_, P> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, s: &Self::Param) -> Result<f64, argmin::core::Error> {
        Ok(self.0.cost_at(s))
    }
}

/// The particle swarm's view of a [`CubeProblem`]. argmin's swarm uses a particle's new cost
/// only to compare it with that particle's best, so each particle is evaluated with
/// [`CubeProblem::cost_below`] its best, with its own [`TermOrder`]: the same search, with less
/// work where a particle does not improve. `particles` mirrors the particles' best costs in
/// argmin's order: the first bulk evaluation is the initial swarm, which argmin then sorts by
/// cost (stably); every later one holds the particles' new positions in that order, and a best
/// is replaced by a lower cost.
struct Swarm<'a, P> {
    problem: &'a P,
    particles: Mutex<Vec<(f64, TermOrder)>>,
}

impl<P: CubeProblem> argmin::core::CostFunction for Swarm<'_, P> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, s: &Self::Param) -> Result<f64, argmin::core::Error> {
        Ok(self.problem.cost_at(s))
    }
    fn bulk_cost<Q>(&self, params: &[Q]) -> Result<Vec<f64>, argmin::core::Error>
    where
        Q: std::borrow::Borrow<Self::Param> + argmin::core::SyncAlias,
        f64: argmin::core::SendAlias,
        Self: argmin::core::SyncAlias,
    {
        let mut particles = self
            .particles
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        let initial = particles.is_empty();
        if initial {
            particles.resize(params.len(), (f64::INFINITY, TermOrder::default()));
        } else if particles.len() != params.len() {
            return Err(argmin::core::Error::msg(format!(
                "particle swarm: {} positions for {} particles",
                params.len(),
                particles.len()
            )));
        }
        let costs: Vec<f64> = params
            .par_iter()
            .zip(particles.par_iter_mut())
            .map(|(s, (best, order))| self.problem.cost_below(s.borrow(), *best, order))
            .collect();
        for ((best, _), &c) in particles.iter_mut().zip(&costs) {
            if c < *best {
                *best = c;
            }
        }
        if initial {
            particles.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
        }
        Ok(costs)
    }
}

/// The best point found by [`minimize`].
#[derive(Debug, Clone, PartialEq)]
pub struct Minimum {
    /// The point, clamped into the cube.
    pub point: Vec<f64>,
    /// Its cost.
    pub cost: f64,
    /// Cost evaluations used.
    pub evaluations: u64,
    /// How the search ended.
    pub convergence: Convergence,
}

/// Seed of start `k`: independent streams for every start of every fit.
fn start_seed(seed: u64, k: usize) -> u64 {
    seed ^ (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
}

/// The end of one start: where its polish began and where it ended.
#[derive(Debug, Clone)]
struct End {
    origin: Vec<f64>,
    point: Vec<f64>,
    cost: f64,
    /// Whether its polish stopped where it crept ([`crate::lm::Creep`]).
    crept: bool,
}

/// Minimises a cube problem: independent starts (a Latin-hypercube point or a seeded particle
/// swarm's best, then a polish; see [`Budget`]) in batches until `budget.agree` of them agree
/// with the best from distinct regions, the best start verified by Nelder-Mead from a fresh
/// simplex, `start` (if given) polished and verified too; the best point is then moved onto
/// any bound it lies within 1e-3 of where that does not raise the cost. Deterministic for a
/// seed, whatever the number of threads: each start depends only on the seed and its index,
/// and the batches and the verification do not depend on the threads.
///
/// # Errors
/// [`IdentifyError::Optimizer`] for an inadmissible budget or an optimizer failure.
pub fn minimize<P: CubeProblem>(
    problem: &P,
    budget: &Budget,
    seed: u64,
    start: Option<&[f64]>,
) -> Result<Minimum, IdentifyError> {
    budget.validate()?;
    let d = problem.dim();
    let before = problem.evaluations();
    if d == 0 {
        return Ok(nothing_free(problem, before));
    }
    let given = start
        .map(|s| {
            let (point, cost, _) =
                refine(problem, s.to_vec(), budget.polish_iterations, Polish::Full)?;
            Ok::<_, IdentifyError>(End {
                origin: s.to_vec(),
                point,
                cost,
                crept: false,
            })
        })
        .transpose()?;
    // Independent starts check each other; a single start polishes in full.
    let polish = if budget.agree >= 2 {
        Polish::Start
    } else {
        Polish::Full
    };
    let origins = latin_hypercube(d, budget.max_starts.div_ceil(2), seed);
    let mut runs: Vec<End> = Vec::new();
    // The start last verified by a fresh simplex (a verification only lowers its cost, so an
    // earlier one cannot be the best again once another is).
    let mut verified = None;
    let agreeing = loop {
        let k = runs.len();
        let batch = if k == 0 { budget.starts } else { BATCH };
        let batch = batch.min(budget.max_starts - k);
        let new: Vec<_> = (k..k + batch)
            .into_par_iter()
            .map(|k| {
                let origin = (k % 2 == 0 && budget.max_starts > 1).then(|| origins[k / 2].clone());
                one_start(problem, budget, start_seed(seed, k), origin, polish)
            })
            .collect::<Result<_, _>>()?;
        runs.extend(new);
        let mut agreeing = agreement(&runs, given.as_ref(), budget.tolerance);
        let done =
            |agreeing, runs: &[_]| agreeing >= budget.agree || runs.len() >= budget.max_starts;
        if done(agreeing, &runs) && polish == Polish::Start {
            verify_best(problem, budget, &mut runs, &mut verified)?;
            agreeing = agreement(&runs, given.as_ref(), budget.tolerance);
        }
        if done(agreeing, &runs) {
            break agreeing;
        }
    };
    let costs: Vec<f64> = runs.iter().map(|r| r.cost).collect();
    let best = runs
        .into_iter()
        .chain(given)
        .min_by(|a, b| a.cost.total_cmp(&b.cost))
        .expect("at least one start");
    let (point, cost) = snap_to_bounds(problem, best.point, best.cost);
    let evaluations = problem.evaluations() - before;
    Ok(Minimum {
        point,
        cost,
        evaluations,
        convergence: Convergence {
            starts: costs.len(),
            agreeing,
            evaluations,
            costs,
        },
    })
}

/// `n` points of a Latin hypercube on `[0, 1]^d` seeded by `seed`: on every axis, each point
/// alone in one of `n` equal strata, at a uniform place within it.
fn latin_hypercube(d: usize, n: usize, seed: u64) -> Vec<Vec<f64>> {
    use rand::seq::SliceRandom;
    use rand::Rng;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ 0x4C41_5449_4E48_5950);
    let mut points = vec![vec![0.0; d]; n];
    for j in 0..d {
        let mut strata: Vec<usize> = (0..n).collect();
        strata.shuffle(&mut rng);
        for (point, stratum) in points.iter_mut().zip(strata) {
            point[j] = (stratum as f64 + rng.random::<f64>()) / n as f64;
        }
    }
    points
}

/// The minimum where nothing is free: the cost of the empty point.
fn nothing_free<P: CubeProblem>(problem: &P, before: u64) -> Minimum {
    let cost = problem.cost_at(&[]);
    let evaluations = problem.evaluations() - before;
    Minimum {
        point: Vec::new(),
        cost,
        evaluations,
        convergence: Convergence {
            starts: 1,
            agreeing: 1,
            evaluations,
            costs: vec![cost],
        },
    }
}

/// Verifies the best start's end ([`Polish::Verify`], or [`Polish::Full`] where its polish
/// stopped creeping) unless it was verified already.
fn verify_best<P: CubeProblem>(
    problem: &P,
    budget: &Budget,
    runs: &mut [End],
    verified: &mut Option<usize>,
) -> Result<(), IdentifyError> {
    let best = best_start(runs);
    if *verified == Some(best) {
        return Ok(());
    }
    *verified = Some(best);
    let x = runs[best].point.clone();
    let kind = if runs[best].crept {
        Polish::Full
    } else {
        Polish::Verify
    };
    let (y, c, _) = refine(problem, x, budget.polish_iterations, kind)?;
    if c < runs[best].cost {
        (runs[best].point, runs[best].cost) = (y, c);
    }
    Ok(())
}

/// The starts whose cost is within `tolerance` (relative) of the best, counted once per region
/// (see [`Convergence::agreeing`]).
fn agreement(runs: &[End], given: Option<&End>, tolerance: f64) -> usize {
    let best = runs
        .iter()
        .chain(given)
        .map(|r| r.cost)
        .fold(f64::INFINITY, f64::min);
    let mut counted: Vec<&[f64]> = Vec::new();
    let region = runs
        .first()
        .map_or(REGION, |r| REGION * (r.origin.len() as f64 / 6.0).sqrt());
    for r in runs
        .iter()
        .filter(|r| r.cost <= best + tolerance * best.abs())
    {
        let apart = |o: &&[f64]| {
            let squared: f64 = o
                .iter()
                .zip(&r.origin)
                .map(|(a, b)| (a - b) * (a - b))
                .sum();
            squared.sqrt() >= region
        };
        if counted.iter().all(apart) {
            counted.push(&r.origin);
        }
    }
    counted.len()
}

/// The index of the start with the lowest cost (the first of equals).
fn best_start(runs: &[End]) -> usize {
    (0..runs.len())
        .min_by(|&a, &b| runs[a].cost.total_cmp(&runs[b].cost))
        .expect("at least one start")
}

/// One independent start: the polish by `polish` of `origin`, or where there is none, of the
/// best point of a particle swarm seeded by `seed`.
fn one_start<P: CubeProblem>(
    problem: &P,
    budget: &Budget,
    seed: u64,
    origin: Option<Vec<f64>>,
    polish: Polish,
) -> Result<End, IdentifyError> {
    let origin = match origin {
        Some(origin) => origin,
        None => swarm_best(problem, budget, seed)?,
    };
    let (point, cost, crept) = refine(problem, origin.clone(), budget.polish_iterations, polish)?;
    Ok(End {
        origin,
        point,
        cost,
        crept,
    })
}

/// The best point of a particle swarm seeded by `seed`.
fn swarm_best<P: CubeProblem>(
    problem: &P,
    budget: &Budget,
    seed: u64,
) -> Result<Vec<f64>, IdentifyError> {
    let d = problem.dim();
    let rng = rand::rngs::StdRng::seed_from_u64(seed);
    let swarm =
        ParticleSwarm::new((vec![0.0; d], vec![1.0; d]), budget.particles).with_rng_generator(rng);
    let swarm_problem = Swarm {
        problem,
        particles: Mutex::new(Vec::new()),
    };
    let res = Executor::new(swarm_problem, swarm)
        .configure(|s| s.max_iters(budget.iterations))
        .run()
        .map_err(optimizer_error)?;
    Ok(res
        .state()
        .get_best_param()
        .map(|b| b.position.clone())
        .unwrap_or_else(|| vec![0.5; d]))
}

/// How [`refine`] polishes a point.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Polish {
    /// A start's end: Levenberg-Marquardt stopped where it creeps ([`crate::lm::START_CREEP`]),
    /// then Nelder-Mead only where it neither converged nor crept (or the problem has no
    /// residuals). Over the fixtures' starts, a Nelder-Mead round after a
    /// converged Levenberg-Marquardt polish never lowered the cost (BENCHMARKS.md, "Identification: convergence");
    /// the agreement of independent starts and the verification of the best check them instead.
    Start,
    /// The verification of a start's end: a Nelder-Mead round from a fresh simplex first (its
    /// Levenberg-Marquardt polish has converged), then as [`Polish::Full`] if that gains.
    Verify,
    /// A given point: Levenberg-Marquardt, then Nelder-Mead rounds.
    Full,
}

/// Local polish of `x`: Levenberg-Marquardt where the problem has residuals, then a
/// Nelder-Mead round of `iterations` from a fresh simplex (which also escapes where the
/// Levenberg-Marquardt steps stall), repeated while that round still gains more than 1e-9
/// relative; `kind` skips the parts of the first round that [`Polish`] says are not needed.
/// The point, its cost and whether the polish stopped where it crept.
fn refine<P: CubeProblem>(
    problem: &P,
    x: Vec<f64>,
    iterations: u64,
    kind: Polish,
) -> Result<(Vec<f64>, f64, bool), IdentifyError> {
    let (mut x, mut cost) = (x.clone(), problem.cost_at(&x));
    let creep = (kind == Polish::Start).then_some(crate::lm::START_CREEP);
    let mut crept = false;
    for round in 0..POLISH_ROUNDS {
        let mut converged = false;
        let least_squares = round > 0 || kind != Polish::Verify;
        if let Some(end) = least_squares
            .then(|| crate::lm::polish(problem, &x, cost, creep))
            .flatten()
        {
            if end.cost < cost {
                (x, cost) = (end.x, end.cost);
            }
            (converged, crept) = (end.converged, end.crept);
        }
        if (converged || crept) && kind == Polish::Start {
            break;
        }
        let (y, c) = polish(problem, x.clone(), iterations)?;
        let gain = cost - c;
        if c < cost {
            (x, cost) = (y, c);
        }
        // NaN gains end the polish too.
        if gain.is_nan() || gain <= 1e-9 * cost.abs() {
            break;
        }
    }
    Ok((x.iter().map(|v| v.clamp(0.0, 1.0)).collect(), cost, crept))
}

/// Moves coordinates within 1e-3 of a face of the cube onto it where the cost does not rise:
/// Nelder-Mead approaches an optimum on a bound only asymptotically, and a parameter on its
/// bound must be reported as such.
fn snap_to_bounds<P: CubeProblem>(problem: &P, mut x: Vec<f64>, mut cost: f64) -> (Vec<f64>, f64) {
    for j in 0..x.len() {
        let face = if x[j] < 1e-3 {
            0.0
        } else if x[j] > 1.0 - 1e-3 {
            1.0
        } else {
            continue;
        };
        if x[j] == face {
            continue;
        }
        let mut y = x.clone();
        y[j] = face;
        let c = problem.cost_at(&y);
        if c <= cost {
            (x, cost) = (y, c);
        }
    }
    (x, cost)
}

/// The coordinates of a unit-cube point that lie within 1e-6 (relative to the searched
/// interval, on its scale) of a bound, in search order.
pub fn at_bound(point: &[f64]) -> Vec<usize> {
    (0..point.len())
        .filter(|&j| point[j] <= 1e-6 || point[j] >= 1.0 - 1e-6)
        .collect()
}

/// Fits base parameters: [`minimize`] the objective, then evaluate the optimum.
///
/// # Errors
/// As [`minimize`]; [`IdentifyError::Model`] if the optimum cannot be evaluated.
pub fn fit<I: Input + Sync>(
    objective: &Objective<'_, I>,
    budget: &Budget,
    seed: u64,
    start: Option<&[f64]>,
) -> Result<FitResult, IdentifyError> {
    let clock = Instant::now();
    let m = minimize(objective, budget, seed, start)?;
    let (predictions, costs) = objective.evaluate(&m.point)?;
    Ok(FitResult {
        at_bound: at_bound(&m.point),
        params: objective.space().decode(&m.point),
        point: m.point,
        costs,
        cost: m.cost,
        predictions,
        evaluations: m.evaluations,
        wall_s: clock.elapsed().as_secs_f64(),
        convergence: m.convergence,
    })
}

/// Nelder-Mead from `x0` with an initial simplex of edge 0.05 (pointing into the cube).
fn polish<P: CubeProblem>(
    problem: &P,
    x0: Vec<f64>,
    iterations: u64,
) -> Result<(Vec<f64>, f64), IdentifyError> {
    let d = x0.len();
    let mut simplex = vec![x0.clone()];
    for i in 0..d {
        let mut v = x0.clone();
        v[i] += if v[i] > 0.5 { -0.05 } else { 0.05 };
        simplex.push(v);
    }
    let nm = NelderMead::new(simplex)
        .with_sd_tolerance(1e-13)
        .map_err(optimizer_error)?;
    let res = Executor::new(Cube(problem), nm)
        .configure(|s| s.max_iters(iterations))
        .run()
        .map_err(optimizer_error)?;
    let state = res.state();
    let s = state.get_best_param().cloned().unwrap_or(x0);
    Ok((s, state.get_best_cost()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latin_hypercube_points_each_hold_their_own_stratum_on_every_axis() {
        let points = latin_hypercube(3, 10, 42);
        assert_eq!(points.len(), 10);
        for j in 0..3 {
            let mut strata: Vec<usize> = points.iter().map(|p| (p[j] * 10.0) as usize).collect();
            strata.sort_unstable();
            assert_eq!(strata, (0..10).collect::<Vec<_>>(), "axis {j}");
        }
        assert_eq!(points, latin_hypercube(3, 10, 42));
        assert_ne!(points, latin_hypercube(3, 10, 43));
    }

    fn end(origin: [f64; 2], cost: f64) -> End {
        End {
            origin: origin.to_vec(),
            point: vec![0.5, 0.5],
            cost,
            crept: false,
        }
    }

    #[test]
    fn agreement_counts_starts_begun_in_the_same_region_once() {
        // Three starts at the best cost, two of them begun 0.1 apart (the region in two
        // dimensions is 0.5 √(1/3) = 0.289): two regions. The fourth is 2 % above the best,
        // outside the 1 % tolerance.
        let runs = [
            end([0.1, 0.1], 1.0),
            end([0.15, 0.18], 1.005),
            end([0.9, 0.2], 1.0),
            end([0.5, 0.9], 1.02),
        ];
        assert_eq!(agreement(&runs, None, 0.01), 2);
        assert_eq!(agreement(&runs, None, 0.03), 3);
        // Origins 0.3 apart are distinct regions, 0.28 apart not.
        let apart = [end([0.0, 0.0], 1.0), end([0.18, 0.24], 1.0)];
        assert_eq!(agreement(&apart, None, 0.0), 2);
        let near = [end([0.0, 0.0], 1.0), end([0.168, 0.224], 1.0)];
        assert_eq!(agreement(&near, None, 0.0), 1);
        // A given point's lower cost sets the best that the starts must agree with.
        let given = end([0.5, 0.5], 0.5);
        assert_eq!(agreement(&runs, Some(&given), 0.01), 0);
    }
}

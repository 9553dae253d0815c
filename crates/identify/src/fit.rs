//! Global search with argmin's particle swarm, then Nelder-Mead polishing, from several seeded
//! starts. Everything runs on the unit cube of the [`crate::Space`].

use crate::objective::{Costs, Objective, Prediction};
use crate::IdentifyError;
use argmin::core::{Executor, State};
use argmin::solver::neldermead::NelderMead;
use argmin::solver::particleswarm::ParticleSwarm;
use bw_models::input::Input;
use bw_models::BaseParams;
use rand::SeedableRng;
use std::time::Instant;

/// Optimizer budget.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    /// Particles of the swarm.
    pub particles: usize,
    /// Swarm iterations.
    pub iterations: u64,
    /// Nelder-Mead iterations per polish.
    pub polish_iterations: u64,
    /// Independent swarm starts (each polished).
    pub starts: usize,
}

impl Default for Budget {
    fn default() -> Self {
        Self {
            particles: 24,
            iterations: 60,
            polish_iterations: 600,
            starts: 2,
        }
    }
}

impl Budget {
    /// About how many cost evaluations the budget allows (for progress bars).
    pub fn evaluations(&self, dim: usize) -> u64 {
        self.starts as u64
            * (self.particles as u64 * (self.iterations + 1)
                + self.polish_iterations * 2
                + dim as u64
                + 1)
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
}

fn optimizer_error(e: argmin::core::Error) -> IdentifyError {
    IdentifyError::Optimizer {
        message: e.to_string(),
    }
}

/// A cost on the unit cube `[0, 1]^d`, always finite (penalised outside the cube).
pub trait CubeProblem: Sync {
    /// Dimension `d`.
    fn dim(&self) -> usize;
    /// The cost at `s`.
    fn cost_at(&self, s: &[f64]) -> f64;
    /// Cost evaluations so far.
    fn evaluations(&self) -> u64;
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

/// The best point found by [`minimize`].
#[derive(Debug, Clone, PartialEq)]
pub struct Minimum {
    /// The point, clamped into the cube.
    pub point: Vec<f64>,
    /// Its cost.
    pub cost: f64,
    /// Cost evaluations used.
    pub evaluations: u64,
}

/// Minimises a cube problem: `budget.starts` particle swarms seeded from `seed`, each best
/// point (and `start`, if given) polished by Nelder-Mead twice (the second time from a fresh
/// simplex); the best wins. Deterministic for a seed, whatever the number of threads.
///
/// # Errors
/// [`IdentifyError::Optimizer`] for a degenerate budget or an optimizer failure.
pub fn minimize<P: CubeProblem>(
    problem: &P,
    budget: &Budget,
    seed: u64,
    start: Option<&[f64]>,
) -> Result<Minimum, IdentifyError> {
    let d = problem.dim();
    if budget.particles < 2 || budget.starts == 0 {
        return Err(IdentifyError::Optimizer {
            message: "need at least 2 particles and 1 start".into(),
        });
    }
    let before = problem.evaluations();
    if d == 0 {
        let cost = problem.cost_at(&[]);
        return Ok(Minimum {
            point: Vec::new(),
            cost,
            evaluations: problem.evaluations() - before,
        });
    }
    let mut candidates: Vec<Vec<f64>> = start.map(|s| vec![s.to_vec()]).unwrap_or_default();
    for k in 0..budget.starts {
        let rng = rand::rngs::StdRng::seed_from_u64(
            seed ^ (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15),
        );
        let swarm = ParticleSwarm::new((vec![0.0; d], vec![1.0; d]), budget.particles)
            .with_rng_generator(rng);
        let res = Executor::new(Cube(problem), swarm)
            .configure(|s| s.max_iters(budget.iterations))
            .run()
            .map_err(optimizer_error)?;
        if let Some(best) = res.state().get_best_param() {
            candidates.push(best.position.clone());
        }
    }
    let mut best: Option<(Vec<f64>, f64)> = None;
    for c in candidates {
        // Simplices collapse prematurely in narrow valleys; a restart is cheap.
        let (s, _) = polish(problem, c, budget.polish_iterations / 2)?;
        let (s, cost) = polish(problem, s, budget.polish_iterations / 2)?;
        if best.as_ref().is_none_or(|(_, bc)| cost < *bc) {
            best = Some((s, cost));
        }
    }
    let (point, cost) = best.expect("at least one candidate");
    Ok(Minimum {
        point: point.iter().map(|x| x.clamp(0.0, 1.0)).collect(),
        cost,
        evaluations: problem.evaluations() - before,
    })
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
        params: objective.space().decode(&m.point),
        point: m.point,
        costs,
        cost: m.cost,
        predictions,
        evaluations: m.evaluations,
        wall_s: clock.elapsed().as_secs_f64(),
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

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

/// Fits the objective: `budget.starts` particle swarms seeded from `seed`, each best point (and
/// `start`, if given) polished by Nelder-Mead; the best result wins. Deterministic for a seed,
/// whatever the number of threads.
///
/// # Errors
/// [`IdentifyError::Optimizer`] for a degenerate budget or an optimizer failure;
/// [`IdentifyError::Model`] if the optimum cannot be evaluated.
pub fn fit<I: Input + Sync>(
    objective: &Objective<'_, I>,
    budget: &Budget,
    seed: u64,
    start: Option<&[f64]>,
) -> Result<FitResult, IdentifyError> {
    let clock = Instant::now();
    let d = objective.space().dim();
    if budget.particles < 2 || budget.starts == 0 {
        return Err(IdentifyError::Optimizer {
            message: "need at least 2 particles and 1 start".into(),
        });
    }
    let before = objective.evaluations();
    let mut best: Option<(Vec<f64>, f64)> = None;
    let mut keep = |s: Vec<f64>, c: f64| {
        if best.as_ref().is_none_or(|(_, bc)| c < *bc) {
            best = Some((s, c));
        }
    };
    let mut candidates: Vec<Vec<f64>> = start.map(|s| vec![s.to_vec()]).unwrap_or_default();
    if d > 0 {
        for k in 0..budget.starts {
            let rng = rand::rngs::StdRng::seed_from_u64(
                seed ^ (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15),
            );
            let swarm = ParticleSwarm::new((vec![0.0; d], vec![1.0; d]), budget.particles)
                .with_rng_generator(rng);
            let res = Executor::new(objective, swarm)
                .configure(|s| s.max_iters(budget.iterations))
                .run()
                .map_err(optimizer_error)?;
            let state = res.state();
            if let Some(best) = state.get_best_param() {
                candidates.push(best.position.clone());
            }
        }
        for c in candidates {
            // Nelder-Mead, then once more from its result with a fresh simplex: simplices
            // collapse prematurely in narrow valleys, and a restart is cheap.
            let (s, _) = polish(objective, c, budget.polish_iterations / 2)?;
            let (s, cost) = polish(objective, s, budget.polish_iterations / 2)?;
            keep(s, cost);
        }
    } else {
        keep(Vec::new(), objective.scalar(&[]));
    }
    let (point, cost) = best.expect("at least one candidate");
    let point: Vec<f64> = point.iter().map(|x| x.clamp(0.0, 1.0)).collect();
    let (predictions, costs) = objective.evaluate(&point)?;
    Ok(FitResult {
        params: objective.space().decode(&point),
        point,
        costs,
        cost,
        predictions,
        evaluations: objective.evaluations() - before,
        wall_s: clock.elapsed().as_secs_f64(),
    })
}

/// Nelder-Mead from `x0` with an initial simplex of edge 0.05 (pointing into the cube).
fn polish<I: Input + Sync>(
    objective: &Objective<'_, I>,
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
    let res = Executor::new(objective, nm)
        .configure(|s| s.max_iters(iterations))
        .run()
        .map_err(optimizer_error)?;
    let state = res.state();
    let s = state.get_best_param().cloned().unwrap_or(x0);
    Ok((s, state.get_best_cost()))
}

//! Coverage studies: does the 95 % band of [`crate::Uncertainty`] contain the true `e(v0)` as
//! often as it claims? Each replicate is an independent task, a pure function of its
//! [`CoverageTask`] and its seed: synthetic CoR data from known parameters plus Gaussian noise,
//! a fit from the bounds, the band at the data speeds, and how many of its points contain the
//! truth. Replicates run in parallel with rayon and give identical results on any thread count
//! or machine, so a study can be spread over a cluster one replicate per task. The same holds for
//! the posterior's credible band ([`PosteriorTask`], [`posterior_replicate`]).

use crate::data::{Dataset, Point};
use crate::error::IdentifyError;
use crate::fit::{fit, Budget};
use crate::objective::{Objective, Weights};
use crate::posterior::{band as posterior_band, NoiseScale, PosteriorProblem, PosteriorSpec};
use crate::smc::{sample, SmcSettings};
use crate::space::Space;
use crate::uncertainty::uncertainty;
use bw_models::input::Zero;
use bw_models::{BaseParams, Settings};
use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, Normal};
use rayon::prelude::*;
use std::path::Path;

/// One coverage study: the truth, where it is measured, how noisily, and how it is fitted.
#[derive(Debug, Clone)]
pub struct CoverageTask {
    /// The search space of the fits (its model is the truth's model).
    pub space: Space,
    /// The true base parameters (`u = 0`).
    pub truth: BaseParams,
    /// Impact speeds of the synthetic data (m/s); repeats allowed.
    pub speeds: Vec<f64>,
    /// Standard deviation of the Gaussian noise added to `e`.
    pub noise: f64,
    /// The fits' budget.
    pub budget: Budget,
    /// Solver settings of the fits' search.
    pub settings: Settings,
}

/// The outcome of one replicate.
#[derive(Debug, Clone, PartialEq)]
pub struct Replicate {
    /// Its seed.
    pub seed: u64,
    /// Data points whose band contains the true `e` (0 when there are no intervals).
    pub covered: usize,
    /// Data points.
    pub points: usize,
    /// Mean half-width of the band over the data points (NaN without intervals).
    pub halfwidth: f64,
    /// `J1` of the fit.
    pub j1: f64,
    /// The free quantities the fit left on a bound of the search (held there by the band).
    pub at_bound: Vec<&'static str>,
    /// Model evaluations of the fit or the posterior.
    pub evaluations: u64,
    /// Why there are no intervals, if there are none.
    pub error: Option<String>,
}

/// Runs replicate `seed` of `task`.
///
/// # Errors
/// [`IdentifyError::Model`] if the truth cannot be simulated; fit failures as [`fit`].
pub fn replicate(task: &CoverageTask, seed: u64) -> Result<Replicate, IdentifyError> {
    let map = task.space.map(&task.truth)?;
    let settings = Settings::default();
    let truth: Vec<f64> = task
        .speeds
        .iter()
        .map(|&v0| map.impact(Zero, v0, &settings).map(|o| o.e))
        .collect::<Result<_, _>>()?;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, task.noise).map_err(|e| IdentifyError::Objectives {
        reason: format!("noise {}: {e}", task.noise),
    })?;
    let data = Dataset {
        path: Path::new(&format!("synthetic-{seed}.csv")).to_owned(),
        points: task
            .speeds
            .iter()
            .zip(&truth)
            .map(|(&v0, &e)| Point {
                v0,
                e: Some(e + normal.sample(&mut rng)),
                t_d: None,
                spread: None,
                noise: None,
                line: 0,
            })
            .collect(),
        warnings: Vec::new(),
        reconstructed: false,
        noise_column: None,
    };
    let weights = Weights { j1: 1.0, j2: 0.0 };
    let search = Objective::new(&task.space, &data, &Zero, task.settings, weights)?;
    let result = fit(&search, &task.budget, seed, None)?;
    let exact = Objective::new(&task.space, &data, &Zero, settings, weights)?;
    let j1 = result.costs.j1.unwrap_or(f64::NAN);
    let points = task.speeds.len();
    let names = task.space.free_names();
    let on_bound: Vec<&'static str> = result.at_bound.iter().map(|&j| names[j]).collect();
    let band = uncertainty(&exact, &result.point, &result.at_bound)
        .and_then(|u| u.band(&exact, &task.speeds));
    Ok(match band {
        Ok(band) => Replicate {
            seed,
            covered: band
                .iter()
                .zip(&truth)
                .filter(|(b, t)| b.e[1] <= **t && **t <= b.e[2])
                .count(),
            points,
            halfwidth: band.iter().map(|b| (b.e[2] - b.e[1]) / 2.0).sum::<f64>() / points as f64,
            j1,
            at_bound: on_bound.clone(),
            evaluations: result.evaluations,
            error: None,
        },
        Err(e) => Replicate {
            seed,
            covered: 0,
            points,
            halfwidth: f64::NAN,
            j1,
            at_bound: on_bound,
            evaluations: result.evaluations,
            error: Some(e.to_string()),
        },
    })
}

/// A coverage study of the posterior's 95 % credible band: the truth, the design, the noise,
/// and how the posterior is sampled.
#[derive(Debug, Clone)]
pub struct PosteriorTask {
    /// The search space (its bounds are the prior; its model is the truth's model).
    pub space: Space,
    /// The true base parameters (`u = 0`).
    pub truth: BaseParams,
    /// Impact speeds of the synthetic data (m/s); repeats allowed.
    pub speeds: Vec<f64>,
    /// Standard deviation of the Gaussian noise added to `e`.
    pub noise: f64,
    /// Whether the posterior is told the noise (an `e_std` column) or samples it.
    pub given_noise: bool,
    /// Whether each replicate draws its truth from the prior instead of using `truth`: a point
    /// uniform in the bounds and, with sampled noise, a noise scale log-uniform in
    /// `[noise / 2, 2 noise]`, the sampled scale's prior (redrawn with the data until every
    /// speed separates and no datum is negative). Pooled over
    /// such replicates an exact posterior's 95 % band covers the truth at 95 % of the points,
    /// whatever the model, so this checks the sampler; a fixed truth checks the prior as well.
    pub from_prior: bool,
    /// The sampler.
    pub smc: SmcSettings,
    /// The budget of the fit whose optimum centres the sampler's reference.
    pub budget: Budget,
    /// Posterior draws behind the band.
    pub draws: usize,
    /// Solver settings of the likelihood.
    pub settings: Settings,
}

/// Runs replicate `seed` of a posterior coverage study: synthetic data, the posterior, its band
/// at the data's distinct speeds, and how many of them contain the true `e`.
///
/// # Errors
/// [`IdentifyError::Model`] if the truth cannot be simulated; sampler failures as
/// [`crate::sample`].
pub fn posterior_replicate(task: &PosteriorTask, seed: u64) -> Result<Replicate, IdentifyError> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let (truth, noise, csv) = if task.from_prior {
        prior_draw(task, seed)?
    } else {
        let e = synthetic(task, &task.truth, task.noise, &mut rng)?;
        (task.truth, task.noise, csv_of(task, &e, task.noise))
    };
    let map = task.space.map(&truth)?;
    let truth_at = |v0: f64| map.impact(Zero, v0, &Settings::default()).map(|o| o.e);
    let data = Dataset::parse(Path::new(&format!("synthetic-{seed}.csv")), &csv)?;
    let mut spec = PosteriorSpec::new(&data, Weights { j1: 1.0, j2: 0.0 });
    if !task.given_noise {
        spec.e_noise = if task.from_prior {
            NoiseScale::Sampled {
                lo: task.noise / 2.0,
                hi: task.noise * 2.0,
            }
        } else {
            NoiseScale::Sampled { lo: 1e-4, hi: 0.5 }
        };
    }
    let problem = PosteriorProblem::new(&task.space, &data, &Zero, task.settings, &spec)?;
    let objective = Objective::new(&task.space, &data, &Zero, task.settings, spec.weights)?;
    let optimum = fit(&objective, &task.budget, seed, None)?;
    let reference = problem.reference_at(&optimum.point, &optimum.costs);
    let post = sample(&problem, &task.smc, &reference, seed)?;
    let speeds = crate::objective::distinct_speeds(&data);
    let band = posterior_band(&problem, &post, &speeds, (task.draws, seed), noise)?;
    let mut covered = 0;
    for b in &band {
        let t = truth_at(b.v0)?;
        covered += usize::from(b.e[1] <= t && t <= b.e[2]);
    }
    let points = band.len();
    Ok(Replicate {
        seed,
        covered,
        points,
        halfwidth: band.iter().map(|b| (b.e[2] - b.e[1]) / 2.0).sum::<f64>() / points as f64,
        j1: f64::NAN,
        at_bound: Vec::new(),
        evaluations: post.evaluations,
        error: None,
    })
}

/// Synthetic CoRs of `task` at its speeds from `truth`, with Gaussian noise of standard
/// deviation `noise`.
///
/// # Errors
/// [`IdentifyError::Model`] if the truth cannot be simulated at a speed.
fn synthetic(
    task: &PosteriorTask,
    truth: &BaseParams,
    noise: f64,
    rng: &mut rand::rngs::StdRng,
) -> Result<Vec<f64>, IdentifyError> {
    let map = task.space.map(truth)?;
    let normal = Normal::new(0.0, noise).map_err(|e| IdentifyError::Objectives {
        reason: format!("noise {noise}: {e}"),
    })?;
    task.speeds
        .iter()
        .map(|&v0| Ok(map.impact(Zero, v0, &Settings::default())?.e + normal.sample(rng)))
        .collect()
}

/// The data of `task` as a CSV with an `e_std` column: CoRs `e` of standard deviation `noise`.
fn csv_of(task: &PosteriorTask, e: &[f64], noise: f64) -> String {
    let mut csv = String::from("v_0,e,e_std\n");
    for (v0, e) in task.speeds.iter().zip(e) {
        csv += &format!("{v0},{e},{noise}\n");
    }
    csv
}

/// The truth, noise and data of replicate `seed` drawn from the prior (see
/// [`PosteriorTask::from_prior`]), from a stream of its own. Draws whose truth does not
/// separate at every speed, or whose data hold a negative CoR, are drawn again: a condition on
/// the data alone leaves the posterior of the data that pass it unchanged.
///
/// # Errors
/// [`IdentifyError::Posterior`] if 1000 draws hold none that passes.
fn prior_draw(task: &PosteriorTask, seed: u64) -> Result<(BaseParams, f64, String), IdentifyError> {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ 0x7275_7468_5052_494F);
    let settings = Settings::default();
    for _ in 0..1000 {
        let s: Vec<f64> = (0..task.space.dim()).map(|_| rng.random()).collect();
        let noise = if task.given_noise {
            task.noise
        } else {
            task.noise * 4f64.powf(rng.random::<f64>() - 0.5)
        };
        let truth = task.space.decode(&s);
        let Ok(map) = task.space.map(&truth) else {
            continue;
        };
        let separates = task.speeds.iter().all(|&v0| {
            map.impact(Zero, v0, &settings)
                .is_ok_and(|o| o.t_s.is_some() && o.e.is_finite())
        });
        if !separates {
            continue;
        }
        let e = synthetic(task, &truth, noise, &mut rng)?;
        if e.iter().all(|e| *e >= 0.0) {
            return Ok((truth, noise, csv_of(task, &e, noise)));
        }
    }
    Err(IdentifyError::Posterior {
        reason: format!(
            "seed {seed}: 1000 draws from the prior hold no truth that separates at every \
             speed with data of no negative CoR"
        ),
    })
}

/// Runs replicates `seeds` of `task` in parallel (results in seed order).
///
/// # Errors
/// The first replicate's error, in seed order.
pub fn study(
    task: &CoverageTask,
    seeds: std::ops::Range<u64>,
) -> Result<Vec<Replicate>, IdentifyError> {
    seeds.into_par_iter().map(|s| replicate(task, s)).collect()
}

/// The fraction of all data points, over `replicates`, whose band contains the truth.
pub fn coverage(replicates: &[Replicate]) -> f64 {
    let covered: usize = replicates.iter().map(|r| r.covered).sum();
    let points: usize = replicates.iter().map(|r| r.points).sum();
    covered as f64 / points.max(1) as f64
}

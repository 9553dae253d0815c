//! Runs and evaluates the fits of an identification config ([`run_fit`], [`eval_fit`],
//! [`run_loop_fit`], [`eval_loop_fit`]); [`render`] turns their reports into JSON, CSV and SVG.

mod compare;
mod coverage;
mod drops;
mod posterior;
mod reference;
mod render;
mod report;
mod search;
mod text;

pub use compare::{compare_all, compare_summary, groups, verdict, Comparison};
pub use coverage::{coverage_study, coverage_summary, coverage_task, run_coverage, CoverageReport};
pub use posterior::{
    posterior_all, posterior_from_runs, posterior_run, posterior_summary, render_posterior,
    run_json, run_of_json, run_posterior, samples_json, unit_of, PosteriorReport, BAND_COLUMNS,
    SAMPLE_COLUMNS,
};
pub use reference::{ReferenceReport, Standing};
pub use render::{loop_summary, render, render_loops, slug, summary, units};
use report::{fail, missing_params, reporting, search_warnings};
pub use report::{DropOutcome, FitReport, LoopReport, ParetoPoint};
pub use text::{fit_text, loop_fit_text, posterior_text};

use crate::fit::checkpoint::Checkpoint;
use crate::fit::config::FitConfig;
use crate::signal::Signal;
use crate::AppError;
use bwc_identify::{
    analyse, fit, predict, uncertainty, BandPoint, Budget, Costs, Dataset, Objective, Weights,
};
use std::path::Path;
use std::time::Instant;

/// Speeds of a report's model curve: 60 on a log grid from half the slowest to twice the
/// fastest measured speed (the data's range and beyond, to show what the data do not cover).
pub fn curve_speeds(data: &Dataset) -> Vec<f64> {
    let (lo, hi) = data.points.iter().fold((f64::INFINITY, 0.0f64), |a, p| {
        (a.0.min(p.v0), a.1.max(p.v0))
    });
    let (lo, hi) = (lo / 2.0, hi * 2.0);
    (0..60)
        .map(|i| lo * (hi / lo).powf(i as f64 / 59.0))
        .collect()
}

/// The model `map` at `speeds` without a band (limits equal to the value).
fn plain_curve(
    f: &FitConfig,
    map: &bwc_identify::FitModel,
    speeds: &[f64],
) -> Result<Vec<BandPoint>, bw_models::ModelError> {
    let grid = Dataset::at_speeds(&f.data.path, speeds);
    Ok(predict(map, &f.input, &grid, &reporting())?
        .iter()
        .map(|p| BandPoint {
            v0: p.v0,
            e: [p.e; 3],
            t_d: [if p.separated { p.t_d } else { f64::NAN }; 3],
        })
        .collect())
}

/// Fits `f` from its bounds (seeded by `seed` combined with the fit's own seed); with a
/// `checkpoint`, the search it holds for this fit and seed is taken and a new one recorded
/// (drop-test fits and Pareto fronts are computed again).
///
/// # Errors
/// [`AppError::Identify`] if the optimizer or a final evaluation fails; [`AppError::Io`] if the
/// checkpoint cannot be written.
pub fn run_fit(
    config: &Path,
    f: &FitConfig,
    seed: u64,
    progress: &(dyn Fn() + Sync),
    checkpoint: Option<&Checkpoint>,
) -> Result<FitReport, AppError> {
    if let Some(d) = &f.drops {
        return drops::run_drop_fit(config, f, d, seed, progress);
    }
    let clock = Instant::now();
    let err = fail(config, &f.name);
    let objective = Objective::new(&f.space, &f.data, &f.input, f.settings, f.weights)
        .map_err(&err)?
        .with_progress(progress);
    let result = search::search(config, f, &objective, seed, checkpoint)?;
    // Report the costs at the reporting (accurate) settings.
    let exact =
        Objective::new(&f.space, &f.data, &f.input, reporting(), f.weights).map_err(&err)?;
    let (predictions, costs) = exact.evaluate(&result.point).map_err(&err)?;
    let identifiability = Some(analyse(&exact, &result.point).map_err(&err)?);
    let mut warnings = [&f.data.warnings[..], &f.hints].concat();
    warnings.extend(search_warnings(
        f,
        &result.convergence,
        &result.at_bound,
        &result.point,
    ));
    let speeds = curve_speeds(&f.data);
    let (unc, curve, band) = intervals(config, f, &exact, &result, &speeds, &mut warnings)?;
    let (pareto, pareto_evaluations) = match f.pareto {
        Some(count) => pareto_front(config, f, count, seed, progress, &exact, &result.point)?,
        None => (Vec::new(), 0),
    };
    let evaluations = result.evaluations + pareto_evaluations;
    let beside = (&result.point[..], identifiability.as_ref());
    let reference = match &f.reference {
        Some(rf) => reference_report(config, f, rf, &costs, beside, &speeds)?,
        None => None,
    };
    if let Some(r) = reference
        .as_ref()
        .filter(|r| r.standing == Standing::ReferenceLower)
    {
        warnings.push(format!(
            "\"{}\": the reference ({}) costs {:.3} times the fit's: {}",
            f.name,
            r.label,
            r.cost_ratio,
            r.remedy()
        ));
    }
    Ok(FitReport {
        name: f.name.clone(),
        model: f.model_name(),
        family: f.space.family_params(&result.params),
        params: result.params,
        uses_input_scales: f.uses_input_scales,
        costs,
        evaluations,
        wall_s: clock.elapsed().as_secs_f64(),
        predictions,
        identifiability,
        convergence: Some(result.convergence),
        at_bound: f.space.names_at(&result.at_bound),
        pareto,
        uncertainty: Some(unc),
        curve,
        band,
        warnings,
        drop: None,
        reference,
    })
}

/// The intervals (or why there are none), the curve and the band at the data.
type Intervals = (
    Result<bwc_identify::Uncertainty, String>,
    Vec<BandPoint>,
    Vec<BandPoint>,
);

/// The intervals at the optimum of a search, with the model's band on the curve's `speeds`
/// and at the data's; or, where there are none (a warning says why), the plain curve.
fn intervals<I: bw_models::input::Input + Sync>(
    config: &Path,
    f: &FitConfig,
    exact: &Objective<'_, I>,
    result: &search::Searched,
    speeds: &[f64],
    warnings: &mut Vec<String>,
) -> Result<Intervals, AppError> {
    let err = fail(config, &f.name);
    let data_speeds: Vec<f64> = f.data.points.iter().map(|p| p.v0).collect();
    Ok(match uncertainty(exact, &result.point, &result.at_bound) {
        Ok(u) => {
            let curve = u.band(exact, speeds).map_err(&err)?;
            let band = u.band(exact, &data_speeds).map_err(&err)?;
            (Ok(u), curve, band)
        }
        Err(e) => {
            warnings.push(format!("\"{}\": no intervals: {e}", f.name));
            let map = f.space.map(&result.params).map_err(&err)?;
            let curve = plain_curve(f, &map, speeds).map_err(|e| err(e.into()))?;
            (Err(e.to_string()), curve, Vec::new())
        }
    })
}

/// The reference vector `rf` of fit `f` on the fit's data, beside the fit at the unit-cube
/// point `s` with `costs`; its curve at `speeds`. `None` where a weighted cost has no value
/// (the reference does not separate at a speed with a duration).
///
/// # Errors
/// [`AppError::Identify`] where the reference is not admissible or a simulation fails.
fn reference_report(
    config: &Path,
    f: &FitConfig,
    rf: &crate::fit::config::Reference,
    costs: &Costs,
    (s, identifiability): (&[f64], Option<&bwc_identify::Identifiability>),
    speeds: &[f64],
) -> Result<Option<ReferenceReport>, AppError> {
    let err = fail(config, &f.name);
    let map = f.space.map(&rf.params).map_err(&err)?;
    let predictions = predict(&map, &f.input, &f.data, &reporting()).map_err(|e| err(e.into()))?;
    let ref_costs = Costs::of(&f.data, &predictions);
    let curve = plain_curve(f, &map, speeds).map_err(|e| err(e.into()))?;
    let Some(pair) = reference::CostPair::of(f.weights, &ref_costs, costs) else {
        return Ok(None);
    };
    Ok(Some(reference::compare(
        f,
        rf,
        ref_costs,
        &pair,
        (s, identifiability),
        curve,
    )))
}

/// The Pareto front of `f`'s two costs: `count` fits with weights from all CoR to all duration,
/// each from the main optimum `from` with a small swarm and the full polish, their costs at the
/// accurate settings (`exact`); and the evaluations they took.
fn pareto_front(
    config: &Path,
    f: &FitConfig,
    count: usize,
    seed: u64,
    progress: &(dyn Fn() + Sync),
    exact: &Objective<'_, Signal>,
    from: &[f64],
) -> Result<(Vec<ParetoPoint>, u64), AppError> {
    let err = fail(config, &f.name);
    // Normalise each cost by the variance of its data so the weights are comparable.
    let var = |xs: Vec<f64>| {
        let m = xs.iter().sum::<f64>() / xs.len() as f64;
        (xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / xs.len() as f64).max(1e-30)
    };
    let ve = var(f.data.points.iter().filter_map(|p| p.e).collect());
    let vt = var(f.data.points.iter().filter_map(|p| p.t_d).collect());
    let budget = Budget {
        particles: (f.budget.particles / 4).max(8),
        iterations: f.budget.iterations / 4,
        ..f.budget.single()
    };
    let (mut front, mut evaluations) = (Vec::with_capacity(count), 0);
    for k in 0..count {
        let w = k as f64 / (count - 1) as f64;
        let weights = Weights {
            j1: w / ve,
            j2: (1.0 - w) / vt,
        };
        let o = Objective::new(&f.space, &f.data, &f.input, f.settings, weights)
            .map_err(&err)?
            .with_progress(progress);
        let r = fit(&o, &budget, seed ^ f.seed ^ (k as u64 + 1), Some(from)).map_err(&err)?;
        evaluations += r.evaluations;
        let (_, c) = exact.evaluate(&r.point).map_err(&err)?;
        front.push(ParetoPoint {
            w,
            j1: c.j1.unwrap_or(f64::NAN),
            j2: c.j2.unwrap_or(f64::NAN),
            family: f.space.family_params(&r.params),
            params: r.params,
        });
    }
    Ok((front, evaluations))
}

/// Evaluates the costs of `f` at its `[fit.params]`.
///
/// # Errors
/// [`AppError::Invalid`] when the fit has no `[fit.params]`; [`AppError::Identify`] when a
/// simulation fails.
pub fn eval_fit(config: &Path, f: &FitConfig) -> Result<FitReport, AppError> {
    if let Some(d) = &f.drops {
        return drops::eval_drop_fit(config, f, d);
    }
    let clock = Instant::now();
    let err = fail(config, &f.name);
    let params = f
        .params
        .ok_or_else(|| missing_params(config, "[fit.params]", &f.name))?;
    let map = f.space.map(&params).map_err(&err)?;
    let predictions = predict(&map, &f.input, &f.data, &reporting()).map_err(|e| err(e.into()))?;
    let costs = Costs::of(&f.data, &predictions);
    let curve = plain_curve(f, &map, &curve_speeds(&f.data)).map_err(|e| err(e.into()))?;
    Ok(FitReport {
        name: f.name.clone(),
        model: f.model_name(),
        family: f.space.family_params(&params),
        params,
        uses_input_scales: f.uses_input_scales,
        costs,
        evaluations: 1,
        wall_s: clock.elapsed().as_secs_f64(),
        predictions,
        identifiability: None,
        convergence: None,
        at_bound: Vec::new(),
        pareto: Vec::new(),
        uncertainty: None,
        curve,
        band: Vec::new(),
        warnings: [&f.data.warnings[..], &f.hints].concat(),
        drop: None,
        reference: None,
    })
}

/// Fits the contact law of a loop fit from its bounds.
///
/// # Errors
/// [`AppError::Identify`] if the optimizer or the final evaluation fails.
pub fn run_loop_fit(
    config: &Path,
    f: &crate::fit::config::LoopFitConfig,
    seed: u64,
    progress: &(dyn Fn() + Sync),
) -> Result<LoopReport, AppError> {
    let clock = Instant::now();
    let err = fail(config, &f.name);
    let objective =
        bwc_identify::LoopObjective::new(&f.space, &f.loops, f.m, reporting()).map_err(&err)?;
    let counted = Counted {
        inner: &objective,
        progress,
    };
    let min = bwc_identify::minimize(&counted, &f.budget, seed ^ f.seed, None).map_err(&err)?;
    let (cost, curves) = objective.evaluate(&min.point).map_err(&err)?;
    Ok(LoopReport {
        name: f.name.clone(),
        model: f.kind.name(),
        law: f.space.decode(&min.point),
        cost,
        evaluations: min.evaluations,
        wall_s: clock.elapsed().as_secs_f64(),
        curves,
        at_bound: f.space.names_at(&bwc_identify::at_bound(&min.point)),
        convergence: Some(min.convergence),
    })
}

/// Evaluates the loop cost at a loop fit's `[loop_fit.params]`.
///
/// # Errors
/// [`AppError::Invalid`] without `[loop_fit.params]`; [`AppError::Identify`] when a simulation fails.
pub fn eval_loop_fit(
    config: &Path,
    f: &crate::fit::config::LoopFitConfig,
) -> Result<LoopReport, AppError> {
    let clock = Instant::now();
    let law = f
        .params
        .ok_or_else(|| missing_params(config, "[loop_fit.params]", &f.name))?;
    let err = fail(config, &f.name);
    let objective =
        bwc_identify::LoopObjective::new(&f.space, &f.loops, f.m, reporting()).map_err(&err)?;
    let curves = objective.simulate(&law).map_err(&err)?;
    let cost = f
        .loops
        .iter()
        .zip(&curves)
        .map(|(l, c)| bwc_identify::loop_cost(l, c))
        .sum::<f64>()
        / f.loops.len() as f64;
    Ok(LoopReport {
        name: f.name.clone(),
        model: f.kind.name(),
        law,
        cost,
        evaluations: 1,
        wall_s: clock.elapsed().as_secs_f64(),
        curves,
        convergence: None,
        at_bound: Vec::new(),
    })
}

/// Counts progress for a cube problem.
struct Counted<'a, P> {
    inner: &'a P,
    progress: &'a (dyn Fn() + Sync),
}

impl<P: bwc_identify::CubeProblem> bwc_identify::CubeProblem for Counted<'_, P> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn cost_at(&self, s: &[f64]) -> f64 {
        (self.progress)();
        self.inner.cost_at(s)
    }
    fn evaluations(&self) -> u64 {
        self.inner.evaluations()
    }
}

/// Evaluations the searches of `config` plan (for a progress bar; the converging search may
/// stop earlier or take more starts).
pub fn planned_evaluations(config: &crate::fit::config::Config) -> u64 {
    let fits: u64 = config
        .fits
        .iter()
        .map(|f| f.budget.evaluations(f.space.dim()) * (1 + f.pareto.unwrap_or(0) as u64))
        .sum();
    let loops: u64 = config
        .loop_fits
        .iter()
        .map(|f| f.budget.evaluations(f.space.free_names().len()))
        .sum();
    fits + loops
}

/// Every fit of `config` (`bwc-identify run` with `seed`; `eval` at the `[fit.params]` without),
/// side by side on the current rayon pool, `tick` called per cost evaluation. Each fit is
/// deterministic, so the results do not depend on the thread count.
///
/// # Errors
/// The first failure in config order.
pub fn fit_all(
    path: &Path,
    config: &crate::fit::config::Config,
    seed: Option<u64>,
    tick: &(dyn Fn() + Sync),
    checkpoint: Option<&Checkpoint>,
) -> Result<(Vec<FitReport>, Vec<LoopReport>), AppError> {
    use rayon::prelude::*;
    let Some(seed) = seed else {
        let fits = config
            .fits
            .iter()
            .map(|f| eval_fit(path, f))
            .collect::<Result<_, _>>()?;
        let loops = config
            .loop_fits
            .iter()
            .map(|f| eval_loop_fit(path, f))
            .collect::<Result<_, _>>()?;
        return Ok((fits, loops));
    };
    let reports: Vec<_> = config
        .fits
        .par_iter()
        .map(|f| run_fit(path, f, seed, tick, checkpoint))
        .collect();
    let loops: Vec<_> = config
        .loop_fits
        .par_iter()
        .map(|f| run_loop_fit(path, f, seed, tick))
        .collect();
    Ok((
        reports.into_iter().collect::<Result<_, _>>()?,
        loops.into_iter().collect::<Result<_, _>>()?,
    ))
}

/// The object `bwc-identify run --json` prints (and `summary.json` holds, without `"files"`):
/// the fits (base-parameter fits first, then loop fits), the units, the config as parsed and
/// the provenance.
pub fn summary_of(
    config: &crate::fit::config::Config,
    reports: &[FitReport],
    loops: &[LoopReport],
) -> serde_json::Value {
    let mut v = crate::outdir::provenance("bwc-identify");
    let mut fits = summary(reports);
    if let Some(list) = fits["fits"].as_array_mut() {
        list.extend(loop_summary(loops));
    }
    v["fits"] = fits["fits"].take();
    v["units"] = units();
    v["config"] = config.describe();
    v
}

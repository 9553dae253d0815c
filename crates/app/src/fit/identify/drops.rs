//! Fits and evaluations of drop-test data ([`crate::fit::config::DropFit`]): the bounce sequence
//! simulated at each release height, the cost `J_drop` (s² for intervals, m² for heights).

use super::report::{fail, missing_params, reporting, search_warnings, DropOutcome, FitReport};
use crate::fit::config::{DropFit, FitConfig};
use crate::AppError;
use bwc_identify::{at_bound, minimize, Costs, DropObjective};
use std::path::Path;
use std::time::Instant;

/// Why a drop-test fit reports no intervals, identifiability or prediction band.
const NO_INTERVALS: &str = "the sensitivity analysis behind intervals, identifiability and the \
     prediction band is made for CoR and duration data; a drop-test fit reports its cost, its \
     search's agreement and the parameters on bounds. To see what the drops determine, fit the \
     CoRs they imply (e = sqrt(h1 / h0), or from successive intervals) as CoR data";

/// The outcome at a point of the unit cube, at the default solver settings.
fn outcome(f: &FitConfig, d: &DropFit, s: &[f64], config: &Path) -> Result<DropOutcome, AppError> {
    let err = fail(config, &f.name);
    let exact = DropObjective::new(&f.space, &d.data, d.setup, reporting()).map_err(&err)?;
    let predicted = exact.predict(s).map_err(&err)?;
    Ok(DropOutcome {
        kind: d.data.kind,
        cost: exact.cost_of(&predicted),
        rows: d.data.rows.iter().copied().zip(predicted).collect(),
    })
}

/// A report without the CoR and duration parts of other fits.
fn report(f: &FitConfig, params: bw_models::BaseParams, drop: DropOutcome) -> FitReport {
    FitReport {
        name: f.name.clone(),
        model: f.model_name(),
        family: f.space.family_params(&params),
        params,
        uses_input_scales: f.uses_input_scales,
        costs: Costs { j1: None, j2: None },
        evaluations: 1,
        wall_s: 0.0,
        predictions: Vec::new(),
        identifiability: None,
        convergence: None,
        at_bound: Vec::new(),
        pareto: Vec::new(),
        uncertainty: None,
        curve: Vec::new(),
        band: Vec::new(),
        warnings: Vec::new(),
        drop: Some(drop),
        reference: None,
    }
}

/// Fits a drop-test `[[fit]]` from its bounds (the converging search of every fit).
///
/// # Errors
/// [`AppError::Identify`] naming the fit when the search or the final evaluation fails.
pub fn run_drop_fit(
    config: &Path,
    f: &FitConfig,
    d: &DropFit,
    seed: u64,
    progress: &(dyn Fn() + Sync),
) -> Result<FitReport, AppError> {
    let clock = Instant::now();
    let err = fail(config, &f.name);
    let objective = DropObjective::new(&f.space, &d.data, d.setup, f.settings)
        .map_err(&err)?
        .with_progress(progress);
    let m = minimize(&objective, &f.budget, seed ^ f.seed, f.start.as_deref()).map_err(&err)?;
    let bound = at_bound(&m.point);
    let mut r = report(
        f,
        f.space.decode(&m.point),
        outcome(f, d, &m.point, config)?,
    );
    r.warnings = f.hints.clone();
    r.warnings
        .extend(search_warnings(f, &m.convergence, &bound, &m.point));
    r.warnings
        .push(format!("\"{}\": no intervals: {NO_INTERVALS}", f.name));
    r.uncertainty = Some(Err(NO_INTERVALS.into()));
    r.evaluations = m.evaluations;
    r.convergence = Some(m.convergence);
    r.at_bound = f.space.names_at(&bound);
    r.wall_s = clock.elapsed().as_secs_f64();
    Ok(r)
}

/// `J_drop` at a drop-test fit's `[fit.params]`.
///
/// # Errors
/// [`AppError::Invalid`] without `[fit.params]`; [`AppError::Identify`] when they are outside
/// the space or a simulation fails.
pub fn eval_drop_fit(config: &Path, f: &FitConfig, d: &DropFit) -> Result<FitReport, AppError> {
    let clock = Instant::now();
    let params = f
        .params
        .ok_or_else(|| missing_params(config, "[fit.params]", &f.name))?;
    let s = f.space.encode(&params).map_err(fail(config, &f.name))?;
    let mut r = report(f, params, outcome(f, d, &s, config)?);
    r.warnings = f.hints.clone();
    r.wall_s = clock.elapsed().as_secs_f64();
    Ok(r)
}

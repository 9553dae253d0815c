//! A fit's search from its bounds ([`bwc_identify::minimize`]), the part of `run` that costs
//! thousands of evaluations, kept in a checkpoint when one is given so that a run of many fits
//! resumes where it stopped: the rest of a fit's report (intervals, curves, the reference) is
//! computed again from the point found, which gives the same report.

use super::report::fail;
use crate::fit::checkpoint::{exact, fingerprint, float_of, Checkpoint};
use crate::fit::config::FitConfig;
use crate::AppError;
use bw_models::input::Input;
use bw_models::BaseParams;
use bwc_identify::{at_bound, minimize, Convergence, Objective};
use serde_json::{json, Value};
use std::path::Path;

/// Where a fit's search ended.
pub(super) struct Searched {
    /// The point on the unit cube.
    pub point: Vec<f64>,
    /// Its base parameters.
    pub params: BaseParams,
    /// Cost evaluations of the search.
    pub evaluations: u64,
    /// How the search ended.
    pub convergence: Convergence,
    /// The coordinates of `point` on a bound of the search.
    pub at_bound: Vec<usize>,
}

/// Searches fit `f` from its bounds with `seed` (combined with the fit's own), or takes the
/// search `checkpoint` holds for this fit and seed; a new search is recorded there.
///
/// # Errors
/// [`AppError::Identify`] if the optimizer fails; [`AppError::Io`] if the checkpoint cannot
/// be written.
pub(super) fn search<I: Input + Sync>(
    config: &Path,
    f: &FitConfig,
    objective: &Objective<'_, I>,
    seed: u64,
    checkpoint: Option<&Checkpoint>,
) -> Result<Searched, AppError> {
    let print = fingerprint(&[&"run", f, &seed]);
    let kept = checkpoint.and_then(|c| c.get(&f.name, &print));
    let minimum = match kept.and_then(minimum_of_json) {
        Some(m) => m,
        None => {
            let m = minimize(objective, &f.budget, seed ^ f.seed, f.start.as_deref())
                .map_err(fail(config, &f.name))?;
            if let Some(c) = checkpoint {
                c.record(&f.name, &print, minimum_json(&m))?;
            }
            m
        }
    };
    let space = objective.space();
    Ok(Searched {
        at_bound: at_bound(&minimum.point),
        params: space.decode(&minimum.point),
        point: minimum.point,
        evaluations: minimum.evaluations,
        convergence: minimum.convergence,
    })
}

/// A search's end as a checkpoint holds it, every number exact.
fn minimum_json(m: &bwc_identify::Minimum) -> Value {
    let c = &m.convergence;
    json!({
        "point": m.point, "cost": exact(m.cost), "evaluations": m.evaluations,
        "starts": c.starts, "agreeing": c.agreeing, "search_evaluations": c.evaluations,
        "costs": c.costs.iter().map(|&x| exact(x)).collect::<Vec<_>>(),
    })
}

/// The search's end of [`minimum_json`]; `None` for an entry that is not one (searched again).
fn minimum_of_json(v: &Value) -> Option<bwc_identify::Minimum> {
    let floats =
        |key: &str| -> Option<Vec<f64>> { v[key].as_array()?.iter().map(float_of).collect() };
    Some(bwc_identify::Minimum {
        point: floats("point")?,
        cost: float_of(&v["cost"])?,
        evaluations: v["evaluations"].as_u64()?,
        convergence: Convergence {
            starts: usize::try_from(v["starts"].as_u64()?).ok()?,
            agreeing: usize::try_from(v["agreeing"].as_u64()?).ok()?,
            evaluations: v["search_evaluations"].as_u64()?,
            costs: floats("costs")?,
        },
    })
}

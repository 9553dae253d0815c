//! `bwc-identify coverage`: a coverage study on a fit's own design (its speeds and bounds), so
//! that a user can check the 95 % band before trusting it on their data. Each replicate is an
//! independent task, a pure function of the config and its seed (`--first-seed` and
//! `--replicates` shard a study over machines).

use super::report::{fail, reporting};
use crate::fit::checkpoint::{exact, fingerprint, float_of, Checkpoint};
use crate::fit::config::FitConfig;
use crate::AppError;
use bw_models::input::Input;
use bw_models::BaseParams;
use bwc_identify::{coverage, fit, replicate, CoverageTask, Objective, Replicate};
use rayon::prelude::*;
use serde_json::{json, Value};
use std::path::Path;

/// One fit's study.
#[derive(Debug, Clone)]
pub struct CoverageReport {
    /// Fit name.
    pub name: String,
    /// The true parameters of the synthetic data (of a family's fit, the search's slots: see
    /// `family`).
    pub truth: BaseParams,
    /// A contact-law family's true law, under its own names.
    pub family: Option<bw_models::FamilyParams>,
    /// Where the truth came from: `"params"` (`[fit.params]`) or `"fit"` (the fit's optimum).
    pub truth_from: &'static str,
    /// Noise standard deviation of `e`.
    pub noise: f64,
    /// The replicates, in seed order.
    pub replicates: Vec<Replicate>,
}

/// Runs replicates `seeds` of a coverage study of `f`: synthetic CoR data at the fit's speeds
/// from `[fit.params]` (or, without it, from the fit's optimum on its data), Gaussian noise of
/// standard deviation `noise` (default: the truth's residual standard deviation on the data,
/// `sqrt(sum (e_model - e)^2 / (M - 1))`), each fitted from the bounds with the fit's budget.
/// With a `checkpoint`, the replicates it holds for this design are taken from it and each
/// new one is recorded as it finishes.
///
/// # Errors
/// [`AppError::Invalid`] for a fit with an input or a duration objective (studies cover CoR-only
/// fits without input); [`AppError::Identify`] when a fit or simulation fails;
/// [`AppError::Io`] when the checkpoint cannot be written.
pub fn run_coverage(
    config: &Path,
    f: &FitConfig,
    noise: Option<f64>,
    seeds: std::ops::Range<u64>,
    checkpoint: Option<&Checkpoint>,
) -> Result<CoverageReport, AppError> {
    let err = fail(config, &f.name);
    if !f.input.is_zero() || f.weights.j2 > 0.0 || f.space.known().is_some() {
        return Err(AppError::Invalid {
            path: config.to_owned(),
            line: 1,
            key: format!("[[fit]] \"{}\"", f.name),
            message: "coverage studies cover CoR-only fits without input, [fit.known] or a J2 \
                      weight"
                .into(),
        });
    }
    let (truth, truth_from) = match f.params {
        Some(p) => (p, "params"),
        None => {
            let search =
                Objective::new(&f.space, &f.data, &f.input, f.settings, f.weights).map_err(&err)?;
            (
                fit(&search, &f.budget, f.seed, None).map_err(&err)?.params,
                "fit",
            )
        }
    };
    let noise = match noise {
        Some(n) => n,
        None => {
            let map = f.space.map(&truth).map_err(&err)?;
            let p = bwc_identify::predict(&map, &f.input, &f.data, &reporting())
                .map_err(|e| err(e.into()))?;
            let r: Vec<f64> = f
                .data
                .points
                .iter()
                .zip(&p)
                .filter_map(|(d, q)| d.e.map(|e| q.e - e))
                .collect();
            (r.iter().map(|x| x * x).sum::<f64>() / (r.len().max(2) - 1) as f64).sqrt()
        }
    };
    let task = coverage_task(f, truth, noise);
    let print = fingerprint(&[&"coverage", &task]);
    let replicates = seeds
        .into_par_iter()
        .map(|seed| {
            let key = format!("{}/{seed}", f.name);
            let kept = checkpoint.and_then(|c| c.get(&key, &print));
            if let Some(r) = kept.and_then(|v| replicate_of_json(v, &task)) {
                return Ok(r);
            }
            let r = replicate(&task, seed).map_err(&err)?;
            if let Some(c) = checkpoint {
                c.record(&key, &print, replicate_json(&r))?;
            }
            Ok(r)
        })
        .collect::<Result<Vec<_>, AppError>>()?;
    Ok(CoverageReport {
        name: f.name.clone(),
        family: f.space.family_params(&truth),
        truth,
        truth_from,
        noise,
        replicates,
    })
}

/// The coverage study of `f`'s design (its speeds, bounds, budget and search settings) with
/// synthetic data from `truth` plus noise of standard deviation `noise`.
pub fn coverage_task(f: &FitConfig, truth: BaseParams, noise: f64) -> CoverageTask {
    CoverageTask {
        space: f.space.clone(),
        truth,
        speeds: f.data.points.iter().map(|p| p.v0).collect(),
        noise,
        budget: f.budget,
        settings: f.settings,
    }
}

/// A replicate as a checkpoint holds it: every field, the numbers exact (non-finite ones as
/// strings, which JSON numbers cannot be).
fn replicate_json(r: &Replicate) -> Value {
    json!({
        "seed": r.seed, "covered": r.covered, "points": r.points,
        "halfwidth": exact(r.halfwidth), "J1": exact(r.j1), "at_bound": r.at_bound,
        "evaluations": r.evaluations, "error": r.error,
    })
}

/// The replicate of [`replicate_json`]; `None` for an entry that is not one (recomputed then).
fn replicate_of_json(v: &Value, task: &CoverageTask) -> Option<Replicate> {
    let names = task.space.free_names();
    Some(Replicate {
        seed: v["seed"].as_u64()?,
        covered: usize::try_from(v["covered"].as_u64()?).ok()?,
        points: usize::try_from(v["points"].as_u64()?).ok()?,
        halfwidth: float_of(&v["halfwidth"])?,
        j1: float_of(&v["J1"])?,
        at_bound: v["at_bound"]
            .as_array()?
            .iter()
            .map(|n| names.iter().copied().find(|m| Some(*m) == n.as_str()))
            .collect::<Option<_>>()?,
        evaluations: v["evaluations"].as_u64()?,
        error: match &v["error"] {
            Value::Null => None,
            e => Some(e.as_str()?.to_owned()),
        },
    })
}

/// `{"coverage": [...]}`: per fit the truth, the noise, the coverage and every replicate.
pub fn coverage_summary(reports: &[CoverageReport]) -> Value {
    let studies: Vec<Value> = reports
        .iter()
        .map(|r| {
            let t = r.truth;
            let truth = match &r.family {
                Some(law) => json!({ law.family.param_name(): law.param }),
                None => json!({"B_b": t.b_b, "Gamma_b": t.gamma_b, "kappa": t.kappa, "sigma_b": t.sigma_b, "n": t.n, "p": t.p}),
            };
            json!({
                "name": r.name,
                "truth": truth,
                "truth_from": r.truth_from,
                "noise": r.noise,
                "level": bwc_identify::LEVEL,
                "coverage": coverage(&r.replicates),
                "replicates": r.replicates.iter().map(|x| json!({
                    "seed": x.seed, "covered": x.covered, "points": x.points,
                    "halfwidth": x.halfwidth.is_finite().then_some(x.halfwidth),
                    "J1": x.j1, "at_bound": x.at_bound, "error": x.error,
                    "evaluations": x.evaluations,
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({ "coverage": studies })
}

/// The coverage study of every CoR-only fit of `config` (or only the one named `only`) over
/// the replicates of `seeds` (`bwc-identify coverage`), resumed from `checkpoint` if given.
///
/// # Errors
/// [`AppError::Invalid`] for a non-positive `noise` or no fit named `only`; as
/// [`run_coverage`].
pub fn coverage_study(
    path: &Path,
    config: &crate::fit::config::Config,
    noise: Option<f64>,
    only: Option<&str>,
    seeds: std::ops::Range<u64>,
    checkpoint: Option<&Checkpoint>,
) -> Result<Vec<CoverageReport>, AppError> {
    let invalid = |key: &str, message: String| AppError::Invalid {
        path: path.to_owned(),
        line: 1,
        key: key.into(),
        message,
    };
    if let Some(n) = noise.filter(|n| !(n.is_finite() && *n > 0.0)) {
        return Err(invalid(
            "--noise",
            format!("{n} is not admissible: a standard deviation > 0"),
        ));
    }
    let fits: Vec<_> = config
        .fits
        .iter()
        .filter(|f| only.is_none_or(|n| n == f.name))
        .collect();
    if fits.is_empty() {
        let names: Vec<&str> = config.fits.iter().map(|f| f.name.as_str()).collect();
        return Err(invalid(
            "--fit",
            format!("no [[fit]] named {only:?}: the config has {names:?}"),
        ));
    }
    fits.iter()
        .map(|f| run_coverage(path, f, noise, seeds.clone(), checkpoint))
        .collect()
}

//! `bwc-identify compare`: which law the data support. Every `[[fit]]` of a config (Bouc-Wen
//! models and contact-law families alike) is fitted to its data, and the fits on the same data
//! file are set side by side: the cost at the optimum, AIC and BIC of the Gaussian likelihood
//! with the noise's variance at its maximum-likelihood value, the log evidence of the posterior
//! (`bwc-identify posterior`), and the held-out error of k-fold cross-validation by speed
//! group (each distinct speed in one fold, folds dealt in order of speed).

use super::posterior::run_posterior;
use super::report::{fail, reporting};
use super::run_fit;
use crate::fit::config::{Config, FitConfig};
use crate::AppError;
use bwc_identify::{fit, predict, Dataset, Objective};
use serde_json::{json, Value};
use std::path::Path;

/// One fit's standing among the models fitted to the same data.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Comparison {
    /// The fit's name.
    pub name: String,
    /// The model's name (`"shccm"`, `"mcm"`, a family's).
    pub model: &'static str,
    /// The data file.
    pub data: String,
    /// Searched quantities `k`.
    pub free: usize,
    /// Data values fitted `n` (CoRs and durations).
    pub n: usize,
    /// The weighted cost `w1 J1 + w2 J2` at the optimum.
    pub cost: f64,
    /// `2 k' - 2 log L̂`, `k'` counting one noise variance per quantity.
    pub aic: f64,
    /// `k' ln n - 2 log L̂`.
    pub bic: f64,
    /// The posterior's log evidence and its Monte Carlo error.
    pub log_evidence: (f64, f64),
    /// The root-mean-square held-out CoR error of the cross-validation (NaN without CoRs).
    pub cv_rmse: f64,
    /// Folds of the cross-validation.
    pub folds: usize,
}

/// Compares every fit of `config` (see the module's text) with `folds` folds, the posteriors
/// sampled with `sizes` (particles, runs; the config's where `None`).
///
/// # Errors
/// A fit's or a posterior's failure; [`AppError::Argument`] for fewer than 2 folds or a fit
/// whose data have fewer distinct speeds than folds.
pub fn compare_all(
    path: &Path,
    config: &Config,
    seed: u64,
    folds: usize,
    sizes: (Option<usize>, Option<usize>),
) -> Result<Vec<Comparison>, AppError> {
    config
        .fits
        .iter()
        .map(|f| compare_one(path, f, seed, folds, sizes))
        .collect()
}

fn compare_one(
    path: &Path,
    f: &FitConfig,
    seed: u64,
    folds: usize,
    sizes: (Option<usize>, Option<usize>),
) -> Result<Comparison, AppError> {
    let report = run_fit(path, f, seed, &|| {}, None)?;
    let (n1, n2) = (
        f.data
            .points
            .iter()
            .filter(|p| p.e.is_some() && f.weights.j1 > 0.0)
            .count(),
        f.data
            .points
            .iter()
            .filter(|p| p.t_d.is_some() && f.weights.j2 > 0.0)
            .count(),
    );
    let n = n1 + n2;
    // log L̂ with each quantity's variance at its maximum-likelihood value, the mean square.
    let term = |count: usize, mse: Option<f64>| match (count, mse) {
        (0, _) | (_, None) => (0.0, 0),
        (c, Some(j)) => {
            let c = c as f64;
            (
                -0.5 * c * ((2.0 * std::f64::consts::PI * j.max(1e-300)).ln() + 1.0),
                1,
            )
        }
    };
    let (l1, k1) = term(n1, report.costs.j1);
    let (l2, k2) = term(n2, report.costs.j2);
    let k = (f.space.dim() + k1 + k2) as f64;
    let log_l = l1 + l2;
    let post = run_posterior(path, f, seed, sizes, None)?;
    Ok(Comparison {
        name: f.name.clone(),
        model: f.model_name(),
        data: f.data.path.display().to_string(),
        free: f.space.dim(),
        n,
        cost: report.costs.weighted(f.weights),
        aic: 2.0 * k - 2.0 * log_l,
        bic: k * (n as f64).ln() - 2.0 * log_l,
        log_evidence: (post.log_evidence, post.log_evidence_error),
        cv_rmse: cross_validate(path, f, seed, folds)?,
        folds,
    })
}

/// The root-mean-square held-out CoR error of `folds`-fold cross-validation by speed group.
fn cross_validate(path: &Path, f: &FitConfig, seed: u64, folds: usize) -> Result<f64, AppError> {
    let err = fail(path, &f.name);
    let mut speeds: Vec<f64> = f.data.points.iter().map(|p| p.v0).collect();
    speeds.sort_by(f64::total_cmp);
    speeds.dedup();
    if folds < 2 || speeds.len() < folds {
        return Err(AppError::Argument {
            argument: "--folds".into(),
            message: format!(
                "{folds} folds for \"{}\", whose data have {} distinct speeds: need 2 <= folds <= \
                 distinct speeds",
                f.name,
                speeds.len()
            ),
        });
    }
    let fold_of = |v0: f64| speeds.partition_point(|&s| s < v0) % folds;
    let (mut squares, mut count) = (0.0, 0usize);
    for k in 0..folds {
        let subset = |held: bool| Dataset {
            points: f
                .data
                .points
                .iter()
                .filter(|p| (fold_of(p.v0) == k) == held)
                .copied()
                .collect(),
            ..f.data.clone()
        };
        let (train, test) = (subset(false), subset(true));
        let objective =
            Objective::new(&f.space, &train, &f.input, f.settings, f.weights).map_err(&err)?;
        let result =
            fit(&objective, &f.budget, seed ^ f.seed ^ (k as u64 + 1), None).map_err(&err)?;
        let map = f.space.map(&result.params).map_err(&err)?;
        let predictions =
            predict(&map, &f.input, &test, &reporting()).map_err(|e| err(e.into()))?;
        for (d, p) in test.points.iter().zip(&predictions) {
            if let Some(e) = d.e {
                squares += (p.e - e).powi(2);
                count += 1;
            }
        }
    }
    Ok(if count == 0 {
        f64::NAN
    } else {
        (squares / count as f64).sqrt()
    })
}

/// `{"comparisons": [{"data", "models": [...], "supported"}]}`: per data file, the fits on it
/// with their `cost`, `AIC`, `BIC`, `log_evidence`, `log_evidence_error`, `cv_rmse`, and a
/// sentence on what the data support.
pub fn compare_summary(rows: &[Comparison]) -> Value {
    let groups = groups(rows);
    let list: Vec<Value> = groups
        .iter()
        .map(|(data, members)| {
            let models: Vec<Value> = members
                .iter()
                .map(|r| {
                    json!({
                        "name": r.name, "model": r.model, "free": r.free, "n": r.n,
                        "cost": r.cost, "AIC": r.aic, "BIC": r.bic,
                        "log_evidence": r.log_evidence.0, "log_evidence_error": r.log_evidence.1,
                        "cv_rmse": if r.cv_rmse.is_finite() { json!(r.cv_rmse) } else { Value::Null },
                        "folds": r.folds,
                    })
                })
                .collect();
            json!({"data": data, "models": models, "supported": verdict(members)})
        })
        .collect();
    json!({ "comparisons": list })
}

/// The fits grouped by data file, in config order.
pub fn groups(rows: &[Comparison]) -> Vec<(String, Vec<&Comparison>)> {
    let mut out: Vec<(String, Vec<&Comparison>)> = Vec::new();
    for r in rows {
        match out.iter_mut().find(|(d, _)| *d == r.data) {
            Some((_, m)) => m.push(r),
            None => out.push((r.data.clone(), vec![r])),
        }
    }
    out
}

/// What the data support, in a sentence: the best fit by evidence, by BIC and by held-out
/// error, and how decisively: the log Bayes factor less twice its error, above 1 positively,
/// above 3 strongly, above 5 decisively (Kass & Raftery 1995).
pub fn verdict(members: &[&Comparison]) -> String {
    if members.len() < 2 {
        return "one model only: nothing to compare".into();
    }
    let best = |key: &dyn Fn(&Comparison) -> f64| {
        let mut sorted: Vec<&&Comparison> = members.iter().collect();
        sorted.sort_by(|a, b| key(a).total_cmp(&key(b)));
        (sorted[0], sorted[1])
    };
    let (ev, ev2) = best(&|r| -r.log_evidence.0);
    let (bic, bic2) = best(&|r| r.bic);
    let (cv, _) = best(&|r| {
        if r.cv_rmse.is_nan() {
            f64::INFINITY
        } else {
            r.cv_rmse
        }
    });
    let ln_bf = ev.log_evidence.0 - ev2.log_evidence.0;
    let error = ev.log_evidence.1.hypot(ev2.log_evidence.1);
    // Kass & Raftery's scale of the log Bayes factor, less twice its Monte Carlo error.
    let sure = ln_bf - 2.0 * error;
    let strength = if sure > 5.0 {
        "decisively"
    } else if sure > 3.0 {
        "strongly"
    } else if sure > 1.0 {
        "positively"
    } else {
        "not distinguishably"
    };
    let others = if ev.name == bic.name && ev.name == cv.name {
        format!(
            "BIC ({:.1} below \"{}\") and the held-out error agree",
            bic2.bic - bic.bic,
            bic2.name
        )
    } else {
        format!(
            "the lowest BIC is \"{}\"'s ({:.1} below \"{}\"), the lowest held-out error \"{}\"'s",
            bic.name,
            bic2.bic - bic.bic,
            bic2.name,
            cv.name
        )
    };
    format!(
        "the evidence supports \"{}\" ({}) {strength} over \"{}\" (log Bayes factor {ln_bf:.1} \
         +- {error:.1}); {others}",
        ev.name, ev.model, ev2.name,
    )
}

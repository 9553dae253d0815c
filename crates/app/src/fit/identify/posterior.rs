//! `bwc-identify posterior`: the posterior of each fit's searched quantities by sequential Monte
//! Carlo ([`bwc_identify::sample`]), its marginal summaries, the evidence, and the credible bands
//! of `e(v0)` and `t_d(v0)`. A run is a pure function of the seed and its index, so runs can be
//! computed anywhere ([`posterior_run`], one per worker) and pooled ([`posterior_from_runs`]) to
//! the same result as [`run_posterior`].

use super::curve_speeds;
use super::report::fail;
use crate::fit::checkpoint::{fingerprint, Checkpoint};
use crate::fit::config::{Config, FitConfig};
use crate::fit::corner::CornerColumn;
use crate::AppError;
use bwc_identify::{
    disagreement, fit, marginals, pool, posterior_band, run_spread, smc_run, FitResult, Marginal,
    NoiseScale, Objective, PosteriorBandPoint, PosteriorProblem, PosteriorSpec, Prior,
    SmcReference, SmcRun, SmcSettings, Stage,
};
use rayon::prelude::*;
use serde_json::{json, Value};
use std::path::Path;
use std::time::Instant;

/// One fit's posterior.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct PosteriorReport {
    /// The fit's name.
    pub name: String,
    /// The model key.
    pub model: &'static str,
    /// The sampled coordinates: the free quantities (`g`, not `Γ_b`), then `sigma_e`,
    /// `sigma_t` where sampled.
    pub names: Vec<&'static str>,
    /// Their marginal summaries.
    pub marginals: Vec<Marginal>,
    /// `log ∫ prior L` (the likelihood's density in the data's units).
    pub log_evidence: f64,
    /// Its Monte Carlo standard error.
    pub log_evidence_error: f64,
    /// Likelihood evaluations (each simulates every distinct speed).
    pub evaluations: u64,
    /// Wall-clock time (s).
    pub wall_s: f64,
    /// Particles per run and runs.
    pub particles: usize,
    /// Independent runs.
    pub runs: usize,
    /// The effective sample size of the pooled weights.
    pub ess: f64,
    /// The noise model, in words.
    pub noise: String,
    /// The priors other than uniform.
    pub priors: Vec<Prior>,
    /// Per particle: the full base parameters `P*` (B_b, Γ_b, κ, σ_b, n, p, U_b, T_b), or a
    /// family's damping parameter and `T_b`, then the sampled noise scales
    /// ([`PosteriorReport::columns`]).
    pub samples: Vec<Vec<f64>>,
    /// The names of the columns of `samples`.
    pub columns: Vec<&'static str>,
    /// Per particle: the sampled coordinates' values, in the order of `names`.
    pub values: Vec<Vec<f64>>,
    /// Whether each of `names` is sampled on a log scale.
    pub log_scale: Vec<bool>,
    /// The particles' weights (summing to 1).
    pub weights: Vec<f64>,
    /// The run each particle comes from.
    pub run: Vec<usize>,
    /// The particles' log-likelihoods.
    pub log_likelihood: Vec<f64>,
    /// Each run's stages.
    pub stages: Vec<Vec<Stage>>,
    /// Each run's log evidence.
    pub run_log_evidence: Vec<f64>,
    /// The band on the curve speeds of `run` ([`curve_speeds`]).
    pub curve: Vec<PosteriorBandPoint>,
    /// Whether the CoR and the duration entered the likelihood.
    pub uses: (bool, bool),
    /// Warnings (the data's, and where the sample is thin).
    pub warnings: Vec<String>,
}

/// The columns of [`PosteriorReport::samples`] before the noise scales.
pub const SAMPLE_COLUMNS: [&str; 8] =
    ["B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "U_b", "T_b"];

/// The settings of `f`'s sampler, with `particles` and `runs` overriding the config's.
fn settings_of(f: &FitConfig, particles: Option<usize>, runs: Option<usize>) -> SmcSettings {
    SmcSettings::new(
        particles.unwrap_or(f.posterior.particles),
        runs.unwrap_or(f.posterior.runs),
    )
}

/// The posterior problem of fit `f`, at the search's accuracy (`[fit.solver]`, rtol 1e-8 by
/// default): the likelihood compares predictions with data to their noise, orders of magnitude
/// above the solver's error.
fn problem<'a>(
    config: &Path,
    f: &'a FitConfig,
) -> Result<(PosteriorProblem<'a, crate::signal::Signal>, PosteriorSpec), AppError> {
    let err = fail(config, &f.name);
    if f.drops.is_some() {
        return Err(err(bwc_identify::IdentifyError::Posterior {
            reason: "posteriors of drop-test fits (intervals or heights) are not supported: \
                     derive CoRs (v_0, e) from the drops and fit those"
                .into(),
        }));
    }
    let mut spec = PosteriorSpec::new(&f.data, f.weights);
    (spec.e_noise, spec.t_noise) = f.posterior.noise(PosteriorSpec::default_noise(&f.data));
    spec.priors = f.posterior.priors.clone();
    let p = PosteriorProblem::new(&f.space, &f.data, &f.input, f.settings, &spec).map_err(&err)?;
    Ok((p, spec))
}

/// The sampler's reference of fit `f`: around the optimum of the fit's own search (as
/// `bwc-identify run` finds it with `seed`), and that optimum.
fn reference(
    config: &Path,
    f: &FitConfig,
    p: &PosteriorProblem<'_, crate::signal::Signal>,
    seed: u64,
) -> Result<(SmcReference, FitResult), AppError> {
    let err = fail(config, &f.name);
    let objective =
        Objective::new(&f.space, &f.data, &f.input, f.settings, f.weights).map_err(&err)?;
    let optimum = fit(&objective, &f.budget, seed ^ f.seed, f.start.as_deref()).map_err(&err)?;
    Ok((p.reference_at(&optimum.point, &optimum.costs), optimum))
}

/// Run `index` of fit `f`'s sampler with `seed` (combined with the fit's seed, as `run` does),
/// its reference from the fit's search (which each run repeats: it is deterministic).
///
/// # Errors
/// As [`run_posterior`].
pub fn posterior_run(
    config: &Path,
    f: &FitConfig,
    seed: u64,
    (particles, runs): (Option<usize>, Option<usize>),
    index: usize,
) -> Result<SmcRun, AppError> {
    let (p, _) = problem(config, f)?;
    let (r, _) = reference(config, f, &p, seed)?;
    let settings = settings_of(f, particles, runs);
    smc_run(&p, &settings, &r, seed ^ f.seed, index).map_err(fail(config, &f.name))
}

/// Samples fit `f`'s posterior: every run of [`posterior_run`] in parallel, pooled. With a
/// `checkpoint`, the runs it holds for this fit, seed and sampler settings are taken from it
/// and each new one is recorded as it finishes.
///
/// # Errors
/// [`AppError::Identify`] for a drop-test fit, for data or settings a
/// posterior cannot use (one point, a noise column with zeros, a prior outside the bounds) or
/// a sampler that does not reach the posterior; [`AppError::Io`] when the checkpoint cannot
/// be written.
pub fn run_posterior(
    config: &Path,
    f: &FitConfig,
    seed: u64,
    sizes: (Option<usize>, Option<usize>),
    checkpoint: Option<&Checkpoint>,
) -> Result<PosteriorReport, AppError> {
    let clock = Instant::now();
    let (p, _) = problem(config, f)?;
    let settings = settings_of(f, sizes.0, sizes.1);
    let print = fingerprint(&[&"posterior", f, &seed, &settings]);
    let kept = |k: usize| {
        let v = checkpoint?.get(&format!("{}/{k}", f.name), &print)?;
        run_of_json(v).ok().filter(|r| r.index == k)
    };
    let mut runs: Vec<Option<SmcRun>> = (0..settings.runs).map(kept).collect();
    // The reference search's evaluations count in the report: kept with the runs, so that a
    // study resumed with every run done reports what an uninterrupted one does.
    let reference_key = format!("{}/reference", f.name);
    let kept_reference = checkpoint
        .and_then(|c| c.get(&reference_key, &print))
        .and_then(|v| v["evaluations"].as_u64());
    let mut evaluations = kept_reference.unwrap_or(0);
    if runs.iter().any(Option::is_none) || kept_reference.is_none() {
        let (r, optimum) = reference(config, f, &p, seed)?;
        evaluations = optimum.evaluations;
        if let Some(c) = checkpoint.filter(|_| kept_reference.is_none()) {
            c.record(&reference_key, &print, json!({"evaluations": evaluations}))?;
        }
        runs.par_iter_mut()
            .enumerate()
            .filter(|(_, run)| run.is_none())
            .try_for_each(|(k, run)| {
                let fresh =
                    smc_run(&p, &settings, &r, seed ^ f.seed, k).map_err(fail(config, &f.name))?;
                if let Some(c) = checkpoint {
                    c.record(&format!("{}/{k}", f.name), &print, run_json(&fresh))?;
                }
                *run = Some(fresh);
                Ok::<_, AppError>(())
            })?;
    }
    let runs: Vec<SmcRun> = runs.into_iter().flatten().collect();
    let mut report = posterior_from_runs(config, f, seed, runs)?;
    report.wall_s = clock.elapsed().as_secs_f64();
    report.evaluations += evaluations;
    Ok(report)
}

/// Pools runs of fit `f`'s sampler (from [`posterior_run`], computed anywhere) into its
/// report; `seed` draws the band's samples.
///
/// # Errors
/// As [`run_posterior`].
pub fn posterior_from_runs(
    config: &Path,
    f: &FitConfig,
    seed: u64,
    runs: Vec<SmcRun>,
) -> Result<PosteriorReport, AppError> {
    let clock = Instant::now();
    let err = fail(config, &f.name);
    let (p, spec) = problem(config, f)?;
    let run_log_evidence = runs.iter().map(|r| r.log_evidence).collect();
    let (particles, count) = (runs.first().map_or(0, |r| r.particles.len()), runs.len());
    let post = pool(runs).map_err(&err)?;
    let column_noise = median_noise(f);
    let curve = posterior_band(
        &p,
        &post,
        &curve_speeds(&f.data),
        (f.posterior.draws, seed ^ f.seed),
        column_noise,
    )
    .map_err(&err)?;
    let mut warnings = [&f.data.warnings[..], &f.hints].concat();
    if post.ess < 100.0 {
        warnings.push(format!(
            "\"{}\": the pooled sample's effective size is {:.0}: raise particles or runs",
            f.name, post.ess
        ));
    }
    if let Some(w) = disagreement(&f.name, count, &run_spread(&p, &post)) {
        warnings.push(w);
    }
    let samples = post
        .particles
        .iter()
        .map(|s| {
            let b = f.space.decode(&s[..f.space.dim()]);
            let mut row = match f.space.family_params(&b) {
                Some(law) => vec![law.param, law.t_b],
                None => vec![b.b_b, b.gamma_b, b.kappa, b.sigma_b, b.n, b.p, b.u_b, b.t_b],
            };
            let (se, st) = p.noise_at(s);
            row.extend([se, st].into_iter().filter(|x| !x.is_nan()));
            row
        })
        .collect();
    Ok(PosteriorReport {
        name: f.name.clone(),
        model: f.model_name(),
        names: p.names(),
        marginals: marginals(&p, &post),
        log_evidence: post.log_evidence,
        log_evidence_error: post.log_evidence_error,
        evaluations: post.evaluations,
        wall_s: clock.elapsed().as_secs_f64(),
        particles,
        runs: count,
        ess: post.ess,
        noise: noise_words(f, &spec, column_noise),
        priors: spec.priors.clone(),
        columns: sample_columns(f, &p.names()),
        samples,
        values: post.particles.iter().map(|s| p.values(s)).collect(),
        log_scale: log_scales(f, &p.names()),
        weights: post.weights,
        run: post.run,
        log_likelihood: post.log_likelihood,
        stages: post.runs.iter().map(|r| r.stages.clone()).collect(),
        run_log_evidence,
        curve,
        uses: (f.weights.j1 > 0.0, f.weights.j2 > 0.0),
        warnings,
    })
}

/// The columns of a posterior's samples: `P*` or a family's parameters, then the sampled noise
/// scales among `names`.
fn sample_columns(f: &FitConfig, names: &[&'static str]) -> Vec<&'static str> {
    let head: Vec<&'static str> = match f.family {
        Some(family) => vec![family.param_name(), "T_b"],
        None => SAMPLE_COLUMNS.to_vec(),
    };
    head.into_iter()
        .chain(
            names
                .iter()
                .copied()
                .filter(|n| *n == "sigma_e" || *n == "sigma_t"),
        )
        .collect()
}

/// Whether each coordinate named in `names` is sampled on a log scale (the noise scales are).
fn log_scales(f: &FitConfig, names: &[&str]) -> Vec<bool> {
    names
        .iter()
        .map(|n| {
            let i = bwc_identify::NAMES.iter().position(|m| m == n);
            match i.map(|i| f.space.params()[i]) {
                Some(bwc_identify::Param::Free { log, .. }) => log,
                _ => n.starts_with("sigma_"),
            }
        })
        .collect()
}

/// The median of the data's noise column (the noise of a new CoR measurement with given
/// noise), NaN without one.
fn median_noise(f: &FitConfig) -> f64 {
    let mut v: Vec<f64> = f.data.points.iter().filter_map(|p| p.noise).collect();
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The noise model in words.
fn noise_words(f: &FitConfig, spec: &PosteriorSpec, column_noise: f64) -> String {
    let scale = |s: NoiseScale, what: &str, unit: &str| match s {
        NoiseScale::Sampled { lo, hi } => {
            format!("{what}: one Gaussian scale, sampled log-uniformly in [{lo:e}, {hi:e}]{unit}")
        }
        _ => format!(
            "{what}: Gaussian, per point from column `{}` (a new measurement: {column_noise:.3e}, \
             the column's median)",
            f.data.noise_column.unwrap_or("-")
        ),
    };
    let mut parts = Vec::new();
    if f.weights.j1 > 0.0 {
        parts.push(scale(spec.e_noise, "e", ""));
    }
    if f.weights.j2 > 0.0 {
        parts.push(scale(spec.t_noise, "t_d", " s"));
    }
    parts.join("; ")
}

/// Every fit of `config` (or only the one named `only`), one after another (each runs its
/// particles in parallel).
///
/// # Errors
/// [`AppError::Argument`] when `only` names no fit; the first fit's failure.
pub fn posterior_all(
    path: &Path,
    config: &Config,
    seed: u64,
    only: Option<&str>,
    sizes: (Option<usize>, Option<usize>),
    checkpoint: Option<&Checkpoint>,
) -> Result<Vec<PosteriorReport>, AppError> {
    let fits: Vec<&FitConfig> = config
        .fits
        .iter()
        .filter(|f| only.is_none_or(|n| f.name == n))
        .collect();
    if fits.is_empty() {
        let names: Vec<&str> = config.fits.iter().map(|f| f.name.as_str()).collect();
        return Err(AppError::Argument {
            argument: "--fit".into(),
            message: format!(
                "{:?} names no [[fit]]: one of {names:?}",
                only.unwrap_or("")
            ),
        });
    }
    fits.into_iter()
        .map(|f| run_posterior(path, f, seed, sizes, checkpoint))
        .collect()
}

/// The JSON of posteriors: `{"posteriors": [...]}`, each with its evidence, marginals, noise
/// model, priors, sampler settings and the band at the curve speeds.
pub fn posterior_summary(reports: &[PosteriorReport]) -> Value {
    let list: Vec<Value> = reports.iter().map(one_summary).collect();
    json!({ "posteriors": list })
}

fn one_summary(r: &PosteriorReport) -> Value {
    let marginals: serde_json::Map<String, Value> = r
        .marginals
        .iter()
        .map(|m| {
            (
                m.name.to_string(),
                json!({
                    "median": m.median,
                    "lo": m.interval[0],
                    "hi": m.interval[1],
                    "mean": m.mean,
                    "sd": m.sd,
                    "unit": unit_of(m.name),
                }),
            )
        })
        .collect();
    let priors: Vec<Value> = r
        .priors
        .iter()
        .map(|p| json!({"quantity": p.name, "normal": [p.mean, p.sd]}))
        .collect();
    let band: Vec<Value> = r.curve.iter().map(band_json).collect();
    json!({
        "name": r.name,
        "model": r.model,
        "log_evidence": r.log_evidence,
        "log_evidence_error": r.log_evidence_error,
        "run_log_evidence": r.run_log_evidence,
        "evaluations": r.evaluations,
        "wall_s": r.wall_s,
        "particles": r.particles,
        "runs": r.runs,
        "ess": r.ess,
        "noise": r.noise,
        "prior": "uniform on each searched quantity's bounds, on its search scale (log-uniform \
                  where `log` names it), except the priors listed",
        "priors": priors,
        "marginals": marginals,
        "level": 0.95,
        "band": band,
        "stages": r.stages.iter().map(|s| s.iter().map(|x| json!({
            "beta": x.beta, "acceptance": if x.acceptance.is_nan() { Value::Null } else { json!(x.acceptance) }, "moves": x.moves,
        })).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "warnings": r.warnings,
    })
}

/// The weighted sample of a posterior as JSON columns: `columns` (the full P*, or a family's
/// parameters, then the sampled noise scales), `values` (one list per column), `weight`, `run`, `log_likelihood`.
pub fn samples_json(r: &PosteriorReport) -> Value {
    let columns = &r.columns;
    let values: Vec<Vec<f64>> = (0..columns.len())
        .map(|j| r.samples.iter().map(|s| s[j]).collect())
        .collect();
    json!({
        "columns": columns,
        "values": values,
        "weight": r.weights,
        "run": r.run,
        "log_likelihood": r.log_likelihood,
    })
}

/// One sampler run as JSON (for pooling runs computed elsewhere: [`run_of_json`]). Numbers
/// survive the round trip bit for bit (serde_json's `float_roundtrip`).
pub fn run_json(run: &SmcRun) -> Value {
    json!({
        "index": run.index,
        "particles": run.particles,
        "weights": run.weights,
        "log_likelihood": run.log_likelihood,
        "log_evidence": run.log_evidence,
        "stages": run.stages.iter().map(|s| json!([s.beta, if s.acceptance.is_nan() { Value::Null } else { json!(s.acceptance) }, s.moves])).collect::<Vec<_>>(),
        "evaluations": run.evaluations,
    })
}

/// A sampler run from the JSON of [`run_json`].
///
/// # Errors
/// [`AppError::Argument`] naming the key that is missing or malformed.
pub fn run_of_json(v: &Value) -> Result<SmcRun, AppError> {
    let bad = |key: &str| AppError::Argument {
        argument: format!("a posterior run's `{key}`"),
        message: "missing or malformed: pass the JSON a posterior run returned".into(),
    };
    let floats = |key: &str| -> Result<Vec<f64>, AppError> {
        v[key]
            .as_array()
            .ok_or_else(|| bad(key))?
            .iter()
            .map(|x| {
                x.as_f64()
                    .or(x.is_null().then_some(f64::NEG_INFINITY))
                    .ok_or_else(|| bad(key))
            })
            .collect()
    };
    let particles = v["particles"]
        .as_array()
        .ok_or_else(|| bad("particles"))?
        .iter()
        .map(|p| {
            p.as_array()
                .ok_or_else(|| bad("particles"))?
                .iter()
                .map(|x| x.as_f64().ok_or_else(|| bad("particles")))
                .collect()
        })
        .collect::<Result<Vec<Vec<f64>>, _>>()?;
    let stages = v["stages"]
        .as_array()
        .ok_or_else(|| bad("stages"))?
        .iter()
        .map(|s| {
            Ok(Stage {
                beta: s[0].as_f64().ok_or_else(|| bad("stages"))?,
                acceptance: s[1].as_f64().unwrap_or(f64::NAN),
                moves: s[2].as_u64().ok_or_else(|| bad("stages"))? as usize,
            })
        })
        .collect::<Result<_, AppError>>()?;
    Ok(SmcRun {
        index: v["index"].as_u64().ok_or_else(|| bad("index"))? as usize,
        particles,
        weights: floats("weights")?,
        log_likelihood: floats("log_likelihood")?,
        log_evidence: v["log_evidence"]
            .as_f64()
            .ok_or_else(|| bad("log_evidence"))?,
        stages,
        evaluations: v["evaluations"]
            .as_u64()
            .ok_or_else(|| bad("evaluations"))?,
    })
}

fn band_json(b: &PosteriorBandPoint) -> Value {
    let n = |x: f64| if x.is_finite() { json!(x) } else { Value::Null };
    json!({
        "v_0": b.v0,
        "e": n(b.e[0]), "e_lo": n(b.e[1]), "e_hi": n(b.e[2]),
        "e_new_lo": n(b.e_new[0]), "e_new_hi": n(b.e_new[1]),
        "t_d": n(b.t_d[0]), "t_d_lo": n(b.t_d[1]), "t_d_hi": n(b.t_d[2]),
        "t_d_new_lo": n(b.t_d_new[0]), "t_d_new_hi": n(b.t_d_new[1]),
    })
}

/// The unit of a sampled coordinate.
pub fn unit_of(name: &str) -> &'static str {
    match name {
        "U_b" => "N",
        "T_b" | "sigma_t" => "s",
        // A contact-law family's parameter: its own unit (`alpha` s/m, `v_y` m/s).
        _ => (bw_models::FAMILIES.iter())
            .map(|f| f.spec().param)
            .find(|p| p.name == name)
            .map_or("-", |p| p.unit),
    }
}

/// A posterior's files: `<stem>_posterior.csv` (the weighted sample), `<stem>_posterior_band.csv`
/// (the bands on the curve speeds), `<stem>_posterior_cor.svg` and `<stem>_posterior_t_d.svg`
/// (data, median curve and 95 % credible band), `<stem>_corner.svg`.
///
/// # Errors
/// [`AppError::Csv`] or [`AppError::Plot`] when rendering fails.
pub fn render_posterior(
    f: &FitConfig,
    r: &PosteriorReport,
    out: &Path,
) -> Result<Vec<(String, Vec<u8>)>, AppError> {
    let stem = super::slug(&r.name);
    let mut files = vec![samples_csv(r, out, &format!("{stem}_posterior.csv"))?];
    files.push(band_csv(r, out, &format!("{stem}_posterior_band.csv"))?);
    let perr = |name: &str| {
        let path = out.join(name);
        move |message: String| AppError::Plot { path, message }
    };
    for (used, q) in [(r.uses.0, "cor"), (r.uses.1, "t_d")] {
        if used {
            let name = format!("{stem}_posterior_{q}.svg");
            let svg = band_figure(f, r, q == "cor").map_err(perr(&name))?;
            files.push((name, svg.into_bytes()));
        }
    }
    let name = format!("{stem}_corner.svg");
    let columns: Vec<CornerColumn> = r
        .names
        .iter()
        .enumerate()
        .map(|(j, n)| CornerColumn {
            label: match unit_of(n) {
                "-" => n.to_string(),
                u => format!("{n} ({u})"),
            },
            values: r.values.iter().map(|v| v[j]).collect(),
            log: r.log_scale[j],
        })
        .collect();
    let title = format!(
        "{}: posterior ({} particles, ESS {:.0})",
        r.name,
        r.weights.len(),
        r.ess
    );
    let svg = crate::fit::corner::corner(&title, &columns, &r.weights).map_err(perr(&name))?;
    files.push((name, svg.into_bytes()));
    Ok(files)
}

/// The chart of the CoR (or the duration) with the posterior's median and credible band.
fn band_figure(f: &FitConfig, r: &PosteriorReport, cor: bool) -> Result<String, String> {
    let data: Vec<(f64, f64, Option<f64>)> = f
        .data
        .points
        .iter()
        .filter_map(|p| {
            if cor {
                p.e.map(|e| (p.v0, e, p.noise.or(p.spread)))
            } else {
                p.t_d.map(|t| (p.v0, t, None))
            }
        })
        .collect();
    let model: Vec<(f64, f64, f64, f64)> = r
        .curve
        .iter()
        .map(|b| {
            let q = if cor { b.e } else { b.t_d };
            (b.v0, q[0], q[1], q[2])
        })
        .collect();
    let (lo, hi) = f.data.points.iter().fold((f64::INFINITY, 0.0f64), |a, p| {
        (a.0.min(p.v0), a.1.max(p.v0))
    });
    let (title, y) = if cor {
        (
            "coefficient of restitution",
            "coefficient of restitution e (-)",
        )
    } else {
        ("contact duration", "contact duration t_d (s)")
    };
    crate::plot::fit_chart(
        &format!("{}: {title}, posterior", r.name),
        ("impact speed v0 (m/s)", y),
        ("measured", &data),
        (
            &format!(
                "posterior median (log Z = {:.2} +- {:.2})",
                r.log_evidence, r.log_evidence_error
            ),
            &model,
        ),
        None,
        "95 % credible band",
        hi > 3.0 * lo,
    )
}

/// The weighted sample as CSV: run, weight, log_likelihood, the full P* (or a family's
/// parameters), the noise scales.
fn samples_csv(r: &PosteriorReport, out: &Path, name: &str) -> Result<(String, Vec<u8>), AppError> {
    let cerr = |source| AppError::Csv {
        path: out.join(name),
        source,
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    let header: Vec<&str> = ["run", "weight", "log_likelihood"]
        .into_iter()
        .chain(r.columns.iter().copied())
        .collect();
    w.write_record(&header).map_err(cerr)?;
    for (i, row) in r.samples.iter().enumerate() {
        let mut rec = vec![
            r.run[i].to_string(),
            r.weights[i].to_string(),
            r.log_likelihood[i].to_string(),
        ];
        rec.extend(row.iter().map(|x| x.to_string()));
        w.write_record(&rec).map_err(cerr)?;
    }
    Ok((name.to_string(), w.into_inner().expect("in-memory writer")))
}

/// The bands as CSV (empty fields where a quantity is not predicted).
fn band_csv(r: &PosteriorReport, out: &Path, name: &str) -> Result<(String, Vec<u8>), AppError> {
    let cerr = |source| AppError::Csv {
        path: out.join(name),
        source,
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(BAND_COLUMNS).map_err(cerr)?;
    let o = |x: f64| {
        if x.is_finite() {
            x.to_string()
        } else {
            String::new()
        }
    };
    for b in &r.curve {
        let row = [
            b.v0,
            b.e[0],
            b.e[1],
            b.e[2],
            b.e_new[0],
            b.e_new[1],
            b.t_d[0],
            b.t_d[1],
            b.t_d[2],
            b.t_d_new[0],
            b.t_d_new[1],
        ];
        w.write_record(row.map(o)).map_err(cerr)?;
    }
    Ok((name.to_string(), w.into_inner().expect("in-memory writer")))
}

/// The columns of `<stem>_posterior_band.csv`.
pub const BAND_COLUMNS: [&str; 11] = [
    "v_0",
    "e",
    "e_lo",
    "e_hi",
    "e_new_lo",
    "e_new_hi",
    "t_d",
    "t_d_lo",
    "t_d_hi",
    "t_d_new_lo",
    "t_d_new_hi",
];

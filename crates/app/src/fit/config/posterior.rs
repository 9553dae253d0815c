//! `[fit.posterior]` (how `bwc-identify posterior` samples a fit) and `[fit.prior]` (priors
//! other than uniform on the search scale):
//!
//! ```toml
//! [fit.posterior]
//! particles = 500          # per run
//! runs = 4                 # independent runs: their spread is the evidence's error
//! noise = "given"          # or "sampled"; default: given where the data have e_sem / e_std
//! sigma_e = [1e-4, 0.5]    # bounds of a sampled CoR noise scale (log-uniform prior)
//! sigma_t = [1e-6, 1e-3]   # bounds of the duration's noise scale (s)
//! draws = 400              # posterior draws behind the bands
//! [fit.prior]
//! kappa = { normal = [0.5, 0.1] }   # mean, sd; truncated to the bounds
//! ```

use super::search::{count, Pair};
use crate::tables::Ctx;
use crate::AppError;
use bwc_identify::{NoiseScale, Prior, Space, NAMES};
use serde::Deserialize;
use std::collections::BTreeMap;
use toml::Spanned;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPosterior {
    particles: Option<Spanned<i64>>,
    runs: Option<Spanned<i64>>,
    noise: Option<Spanned<String>>,
    sigma_e: Option<Pair>,
    sigma_t: Option<Pair>,
    draws: Option<Spanned<i64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawPrior {
    normal: Option<Pair>,
}

/// The priors of `[fit.prior]`, by quantity.
pub(super) type RawPriors = BTreeMap<String, Spanned<RawPrior>>;

/// How a fit's posterior is sampled.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct PosteriorConfig {
    /// Particles per run.
    pub particles: usize,
    /// Independent runs.
    pub runs: usize,
    /// `noise`: `Some(true)` for "given", `Some(false)` for "sampled", `None` for the default
    /// (given where the data have a noise column).
    pub given_noise: Option<bool>,
    /// Bounds of a sampled CoR noise scale.
    pub sigma_e: Option<(f64, f64)>,
    /// Bounds of the duration's noise scale (s).
    pub sigma_t: Option<(f64, f64)>,
    /// Posterior draws behind the bands.
    pub draws: usize,
    /// Priors other than uniform.
    pub priors: Vec<Prior>,
}

impl Default for PosteriorConfig {
    fn default() -> Self {
        Self {
            particles: 500,
            runs: 4,
            given_noise: None,
            sigma_e: None,
            sigma_t: None,
            draws: 400,
            priors: Vec::new(),
        }
    }
}

/// `[lo, hi]` with `0 < lo < hi`.
fn scale_bounds(ctx: &Ctx, pair: &Option<Pair>, key: &str) -> Result<Option<(f64, f64)>, AppError> {
    let Some(pair) = pair else {
        return Ok(None);
    };
    let v = pair.get_ref();
    if v.len() != 2 {
        return Err(ctx.invalid(&pair.span(), key, "give [lower, upper]"));
    }
    let (lo, hi) = (ctx.num(&v[0], key)?, ctx.num(&v[1], key)?);
    if !(lo > 0.0 && hi > lo) {
        return Err(ctx.invalid(
            &pair.span(),
            key,
            format!("[{lo}, {hi}] is not admissible: 0 < lower < upper (a log-uniform prior)"),
        ));
    }
    Ok(Some((lo, hi)))
}

/// `[fit.posterior]` and `[fit.prior]` of a fit with search space `space`.
///
/// # Errors
/// [`AppError::Invalid`] naming the key: counts out of range, an unknown noise model, noise
/// bounds that are not `0 < lo < hi`, a prior on a quantity that is not searched, with a mean
/// outside the bounds or a standard deviation that is not positive.
pub(super) fn posterior(
    ctx: &Ctx,
    raw: Option<&Spanned<RawPosterior>>,
    priors: Option<&RawPriors>,
    space: &Space,
) -> Result<PosteriorConfig, AppError> {
    let d = PosteriorConfig::default();
    let mut out = PosteriorConfig {
        priors: prior_list(ctx, priors, space)?,
        ..d.clone()
    };
    let Some(raw) = raw else {
        return Ok(out);
    };
    let r = raw.get_ref();
    let n = |v: &Option<Spanned<i64>>, key: &str, min, max, default: usize| {
        count(
            ctx,
            v,
            &format!("[fit.posterior].{key}"),
            min,
            max,
            default as i64,
        )
        .map(|x| x as usize)
    };
    out.particles = n(&r.particles, "particles", 16, 1_000_000, d.particles)?;
    out.runs = n(&r.runs, "runs", 2, 10_000, d.runs)?;
    out.draws = n(&r.draws, "draws", 20, 1_000_000, d.draws)?;
    out.given_noise = match &r.noise {
        None => None,
        Some(s) => match s.get_ref().as_str() {
            "given" => Some(true),
            "sampled" => Some(false),
            other => {
                return Err(ctx.invalid(
                    &s.span(),
                    "[fit.posterior].noise",
                    format!(
                        "{other:?} is not a noise model: \"given\" (the data's e_sem or e_std \
                         column) or \"sampled\""
                    ),
                ))
            }
        },
    };
    out.sigma_e = scale_bounds(ctx, &r.sigma_e, "[fit.posterior].sigma_e")?;
    out.sigma_t = scale_bounds(ctx, &r.sigma_t, "[fit.posterior].sigma_t")?;
    Ok(out)
}

/// The priors of `[fit.prior]`, each checked against `space`.
fn prior_list(
    ctx: &Ctx,
    priors: Option<&RawPriors>,
    space: &Space,
) -> Result<Vec<Prior>, AppError> {
    let Some(priors) = priors else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for (name, raw) in priors {
        let key = format!("[fit.prior].{name}");
        let Some(&name) = NAMES.iter().find(|n| **n == name.as_str()) else {
            return Err(ctx.invalid(
                &raw.span(),
                &key,
                format!("not a searchable quantity: one of {NAMES:?}"),
            ));
        };
        let Some(pair) = &raw.get_ref().normal else {
            return Err(ctx.invalid(
                &raw.span(),
                format!("[fit.prior.{name}].normal"),
                "missing required key: the prior's kind, normal = [mean, sd]",
            ));
        };
        let v = pair.get_ref();
        if v.len() != 2 {
            return Err(ctx.invalid(&pair.span(), &key, "give normal = [mean, sd]"));
        }
        let prior = Prior {
            name,
            mean: ctx.num(&v[0], &key)?,
            sd: ctx.num(&v[1], &key)?,
        };
        prior
            .validate(space)
            .map_err(|e| ctx.invalid(&pair.span(), &key, e.to_string()))?;
        out.push(prior);
    }
    Ok(out)
}

impl PosteriorConfig {
    /// The noise scales for data with (or without) a noise column and durations up to
    /// `defaults`: the config's choice, else the library's defaults.
    pub fn noise(&self, defaults: (NoiseScale, NoiseScale)) -> (NoiseScale, NoiseScale) {
        let sampled_e = || {
            let (lo, hi) = self.sigma_e.unwrap_or((1e-4, 0.5));
            NoiseScale::Sampled { lo, hi }
        };
        let e = match self.given_noise {
            Some(true) => NoiseScale::Column,
            Some(false) => sampled_e(),
            None if self.sigma_e.is_some() => sampled_e(),
            None => defaults.0,
        };
        let t = self
            .sigma_t
            .map_or(defaults.1, |(lo, hi)| NoiseScale::Sampled { lo, hi });
        (e, t)
    }
}

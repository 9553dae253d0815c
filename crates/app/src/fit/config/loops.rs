//! `[[loop_fit]]` tables: contact laws fitted to measured hysteresis loops.

use super::search::{optimizer, param_of, Pair, RawOptimizer};
use crate::tables::{contact_law, model_kind, span, Ctx, Num};
use crate::AppError;
use bw_models::ModelKind;
use bwc_identify::{Budget, IdentifyError, LawSpace, Param, LAW_NAMES};
use serde::Deserialize;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml::Spanned;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawLoopFit {
    name: Option<Spanned<String>>,
    model: Option<Spanned<String>>,
    m: Option<Num>,
    loops: Option<Spanned<Vec<Spanned<RawLoopRef>>>>,
    log: Option<Spanned<Vec<Spanned<String>>>>,
    bounds: Option<Spanned<RawLaw<Pair>>>,
    fixed: Option<Spanned<RawLaw<Num>>>,
    params: Option<Spanned<RawLaw<Num>>>,
    optimizer: Option<Spanned<RawOptimizer>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoopRef {
    data: Spanned<String>,
    v0: Num,
}

/// Contact-law quantities (`g = gamma / beta` in bounds and fixed values; `gamma` in params).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLaw<T> {
    k: Option<T>,
    c: Option<T>,
    n: Option<T>,
    p: Option<T>,
    alpha: Option<T>,
    beta: Option<T>,
    g: Option<T>,
    gamma: Option<T>,
    #[serde(rename = "A")]
    a: Option<T>,
}

impl<T> Default for RawLaw<T> {
    fn default() -> Self {
        Self {
            k: None,
            c: None,
            n: None,
            p: None,
            alpha: None,
            beta: None,
            g: None,
            gamma: None,
            a: None,
        }
    }
}

/// One validated hysteresis-loop fit.
#[derive(Debug, Clone)]
pub struct LoopFitConfig {
    /// Name (unique in the config).
    pub name: String,
    /// The model.
    pub kind: ModelKind,
    /// Known mass (kg).
    pub m: f64,
    /// The measured loops.
    pub loops: Vec<bwc_identify::Loop>,
    /// The search space of the contact law.
    pub space: bwc_identify::LawSpace,
    /// Optimizer budget.
    pub budget: Budget,
    /// Seed.
    pub seed: u64,
    /// Contact law for `eval`, if given.
    pub params: Option<bw_models::Physical>,
}

/// The loop fit `index` of the config in `dir`, validated.
pub(super) fn parse_loop_fit(
    ctx: &Ctx,
    dir: &Path,
    f: &Spanned<RawLoopFit>,
    index: usize,
) -> Result<LoopDraft, AppError> {
    let t = f.span();
    let r = f.get_ref();
    let name = r.name.as_ref().map_or_else(
        || format!("loop fit {}", index + 1),
        |n| n.get_ref().clone(),
    );
    let kind = match &r.model {
        Some(m) => model_kind(ctx, m, "[[loop_fit]].model")?,
        None => {
            return Err(ctx.invalid(
                &t,
                "[[loop_fit]].model",
                "missing required key: \"shccm\" or \"mcm\"",
            ))
        }
    };
    let m = ctx.req(&r.m, &t, "[[loop_fit]].m")?;
    if m <= 0.0 {
        return Err(ctx.invalid(
            &span(&r.m).unwrap_or(t.clone()),
            "[[loop_fit]].m",
            format!("{m} is not admissible: m > 0 (kg)"),
        ));
    }
    let sources = loop_sources(ctx, dir, r, &t)?;
    let space = law_space(ctx, r, kind, &name, &t)?;
    let params = match &r.params {
        None => None,
        Some(p) => Some(law_to_evaluate(ctx, p, kind)?),
    };
    let (budget, seed) = optimizer(ctx, &r.optimizer, "[loop_fit.optimizer]", index)?;
    Ok(LoopDraft {
        fit: LoopFitConfig {
            name,
            kind,
            m,
            loops: Vec::new(),
            space,
            budget,
            seed,
            params,
        },
        sources,
    })
}

/// Each loop's CSV file (relative to `dir`) and impact speed.
fn loop_sources(
    ctx: &Ctx,
    dir: &Path,
    r: &RawLoopFit,
    t: &Range<usize>,
) -> Result<Vec<(PathBuf, f64)>, AppError> {
    let refs = r.loops.as_ref().ok_or_else(|| {
        ctx.invalid(
            t,
            "[[loop_fit]].loops",
            "missing: [{ data = \"...csv\", v0 = ... }, ...]",
        )
    })?;
    let mut sources = Vec::new();
    for l in refs.get_ref() {
        let lr = l.get_ref();
        let v0 = ctx.num(&lr.v0, "[[loop_fit]].loops.v0")?;
        sources.push((dir.join(lr.data.get_ref()), v0));
    }
    if sources.is_empty() {
        return Err(ctx.invalid(&refs.span(), "[[loop_fit]].loops", "no loops"));
    }
    Ok(sources)
}

/// Which contact-law quantities are searched on a log scale (`log = [...]`).
fn log_scales(ctx: &Ctx, r: &RawLoopFit) -> Result<[bool; 8], AppError> {
    let mut log = [false; 8];
    for item in r.log.iter().flat_map(|l| l.get_ref()) {
        match LAW_NAMES.iter().position(|n| n == item.get_ref()) {
            Some(i) => log[i] = true,
            None => {
                return Err(ctx.invalid(
                    &item.span(),
                    "[[loop_fit]].log",
                    format!(
                        "\"{}\" is not a contact-law quantity: use {}",
                        item.get_ref(),
                        LAW_NAMES.join(", ")
                    ),
                ))
            }
        }
    }
    Ok(log)
}

/// The search space from `[loop_fit.bounds]` and `[loop_fit.fixed]`.
fn law_space(
    ctx: &Ctx,
    r: &RawLoopFit,
    kind: ModelKind,
    name: &str,
    t: &Range<usize>,
) -> Result<LawSpace, AppError> {
    let log = log_scales(ctx, r)?;
    let (empty_b, empty_v) = (RawLaw::default(), RawLaw::default());
    let b = r.bounds.as_ref().map_or(&empty_b, |b| b.get_ref());
    let v = r.fixed.as_ref().map_or(&empty_v, |v| v.get_ref());
    let bounds = [&b.k, &b.c, &b.n, &b.p, &b.alpha, &b.beta, &b.g, &b.a];
    let fixed = [&v.k, &v.c, &v.n, &v.p, &v.alpha, &v.beta, &v.g, &v.a];
    for (table, gamma) in [
        ("[loop_fit.bounds]", span(&b.gamma)),
        ("[loop_fit.fixed]", span(&v.gamma)),
    ] {
        if let Some(s) = gamma {
            return Err(ctx.invalid(
                &s,
                format!("{table}.gamma"),
                "give g = gamma / beta in [-1, 1] instead",
            ));
        }
    }
    let bounds_span = r.bounds.as_ref().map_or(t.clone(), |b| b.span());
    let mut params = [Param::Fixed(1.0); 8];
    // Every given bound is checked before the missing ones are reported, all at once.
    let mut missing = Vec::new();
    for (i, param) in params.iter_mut().enumerate() {
        let key = LAW_NAMES[i];
        match param_of(ctx, "loop_fit", key, bounds[i], fixed[i], log[i])? {
            Some(p) => *param = p,
            None => missing.push(key),
        }
    }
    if let Some(first) = missing.first() {
        return Err(ctx.invalid(
            &bounds_span,
            format!("[loop_fit.bounds].{first}"),
            format!(
                "missing {}: give each bounds in [loop_fit.bounds] or a value in \
                 [loop_fit.fixed]",
                missing.join(", ")
            ),
        ));
    }
    LawSpace::new(kind, params).map_err(|e| match e {
        IdentifyError::Bounds {
            name,
            lo,
            hi,
            allowed,
        } => {
            let i = LAW_NAMES.iter().position(|n| *n == name).unwrap_or(0);
            let (table, s) = if bounds[i].is_some() {
                ("[loop_fit.bounds]", span(bounds[i]))
            } else {
                ("[loop_fit.fixed]", span(fixed[i]))
            };
            ctx.invalid(
                &s.unwrap_or(t.clone()),
                format!("{table}.{name}"),
                format!("[{lo}, {hi}] is not admissible: {allowed}"),
            )
        }
        other => ctx.invalid(t, format!("[[loop_fit]] \"{name}\""), other.to_string()),
    })
}

/// The contact law of `[loop_fit.params]` (for `eval`), validated.
fn law_to_evaluate(
    ctx: &Ctx,
    p: &Spanned<RawLaw<Num>>,
    kind: ModelKind,
) -> Result<bw_models::Physical, AppError> {
    let q = p.get_ref();
    let fields = [&q.k, &q.c, &q.n, &q.p, &q.alpha, &q.beta, &q.gamma, &q.a];
    let (law, _) = contact_law(ctx, "[loop_fit.params]", &p.span(), fields, kind)?;
    Ok(law)
}

/// A `[[loop_fit]]` validated up to its loop files.
pub(super) struct LoopDraft {
    fit: LoopFitConfig,
    /// Each loop's CSV file and impact speed (m/s).
    sources: Vec<(std::path::PathBuf, f64)>,
}

impl LoopDraft {
    /// The fit's name.
    pub(super) fn name(&self) -> &str {
        &self.fit.name
    }

    /// Reads the loop files.
    ///
    /// # Errors
    /// [`AppError::Identify`] for a loop file's own errors (with its path and line).
    pub(super) fn with_data(self, ctx: &Ctx) -> Result<LoopFitConfig, AppError> {
        let mut fit = self.fit;
        for (path, v0) in &self.sources {
            let l = bwc_identify::Loop::load(path, *v0).map_err(|source| AppError::Identify {
                path: ctx.path.to_owned(),
                fit: fit.name.clone(),
                source,
            })?;
            fit.loops.push(l);
        }
        Ok(fit)
    }
}

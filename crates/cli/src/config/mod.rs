//! Identification configs: `[[fit]]` tables validated into search spaces and objectives.
//!
//! ```toml
//! [[fit]]
//! name = "DSS NDBWSHCCM"
//! model = "shccm"
//! data = "data/kharaz_dss.csv"       # relative to the config
//! objectives = { J1 = 1.0 }           # weights of J1 (CoR) and J2 (duration)
//! log = ["sigma_b"]                   # quantities searched on a log scale
//! [fit.bounds]                        # B_b, g = Gamma_b / B_b, kappa, sigma_b, n, p, U_b, T_b
//! B_b = [0.0, 5.0]
//! [fit.fixed]                         # values held fixed
//! [fit.input]                         # physical input u(t), as in scenes
//! [fit.known]                         # m, k: T_b = m U_b and (m/k) kappa / T_b^(p+1) <= 1
//! [fit.optimizer]                     # particles, iterations, polish, starts, seed
//! [fit.solver]                        # search accuracy (default rtol 1e-8)
//! [fit.start]                         # optional starting point (full P*)
//! [fit.params]                        # P* for `bwc-identify eval`
//! [fit.pareto]                        # count: weights of a Pareto sweep over (J1, J2)
//! ```

mod describe;
mod fit;
mod loops;

pub use loops::LoopFitConfig;

use crate::signal::Signal;
use crate::tables::{Ctx, Num, RawInput, RawSolver};
use crate::CliError;
use bw_models::{BaseParams, ModelKind, Settings};
use bwc_identify::{Budget, Dataset, Param, Space, Weights};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use toml::Spanned;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    fit: Option<Vec<Spanned<RawFit>>>,
    loop_fit: Option<Vec<Spanned<loops::RawLoopFit>>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFit {
    name: Option<Spanned<String>>,
    model: Option<Spanned<String>>,
    data: Option<Spanned<String>>,
    objectives: Option<Spanned<RawObjectives>>,
    log: Option<Spanned<Vec<Spanned<String>>>>,
    bounds: Option<Spanned<RawQuantities<Pair>>>,
    fixed: Option<Spanned<RawQuantities<Num>>>,
    start: Option<Spanned<RawPoint>>,
    params: Option<Spanned<RawPoint>>,
    input: Option<Spanned<RawInput>>,
    known: Option<Spanned<RawKnown>>,
    optimizer: Option<Spanned<RawOptimizer>>,
    solver: Option<Spanned<RawSolver>>,
    pareto: Option<Spanned<RawPareto>>,
    sequence: Option<Spanned<RawDropSequence>>,
}

/// `[fit.sequence]` of a drop-test fit: the ball's mass, gravity and air drag.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDropSequence {
    m: Option<Num>,
    g: Option<Num>,
    drag: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawObjectives {
    #[serde(rename = "J1")]
    j1: Option<Num>,
    #[serde(rename = "J2")]
    j2: Option<Num>,
}

type Pair = Spanned<Vec<Num>>;

/// Searchable base quantities (`g = Gamma_b / B_b`): bounds (`T = Pair`) or fixed values.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawQuantities<T> {
    #[serde(rename = "B_b")]
    b_b: Option<T>,
    g: Option<T>,
    kappa: Option<T>,
    sigma_b: Option<T>,
    n: Option<T>,
    p: Option<T>,
    #[serde(rename = "U_b")]
    u_b: Option<T>,
    #[serde(rename = "T_b")]
    t_b: Option<T>,
}

impl<T> Default for RawQuantities<T> {
    fn default() -> Self {
        Self {
            b_b: None,
            g: None,
            kappa: None,
            sigma_b: None,
            n: None,
            p: None,
            u_b: None,
            t_b: None,
        }
    }
}

impl<T> RawQuantities<T> {
    /// The entries in the order of [`NAMES`].
    fn by_name(&self) -> [&Option<T>; 8] {
        [
            &self.b_b,
            &self.g,
            &self.kappa,
            &self.sigma_b,
            &self.n,
            &self.p,
            &self.u_b,
            &self.t_b,
        ]
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPoint {
    #[serde(rename = "B_b")]
    b_b: Option<Num>,
    #[serde(rename = "Gamma_b")]
    gamma_b: Option<Num>,
    kappa: Option<Num>,
    sigma_b: Option<Num>,
    n: Option<Num>,
    p: Option<Num>,
    #[serde(rename = "U_b")]
    u_b: Option<Num>,
    #[serde(rename = "T_b")]
    t_b: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawKnown {
    m: Option<Num>,
    k: Option<Num>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOptimizer {
    particles: Option<Spanned<i64>>,
    iterations: Option<Spanned<i64>>,
    polish: Option<Spanned<i64>>,
    starts: Option<Spanned<i64>>,
    max_starts: Option<Spanned<i64>>,
    agree: Option<Spanned<i64>>,
    tolerance: Option<Num>,
    seed: Option<Spanned<i64>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPareto {
    count: Option<Spanned<i64>>,
}

/// One validated fit.
#[derive(Debug, Clone)]
pub struct FitConfig {
    /// Name (unique in the config).
    pub name: String,
    /// The model.
    pub kind: ModelKind,
    /// The measurements.
    pub data: Dataset,
    /// The search space.
    pub space: Space,
    /// Physical input `u(t)` (N).
    pub input: Signal,
    /// Weights of `J1` and `J2`.
    pub weights: Weights,
    /// Optimizer budget.
    pub budget: Budget,
    /// Seed of this fit (combined with `--seed`).
    pub seed: u64,
    /// Solver settings of the search.
    pub settings: Settings,
    /// Starting point on the unit cube, if given.
    pub start: Option<Vec<f64>>,
    /// Parameters for `eval`, if given.
    pub params: Option<BaseParams>,
    /// Whether `U_b`, `T_b` matter (an input, a duration objective, or a known mass).
    pub uses_input_scales: bool,
    /// Number of weights of a Pareto sweep, if asked for.
    pub pareto: Option<usize>,
    /// For a drop-test fit (data of intervals or rebound heights): the data and the physics
    /// around the contacts; `data` is then empty.
    pub drops: Option<DropFit>,
}

/// The drop tests of a `[[fit]]` and `[fit.sequence]`.
#[derive(Debug, Clone)]
pub struct DropFit {
    /// Intervals or rebound heights.
    pub data: bwc_identify::DropData,
    /// Mass, gravity, drag, and whether contacts are timed and forced.
    pub setup: bwc_identify::DropSetup,
}

/// A validated config.
#[derive(Debug, Clone)]
pub struct Config {
    /// The file.
    pub path: PathBuf,
    /// The fits of base parameters to CoR / duration data, in file order.
    pub fits: Vec<FitConfig>,
    /// The fits of contact laws to hysteresis loops, in file order.
    pub loop_fits: Vec<LoopFitConfig>,
}

fn count(
    ctx: &Ctx,
    v: &Option<Spanned<i64>>,
    key: &str,
    min: i64,
    max: i64,
    default: i64,
) -> Result<i64, CliError> {
    match v {
        None => Ok(default),
        Some(x) if (min..=max).contains(x.get_ref()) => Ok(*x.get_ref()),
        Some(x) => Err(ctx.invalid(
            &x.span(),
            key,
            format!("{} is not admissible: {min} <= {key} <= {max}", x.get_ref()),
        )),
    }
}

impl Config {
    /// Reads and validates a config and its data files.
    ///
    /// # Errors
    /// [`CliError::Io`], [`CliError::Syntax`] and [`CliError::Invalid`] as for scenes;
    /// [`CliError::Identify`] for a data file's own errors (with its path and line).
    pub fn load(path: &Path) -> Result<Self, CliError> {
        Self::parse(path, &crate::tables::read_text(path)?)
    }

    /// Validates a config given as text; data files are read relative to `path`'s folder.
    ///
    /// # Errors
    /// As [`Config::load`]; a file with several mistakes reports them all ([`CliError::Many`]).
    pub fn parse(path: &Path, src: &str) -> Result<Self, CliError> {
        crate::tables::every_error(src, |text| Self::parse_one(path, text))
    }

    /// Validates the text, stopping at its first mistake.
    fn parse_one(path: &Path, src: &str) -> Result<Self, CliError> {
        let ctx = Ctx { path, src };
        let raw: RawConfig =
            toml::from_str(src).map_err(|e| crate::tables::syntax_error(&ctx, &e))?;
        let fits = raw.fit.unwrap_or_default();
        let loop_fits = raw.loop_fit.unwrap_or_default();
        if fits.is_empty() && loop_fits.is_empty() {
            return Err(ctx.invalid(
                &(0..0),
                "[[fit]]",
                "no fits: add at least one [[fit]] or [[loop_fit]] table",
            ));
        }
        let dir = path.parent().unwrap_or(Path::new("."));
        let mut drafts: Vec<fit::Draft> = Vec::new();
        for (i, f) in fits.iter().enumerate() {
            let draft = fit::parse_fit(&ctx, dir, f, i)?;
            if drafts.iter().any(|o| o.name() == draft.name()) {
                return Err(ctx.invalid(
                    &f.span(),
                    "[[fit]].name",
                    format!("\"{}\" is used twice: names must be unique", draft.name()),
                ));
            }
            drafts.push(draft);
        }
        let mut loop_drafts: Vec<loops::LoopDraft> = Vec::new();
        for (i, f) in loop_fits.iter().enumerate() {
            let fit = loops::parse_loop_fit(&ctx, dir, f, i)?;
            if drafts.iter().any(|o| o.name() == fit.name())
                || loop_drafts.iter().any(|o| o.name() == fit.name())
            {
                return Err(ctx.invalid(
                    &f.span(),
                    "[[loop_fit]].name",
                    format!("\"{}\" is used twice: names must be unique", fit.name()),
                ));
            }
            loop_drafts.push(fit);
        }
        // The data files are read once the whole config has parsed.
        let out = drafts
            .into_iter()
            .map(|d| d.with_data(&ctx))
            .collect::<Result<Vec<_>, _>>()?;
        let loops_out = loop_drafts
            .into_iter()
            .map(|d| d.with_data(&ctx))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Config {
            path: path.to_owned(),
            fits: out,
            loop_fits: loops_out,
        })
    }
}

fn optimizer(
    ctx: &Ctx,
    o: &Option<Spanned<RawOptimizer>>,
    table: &str,
    index: usize,
) -> Result<(Budget, u64), CliError> {
    let empty = RawOptimizer {
        particles: None,
        iterations: None,
        polish: None,
        starts: None,
        max_starts: None,
        agree: None,
        tolerance: None,
        seed: None,
    };
    let r = o.as_ref().map_or(&empty, |o| o.get_ref());
    let d = Budget::default();
    let key = |k: &str| format!("{table}.{k}");
    let n = |v: &Option<Spanned<i64>>, k: &str, min: i64, max: i64, default: usize| {
        count(ctx, v, &key(k), min, max, default as i64).map(|x| x as usize)
    };
    let starts = n(&r.starts, "starts", 1, 1_000, d.starts)?;
    // An explicit `starts` alone keeps the old meaning: exactly that many starts.
    let max_default = if r.starts.is_some() && r.max_starts.is_none() {
        starts
    } else {
        d.max_starts.max(starts)
    };
    let max_starts = n(
        &r.max_starts,
        "max_starts",
        starts as i64,
        1_000,
        max_default,
    )?;
    let agree = n(
        &r.agree,
        "agree",
        1,
        max_starts as i64,
        d.agree.min(max_starts),
    )?;
    let tolerance = agreement(ctx, &r.tolerance, &key("tolerance"), d.tolerance)?;
    let budget = Budget {
        particles: n(&r.particles, "particles", 2, 10_000, d.particles)?,
        iterations: n(
            &r.iterations,
            "iterations",
            0,
            1_000_000,
            d.iterations as usize,
        )? as u64,
        polish_iterations: n(
            &r.polish,
            "polish",
            0,
            1_000_000,
            d.polish_iterations as usize,
        )? as u64,
        starts,
        max_starts,
        agree,
        tolerance,
    };
    Ok((
        budget,
        count(ctx, &r.seed, &key("seed"), 0, i64::MAX, index as i64)? as u64,
    ))
}

/// `[fit.optimizer].tolerance`: how close (relative) the costs of starts that agree are.
fn agreement(ctx: &Ctx, v: &Option<Num>, key: &str, default: f64) -> Result<f64, CliError> {
    match ctx.opt(v, key)? {
        None => Ok(default),
        Some(t) if (0.0..=1.0).contains(&t) => Ok(t),
        Some(t) => {
            let span = v.as_ref().map(|x| x.span()).unwrap_or_default();
            Err(ctx.invalid(
                &span,
                key,
                format!("{t} is not admissible: 0 <= tolerance <= 1 (relative)"),
            ))
        }
    }
}

/// A searchable quantity from `[<table>.bounds].key = [lo, hi]` or `[<table>.fixed].key`
/// (`None` when neither is given).
fn param_of(
    ctx: &Ctx,
    table: &str,
    key: &str,
    bound: &Option<Pair>,
    fixed: &Option<Num>,
    log: bool,
) -> Result<Option<Param>, CliError> {
    match (bound, fixed) {
        (Some(_), Some(x)) => Err(ctx.invalid(
            &x.span(),
            format!("[{table}.fixed].{key}"),
            "both bounded and fixed: give one",
        )),
        (Some(pair), None) => {
            let name = format!("[{table}.bounds].{key}");
            if pair.get_ref().len() != 2 {
                return Err(ctx.invalid(&pair.span(), name, "give [lower, upper]"));
            }
            let lo = ctx.num(&pair.get_ref()[0], &name)?;
            let hi = ctx.num(&pair.get_ref()[1], &name)?;
            Ok(Some(Param::Free { lo, hi, log }))
        }
        (None, Some(x)) => Ok(Some(Param::Fixed(
            ctx.num(x, &format!("[{table}.fixed].{key}"))?,
        ))),
        (None, None) => Ok(None),
    }
}

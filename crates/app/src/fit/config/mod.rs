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
//! [fit.posterior]                     # particles, runs, noise, sigma_e, sigma_t, draws
//! [fit.prior]                         # kappa = { normal = [mean, sd] }, ...
//! ```

mod describe;
mod family;
mod fit;
mod loops;
mod posterior;
mod search;

pub use loops::LoopFitConfig;
pub use posterior::PosteriorConfig;

use crate::signal::Signal;
use crate::tables::{Ctx, Num, RawInput, RawSolver};
use crate::AppError;
use bw_models::{BaseParams, Family, ModelKind, Settings};
use bwc_identify::{Budget, Dataset, Space, Weights, NAMES};
use search::{Pair, RawOptimizer};
use serde::Deserialize;
use std::collections::BTreeMap;
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
    reference: Option<Spanned<RawPoint>>,
    input: Option<Spanned<RawInput>>,
    known: Option<Spanned<RawKnown>>,
    optimizer: Option<Spanned<RawOptimizer>>,
    solver: Option<Spanned<RawSolver>>,
    pareto: Option<Spanned<RawPareto>>,
    sequence: Option<Spanned<RawDropSequence>>,
    posterior: Option<Spanned<posterior::RawPosterior>>,
    prior: Option<posterior::RawPriors>,
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

/// Searchable base quantities (`g = Gamma_b / B_b`) and the families' parameters
/// ([`Family::param_names`]): bounds (`T = Pair`) or fixed values. Any other key is an error
/// that lists the admissible ones.
#[derive(Debug, Deserialize)]
#[serde(
    try_from = "BTreeMap<String, T>",
    bound(deserialize = "T: Deserialize<'de>")
)]
struct RawQuantities<T> {
    /// The Bouc-Wen quantities, in the order of [`NAMES`].
    base: [Option<T>; 8],
    /// The families' parameters by name.
    family: BTreeMap<&'static str, T>,
}

impl<T> Default for RawQuantities<T> {
    fn default() -> Self {
        Self {
            base: std::array::from_fn(|_| None),
            family: BTreeMap::new(),
        }
    }
}

impl<T> TryFrom<BTreeMap<String, T>> for RawQuantities<T> {
    type Error = String;

    fn try_from(map: BTreeMap<String, T>) -> Result<Self, String> {
        let mut q = Self::default();
        let family = Family::param_names();
        for (key, value) in map {
            if let Some(i) = NAMES.iter().position(|n| *n == key) {
                q.base[i] = Some(value);
            } else if let Some(n) = family.iter().find(|n| **n == key) {
                q.family.insert(n, value);
            } else {
                let known: Vec<String> = NAMES
                    .iter()
                    .chain(&family)
                    .map(|n| format!("`{n}`"))
                    .collect();
                return Err(format!(
                    "unknown field `{key}`, expected one of {}",
                    known.join(", ")
                ));
            }
        }
        Ok(q)
    }
}

impl<T> RawQuantities<T> {
    /// A family's parameter by name ([`Family::param_name`]).
    fn family_entry(&self, name: &str) -> Option<&T> {
        self.family.get(name)
    }

    /// The names of every quantity given (Bouc-Wen and family parameters alike).
    fn given(&self) -> Vec<&'static str> {
        NAMES
            .iter()
            .zip(&self.base)
            .filter(|(_, v)| v.is_some())
            .map(|(n, _)| *n)
            .chain(self.family.keys().copied())
            .collect()
    }

    /// The entries in the order of [`NAMES`].
    fn by_name(&self) -> [&Option<T>; 8] {
        std::array::from_fn(|i| &self.base[i])
    }

    /// `T_b`, given for a family's fit.
    fn t_b(&self) -> &Option<T> {
        &self.base[7]
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
    /// What the point is (`[fit.reference]` and `[fit.params]`), e.g. "Table 3, DSS (1)".
    label: Option<Spanned<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawKnown {
    m: Option<Num>,
    k: Option<Num>,
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
    /// The vector `run` reports beside the fit: `[fit.reference]`, or else `[fit.params]`.
    pub reference: Option<Reference>,
    /// Whether `U_b`, `T_b` matter (an input, a duration objective, or a known mass).
    pub uses_input_scales: bool,
    /// Values of the fit's table whose magnitude suggests a unit slip
    /// ([`crate::plausible`]); reported with the fit's warnings.
    pub hints: Vec<String>,
    /// Number of weights of a Pareto sweep, if asked for.
    pub pareto: Option<usize>,
    /// For a drop-test fit (data of intervals or rebound heights): the data and the physics
    /// around the contacts; `data` is then empty.
    pub drops: Option<DropFit>,
    /// How `bwc-identify posterior` samples the fit (`[fit.posterior]`, `[fit.prior]`).
    pub posterior: PosteriorConfig,
    /// The contact-law family fitted instead of a Bouc-Wen model, if any (`kind` is then
    /// unused).
    pub family: Option<bw_models::Family>,
}

impl RawFit {
    /// Every quantity `[fit.bounds]` and `[fit.fixed]` give: the table, the name and the
    /// table's span.
    fn given_quantities(&self) -> Vec<(&'static str, &'static str, std::ops::Range<usize>)> {
        let bounds = self.bounds.iter().flat_map(|b| {
            b.get_ref()
                .given()
                .into_iter()
                .map(|n| ("bounds", n, b.span()))
        });
        let fixed = self.fixed.iter().flat_map(|v| {
            v.get_ref()
                .given()
                .into_iter()
                .map(|n| ("fixed", n, v.span()))
        });
        bounds.chain(fixed).collect()
    }
}

impl FitConfig {
    /// The model's name as the config gives it: `"shccm"`, `"mcm"` or a family's.
    pub fn model_name(&self) -> &'static str {
        self.family.map_or(self.kind.name(), |f| f.name())
    }
}

/// A reference vector of a fit (a published fit, an earlier one): `run` reports its cost on the
/// same data beside the fit's.
#[derive(Debug, Clone, PartialEq)]
pub struct Reference {
    /// What it is: `[fit.reference].label`, or the table it came from.
    pub label: String,
    /// The base parameters.
    pub params: BaseParams,
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

impl Config {
    /// Reads and validates a config and its data files.
    ///
    /// # Errors
    /// [`AppError::Io`], [`AppError::Syntax`] and [`AppError::Invalid`] as for scenes;
    /// [`AppError::Identify`] for a data file's own errors (with its path and line).
    pub fn load(path: &Path) -> Result<Self, AppError> {
        Self::parse(path, &crate::tables::read_text(path)?)
    }

    /// Validates a config given as text; data files are read relative to `path`'s folder.
    ///
    /// # Errors
    /// As [`Config::load`]; a file with several mistakes reports them all ([`AppError::Many`]).
    pub fn parse(path: &Path, src: &str) -> Result<Self, AppError> {
        crate::tables::every_error(src, |text| Self::parse_one(path, text))
    }

    /// Validates the text, stopping at its first mistake.
    fn parse_one(path: &Path, src: &str) -> Result<Self, AppError> {
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

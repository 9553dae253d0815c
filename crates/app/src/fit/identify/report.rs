//! What a fit reports ([`FitReport`], [`LoopReport`]): its parameters, costs, predictions,
//! uncertainty and warnings, with the settings of the evaluations that report it and the
//! errors of a fit.

use crate::fit::config::FitConfig;
use crate::AppError;
use bw_models::{BaseParams, Settings};
use bwc_identify::{
    BandPoint, Convergence, Costs, DropKind, DropRow, Identifiability, Prediction, Uncertainty,
};
use std::path::Path;

/// The settings of the evaluations that report a fit (costs, predictions, bands, loops,
/// coverage truths): one run at rtol 1e-11, atol 1e-13. Its error in `e` (at most 1e-12 on the
/// work-precision cases, BENCHMARKS.md) is far below any dataset's, and checking each CoR to
/// the defaults' `e_tol` would double the cost of these evaluations (BENCHMARKS.md, "Identification: time").
pub(crate) fn reporting() -> Settings {
    Settings {
        rtol: 1e-11,
        atol: 1e-13,
        e_tol: None,
        ..Settings::default()
    }
}

/// One point of a Pareto front.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoPoint {
    /// Weight of the normalised `J1` (that of `J2` is `1 - w`).
    pub w: f64,
    /// `J1` at the optimum of this weight.
    pub j1: f64,
    /// `J2` at the optimum of this weight.
    pub j2: f64,
    /// The optimum.
    pub params: BaseParams,
    /// A contact-law family's optimum, under its own names.
    pub family: Option<bw_models::FamilyParams>,
}

/// The result of one fit (or one evaluation).
#[derive(Debug, Clone)]
pub struct FitReport {
    /// Fit name.
    pub name: String,
    /// `"shccm"` or `"mcm"`.
    pub model: &'static str,
    /// Base parameters (of a family's fit, the search's slots: see `family`).
    pub params: BaseParams,
    /// A contact-law family's fitted law, under its own names.
    pub family: Option<bw_models::FamilyParams>,
    /// Whether `U_b`, `T_b` are meaningful (otherwise reported as null).
    pub uses_input_scales: bool,
    /// Costs at the default (accurate) solver settings.
    pub costs: Costs,
    /// Cost evaluations.
    pub evaluations: u64,
    /// Wall time (s).
    pub wall_s: f64,
    /// Model predictions at the data points.
    pub predictions: Vec<Prediction>,
    /// Identifiability at the optimum (runs only).
    pub identifiability: Option<Identifiability>,
    /// How the search ended (runs only).
    pub convergence: Option<Convergence>,
    /// Free quantities on a bound of the search (runs only).
    pub at_bound: Vec<&'static str>,
    /// Pareto front, if asked for.
    pub pareto: Vec<ParetoPoint>,
    /// Confidence intervals (runs only), or why there are none.
    pub uncertainty: Option<Result<Uncertainty, String>>,
    /// The model (with its band, where there are intervals) on a log grid from half the
    /// slowest to twice the fastest measured speed.
    pub curve: Vec<BandPoint>,
    /// The band at the data points, in data order (empty without intervals).
    pub band: Vec<BandPoint>,
    /// Warnings about this fit: data, convergence, bounds, intervals.
    pub warnings: Vec<String>,
    /// For a drop-test fit: `J_drop` and the rows with the model's values.
    pub drop: Option<DropOutcome>,
    /// The reference vector beside the fit (runs of fits that name one).
    pub reference: Option<super::ReferenceReport>,
}

/// `eval` needs the parameters of `table` (`[fit.params]`, `[loop_fit.params]`) of fit `name`.
pub(crate) fn missing_params(config: &Path, table: &str, name: &str) -> AppError {
    AppError::Invalid {
        path: config.to_owned(),
        line: 1,
        key: format!("{table} of \"{name}\""),
        message: "missing: `eval` needs the parameters to evaluate".into(),
    }
}

/// Warnings on how a search ended (`s` the optimum on the unit cube).
pub(crate) fn search_warnings(
    f: &FitConfig,
    c: &Convergence,
    at_bound: &[usize],
    s: &[f64],
) -> Vec<String> {
    let mut w = Vec::new();
    // Nothing free: nothing was searched.
    if c.agreeing < 2 && f.space.dim() > 0 {
        w.push(format!(
            "\"{}\": only {} of {} starts reached the best cost within {} % (counted once per \
             region of the box their polishes began in): the optimum may not be global; raise \
             [fit.optimizer].max_starts",
            f.name,
            c.agreeing,
            c.starts,
            f.budget.tolerance * 100.0
        ));
    }
    let values = f.space.quantities(s);
    // A searched quantity by its position in the search (`j`) and among the quantities (`i`):
    // a comparison law's parameters have names of their own in a Bouc-Wen slot.
    let names = f.space.free_names();
    for (j, &i) in f.space.free_indices().iter().enumerate() {
        let name = names[j];
        if !at_bound.contains(&j) {
            continue;
        }
        let (lo, hi) = f.space.bounds(i).unwrap_or((f64::NAN, f64::NAN));
        let value = values[i];
        let upper = s[j] >= 0.5;
        if upper && f.space.on_constraint(i, s) {
            w.push(format!(
                "\"{}\": {name} = {value} is on the constraint (m/k) kappa / T_b^(p+1) <= 1 of \
                 [fit.known]",
                f.name
            ));
            continue;
        }
        let (side, bound) = if upper { ("upper", hi) } else { ("lower", lo) };
        match f.space.model_limit(i, bound) {
            Some(allowed) => w.push(format!(
                "\"{}\": {name} = {value} is on its {side} bound {bound}, the model's own limit \
                 ({allowed}): the data want {name} at or beyond it, where the law cannot go; the \
                 fit is the best the model allows there",
                f.name
            )),
            None => w.push(format!(
                "\"{}\": {name} = {value} is on its {side} bound {bound}: widen \
                 [fit.bounds].{name} if the model allows",
                f.name
            )),
        }
    }
    w
}

/// Wraps a library error of the fit named `name` in the config at `path`.
pub(crate) fn fail<'a>(
    path: &'a Path,
    name: &'a str,
) -> impl Fn(bwc_identify::IdentifyError) -> AppError + 'a {
    move |source| AppError::Identify {
        path: path.to_owned(),
        fit: name.to_owned(),
        source,
    }
}

/// The result of one loop fit (or evaluation).
#[derive(Debug, Clone)]
pub struct LoopReport {
    /// Fit name.
    pub name: String,
    /// `"shccm"` or `"mcm"`.
    pub model: &'static str,
    /// The contact law (SI).
    pub law: bw_models::Physical,
    /// Loop cost at the law (see `bwc_identify::loop_cost`).
    pub cost: f64,
    /// Cost evaluations.
    pub evaluations: u64,
    /// Wall time (s).
    pub wall_s: f64,
    /// Simulated loops, one per measured loop.
    pub curves: Vec<bwc_identify::Curve>,
    /// How the search ended (runs only).
    pub convergence: Option<Convergence>,
    /// Free quantities on a bound of the search (runs only).
    pub at_bound: Vec<&'static str>,
}

impl LoopReport {
    /// Its warnings: a search whose starts did not agree, quantities on a bound.
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        if let Some(c) = self.convergence.as_ref().filter(|c| c.agreeing < 2) {
            w.push(format!(
                "\"{}\": only {} of {} starts reached the best cost within the tolerance: the \
                 optimum may not be global; raise [loop_fit.optimizer].max_starts",
                self.name, c.agreeing, c.starts
            ));
        }
        for name in &self.at_bound {
            w.push(format!(
                "\"{}\": {name} is on a bound of [loop_fit.bounds]",
                self.name
            ));
        }
        w
    }
}

/// The drop-test part of a report: the cost and every row with the model's value.
#[derive(Debug, Clone)]
pub struct DropOutcome {
    /// Intervals or heights.
    pub kind: DropKind,
    /// `J_drop` at the default (accurate) solver settings.
    pub cost: f64,
    /// Each measured row and the model's value (s or m; NaN where the sequence ended first).
    pub rows: Vec<(DropRow, f64)>,
}

impl DropOutcome {
    /// The unit of `J_drop`.
    pub fn unit(&self) -> &'static str {
        match self.kind {
            DropKind::Intervals => "s^2",
            DropKind::Heights => "m^2",
        }
    }
}

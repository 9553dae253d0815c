//! A fit beside its reference vector (`[fit.reference]` or `[fit.params]`): the reference's
//! cost on the same data, its curve, and a sentence on what the comparison means.
//!
//! The comparison is made in the search's unit-cube coordinates (each free quantity relative
//! to its bounds, on a log scale where the search is): the difference `d` between the two
//! points is split along the right singular vectors of the fit's sensitivity matrix
//! ([`bwc_identify::Identifiability`]). The share of `|d|²` along the directions whose
//! singular value is below [`bwc_identify::WEAK`] times the largest says whether the two
//! vectors differ in what the data leave undetermined.

use crate::fit::config::{FitConfig, Reference};
use bw_models::BaseParams;
use bwc_identify::{BandPoint, Costs, Identifiability, Weights};

/// Two costs within this relative difference count as equal.
const SAME_COST: f64 = 1e-2;

/// How the reference's cost compares with the fit's.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Standing {
    /// The fit's cost is lower by more than 1 %.
    FitLower,
    /// Within 1 % of each other.
    Equal,
    /// The reference's cost is lower by more than 1 %: the search missed its basin.
    ReferenceLower,
}

impl Standing {
    /// Its name in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Standing::FitLower => "fit_lower",
            Standing::Equal => "equal",
            Standing::ReferenceLower => "reference_lower",
        }
    }
}

/// The reference vector evaluated on the fit's data and compared with the fit.
#[derive(Debug, Clone)]
pub struct ReferenceReport {
    /// What it is (`[fit.reference].label`, or the table it came from).
    pub label: String,
    /// Its base parameters.
    pub params: BaseParams,
    /// Its costs on the fit's data, at the reporting settings.
    pub costs: Costs,
    /// Its weighted cost over the fit's (the objective's weights; `J_drop` for drop tests).
    pub cost_ratio: f64,
    /// How the two costs compare.
    pub standing: Standing,
    /// Free quantities of the reference outside the fit's bounds (compared at the bound).
    pub outside_bounds: Vec<&'static str>,
    /// Share (0 to 1) of the squared distance between the two points, in unit-cube
    /// coordinates, along the weakly determined directions; `None` without an identifiability
    /// analysis or where the points coincide.
    pub weak_share: Option<f64>,
    /// How many directions are weakly determined, of how many.
    pub weak_directions: (usize, usize),
    /// The quantities that dominate the weakly determined directions.
    pub weak_names: Vec<&'static str>,
    /// The model at the reference on the fit's curve speeds: `(v0, e, t_d)`.
    pub curve: Vec<BandPoint>,
    /// What the comparison means, in words.
    pub summary: String,
}

impl ReferenceReport {
    /// Where the reference costs less than the fit, why and what helps: bounds that exclude
    /// it, or a search that missed its basin.
    pub fn remedy(&self) -> String {
        if self.outside_bounds.is_empty() {
            "the search missed the reference's basin; raise [fit.optimizer].max_starts or \
             particles"
                .into()
        } else {
            format!(
                "the reference lies outside [fit.bounds] in {}; widen them to let the search \
                 reach it",
                self.outside_bounds.join(", ")
            )
        }
    }
}

/// The weighted cost the fit minimised (`None` where a weighted term has no value).
fn weighted(costs: &Costs, w: Weights) -> Option<f64> {
    let term = |j: Option<f64>, w: f64| if w > 0.0 { j.map(|j| w * j) } else { Some(0.0) };
    Some(term(costs.j1, w.j1)? + term(costs.j2, w.j2)?)
}

/// What was compared, for the sentence: the cost's name and its value at each vector.
pub(crate) struct CostPair {
    /// `J1`, `J2`, `J1 + J2` weighted, or `J_drop`.
    pub name: String,
    /// The reference's cost.
    pub reference: f64,
    /// The fit's cost.
    pub fit: f64,
}

impl CostPair {
    /// The pair of a CoR / duration fit with weights `w`.
    pub fn of(w: Weights, reference: &Costs, fit: &Costs) -> Option<Self> {
        let name = match (w.j1 > 0.0, w.j2 > 0.0) {
            (true, false) => "J1",
            (false, true) => "J2",
            _ => "the weighted cost",
        };
        Some(Self {
            name: name.into(),
            reference: weighted(reference, w)?,
            fit: weighted(fit, w)?,
        })
    }
}

/// The comparison of `reference` with the fit at the unit-cube point `s` (costs `pair`).
pub(crate) fn compare(
    f: &FitConfig,
    reference: &Reference,
    costs: Costs,
    pair: &CostPair,
    (s, identifiability): (&[f64], Option<&Identifiability>),
    curve: Vec<BandPoint>,
) -> ReferenceReport {
    let ratio = pair.reference / pair.fit;
    let standing = if pair.reference < pair.fit * (1.0 - SAME_COST) {
        Standing::ReferenceLower
    } else if pair.reference > pair.fit * (1.0 + SAME_COST) {
        Standing::FitLower
    } else {
        Standing::Equal
    };
    let (point, outside_bounds) = f.space.nearest_point(&reference.params).unwrap_or_default();
    let d: Vec<f64> = point.iter().zip(s).map(|(a, b)| a - b).collect();
    let weak_share = identifiability.and_then(|id| id.weak_share(&d));
    let weak_directions = identifiability.map_or((0, 0), |id| (id.weak_count(), id.names.len()));
    let weak_names = identifiability.map_or_else(Vec::new, |id| id.weak_names());
    let mut r = ReferenceReport {
        label: reference.label.clone(),
        params: reference.params,
        costs,
        cost_ratio: ratio,
        standing,
        outside_bounds,
        weak_share,
        weak_directions,
        weak_names,
        curve,
        summary: String::new(),
    };
    r.summary = sentence(&r, pair);
    r
}

/// What the comparison means: which vector fits better, and whether they differ in what the
/// data determine.
fn sentence(r: &ReferenceReport, pair: &CostPair) -> String {
    let cost = format!(
        "The reference ({}) has {} = {:.3e} on the same data",
        r.label, pair.name, pair.reference
    );
    // J1 is a mean square: its root is the typical error in e, which a reader can judge.
    let rms = if pair.name == "J1" {
        format!(
            " (an RMS error in e of {:.1e} against {:.1e})",
            pair.reference.sqrt(),
            pair.fit.sqrt()
        )
    } else {
        String::new()
    };
    let mut s = match r.standing {
        Standing::FitLower => format!(
            "{cost}, {} times the fit's {:.3e}{rms}: the fit reproduces these data better.",
            sig2(r.cost_ratio),
            pair.fit
        ),
        Standing::Equal => format!(
            "{cost}, within 1 % of the fit's {:.3e}: both reproduce these data equally well.",
            pair.fit
        ),
        Standing::ReferenceLower => {
            format!("{cost}, below the fit's {:.3e}: {}.", pair.fit, r.remedy())
        }
    };
    let (weak, of) = r.weak_directions;
    match r.weak_share {
        Some(share) if weak > 0 && share >= 0.5 => s.push_str(&format!(
            " {:.0} % of the difference between the two vectors lies along the {weak} of {of} \
             directions the data determine least ({}): the data do not single out one vector, \
             so vectors far apart reproduce them about equally well.",
            100.0 * share,
            r.weak_names.join(", ")
        )),
        Some(share) if weak > 0 => s.push_str(&format!(
            " Only {:.0} % of the difference between the two vectors lies along the {weak} of \
             {of} directions the data determine least ({}): the vectors differ in what the data \
             do determine.",
            100.0 * share,
            r.weak_names.join(", ")
        )),
        Some(_) => s.push_str(
            " The data determine every direction (all singular values within a factor 100 of \
             the largest): the vectors differ in what the data do determine.",
        ),
        None => {}
    }
    if !r.outside_bounds.is_empty() && r.standing != Standing::ReferenceLower {
        s.push_str(&format!(
            " The reference lies outside [fit.bounds] in {} (compared at the nearest bound).",
            r.outside_bounds.join(", ")
        ));
    }
    s
}

/// `x` with two significant digits, in plain notation up to 10,000.
fn sig2(x: f64) -> String {
    if x.abs() < 1e4 && x != 0.0 {
        let e = x.abs().log10().floor() as i32;
        let unit = 10f64.powi(e - 1);
        let rounded = (x / unit).round() * unit;
        let digits = (1 - e).max(0) as usize;
        format!("{rounded:.digits$}")
    } else {
        format!("{x:.1e}")
    }
}

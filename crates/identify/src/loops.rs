//! Hysteresis-loop fitting in SI units (the paper's Cross study, Section 7.3): find the contact
//! law `(k, c, n, p, α, β, γ, A)` of a model with known mass `m` whose force-compression loops
//! match measured ones at several impact speeds.
//!
//! Cost: each loop (measured and simulated, chronological from impact to separation) is
//! parametrised by its normalised arc length in coordinates scaled by the measured maxima
//! (`x / max|x|`, `F / max F`); a measured point at arc fraction `τ` is compared with the
//! simulated loop at the same fraction. The cost is the mean squared distance over the points,
//! averaged over the loops (0 for identical loops, about 1 for unrelated ones). It needs no
//! timing of the measured points, so digitised loops can be used as they are.

use crate::csv_file::{self, CsvText};
use crate::error::IdentifyError;
use crate::problem::CubeProblem;
use crate::space::{values_at, Param};
use bw_models::input::Zero;
use bw_models::{
    nondimensionalize, simulate, Bwmcm, Bwshccm, CollisionModel, ModelKind, Physical,
    PhysicalParams, Sampling, Settings,
};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Names of the searchable contact-law quantities, in order (`g = γ / β`).
pub const LAW_NAMES: [&str; 8] = ["k", "c", "n", "p", "alpha", "beta", "g", "A"];

/// A measured force-compression loop.
#[derive(Debug, Clone, PartialEq)]
pub struct Loop {
    /// Where it came from.
    pub path: PathBuf,
    /// Impact speed (m/s).
    pub v0: f64,
    /// Relative displacement (m; negative in compression), chronological.
    pub x: Vec<f64>,
    /// Contact force (N).
    pub f: Vec<f64>,
}

impl Loop {
    /// Reads a loop: CSV with `#` comments and a header `x_mm,F_N` (compression in mm) or `x,F`
    /// (signed displacement in m), rows in chronological order.
    ///
    /// # Errors
    /// [`IdentifyError::Io`] or [`IdentifyError::Data`] naming the line.
    pub fn load(path: &Path, v0: f64) -> Result<Self, IdentifyError> {
        if !(v0.is_finite() && v0 > 0.0) {
            return Err(csv_file::data_error(
                path,
                0,
                format!("impact speed {v0} is not admissible: v0 > 0 (m/s)"),
            ));
        }
        let text = csv_file::read(path)?;
        let mut csv = CsvText::new(path, &text)?;
        let (xi, fi, scale) = match (csv.column("x_mm"), csv.column("x")) {
            (Some(i), _) => (i, csv.column("F_N"), -1e-3),
            (None, Some(i)) => (i, csv.column("F"), 1.0),
            _ => {
                return Err(csv.error(
                    csv.header_line,
                    format!(
                        "no column `x_mm` (with `F_N`) or `x` (with `F`) in {:?}",
                        csv.names()
                    ),
                ))
            }
        };
        let fi =
            fi.ok_or_else(|| csv.error(csv.header_line, "no force column `F_N` / `F`".into()))?;
        let points = csv.rows(|rec, _| {
            let num = |c: usize| -> Result<f64, String> {
                let raw = rec.get(c).ok_or("missing column in this row")?;
                raw.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| format!("{raw:?} is not a finite number"))
            };
            Ok((num(xi)? * scale, num(fi)?))
        })?;
        let (x, f): (Vec<f64>, Vec<f64>) = points.into_iter().unzip();
        if x.len() < 3 {
            return Err(csv.error(csv.header_line, "a loop needs at least 3 points".into()));
        }
        Ok(Self {
            path: path.to_owned(),
            v0,
            x,
            f,
        })
    }
}

/// Validated bounds of the contact-law quantities.
#[derive(Debug, Clone, PartialEq)]
pub struct LawSpace {
    kind: ModelKind,
    params: [Param; 8],
    free: Vec<usize>,
}

fn law_admissible(kind: ModelKind, i: usize, v: f64) -> Result<(), &'static str> {
    let ok = match i {
        1 if kind == ModelKind::Mcm => v > 0.0,
        1 => v >= 0.0,
        2 | 3 => v >= 1.0,
        4 => v > 0.0 && v < 1.0,
        5 => v >= 0.0,
        6 => (-1.0..=1.0).contains(&v),
        _ => v > 0.0,
    };
    if ok && v.is_finite() {
        return Ok(());
    }
    Err(match i {
        0 => "k > 0",
        1 if kind == ModelKind::Mcm => "c > 0 for the BWMCM",
        1 => "c >= 0",
        2 => "n >= 1",
        3 => "p >= 1",
        4 => "0 < alpha < 1",
        5 => "beta >= 0",
        6 => "-1 <= g = gamma / beta <= 1",
        _ => "A > 0",
    })
}

impl LawSpace {
    /// Builds the space from one entry per name in [`LAW_NAMES`].
    ///
    /// # Errors
    /// [`IdentifyError::Bounds`] as for [`crate::Space::new`].
    pub fn new(kind: ModelKind, params: [Param; 8]) -> Result<Self, IdentifyError> {
        for (i, p) in params.iter().enumerate() {
            let bad = |lo, hi, allowed| IdentifyError::Bounds {
                name: LAW_NAMES[i],
                lo,
                hi,
                allowed,
            };
            match *p {
                Param::Fixed(v) => law_admissible(kind, i, v).map_err(|a| bad(v, v, a))?,
                Param::Free { lo, hi, log } => {
                    if lo.is_nan() || hi.is_nan() || lo > hi {
                        return Err(bad(lo, hi, "lower bound <= upper bound"));
                    }
                    law_admissible(kind, i, lo).map_err(|a| bad(lo, hi, a))?;
                    law_admissible(kind, i, hi).map_err(|a| bad(lo, hi, a))?;
                    if log && lo <= 0.0 {
                        return Err(bad(lo, hi, "lower bound > 0 on a logarithmic scale"));
                    }
                }
                Param::Derived => return Err(bad(f64::NAN, f64::NAN, "a bound or a value")),
            }
        }
        let free = (0..8)
            .filter(|&i| matches!(params[i], Param::Free { .. }))
            .collect();
        Ok(Self { kind, params, free })
    }

    /// Every quantity of [`LAW_NAMES`]: held or searched.
    pub fn params(&self) -> &[Param; 8] {
        &self.params
    }

    /// The model.
    pub fn kind(&self) -> ModelKind {
        self.kind
    }

    /// Names of the free quantities.
    pub fn free_names(&self) -> Vec<&'static str> {
        self.free.iter().map(|&i| LAW_NAMES[i]).collect()
    }

    /// Names of the free quantities at search coordinates `coords` (as
    /// [`crate::at_bound`] gives them).
    pub fn names_at(&self, coords: &[usize]) -> Vec<&'static str> {
        coords.iter().map(|&j| LAW_NAMES[self.free[j]]).collect()
    }

    /// The contact law at a point of the unit cube.
    pub fn decode(&self, s: &[f64]) -> Physical {
        let v = values_at(&self.params, &self.free, s);
        Physical {
            k: v[0],
            c: v[1],
            n: v[2],
            p: v[3],
            alpha: v[4],
            beta: v[5],
            gamma: v[6] * v[5],
            a: v[7],
        }
    }
}

/// Points of a simulated loop `(x, F)`.
pub type Curve = Vec<(f64, f64)>;

/// The force-compression curve of one simulated impact.
fn curve<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    sampling: Sampling,
) -> Result<Curve, bw_models::ModelError> {
    let mut c = Vec::new();
    simulate(model, settings, sampling, |_, y| {
        c.push((model.displacement(y), model.force(y)))
    })?;
    Ok(c)
}

/// The loop-fitting problem.
pub struct LoopObjective<'a> {
    space: &'a LawSpace,
    loops: &'a [Loop],
    m: f64,
    settings: Settings,
    evaluations: AtomicU64,
}

/// Normalised arc length along a polyline in scaled coordinates.
fn arc(points: impl Iterator<Item = (f64, f64)>) -> (Vec<(f64, f64)>, Vec<f64>) {
    let pts: Vec<(f64, f64)> = points.collect();
    let mut s = vec![0.0; pts.len()];
    for i in 1..pts.len() {
        s[i] = s[i - 1]
            + ((pts[i].0 - pts[i - 1].0).powi(2) + (pts[i].1 - pts[i - 1].1).powi(2)).sqrt();
    }
    let total = s.last().copied().unwrap_or(0.0);
    if total > 0.0 {
        s.iter_mut().for_each(|v| *v /= total);
    }
    (pts, s)
}

/// The documented loop distance (see the module docs).
pub fn loop_cost(measured: &Loop, model: &[(f64, f64)]) -> f64 {
    let sx = measured
        .x
        .iter()
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let sf = measured
        .f
        .iter()
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    let (mp, ms) = arc(measured
        .x
        .iter()
        .zip(&measured.f)
        .map(|(x, f)| (x / sx, f / sf)));
    let (sp, ss) = arc(model.iter().map(|(x, f)| (x / sx, f / sf)));
    if sp.len() < 2 {
        return 1.0;
    }
    let mut total = 0.0;
    for (p, tau) in mp.iter().zip(&ms) {
        let j = ss.partition_point(|v| v < tau).clamp(1, ss.len() - 1);
        let w = if ss[j] > ss[j - 1] {
            ((tau - ss[j - 1]) / (ss[j] - ss[j - 1])).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = (
            sp[j - 1].0 + w * (sp[j].0 - sp[j - 1].0),
            sp[j - 1].1 + w * (sp[j].1 - sp[j - 1].1),
        );
        total += (p.0 - q.0).powi(2) + (p.1 - q.1).powi(2);
    }
    total / mp.len() as f64
}

impl<'a> LoopObjective<'a> {
    /// Fitting `space` to `loops` for mass `m` (kg).
    ///
    /// # Errors
    /// [`IdentifyError::Bounds`] for a non-positive mass, [`IdentifyError::Objectives`] without
    /// loops, [`IdentifyError::Model`] for bad solver settings.
    pub fn new(
        space: &'a LawSpace,
        loops: &'a [Loop],
        m: f64,
        settings: Settings,
    ) -> Result<Self, IdentifyError> {
        if !m.is_finite() || m <= 0.0 {
            return Err(IdentifyError::Bounds {
                name: "m",
                lo: m,
                hi: m,
                allowed: "m > 0 (kg)",
            });
        }
        if loops.is_empty() {
            return Err(IdentifyError::Objectives {
                reason: "no loops to fit".into(),
            });
        }
        settings.validate()?;
        Ok(Self {
            space,
            loops,
            m,
            settings,
            evaluations: AtomicU64::new(0),
        })
    }

    /// The space.
    pub fn space(&self) -> &LawSpace {
        self.space
    }

    /// Simulated loops of a contact law, one per measured loop (about 200 points each).
    ///
    /// # Errors
    /// [`IdentifyError::Model`] when the law is not admissible or a simulation fails.
    pub fn simulate(&self, law: &Physical) -> Result<Vec<Curve>, IdentifyError> {
        let params = PhysicalParams::new(self.space.kind, *law)?;
        self.loops
            .par_iter()
            .map(|l| {
                let (_, scales) = nondimensionalize(&params, self.m, l.v0)?;
                let sampling = Sampling::Grid {
                    dt: scales.t_c / 64.0,
                };
                Ok(match self.space.kind {
                    ModelKind::Shccm => curve(
                        &Bwshccm::new(&params, self.m, l.v0, Zero)?,
                        &self.settings,
                        sampling,
                    )?,
                    ModelKind::Mcm => curve(
                        &Bwmcm::new(&params, self.m, l.v0, Zero)?,
                        &self.settings,
                        sampling,
                    )?,
                })
            })
            .collect()
    }

    /// Cost and simulated loops at a point of the unit cube.
    ///
    /// # Errors
    /// As [`LoopObjective::simulate`].
    pub fn evaluate(&self, s: &[f64]) -> Result<(f64, Vec<Curve>), IdentifyError> {
        let curves = self.simulate(&self.space.decode(s))?;
        let cost = self
            .loops
            .iter()
            .zip(&curves)
            .map(|(l, c)| loop_cost(l, c))
            .sum::<f64>()
            / self.loops.len() as f64;
        Ok((cost, curves))
    }
}

impl CubeProblem for LoopObjective<'_> {
    fn dim(&self) -> usize {
        self.space.free.len()
    }
    fn cost_at(&self, s: &[f64]) -> f64 {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        let outside: f64 = s.iter().map(|x| (x - x.clamp(0.0, 1.0)).powi(2)).sum();
        match self.evaluate(s) {
            Ok((c, _)) if c.is_finite() => c + outside,
            _ => crate::FAILED + outside,
        }
    }
    fn evaluations(&self) -> u64 {
        self.evaluations.load(Ordering::Relaxed)
    }
}

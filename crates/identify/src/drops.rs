//! Drop tests fitted directly: a ball dropped from rest at `h0` on a fixed surface, measured as
//! the intervals between successive impacts (`h0`, `bounce_n`, `interval_s`) or as the height
//! of the first rebound (`h0`, `h1`). The model simulates the bounce sequence
//! ([`bw_models::sequence`]): closed-form flights under gravity `g` with quadratic drag, and at
//! each contact one impact of the base-parameter model `P(P*, u, v)` at the impact speed.
//!
//! Cost (`J_drop`, s² for intervals, m² for heights): the mean squared difference between
//! measured and simulated values, `J_drop = (1/M) Σ (ỹ_i - y_i(P*))²`, over the `M` rows.
//! With `U_b` and `T_b` in the search space (searched, held or derived), each contact feels
//! gravity `u = -m g` and its duration `t_s` (s) counts in the interval; without them the
//! contact is instantaneous and unforced (`interval = 2 v_out / g` without drag), which is
//! below the resolution of the usual acoustic or video timing (a contact of 0.1-1 ms, a force
//! peak hundreds of times `m g`).

use crate::csv_file::{self, CsvText};
use crate::error::IdentifyError;
use crate::objective::{passes, TermOrder};
use crate::problem::CubeProblem;
use crate::space::FitModel;
use crate::space::Space;
use bw_models::input::Constant;
use bw_models::sequence::{drop_sequence, Contact, Flight, Policy, SequenceSettings, Start};
use bw_models::{ModelError, Settings};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// What the rows of a drop-test file measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DropKind {
    /// `interval_s`: time (s) from impact `bounce_n` to impact `bounce_n + 1`.
    Intervals,
    /// `h1`: height (m) of the first rebound's apex above the surface.
    Heights,
}

/// One measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DropRow {
    /// Release height (m).
    pub h0: f64,
    /// Which interval (from 1; 1 for heights).
    pub bounce_n: usize,
    /// The interval (s) or the rebound height (m).
    pub value: f64,
    /// Line in the file.
    pub line: u64,
}

/// A drop-test file.
#[derive(Debug, Clone, PartialEq)]
pub struct DropData {
    /// The file.
    pub path: PathBuf,
    /// What it measures.
    pub kind: DropKind,
    /// Its rows (repeated rows allowed).
    pub rows: Vec<DropRow>,
}

impl DropData {
    /// Whether a CSV header (column names) is that of a drop-test file.
    pub fn is_drop_header(columns: &[String]) -> bool {
        let has = |c: &str| columns.iter().any(|h| h == c);
        has("h0") && (has("h1") || (has("bounce_n") && has("interval_s")))
    }

    /// Reads a drop-test CSV (`#` comment lines; columns `h0` in m and either `bounce_n`,
    /// `interval_s` in s or `h1` in m; other columns ignored).
    ///
    /// # Errors
    /// [`IdentifyError::Io`] if unreadable, [`IdentifyError::Data`] naming the line of a
    /// malformed or inadmissible value, the missing columns, or an empty file.
    pub fn load(path: &Path) -> Result<Self, IdentifyError> {
        let text = csv_file::read(path)?;
        let mut csv = CsvText::new(path, &text)?;
        let col = |name: &str| csv.column(name);
        let (kind, value_col, n_col) = match (col("h0"), col("interval_s"), col("bounce_n"), col("h1")) {
            (Some(_), Some(v), Some(n), _) => (DropKind::Intervals, v, Some(n)),
            (Some(_), _, _, Some(v)) => (DropKind::Heights, v, None),
            _ => {
                return Err(csv.error(
                    csv.header_line,
                    format!("columns {:?}: a drop test needs h0 (m) with bounce_n and interval_s (s), or h0 and h1 (m)", csv.names()),
                ))
            }
        };
        let columns = DropColumns {
            h0: col("h0").expect("checked"),
            value: (
                value_col,
                if kind == DropKind::Heights {
                    "h1"
                } else {
                    "interval_s"
                },
            ),
            bounce_n: n_col,
        };
        let rows = csv.rows(|record, line| columns.row(record, line))?;
        if rows.is_empty() {
            return Err(csv.error(csv.header_line, "no rows: nothing to fit".into()));
        }
        Ok(DropData {
            path: path.to_owned(),
            kind,
            rows,
        })
    }
}

/// The columns of a drop-test file: `h0`, the measured value (`h1` or `interval_s`) and, for
/// intervals, `bounce_n`.
struct DropColumns {
    h0: usize,
    value: (usize, &'static str),
    bounce_n: Option<usize>,
}

impl DropColumns {
    /// The row of `record` (at `line`); a message for a value that is not admissible.
    fn row(&self, record: &csv::StringRecord, line: u64) -> Result<DropRow, String> {
        let positive = |c: usize, name: &str| -> Result<f64, String> {
            let raw = record.get(c).unwrap_or("");
            match raw.parse::<f64>() {
                Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
                _ => Err(format!(
                    "column `{name}`: {raw:?} is not admissible: a number > 0"
                )),
            }
        };
        let bounce_n = match self.bounce_n {
            None => 1,
            Some(c) => {
                let raw = record.get(c).unwrap_or("");
                match raw.parse::<usize>() {
                    Ok(n) if n >= 1 => n,
                    _ => {
                        return Err(format!(
                            "column `bounce_n`: {raw:?} is not admissible: 1, 2, ..."
                        ))
                    }
                }
            }
        };
        Ok(DropRow {
            h0: positive(self.h0, "h0")?,
            bounce_n,
            value: positive(self.value.0, self.value.1)?,
            line,
        })
    }
}

/// The physics of the drops around the contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DropSetup {
    /// Mass of the ball (kg): the contact's input is `u = -m g`.
    pub m: f64,
    /// Gravity (m/s²) and drag (1/m) in flight.
    pub flight: Flight,
    /// Whether contacts feel gravity and last `t_s` (the space has `U_b` and `T_b`).
    pub timed_contacts: bool,
}

/// The identification problem of a drop-test file on the unit cube of a [`Space`].
pub struct DropObjective<'a> {
    space: &'a Space,
    data: &'a DropData,
    setup: DropSetup,
    settings: Settings,
    evaluations: AtomicU64,
    progress: Option<&'a (dyn Fn() + Sync)>,
}

/// Cost of a point whose simulation failed (s² or m²): worse than any feasible point.
const FAILED_DROP: f64 = 1e3;

impl<'a> DropObjective<'a> {
    /// Fitting `space` to `data` with `setup` and the solver `settings` of each contact.
    ///
    /// # Errors
    /// [`IdentifyError::Model`] for inadmissible settings, [`IdentifyError::Bounds`] for a
    /// non-positive mass or gravity, or a negative drag.
    pub fn new(
        space: &'a Space,
        data: &'a DropData,
        setup: DropSetup,
        settings: Settings,
    ) -> Result<Self, IdentifyError> {
        settings.validate()?;
        let f = setup.flight;
        for (name, v, ok, allowed) in [
            ("m", setup.m, setup.m > 0.0, "m > 0 (kg)"),
            ("g", f.g, f.g > 0.0, "g > 0 (m/s^2)"),
            ("drag", f.drag, f.drag >= 0.0, "drag >= 0 (1/m)"),
        ] {
            if !(ok && v.is_finite()) {
                return Err(IdentifyError::Bounds {
                    name,
                    lo: v,
                    hi: v,
                    allowed,
                });
            }
        }
        Ok(Self {
            space,
            data,
            setup,
            settings,
            evaluations: AtomicU64::new(0),
            progress: None,
        })
    }

    /// Calls `progress` after every cost evaluation.
    pub fn with_progress(mut self, progress: &'a (dyn Fn() + Sync)) -> Self {
        self.progress = Some(progress);
        self
    }

    /// The sequence from `h0` for base map `map`, up to `bounces` contacts.
    fn sequence(
        &self,
        map: &FitModel,
        h0: f64,
        bounces: usize,
    ) -> Result<Vec<bw_models::sequence::Bounce>, ModelError> {
        let setup = self.setup;
        let u = if setup.timed_contacts {
            -setup.m * setup.flight.g
        } else {
            0.0
        };
        let contact = |v_in: f64, _: Option<&()>| {
            let out = map.impact(Constant(u), v_in, &self.settings)?;
            let t_s = out.t_s.map(|t| {
                if setup.timed_contacts {
                    t * map.time_scale(v_in)
                } else {
                    0.0
                }
            });
            Ok(Contact {
                t_s,
                v_out: out.e * v_in,
                settled: out.settled_at.is_some(),
                state: (),
            })
        };
        let settings = SequenceSettings {
            flight: setup.flight,
            bounces,
            policy: Policy::Reset,
        };
        drop_sequence(Start::Height(h0), &settings, contact)
    }

    /// The simulated value of every row at a point of the unit cube (each distinct release
    /// height simulated once, in parallel; NaN where the sequence ended before the row's
    /// bounce).
    ///
    /// # Errors
    /// [`IdentifyError::Model`] when the parameters are not admissible or a contact fails.
    pub fn predict(&self, s: &[f64]) -> Result<Vec<f64>, IdentifyError> {
        let map = self.space.map(&self.space.decode(s))?;
        let (heights, bounces) = self.heights();
        let sequences: Vec<_> = heights
            .par_iter()
            .map(|&h0| self.sequence(&map, h0, bounces))
            .collect::<Result<_, _>>()?;
        Ok(self.values(&heights, &sequences))
    }

    /// The distinct release heights in increasing order, and the contacts each sequence needs.
    fn heights(&self) -> (Vec<f64>, usize) {
        let mut heights: Vec<f64> = self.data.rows.iter().map(|r| r.h0).collect();
        heights.sort_by(f64::total_cmp);
        heights.dedup();
        let most = self.data.rows.iter().map(|r| r.bounce_n).max().unwrap_or(1);
        // An interval n ends at contact n + 1.
        let bounces = match self.data.kind {
            DropKind::Intervals => most + 1,
            DropKind::Heights => 1,
        };
        (heights, bounces)
    }

    /// The simulated value of row `r` from its height's sequence (NaN where the sequence ended
    /// before the row's bounce).
    fn value(&self, r: &DropRow, sequence: &[bw_models::sequence::Bounce]) -> f64 {
        let bounce = sequence.get(r.bounce_n - 1);
        match self.data.kind {
            DropKind::Intervals => bounce.and_then(|b| b.interval).unwrap_or(f64::NAN),
            DropKind::Heights => bounce.map_or(f64::NAN, |b| b.apex),
        }
    }

    /// The rows' values height after height in `order`, or the partial cost (from `outside`)
    /// at which `passed` stopped them; `Ok(None)` where a simulation fails.
    fn predict_below(
        &self,
        s: &[f64],
        outside: f64,
        passed: impl Fn(f64) -> bool,
        order: &mut TermOrder,
    ) -> Result<Option<Vec<f64>>, f64> {
        let Ok(map) = self.space.map(&self.space.decode(s)) else {
            return Ok(None);
        };
        let (heights, bounces) = self.heights();
        let scale = 1.0 / (self.data.rows.len() as f64).sqrt();
        let sequences = order.accumulate(heights.len(), outside, passed, |k| {
            let sequence = self.sequence(&map, heights[k], bounces).ok()?;
            let rows = self.data.rows.iter().filter(|r| r.h0 == heights[k]);
            let squares: f64 = rows
                .map(|r| residual(scale, r.value, self.value(r, &sequence)).powi(2))
                .sum();
            Some((sequence, squares))
        })?;
        Ok(sequences.map(|sequences| self.values(&heights, &sequences)))
    }

    /// The simulated value of every row from the sequences of the distinct `heights`.
    fn values(&self, heights: &[f64], sequences: &[Vec<bw_models::sequence::Bounce>]) -> Vec<f64> {
        self.data
            .rows
            .iter()
            .map(|r| self.value(r, &sequences[heights.partition_point(|&h| h < r.h0)]))
            .collect()
    }

    /// `J_drop` of predictions against the data.
    pub fn cost_of(&self, predicted: &[f64]) -> f64 {
        let r = self.residuals_of(predicted);
        r.iter().map(|x| x * x).sum()
    }

    /// Residuals `(ỹ_i - y_i) / sqrt(M)`, whose sum of squares is `J_drop` (a row whose bounce
    /// the simulation did not reach counts as a miss by the measured value).
    fn residuals_of(&self, predicted: &[f64]) -> Vec<f64> {
        let scale = 1.0 / (self.data.rows.len() as f64).sqrt();
        self.data
            .rows
            .iter()
            .zip(predicted)
            .map(|(r, &p)| residual(scale, r.value, p))
            .collect()
    }

    /// The residual vector of predictions (`None` for a failed simulation) and the distance
    /// outside the cube.
    fn residuals_with(&self, predicted: Option<&[f64]>, outside: f64) -> Vec<f64> {
        let mut r = match predicted {
            Some(p) => self.residuals_of(p),
            None => self.data.rows.iter().map(|_| FAILED_DROP.sqrt()).collect(),
        };
        r.push(outside.sqrt());
        r
    }

    /// The residuals at `s` as [`CubeProblem::residuals_at`] gives them, or where the heights
    /// simulated in `order` have passed `bound`, the partial cost. Counts as one evaluation.
    fn residuals_or_partial(
        &self,
        s: &[f64],
        bound: f64,
        order: &mut TermOrder,
    ) -> Result<Vec<f64>, f64> {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        if let Some(p) = self.progress {
            p();
        }
        let outside: f64 = s.iter().map(|x| (x - x.clamp(0.0, 1.0)).powi(2)).sum();
        let passed = passes(bound, FAILED_DROP);
        if passed(outside) {
            return Err(outside);
        }
        let p = self.predict_below(s, outside, passed, order)?;
        Ok(self.residuals_with(p.as_deref(), outside))
    }

    /// The space.
    pub fn space(&self) -> &Space {
        self.space
    }
}

impl CubeProblem for DropObjective<'_> {
    fn dim(&self) -> usize {
        self.space.dim()
    }
    fn cost_at(&self, s: &[f64]) -> f64 {
        self.residuals_at(s)
            .map_or(FAILED_DROP, |r| r.iter().map(|x| x * x).sum())
    }
    fn evaluations(&self) -> u64 {
        self.evaluations.load(Ordering::Relaxed)
    }
    fn residuals_at(&self, s: &[f64]) -> Option<Vec<f64>> {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        let outside: f64 = s.iter().map(|x| (x - x.clamp(0.0, 1.0)).powi(2)).sum();
        let r = self.residuals_with(self.predict(s).ok().as_deref(), outside);
        if let Some(p) = self.progress {
            p();
        }
        Some(r)
    }
    /// As [`crate::Objective::scalar_below`], height by height: the cost bit for bit where it
    /// is below `bound`, else a partial sum above it (every term is nonnegative).
    fn cost_below(&self, s: &[f64], bound: f64, order: &mut TermOrder) -> f64 {
        match self.residuals_or_partial(s, bound, order) {
            Ok(r) => r.iter().map(|x| x * x).sum(),
            Err(partial) => partial,
        }
    }
    fn residuals_below(&self, s: &[f64], bound: f64, order: &mut TermOrder) -> Option<Vec<f64>> {
        self.residuals_or_partial(s, bound, order).ok()
    }
}

/// The residual of one row: `(ỹ - y) scale`, a miss by the measured value where the
/// simulation did not reach the row's bounce.
fn residual(scale: f64, measured: f64, simulated: f64) -> f64 {
    scale
        * if simulated.is_finite() {
            measured - simulated
        } else {
            measured
        }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::space::Param;
    use bw_models::ModelKind;

    /// The Hunt-Crossley limit (B_b = Γ_b = 0): e(σ) is the root in (0, 1) of
    /// σ - ln(1+σ) = -σe - ln(1-σe), with σ = σ_b v for the NDBWSHCCM.
    fn hunt_crossley_e(sigma: f64) -> f64 {
        let g = |e: f64| sigma - sigma.ln_1p() + sigma * e + (-sigma * e).ln_1p();
        let (mut lo, mut hi) = (1e-12, 1.0 - 1e-12);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    #[test]
    fn intervals_and_heights_follow_the_closed_form_sequence() {
        let sigma_b = 0.05;
        let fixed = |v: f64| Param::Fixed(v);
        let params = [
            fixed(0.0),
            fixed(0.0),
            fixed(0.5),
            Param::Free {
                lo: 0.01,
                hi: 0.1,
                log: false,
            },
            fixed(1.5),
            fixed(1.5),
            fixed(1.0),
            fixed(1.0),
        ];
        let space = Space::new(ModelKind::Shccm, params, None).unwrap();
        let s = [(sigma_b - 0.01) / 0.09];
        let (g, h0) = (9.81, 0.5);
        let dir = std::env::temp_dir().join(format!("bwc-drops-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("intervals.csv");
        std::fs::write(
            &file,
            "# synthetic\nh0,bounce_n,interval_s\n0.5,1,0.1\n0.5,2,0.1\n0.5,3,0.1\n",
        )
        .unwrap();
        let data = DropData::load(&file).unwrap();
        assert_eq!(
            (data.kind, data.rows.len(), data.rows[2].line),
            (DropKind::Intervals, 3, 5)
        );
        let setup = DropSetup {
            m: 0.01,
            flight: Flight { g, drag: 0.0 },
            timed_contacts: false,
        };
        let objective = DropObjective::new(&space, &data, setup, Settings::default()).unwrap();
        let predicted = objective.predict(&s).unwrap();
        // Instantaneous contacts: v_(n+1) = e(σ_b v_n) v_n, interval_n = 2 v_(n+1) / g.
        let mut v = (2.0 * g * h0).sqrt();
        for p in predicted {
            v *= hunt_crossley_e(sigma_b * v);
            assert!((p - 2.0 * v / g).abs() < 1e-9 * p, "{p} vs {}", 2.0 * v / g);
        }
        let heights = dir.join("heights.csv");
        std::fs::write(&heights, "h0,h1\n0.5,0.3\n").unwrap();
        let data = DropData::load(&heights).unwrap();
        let objective = DropObjective::new(&space, &data, setup, Settings::default()).unwrap();
        let h1 = objective.predict(&s).unwrap()[0];
        let e = hunt_crossley_e(sigma_b * (2.0 * g * h0).sqrt());
        assert!((h1 - e * e * h0).abs() < 1e-9 * h1, "{h1}");
        std::fs::write(&heights, "h0,h1\n0.5,-0.3\n").unwrap();
        let bad = DropData::load(&heights).unwrap_err().to_string();
        assert!(bad.contains(":2:") && bad.contains("`h1`"), "{bad}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}

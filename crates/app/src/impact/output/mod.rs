//! Output files: `summary.json`, `sweep.csv`, `trajectory.csv`, `loop.csv` and SVG plots, all
//! rendered in memory first and then written to a temporary name and renamed, so that a failed
//! run leaves no half-written file.

mod figures;
mod run_summary;
mod study;

pub use run_summary::{RunSummary, RUN_KEYS};
pub use study::{Study, FIGURE_POINTS, FIGURE_RUNS, RUNS_FILE};

use crate::impact::runs::Run;
use crate::impact::scene::{Scene, System};
use serde::Serialize;

/// A tighter run under `e_tol` that failed (`bw_models::FailedRun`).
#[derive(Debug, Serialize)]
pub struct FailedRunSummary {
    /// Its relative tolerance.
    pub rtol: f64,
    /// Whether it needed more than `[solver] max_steps` steps.
    pub out_of_steps: bool,
}

/// The interpolant a run of a sweep came from (`bw_models::sweep`).
#[derive(Debug, Serialize)]
pub struct InterpolationSummary {
    /// Degree of the Chebyshev interpolant in `ln v0`.
    pub degree: usize,
    /// Error estimate: absolute in `e`, relative to the piece's largest `|t_s|` in `t_s`.
    pub estimate: f64,
    /// Lowest speed of its piece (m/s).
    pub from: f64,
    /// Highest speed of its piece (m/s).
    pub to: f64,
}

/// One contact of a sequence. Times in s (`t_contact` from release), speeds in m/s, heights in m.
#[derive(Debug, Serialize)]
pub struct BounceSummary {
    /// Top of the next flight above the separation point (m).
    pub apex: f64,
    /// `v_out / v_in`.
    pub e: f64,
    /// From this contact's onset to the next one's (s), null for the last.
    pub interval: Option<f64>,
    /// Number of the contact, from 1.
    pub n: usize,
    /// `"separated"`, `"settled"` or `"horizon"`.
    pub outcome: &'static str,
    /// Onset of the contact (s from release).
    pub t_contact: f64,
    /// Contact duration (s), null without separation.
    pub t_s: Option<f64>,
    /// Impact speed (m/s).
    pub v_in: f64,
    /// Rebound speed (m/s).
    pub v_out: f64,
    /// Displacement at separation (m; negative: below where the contact began).
    pub x_s: f64,
}

impl BounceSummary {
    fn of((b, x_s): &crate::impact::runs::Bounced) -> Self {
        use bw_models::sequence::BounceEnd;
        BounceSummary {
            n: b.n,
            t_contact: b.t_contact,
            v_in: b.v_in,
            v_out: b.v_out,
            e: b.e,
            t_s: b.t_s,
            apex: b.apex,
            interval: b.interval,
            x_s: *x_s,
            outcome: match b.end {
                BounceEnd::Separated => "separated",
                BounceEnd::Settled => "settled",
                BounceEnd::Horizon => "horizon",
            },
        }
    }
}

/// Where a settled contact came to rest, in the run's units (`time_unit`; N and m for SI
/// runs, nondimensional otherwise).
#[derive(Debug, Serialize)]
pub struct RestSummary {
    /// Contact force.
    #[serde(rename = "F")]
    pub f: f64,
    /// When it was found at rest.
    pub t: f64,
    /// Input: at rest `F + u = 0`.
    pub u: f64,
    /// Relative displacement.
    pub x: f64,
}

/// Nondimensional parameters, keyed as in a scene's `[nondimensional]` table.
#[derive(Debug, Serialize)]
#[allow(non_snake_case)]
pub struct NondimSummary {
    /// `B`.
    pub B: f64,
    /// `Γ`.
    pub Gamma: f64,
    /// `κ`.
    pub kappa: f64,
    /// `n`.
    pub n: f64,
    /// `p`.
    pub p: f64,
    /// `σ`.
    pub sigma: f64,
}

/// The JSON summary: `{"runs": [...]}`.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// One entry per run, in scene order.
    pub runs: Vec<RunSummary>,
}

impl Summary {
    /// Summarises runs (with their bounces when `sequence`).
    pub fn new(runs: &[Run], sequence: bool) -> Self {
        Summary {
            runs: runs.iter().map(|r| RunSummary::of(r, sequence)).collect(),
        }
    }

    /// The JSON text `bwc-simulate --json` prints for `runs`, the runs of `scene`: `{"command",
    /// "runs", "scene", "tool", "units", "version"}` ([`SummaryWriter`]).
    pub fn provenance_json(&self, scene: &Scene, runs: &[Run]) -> String {
        let mut w = SummaryWriter::array(Vec::new(), scene).expect("in-memory writer");
        w.add_summaries(&self.runs).expect("in-memory writer");
        let tally = crate::impact::simulate::Tally::of(scene, runs);
        let text = w.finish(scene, &tally, None).expect("in-memory writer");
        String::from_utf8(text).expect("JSON is UTF-8")
    }
}

/// The JSON summary of a scene's runs written as they come, in either of two forms:
///
/// * an array: `{"command": [...], "runs": [...], "scene": {...}, "tool": "bwc-simulate",
///   "units": {...}, "version": "..."}` (and `"files"` last in `summary.json`), the keys in
///   sorted order, the runs written one by one as they are added;
/// * JSON Lines: one run per line, for `runs.jsonl`.
pub struct SummaryWriter<W> {
    sink: W,
    sequence: bool,
    lines: bool,
    first: bool,
}

impl<W: std::io::Write> SummaryWriter<W> {
    /// The array form: writes the head up to the runs' opening bracket.
    ///
    /// # Errors
    /// What writing to `sink` returned.
    pub fn array(mut sink: W, scene: &Scene) -> std::io::Result<Self> {
        let command: Vec<String> = std::env::args().collect();
        write!(sink, "{{\"command\":")?;
        serde_json::to_writer(&mut sink, &command)?;
        write!(sink, ",\"runs\":[")?;
        Ok(SummaryWriter {
            sink,
            sequence: scene.sequence.is_some(),
            lines: false,
            first: true,
        })
    }

    /// The JSON Lines form.
    pub fn lines(sink: W, scene: &Scene) -> Self {
        SummaryWriter {
            sink,
            sequence: scene.sequence.is_some(),
            lines: true,
            first: true,
        }
    }

    /// Whether this is the JSON Lines form.
    pub fn is_lines(&self) -> bool {
        self.lines
    }

    /// Where the text goes.
    pub fn sink(&self) -> &W {
        &self.sink
    }

    /// Writes the summaries of the next runs.
    ///
    /// # Errors
    /// What writing to the sink returned.
    pub fn add(&mut self, runs: &[Run]) -> std::io::Result<()> {
        self.add_summaries(&Summary::new(runs, self.sequence).runs)
    }

    fn add_summaries(&mut self, runs: &[RunSummary]) -> std::io::Result<()> {
        for r in runs {
            if self.lines {
                serde_json::to_writer(&mut self.sink, r)?;
                self.sink.write_all(b"\n")?;
            } else {
                if !self.first {
                    self.sink.write_all(b",")?;
                }
                serde_json::to_writer(&mut self.sink, r)?;
            }
            self.first = false;
        }
        Ok(())
    }

    /// Closes the array (with `files` as the last key, where given) and returns the sink; the
    /// JSON Lines form is returned as it is. No newline is written.
    ///
    /// # Errors
    /// What writing to the sink returned.
    pub fn finish(
        mut self,
        scene: &Scene,
        tally: &crate::impact::simulate::Tally,
        files: Option<&[String]>,
    ) -> std::io::Result<W> {
        if !self.lines {
            let w = &mut self.sink;
            write!(w, "],\"scene\":")?;
            serde_json::to_writer(&mut *w, &scene.describe())?;
            write!(w, ",\"tool\":\"bwc-simulate\",\"units\":")?;
            serde_json::to_writer(&mut *w, &units(scene, tally.time_unit()))?;
            write!(w, ",\"version\":\"{}\"", env!("CARGO_PKG_VERSION"))?;
            if let Some(files) = files {
                write!(w, ",\"files\":")?;
                serde_json::to_writer(&mut *w, files)?;
            }
            write!(w, "}}")?;
        }
        self.sink.flush()?;
        Ok(self.sink)
    }
}

/// Whether the states of a scene's runs are in SI units: trajectories of `[nondimensional]` and
/// `[base]` systems are in the model's own (nondimensional) variables.
pub(crate) fn si_states(scene: &Scene) -> bool {
    scene
        .systems
        .iter()
        .all(|s| matches!(s.system, System::Physical { .. } | System::Bodies { .. }))
}

/// The unit of every JSON key of a run and of every CSV column (`"1"`: dimensionless; the
/// nondimensional quantities are in the scales of Table 1). A unit given for an object holds for
/// all its entries (`nondimensional`); the map under an array's key is that of each element
/// (`bounces`).
/// `time_unit`: that of `t_s` of every run ([`crate::impact::simulate::Tally::time_unit`]; `None`
/// without runs: s).
pub fn units(scene: &Scene, time_unit: Option<&str>) -> serde_json::Value {
    let nd = "nondimensional";
    let t = time_unit.unwrap_or("s");
    let si = si_states(scene);
    let (m, ms, n) = if si { ("m", "m/s", "N") } else { (nd, nd, nd) };
    let runs = run_summary::run_units(run_summary::SceneUnits { t, m, n });
    serde_json::json!({
        "runs": runs,
        "sweep.csv": study::sweep_units(t),
        "trajectory.csv": {"v_0": "m/s", "name": "text", "t": t, "x": m, "v": ms, "u": n,
            "F": n, "z": m, "r": m, "y": m, "x_m_1": "m", "x_m_2": "m", "x_m": "m",
            "v_m_1": "m/s", "v_m_2": "m/s", "v_m": "m/s", "u_1": "N", "u_2": "N"},
        "loop.csv": {"v_0": "m/s", "x": m, "F": n, "name": "text"},
        "bounces.csv": bounce_units(),
    })
}

/// The unit of each key of a bounce (`bounces` of a run, `bounces.csv`).
fn bounce_units() -> serde_json::Value {
    serde_json::json!({"n": "count", "t_contact": "s", "v_in": "m/s", "v_out": "m/s",
        "e": "1", "t_s": "s", "apex": "m", "interval": "s", "x_s": "m", "outcome": "text"})
}

/// `bounces.csv`: the columns of [`BounceSummary`], one row per contact.
pub(super) fn bounces_csv(runs: &[Run]) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "n",
        "t_contact",
        "v_in",
        "v_out",
        "e",
        "t_s",
        "apex",
        "interval",
        "x_s",
        "outcome",
    ])?;
    for b in runs.iter().flat_map(|r| &r.bounces).map(BounceSummary::of) {
        w.write_record([
            b.n.to_string(),
            b.t_contact.to_string(),
            b.v_in.to_string(),
            b.v_out.to_string(),
            b.e.to_string(),
            opt(b.t_s),
            b.apex.to_string(),
            opt(b.interval),
            b.x_s.to_string(),
            b.outcome.to_string(),
        ])?;
    }
    Ok(w.into_inner().expect("in-memory writer"))
}

/// `"interpolated"` for a run of a sweep served by an interpolant, else `"simulated"`.
pub fn source(r: &Run) -> &'static str {
    if r.interpolation.is_some() {
        "interpolated"
    } else {
        "simulated"
    }
}

pub(super) fn opt(v: Option<f64>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

//! Output files: `summary.json`, `sweep.csv`, `trajectory.csv`, `loop.csv` and SVG plots, all
//! rendered in memory first and then written to a temporary name and renamed, so that a failed
//! run leaves no half-written file.

mod figures;
mod study;

pub use study::{Study, FIGURE_POINTS, FIGURE_RUNS, RUNS_FILE};

use crate::runs::{Outcome, Run};
use crate::scene::{Scene, System};
use bw_models::Check;
use serde::Serialize;

/// One run in the JSON summary. Key names are a fixed contract; keys may be added.
#[derive(Debug, Serialize)]
pub struct RunSummary {
    /// The time scale `T_c` (s): solver times (`t_max`, `max_step`) are multiples of it; null
    /// for nondimensional runs.
    #[serde(rename = "T_c")]
    pub t_c: Option<f64>,
    /// Accepted steps.
    pub accepted: u64,
    /// `"double"`, or `"double-double"` where the reported run is the double-double one
    /// (`[solver] double_double`: the double-precision runs could not meet `e_tol`).
    pub arithmetic: &'static str,
    /// The contacts of a `[sequence]` scene (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bounces: Option<Vec<BounceSummary>>,
    /// What the check of `e` against `[solver] e_tol` found: `"met"` (`e_error` at most
    /// `e_tol`), `"unmet"` (above it, and no tighter run was possible), `"unverified"` (no run
    /// at another tolerance finished: `e` is one unchecked run) or `"off"` (one run: no `e_tol`,
    /// or a trajectory); null for an interpolated row or a failed run.
    pub check: Option<&'static str>,
    /// Where `check` is `"unmet"` under `[solver] double_double`: why the double-double retry
    /// reported nothing (`e` is then the double-precision one), as the predicate the warning
    /// prints after "the double-double retry" (`"was not tried: ..."`); null otherwise.
    pub double_double_declined: Option<String>,
    /// Coefficient of restitution.
    pub e: f64,
    /// The estimate of the error in `e` of a CoR checked against a run at another tolerance
    /// (`[solver] e_tol`); null for a single run, a trajectory or an interpolated row.
    pub e_error: Option<f64>,
    /// For a failed run, what went wrong and which setting would help; null otherwise.
    pub error: Option<String>,
    /// Located events.
    pub events: u64,
    /// Where `e` and `t_s` came from an interpolant of the sweep (`"source": "interpolated"`):
    /// its error estimate and piece; null for a simulated run.
    pub interpolation: Option<InterpolationSummary>,
    /// Jacobian evaluations (RODAS4 steps).
    pub jacobians: u64,
    /// `"shccm"` or `"mcm"`.
    pub model: &'static str,
    /// System name, if any.
    pub name: Option<String>,
    /// The nondimensional parameters the run integrated; null for a failed run.
    pub nondimensional: Option<NondimSummary>,
    /// How the run ended: `"separated"`, `"settled"`, `"horizon"` or `"failed"`.
    pub outcome: &'static str,
    /// Whether `e` and `t_s` came from the phase path (`[solver] phase`: quadratures in phase
    /// space, no time steps, so every count is 0 and `e_error` is its own estimate).
    pub phase: bool,
    /// Rejected steps.
    pub rejected: u64,
    /// For a settled contact, where it came to rest (`F + u = 0`); null otherwise.
    pub rest: Option<RestSummary>,
    /// RHS evaluations (of every run behind a checked CoR).
    pub rhs_evals: u64,
    /// The relative tolerance of the reported run (`[solver] rtol`, or tighter where `e_tol`
    /// asked for it); null for an interpolated row or a failed run.
    pub rtol: Option<f64>,
    /// Whether the bodies separated.
    pub separated: bool,
    /// Steps taken by Taylor series (0 on the Runge-Kutta path; counted in `accepted`).
    pub series_steps: u64,
    /// `"simulated"`, or `"interpolated"` (then every count is 0: see `interpolation`).
    pub source: &'static str,
    /// When the run switched to RODAS4 because it had become stiff (unit of `t_s`), or null.
    pub stiff_from: Option<f64>,
    /// For a simulated run of a sweep whose speed the sweep tried to interpolate and gave up
    /// on: why (`"noise"`: a larger `[sweep].tolerance` helps; `"too-few-speeds"`: a kink or
    /// steep stretch, more speeds help; `"not-smooth"`: runs without a separation or failed
    /// split the range; `"budget"`); null otherwise.
    pub sweep_gave_up: Option<&'static str>,
    /// Contact duration (s), null where no time scale exists.
    pub t_d: Option<f64>,
    /// Separation time (nondimensional for nondimensional scenes, s otherwise), null without separation.
    pub t_s: Option<f64>,
    /// As `e_error`, for `t_s` (its unit), where both runs separated.
    pub t_s_error: Option<f64>,
    /// Under `[solver] e_tol`: the tighter run that failed, so that the check stopped at the
    /// run before it (`rtol`, and `out_of_steps`: whether a larger `[solver] max_steps` would
    /// let it finish); null where none failed.
    pub tighter_failed: Option<FailedRunSummary>,
    /// Unit of `t_s`.
    pub time_unit: &'static str,
    /// Impact speed (m/s), null for nondimensional scenes.
    pub v0: Option<f64>,
}

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
    fn of((b, x_s): &crate::runs::Bounced) -> Self {
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
            runs: runs
                .iter()
                .map(|r| RunSummary {
                    v0: r.v0,
                    t_s: r.t_s,
                    e: r.e,
                    t_d: r.t_d,
                    separated: r.outcome == Outcome::Separated,
                    rhs_evals: r.stats.rhs_evals,
                    rtol: r.rtol.map(crate::format::tidy),
                    e_error: r.e_error,
                    t_s_error: r.t_s_error,
                    check: r.check.map(Check::name),
                    tighter_failed: r.tighter_failed.map(|f| FailedRunSummary {
                        rtol: crate::format::tidy(f.rtol),
                        out_of_steps: f.out_of_steps,
                    }),
                    double_double_declined: r.double_double_declined.map(|d| d.to_string()),
                    phase: r.phase,
                    arithmetic: if r.double_double {
                        "double-double"
                    } else {
                        "double"
                    },
                    accepted: r.stats.accepted,
                    rejected: r.stats.rejected,
                    events: r.stats.events,
                    interpolation: r.interpolation.map(|i| InterpolationSummary {
                        degree: i.degree,
                        estimate: i.estimate,
                        from: i.from,
                        to: i.to,
                    }),
                    source: source(r),
                    jacobians: r.stats.jacobians,
                    stiff_from: r.stiff_from,
                    sweep_gave_up: r.sweep_gave_up.map(|g| g.name()),
                    series_steps: r.series_steps,
                    model: r.model.name(),
                    name: r.name.clone(),
                    time_unit: r.time_unit,
                    outcome: r.outcome.name(),
                    error: r.error.clone(),
                    rest: r.rest.map(|q| RestSummary {
                        t: q.t,
                        x: q.x,
                        f: q.f,
                        u: q.u,
                    }),
                    t_c: r.t_c,
                    nondimensional: r.nondimensional.map(|q| NondimSummary {
                        B: q.b,
                        Gamma: q.gamma,
                        kappa: q.kappa,
                        sigma: q.sigma,
                        n: q.n,
                        p: q.p,
                    }),
                    bounces: sequence.then(|| r.bounces.iter().map(BounceSummary::of).collect()),
                })
                .collect(),
        }
    }

    /// The JSON text `bwc-simulate --json` prints for `runs`, the runs of `scene`: `{"command",
    /// "runs", "scene", "tool", "units", "version"}` ([`SummaryWriter`]).
    pub fn provenance_json(&self, scene: &Scene, runs: &[Run]) -> String {
        let mut w = SummaryWriter::array(Vec::new(), scene).expect("in-memory writer");
        w.add_summaries(&self.runs).expect("in-memory writer");
        let tally = crate::simulate::Tally::of(scene, runs);
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
        tally: &crate::simulate::Tally,
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
/// `time_unit`: that of `t_s` of every run ([`crate::simulate::Tally::time_unit`]; `None`
/// without runs: s).
pub fn units(scene: &Scene, time_unit: Option<&str>) -> serde_json::Value {
    let nd = "nondimensional";
    let t = time_unit.unwrap_or("s");
    let si = si_states(scene);
    let (m, ms, n) = if si { ("m", "m/s", "N") } else { (nd, nd, nd) };
    let bounces = serde_json::json!({"n": "count", "t_contact": "s", "v_in": "m/s",
        "v_out": "m/s", "e": "1", "t_s": "s", "apex": "m", "interval": "s", "x_s": "m",
        "outcome": "text"});
    serde_json::json!({
        "runs": {"v0": "m/s", "e": "1", "t_s": t, "t_d": "s", "T_c": "s", "stiff_from": t,
            "rest": {"t": t, "x": m, "F": n, "u": n}, "nondimensional": "1",
            "rhs_evals": "count", "accepted": "count", "rejected": "count", "events": "count",
            "jacobians": "count", "series_steps": "count", "source": "text",
            "rtol": "1", "e_error": "1", "t_s_error": t, "check": "text",
            "tighter_failed": {"rtol": "1", "out_of_steps": "true/false"}, "arithmetic": "text",
            "double_double_declined": "text", "phase": "true/false",
            "interpolation": {"degree": "count", "estimate": "1", "from": "m/s", "to": "m/s"},
            "name": "text", "model": "text", "outcome": "text", "separated": "true/false",
            "error": "text", "sweep_gave_up": "text", "time_unit": "text",
            "bounces": bounces},
        "sweep.csv": {"v_0": "m/s", "e": "1", "t_d": "s", "t_s": t, "separated": "true/false",
            "name": "text", "outcome": "text", "source": "text"},
        "trajectory.csv": {"v_0": "m/s", "name": "text", "t": t, "x": m, "v": ms, "u": n,
            "F": n, "z": m, "r": m, "y": m, "x_m_1": "m", "x_m_2": "m", "x_m": "m",
            "v_m_1": "m/s", "v_m_2": "m/s", "v_m": "m/s", "u_1": "N", "u_2": "N"},
        "loop.csv": {"v_0": "m/s", "x": m, "F": n, "name": "text"},
        "bounces.csv": bounces,
    })
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

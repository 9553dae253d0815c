//! One run in the JSON summary ([`RunSummary`]): every key with its unit and its value from a
//! [`Run`], each written once in the list below, from which the struct, its construction, the
//! `"units"` of a run ([`run_units`]) and the list of keys ([`RUN_KEYS`]) all come. A new key
//! is its entry here (in sorted order) and its row in the guide's `reference/outputs.md`; tests
//! check that every key has its unit and its row.

use super::{BounceSummary, FailedRunSummary, InterpolationSummary, NondimSummary, RestSummary};
use crate::impact::runs::{Outcome, Run};
use bw_models::Cor;
use bwc_ode::Stats;
use serde::Serialize;
use serde_json::{json, Value};

/// The units of a scene's runs: of its times (`t`), displacements (`m`) and forces (`n`):
/// SI, or nondimensional.
#[derive(Debug, Clone, Copy)]
pub(super) struct SceneUnits<'a> {
    pub t: &'a str,
    pub m: &'a str,
    pub n: &'a str,
}

/// What a key's value is computed from besides the run: how it was solved and whether the
/// scene is a sequence.
struct Solved<'a> {
    solver: Option<&'a Cor>,
    stats: Stats,
    sequence: bool,
}

/// `run_summary! { |r, s, u| $( docs key field: type = unit, value; )* }`: the struct
/// [`RunSummary`] with a field per entry (serialized under `key`), [`RunSummary::of`] with
/// each field's `value` (of the run `r` and its [`Solved`] `s`) and [`run_units`] with each
/// key's `unit` (of the [`SceneUnits`] `u`). Keys in sorted order, as serde_json's maps are.
macro_rules! run_summary {
    (|$r:ident, $s:ident, $u:ident| $(
        $(#[$meta:meta])*
        $key:literal $field:ident: $ty:ty = $unit:expr, $value:expr;
    )*) => {
        /// One run in the JSON summary. Key names are a fixed contract; keys may be added.
        #[derive(Debug, Serialize)]
        pub struct RunSummary {
            $(
                $(#[$meta])*
                #[serde(rename = $key)]
                pub $field: $ty,
            )*
        }

        impl RunSummary {
            /// The summary of run `r` (with its bounces in a `sequence` scene).
            pub fn of($r: &Run, sequence: bool) -> Self {
                let solver = $r.solver.as_ref();
                let $s = Solved {
                    solver,
                    stats: solver.map(|c| c.stats).unwrap_or_default(),
                    sequence,
                };
                RunSummary { $($field: $value,)* }
            }
        }

        /// The keys of a run, in the order they are written.
        pub const RUN_KEYS: &[&str] = &[$($key),*];

        /// The unit of every key of a run, in the scene's units `u`.
        pub(super) fn run_units($u: SceneUnits<'_>) -> Value {
            let mut map = serde_json::Map::new();
            $(map.insert($key.to_string(), json!($unit));)*
            Value::Object(map)
        }
    };
}

run_summary! { |r, s, u|
    /// The time scale `T_c` (s): solver times (`t_max`, `max_step`) are multiples of it; null
    /// for nondimensional runs.
    "T_c" t_c: Option<f64> = "s", r.t_c;
    /// Accepted steps.
    "accepted" accepted: u64 = "count", s.stats.accepted;
    /// `"double"`, or `"double-double"` where the reported run is the double-double one
    /// (`[solver] double_double`: the double-precision runs could not meet `e_tol`).
    "arithmetic" arithmetic: &'static str = "text",
        if s.solver.is_some_and(|c| c.double_double) { "double-double" } else { "double" };
    /// The contacts of a `[sequence]` scene (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    "bounces" bounces: Option<Vec<BounceSummary>> = super::bounce_units(),
        s.sequence.then(|| r.bounces.iter().map(BounceSummary::of).collect());
    /// What the check of `e` against `[solver] e_tol` found: `"met"` (`e_error` at most
    /// `e_tol`), `"unmet"` (above it, and no tighter run was possible), `"unverified"` (no run
    /// at another tolerance finished: `e` is one unchecked run) or `"off"` (one run: no `e_tol`,
    /// or a trajectory); null for an interpolated row or a failed run.
    "check" check: Option<&'static str> = "text", s.solver.map(|c| c.check.name());
    /// Where `check` is `"unmet"` under `[solver] double_double`: why the double-double retry
    /// reported nothing (`e` is then the double-precision one), as the predicate the warning
    /// prints after "the double-double retry" (`"was not tried: ..."`); null otherwise.
    "double_double_declined" double_double_declined: Option<String> = "text",
        s.solver.and_then(|c| c.double_double_declined).map(|d| d.to_string());
    /// Coefficient of restitution.
    "e" e: f64 = "1", r.e;
    /// The estimate of the error in `e` of a CoR checked against a run at another tolerance
    /// (`[solver] e_tol`); null for a single run, a trajectory or an interpolated row.
    "e_error" e_error: Option<f64> = "1", s.solver.and_then(|c| c.e_error);
    /// For a failed run, what went wrong and which setting would help; null otherwise.
    "error" error: Option<String> = "text", r.error.clone();
    /// Located events.
    "events" events: u64 = "count", s.stats.events;
    /// Where `e` and `t_s` came from an interpolant of the sweep (`"source": "interpolated"`):
    /// its error estimate and piece; null for a simulated run.
    "interpolation" interpolation: Option<InterpolationSummary> =
        json!({"degree": "count", "estimate": "1", "from": "m/s", "to": "m/s"}),
        r.interpolation.map(|i| InterpolationSummary {
            degree: i.degree,
            estimate: i.estimate,
            from: i.from,
            to: i.to,
        });
    /// Jacobian evaluations (RODAS4 steps).
    "jacobians" jacobians: u64 = "count", s.stats.jacobians;
    /// `"shccm"` or `"mcm"`.
    "model" model: &'static str = "text", r.model.name();
    /// System name, if any.
    "name" name: Option<String> = "text", r.name.clone();
    /// The nondimensional parameters the run integrated; null for a failed run.
    "nondimensional" nondimensional: Option<NondimSummary> = "1",
        r.nondimensional.map(|q| NondimSummary {
            B: q.b,
            Gamma: q.gamma,
            kappa: q.kappa,
            sigma: q.sigma,
            n: q.n,
            p: q.p,
        });
    /// How the run ended: `"separated"`, `"settled"`, `"horizon"` or `"failed"`.
    "outcome" outcome: &'static str = "text", r.outcome.name();
    /// Whether `e` and `t_s` came from the phase path (`[solver] phase`: quadratures in phase
    /// space, no time steps, so every count is 0 and `e_error` is its own estimate).
    "phase" phase: bool = "true/false", s.solver.is_some_and(|c| c.phase);
    /// Rejected steps.
    "rejected" rejected: u64 = "count", s.stats.rejected;
    /// For a settled contact, where it came to rest (`F + u = 0`); null otherwise.
    "rest" rest: Option<RestSummary> = json!({"t": u.t, "x": u.m, "F": u.n, "u": u.n}),
        r.rest.map(|q| RestSummary {
            t: q.t,
            x: q.x,
            f: q.f,
            u: q.u,
        });
    /// RHS evaluations (of every run behind a checked CoR).
    "rhs_evals" rhs_evals: u64 = "count", s.stats.rhs_evals;
    /// The relative tolerance of the reported run (`[solver] rtol`, or tighter where `e_tol`
    /// asked for it); null for an interpolated row or a failed run.
    "rtol" rtol: Option<f64> = "1", s.solver.map(|c| crate::format::tidy(c.rtol));
    /// Whether the bodies separated.
    "separated" separated: bool = "true/false", r.outcome == Outcome::Separated;
    /// Steps taken by Taylor series (0 on the Runge-Kutta path; counted in `accepted`).
    "series_steps" series_steps: u64 = "count", s.solver.map_or(0, |c| c.series_steps);
    /// `"simulated"`, or `"interpolated"` (then every count is 0: see `interpolation`).
    "source" source: &'static str = "text", super::source(r);
    /// When the run switched to RODAS4 because it had become stiff (unit of `t_s`), or null.
    "stiff_from" stiff_from: Option<f64> = u.t, s.solver.and_then(|c| c.stiff_from);
    /// For a simulated run of a sweep whose speed the sweep tried to interpolate and gave up
    /// on: why (`"noise"`: a larger `[sweep].tolerance` helps; `"too-few-speeds"`: a kink or
    /// steep stretch, more speeds help; `"not-smooth"`: runs without a separation or failed
    /// split the range; `"budget"`); null otherwise.
    "sweep_gave_up" sweep_gave_up: Option<&'static str> = "text",
        r.sweep_gave_up.map(|g| g.name());
    /// Contact duration (s), null where no time scale exists.
    "t_d" t_d: Option<f64> = "s", r.t_d;
    /// Separation time (nondimensional for nondimensional scenes, s otherwise), null without
    /// separation.
    "t_s" t_s: Option<f64> = u.t, r.t_s;
    /// As `e_error`, for `t_s` (its unit), where both runs separated.
    "t_s_error" t_s_error: Option<f64> = u.t, s.solver.and_then(|c| c.t_s_error);
    /// Under `[solver] e_tol`: the tighter run that failed, so that the check stopped at the
    /// run before it (`rtol`, and `out_of_steps`: whether a larger `[solver] max_steps` would
    /// let it finish); null where none failed.
    "tighter_failed" tighter_failed: Option<FailedRunSummary> =
        json!({"rtol": "1", "out_of_steps": "true/false"}),
        s.solver.and_then(|c| c.tighter_failed).map(|f| FailedRunSummary {
            rtol: crate::format::tidy(f.rtol),
            out_of_steps: f.out_of_steps,
        });
    /// Unit of `t_s`.
    "time_unit" time_unit: &'static str = "text", r.time_unit;
    /// Impact speed (m/s), null for nondimensional scenes.
    "v0" v0: Option<f64> = "m/s", r.v0;
}

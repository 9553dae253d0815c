//! Values as JSON keyed as a scene or a config writes them: base parameters (`[base]`), an
//! input (`[input]`) and solver settings (`[solver]`), for the provenance blocks of the pair
//! scenes, the chains and the configs.

use crate::signal::Signal;
use bw_models::{BaseParams, Settings, Stiffness};
use serde_json::{json, Value};

/// Base parameters keyed as in `[base]`.
pub(crate) fn base_json(b: &BaseParams) -> Value {
    json!({"B_b": b.b_b, "Gamma_b": b.gamma_b, "kappa": b.kappa, "sigma_b": b.sigma_b,
        "n": b.n, "p": b.p, "U_b": b.u_b, "T_b": b.t_b})
}

/// An input keyed as in `[input]`.
pub(crate) fn signal_json(s: &Signal) -> Value {
    match s {
        Signal::Constant(c) => json!({"kind": "constant", "value": c}),
        Signal::Arctan(a) => json!({"kind": "arctan", "m": a.m, "D": a.d, "omega": a.omega}),
        Signal::Table(t) => {
            let (ts, us): (Vec<f64>, Vec<f64>) = t.points().unzip();
            json!({"kind": "table", "t": ts, "u": us})
        }
        Signal::Sum(terms) => {
            json!({"kind": "sum", "terms": terms.iter().map(signal_json).collect::<Vec<_>>()})
        }
    }
}

/// Solver settings keyed as in `[solver]` (`max_step` null for none).
pub(crate) fn settings_json(s: &Settings) -> Value {
    let method = match s.stiffness {
        Stiffness::Rosenbrock => "rosenbrock".to_string(),
        _ => s.method.name.to_lowercase(),
    };
    json!({
        "method": method,
        "rtol": s.rtol,
        "atol": s.atol,
        "max_step": s.max_step.is_finite().then_some(s.max_step),
        "t_max": s.t_max,
        "max_steps": s.max_steps,
        "stop_at_kinks": s.stop_at_kinks,
        "switch_when_stiff": s.stiffness == Stiffness::Switch,
        "series": s.series,
        "e_tol": s.e_tol,
        "double_double": s.double_double,
        "phase": s.phase,
    })
}

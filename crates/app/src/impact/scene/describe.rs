//! A validated scene as JSON, every parameter with its unit's key and the defaults filled in:
//! the provenance block `"scene"` of `summary.json`.

use super::{OutputSpec, Scene, System, SystemSpec};
use crate::tables::{base_json, settings_json, signal_json};
use serde_json::{json, Value};

impl Scene {
    /// The scene as parsed: the systems with every parameter, the speeds, the solver settings
    /// and the outputs, defaults filled in (keys as in a scene file). The speeds of a study
    /// with more runs than `[output].summary_runs` (whose runs are listed in `runs.jsonl`, each
    /// with its `v0`) are given as `{"count", "first", "last", "listed_in"}`.
    pub fn describe(&self) -> Value {
        let v0 = if self.runs_listed_apart() {
            json!({"count": self.speeds.len(), "first": self.speeds.first(),
                "last": self.speeds.last(), "listed_in": crate::impact::output::RUNS_FILE})
        } else {
            json!(self.speeds)
        };
        json!({
            "path": self.path.display().to_string(),
            "systems": self.systems.iter().map(system).collect::<Vec<_>>(),
            "v0": v0,
            "solver": settings_json(&self.settings),
            "output": output(&self.output),
            "sequence": self.sequence.map(|q| sequence(&q)),
            "sweep": {"interpolate": self.sweep.interpolate, "tolerance": self.sweep.tolerance},
        })
    }
}

fn system(spec: &SystemSpec) -> Value {
    let mut v = match &spec.system {
        System::Nondimensional { params, u } => {
            let p = params.get();
            json!({"nondimensional": {"B": p.b, "Gamma": p.gamma, "kappa": p.kappa,
                "sigma": p.sigma, "n": p.n, "p": p.p, "U": u}})
        }
        System::Base {
            map,
            input,
            time_scale_known,
        } => {
            let mut b = base_json(map.base());
            if !time_scale_known {
                b["T_b"] = Value::Null;
            }
            json!({"base": b, "input": signal_json(input)})
        }
        System::Physical { params, m, input } => {
            let mut p = physical(params);
            p["m"] = json!(m);
            json!({"physical": p, "input": signal_json(input)})
        }
        System::Bodies { params, bodies } => {
            let ((m1, m2), (v1, v2), (l1, l2)) =
                (bodies.masses(), bodies.velocities(), bodies.distances());
            let (u1, u2) = bodies.inputs();
            // A fixed body 2 has m2 = +inf, which JSON cannot hold.
            let m2 = if m2.is_finite() {
                json!(m2)
            } else {
                json!("inf")
            };
            json!({
                "physical": physical(params),
                "bodies": {"m1": m1, "m2": m2, "v1": v1, "v2": v2, "l1": l1, "l2": l2,
                    "u1": signal_json(u1), "u2": signal_json(u2)},
            })
        }
    };
    v["model"] = json!(spec.kind.name());
    v["name"] = json!(spec.name);
    v
}

fn physical(params: &bw_models::PhysicalParams) -> Value {
    let l = params.law();
    json!({"k": l.k, "c": l.c, "n": l.n, "p": l.p, "alpha": l.alpha, "beta": l.beta,
        "gamma": l.gamma, "A": l.a})
}

fn output(o: &OutputSpec) -> Value {
    json!({"trajectory": o.trajectory, "dt": o.dt, "loops": o.loops, "sweep": o.sweep,
        "plots": o.plots, "summary_runs": o.summary_runs})
}

fn sequence(q: &super::SequenceSpec) -> Value {
    use bw_models::sequence::{Policy, Start};
    let (h0, v0) = match q.start {
        Start::Height(h) => (Some(h), None),
        Start::Speed(v) => (None, Some(v)),
    };
    let s = &q.settings;
    json!({"h0": h0, "v0": v0, "g": s.flight.g, "drag": s.flight.drag, "bounces": s.bounces,
        "policy": match s.policy { Policy::Reset => "reset", Policy::Carry => "carry" }})
}

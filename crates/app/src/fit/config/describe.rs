//! A validated config as JSON, defaults filled in: the provenance block `"config"` of
//! `summary.json`.

use super::{Config, FitConfig, LoopFitConfig};
use crate::tables::{base_json, settings_json, signal_json};
use bwc_identify::{Budget, Param, LAW_NAMES, NAMES};
use serde_json::{json, Map, Value};

impl Config {
    /// The config as parsed: every fit with its data file, objectives, searched and held
    /// quantities, search budget, seed and solver settings (keys as in a config file).
    pub fn describe(&self) -> Value {
        json!({
            "path": self.path.display().to_string(),
            "fit": self.fits.iter().map(fit).collect::<Vec<_>>(),
            "loop_fit": self.loop_fits.iter().map(loop_fit).collect::<Vec<_>>(),
        })
    }
}

fn fit(f: &FitConfig) -> Value {
    json!({
        "name": f.name,
        "model": f.model_name(),
        "data": f.data.path.display().to_string(),
        "points": f.data.points.len(),
        "objectives": {"J1": f.weights.j1, "J2": f.weights.j2},
        "quantities": fit_quantities(f),
        "known": f.space.known().map(|k| json!({"m": k.m, "k": k.k})),
        "input": signal_json(&f.input),
        "optimizer": optimizer(&f.budget, f.seed),
        "solver": settings_json(&f.settings),
        "start": f.start,
        "params": f.params.as_ref().map(base_json),
        "reference": f.reference.as_ref().map(|r| json!({"label": r.label, "params": base_json(&r.params)})),
        "pareto": f.pareto.map(|count| json!({"count": count})),
        "posterior": posterior(&f.posterior),
        "drops": f.drops.as_ref().map(|d| json!({
            "kind": match d.data.kind {
                bwc_identify::DropKind::Intervals => "intervals",
                bwc_identify::DropKind::Heights => "heights",
            },
            "rows": d.data.rows.len(),
            "sequence": {"m": d.setup.m, "g": d.setup.flight.g, "drag": d.setup.flight.drag,
                "timed_contacts": d.setup.timed_contacts},
        })),
    })
}

fn loop_fit(f: &LoopFitConfig) -> Value {
    json!({
        "name": f.name,
        "model": f.kind.name(),
        "m": f.m,
        "loops": f.loops.len(),
        "quantities": quantities(&LAW_NAMES, f.space.params()),
        "optimizer": optimizer(&f.budget, f.seed),
    })
}

/// Each quantity: its held value, `"derived"`, or its bounds and scale.
/// A fit's quantities by name: a family's only its damping parameter and `T_b`.
fn fit_quantities(f: &FitConfig) -> Value {
    let mut names = NAMES;
    for (i, n) in names.iter_mut().enumerate() {
        *n = f.space.name(i);
    }
    let mut v = quantities(&names, f.space.params());
    if let (Some(family), Some(m)) = (f.family, v.as_object_mut()) {
        m.retain(|k, _| k == family.param_name() || k == "T_b");
    }
    v
}

/// `[fit.posterior]` and `[fit.prior]` as parsed.
fn posterior(p: &super::PosteriorConfig) -> Value {
    json!({
        "particles": p.particles,
        "runs": p.runs,
        "noise": p.given_noise.map(|g| if g { "given" } else { "sampled" }),
        "sigma_e": p.sigma_e.map(|(lo, hi)| [lo, hi]),
        "sigma_t": p.sigma_t.map(|(lo, hi)| [lo, hi]),
        "draws": p.draws,
        "prior": p.priors.iter().map(|q| json!({"quantity": q.name, "normal": [q.mean, q.sd]})).collect::<Vec<_>>(),
    })
}

fn quantities(names: &[&str; 8], params: &[Param; 8]) -> Value {
    let mut m = Map::new();
    for (name, p) in names.iter().zip(params) {
        let v = match p {
            Param::Fixed(x) => json!(x),
            Param::Derived => json!("derived"),
            Param::Free { lo, hi, log } => {
                json!({"bounds": [lo, hi], "scale": if *log { "log" } else { "linear" }})
            }
        };
        m.insert((*name).to_string(), v);
    }
    Value::Object(m)
}

fn optimizer(b: &Budget, seed: u64) -> Value {
    json!({
        "particles": b.particles,
        "iterations": b.iterations,
        "polish": b.polish_iterations,
        "starts": b.starts,
        "max_starts": b.max_starts,
        "agree": b.agree,
        "tolerance": b.tolerance,
        "seed": seed,
    })
}

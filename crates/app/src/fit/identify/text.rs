//! The reports of [`super`] as the text `bwc-identify` prints: a fit ([`fit_text`]), a
//! hysteresis-loop fit ([`loop_fit_text`]) and a posterior ([`posterior_text`]). Pure
//! formatting: the front end only writes them out.

use super::{render, FitReport, LoopReport, PosteriorReport};
use std::fmt::Write;

/// One fit's result: costs, parameters (a family's under their own names), identifiability,
/// how the search ended (`tolerance`: the fit's agreement tolerance), intervals, predictions
/// and the reference beside it; one line each, the parameters' indented.
pub fn fit_text(r: &FitReport, tolerance: f64) -> String {
    let mut t = String::new();
    let costs = match &r.drop {
        Some(d) => format!("J_drop = {:.3e} {}", d.cost, d.unit()),
        None => format!(
            "J1 = {}, J2 = {}",
            r.costs.j1.map_or("-".into(), |j| format!("{j:.3e}")),
            r.costs.j2.map_or("-".into(), |j| format!("{j:.3e} s^2"))
        ),
    };
    let _ = writeln!(
        t,
        "{} ({}): {costs}, {} evaluations, {:.2} s",
        r.name, r.model, r.evaluations, r.wall_s
    );
    let _ = writeln!(t, "    {}", params_line(r));
    if let Some(id) = &r.identifiability {
        let sv: Vec<String> = (id.singular_values.iter())
            .map(|s| format!("{s:.2e}"))
            .collect();
        let _ = writeln!(
            t,
            "    sensitivity singular values [{}]; weakest direction: {}",
            sv.join(", "),
            id.weakest_names().join(" + ")
        );
    }
    if let Some(c) = &r.convergence {
        let bound = match r.at_bound.is_empty() {
            true => String::new(),
            false => format!("; on a bound: {}", r.at_bound.join(", ")),
        };
        let _ = writeln!(
            t,
            "    search: {} of {} starts agree within {} %{bound}",
            c.agreeing,
            c.starts,
            tolerance * 100.0
        );
    }
    if let Some(Ok(u)) = &r.uncertainty {
        let iv: Vec<String> = (u.params.iter())
            .map(|(n, i)| match i {
                Some([lo, hi]) => format!("{n} [{}, {}]", bound_text(*lo), bound_text(*hi)),
                None => format!("{n} on its bound"),
            })
            .collect();
        let _ = writeln!(t, "    95 % intervals ({}): {}", u.method, iv.join(", "));
    }
    if let Some(s) = r.curve.first().and(predictions_summary(r)) {
        let _ = writeln!(t, "    {s}");
    }
    if let Some(rf) = &r.reference {
        let _ = writeln!(t, "    {}", rf.summary);
    }
    t
}

/// The fitted parameters: `P*` (with `U_b`, `T_b` where they matter), or a family's
/// parameter (with `T_b` in s where it matters).
fn params_line(r: &FitReport) -> String {
    let p = r.params;
    let mut line = match &r.family {
        Some(law) => {
            let unit = match law.family.spec().param.unit {
                "-" => String::new(),
                u => format!(" {u}"),
            };
            format!("{} = {:.6e}{unit}", law.family.param_name(), law.param)
        }
        None => format!(
            "B_b = {:.6}, Gamma_b = {:.6}, kappa = {:.6}, sigma_b = {:.6e}, n = {:.6}, p = {:.6}",
            p.b_b, p.gamma_b, p.kappa, p.sigma_b, p.n, p.p
        ),
    };
    match (&r.family, r.uses_input_scales) {
        (Some(law), true) => line += &format!(", T_b = {:.6e} s", law.t_b),
        (None, true) => line += &format!(", U_b = {:.6e}, T_b = {:.6e}", p.u_b, p.t_b),
        (_, false) => {}
    }
    line
}

/// The sentence of the JSON's `predictions.e.summary`, if there are intervals.
fn predictions_summary(r: &FitReport) -> Option<String> {
    let v = render::summary(std::slice::from_ref(r));
    v["fits"][0]["predictions"]["e"]["summary"]
        .as_str()
        .map(String::from)
}

/// One hysteresis-loop fit's result: its cost and the fitted law.
pub fn loop_fit_text(r: &LoopReport) -> String {
    let l = r.law;
    format!(
        "{} ({}, loops): cost = {:.3e}, {} evaluations, {:.2} s\n    k = {:.6e}, c = {:.6e}, \
         n = {:.4}, p = {:.4}, alpha = {:.4}, beta = {:.4e}, gamma = {:.4e}, A = {:.4}\n",
        r.name,
        r.model,
        r.cost,
        r.evaluations,
        r.wall_s,
        l.k,
        l.c,
        l.n,
        l.p,
        l.alpha,
        l.beta,
        l.gamma,
        l.a
    )
}

/// One posterior: the evidence, the sampler's effort, the noise and the marginals with units.
pub fn posterior_text(r: &PosteriorReport) -> String {
    let mut t = format!(
        "{} ({}): log Z = {:.3} +- {:.3}, {} evaluations, {:.2} s, {} runs x {} particles, ESS \
         {:.0}\n    noise: {}\n",
        r.name,
        r.model,
        r.log_evidence,
        r.log_evidence_error,
        r.evaluations,
        r.wall_s,
        r.runs,
        r.particles,
        r.ess,
        r.noise
    );
    for m in &r.marginals {
        let unit = match super::unit_of(m.name) {
            "-" => String::new(),
            u => format!(" {u}"),
        };
        let _ = writeln!(
            t,
            "    {:8} median {:.4e}, 95 % credible [{:.4e}, {:.4e}]{unit}",
            m.name, m.median, m.interval[0], m.interval[1]
        );
    }
    t
}

/// An interval's end: four decimals, or four significant digits where those would round a
/// small value away (a `T_b` of microseconds).
fn bound_text(x: f64) -> String {
    if x == 0.0 || x.abs() >= 0.01 {
        format!("{x:.4}")
    } else {
        format!("{x:.4e}")
    }
}

#[cfg(test)]
mod tests {
    /// A duration scale of microseconds keeps its digits (it printed as `[0.0000, 0.0000]`).
    #[test]
    fn small_interval_ends_keep_their_digits() {
        assert_eq!(super::bound_text(7.0727e-6), "7.0727e-6");
        assert_eq!(super::bound_text(-14.75286), "-14.7529");
        assert_eq!(super::bound_text(0.0), "0.0000");
    }
}

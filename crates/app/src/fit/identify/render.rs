//! The reports of [`super`] as JSON, CSV and SVG: pure formatting, no simulation.

use super::reference::ReferenceReport;
use super::report::{DropOutcome, FitReport, LoopReport};
use crate::fit::config::{FitConfig, LoopFitConfig};
use crate::plot::{self, Axis, Series, Style};
use crate::AppError;
use bw_models::{BaseParams, FamilyParams};
use bwc_identify::{BandPoint, Uncertainty};
use serde_json::{json, Value};
use std::path::Path;

/// A law's parameters: `P*`, or a family's parameter and `T_b` under their own names.
fn params_json(p: &BaseParams, family: Option<&FamilyParams>, input_scales: bool) -> Value {
    if let Some(law) = family {
        let mut v = json!({ "T_b": input_scales.then_some(law.t_b) });
        v[law.family.param_name()] = json!(law.param);
        return v;
    }
    json!({
        "B_b": p.b_b, "Gamma_b": p.gamma_b, "kappa": p.kappa, "sigma_b": p.sigma_b, "n": p.n, "p": p.p,
        "U_b": input_scales.then_some(p.u_b), "T_b": input_scales.then_some(p.t_b),
    })
}

/// The JSON summary `{"fits": [...]}` (key names are a fixed contract; keys may be added).
pub fn summary(reports: &[FitReport]) -> Value {
    let fits: Vec<Value> = reports
        .iter()
        .map(|r| {
            let mut v = json!({
                "name": r.name, "model": r.model, "params": params_json(&r.params, r.family.as_ref(), r.uses_input_scales),
                "J1": r.costs.j1, "J2": r.costs.j2, "evaluations": r.evaluations, "wall_s": r.wall_s,
            });
            if let Some(id) = &r.identifiability {
                let weakest: serde_json::Map<String, Value> = id.names.iter().zip(&id.weakest).map(|(n, w)| (n.to_string(), json!(w))).collect();
                v["identifiability"] = json!({
                    "singular_values": id.singular_values,
                    "condition": if id.condition.is_finite() { json!(id.condition) } else { Value::Null },
                    "weakest_direction": weakest,
                });
            }
            if let Some(c) = &r.convergence {
                v["convergence"] = json!({"starts": c.starts, "agreeing": c.agreeing, "evaluations": c.evaluations, "costs": c.costs});
                v["at_bound"] = json!(r.at_bound);
            }
            match &r.uncertainty {
                Some(Ok(u)) => {
                    v["intervals"] = intervals_json(u);
                    v["predictions"] = determined(r);
                }
                Some(Err(why)) => v["intervals"] = json!({"method": null, "error": why}),
                None => {}
            }
            if let Some(d) = &r.drop {
                v["J_drop"] = json!(d.cost);
                v["J_drop_unit"] = json!(d.unit());
                v["drops"] = d
                    .rows
                    .iter()
                    .map(|(row, model)| {
                        json!({"h0": row.h0, "bounce_n": row.bounce_n, "measured": row.value,
                            "model": if model.is_finite() { json!(model) } else { Value::Null }})
                    })
                    .collect();
            }
            if let Some(rf) = &r.reference {
                v["reference"] = reference_json(rf, r.uses_input_scales);
            }
            v["warnings"] = json!(r.warnings);
            if !r.pareto.is_empty() {
                v["pareto"] = r.pareto.iter().map(|p| json!({"w": p.w, "J1": p.j1, "J2": p.j2, "params": params_json(&p.params, p.family.as_ref(), r.uses_input_scales)})).collect();
            }
            v
        })
        .collect();
    json!({ "fits": fits })
}

/// The reference vector beside a fit: its parameters and costs, how it compares, and why.
fn reference_json(rf: &ReferenceReport, input_scales: bool) -> Value {
    json!({
        "label": rf.label,
        "params": params_json(&rf.params, None, input_scales),
        "J1": rf.costs.j1,
        "J2": rf.costs.j2,
        "cost_ratio": rf.cost_ratio,
        "standing": rf.standing.name(),
        "outside_bounds": rf.outside_bounds,
        "weak_share": rf.weak_share,
        "weak_directions": rf.weak_directions.0,
        "directions": rf.weak_directions.1,
        "weak_names": rf.weak_names,
        "summary": rf.summary,
    })
}

fn intervals_json(u: &Uncertainty) -> Value {
    let params: serde_json::Map<String, Value> = u
        .params
        .iter()
        .map(|(n, i)| (n.to_string(), json!(i)))
        .collect();
    json!({
        "method": u.method, "level": u.level, "params": params, "clipped": u.clipped,
        "sigma": u.sigma_e.or(u.sigma_t_d), "sigma_e": u.sigma_e, "sigma_t_d": u.sigma_t_d,
        "dof": u.dof, "rank": u.rank,
    })
}

/// What the data pin down: the band's half-width of `e` (and `t_d`) inside the measured speed
/// range and at half the slowest and twice the fastest speed, with a sentence saying so.
fn determined(r: &FitReport) -> Value {
    let (lo, hi) = r.predictions.iter().fold((f64::INFINITY, 0.0f64), |a, p| {
        (a.0.min(p.v0), a.1.max(p.v0))
    });
    let half = |b: &BandPoint, q: usize| {
        if q == 0 {
            (b.e[2] - b.e[1]) / 2.0
        } else {
            (b.t_d[2] - b.t_d[1]) / 2.0
        }
    };
    let quantity = |q: usize, unit: &str, name: &str| {
        let inside: Vec<f64> = r
            .curve
            .iter()
            .filter(|b| b.v0 >= lo * (1.0 - 1e-12) && b.v0 <= hi * (1.0 + 1e-12))
            .map(|b| half(b, q))
            .collect();
        let max_inside = inside.iter().copied().fold(0.0, f64::max);
        let (first, last) = (r.curve.first(), r.curve.last());
        // Without separation (no duration predicted) e = 0 there, with nothing to bound.
        let end = |b: &BandPoint| {
            (
                b.v0,
                if b.t_d[0].is_nan() {
                    f64::NAN
                } else {
                    half(b, q)
                },
            )
        };
        let below = first.map(end);
        let above = last.map(end);
        // At a speed where the model does not separate there is no duration to bound.
        let at = |b: Option<(f64, f64)>| match b {
            Some((v0, h)) if h.is_finite() => format!("+/-{h:.2e}{unit} at {} m/s", sig3(v0)),
            Some((v0, _)) => format!("no separation (e = 0) at {} m/s", sig3(v0)),
            None => "nothing".into(),
        };
        let sentence = format!(
            "{name} is determined to +/-{max_inside:.2e}{unit} over the measured {}-{} m/s; {} and {} outside it",
            sig3(lo),
            sig3(hi),
            at(below),
            at(above),
        );
        json!({
            "inside": {"v0": [lo, hi], "halfwidth_max": max_inside},
            "below": below.map(|b| json!({"v0": b.0, "halfwidth": b.1})),
            "above": above.map(|b| json!({"v0": b.0, "halfwidth": b.1})),
            "summary": sentence,
        })
    };
    let mut v = json!({ "e": quantity(0, "", "e") });
    if r.uses_input_scales && r.costs.j2.is_some() {
        v["t_d"] = quantity(1, " s", "t_d");
    }
    v
}

/// `x` with three significant digits (a speed in a sentence).
fn sig3(x: f64) -> String {
    let decimals = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

/// File-name stem of a fit: lowercase letters, digits and `_`.
pub fn slug(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect();
    let s = s
        .split('_')
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join("_");
    if s.is_empty() {
        "fit".into()
    } else {
        s
    }
}

/// A fitted quantity with a chart of its own.
#[derive(Clone, Copy)]
enum Quantity {
    /// `e`.
    Cor,
    /// `t_d` (s).
    Duration,
}

impl Quantity {
    fn suffix(self) -> &'static str {
        match self {
            Quantity::Cor => "cor",
            Quantity::Duration => "t_d",
        }
    }
}

/// The chart of one fitted quantity: the data (with their spread), the fitted curve and its band.
fn fit_figure(
    f: &FitConfig,
    r: &FitReport,
    q: Quantity,
    band_label: &str,
    log_x: bool,
) -> Result<String, String> {
    let points = f.data.points.iter();
    let pick = |c: &BandPoint| match q {
        Quantity::Cor => c.e[0],
        Quantity::Duration => c.t_d[0],
    };
    let reference = r.reference.as_ref().map(|rf| {
        let cost = match q {
            Quantity::Cor => format!("J1 = {:.2e}", rf.costs.j1.unwrap_or(f64::NAN)),
            Quantity::Duration => format!("J2 = {:.2e} s^2", rf.costs.j2.unwrap_or(f64::NAN)),
        };
        let points: Vec<(f64, f64)> = rf.curve.iter().map(|c| (c.v0, pick(c))).collect();
        (format!("reference: {} ({cost})", rf.label), points)
    });
    let (data, model, label, title, y): (Vec<_>, Vec<_>, _, _, _) = match q {
        Quantity::Cor => (
            points
                .filter_map(|p| p.e.map(|e| (p.v0, e, p.spread)))
                .collect(),
            r.curve
                .iter()
                .map(|c| (c.v0, c.e[0], c.e[1], c.e[2]))
                .collect(),
            format!("J1 = {:.2e}", r.costs.j1.unwrap_or(f64::NAN)),
            "coefficient of restitution",
            "coefficient of restitution e (-)",
        ),
        Quantity::Duration => (
            points
                .filter_map(|p| p.t_d.map(|t| (p.v0, t, None)))
                .collect(),
            r.curve
                .iter()
                .map(|c| (c.v0, c.t_d[0], c.t_d[1], c.t_d[2]))
                .collect(),
            format!("J2 = {:.2e} s^2", r.costs.j2.unwrap_or(f64::NAN)),
            "contact duration",
            "contact duration t_d (s)",
        ),
    };
    plot::fit_chart(
        &format!("{}: {title}", r.name),
        ("impact speed v0 (m/s)", y),
        (
            if f.data.reconstructed {
                "data (reconstructed, not measured)"
            } else {
                "measured"
            },
            &data,
        ),
        (&format!("{} fit ({label})", model_name(r.model)), &model),
        reference.as_ref().map(|(l, p)| (l.as_str(), p.as_slice())),
        band_label,
        log_x,
    )
}

/// The name in a figure of a model given by its key: the paper's for the Bouc-Wen models
/// (`"shccm"`, `"mcm"`), a family's title ([`bw_models::FamilySpec::title`]).
fn model_name(key: &str) -> &'static str {
    if let Some(family) = bw_models::Family::parse(key) {
        return family.spec().title;
    }
    match bw_models::ModelKind::parse(key) {
        Some(bw_models::ModelKind::Shccm) => "NDBWSHCCM",
        Some(bw_models::ModelKind::Mcm) => "NDBWMCM",
        None => "model",
    }
}

/// Renders, per fit, a CSV of data vs model (with the band's limits where
/// there are intervals) and SVG plots (CoR and duration against v0 with the band, the Pareto
/// front).
///
/// # Errors
/// [`AppError::Csv`] or [`AppError::Plot`] when rendering fails.
pub fn render(
    fits: &[FitConfig],
    reports: &[FitReport],
    out: &Path,
) -> Result<Vec<(String, Vec<u8>)>, AppError> {
    let mut files = Vec::new();
    for (f, r) in fits.iter().zip(reports) {
        let stem = slug(&r.name);
        if let Some(d) = &r.drop {
            files.extend(drop_files(r, d, out, &stem)?);
            continue;
        }
        files.push(data_csv(f, r, out, &format!("{stem}.csv"))?);
        let perr = |name: &str| {
            let path = out.join(name);
            move |message: String| AppError::Plot { path, message }
        };
        let band_label = if r.band.is_empty() {
            ""
        } else {
            "95 % confidence band"
        };
        let log_x = spans_decade(f);
        let quantities = [
            (f.data.has_cor(), Quantity::Cor),
            (
                f.data.has_durations() && r.uses_input_scales,
                Quantity::Duration,
            ),
        ];
        for (_, q) in quantities.into_iter().filter(|(shown, _)| *shown) {
            let name = format!("{stem}_{}.svg", q.suffix());
            let svg = fit_figure(f, r, q, band_label, log_x).map_err(perr(&name))?;
            files.push((name, svg.into_bytes()));
        }
        if !r.pareto.is_empty() {
            files.extend(pareto_files(r, out, &stem)?);
        }
    }
    Ok(files)
}

/// Whether the data's speeds span more than a factor of 3 (then v0 is drawn on a log axis).
fn spans_decade(f: &FitConfig) -> bool {
    let (lo, hi) = f.data.points.iter().fold((f64::INFINITY, 0.0f64), |a, p| {
        (a.0.min(p.v0), a.1.max(p.v0))
    });
    hi > 3.0 * lo
}

/// `<stem>.csv`: v_0, e, e_model, t_d, t_d_model, and the band's e_lo, e_hi, t_d_lo, t_d_hi.
fn data_csv(
    f: &FitConfig,
    r: &FitReport,
    out: &Path,
    name: &str,
) -> Result<(String, Vec<u8>), AppError> {
    let cerr = |source| AppError::Csv {
        path: out.join(name),
        source,
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "v_0",
        "e",
        "e_model",
        "t_d",
        "t_d_model",
        "e_lo",
        "e_hi",
        "t_d_lo",
        "t_d_hi",
    ])
    .map_err(cerr)?;
    let o = |x: Option<f64>| x.map(|v| v.to_string()).unwrap_or_default();
    for (i, (d, p)) in f.data.points.iter().zip(&r.predictions).enumerate() {
        let b = r.band.get(i);
        let td = r.uses_input_scales;
        w.write_record([
            d.v0.to_string(),
            o(d.e),
            p.e.to_string(),
            o(d.t_d),
            o(td.then_some(p.t_d)),
            o(b.map(|b| b.e[1])),
            o(b.map(|b| b.e[2])),
            o(b.filter(|_| td).map(|b| b.t_d[1])),
            o(b.filter(|_| td).map(|b| b.t_d[2])),
        ])
        .map_err(cerr)?;
    }
    Ok((name.to_string(), w.into_inner().expect("in-memory writer")))
}

/// `<stem>_pareto.csv` and `<stem>_pareto.svg`.
fn pareto_files(r: &FitReport, out: &Path, stem: &str) -> Result<Vec<(String, Vec<u8>)>, AppError> {
    let name = format!("{stem}_pareto.csv");
    let mut w = csv::Writer::from_writer(Vec::new());
    // A family's fit: its parameter and T_b under their own names; a Bouc-Wen fit: P*.
    let header: Vec<String> = match r.family {
        Some(law) => vec!["w", "J1", "J2", law.family.param_name(), "T_b"],
        None => vec![
            "w", "J1", "J2", "B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "U_b", "T_b",
        ],
    }
    .into_iter()
    .map(String::from)
    .collect();
    let rows = std::iter::once(header).chain(r.pareto.iter().map(|p| {
        let values = match p.family {
            Some(law) => vec![p.w, p.j1, p.j2, law.param, law.t_b],
            None => {
                let q = p.params;
                vec![
                    p.w, p.j1, p.j2, q.b_b, q.gamma_b, q.kappa, q.sigma_b, q.n, q.p, q.u_b, q.t_b,
                ]
            }
        };
        values.into_iter().map(|x| x.to_string()).collect()
    }));
    for row in rows {
        w.write_record(&row).map_err(|source| AppError::Csv {
            path: out.join(&name),
            source,
        })?;
    }
    let svg_name = format!("{stem}_pareto.svg");
    let series = [Series {
        label: "Pareto front (one point per weight)".into(),
        points: r.pareto.iter().map(|p| (p.j1, p.j2)).collect(),
        style: Style::LineAndMarkers,
        color: 0,
    }];
    // Costs span orders of magnitude along a front: log axes where they do.
    let (x, y) = (
        Axis::log_if_spanning(
            "J1, mean squared CoR error (-)",
            r.pareto.iter().map(|p| p.j1),
            1.0,
        ),
        Axis::log_if_spanning(
            "J2, mean squared duration error (s^2)",
            r.pareto.iter().map(|p| p.j2),
            1.0,
        ),
    );
    let svg = plot::chart(&format!("{}: Pareto front", r.name), x, y, &series);
    csv_and_chart(out, (name, w), svg_name, svg)
}

/// JSON entries of loop fits (in `"fits"` after the base-parameter fits).
pub fn loop_summary(reports: &[LoopReport]) -> Vec<Value> {
    reports
        .iter()
        .map(|r| {
            let l = r.law;
            json!({
                "name": r.name, "model": r.model, "kind": "loops",
                "params": {"k": l.k, "c": l.c, "n": l.n, "p": l.p, "alpha": l.alpha, "beta": l.beta, "gamma": l.gamma, "A": l.a},
                "cost": r.cost, "J1": null, "J2": null, "evaluations": r.evaluations, "wall_s": r.wall_s,
                "convergence": r.convergence.as_ref().map(|c| json!({"starts": c.starts, "agreeing": c.agreeing, "evaluations": c.evaluations, "costs": c.costs})),
                "at_bound": r.at_bound,
                "warnings": r.warnings(),
            })
        })
        .collect()
}

/// Renders a loop fit: `<name>_loops.csv` (v_0, source, x, F) and `<name>_loops.svg`.
///
/// # Errors
/// [`AppError::Csv`] or [`AppError::Plot`] when rendering fails.
pub fn render_loops(
    f: &LoopFitConfig,
    r: &LoopReport,
    out: &Path,
) -> Result<Vec<(String, Vec<u8>)>, AppError> {
    let stem = slug(&r.name);
    let csv_name = format!("{stem}_loops.csv");
    let mut w = csv::Writer::from_writer(Vec::new());
    let cerr = |source| AppError::Csv {
        path: out.join(&csv_name),
        source,
    };
    w.write_record(["v_0", "source", "x", "F"]).map_err(cerr)?;
    let mut series = Vec::new();
    for (l, c) in f.loops.iter().zip(&r.curves) {
        let data: Vec<(f64, f64)> = l.x.iter().copied().zip(l.f.iter().copied()).collect();
        for (source, points) in [("data", &data), ("model", c)] {
            for (x, force) in points {
                w.write_record([
                    l.v0.to_string(),
                    source.into(),
                    x.to_string(),
                    force.to_string(),
                ])
                .map_err(|source| AppError::Csv {
                    path: out.join(&csv_name),
                    source,
                })?;
            }
        }
        // The data and the model at one speed share a colour.
        let color = series.len() / 2;
        series.push(Series {
            label: format!("measured, v0 = {} m/s", l.v0),
            points: l.x.iter().zip(&l.f).map(|(x, f)| (-x * 1e3, *f)).collect(),
            style: Style::Markers,
            color,
        });
        series.push(Series {
            label: format!(
                "{} model, v0 = {} m/s",
                model_name(r.model).trim_start_matches("ND"),
                l.v0
            ),
            points: c.iter().map(|(x, f)| (-x * 1e3, *f)).collect(),
            style: Style::Line,
            color,
        });
    }
    let svg_name = format!("{stem}_loops.svg");
    let svg = plot::chart(
        &format!("{}: loops (cost {:.2e})", r.name, r.cost),
        Axis::linear("compression |x| (mm)"),
        Axis::linear("contact force F (N)"),
        &series,
    );
    csv_and_chart(out, (csv_name, w), svg_name, svg)
}

/// The unit of every JSON key and CSV column of an identification (`"1"`: dimensionless; the
/// base parameters carry powers of the impact speed in m/s, from the map `P(P*, u, v0)`).
pub fn units() -> serde_json::Value {
    let mut params = serde_json::json!({
        "B_b": "(m/s)^(-2n/(p+1))", "Gamma_b": "(m/s)^(-2n/(p+1))", "kappa": "1",
        "sigma_b": "NDBWSHCCM (m/s)^-1, NDBWMCM (m/s)^(-(p-1)/(p+1))", "n": "1", "p": "1",
        "U_b": "(m/s)^(2p/(p+1)) / N", "T_b": "s (m/s)^((p-1)/(p+1))",
    });
    // A contact-law family's parameter, under its own name (also a column of its Pareto front).
    let mut pareto = json!({"w": "1", "J1": "1", "J2": "s^2", "B_b": params["B_b"],
        "Gamma_b": params["Gamma_b"], "kappa": "1", "sigma_b": params["sigma_b"], "n": "1",
        "p": "1", "U_b": params["U_b"], "T_b": params["T_b"]});
    for p in bw_models::FAMILIES.iter().map(|f| f.spec().param) {
        let unit = json!(if p.unit == "-" { "1" } else { p.unit });
        params[p.name] = unit.clone();
        pareto[p.name] = unit;
    }
    serde_json::json!({
        "params": params,
        "J1": "1", "J2": "s^2", "J_drop": "s^2 (intervals) or m^2 (rebound heights)", "wall_s": "s",
        "intervals": {"sigma": "1 (e) or s (t_d, duration-only fits)", "sigma_e": "1",
            "sigma_t_d": "s", "dof": "count", "rank": "count", "level": "1"},
        "drops": {"h0": "m", "bounce_n": "count", "measured": "s or m", "model": "s or m"},
        "<fit>_drops.csv": {"h0": "m", "bounce_n": "count", "measured": "s (interval) or m (h1)",
            "model": "s (interval) or m (h1)"},
        "<fit>.csv": {"v_0": "m/s", "e": "1", "e_model": "1", "t_d": "s", "t_d_model": "s",
            "e_lo": "1", "e_hi": "1", "t_d_lo": "s", "t_d_hi": "s"},
        "<fit>_pareto.csv": pareto,
        "<loop fit>_loops.csv": {"v_0": "m/s", "source": "data or model", "x": "m", "F": "N"},
    })
}

/// `<stem>_drops.csv` (h0, bounce_n, measured, model) and `<stem>_drops.svg`: measured
/// intervals against the bounce number, one colour per release height, the model as a line
/// (or the rebound heights against the release height).
fn drop_files(
    r: &FitReport,
    d: &DropOutcome,
    out: &Path,
    stem: &str,
) -> Result<Vec<(String, Vec<u8>)>, AppError> {
    let name = format!("{stem}_drops.csv");
    let cerr = |source| AppError::Csv {
        path: out.join(&name),
        source,
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(["h0", "bounce_n", "measured", "model"])
        .map_err(cerr)?;
    for (row, model) in &d.rows {
        let model = if model.is_finite() {
            model.to_string()
        } else {
            String::new()
        };
        w.write_record([
            row.h0.to_string(),
            row.bounce_n.to_string(),
            row.value.to_string(),
            model,
        ])
        .map_err(cerr)?;
    }
    let (series, (x, y, title)) = match d.kind {
        bwc_identify::DropKind::Intervals => (
            interval_series(r, d),
            (
                "bounce number n",
                "interval from impact n to n + 1 (s)",
                "bounce intervals",
            ),
        ),
        bwc_identify::DropKind::Heights => (
            height_series(r, d),
            (
                "release height h0 (m)",
                "rebound height h1 (m)",
                "rebound heights",
            ),
        ),
    };
    let svg_name = format!("{stem}_drops.svg");
    let svg = plot::chart(
        &format!("{}: {title} (J_drop = {:.2e} {})", r.name, d.cost, d.unit()),
        Axis::linear(x),
        Axis::linear(y),
        &series,
    );
    csv_and_chart(out, (name, w), svg_name, svg)
}

/// Measured bounce intervals against the bounce number, and the model's, per release height.
fn interval_series(r: &FitReport, d: &DropOutcome) -> Vec<Series> {
    let mut heights: Vec<f64> = d.rows.iter().map(|(row, _)| row.h0).collect();
    heights.sort_by(f64::total_cmp);
    heights.dedup();
    let mut series = Vec::new();
    for (i, h0) in heights.iter().enumerate() {
        let rows: Vec<_> = d.rows.iter().filter(|(row, _)| row.h0 == *h0).collect();
        series.push(Series {
            label: format!("measured, h0 = {h0} m"),
            points: rows
                .iter()
                .map(|(row, _)| (row.bounce_n as f64, row.value))
                .collect(),
            style: Style::Markers,
            color: i,
        });
        let mut model: Vec<(f64, f64)> = rows
            .iter()
            .map(|(row, m)| (row.bounce_n as f64, *m))
            .collect();
        model.sort_by(|a, b| a.0.total_cmp(&b.0));
        model.dedup_by(|a, b| a.0 == b.0);
        series.push(Series {
            label: format!("{} fit, h0 = {h0} m", model_name(r.model)),
            points: model,
            style: Style::LineAndMarkers,
            color: i,
        });
    }
    series
}

/// Measured rebound heights against the release height, and the model's.
fn height_series(r: &FitReport, d: &DropOutcome) -> Vec<Series> {
    let mut model: Vec<(f64, f64)> = d.rows.iter().map(|(row, m)| (row.h0, *m)).collect();
    model.sort_by(|a, b| a.0.total_cmp(&b.0));
    model.dedup_by(|a, b| a.0 == b.0);
    vec![
        Series {
            label: "measured".into(),
            points: d.rows.iter().map(|(row, _)| (row.h0, row.value)).collect(),
            style: Style::Markers,
            color: 3,
        },
        Series {
            label: format!("{} fit", model_name(r.model)),
            points: model,
            style: Style::LineAndMarkers,
            color: 0,
        },
    ]
}

/// A CSV and its chart as output files; a drawing error names the chart's file.
fn csv_and_chart(
    out: &Path,
    (csv_name, w): (String, csv::Writer<Vec<u8>>),
    svg_name: String,
    svg: Result<String, String>,
) -> Result<Vec<(String, Vec<u8>)>, AppError> {
    let svg = svg.map_err(|message| AppError::Plot {
        path: out.join(&svg_name),
        message,
    })?;
    Ok(vec![
        (csv_name, w.into_inner().expect("in-memory writer")),
        (svg_name, svg.into_bytes()),
    ])
}

//! Runs and evaluates the fits of an identification config, and renders their outputs.

use crate::config::FitConfig;
use crate::plot::{self, Series, SeriesLabelPosition};
use crate::CliError;
use bw_models::{BaseParams, Settings};
use bwc_identify::{
    analyse, fit, predict, Budget, Convergence, Costs, Identifiability, Objective, Prediction, Weights,
};
use serde_json::{json, Value};
use std::path::Path;
use std::time::Instant;

/// One point of a Pareto front.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoPoint {
    /// Weight of the normalised `J1` (that of `J2` is `1 - w`).
    pub w: f64,
    /// `J1` at the optimum of this weight.
    pub j1: f64,
    /// `J2` at the optimum of this weight.
    pub j2: f64,
    /// The optimum.
    pub params: BaseParams,
}

/// The result of one fit (or one evaluation).
#[derive(Debug, Clone)]
pub struct FitReport {
    /// Fit name.
    pub name: String,
    /// `"shccm"` or `"mcm"`.
    pub model: &'static str,
    /// Base parameters.
    pub params: BaseParams,
    /// Whether `U_b`, `T_b` are meaningful (otherwise reported as null).
    pub uses_input_scales: bool,
    /// Costs at the default (accurate) solver settings.
    pub costs: Costs,
    /// Cost evaluations.
    pub evaluations: u64,
    /// Wall time (s).
    pub wall_s: f64,
    /// Model predictions at the data points.
    pub predictions: Vec<Prediction>,
    /// Identifiability at the optimum (runs only).
    pub identifiability: Option<Identifiability>,
    /// How the search ended (runs only).
    pub convergence: Option<Convergence>,
    /// Free quantities on a bound of the search (runs only).
    pub at_bound: Vec<&'static str>,
    /// Pareto front, if asked for.
    pub pareto: Vec<ParetoPoint>,
}

fn fail<'a>(
    path: &'a Path,
    f: &'a FitConfig,
) -> impl Fn(bwc_identify::IdentifyError) -> CliError + 'a {
    let path = path.to_owned();
    move |source| CliError::Identify {
        path: path.clone(),
        fit: f.name.clone(),
        source,
    }
}

/// Fits `f` from its bounds (seeded by `seed` combined with the fit's own seed).
///
/// # Errors
/// [`CliError::Identify`] if the optimizer or a final evaluation fails.
pub fn run_fit(
    config: &Path,
    f: &FitConfig,
    seed: u64,
    progress: &(dyn Fn() + Sync),
) -> Result<FitReport, CliError> {
    let clock = Instant::now();
    let err = fail(config, f);
    let objective = Objective::new(&f.space, &f.data, &f.input, f.settings, f.weights)
        .map_err(&err)?
        .with_progress(progress);
    let result = fit(&objective, &f.budget, seed ^ f.seed, f.start.as_deref()).map_err(&err)?;
    // Report the costs at the default (accurate) settings.
    let exact = Objective::new(&f.space, &f.data, &f.input, Settings::default(), f.weights)
        .map_err(&err)?;
    let (predictions, costs) = exact.evaluate(&result.point).map_err(&err)?;
    let identifiability = Some(analyse(&exact, &result.point).map_err(&err)?);
    let mut evaluations = result.evaluations;
    let mut pareto = Vec::new();
    if let Some(count) = f.pareto {
        // Normalise each cost by the variance of its data so the weights are comparable.
        let var = |xs: Vec<f64>| {
            let m = xs.iter().sum::<f64>() / xs.len() as f64;
            (xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / xs.len() as f64).max(1e-30)
        };
        let ve = var(f.data.points.iter().filter_map(|p| p.e).collect());
        let vt = var(f.data.points.iter().filter_map(|p| p.t_d).collect());
        // Each weight starts from the main optimum: a small swarm and the full polish suffice.
        let budget = Budget {
            particles: (f.budget.particles / 4).max(8),
            iterations: f.budget.iterations / 4,
            ..f.budget.single()
        };
        for k in 0..count {
            let w = k as f64 / (count - 1) as f64;
            let weights = Weights {
                j1: w / ve,
                j2: (1.0 - w) / vt,
            };
            let o = Objective::new(&f.space, &f.data, &f.input, f.settings, weights)
                .map_err(&err)?
                .with_progress(progress);
            let r = fit(
                &o,
                &budget,
                seed ^ f.seed ^ (k as u64 + 1),
                Some(&result.point),
            )
            .map_err(&err)?;
            evaluations += r.evaluations;
            let (_, c) = exact.evaluate(&r.point).map_err(&err)?;
            pareto.push(ParetoPoint {
                w,
                j1: c.j1.unwrap_or(f64::NAN),
                j2: c.j2.unwrap_or(f64::NAN),
                params: r.params,
            });
        }
    }
    Ok(FitReport {
        name: f.name.clone(),
        model: f.kind.name(),
        params: result.params,
        uses_input_scales: f.uses_input_scales,
        costs,
        evaluations,
        wall_s: clock.elapsed().as_secs_f64(),
        predictions,
        identifiability,
        convergence: Some(result.convergence),
        at_bound: result.at_bound,
        pareto,
    })
}

/// Evaluates the costs of `f` at its `[fit.params]`.
///
/// # Errors
/// [`CliError::Invalid`] when the fit has no `[fit.params]`; [`CliError::Identify`] when a
/// simulation fails.
pub fn eval_fit(config: &Path, f: &FitConfig) -> Result<FitReport, CliError> {
    let clock = Instant::now();
    let err = fail(config, f);
    let params = f.params.ok_or_else(|| CliError::Invalid {
        path: config.to_owned(),
        line: 1,
        key: format!("[fit.params] of \"{}\"", f.name),
        message: "missing: `eval` needs the parameters to evaluate".into(),
    })?;
    let map = f.space.map(&params).map_err(&err)?;
    let predictions =
        predict(&map, &f.input, &f.data, &Settings::default()).map_err(|e| err(e.into()))?;
    let costs = Costs::of(&f.data, &predictions);
    Ok(FitReport {
        name: f.name.clone(),
        model: f.kind.name(),
        params,
        uses_input_scales: f.uses_input_scales,
        costs,
        evaluations: 1,
        wall_s: clock.elapsed().as_secs_f64(),
        predictions,
        identifiability: None,
        convergence: None,
        at_bound: Vec::new(),
        pareto: Vec::new(),
    })
}

fn params_json(p: &BaseParams, input_scales: bool) -> Value {
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
                "name": r.name, "model": r.model, "params": params_json(&r.params, r.uses_input_scales),
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
            if !r.pareto.is_empty() {
                v["pareto"] = r.pareto.iter().map(|p| json!({"w": p.w, "J1": p.j1, "J2": p.j2, "params": params_json(&p.params, r.uses_input_scales)})).collect();
            }
            v
        })
        .collect();
    json!({ "fits": fits })
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

/// Renders `summary.json` and, per fit, a CSV of data vs model and SVG plots (CoR and duration
/// against v0, the Pareto front).
///
/// # Errors
/// [`CliError::Csv`] or [`CliError::Plot`] when rendering fails; [`CliError::Identify`] if a
/// model curve cannot be computed.
pub fn render(
    config: &Path,
    fits: &[FitConfig],
    reports: &[FitReport],
    out: &Path,
) -> Result<Vec<(String, Vec<u8>)>, CliError> {
    let mut files = vec![(
        "summary.json".to_string(),
        (summary(reports).to_string() + "\n").into_bytes(),
    )];
    for (f, r) in fits.iter().zip(reports) {
        let stem = slug(&r.name);
        let csv_name = format!("{stem}.csv");
        let mut w = csv::Writer::from_writer(Vec::new());
        let cerr = |source| CliError::Csv {
            path: out.join(&csv_name),
            source,
        };
        w.write_record(["v_0", "e", "e_model", "t_d", "t_d_model"])
            .map_err(cerr)?;
        for (d, p) in f.data.points.iter().zip(&r.predictions) {
            let o = |x: Option<f64>| x.map(|v| v.to_string()).unwrap_or_default();
            w.write_record([
                d.v0.to_string(),
                o(d.e),
                p.e.to_string(),
                o(d.t_d),
                if r.uses_input_scales {
                    p.t_d.to_string()
                } else {
                    String::new()
                },
            ])
            .map_err(|source| CliError::Csv {
                path: out.join(&csv_name),
                source,
            })?;
        }
        files.push((csv_name, w.into_inner().expect("in-memory writer")));

        // Model curve on a log grid over the data's speed range.
        let (lo, hi) = f.data.points.iter().fold((f64::INFINITY, 0.0f64), |a, p| {
            (a.0.min(p.v0), a.1.max(p.v0))
        });
        let grid: Vec<f64> = (0..60)
            .map(|i| lo * (hi / lo).powf(i as f64 / 59.0))
            .collect();
        let curve_data = bwc_identify::Dataset {
            path: f.data.path.clone(),
            points: grid
                .iter()
                .map(|&v0| bwc_identify::Point {
                    v0,
                    e: None,
                    t_d: None,
                })
                .collect(),
        };
        let map = f.space.map(&r.params).map_err(fail(config, f))?;
        let curve = predict(&map, &f.input, &curve_data, &Settings::default())
            .map_err(|e| fail(config, f)(e.into()))?;
        let perr = |name: String| {
            move |message: String| CliError::Plot {
                path: out.join(&name),
                message,
            }
        };
        // Data points and the model curve of one aggregate quantity against v0.
        let quantity = |suffix: &str,
                        title: &str,
                        ylabel: &str,
                        cost: String,
                        data: &dyn Fn(&bwc_identify::Point) -> Option<f64>,
                        model: &dyn Fn(&Prediction) -> f64| {
            let name = format!("{stem}_{suffix}.svg");
            let series = [
                Series {
                    label: "data".into(),
                    points: f
                        .data
                        .points
                        .iter()
                        .filter_map(|p| data(p).map(|y| (p.v0, y)))
                        .collect(),
                },
                Series {
                    label: format!("{} ({cost})", r.model),
                    points: curve.iter().map(|c| (c.v0, model(c))).collect(),
                },
            ];
            plot::chart(
                &format!("{}: {title}", r.name),
                "v0 (m/s)",
                ylabel,
                &series,
                false,
                SeriesLabelPosition::UpperRight,
            )
            .map(|svg| (name.clone(), svg.into_bytes()))
            .map_err(perr(name))
        };
        if f.data.has_cor() {
            let cost = format!("J1 = {:.2e}", r.costs.j1.unwrap_or(f64::NAN));
            files.push(quantity("cor", "CoR", "e", cost, &|p| p.e, &|c| c.e)?);
        }
        if f.data.has_durations() && r.uses_input_scales {
            let cost = format!("J2 = {:.2e}", r.costs.j2.unwrap_or(f64::NAN));
            files.push(quantity(
                "t_d",
                "contact duration",
                "t_d (s)",
                cost,
                &|p| p.t_d,
                &|c| c.t_d,
            )?);
        }
        if !r.pareto.is_empty() {
            let name = format!("{stem}_pareto.csv");
            let mut w = csv::Writer::from_writer(Vec::new());
            let rows = std::iter::once(
                [
                    "w", "J1", "J2", "B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "U_b", "T_b",
                ]
                .map(String::from),
            )
            .chain(r.pareto.iter().map(|p| {
                let q = p.params;
                [
                    p.w, p.j1, p.j2, q.b_b, q.gamma_b, q.kappa, q.sigma_b, q.n, q.p, q.u_b, q.t_b,
                ]
                .map(|x| x.to_string())
            }));
            for row in rows {
                w.write_record(&row).map_err(|source| CliError::Csv {
                    path: out.join(&name),
                    source,
                })?;
            }
            files.push((name, w.into_inner().expect("in-memory writer")));
            let svg_name = format!("{stem}_pareto.svg");
            let series = [Series {
                label: "Pareto front".into(),
                points: r.pareto.iter().map(|p| (p.j1, p.j2)).collect(),
            }];
            let svg = plot::chart(
                &format!("{}: Pareto front", r.name),
                "J1",
                "J2 (s^2)",
                &series,
                true,
                SeriesLabelPosition::UpperRight,
            )
            .map_err(perr(svg_name.clone()))?;
            files.push((svg_name, svg.into_bytes()));
        }
    }
    Ok(files)
}

/// The result of one loop fit (or evaluation).
#[derive(Debug, Clone)]
pub struct LoopReport {
    /// Fit name.
    pub name: String,
    /// `"shccm"` or `"mcm"`.
    pub model: &'static str,
    /// The contact law (SI).
    pub law: bw_models::Physical,
    /// Loop cost at the law (see `bwc_identify::loop_cost`).
    pub cost: f64,
    /// Cost evaluations.
    pub evaluations: u64,
    /// Wall time (s).
    pub wall_s: f64,
    /// Simulated loops, one per measured loop.
    pub curves: Vec<bwc_identify::Curve>,
}

/// Fits the contact law of a loop fit from its bounds.
///
/// # Errors
/// [`CliError::Identify`] if the optimizer or the final evaluation fails.
pub fn run_loop_fit(
    config: &Path,
    f: &crate::config::LoopFitConfig,
    seed: u64,
    progress: &(dyn Fn() + Sync),
) -> Result<LoopReport, CliError> {
    let clock = Instant::now();
    let err = |source| CliError::Identify {
        path: config.to_owned(),
        fit: f.name.clone(),
        source,
    };
    let objective = bwc_identify::LoopObjective::new(&f.space, &f.loops, f.m, Settings::default())
        .map_err(err)?;
    let counted = Counted {
        inner: &objective,
        progress,
    };
    let min = bwc_identify::minimize(&counted, &f.budget, seed ^ f.seed, None).map_err(err)?;
    let (cost, curves) = objective.evaluate(&min.point).map_err(err)?;
    Ok(LoopReport {
        name: f.name.clone(),
        model: f.kind.name(),
        law: f.space.decode(&min.point),
        cost,
        evaluations: min.evaluations,
        wall_s: clock.elapsed().as_secs_f64(),
        curves,
    })
}

/// Evaluates the loop cost at a loop fit's `[loop_fit.params]`.
///
/// # Errors
/// [`CliError::Invalid`] without `[loop_fit.params]`; [`CliError::Identify`] when a simulation fails.
pub fn eval_loop_fit(
    config: &Path,
    f: &crate::config::LoopFitConfig,
) -> Result<LoopReport, CliError> {
    let clock = Instant::now();
    let law = f.params.ok_or_else(|| CliError::Invalid {
        path: config.to_owned(),
        line: 1,
        key: format!("[loop_fit.params] of \"{}\"", f.name),
        message: "missing: `eval` needs the parameters to evaluate".into(),
    })?;
    let err = |source| CliError::Identify {
        path: config.to_owned(),
        fit: f.name.clone(),
        source,
    };
    let objective = bwc_identify::LoopObjective::new(&f.space, &f.loops, f.m, Settings::default())
        .map_err(err)?;
    let curves = objective.simulate(&law).map_err(err)?;
    let cost = f
        .loops
        .iter()
        .zip(&curves)
        .map(|(l, c)| bwc_identify::loop_cost(l, c))
        .sum::<f64>()
        / f.loops.len() as f64;
    Ok(LoopReport {
        name: f.name.clone(),
        model: f.kind.name(),
        law,
        cost,
        evaluations: 1,
        wall_s: clock.elapsed().as_secs_f64(),
        curves,
    })
}

/// Counts progress for a cube problem.
struct Counted<'a, P> {
    inner: &'a P,
    progress: &'a (dyn Fn() + Sync),
}

impl<P: bwc_identify::CubeProblem> bwc_identify::CubeProblem for Counted<'_, P> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn cost_at(&self, s: &[f64]) -> f64 {
        (self.progress)();
        self.inner.cost_at(s)
    }
    fn evaluations(&self) -> u64 {
        self.inner.evaluations()
    }
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
            })
        })
        .collect()
}

/// Renders a loop fit: `<name>_loops.csv` (v_0, source, x, F) and `<name>_loops.svg`.
///
/// # Errors
/// [`CliError::Csv`] or [`CliError::Plot`] when rendering fails.
pub fn render_loops(
    f: &crate::config::LoopFitConfig,
    r: &LoopReport,
    out: &Path,
) -> Result<Vec<(String, Vec<u8>)>, CliError> {
    let stem = slug(&r.name);
    let csv_name = format!("{stem}_loops.csv");
    let mut w = csv::Writer::from_writer(Vec::new());
    let cerr = |source| CliError::Csv {
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
                .map_err(|source| CliError::Csv {
                    path: out.join(&csv_name),
                    source,
                })?;
            }
        }
        series.push(Series {
            label: format!("data, v0 = {} m/s", l.v0),
            points: l.x.iter().zip(&l.f).map(|(x, f)| (-x * 1e3, *f)).collect(),
        });
        series.push(Series {
            label: format!("{}, v0 = {} m/s", r.model, l.v0),
            points: c.iter().map(|(x, f)| (-x * 1e3, *f)).collect(),
        });
    }
    let svg_name = format!("{stem}_loops.svg");
    let svg = plot::chart(
        &format!("{}: loops (cost {:.2e})", r.name, r.cost),
        "|x| (mm)",
        "F (N)",
        &series,
        false,
        SeriesLabelPosition::UpperLeft,
    )
    .map_err(|message| CliError::Plot {
        path: out.join(&svg_name),
        message,
    })?;
    Ok(vec![
        (csv_name, w.into_inner().expect("in-memory writer")),
        (svg_name, svg.into_bytes()),
    ])
}

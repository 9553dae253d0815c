//! The Bouc-Wen laws fitted to a law from materials: the reference law's CoR and duration at
//! the table's speeds as a dataset, a config with one `[[fit]]` per model on it, and how
//! closely each fit follows the reference.

use super::{MaterialsReport, MaterialsSpec};
use crate::fit::config::Config;
use crate::fit::identify::{fit_all, FitReport, LoopReport};
use crate::AppError;
use bw_models::input::Zero;
use std::path::Path;

/// The name of the reference's dataset in the output folder.
pub const REFERENCE_CSV: &str = "reference.csv";
/// The name of the fits' config in the output folder.
pub const FIT_TOML: &str = "fit.toml";

/// How closely one fitted Bouc-Wen law follows the reference law.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Following {
    /// The fit.
    pub fit: FitReport,
    /// The largest `|e - e_ref|`.
    pub e_error: f64,
    /// The largest `|t_d - t_d,ref| / t_d,ref`.
    pub t_d_error: f64,
    /// The largest `|F_max - F_max,ref| / F_max,ref` (the peak force, sampled at 1/2000 of
    /// the reference's duration); NaN where the fit gives no SI law.
    pub force_error: f64,
    /// The speeds (m/s) where `|e - e_ref| > 0.01`, the duration is off by more than 5 % or
    /// the peak force by more than 10 %.
    pub stops_following: Vec<f64>,
    /// The pair's effective mass (kg): with it the fit's base parameters give the SI law.
    pub mass: f64,
}

/// The reference dataset: `v_0,e,t_d` at the table's speeds, with header lines saying what
/// it is.
pub fn reference_csv(spec: &MaterialsSpec, report: &MaterialsReport) -> String {
    let mut out = format!(
        "# REFERENCE LAW, not measured: Thornton's (1997) elastic-perfectly-plastic law from the \
         materials of {}\n# (bwc-identify materials); e in closed form, t_d (s) from its \
         simulated impact.\nv_0,e,t_d\n",
        spec.path.display()
    );
    for r in &report.rows {
        out += &format!("{:?},{:?},{:?}\n", r.v0, r.e, r.t_d);
    }
    out
}

/// The config of the two fits on [`REFERENCE_CSV`]: the BWSHCCM and the BWMCM, CoR and
/// duration weighted alike (`J2` scaled by the mean duration), `T_b` searched on a log scale
/// over two decades either side of the Hertz law's.
pub fn fit_toml(report: &MaterialsReport) -> String {
    let p = &report.pair;
    let mean_t: f64 = report.rows.iter().map(|r| r.t_d).sum::<f64>() / report.rows.len() as f64;
    let mut out = String::from(
        "# The Bouc-Wen laws fitted to a law from materials (bwc-identify materials --fit):\n\
         # reference.csv holds the reference law's CoR and duration.\n",
    );
    for model in ["shccm", "mcm"] {
        out += &format!(
            "\n[[fit]]\nname = \"materials {model}\"\nmodel = \"{model}\"\ndata = \"{REFERENCE_CSV}\"\n\
             objectives = {{ J1 = 1.0, J2 = {:?} }}\nlog = [\"sigma_b\", \"T_b\"]\n\n\
             [fit.bounds]\nB_b = [0.0, 100.0]\ng = [-1.0, 1.0]\n\
             kappa = [0.02, 0.98]\nsigma_b = [1.0e-5, 0.5]\nn = [1.0, 6.0]\np = [1.0, 3.0]\n\
             T_b = [{:?}, {:?}]\n\n[fit.fixed]\nU_b = 1.0   # unused: no external force\n",
            1.0 / (mean_t * mean_t),
            p.t_b / 100.0,
            p.t_b * 100.0
        );
    }
    out + &loop_fits_toml(report)
}

/// The `[[loop_fit]]`s of both models on the reference loops ([`loop_rows`]), their bounds
/// wide around the loops' own scales: `k` and `c` from `F_max / δ_max^p` over `p` in
/// `[1, 2]`, `beta` from `1 / δ_max^n`.
fn loop_fits_toml(report: &MaterialsReport) -> String {
    let rows = loop_rows(report);
    let Some(top) = rows.last() else {
        return String::new();
    };
    let (d, f, v) = (top.delta_max, top.force_max, top.v0);
    let loops: Vec<String> = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            format!(
                "{{ data = \"reference_loop_{}.csv\", v0 = {:?} }}",
                i + 1,
                r.v0
            )
        })
        .collect();
    let mut out = String::new();
    for model in ["shccm", "mcm"] {
        out += &format!(
            "\n[[loop_fit]]\nname = \"materials loops {model}\"\nmodel = \"{model}\"\nm = {:?}\n\
             loops = [{}]\nlog = [\"k\", \"c\", \"beta\"]\n\n[loop_fit.bounds]\n\
             k = [{:?}, {:?}]\nc = [{:?}, {:?}]\nn = [1.0, 2.0]\np = [1.0, 2.0]\n\
             alpha = [0.02, 0.98]\nbeta = [{:?}, {:?}]\ng = [-1.0, 1.0]\nA = [0.5, 1.5]\n\n\
             [loop_fit.optimizer]\nparticles = 32\niterations = 60\nstarts = 2\n",
            report.pair.m_star,
            loops.join(", "),
            1e-2 * f / d,
            1e2 * f / (d * d),
            1e-3 * f / (d * v),
            1e2 * f / (d * d * v),
            1e-2 / d,
            1e2 / (d * d),
        );
    }
    out
}

/// The fits to a law from materials: on its CoR and duration, and on its loops.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct MaterialsFits {
    /// Each model fitted to the CoR and the duration.
    pub fits: Vec<Following>,
    /// Each model fitted to the reference's force-penetration loops, as JSON
    /// (`name`, `model`, `loop_cost`, `SI`, `e_error`, `t_d_error`, `F_max_error`).
    pub loop_fits: Vec<serde_json::Value>,
}

/// Writes the dataset, the loops, the config and `summary.json` (the report) into `dir`, each
/// file atomically, fits both models to the CoR and duration and to the loops (seed `seed`),
/// and says how closely each follows the reference; `summary.json` is then written again with
/// the fits (keys `fits`, `loop_fits`).
///
/// # Errors
/// [`AppError::Output`] where the folder cannot be written, and as [`fit_all`].
pub fn fit_to_reference(
    dir: &Path,
    spec: &MaterialsSpec,
    report: &MaterialsReport,
    seed: u64,
) -> Result<MaterialsFits, AppError> {
    let files = || {
        let mut files = vec![
            (
                REFERENCE_CSV.to_string(),
                reference_csv(spec, report).into_bytes(),
            ),
            (FIT_TOML.to_string(), fit_toml(report).into_bytes()),
        ];
        for (i, r) in loop_rows(report).into_iter().enumerate() {
            let name = format!("reference_loop_{}.csv", i + 1);
            files.push((name, reference_loop(report, r).into_bytes()));
        }
        files
    };
    let mut summary = report.json(spec);
    summary["provenance"] = crate::outdir::provenance("bwc-identify");
    crate::outdir::write_all(dir, summary.clone(), files())?;
    let path = dir.join(FIT_TOML);
    let config = Config::load(&path)?;
    let (fits, loops) = fit_all(&path, &config, Some(seed), &|| {}, None)?;
    let fits: Vec<Following> = fits.into_iter().map(|f| following(f, report)).collect();
    summary["fits"] = fits.iter().map(following_json).collect();
    let loop_fits: Vec<serde_json::Value> = loops
        .iter()
        .map(|l| loop_following_json(l, report))
        .collect();
    summary["loop_fits"] = loop_fits.clone().into();
    crate::outdir::write_all(dir, summary, files())?;
    Ok(MaterialsFits { fits, loop_fits })
}

fn following(fit: FitReport, report: &MaterialsReport) -> Following {
    let mass = report.pair.m_star;
    let si = si_params(&fit, mass);
    let (mut e_error, mut t_d_error, mut force_error) = (0.0f64, 0.0f64, 0.0f64);
    let mut stops = Vec::new();
    for (p, r) in fit.predictions.iter().zip(&report.rows) {
        let de = (p.e - r.e).abs();
        let dt = ((p.t_d - r.t_d) / r.t_d).abs();
        let peak = si
            .as_ref()
            .and_then(|(law, m)| si_impact(law, *m, r.v0, r.t_d));
        // A peak that cannot be had makes the largest error NaN, and stays so.
        let df = peak.map_or(f64::NAN, |(_, _, f)| {
            ((f - r.force_max) / r.force_max).abs()
        });
        e_error = e_error.max(de);
        t_d_error = t_d_error.max(dt);
        force_error = if df.is_nan() || force_error.is_nan() {
            f64::NAN
        } else {
            force_error.max(df)
        };
        if de > 0.01 || dt > 0.05 || df.is_nan() || df > 0.1 || !p.separated {
            stops.push(r.v0);
        }
    }
    Following {
        fit,
        e_error,
        t_d_error,
        force_error,
        stops_following: stops,
        mass,
    }
}

/// The SI law of a fit (its `U_b` from the pair's mass) and that mass.
fn si_params(fit: &FitReport, mass: f64) -> Option<(bw_models::PhysicalParams, f64)> {
    let kind = bw_models::ModelKind::parse(fit.model)?;
    let mut base = fit.params;
    // An unforced fit leaves `U_b` free; the pair's mass fixes it, `U_b = T_b / m`.
    base.u_b = base.t_b / mass;
    bw_models::BaseMap::new(kind, base)
        .and_then(|m| m.physical())
        .ok()
}

/// One impact of an SI law with mass `m` at `v0`: `(e, t_s, peak force)`, the force sampled
/// on a grid of 1/2000 of `t_d` (s), the reference's duration.
fn si_impact(
    params: &bw_models::PhysicalParams,
    m: f64,
    v0: f64,
    t_d: f64,
) -> Option<(f64, f64, f64)> {
    use bw_models::{simulate, Bwmcm, Bwshccm, CollisionModel, ModelKind, Sampling, Settings};
    let sampling = Sampling::Grid { dt: t_d / 2000.0 };
    let settings = Settings::default();
    let mut peak = 0.0f64;
    let impact = match params.kind() {
        ModelKind::Shccm => {
            let model = Bwshccm::new(params, m, v0, Zero).ok()?;
            simulate(&model, &settings, sampling, |_, y| {
                peak = peak.max(model.force(y))
            })
            .ok()?
            .cor()
        }
        ModelKind::Mcm => {
            let model = Bwmcm::new(params, m, v0, Zero).ok()?;
            simulate(&model, &settings, sampling, |_, y| {
                peak = peak.max(model.force(y))
            })
            .ok()?
            .cor()
        }
    };
    Some((impact.e, impact.t_s?, peak))
}

/// The speeds of the reference loops: three of the table's, at a quarter, a half and three
/// quarters of it; none where the contact does not yield.
fn loop_rows(report: &MaterialsReport) -> Vec<&super::MaterialsRow> {
    let n = report.rows.len();
    if report.pair.delta_y.is_none() || n < 3 {
        return Vec::new();
    }
    [n / 4, n / 2, 3 * n / 4]
        .iter()
        .map(|&i| &report.rows[i])
        .collect()
}

/// The reference law's force-penetration loop at `row`'s speed: Thornton's loading to the
/// deepest point, then its unloading to the residual penetration; `x,F` (m, N), chronological.
fn reference_loop(report: &MaterialsReport, row: &super::MaterialsRow) -> String {
    let p = &report.pair;
    let law = bw_models::AnyLaw::of_law(
        "thornton",
        &[("k", p.k), ("delta_y", p.delta_y.unwrap_or(f64::NAN))],
    );
    let mut out = format!(
        "# REFERENCE LAW, not measured: Thornton's force-penetration loop at v0 = {} m/s, from the \
         materials (bwc-identify materials).\nx,F\n",
        row.v0
    );
    let Ok(law) = law else { return out };
    let (dm, fm) = (row.delta_max, row.force_max);
    let df = dm - fm / (p.k * dm.sqrt());
    for i in 0..=40 {
        let d = dm * f64::from(i) / 40.0;
        out += &format!("{:?},{:?}\n", -d, law.eval(&[-d, -d], -1.0).1);
    }
    for i in 1..=40 {
        let d = dm - (dm - df) * f64::from(i) / 40.0;
        out += &format!("{:?},{:?}\n", -d, law.eval(&[-d, -dm], 1.0).1.max(0.0));
    }
    out
}

/// How closely a law fitted to the reference's loops follows its CoR, duration and peak force:
/// JSON with `name`, `model`, `SI` (the law and the pair's `m`), `loop_cost`, `e_error`,
/// `t_d_error`, `F_max_error`.
fn loop_following_json(lr: &LoopReport, report: &MaterialsReport) -> serde_json::Value {
    let m = report.pair.m_star;
    let l = &lr.law;
    let (mut de, mut dt, mut df) = (0.0f64, 0.0f64, 0.0f64);
    let kind = bw_models::ModelKind::parse(lr.model);
    let params = kind.and_then(|k| bw_models::PhysicalParams::new(k, *l).ok());
    for r in &report.rows {
        let Some((e, t, f)) = params.as_ref().and_then(|p| si_impact(p, m, r.v0, r.t_d)) else {
            // An impact that fails leaves the errors unknown: NaN (null in the JSON).
            (de, dt, df) = (f64::NAN, f64::NAN, f64::NAN);
            break;
        };
        de = de.max((e - r.e).abs());
        dt = dt.max(((t - r.t_d) / r.t_d).abs());
        df = df.max(((f - r.force_max) / r.force_max).abs());
    }
    serde_json::json!({
        "name": lr.name, "model": lr.model, "loop_cost": lr.cost,
        "SI": {"k": l.k, "c": l.c, "n": l.n, "p": l.p, "alpha": l.alpha, "beta": l.beta,
               "gamma": l.gamma, "A": l.a, "m": m},
        "e_error": de, "t_d_error": dt, "F_max_error": df,
    })
}

/// A fit's law and how closely it follows, as JSON: `name`, `model`, `params` (base), `SI`
/// (the law's `k, c, n, p, alpha, beta, gamma, A` with `A = 1`, and the pair's `m`), `J1`, `J2`,
/// `e_error`, `t_d_error`, `stops_following` (m/s).
pub fn following_json(f: &Following) -> serde_json::Value {
    let b = &f.fit.params;
    let si = si_law(f);
    serde_json::json!({
        "name": f.fit.name, "model": f.fit.model,
        "params": {"B_b": b.b_b, "Gamma_b": b.gamma_b, "kappa": b.kappa, "sigma_b": b.sigma_b,
                   "n": b.n, "p": b.p, "U_b": b.u_b, "T_b": b.t_b},
        "SI": si,
        "J1": f.fit.costs.j1, "J2": f.fit.costs.j2,
        "e_error": f.e_error, "t_d_error": f.t_d_error, "F_max_error": f.force_error,
        "stops_following": f.stops_following,
    })
}

/// The fit's SI law with its mass, or null where the base parameters give none.
fn si_law(f: &Following) -> serde_json::Value {
    let Some((law, m)) = si_params(&f.fit, f.mass) else {
        return serde_json::Value::Null;
    };
    let l = law.law();
    serde_json::json!({"k": l.k, "c": l.c, "n": l.n, "p": l.p, "alpha": l.alpha,
                       "beta": l.beta, "gamma": l.gamma, "A": l.a, "m": m})
}

/// A loop fit's law and how closely it follows, as text.
pub fn loop_following_text(v: &serde_json::Value) -> String {
    let pct = |k: &str| {
        v[k].as_f64()
            .map_or("-".to_string(), |x| format!("{:.2} %", 100.0 * x))
    };
    format!(
        "{}: loop cost {:.3e}; against the reference: largest |de| = {:.4}, largest t_d error = \
         {}, largest peak-force error = {}",
        v["name"].as_str().unwrap_or(""),
        v["loop_cost"].as_f64().unwrap_or(f64::NAN),
        v["e_error"].as_f64().unwrap_or(f64::NAN),
        pct("t_d_error"),
        pct("F_max_error"),
    )
}

/// A fit's law and how closely it follows, as text.
pub fn following_text(f: &Following) -> String {
    let b = &f.fit.params;
    let stops = if f.stops_following.is_empty() {
        "follows it at every speed (|de| <= 0.01, t_d within 5 %, peak force within 10 %)"
            .to_string()
    } else {
        let v: Vec<String> = f
            .stops_following
            .iter()
            .map(|v| format!("{v:.4}"))
            .collect();
        format!("stops following it at v0 = {} m/s", v.join(", "))
    };
    format!(
        "{}: B_b = {:.6}, Gamma_b = {:.6}, kappa = {:.6}, sigma_b = {:.6e}, n = {:.6}, p = {:.6}, \
         U_b = {:.6e}, T_b = {:.6e} s\n  against the reference: largest |de| = {:.4}, largest \
         t_d error = {:.2} %, largest peak-force error = {:.2} %; {stops}",
        f.fit.name,
        b.b_b,
        b.gamma_b,
        b.kappa,
        b.sigma_b,
        b.n,
        b.p,
        b.u_b,
        b.t_b,
        f.e_error,
        100.0 * f.t_d_error,
        100.0 * f.force_error,
    )
}

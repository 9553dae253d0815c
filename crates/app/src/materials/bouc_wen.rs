//! The Bouc-Wen laws fitted to a law from materials: the reference law's CoR and duration at
//! the table's speeds as a dataset, a config with one `[[fit]]` per model on it, and how
//! closely each fit follows the reference.

use super::{MaterialsReport, MaterialsSpec};
use crate::fit::config::Config;
use crate::fit::identify::{fit_all, FitReport};
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
    out
}

/// Writes the dataset, the config and `summary.json` (the report) into `dir`, each file
/// atomically, fits both models (seed `seed`), and says how closely each follows the
/// reference; `summary.json` is then written again with the fits (key `fits`).
///
/// # Errors
/// [`AppError::Output`] where the folder cannot be written, and as [`fit_all`].
pub fn fit_to_reference(
    dir: &Path,
    spec: &MaterialsSpec,
    report: &MaterialsReport,
    seed: u64,
) -> Result<Vec<Following>, AppError> {
    let files = || {
        vec![
            (
                REFERENCE_CSV.to_string(),
                reference_csv(spec, report).into_bytes(),
            ),
            (FIT_TOML.to_string(), fit_toml(report).into_bytes()),
        ]
    };
    let mut summary = report.json(spec);
    summary["provenance"] = crate::outdir::provenance("bwc-identify");
    crate::outdir::write_all(dir, summary.clone(), files())?;
    let path = dir.join(FIT_TOML);
    let config = Config::load(&path)?;
    let (fits, _) = fit_all(&path, &config, Some(seed), &|| {}, None)?;
    let fits: Vec<Following> = fits.into_iter().map(|f| following(f, report)).collect();
    summary["fits"] = fits.iter().map(following_json).collect();
    crate::outdir::write_all(dir, summary, files())?;
    Ok(fits)
}

fn following(fit: FitReport, report: &MaterialsReport) -> Following {
    let mass = report.pair.m_star;
    let (mut e_error, mut t_d_error, mut force_error) = (0.0f64, 0.0f64, 0.0f64);
    let mut stops = Vec::new();
    for (p, r) in fit.predictions.iter().zip(&report.rows) {
        let de = (p.e - r.e).abs();
        let dt = ((p.t_d - r.t_d) / r.t_d).abs();
        let df = peak_force(&fit, mass, r.v0, r.t_d)
            .map_or(f64::NAN, |f| ((f - r.force_max) / r.force_max).abs());
        e_error = e_error.max(de);
        t_d_error = t_d_error.max(dt);
        force_error = if df.is_nan() {
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

/// The peak force (N) of the fit's SI law in an impact at `v0`, sampled on a grid of 1/2000
/// of the duration `t_d` (s).
fn peak_force(fit: &FitReport, mass: f64, v0: f64, t_d: f64) -> Option<f64> {
    use bw_models::{simulate, Bwmcm, Bwshccm, CollisionModel, ModelKind, Sampling, Settings};
    let (params, m) = si_params(fit, mass)?;
    let sampling = Sampling::Grid { dt: t_d / 2000.0 };
    let settings = Settings::default();
    let mut peak = 0.0f64;
    let ok = match params.kind() {
        ModelKind::Shccm => {
            let model = Bwshccm::new(&params, m, v0, Zero).ok()?;
            simulate(&model, &settings, sampling, |_, y| {
                peak = peak.max(model.force(y))
            })
            .is_ok()
        }
        ModelKind::Mcm => {
            let model = Bwmcm::new(&params, m, v0, Zero).ok()?;
            simulate(&model, &settings, sampling, |_, y| {
                peak = peak.max(model.force(y))
            })
            .is_ok()
        }
    };
    ok.then_some(peak)
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

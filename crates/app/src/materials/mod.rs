//! Laws from materials and geometry: a `[materials]` table ([`MaterialsSpec`]) and the document
//! `bwc-identify materials` prints ([`MaterialsReport`]): the derived contact quantities, the
//! Hertz and Thornton laws in the terms every front end takes, and Thornton's CoR, duration,
//! deepest penetration and peak force over a range of impact speeds.
//!
//! ```
//! use bwc_app::materials::{MaterialsReport, MaterialsSpec};
//! let spec = MaterialsSpec::parse(std::path::Path::new("m.toml"), r#"
//!     [materials.body1]
//!     material = "alumina"
//!     radius = 2.5e-3
//!     [materials.body2]
//!     material = "aluminium-6082-t6"
//! "#)?;
//! let report = MaterialsReport::of(&spec)?;
//! assert_eq!(spec.pair.yields_first, Some(2));
//! assert!(report.rows.iter().all(|r| r.e <= 1.0));
//! # Ok::<(), bwc_app::AppError>(())
//! ```

mod bouc_wen;
mod file;

pub use bouc_wen::{
    fit_to_reference, fit_toml, following_json, following_text, loop_following_text, reference_csv,
    Following, MaterialsFits, FIT_TOML, REFERENCE_CSV,
};
pub use file::{BodySpec, MaterialsSpec};

use crate::AppError;
use bw_models::materials::MaterialPair;
use bw_models::{family_impact, Family, FamilyParams, Settings};
use serde_json::{json, Value};

/// The largest contact radius, relative to `R*`, at which the small-strain contact theory the
/// laws rest on is taken to hold.
const SMALL_STRAIN: f64 = 0.3;

/// One impact speed's outcome under Thornton's law (Hertz's where the contact does not yield).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct MaterialsRow {
    /// The impact speed (m/s).
    pub v0: f64,
    /// The CoR.
    pub e: f64,
    /// The contact duration, onset to separation (s).
    pub t_d: f64,
    /// The deepest penetration (m).
    pub delta_max: f64,
    /// The peak force (N).
    pub force_max: f64,
    /// The contact radius at the deepest penetration over `R*`.
    pub a_over_r: f64,
    /// The CoR under Jackson and Green's law (NaN where neither body yields).
    pub e_jg: f64,
    /// The duration under Jackson and Green's law (s).
    pub t_d_jg: f64,
}

/// What `bwc-identify materials` prints.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct MaterialsReport {
    /// The pair's derived quantities.
    pub pair: MaterialPair,
    /// The law by speed.
    pub rows: Vec<MaterialsRow>,
    /// Notes on the assumptions and on speeds outside the law's validity.
    pub notes: Vec<String>,
}

impl MaterialsReport {
    /// The laws and their CoR table for `spec`.
    ///
    /// # Errors
    /// [`AppError::Simulation`] where an impact fails.
    pub fn of(spec: &MaterialsSpec) -> Result<Self, AppError> {
        let pair = spec.pair.clone();
        let jg = jackson_green(spec);
        let mut rows = Vec::with_capacity(spec.speeds.len());
        for &v0 in &spec.speeds {
            let mut r = row(spec, &pair, v0)?;
            if let Some(law) = jg {
                (r.e_jg, r.t_d_jg) = jg_impact(spec, law, pair.m_star, v0)?;
            }
            rows.push(r);
        }
        let mut notes = vec![
            "Thornton (1997): elastic-perfectly-plastic, no strain hardening, no rate \
             dependence; yield at the peak Hertz pressure C(nu) S_y (Jackson & Green 2005)"
                .to_string(),
            "Jackson & Green (2005) with Jackson, Chusoipin & Green's unloading: a fit to \
             finite-element results for an elastic-perfectly-plastic sphere on a rigid flat \
             (e_jackson_green, t_d_jackson_green)"
                .to_string(),
        ];
        if pair.p_y.is_none() {
            notes.push("neither body yields: the law is Hertz's, elastic (e = 1)".to_string());
        }
        let beyond: Vec<String> = rows
            .iter()
            .filter(|r| r.a_over_r > SMALL_STRAIN)
            .map(|r| format!("{}", r.v0))
            .collect();
        if !beyond.is_empty() {
            notes.push(format!(
                "at v0 = {} m/s the contact radius exceeds {SMALL_STRAIN} R*: beyond the \
                 small-strain contact theory the law rests on (a/R* is in the table)",
                beyond.join(", ")
            ));
        }
        notes.extend(pair.hints.iter().cloned());
        Ok(Self { pair, rows, notes })
    }

    /// The report as JSON: `bodies`, `derived`, `laws`, `cor`, `units`, `notes`.
    pub fn json(&self, spec: &MaterialsSpec) -> Value {
        let p = &self.pair;
        let bodies: Vec<Value> = spec.bodies.iter().map(body_json).collect();
        let rows: Vec<Value> = self
            .rows
            .iter()
            .map(|r| {
                json!({"v0": r.v0, "e": r.e, "t_d": r.t_d, "delta_max": r.delta_max,
                       "F_max": r.force_max, "a_over_R": r.a_over_r,
                       "e_jackson_green": finite(r.e_jg), "t_d_jackson_green": finite(r.t_d_jg)})
            })
            .collect();
        json!({
            "bodies": bodies,
            "derived": {
                "E_star": p.e_star, "R_star": p.r_star, "m_star": finite(p.m_star), "k": p.k,
                "p": 1.5, "p_y": p.p_y, "yields_first": p.yields_first, "delta_y": p.delta_y,
                "F_y": p.force_y, "a_y": p.a_y, "v_y": p.v_y, "T_b": finite(p.t_b),
            },
            "laws": {
                "hertz": {"element": {"law": "hunt-crossley", "k": p.k, "alpha": 0.0}},
                "thornton": p.delta_y.map(|d| json!({
                    "element": {"law": "thornton", "k": p.k, "delta_y": d},
                    "family": {"model": "thornton", "v_y": p.v_y, "T_b": finite(p.t_b)},
                })),
                "jackson_green": jg_params(spec).map(|(e, r, s, nu)| json!({
                    "element": {"law": "jackson-green", "E_star": e, "R": r, "S_y": s, "nu": nu},
                })),
            },
            "cor": rows,
            "units": units(),
            "notes": self.notes,
        })
    }

    /// The report as text: the derived quantities with units, the laws, the table.
    pub fn text(&self, spec: &MaterialsSpec) -> String {
        let p = &self.pair;
        let mut out = format!("{}\n", spec.path.display());
        for (i, b) in spec.bodies.iter().enumerate() {
            let name = b.material.as_deref().unwrap_or("(own values)");
            let shape = if b.body.radius.is_finite() {
                format!("R = {:.6} m", b.body.radius)
            } else {
                "flat".to_string()
            };
            let mass = b
                .body
                .mass
                .map_or("immovable".to_string(), |m| format!("m = {m:.6e} kg"));
            out += &format!("  body {}: {name}, {shape}, {mass}\n", i + 1);
        }
        let opt =
            |x: Option<f64>, unit: &str| x.map_or("-".to_string(), |x| format!("{x:.6e} {unit}"));
        out += &format!(
            "  E* = {:.6e} Pa, R* = {:.6e} m, m* = {:.6e} kg\n  Hertz: k = {:.6e} N/m^(3/2), p = 3/2\n",
            p.e_star, p.r_star, p.m_star, p.k
        );
        out += &format!(
            "  yield: p_y = {}, first in body {}, delta_y = {}, F_y = {}, a_y = {}, v_y = {}\n",
            opt(p.p_y, "Pa"),
            p.yields_first.map_or("-".to_string(), |i| i.to_string()),
            opt(p.delta_y, "m"),
            opt(p.force_y, "N"),
            opt(p.a_y, "m"),
            opt(p.v_y, "m/s"),
        );
        out += "  v0 (m/s)      e          t_d (s)       delta_max (m)  F_max (N)     a/R*    \
                e (J-G)    t_d (J-G, s)\n";
        for r in &self.rows {
            out += &format!(
                "  {:<12.6e}  {:<9.6}  {:<12.6e}  {:<13.6e}  {:<12.6e}  {:<6.4}  {:<9.6}  \
                 {:.6e}\n",
                r.v0, r.e, r.t_d, r.delta_max, r.force_max, r.a_over_r, r.e_jg, r.t_d_jg
            );
        }
        for n in &self.notes {
            out += &format!("  note: {n}\n");
        }
        out
    }
}

/// `x`, or null where it is infinite (an immovable pair's mass).
fn finite(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

fn body_json(b: &BodySpec) -> Value {
    let m = &b.body.material;
    json!({
        "material": b.material, "source": b.source, "own": b.own,
        "youngs_modulus": m.youngs_modulus, "poisson": m.poisson, "density": m.density,
        "yield_strength": m.yield_strength, "yield_pressure": b.body.yield_onset(),
        "radius": finite(b.body.radius), "mass": b.body.mass,
    })
}

/// The unit of every number of the JSON report, by key.
pub fn units() -> Value {
    json!({
        "youngs_modulus": "Pa", "poisson": "-", "density": "kg/m^3", "yield_strength": "Pa",
        "yield_pressure": "Pa", "radius": "m (null: a flat)", "mass": "kg (null: immovable)",
        "E_star": "Pa", "R_star": "m", "m_star": "kg", "k": "N/m^(3/2)", "p": "-",
        "p_y": "Pa", "yields_first": "body 1 or 2", "delta_y": "m", "F_y": "N", "a_y": "m",
        "v_y": "m/s", "T_b": "s", "alpha": "s/m", "v0": "m/s", "e": "-", "t_d": "s",
        "delta_max": "m", "F_max": "N", "a_over_R": "-", "E_star": "Pa", "R": "m", "S_y": "Pa",
        "nu": "-", "e_jackson_green": "-", "t_d_jackson_green": "s",
        "e_error": "- (largest |e - e_ref|)", "t_d_error": "- (largest relative error)",
        "F_max_error": "- (largest relative error)", "loop_cost": "- (bwc_identify::loop_cost)",
        "J1": "-", "J2": "s^2", "stops_following": "m/s",
        "SI": "a fitted Bouc-Wen law: k kg m^(1-p) s^-2, c kg m^-p s^-1 (shccm) or kg/s (mcm), \
               n, p, alpha, A -, beta and gamma m^-n, m kg",
    })
}

/// Thornton's impact at `v0` (Hertz's below yield): `e` in closed form, the duration from the
/// family's impact, the deepest penetration and the peak force from the energy balance
/// `m* v0² / 2 = ∫ F dδ` over the loading.
fn row(spec: &MaterialsSpec, p: &MaterialPair, v0: f64) -> Result<MaterialsRow, AppError> {
    let settings = Settings::default();
    let energy = 0.5 * p.m_star * v0 * v0;
    let hertz_depth = |w: f64| (2.5 * w / p.k).powf(0.4);
    let (family, param) = match p.v_y {
        Some(v_y) => (Family::Thornton, v_y),
        None => (Family::HuntCrossley, 0.0),
    };
    let law = FamilyParams {
        family,
        param,
        t_b: p.t_b,
    };
    let cor = family_impact(&law, v0, &settings).map_err(|source| AppError::Simulation {
        path: spec.path.clone(),
        run: format!("v0 = {v0}"),
        source,
    })?;
    let (delta_max, force_max) = match (p.delta_y, p.force_y) {
        (Some(dy), Some(fy)) if energy > 0.4 * p.k * dy.powf(2.5) => {
            let slope = 1.5 * p.k * dy.sqrt();
            let rest = energy - 0.4 * p.k * dy.powf(2.5);
            let beyond = ((fy * fy + 2.0 * slope * rest).sqrt() - fy) / slope;
            (dy + beyond, fy + slope * beyond)
        }
        _ => {
            let d = hertz_depth(energy);
            (d, p.k * d.powf(1.5))
        }
    };
    Ok(MaterialsRow {
        v0,
        e: law.closed_form_cor(v0).unwrap_or(cor.e),
        t_d: cor.t_s.map_or(f64::NAN, |t| t * law.time_scale(v0)),
        delta_max,
        force_max,
        a_over_r: (p.r_star * delta_max).sqrt() / p.r_star,
        e_jg: f64::NAN,
        t_d_jg: f64::NAN,
    })
}

/// Jackson and Green's parameters for the pair: `E*`, `R*`, and the yield strength and
/// Poisson's ratio of the body that yields first (its `S_y` from a given yield pressure as
/// `p_y / C(ν)`); `None` where neither yields.
fn jg_params(spec: &MaterialsSpec) -> Option<(f64, f64, f64, f64)> {
    let p = &spec.pair;
    let body = &spec.bodies[usize::from(p.yields_first?) - 1].body;
    let nu = body.material.poisson;
    let s_y = body.yield_onset()? / bw_models::materials::yield_factor(nu);
    Some((p.e_star, p.r_star, s_y, nu))
}

fn jackson_green(spec: &MaterialsSpec) -> Option<bw_models::AnyLaw> {
    let (e, r, s, nu) = jg_params(spec)?;
    bw_models::AnyLaw::of_law(
        "jackson-green",
        &[("E_star", e), ("R", r), ("S_y", s), ("nu", nu)],
    )
    .ok()
}

/// Jackson and Green's impact at `v0`: a body of the pair's mass `m` meeting a wall, run as a
/// chain: `(e, t_d)`.
fn jg_impact(
    spec: &MaterialsSpec,
    law: bw_models::AnyLaw,
    m: f64,
    v0: f64,
) -> Result<(f64, f64), AppError> {
    use bw_models::chain::{Chain, ChainBody, ChainSettings, Stop, Walls};
    use bw_models::input::Constant;
    let fail = |source| AppError::Simulation {
        path: spec.path.clone(),
        run: format!("v0 = {v0} (Jackson-Green)"),
        source,
    };
    let body = ChainBody::new(m, 1.0, -v0, 1.0, Constant(0.0));
    let settings = ChainSettings::default().with_tolerances(1e-10, 1e-16);
    let chain =
        Chain::new(vec![body], vec![law], Walls::new(Some(0.5), None), settings).map_err(fail)?;
    // Far longer than any contact of the table (the Hertz duration at v0, times 100).
    let horizon = 100.0 * 3.22 * spec.pair.t_b * v0.powf(-0.2);
    let run = chain
        .run(Stop::settled(horizon), None, |_| {})
        .map_err(fail)?;
    let c = run.contacts.first();
    let e = c.and_then(|c| c.rebound()).unwrap_or(f64::NAN);
    let t_d = c
        .and_then(|c| c.separation.map(|s| s - c.onset))
        .unwrap_or(f64::NAN);
    Ok((e, t_d))
}

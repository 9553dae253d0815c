//! Laws from parameters (SI or base), and the one-shot impact.

use crate::registry::{dead, Kind, Registry};
use crate::status::{arg, guard, invalid, out, BwcStatus, Failure};
use bw_models::input::Constant;
use bw_models::{
    impact, BaseMap, BaseParams, Bwmcm, Bwshccm, ModelKind, Physical, PhysicalParams, Settings,
};
use std::sync::RwLock;

/// A law's handle: 0 is never one, and no contact handle has the same value (one given where
/// the other is expected is `BWC_STATUS_INVALID_HANDLE`, naming both kinds).
pub type BwcLaw = u64;

/// `model` of the Bouc-Wen-Simon-Hunt-Crossley law (states x, z).
pub const BWC_MODEL_SHCCM: u32 = 0;
/// `model` of the Bouc-Wen-Maxwell law (states r, y, z).
pub const BWC_MODEL_MCM: u32 = 1;

/// A law's SI parameters (the names of `[physical]` scenes).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcLawParams {
    /// `BWC_MODEL_SHCCM` or `BWC_MODEL_MCM`.
    pub model: u32,
    /// Stiffness `k` (kg m^(1-p) s^-2), > 0.
    pub k: f64,
    /// Damping `c`: kg m^-p s^-1 (SHCCM, >= 0) or kg s^-1 (MCM, > 0).
    pub c: f64,
    /// Bouc-Wen exponent `n` >= 1.
    pub n: f64,
    /// Force exponent `p` >= 1.
    pub p: f64,
    /// Share of the elastic element `alpha`, in (0, 1).
    pub alpha: f64,
    /// Bouc-Wen `beta` (m^-n), >= 0.
    pub beta: f64,
    /// Bouc-Wen `gamma` (m^-n), in [-beta, beta].
    pub gamma: f64,
    /// Bouc-Wen `A` > 0.
    pub a: f64,
}

/// A law's base parameters `P*` (the names of `[base]` scenes).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcBaseParams {
    /// `BWC_MODEL_SHCCM` or `BWC_MODEL_MCM`.
    pub model: u32,
    /// `B_b` >= 0.
    pub b_b: f64,
    /// `Gamma_b` in [-B_b, B_b].
    pub gamma_b: f64,
    /// `kappa` in (0, 1).
    pub kappa: f64,
    /// `sigma_b` >= 0 (SHCCM) or > 0 (MCM).
    pub sigma_b: f64,
    /// `n` >= 1.
    pub n: f64,
    /// `p` >= 1.
    pub p: f64,
    /// `U_b` > 0.
    pub u_b: f64,
    /// `T_b` > 0 (s).
    pub t_b: f64,
}

/// One impact of a law: what [`bwc_impact`] gives.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcImpact {
    /// The coefficient of restitution `e = v(t_s) / v0` (0 without separation).
    pub e: f64,
    /// The separation time `t_s` = the contact's duration (s); NaN without separation.
    pub t_s: f64,
    /// 1 if the bodies separated, else 0 (they came to rest in contact).
    pub separated: i32,
}

static LAWS: RwLock<Registry<PhysicalParams>> = RwLock::new(Registry::new(Kind::Law));

pub(crate) fn kind(model: u32) -> Result<ModelKind, Failure> {
    match model {
        BWC_MODEL_SHCCM => Ok(ModelKind::Shccm),
        BWC_MODEL_MCM => Ok(ModelKind::Mcm),
        _ => Err(invalid(
            "model",
            f64::from(model),
            "BWC_MODEL_SHCCM (0) or BWC_MODEL_MCM (1)",
        )),
    }
}

/// The parameters of a live law handle.
pub(crate) fn law(handle: BwcLaw) -> Result<PhysicalParams, Failure> {
    let laws = LAWS.read().unwrap_or_else(|e| e.into_inner());
    laws.get(handle)
        .copied()
        .ok_or_else(|| dead("law", handle, Kind::Law))
}

fn keep(params: PhysicalParams, out: &mut BwcLaw) -> Result<(), Failure> {
    let mut laws = LAWS.write().unwrap_or_else(|e| e.into_inner());
    *out = laws
        .insert(params)
        .ok_or_else(|| Failure::new(BwcStatus::Failed, "no handles left: free some laws"))?;
    Ok(())
}

/// Creates a law from SI parameters, validated against the admissible sets.
///
/// # Safety
/// `params` points to a `BwcLawParams` and `out` to a writable `BwcLaw` (NULL is an error).
#[no_mangle]
pub unsafe extern "C" fn bwc_law_new(params: *const BwcLawParams, out: *mut BwcLaw) -> BwcStatus {
    guard("bwc_law_new", || {
        // SAFETY: the caller's contract; NULL is checked.
        let (p, out) = unsafe { (arg(params, "params")?, self::out(out, "out")?) };
        let physical = Physical {
            k: p.k,
            c: p.c,
            n: p.n,
            p: p.p,
            alpha: p.alpha,
            beta: p.beta,
            gamma: p.gamma,
            a: p.a,
        };
        keep(PhysicalParams::new(kind(p.model)?, physical)?, out)
    })
}

/// Creates a law from base parameters alone (`A = 1`), and gives the mass `T_b / U_b` (kg)
/// they were taken with in `mass` (which may be NULL).
///
/// # Safety
/// `base` points to a `BwcBaseParams`, `out` to a writable `BwcLaw`, `mass` to a writable
/// double or is NULL.
#[no_mangle]
pub unsafe extern "C" fn bwc_law_from_base(
    base: *const BwcBaseParams,
    out: *mut BwcLaw,
    mass: *mut f64,
) -> BwcStatus {
    guard("bwc_law_from_base", || {
        // SAFETY: the caller's contract; NULL is checked (and allowed for `mass`).
        let (b, out, mass) = unsafe { (arg(base, "base")?, self::out(out, "out")?, mass.as_mut()) };
        let base = BaseParams {
            b_b: b.b_b,
            gamma_b: b.gamma_b,
            kappa: b.kappa,
            sigma_b: b.sigma_b,
            n: b.n,
            p: b.p,
            u_b: b.u_b,
            t_b: b.t_b,
        };
        let (params, m) = BaseMap::new(kind(b.model)?, base)?.physical()?;
        keep(params, out)?;
        if let Some(mass) = mass {
            *mass = m;
        }
        Ok(())
    })
}

/// Frees a law. Elements made from it keep their own copy. Freeing 0 does nothing.
#[no_mangle]
pub extern "C" fn bwc_law_free(law: BwcLaw) -> BwcStatus {
    guard("bwc_law_free", || {
        if law == 0 {
            return Ok(());
        }
        let mut laws = LAWS.write().unwrap_or_else(|e| e.into_inner());
        laws.remove(law)
            .map(drop)
            .ok_or_else(|| dead("law", law, Kind::Law))
    })
}

/// One impact of two bodies of reduced mass `m` (kg) meeting at `v0` (m/s) under a constant
/// external force `force` on their relative motion (N; `-m g` for a ball's weight on a floor,
/// 0 for none): `e`, `t_s` to the library's defaults (`e` checked to 1e-10).
///
/// # Safety
/// `out` points to a writable `BwcImpact` (NULL is an error).
#[no_mangle]
pub unsafe extern "C" fn bwc_impact(
    law: BwcLaw,
    m: f64,
    v0: f64,
    force: f64,
    out: *mut BwcImpact,
) -> BwcStatus {
    guard("bwc_impact", || {
        // SAFETY: the caller's contract; NULL is checked.
        let out = unsafe { self::out(out, "out")? };
        let params = self::law(law)?;
        if !(m > 0.0 && m.is_finite()) {
            return Err(invalid("m", m, "m > 0 (kg), finite"));
        }
        if !(v0 > 0.0 && v0.is_finite()) {
            return Err(invalid("v0", v0, "v0 > 0 (m/s), finite"));
        }
        if !force.is_finite() {
            return Err(invalid("force", force, "a finite force (N)"));
        }
        let settings = Settings::default();
        let input = Constant(force);
        let (e, t_s) = match params.kind() {
            ModelKind::Shccm => {
                let i = impact(&Bwshccm::new(&params, m, v0, input)?, &settings)?;
                (i.e, i.t_s)
            }
            ModelKind::Mcm => {
                let i = impact(&Bwmcm::new(&params, m, v0, input)?, &settings)?;
                (i.e, i.t_s)
            }
        };
        *out = BwcImpact {
            e,
            t_s: t_s.unwrap_or(f64::NAN),
            separated: i32::from(t_s.is_some()),
        };
        Ok(())
    })
}

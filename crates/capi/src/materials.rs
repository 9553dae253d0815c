//! Laws from materials and geometry: a material of the table by name, and two bodies' Hertz
//! law, onset of yield and Thornton law ([`bw_models::materials`]).

use crate::contact::text;
use crate::status::{arg, guard, out, BwcStatus, Failure};
use bw_models::materials::{material, material_names, Body, Material, MaterialPair};
use std::ffi::c_char;

/// One material (SI units).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcMaterial {
    /// Young's modulus (Pa), > 0.
    pub youngs_modulus: f64,
    /// Poisson's ratio, in (-1, 0.5).
    pub poisson: f64,
    /// Density (kg/m^3), > 0.
    pub density: f64,
    /// Yield strength (Pa), in (0, E); NaN for a material taken as elastic.
    pub yield_strength: f64,
}

/// One body at the contact.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcBody {
    /// Its material.
    pub material: BwcMaterial,
    /// The radius of curvature at the contact (m), > 0; INFINITY for a flat.
    pub radius: f64,
    /// The mass (kg), > 0; NaN for a sphere's `(4/3) pi R^3 rho` (a finite radius) or an
    /// immovable body (a flat).
    pub mass: f64,
    /// The peak contact pressure at which it yields (Pa); NaN for `C(nu) S_y`.
    pub yield_pressure: f64,
}

/// What two bodies give (SI units); NaN where a quantity does not exist (no yield, or an
/// immovable pair's yield speed).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcMaterialPair {
    /// Contact modulus `E*` (Pa).
    pub e_star: f64,
    /// Relative radius `R*` (m).
    pub r_star: f64,
    /// Effective mass `m*` (kg); INFINITY if neither body has a mass.
    pub m_star: f64,
    /// Hertz stiffness `k` (N/m^(3/2)): Thornton's and Hunt-Crossley's `k`.
    pub k: f64,
    /// The contact's yield pressure (Pa).
    pub p_y: f64,
    /// The body that yields first: 1 or 2; 0 if neither does.
    pub yields_first: u32,
    /// Penetration at the onset of yield (m): Thornton's `delta_y`.
    pub delta_y: f64,
    /// Force at the onset of yield (N).
    pub force_y: f64,
    /// Contact radius at the onset of yield (m).
    pub a_y: f64,
    /// Impact speed at which the contact just yields (m/s).
    pub v_y: f64,
    /// Time scale `(m*/k)^(2/5)` (s).
    pub t_b: f64,
}

/// The material of the table called `name` (NUL-terminated UTF-8: `"alumina"`,
/// `"aluminium-6061-t6"`, ...; the guide's reference of materials lists them with their
/// sources). An unknown name is `BWC_STATUS_INVALID_ARGUMENT`, the known ones in the last
/// error.
///
/// # Safety
/// `name` is NUL-terminated; `out` points to a writable `BwcMaterial`.
#[no_mangle]
pub unsafe extern "C" fn bwc_material(name: *const c_char, out: *mut BwcMaterial) -> BwcStatus {
    guard("bwc_material", || {
        // SAFETY: the caller's contract; NULL is checked.
        let (name, out) = unsafe { (text(name, "name")?, self::out(out, "out")?) };
        let entry = material(name).ok_or_else(|| {
            Failure::new(
                BwcStatus::InvalidArgument,
                format!("`{name}` is not a known material: {}", material_names()),
            )
        })?;
        let m = entry.material;
        *out = BwcMaterial {
            youngs_modulus: m.youngs_modulus,
            poisson: m.poisson,
            density: m.density,
            yield_strength: m.yield_strength.unwrap_or(f64::NAN),
        };
        Ok(())
    })
}

fn body(b: &BwcBody) -> Body {
    let some = |x: f64| (!x.is_nan()).then_some(x);
    let m = Material {
        youngs_modulus: b.material.youngs_modulus,
        poisson: b.material.poisson,
        density: b.material.density,
        yield_strength: some(b.material.yield_strength),
    };
    let mut body = match (some(b.mass), b.radius.is_finite()) {
        (Some(mass), _) => Body::new(m, b.radius, Some(mass)),
        (None, true) => Body::sphere(m, b.radius),
        (None, false) => Body::flat(m),
    };
    if let Some(p) = some(b.yield_pressure) {
        body = body.with_yield_pressure(p);
    }
    body
}

/// Two bodies' contact law: `E*`, `R*`, `m*`, the Hertz stiffness, the onset of yield and
/// Thornton's `delta_y` (pass `k` and `delta_y` to `bwc_contact_new_named("thornton", ...)`).
/// An inadmissible value is `BWC_STATUS_INVALID_ARGUMENT`, the body, the quantity and what is
/// admissible in the last error (a modulus that looks like GPa, a radius of two flats, ...).
///
/// # Safety
/// `first` and `second` point to `BwcBody` values; `out` to a writable `BwcMaterialPair`.
#[no_mangle]
pub unsafe extern "C" fn bwc_materials(
    first: *const BwcBody,
    second: *const BwcBody,
    out: *mut BwcMaterialPair,
) -> BwcStatus {
    guard("bwc_materials", || {
        // SAFETY: the caller's contract; NULL is checked.
        let (a, b, out) = unsafe {
            (
                arg(first, "first")?,
                arg(second, "second")?,
                self::out(out, "out")?,
            )
        };
        let p = MaterialPair::new(&body(a), &body(b))?;
        let nan = |x: Option<f64>| x.unwrap_or(f64::NAN);
        *out = BwcMaterialPair {
            e_star: p.e_star,
            r_star: p.r_star,
            m_star: p.m_star,
            k: p.k,
            p_y: nan(p.p_y),
            yields_first: p.yields_first.map_or(0, u32::from),
            delta_y: nan(p.delta_y),
            force_y: nan(p.force_y),
            a_y: nan(p.a_y),
            v_y: nan(p.v_y),
            t_b: p.t_b,
        };
        Ok(())
    })
}

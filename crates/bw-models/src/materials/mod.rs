//! Contact laws from the materials and the geometry of two bodies: the Hertz stiffness, the
//! onset of yield and Thornton's elastic-plastic law, derived from Young's moduli, Poisson's
//! ratios, densities or masses, radii of curvature and yield strengths.
//!
//! The facts used (Johnson, *Contact Mechanics*, 1985, ch. 4 and 6; Thornton 1997; Jackson &
//! Green 2005):
//!
//! * the contact modulus `1/E* = (1 - ν₁²)/E₁ + (1 - ν₂²)/E₂`, the relative radius
//!   `1/R* = 1/R₁ + 1/R₂` (a flat has `R = ∞`), the effective mass `m* = m₁ m₂ / (m₁ + m₂)`
//!   (a body without a mass is immovable: `m* = m` of the other);
//! * Hertz: `F = k δ^(3/2)` with `k = (4/3) E* √R*`, contact radius `a = √(R* δ)`, peak
//!   pressure `p₀ = 2 E* a / (π R*)`;
//! * yield begins under the surface of body `i` when `p₀ = C(νᵢ) S_yᵢ`, with Jackson and
//!   Green's `C(ν) = 1.295 exp(0.736 ν)` (1.61 at `ν = 0.3`, Johnson's 1.6); the body of the
//!   lower `C(ν) S_y` yields first, and its `p_y = C(ν) S_y` is the contact's yield pressure
//!   (a body given its own `yield_pressure` takes that instead);
//! * at yield, `δ_y = R* (π p_y / (2 E*))²`, `F_y = k δ_y^(3/2)`, `a_y = √(R* δ_y)`, and the
//!   impact speed at which a body of mass `m*` just yields stores its kinetic energy
//!   elastically: `(1/2) m* v_y² = (2/5) k δ_y^(5/2)`. For a sphere of density `ρ` on a flat
//!   this is Thornton's `v_y = 1.56 √(p_y⁵ / (E*⁴ ρ))`.
//!
//! ```
//! use bw_models::materials::{material, Body, MaterialPair};
//! let sphere = Body::sphere(material("alumina").unwrap().material, 2.5e-3);
//! let plate = Body::flat(material("aluminium-6061-t6").unwrap().material);
//! let pair = MaterialPair::new(&sphere, &plate)?;
//! assert_eq!(pair.yields_first, Some(2)); // the plate
//! assert!(pair.v_y.unwrap() > 0.01 && pair.v_y.unwrap() < 0.1); // m/s
//! # Ok::<(), bw_models::ModelError>(())
//! ```

mod table;

pub use table::{material, material_names, Entry, MATERIALS};

use crate::error::ModelError;

/// The elastic and plastic constants of one material (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus `E` (Pa).
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν`.
    pub poisson: f64,
    /// Density `ρ` (kg/m³).
    pub density: f64,
    /// Yield strength `S_y` (Pa); `None` for a material taken as elastic (a brittle ceramic
    /// or glass fractures before it yields).
    pub yield_strength: Option<f64>,
}

/// One body at the contact: its material, its radius of curvature there and its mass.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Body {
    /// The material.
    pub material: Material,
    /// The radius of curvature at the contact (m); `f64::INFINITY` for a flat.
    pub radius: f64,
    /// The mass (kg); `None` for an immovable body (a flat), or a sphere's `(4/3) π R³ ρ`
    /// where [`Body::sphere`] made it.
    pub mass: Option<f64>,
    /// The pressure at which it yields (Pa), where it is given rather than derived from the
    /// yield strength.
    pub yield_pressure: Option<f64>,
}

impl Body {
    /// A solid sphere of `radius` (m): its mass from the density.
    pub fn sphere(material: Material, radius: f64) -> Self {
        Self {
            material,
            radius,
            mass: Some(4.0 / 3.0 * std::f64::consts::PI * radius.powi(3) * material.density),
            yield_pressure: None,
        }
    }

    /// An immovable flat (a thick plate or anvil).
    pub fn flat(material: Material) -> Self {
        Self {
            material,
            radius: f64::INFINITY,
            mass: None,
            yield_pressure: None,
        }
    }

    /// A body of `radius` (m, `f64::INFINITY` for a flat) and `mass` (kg; `None` for an
    /// immovable one).
    pub fn new(material: Material, radius: f64, mass: Option<f64>) -> Self {
        Self {
            material,
            radius,
            mass,
            yield_pressure: None,
        }
    }

    /// The same body with its yield pressure given (Pa).
    pub fn with_yield_pressure(mut self, p_y: f64) -> Self {
        self.yield_pressure = Some(p_y);
        self
    }

    /// The pressure at which it yields (Pa): the given one, or `C(ν) S_y`; `None` if elastic.
    pub fn yield_onset(&self) -> Option<f64> {
        self.yield_pressure.or_else(|| {
            let m = &self.material;
            m.yield_strength.map(|s| yield_factor(m.poisson) * s)
        })
    }
}

/// Jackson and Green's (2005) ratio of the peak Hertz pressure to the yield strength at the
/// onset of yield: `C(ν) = 1.295 exp(0.736 ν)`.
pub fn yield_factor(poisson: f64) -> f64 {
    1.295 * (0.736 * poisson).exp()
}

/// What two bodies' materials and geometry give: the Hertz law, the onset of yield and
/// Thornton's law (SI units).
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct MaterialPair {
    /// The contact modulus `E*` (Pa).
    pub e_star: f64,
    /// The relative radius `R*` (m).
    pub r_star: f64,
    /// The effective mass `m*` (kg); infinite where neither body has a mass.
    pub m_star: f64,
    /// The Hertz stiffness `k = (4/3) E* √R*` (N/m^(3/2)); the exponent is 3/2.
    pub k: f64,
    /// The contact's yield pressure `p_y` (Pa): the lower of the bodies'; `None` if both are
    /// elastic.
    pub p_y: Option<f64>,
    /// Which body yields first (1 or 2); `None` if both are elastic.
    pub yields_first: Option<u8>,
    /// The penetration at the onset of yield `δ_y` (m).
    pub delta_y: Option<f64>,
    /// The force at the onset of yield `F_y` (N).
    pub force_y: Option<f64>,
    /// The contact radius at the onset of yield `a_y` (m).
    pub a_y: Option<f64>,
    /// The impact speed at which the contact just yields `v_y` (m/s); `None` where `m*` is
    /// infinite or both bodies are elastic.
    pub v_y: Option<f64>,
    /// The time scale `T_b = (m* / k)^(2/5)` (s) of the Hertz families.
    pub t_b: f64,
    /// Values that look like a unit slip, each naming the likely unit and the fix.
    pub hints: Vec<String>,
}

impl MaterialPair {
    /// Derives the pair's law.
    ///
    /// # Errors
    /// [`ModelError::InvalidMaterial`] naming the body and the quantity for a Poisson's ratio
    /// outside `(-1, 0.5)`, a non-positive or non-finite modulus, density, radius, mass or
    /// yield strength, a yield strength above the modulus, values that can only be in the
    /// wrong unit (a modulus below 1e5 Pa, a density below 10 kg/m³), and two flats.
    pub fn new(first: &Body, second: &Body) -> Result<Self, ModelError> {
        let mut hints = Vec::new();
        for (i, b) in [(1, first), (2, second)] {
            check_body(i, b, &mut hints)?;
        }
        if first.radius.is_infinite() && second.radius.is_infinite() {
            return Err(invalid(
                0,
                "radius",
                f64::INFINITY,
                "at least one curved body: two flats have no Hertz contact",
            ));
        }
        let compliance = |m: &Material| (1.0 - m.poisson * m.poisson) / m.youngs_modulus;
        let e_star = 1.0 / (compliance(&first.material) + compliance(&second.material));
        let r_star = 1.0 / (1.0 / first.radius + 1.0 / second.radius);
        let m_star = match (first.mass, second.mass) {
            (Some(a), Some(b)) => a * b / (a + b),
            (Some(a), None) | (None, Some(a)) => a,
            (None, None) => f64::INFINITY,
        };
        let k = 4.0 / 3.0 * e_star * r_star.sqrt();
        let onsets = [first.yield_onset(), second.yield_onset()];
        let yielding = onsets
            .iter()
            .enumerate()
            .filter_map(|(i, p)| p.map(|p| (i as u8 + 1, p)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        let p_y = yielding.map(|(_, p)| p);
        let delta_y = p_y.map(|p| r_star * (std::f64::consts::PI * p / (2.0 * e_star)).powi(2));
        let v_y = delta_y
            .filter(|_| m_star.is_finite())
            .map(|d| (0.8 * k * d.powf(2.5) / m_star).sqrt());
        Ok(Self {
            e_star,
            r_star,
            m_star,
            k,
            p_y,
            yields_first: yielding.map(|(i, _)| i),
            delta_y,
            force_y: delta_y.map(|d| k * d.powf(1.5)),
            a_y: delta_y.map(|d| (r_star * d).sqrt()),
            v_y,
            t_b: (m_star / k).powf(0.4),
            hints,
        })
    }
}

fn invalid(body: u8, name: &'static str, value: f64, allowed: &'static str) -> ModelError {
    ModelError::InvalidMaterial {
        body,
        name,
        value,
        allowed,
    }
}

/// Checks one body's values; adds a hint for a radius that looks like millimetres.
fn check_body(i: u8, b: &Body, hints: &mut Vec<String>) -> Result<(), ModelError> {
    let m = &b.material;
    let e = m.youngs_modulus;
    if !(e > 0.0 && e.is_finite()) {
        return Err(invalid(i, "youngs_modulus", e, "E > 0 (Pa)"));
    }
    if e < 1e5 {
        let unit = if e < 1e4 { "GPa" } else { "MPa" };
        let allowed = if unit == "GPa" {
            "E in Pa: this looks like GPa (210 GPa is 210e9 Pa)"
        } else {
            "E in Pa: this looks like MPa (70 000 MPa is 70e9 Pa)"
        };
        return Err(invalid(i, "youngs_modulus", e, allowed));
    }
    if !(m.poisson > -1.0 && m.poisson < 0.5) {
        return Err(invalid(i, "poisson", m.poisson, "-1 < nu < 0.5"));
    }
    if !(m.density > 0.0 && m.density.is_finite()) {
        return Err(invalid(i, "density", m.density, "rho > 0 (kg/m^3)"));
    }
    if m.density < 10.0 {
        return Err(invalid(
            i,
            "density",
            m.density,
            "rho in kg/m^3: this looks like g/cm^3 (7.8 g/cm^3 is 7800 kg/m^3)",
        ));
    }
    if let Some(s) = m.yield_strength {
        check_yield(i, "yield_strength", s, e)?;
    }
    if let Some(p) = b.yield_pressure {
        check_yield(i, "yield_pressure", p, e)?;
    }
    if b.radius.is_nan() || b.radius <= 0.0 {
        return Err(invalid(
            i,
            "radius",
            b.radius,
            "R > 0 (m), or inf for a flat",
        ));
    }
    if b.radius.is_finite() && b.radius > 1.0 {
        hints.push(format!(
            "body {i}: radius = {} m is large for a contact's curvature: if it is in mm, it is \
             {} m (a flat is inf)",
            b.radius,
            b.radius * 1e-3
        ));
    }
    if let Some(mass) = b.mass {
        if !(mass > 0.0 && mass.is_finite()) {
            return Err(invalid(
                i,
                "mass",
                mass,
                "m > 0 (kg), or none for an immovable body",
            ));
        }
    }
    Ok(())
}

fn check_yield(i: u8, name: &'static str, s: f64, e: f64) -> Result<(), ModelError> {
    if !(s > 0.0 && s.is_finite()) {
        return Err(invalid(i, name, s, "a stress > 0 (Pa)"));
    }
    if s < 1e4 {
        return Err(invalid(
            i,
            name,
            s,
            "a stress in Pa: this looks like MPa (276 MPa is 276e6 Pa)",
        ));
    }
    if s >= e {
        return Err(invalid(
            i,
            name,
            s,
            "a stress below Young's modulus (a yield strength is a fraction of a percent of E)",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steel() -> Material {
        material("steel-aisi-1045").unwrap().material
    }

    /// Thornton's sphere-on-flat yield speed `1.56 √(p_y⁵ / (E*⁴ ρ))` is the energy balance's
    /// `√(4 k δ_y^(5/2) / (5 m*))` for a sphere.
    #[test]
    fn the_yield_speed_is_thorntons_for_a_sphere_on_a_flat() {
        let sphere = Body::sphere(steel(), 5e-3);
        let plate = Body::flat(material("aluminium-6061-t6").unwrap().material);
        let pair = MaterialPair::new(&sphere, &plate).unwrap();
        let p_y = pair.p_y.unwrap();
        let thornton = 1.56 * (p_y.powi(5) / (pair.e_star.powi(4) * steel().density)).sqrt();
        let v_y = pair.v_y.unwrap();
        // 1.56 is (π⁴/40)^(1/2) = 1.5605 to Thornton's three digits.
        assert!((v_y / thornton - 1.0).abs() < 5e-4, "{v_y} vs {thornton}");
        assert_eq!(pair.yields_first, Some(2));
        // The peak Hertz pressure at δ_y is p_y.
        let a = pair.a_y.unwrap();
        let p0 = 2.0 * pair.e_star * a / (std::f64::consts::PI * pair.r_star);
        assert!((p0 / p_y - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_contact_modulus_radius_and_mass_combine_both_bodies() {
        let (a, b) = (Body::sphere(steel(), 2e-3), Body::sphere(steel(), 6e-3));
        let pair = MaterialPair::new(&a, &b).unwrap();
        let e = steel().youngs_modulus / (2.0 * (1.0 - 0.29 * 0.29));
        assert!((pair.e_star / e - 1.0).abs() < 1e-14);
        assert!((pair.r_star - 1.5e-3).abs() < 1e-15);
        let (ma, mb) = (a.mass.unwrap(), b.mass.unwrap());
        assert!((pair.m_star - ma * mb / (ma + mb)).abs() < 1e-18);
        assert!((yield_factor(0.3) - 1.615).abs() < 1e-3);
    }

    #[test]
    fn bad_bodies_name_the_body_and_the_quantity() {
        let err = |a: Body, b: Body| MaterialPair::new(&a, &b).unwrap_err().to_string();
        let mut m = steel();
        m.poisson = 0.5;
        let e = err(Body::sphere(m, 1e-3), Body::flat(steel()));
        assert!(
            e.contains("body 1") && e.contains("poisson") && e.contains("-1 < nu < 0.5"),
            "{e}"
        );
        let mut m = steel();
        m.youngs_modulus = 210.0;
        let e = err(Body::flat(steel()), Body::sphere(m, 1e-3));
        assert!(e.contains("body 2") && e.contains("looks like GPa"), "{e}");
        let mut m = steel();
        m.yield_strength = Some(276.0);
        assert!(err(Body::sphere(m, 1e-3), Body::flat(steel())).contains("looks like MPa"));
        let mut m = steel();
        m.yield_strength = Some(3e11);
        assert!(err(Body::sphere(m, 1e-3), Body::flat(steel())).contains("below Young's modulus"));
        let e = err(Body::flat(steel()), Body::flat(steel()));
        assert!(e.contains("two flats"), "{e}");
        let pair = MaterialPair::new(&Body::new(steel(), 5.0, Some(1.0)), &Body::flat(steel()));
        assert!(pair.unwrap().hints[0].contains("0.005 m"));
    }

    #[test]
    fn elastic_bodies_have_no_yield() {
        let glass = material("glass-soda-lime").unwrap().material;
        let pair = MaterialPair::new(&Body::sphere(glass, 1e-3), &Body::flat(glass)).unwrap();
        assert_eq!((pair.p_y, pair.yields_first, pair.v_y), (None, None, None));
        assert!(material("unobtainium").is_none());
        assert!(material_names().contains("alumina"));
    }
}

//! Thornton's (1997) elastic-perfectly-plastic sphere: Hertz loading `F = k δ^(3/2)` up to
//! the penetration `δ_y` at which the contact pressure reaches the yield pressure, then the
//! line `F = F_y + π R p_y (δ - δ_y)`; unloading from `(δ_m, F_m)` is Hertzian for the
//! flattened radius `R_p = 4 E* a_m³ / (3 F_m)`, `F = (4/3) E* √R_p (δ - δ_f)^(3/2)`, down to
//! the residual indentation `δ_f`.
//!
//! The facts used, with `k = (4/3) E* √R` and Hertz's `a = √(R δ)`, `p_0 = 2 E* a / (π R)`:
//! the plastic line's slope `π R p_y = 2 E* a_y = (3/2) k √δ_y` is the Hertz tangent at `δ_y`;
//! the unloading stiffness is `k_p = k √(k δ_m^(3/2) / F_m)`; continuity at `F_m` gives
//! `δ_m - δ_f = F_m / (k √δ_m)`; and the yield speed `v_y`, at which all the kinetic energy is
//! stored elastically at `δ_y`, gives `(5/4) m v_y² = k δ_y^(5/2)`. So the law needs only `k`,
//! the mass and `v_y`: nondimensionally (`δ* = (m v0² / k)^(2/5)`) its one parameter is
//! `δ_y / δ* = ((5/4) (v_y / v0)²)^(2/5)`. Below `v_y` the impact is Hertz's and `e = 1`.

use super::deepest::{self, DeepestPoint};
use super::{FamilySpec, ParamSpec};
use crate::cor::impact;
use crate::error::ModelError;
use crate::law_spec::{positive, LawParam, LawSpec, NamedLaw};
use crate::laws::ContactLaw;
use crate::models::{nondimensional_scales, unforced, CollisionModel};
use bwc_ode::{State, System};

pub(super) const SPEC: FamilySpec = FamilySpec {
    name: "thornton",
    title: "Thornton",
    force: "k δ^(3/2) to δ_y, then its tangent; k_p (δ - δ_f)^(3/2) unloading",
    exponent: 1.5,
    param: ParamSpec {
        name: "v_y",
        unit: "m/s",
        allowed: "v_y > 0 (m/s)",
        admits: |v| v > 0.0 && v.is_finite(),
        default_bounds: (1e-3, 10.0),
        default_log: true,
        neutral: 1.0,
    },
    impact: |v_y, v0, settings| impact(&Ndthornton::at(v_y, v0), settings).map(|i| i.cor()),
    closed_form: Some(closed_form),
};

/// Thornton's CoR (1997) at `r = v_y / v0 <= 1`:
/// `e = (6√3/5)^(1/2) (1 - r²/6)^(1/2) (r / (r + 2 √(6/5 - r²/5)))^(1/4)`, and 1 below yield.
fn closed_form(v_y: f64, v0: f64) -> f64 {
    let r = v_y / v0;
    if r >= 1.0 {
        return 1.0;
    }
    let first = (6.0 * 3f64.sqrt() / 5.0).sqrt() * (1.0 - r * r / 6.0).sqrt();
    first * (r / (r + 2.0 * (1.2 - 0.2 * r * r).sqrt())).powf(0.25)
}

/// The loading force of unit stiffness at penetration `d` with yield at `y`: `d^(3/2)` to
/// `y`, its tangent beyond.
fn loading(y: f64, d: f64) -> f64 {
    if d <= 0.0 {
        0.0
    } else if d <= y {
        d * d.sqrt()
    } else {
        y * y.sqrt() + 1.5 * y.sqrt() * (d - y)
    }
}

/// The residual penetration `δ_f` and the stiffness `k_p` (per unit stiffness) of the
/// unloading from the deepest penetration `dm` with yield at `y`.
fn unloading(y: f64, dm: f64) -> (f64, f64) {
    if dm <= 0.0 {
        return (0.0, 1.0);
    }
    let fm = loading(y, dm);
    (dm - fm / dm.sqrt(), dm.powf(0.75) / fm.sqrt())
}

/// The nondimensional Thornton impact, states `(X, V, M)`: `X' = V`, `V' = F`, and `M` the
/// deepest `X` so far (`M' = min(V, 0)`); `X < 0` in compression, `V(0) = -1`. The force is
/// the loading curve while `V < 0` and the unloading curve from `δ_m = -M` after.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ndthornton {
    /// The yield penetration `δ_y / δ*`.
    pub x_y: f64,
}

impl Ndthornton {
    /// The impact at `v0` of a law of yield speed `v_y` (both m/s).
    pub fn at(v_y: f64, v0: f64) -> Self {
        let r = v_y / v0;
        Self {
            x_y: (1.25 * r * r).powf(0.4),
        }
    }

    /// The loading force at penetration `d`: Hertz to `x_y`, its tangent beyond.
    pub fn loading(&self, d: f64) -> f64 {
        loading(self.x_y, d)
    }

    /// The residual penetration `δ_f` and the stiffness `k_p` of the unloading from the
    /// deepest penetration `dm`: `δ_f = δ_m - F_m / √δ_m`, `k_p = δ_m^(3/4) / √F_m`.
    pub fn unloading(&self, dm: f64) -> (f64, f64) {
        unloading(self.x_y, dm)
    }

    /// Whether the contact is loading, the penetration, and the deepest penetration.
    fn phase(y: &State<3>) -> (bool, f64, f64) {
        let d = -y[0];
        (y[1] < 0.0, d, (-y[2]).max(d))
    }
}

impl System<3> for Ndthornton {
    fn rhs(&self, _t: f64, y: &State<3>) -> State<3> {
        State::<3>::new(y[1], self.force(y), y[1].min(0.0))
    }
}

impl CollisionModel<3> for Ndthornton {
    fn initial_state(&self) -> State<3> {
        State::<3>::new(0.0, -1.0, 0.0)
    }
    fn force(&self, y: &State<3>) -> f64 {
        let (loading, d, dm) = Self::phase(y);
        if loading {
            return self.loading(d);
        }
        let (df, kp) = self.unloading(dm);
        let s = (d - df).max(0.0);
        kp * s * s.sqrt()
    }
    fn displacement(&self, y: &State<3>) -> f64 {
        y[0]
    }
    fn velocity(&self, y: &State<3>) -> f64 {
        y[1]
    }
    unforced!();
    nondimensional_scales!(3);
    /// The turn from loading to unloading (`V = 0`) and the yield onset while loading
    /// (`δ = δ_y`), the end of the unloading curve after (`δ = δ_f`).
    fn kinks(&self, _t: f64, y: &State<3>) -> [f64; 2] {
        let (loading, d, dm) = Self::phase(y);
        let edge = if loading {
            d - self.x_y
        } else {
            d - self.unloading(dm).0
        };
        [y[1], edge]
    }
}

/// Thornton's law as a contact element, states `(x, x_m)` (m): `ẋ = u`, and `x_m` the deepest
/// `x` so far (`ẋ_m = u` while the contact loads at its deepest, 0 otherwise). With `δ = -x`,
/// `δ_m = -x_m`: `F = k δ^(3/2)` to the yield penetration `δ_y`, `F = F_y + (3/2) k √δ_y
/// (δ - δ_y)` beyond it while loading, and `F = k_p (δ - δ_f)^(3/2)` off the deepest point
/// (unloading, and elastic reloading up to `δ_m`), with `δ_f`, `k_p` as in the module's
/// notes. For a sphere of radius `R`: `k = (4/3) E* √R`, `δ_y = R (π p_y / (2 E*))²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThorntonLaw {
    /// The Hertz stiffness `k` (N/m^(3/2)).
    pub k: f64,
    /// The yield penetration `δ_y` (m).
    pub delta_y: f64,
}

impl DeepestPoint for ThorntonLaw {
    fn loading(&self, d: f64) -> f64 {
        self.k * loading(self.delta_y, d)
    }
    fn unloading(&self, d: f64, dm: f64) -> f64 {
        let (df, kp) = unloading(self.delta_y, dm);
        let r = (d - df).max(0.0);
        self.k * kp * r * r.sqrt()
    }
    fn residual(&self, dm: f64) -> f64 {
        unloading(self.delta_y, dm).0
    }
    /// `(2/5) k_p (δ - δ_f)^(5/2)` (J).
    fn elastic(&self, d: f64, dm: f64) -> f64 {
        let (df, kp) = unloading(self.delta_y, dm);
        0.4 * self.k * kp * (d - df).max(0.0).powf(2.5)
    }
    fn loading_kink(&self) -> f64 {
        self.delta_y
    }
    fn plastic_from(&self) -> f64 {
        self.delta_y
    }
    /// In closed form, from `E(δ_m) = (2/5) F_m² / (k √δ_m)` on the plastic line.
    fn growth(&self, d: f64, force: f64) -> f64 {
        let slope = 1.5 * self.k * self.delta_y.sqrt();
        0.4 / self.k * (2.0 * force * slope / d.sqrt() - 0.5 * force * force / (d * d.sqrt()))
    }
}

impl ContactLaw<2> for ThorntonLaw {
    fn eval(&self, s: &State<2>, u: f64) -> (State<2>, f64) {
        deepest::eval(self, s, u)
    }
    /// `(2/5) k_p (δ - δ_f)^(5/2)` for the unloading from the deepest point (J).
    fn stored(&self, s: &State<2>) -> f64 {
        deepest::stored(self, s)
    }
    /// 0 off the plastic line; on it, `F δ̇` less the rate at which the deepest point's
    /// elastic energy `E(δ_m) = (2/5) F_m² / (k √δ_m)` grows (W).
    fn dissipation(&self, s: &State<2>, u: f64, _rate: &State<2>, force: f64) -> f64 {
        deepest::dissipation(self, s, u, force)
    }
    /// The turn at the deepest point (`u`, then `δ_m - δ` off it) and the yield while loading
    /// (`δ - δ_y`), the end of the unloading curve off it (`δ - δ_f`).
    fn kinks(&self, s: &State<2>, u: f64) -> [f64; 2] {
        deepest::kinks(self, s, u)
    }
}

impl NamedLaw<2> for ThorntonLaw {
    const SPEC: LawSpec = LawSpec {
        name: "thornton",
        title: "Thornton",
        force: "k δ^(3/2) to δ_y, then its tangent; k_p (δ - δ_f)^(3/2) off the deepest point",
        params: &[
            LawParam::new("k", "N m^-3/2", "k > 0 (N/m^(3/2))", positive, 1e10),
            LawParam::new("delta_y", "m", "delta_y > 0 (m)", positive, 1e-6),
        ],
        states: &["x", "x_m"],
    };
    fn of_values(values: &[f64]) -> Result<Self, ModelError> {
        match *values {
            [k, delta_y] => Ok(Self { k, delta_y }),
            _ => Err(ModelError::NotApplicable {
                reason: "the Thornton law takes 2 values: k, delta_y",
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{family_impact, Family, FamilyParams};
    use super::*;
    use crate::settings::Settings;

    fn law(v_y: f64) -> FamilyParams {
        FamilyParams {
            family: Family::Thornton,
            param: v_y,
            t_b: 1.0,
        }
    }

    #[test]
    fn the_cor_is_thorntons_closed_form_and_one_below_yield() {
        let s = Settings::default();
        for (v_y, v0) in [(2.0, 1.0), (1.0, 1.0), (0.5, 1.0), (0.1, 2.0), (0.01, 3.0)] {
            let e = family_impact(&law(v_y), v0, &s).unwrap().e;
            let want = law(v_y).closed_form_cor(v0).unwrap();
            assert!((e - want).abs() < 1e-7, "v_y {v_y} v0 {v0}: {e} vs {want}");
        }
        assert_eq!(law(2.0).closed_form_cor(1.0), Some(1.0));
    }

    /// Thornton's high-speed limit `e ≈ 1.185 (v_y / v0)^(1/4)` (1997), and the
    /// continuity of his formula at yield.
    #[test]
    fn the_closed_form_has_thorntons_published_limits() {
        let r: f64 = 1e-4;
        let e = closed_form(r, 1.0);
        assert!(
            (e / r.powf(0.25) - 1.185).abs() < 1e-3,
            "{}",
            e / r.powf(0.25)
        );
        assert!((closed_form(1.0 - 1e-12, 1.0) - 1.0).abs() < 1e-9);
    }

    /// The loading line is the Hertz tangent at yield, and the unloading curve starts at the
    /// peak force and ends at `δ_f` with zero force.
    #[test]
    fn loading_and_unloading_meet_where_they_should() {
        let m = Ndthornton::at(0.2, 1.0);
        let y = m.x_y;
        let h = 1e-7 * y;
        assert!((m.loading(y + h) - m.loading(y - h)) / (2.0 * h) - 1.5 * y.sqrt() < 1e-6);
        let dm = 3.0 * y;
        let (df, kp) = m.unloading(dm);
        assert!((kp * (dm - df).powf(1.5) - m.loading(dm)).abs() < 1e-12);
        assert!(df > 0.0 && df < dm);
        let (df0, kp0) = m.unloading(0.5 * y);
        assert!(df0.abs() < 1e-15 && (kp0 - 1.0).abs() < 1e-12);
    }
}

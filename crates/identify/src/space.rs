//! The search space: which base parameters are free, their bounds and scales, and the
//! constraints of Section 7.1. The optimizers work on the unit cube `[0, 1]^d`; a point of it is
//! decoded into base parameters `P*`. `Γ_b` is searched as `g = Γ_b / B_b ∈ [-1, 1]`, so that
//! `-B_b <= Γ_b <= B_b` holds by construction.

use crate::error::IdentifyError;
use bw_models::input::Input;
use bw_models::{
    family_impact, impact_at, BaseMap, BaseParams, Cor, Family, FamilyParams, ModelError,
    ModelKind, Settings,
};

/// Names of the searchable quantities, in order.
pub const NAMES: [&str; 8] = ["B_b", "g", "kappa", "sigma_b", "n", "p", "U_b", "T_b"];

/// One searchable quantity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Param {
    /// Held at a value.
    Fixed(f64),
    /// Computed from the others: `T_b = m U_b` under [`KnownMassStiffness`].
    Derived,
    /// Searched in `[lo, hi]`, on a logarithmic scale when `log` (then `lo > 0`).
    Free {
        /// Lower bound.
        lo: f64,
        /// Upper bound.
        hi: f64,
        /// Logarithmic scale.
        log: bool,
    },
}

/// The Villegas constraints (eq:VRBR:c1, eq:VRBR:c2) for a known mass `m` (kg) and stiffness
/// `k` (N/m^p): `T_b = m U_b` (T_b is eliminated) and `(m/k) κ / T_b^(p+1) <= 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KnownMassStiffness {
    /// Mass `m` (kg).
    pub m: f64,
    /// Stiffness `k`.
    pub k: f64,
}

/// A validated search space.
#[derive(Debug, Clone, PartialEq)]
pub struct Space {
    kind: ModelKind,
    params: [Param; 8],
    known: Option<KnownMassStiffness>,
    free: Vec<usize>,
    /// A contact-law family in place of the Bouc-Wen models: its parameter is searched in the
    /// slot of `sigma_b`, its `T_b` in that of `T_b`; the other slots are fixed. Only
    /// [`Space::name`] and [`Space::map`] read the slot.
    family: Option<Family>,
}

/// The model a point of a [`Space`] describes: a Bouc-Wen model through its base map, or a
/// contact-law family.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FitModel {
    /// The NDBWSHCCM or NDBWMCM at base parameters.
    BoucWen(BaseMap),
    /// A contact-law family.
    Family(FamilyParams),
}

impl FitModel {
    /// One impact at `v0` (m/s) with physical input `u` (N): `e`, and `t_s` in the
    /// nondimensional time.
    ///
    /// # Errors
    /// As [`bw_models::impact_at`] and [`bw_models::family_impact`];
    /// [`ModelError::InvalidParameter`] for a family under an input (the families are fitted
    /// to unforced impacts).
    pub fn impact<I: Input>(&self, u: I, v0: f64, settings: &Settings) -> Result<Cor, ModelError> {
        match self {
            FitModel::BoucWen(map) => impact_at(map, u, v0, settings),
            FitModel::Family(p) if u.is_zero() => family_impact(p, v0, settings),
            FitModel::Family(_) => Err(ModelError::InvalidParameter {
                name: "input",
                value: f64::NAN,
                allowed: "no input: the contact-law families are fitted to unforced impacts",
            }),
        }
    }

    /// The time scale at `v0` (s): a nondimensional duration times this is in seconds.
    pub fn time_scale(&self, v0: f64) -> f64 {
        match self {
            FitModel::BoucWen(map) => map.time_scale(v0),
            FitModel::Family(p) => p.time_scale(v0),
        }
    }
}

/// The value at `t` (clamped into `[0, 1]`) of `[lo, hi]` on a linear or log scale, exactly `lo`
/// and `hi` at the ends.
fn scale(lo: f64, hi: f64, log: bool, t: f64) -> f64 {
    let t = t.clamp(0.0, 1.0);
    if t == 0.0 {
        lo
    } else if t == 1.0 {
        hi
    } else if log {
        lo * (hi / lo).powf(t)
    } else {
        lo + (hi - lo) * t
    }
}

/// The values of `params` at a point `s` of the unit cube whose coordinates are those of the
/// free parameters `free` (indices into `params`): fixed values as they are, free ones scaled
/// from their coordinate.
pub(crate) fn values_at(params: &[Param; 8], free: &[usize], s: &[f64]) -> [f64; 8] {
    let mut v = [0.0; 8];
    for (i, p) in params.iter().enumerate() {
        if let Param::Fixed(x) = p {
            v[i] = *x;
        }
    }
    for (j, &i) in free.iter().enumerate() {
        if let Param::Free { lo, hi, log } = params[i] {
            v[i] = scale(lo, hi, log, s[j]);
        }
    }
    v
}

/// The base parameters of the searchable quantities `v` of [`NAMES`] (`g = Gamma_b / B_b`).
fn base_params(v: &[f64; 8]) -> BaseParams {
    BaseParams {
        b_b: v[0],
        gamma_b: v[1] * v[0],
        kappa: v[2],
        sigma_b: v[3],
        n: v[4],
        p: v[5],
        u_b: v[6],
        t_b: v[7],
    }
}

/// The inverse of [`scale`].
fn unscale(lo: f64, hi: f64, log: bool, v: f64) -> f64 {
    if hi == lo {
        0.5
    } else if log {
        (v / lo).ln() / (hi / lo).ln()
    } else {
        (v - lo) / (hi - lo)
    }
}

/// The largest κ the inequality `(m/k) κ / T_b^(p+1) <= 1` and the upper bound `hi` allow.
fn kappa_max(c: KnownMassStiffness, hi: f64, t_b: f64, p: f64) -> f64 {
    hi.min(c.k / c.m * t_b.powf(p + 1.0))
}

/// Admissible range of each quantity (for messages) and a check.
fn admissible(kind: ModelKind, i: usize, v: f64) -> Result<(), &'static str> {
    let ok = match i {
        0 => v >= 0.0,
        1 => (-1.0..=1.0).contains(&v),
        2 => v > 0.0 && v < 1.0,
        3 if kind == ModelKind::Mcm => v > 0.0,
        3 => v >= 0.0,
        4 | 5 => v >= 1.0,
        _ => v > 0.0,
    };
    if ok && v.is_finite() {
        return Ok(());
    }
    Err(match i {
        0 => "B_b >= 0",
        1 => "-1 <= g = Gamma_b / B_b <= 1",
        2 => "0 < kappa < 1",
        3 if kind == ModelKind::Mcm => "sigma_b > 0 for the NDBWMCM",
        3 => "sigma_b >= 0",
        4 => "n >= 1",
        5 => "p >= 1",
        6 => "U_b > 0",
        _ => "T_b > 0",
    })
}

impl Space {
    /// Builds a space from one entry per name in [`NAMES`].
    ///
    /// # Errors
    /// [`IdentifyError::Bounds`] for `lo > hi`, a bound or fixed value outside the admissible
    /// set, or a log scale with `lo <= 0`; [`IdentifyError::Infeasible`] if `T_b` is given while
    /// it is tied to `U_b`, or if no point satisfies the constraints; [`IdentifyError::Bounds`]
    /// naming `m`/`k` for a non-positive mass or stiffness.
    pub fn new(
        kind: ModelKind,
        params: [Param; 8],
        known: Option<KnownMassStiffness>,
    ) -> Result<Self, IdentifyError> {
        let bad =
            |name: &'static str, lo: f64, hi: f64, allowed: &'static str| IdentifyError::Bounds {
                name,
                lo,
                hi,
                allowed,
            };
        for (i, p) in params.iter().enumerate() {
            let name = NAMES[i];
            match (known.is_some() && i == 7, p) {
                (true, Param::Derived) => continue,
                (true, _) => {
                    return Err(IdentifyError::Infeasible { reason: "T_b = m U_b is eliminated by the known mass: give no bound or value for T_b".into() })
                }
                (false, Param::Derived) => {
                    return Err(IdentifyError::Infeasible { reason: format!("{name} can only be derived (T_b = m U_b) when the mass and stiffness are known") })
                }
                _ => {}
            }
            match *p {
                Param::Derived => unreachable!("handled above"),
                Param::Fixed(v) => admissible(kind, i, v).map_err(|a| bad(name, v, v, a))?,
                Param::Free { lo, hi, log } => {
                    if lo.is_nan() || hi.is_nan() || lo > hi {
                        return Err(bad(name, lo, hi, "lower bound <= upper bound"));
                    }
                    admissible(kind, i, lo).map_err(|a| bad(name, lo, hi, a))?;
                    admissible(kind, i, hi).map_err(|a| bad(name, lo, hi, a))?;
                    if log && lo <= 0.0 {
                        return Err(bad(name, lo, hi, "lower bound > 0 on a logarithmic scale"));
                    }
                }
            }
        }
        if let Some(c) = known {
            if !c.m.is_finite() || c.m <= 0.0 {
                return Err(bad("m", c.m, c.m, "m > 0 (kg)"));
            }
            if !c.k.is_finite() || c.k <= 0.0 {
                return Err(bad("k", c.k, c.k, "k > 0"));
            }
        }
        let free = (0..8)
            .filter(|&i| matches!(params[i], Param::Free { .. }) && !(known.is_some() && i == 7))
            .collect();
        let space = Self {
            kind,
            params,
            known,
            free,
            family: None,
        };
        if space.known.is_some() {
            // The inequality is easiest to meet at small κ, large T_b (large U_b) and small p.
            let mut s = vec![0.0; space.dim()];
            for (j, &i) in space.free.iter().enumerate() {
                s[j] = match i {
                    6 => 1.0,
                    _ => 0.0,
                };
            }
            if space.violation(&space.decode(&s)) > 0.0 {
                return Err(IdentifyError::Infeasible {
                    reason: "no point in the bounds satisfies (m/k) kappa / T_b^(p+1) <= 1".into(),
                });
            }
        }
        Ok(space)
    }

    /// The space of a contact-law family: its parameter ([`Family::param_name`]) and
    /// `T_b` (s), each searched or fixed.
    ///
    /// # Errors
    /// [`IdentifyError::Bounds`] naming the parameter for bounds it does not admit, `lo > hi`,
    /// or a log scale with `lo <= 0`.
    pub fn family(family: Family, param: Param, t_b: Param) -> Result<Self, IdentifyError> {
        let name = family.param_name();
        let check = |name: &'static str, p: Param, test: &dyn Fn(f64) -> Result<(), ModelError>| {
            let (lo, hi, log) = match p {
                Param::Fixed(v) => (v, v, false),
                Param::Free { lo, hi, log } => (lo, hi, log),
                Param::Derived => (f64::NAN, f64::NAN, false),
            };
            let bad = |allowed| IdentifyError::Bounds {
                name,
                lo,
                hi,
                allowed,
            };
            if lo.is_nan() || hi.is_nan() || lo > hi {
                return Err(bad("lower bound <= upper bound"));
            }
            if log && lo <= 0.0 {
                return Err(bad("lower bound > 0 on a logarithmic scale"));
            }
            for v in [lo, hi] {
                if let Err(ModelError::InvalidParameter { allowed, .. }) = test(v) {
                    return Err(bad(allowed));
                }
            }
            Ok(())
        };
        let with = |param, t_b| FamilyParams { family, param, t_b }.validate();
        check(name, param, &|v| with(v, 1.0))?;
        check("T_b", t_b, &|v| with(family.spec().param.neutral, v))?;
        let params = [
            Param::Fixed(0.0),
            Param::Fixed(0.0),
            Param::Fixed(0.5),
            param,
            Param::Fixed(1.0),
            Param::Fixed(family.exponent()),
            Param::Fixed(1.0),
            t_b,
        ];
        let free = (0..8)
            .filter(|&i| matches!(params[i], Param::Free { .. }))
            .collect();
        Ok(Self {
            kind: ModelKind::Shccm,
            params,
            known: None,
            free,
            family: Some(family),
        })
    }

    /// The law of a family's space at `p` (its parameter from the slot of `sigma_b`, `T_b`
    /// from that of `T_b`), not validated; `None` for a Bouc-Wen space.
    pub fn family_params(&self, p: &BaseParams) -> Option<FamilyParams> {
        self.family.map(|family| FamilyParams {
            family,
            param: p.sigma_b,
            t_b: p.t_b,
        })
    }

    /// The contact-law family, if the space is one's.
    pub fn family_of(&self) -> Option<Family> {
        self.family
    }

    /// The name of quantity `i` (index into [`NAMES`]) in this space: a family's parameter in
    /// the slot of `sigma_b`.
    pub fn name(&self, i: usize) -> &'static str {
        match self.family {
            Some(f) if i == 3 => f.param_name(),
            _ => NAMES[i],
        }
    }

    /// The model.
    pub fn kind(&self) -> ModelKind {
        self.kind
    }

    /// Number of free quantities.
    pub fn dim(&self) -> usize {
        self.free.len()
    }

    /// The free quantities' indices into [`NAMES`], in search order.
    pub fn free_indices(&self) -> &[usize] {
        &self.free
    }

    /// Names of the free quantities, in search order.
    pub fn free_names(&self) -> Vec<&'static str> {
        self.free.iter().map(|&i| self.name(i)).collect()
    }

    /// Names of the free quantities at search coordinates `coords` (positions in
    /// [`Space::free_indices`], as [`crate::at_bound`] gives them).
    pub fn names_at(&self, coords: &[usize]) -> Vec<&'static str> {
        coords.iter().map(|&j| self.name(self.free[j])).collect()
    }

    /// Where `bound`, a bound of quantity `i` (index into [`NAMES`]) of a Bouc-Wen space, is the
    /// model's own closed limit (`B_b = 0`, `g = ±1`, `sigma_b = 0` for the NDBWSHCCM, `n = 1`,
    /// `p = 1`): the admissible set it closes, since a bound there cannot be widened.
    pub fn model_limit(&self, i: usize, bound: f64) -> Option<&'static str> {
        if self.family.is_some() {
            return None;
        }
        let at = match i {
            0 => bound == 0.0,
            1 => bound.abs() == 1.0,
            3 => self.kind == ModelKind::Shccm && bound == 0.0,
            4 | 5 => bound == 1.0,
            _ => false,
        };
        at.then(|| admissible(self.kind, i, f64::NAN).unwrap_err())
    }

    /// The bounds `(lo, hi)` of quantity `i` (index into [`NAMES`]) if it is searched.
    pub fn bounds(&self, i: usize) -> Option<(f64, f64)> {
        match self.params.get(i)? {
            Param::Free { lo, hi, .. } => Some((*lo, *hi)),
            _ => None,
        }
    }

    /// Every quantity of [`NAMES`]: held, derived or searched.
    pub fn params(&self) -> &[Param; 8] {
        &self.params
    }

    /// The Villegas constraints, if any.
    pub fn known(&self) -> Option<KnownMassStiffness> {
        self.known
    }

    /// The searchable quantities of [`NAMES`] (with `g`, not `Γ_b`) at a point `s` of the unit
    /// cube (coordinates are clamped into it).
    pub fn quantities(&self, s: &[f64]) -> [f64; 8] {
        let mut v = values_at(&self.params, &self.free, s);
        if let Some(c) = self.known {
            v[7] = c.m * v[6];
            // κ is searched between its lower bound and the largest value the inequality
            // allows at this T_b and p: the constraint is a face of the cube, not a penalty.
            if let Some(j) = self.free.iter().position(|&i| i == 2) {
                if let Param::Free { lo, hi, log } = self.params[2] {
                    v[2] = scale(lo, kappa_max(c, hi, v[7], v[5]).max(lo), log, s[j]);
                }
            }
        }
        v
    }

    /// Base parameters at a point `s` of the unit cube (coordinates are clamped into it).
    pub fn decode(&self, s: &[f64]) -> BaseParams {
        base_params(&self.quantities(s))
    }

    /// The point of the unit cube for base parameters `p` (the inverse of [`Space::decode`]).
    ///
    /// # Errors
    /// [`IdentifyError::Bounds`] if a free quantity of `p` lies outside its bounds.
    pub fn encode(&self, p: &BaseParams) -> Result<Vec<f64>, IdentifyError> {
        let g = if p.b_b > 0.0 { p.gamma_b / p.b_b } else { 0.0 };
        let v = [p.b_b, g, p.kappa, p.sigma_b, p.n, p.p, p.u_b, p.t_b];
        self.free
            .iter()
            .map(|&i| match self.params[i] {
                Param::Free { lo, hi, log } => {
                    if v[i].is_nan() || v[i] < lo || v[i] > hi {
                        return Err(IdentifyError::Bounds {
                            name: NAMES[i],
                            lo: v[i],
                            hi: v[i],
                            allowed: "a starting point inside the bounds",
                        });
                    }
                    let hi = match self.known {
                        Some(c) if i == 2 => {
                            kappa_max(c, hi, c.m * p.u_b, p.p).max(lo).min(hi).max(v[i])
                        }
                        _ => hi,
                    };
                    Ok(unscale(lo, hi, log, v[i]))
                }
                Param::Fixed(_) | Param::Derived => unreachable!("only free indices"),
            })
            .collect()
    }

    /// The point of the unit cube nearest to `p`, each free quantity clamped into its bounds,
    /// and the names of those that were outside (for comparing a published vector with a fit).
    ///
    /// # Errors
    /// [`IdentifyError::Bounds`] where a free quantity of `p` is not a number.
    pub fn nearest_point(
        &self,
        p: &BaseParams,
    ) -> Result<(Vec<f64>, Vec<&'static str>), IdentifyError> {
        let g = if p.b_b > 0.0 { p.gamma_b / p.b_b } else { 0.0 };
        let mut v = [p.b_b, g, p.kappa, p.sigma_b, p.n, p.p, p.u_b, p.t_b];
        let mut outside = Vec::new();
        for &i in &self.free {
            if let Param::Free { lo, hi, .. } = self.params[i] {
                if v[i] < lo || v[i] > hi {
                    outside.push(NAMES[i]);
                    v[i] = v[i].clamp(lo, hi);
                }
            }
        }
        Ok((self.encode(&base_params(&v))?, outside))
    }

    /// Whether the free quantity `i` (index into [`NAMES`]) at cube coordinate 1 sits on the
    /// inequality constraint rather than on its upper bound (κ under [`KnownMassStiffness`]).
    pub fn on_constraint(&self, i: usize, s: &[f64]) -> bool {
        match (self.known, self.params[i]) {
            (Some(_), Param::Free { hi, .. }) if i == 2 => self.quantities(s)[2] < hi,
            _ => false,
        }
    }

    /// How far `p` violates the inequality constraint (0 when satisfied).
    pub fn violation(&self, p: &BaseParams) -> f64 {
        match self.known {
            Some(c) => (c.m / c.k * p.kappa / p.t_b.powf(p.p + 1.0) - 1.0).max(0.0),
            None => 0.0,
        }
    }

    /// The model `p` describes: the base map of `p`, or a family's law (its parameter `p.sigma_b`,
    /// `T_b = p.t_b`).
    ///
    /// # Errors
    /// [`IdentifyError::Model`] if `p` is not admissible for the model.
    pub fn map(&self, p: &BaseParams) -> Result<FitModel, IdentifyError> {
        match self.family_params(p) {
            Some(law) => {
                law.validate()?;
                Ok(FitModel::Family(law))
            }
            None => Ok(FitModel::BoucWen(BaseMap::new(self.kind, *p)?)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn free(lo: f64, hi: f64) -> Param {
        Param::Free { lo, hi, log: false }
    }

    #[test]
    fn a_bound_at_the_models_own_limit_is_named_as_such() {
        let params = [
            free(0.0, 4.0),
            free(-1.0, 1.0),
            free(0.1, 0.9),
            free(0.0, 0.1),
            free(1.0, 2.0),
            free(1.2, 3.0),
            Param::Fixed(1.0),
            Param::Fixed(1.0),
        ];
        let shccm = Space::new(ModelKind::Shccm, params, None).unwrap();
        assert_eq!(shccm.model_limit(4, 1.0), Some("n >= 1"));
        assert_eq!(shccm.model_limit(4, 2.0), None);
        assert_eq!(shccm.model_limit(5, 1.2), None);
        assert_eq!(shccm.model_limit(0, 0.0), Some("B_b >= 0"));
        assert_eq!(
            shccm.model_limit(1, -1.0),
            Some("-1 <= g = Gamma_b / B_b <= 1")
        );
        assert_eq!(shccm.model_limit(3, 0.0), Some("sigma_b >= 0"));
        // kappa's limits are open: a bound at 0.1 or 0.9 can be widened.
        assert_eq!(shccm.model_limit(2, 0.9), None);
        let mut params = params;
        params[3] = free(1e-3, 0.1);
        let mcm = Space::new(ModelKind::Mcm, params, None).unwrap();
        assert_eq!(mcm.model_limit(3, 0.0), None);
    }

    #[test]
    fn decode_encode_and_validation() {
        let params = [
            free(0.0, 4.0),
            free(-1.0, 1.0),
            free(0.1, 0.9),
            Param::Free {
                lo: 1e-4,
                hi: 1.0,
                log: true,
            },
            Param::Fixed(1.0),
            free(1.0, 3.0),
            Param::Fixed(1.0),
            Param::Fixed(1.0),
        ];
        let s = Space::new(ModelKind::Shccm, params, None).unwrap();
        assert_eq!(s.dim(), 5);
        assert_eq!(s.free_names(), vec!["B_b", "g", "kappa", "sigma_b", "p"]);
        let p = s.decode(&[0.5, 0.5, 1.0, 0.5, 0.0]);
        assert_eq!(
            (p.b_b, p.gamma_b, p.kappa, p.n, p.p),
            (2.0, 0.0, 0.9, 1.0, 1.0)
        );
        assert!((p.sigma_b - 1e-2).abs() < 1e-15);
        let back = s.encode(&p).unwrap();
        assert!(
            back.iter()
                .zip([0.5, 0.5, 1.0, 0.5, 0.0])
                .all(|(a, b)| (a - b).abs() < 1e-12),
            "{back:?}"
        );
        // Γ_b stays within ±B_b everywhere.
        let q = s.decode(&[1.0, -1.0, 0.5, 0.5, 0.5]);
        assert_eq!(q.gamma_b, -q.b_b);
        let mut swapped = params;
        swapped[2] = free(0.9, 0.1);
        assert!(matches!(
            Space::new(ModelKind::Shccm, swapped, None),
            Err(IdentifyError::Bounds { name: "kappa", .. })
        ));
        let mut out = params;
        out[2] = free(0.0, 0.9);
        assert!(matches!(
            Space::new(ModelKind::Shccm, out, None),
            Err(IdentifyError::Bounds { name: "kappa", .. })
        ));
        let mut mcm_sigma = params;
        mcm_sigma[3] = free(0.0, 1.0);
        assert!(Space::new(ModelKind::Mcm, mcm_sigma, None).is_err());
        assert!(
            s.encode(&bw_models::BaseParams { b_b: 5.0, ..p }).is_err(),
            "start outside bounds"
        );
    }

    #[test]
    fn villegas_constraints() {
        let known = Some(KnownMassStiffness { m: 0.506, k: 255.0 });
        let mut params = [
            free(0.0, 20.0),
            free(-1.0, 1.0),
            free(0.1, 0.9),
            free(0.01, 0.2),
            free(1.0, 2.0),
            free(1.0, 1.5),
            free(0.01, 0.2),
            Param::Derived,
        ];
        let s = Space::new(ModelKind::Shccm, params, known).unwrap();
        let p = s.decode(&vec![0.5; s.dim()]);
        assert!((p.t_b - 0.506 * p.u_b).abs() < 1e-15);
        assert_eq!(s.dim(), 7);
        // Paper's Table 5 (NDBWSHCCM): κ = 0.324, p = 1, T_b = 0.0255: (m/k) κ / T_b^2 = 0.989 <= 1.
        let paper = BaseParams {
            b_b: 17.4,
            gamma_b: 13.1,
            kappa: 0.324,
            sigma_b: 0.0794,
            n: 1.0,
            p: 1.0,
            u_b: 0.0503,
            t_b: 0.0255,
        };
        assert_eq!(s.violation(&paper), 0.0);
        assert!(s.violation(&BaseParams { t_b: 0.02, ..paper }) > 0.0);
        params[7] = free(0.01, 0.1);
        assert!(matches!(
            Space::new(ModelKind::Shccm, params, known),
            Err(IdentifyError::Infeasible { .. })
        ));
        params[7] = Param::Derived;
        params[6] = free(1e-4, 1e-3);
        assert!(matches!(
            Space::new(ModelKind::Shccm, params, known),
            Err(IdentifyError::Infeasible { .. })
        ));
    }
}

//! How far a state is from a point where the right-hand side is not analytic
//! ([`crate::CollisionModel::clearance`]): the roots of the bases of the powers `|s|^q`.

use crate::{Nondim, State};

/// The time a base `s` moving at `ds` takes to reach 0, where a term `c |s|^q` is not
/// analytic, if it is approaching and the term matters: while the term's integral over the
/// approach, about `c |s|^(q+1) / |ds|`, exceeds `rtol` (nondimensional states are of order
/// 1). Past that, a step may end on or cross the root at an error below the tolerance.
fn clearance(s: f64, ds: f64, terms: &[(f64, f64)], rtol: f64) -> f64 {
    if s * ds >= 0.0 {
        return f64::INFINITY;
    }
    let time = (s / ds).abs();
    let matters = terms
        .iter()
        .any(|&(c, q)| c * s.abs().powf(q) * time > rtol);
    if matters {
        time
    } else {
        f64::INFINITY
    }
}

/// [`crate::CollisionModel::clearance`] of the NDBWSHCCM at `(X, Z, V)` with derivative `f`: `X`
/// carries `κ|X|^p` and `σ|X|^p V`, `Z` carries `(1-κ)|Z|^p` and `(B ± Γ)|Z|^n V`.
pub(crate) fn shccm_clearance(k: &Nondim, y: [f64; 3], f: [f64; 3], rtol: f64) -> f64 {
    let v = y[2].abs();
    let x = clearance(y[0], f[0], &[(k.kappa + k.sigma * v, k.p)], rtol);
    let hysteresis = (k.b.abs() + k.gamma.abs()) * v;
    x.min(clearance(
        y[1],
        f[1],
        &[(1.0 - k.kappa, k.p), (hysteresis, k.n)],
        rtol,
    ))
}

/// A state and its time derivative in natural units: states over Table 1's `scale`, time
/// over `T_c`.
pub(crate) fn in_natural_units<const N: usize>(
    y: &State<N>,
    f: &State<N>,
    scale: State<N>,
    t_c: f64,
) -> (State<N>, State<N>) {
    (y.component_div(&scale), f.component_div(&scale) * t_c)
}

//! The Hunt-Crossley limit of the NDBWSHCCM (`B = Γ = 0`), the examples' known answer.

/// `e` at `σ`: the root in `(0, min(1, 1/σ))` of `σ - ln(1+σ) = -σe - ln(1-σe)` (first integral
/// of `s'' = -s^p (1 + σ s')`), found by bisection.
pub fn hunt_crossley_e(sigma: f64) -> f64 {
    let g = |e: f64| sigma - sigma.ln_1p() + sigma * e + (-sigma * e).ln_1p();
    let (mut lo, mut hi) = (1e-12, (1.0f64).min(1.0 / sigma) * (1.0 - 1e-12));
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

//! What the elastic-plastic sphere laws (Thornton's, Jackson and Green's) share as contact
//! elements: states `(x, x_m)` (m), `x_m` the deepest `x` so far. At the deepest point the
//! contact loads on its loading curve (`ẋ_m = u` while `u < 0`); off it, it unloads and
//! reloads elastically on the curve from the deepest point, down to the residual penetration.
//! A law gives its curves ([`DeepestPoint`]); the functions here are its `ContactLaw`
//! methods.

use bwc_ode::State;

/// The curves of a law that loads at its deepest point and unloads elastically from it.
pub(super) trait DeepestPoint {
    /// The loading force (N) at penetration `d` (m).
    fn loading(&self, d: f64) -> f64;
    /// The force (N) at `d` on the unloading curve from the deepest `dm` (m).
    fn unloading(&self, d: f64, dm: f64) -> f64;
    /// Where the unloading curve from `dm` ends (m).
    fn residual(&self, dm: f64) -> f64;
    /// The energy (J) the unloading from `dm` gives back from `d`.
    fn elastic(&self, d: f64, dm: f64) -> f64;
    /// The penetration (m) where the loading curve changes its formula (a kink).
    fn loading_kink(&self) -> f64;
    /// The penetration (m) below which loading dissipates nothing.
    fn plastic_from(&self) -> f64;
    /// `dE/dδ_m` at `δ_m = d` of the deepest point's elastic energy `E(δ_m) = elastic(δ_m,
    /// δ_m)`, where the loading force there is `force` (N).
    fn growth(&self, d: f64, force: f64) -> f64;
}

/// The penetration, the deepest penetration, and whether the state is at its deepest.
pub(super) fn phase(s: &State<2>) -> (f64, f64, bool) {
    let d = -s[0];
    let dm = (-s[1]).max(d);
    (d, dm, d >= dm)
}

/// The state rate and the force at `s` with input `u`.
pub(super) fn eval(law: &impl DeepestPoint, s: &State<2>, u: f64) -> (State<2>, f64) {
    let (d, dm, deepest) = phase(s);
    let f = if deepest {
        law.loading(d)
    } else {
        law.unloading(d, dm)
    };
    let loads = deepest && u < 0.0;
    (State::<2>::new(u, if loads { u } else { 0.0 }), f)
}

/// The energy stored at `s`: the unloading's from the deepest point.
pub(super) fn stored(law: &impl DeepestPoint, s: &State<2>) -> f64 {
    let (d, dm, _) = phase(s);
    law.elastic(d, dm)
}

/// 0 off the deepest point and below [`DeepestPoint::plastic_from`]; at it, while loading,
/// `F δ̇` less the rate at which the deepest point's elastic energy grows.
pub(super) fn dissipation(law: &impl DeepestPoint, s: &State<2>, u: f64, force: f64) -> f64 {
    let (d, _, deepest) = phase(s);
    if !(deepest && u < 0.0 && d > law.plastic_from()) {
        return 0.0;
    }
    -u * (force - law.growth(d, force))
}

/// The turn at the deepest point (`u`, then `δ_m - δ` off it) and the loading curve's kink
/// while loading, the end of the unloading curve off it.
pub(super) fn kinks(law: &impl DeepestPoint, s: &State<2>, u: f64) -> [f64; 2] {
    let (d, dm, deepest) = phase(s);
    if deepest {
        [u, d - law.loading_kink()]
    } else {
        [dm - d, d - law.residual(dm)]
    }
}

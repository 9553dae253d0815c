//! Property tests of the Lyapunov functions of Appendices B and C (formulas in REFERENCES.md):
//! W' <= 0 everywhere, dV/dT <= 0 wherever ||X||_inf >= K, and along solutions with inputs in
//! U_1, W(X(T)) <= exp(E(inf)) max(W(X(0)), W_K).

use bw_models::input::{Constant, FromFn};
use bw_models::{ModelKind, Ndbwmcm, Ndbwshccm, Nondim, NondimParams, State};
use bwc_ode::{Integrator, Options, System, DOP853};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

/// Deterministic property tests: a fixed seed, no regression files written.
pub fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_seed: RngSeed::Fixed(0x6277_6320),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

fn spow(x: f64, p: f64) -> f64 {
    x.abs().powf(p - 1.0) * x
}

fn w_shccm(q: &Nondim, x: &State<3>) -> f64 {
    let p = q.p;
    q.kappa * x[0].abs().powf(p + 1.0) / (p + 1.0)
        + (1.0 - q.kappa) * x[1].abs().powf(p + 1.0) / (p + 1.0)
        + 0.5 * x[2] * x[2]
}

fn wprime_shccm(q: &Nondim, x: &State<3>) -> f64 {
    let (xx, z, v) = (x[0], x[1], x[2]);
    -q.sigma * xx.abs().powf(q.p) * v * v
        - (1.0 - q.kappa)
            * z.abs().powf(q.p + q.n - 1.0)
            * (q.b * z.abs() * v.abs() + q.gamma * z * v)
}

fn grad_shccm(q: &Nondim, x: &State<3>) -> State<3> {
    State::<3>::new(
        q.kappa * spow(x[0], q.p),
        (1.0 - q.kappa) * spow(x[1], q.p),
        x[2],
    )
}

fn k_shccm(q: &Nondim) -> f64 {
    ((q.p + 1.0) / q.kappa).max((q.p + 1.0) / (1.0 - q.kappa))
}

fn wk_shccm(q: &Nondim) -> f64 {
    let k = k_shccm(q);
    k.powf(q.p + 1.0) / (q.p + 1.0) + 0.5 * k * k
}

fn rdot(q: &Nondim, x: &State<4>) -> f64 {
    q.kappa * q.sigma * spow(x[1], q.p) + (1.0 - q.kappa) * q.sigma * spow(x[2], q.p)
}

fn w_mcm(q: &Nondim, x: &State<4>) -> f64 {
    let p = q.p;
    (x[0] + q.sigma * x[3]).powi(2)
        + q.kappa * x[1].abs().powf(p + 1.0) / (p + 1.0)
        + (1.0 - q.kappa) * x[2].abs().powf(p + 1.0) / (p + 1.0)
        + 0.5 * x[3] * x[3]
}

fn wprime_mcm(q: &Nondim, x: &State<4>) -> f64 {
    let (z, v) = (x[2], x[3]);
    let rd = rdot(q, x);
    -rd * rd / q.sigma
        - (1.0 - q.kappa)
            * z.abs().powf(q.p + q.n - 1.0)
            * (q.b * z.abs() * (v - rd).abs() + q.gamma * z * (v - rd))
}

fn grad_mcm(q: &Nondim, x: &State<4>) -> State<4> {
    let a = 2.0 * (x[0] + q.sigma * x[3]);
    State::<4>::new(
        a,
        q.kappa * spow(x[1], q.p),
        (1.0 - q.kappa) * spow(x[2], q.p),
        q.sigma * a + x[3],
    )
}

fn k_mcm(q: &Nondim) -> f64 {
    let s = q.sigma;
    (2.0 * s * s + 2.0 * s + 1.0)
        * (2.0 * s * s + 1.0)
            .max((q.p + 1.0) / q.kappa)
            .max((q.p + 1.0) / (1.0 - q.kappa))
}

fn wk_mcm(q: &Nondim) -> f64 {
    let k = k_mcm(q);
    (k * (1.0 + q.sigma)).powi(2) + k.powf(q.p + 1.0) / (q.p + 1.0) + 0.5 * k * k
}

prop_compose! {
    fn params(sigma_min: f64)(b in 0.0..20.0f64, g in -1.0..=1.0f64, kappa in 0.02..0.98f64,
        sigma in sigma_min..4.0f64, n in 1.0..4.0f64, p in 1.0..4.0f64) -> Nondim {
        Nondim { b, gamma: g * b, kappa, sigma, n, p }
    }
}

fn scale(e: f64) -> f64 {
    1e-9 * (1.0 + e.abs())
}

proptest! {
    #![proptest_config(config(400))]

    /// The model's right-hand side, the paper's W' and dW/dT = W' + U V agree, and W' <= 0.
    #[test]
    fn shccm_lyapunov_derivative(q in params(0.0), x in -3.0..3.0f64, z in -3.0..3.0f64, v in -3.0..3.0f64, u in -10.0..10.0f64) {
        let params = NondimParams::new(ModelKind::Shccm, q).unwrap();
        let y = State::<3>::new(x, z, v);
        let f = Ndbwshccm::new(&params, Constant(u)).unwrap().rhs(0.0, &y);
        let wp = wprime_shccm(&q, &y);
        let along = grad_shccm(&q, &y).dot(&f);
        prop_assert!((along - (wp + u * v)).abs() <= scale(along) * 10.0, "dW/dT {along} vs {}", wp + u * v);
        prop_assert!(wp <= scale(wp), "W' = {wp}");
    }

    #[test]
    fn mcm_lyapunov_derivative(q in params(1e-3), r in -3.0..3.0f64, y1 in -3.0..3.0f64, z in -3.0..3.0f64, v in -3.0..3.0f64, u in -10.0..10.0f64) {
        let params = NondimParams::new(ModelKind::Mcm, q).unwrap();
        let y = State::<4>::new(r, y1, z, v);
        let f = Ndbwmcm::new(&params, Constant(u)).unwrap().rhs(0.0, &y);
        let wp = wprime_mcm(&q, &y);
        let along = grad_mcm(&q, &y).dot(&f);
        let expected = wp + u * ((2.0 * q.sigma * q.sigma + 1.0) * v + 2.0 * q.sigma * r);
        prop_assert!((along - expected).abs() <= scale(along) * 10.0, "dW/dT {along} vs {expected}");
        prop_assert!(wp <= scale(wp), "W' = {wp}");
    }

    /// dV/dT = e^(-E) (dW/dT - |U| W) <= 0 wherever ||X||_inf >= K (Lemmas B.1, C.1).
    #[test]
    fn lyapunov_decreases_outside_the_ball(q in params(1e-3), dir in prop::array::uniform4(-1.0..1.0f64), stretch in 1.0..3.0f64, u in -10.0..10.0f64) {
        let m = dir.iter().fold(0.0f64, |a, d| a.max(d.abs())).max(1e-3);
        let ks = k_shccm(&q) * stretch / m;
        let y = State::<3>::new(dir[0] * ks, dir[1] * ks, dir[2] * ks);
        if y.amax() >= k_shccm(&q) {
            let dw = wprime_shccm(&q, &y) + u * y[2];
            let w = w_shccm(&q, &y);
            prop_assert!(dw - u.abs() * w <= scale(w), "SHCCM: {dw} - |U| {w}");
        }
        let km = k_mcm(&q) * stretch / m;
        let y = State::<4>::new(dir[0] * km, dir[1] * km, dir[2] * km, dir[3] * km);
        if y.amax() >= k_mcm(&q) {
            let dw = wprime_mcm(&q, &y) + u * ((2.0 * q.sigma * q.sigma + 1.0) * y[3] + 2.0 * q.sigma * y[0]);
            let w = w_mcm(&q, &y);
            prop_assert!(dw - u.abs() * w <= scale(w), "MCM: {dw} - |U| {w}");
        }
    }
}

proptest! {
    #![proptest_config(config(48))]

    /// Along simulated solutions with U(T) = a e^(-T) sin(ω T) (E(inf) <= |a|):
    /// W(X(T)) <= exp(|a|) max(W(X(0)), W_K).
    #[test]
    fn solutions_stay_bounded(q in params(1e-2), x0 in prop::array::uniform4(-4.0..4.0f64), a in -10.0..10.0f64, omega in 0.1..20.0f64) {
        let u = FromFn(move |t: f64| a * (-t).exp() * (omega * t).sin());
        let bound_factor = a.abs().exp() * (1.0 + 1e-8);
        let opts3 = Options::<3>::new(1e-10, 1e-12).with_max_steps(200_000);
        let opts4 = Options::<4>::new(1e-10, 1e-12).with_max_steps(200_000);

        let shccm = Ndbwshccm::new(&NondimParams::new(ModelKind::Shccm, q).unwrap(), u).unwrap();
        let y0 = State::<3>::new(x0[0], x0[1], x0[2]);
        let bound = bound_factor * w_shccm(&q, &y0).max(wk_shccm(&q));
        let mut it = Integrator::new(|t: f64, y: &State<3>| shccm.rhs(t, y), &DOP853, 0.0, y0, opts3).unwrap();
        while it.t() < 30.0 {
            it.step(30.0).unwrap();
            prop_assert!(w_shccm(&q, it.y()) <= bound, "SHCCM W = {} > {bound} at T = {}", w_shccm(&q, it.y()), it.t());
        }

        let mcm = Ndbwmcm::new(&NondimParams::new(ModelKind::Mcm, q).unwrap(), u).unwrap();
        let y0 = State::<4>::new(x0[0], x0[1], x0[2], x0[3]);
        let bound = bound_factor * w_mcm(&q, &y0).max(wk_mcm(&q));
        let mut it = Integrator::new(|t: f64, y: &State<4>| mcm.rhs(t, y), &DOP853, 0.0, y0, opts4).unwrap();
        while it.t() < 30.0 {
            it.step(30.0).unwrap();
            prop_assert!(w_mcm(&q, it.y()) <= bound, "MCM W = {} > {bound} at T = {}", w_mcm(&q, it.y()), it.t());
        }
    }
}

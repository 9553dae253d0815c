//! The cost of a contact element's host step during a contact: a baseball (Table 4's BWSHCCL
//! and BWMCL, 0.145 kg) dropped on a fixed floor at 2 m/s, stepped by a predictor-corrector
//! host at dt = 1e-4, 1e-5 and 1e-6 s (two element steps per host step), in Rust and through
//! the C ABI (`bwc-capi`: handles, status codes, a scratch element copied for the predictor),
//! against one `impact` of the same contact, timed side by side (`bwc_benches::side_by_side`:
//! medians of seven rounds in turns).
//!
//! `cargo run --release -p bwc-benches --bin element-step`

use bw_models::input::Constant;
use bw_models::{impact, Bwmcl, Bwmcm, Bwshccl, Bwshccm, ContactElement, ContactLaw};
use bw_models::{ElementSettings, ModelKind, Physical, PhysicalParams, Settings};
use bwc as capi;
use bwc_benches::side_by_side;

const M: f64 = 0.145;
const G: f64 = 9.81;
const V_IN: f64 = 2.0;

/// Table 4 (Cross 2011) of `kind`.
fn table4(kind: ModelKind) -> PhysicalParams {
    bw_models::published::cross(kind)
}

/// One bounce by the host: element steps taken and the rebound speed (m/s).
fn bounce<L: ContactLaw<N> + Clone, const N: usize>(law: L, dt: f64) -> (u64, f64) {
    let mut element = ContactElement::new(law, ElementSettings::default()).expect("settings");
    let (mut v, mut force, mut steps) = (-V_IN, 0.0, 0);
    loop {
        let guess = v + (force / M - G) * dt;
        let first = element.clone().advance(dt, v, guess).expect("step");
        let next = v + first.impulse / M - G * dt;
        let step = element.advance(dt, v, next).expect("step");
        steps += 2;
        if let Some(tau) = step.separated_at {
            return (steps, v + (next - v) * tau / dt);
        }
        (v, force) = (next, step.force);
    }
}

/// The same bounce through the C ABI.
fn bounce_c(law: &Physical, kind: ModelKind, dt: f64) -> (u64, f64) {
    let params = capi::BwcLawParams {
        model: if kind == ModelKind::Shccm {
            capi::BWC_MODEL_SHCCM
        } else {
            capi::BWC_MODEL_MCM
        },
        k: law.k,
        c: law.c,
        n: law.n,
        p: law.p,
        alpha: law.alpha,
        beta: law.beta,
        gamma: law.gamma,
        a: law.a,
    };
    let ok = capi::BwcStatus::Ok;
    let (mut h, mut contact, mut scratch) = (0, 0, 0);
    let mut step = capi::BwcStep {
        force: 0.0,
        impulse: 0.0,
        work: 0.0,
        separated_at: 0.0,
        began_at: 0.0,
    };
    // SAFETY: valid pointers to live values.
    unsafe {
        assert_eq!(capi::bwc_law_new(&params, &mut h), ok);
        assert_eq!(capi::bwc_contact_new(h, std::ptr::null(), &mut contact), ok);
        assert_eq!(capi::bwc_contact_clone(contact, &mut scratch), ok);
    }
    let (mut v, mut force, mut steps) = (-V_IN, 0.0, 0);
    let v_out = loop {
        let guess = v + (force / M - G) * dt;
        assert_eq!(capi::bwc_contact_copy(contact, scratch), ok);
        // SAFETY: `step` is writable.
        assert_eq!(
            unsafe { capi::bwc_contact_advance(scratch, dt, v, guess, &mut step) },
            ok
        );
        let next = v + step.impulse / M - G * dt;
        // SAFETY: `step` is writable.
        assert_eq!(
            unsafe { capi::bwc_contact_advance(contact, dt, v, next, &mut step) },
            ok
        );
        steps += 2;
        if !step.separated_at.is_nan() {
            break v + (next - v) * step.separated_at / dt;
        }
        (v, force) = (next, step.force);
    };
    for handle in [scratch, contact] {
        assert_eq!(capi::bwc_contact_free(handle), ok);
    }
    assert_eq!(capi::bwc_law_free(h), ok);
    (steps, v_out)
}

fn main() {
    println!("model  dt (s)   element steps  us per step  C us per step  bounce (ms)  impact (us)  bounce/impact  rebound error");
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let params = table4(kind);
        let run_impact = || match kind {
            ModelKind::Shccm => {
                impact(
                    &Bwshccm::new(&params, M, V_IN, Constant(-M * G)).unwrap(),
                    &Settings::default(),
                )
                .unwrap()
                .e
            }
            ModelKind::Mcm => {
                impact(
                    &Bwmcm::new(&params, M, V_IN, Constant(-M * G)).unwrap(),
                    &Settings::default(),
                )
                .unwrap()
                .e
            }
        };
        let run_bounce = |dt: f64| match kind {
            ModelKind::Shccm => bounce(Bwshccl::new(&params).unwrap(), dt),
            ModelKind::Mcm => bounce(Bwmcl::new(&params).unwrap(), dt),
        };
        let e = run_impact();
        for dt in [1e-4, 1e-5, 1e-6] {
            let result = run_bounce(dt);
            assert_eq!(
                result,
                bounce_c(params.law(), kind, dt),
                "C and Rust bounce alike"
            );
            let times = side_by_side(&mut [
                Box::new(|| {
                    std::hint::black_box(run_bounce(dt));
                }),
                Box::new(|| {
                    std::hint::black_box(bounce_c(params.law(), kind, dt));
                }),
                Box::new(|| {
                    std::hint::black_box(run_impact());
                }),
            ]);
            let (b, c, i) = (times[0], times[1], times[2]);
            let (steps, v_out) = result;
            println!(
                "{:<6} {dt:<8e} {steps:>14} {:>12.2} {:>14.2} {:>12.3} {:>12.1} {:>14.0} {:>14.1e}",
                kind.name(),
                b * 1e6 / steps as f64,
                c * 1e6 / steps as f64,
                b * 1e3,
                i * 1e6,
                b / i,
                (v_out / V_IN - e).abs() / e
            );
        }
    }
}

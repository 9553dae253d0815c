//! The contact element held by a host: a ball on a fixed floor, integrated by the host in
//! steps of `dt` with the element's impulse, against the library's own impact of the same law
//! (`impact`, the reference to 1e-10). Each host step is taken twice: once with the velocity
//! predicted from the last force, then again from the same element with the velocity the
//! first pass's impulse gives (a predictor-corrector), so that the host's error is `O(dt²)`.

use super::*;
use bw_models::sequence::Policy;
use bw_models::{AnyContactElement, Penetration};

pub(crate) const M: f64 = 0.145;

/// The host's bounce at `v_in` (m/s) under gravity `g`: rebound speed (m/s), contact duration
/// (s) and the work the contact absorbed (J).
pub(crate) fn host_bounce<L: ContactLaw<N> + Clone, const N: usize>(
    law: L,
    v_in: f64,
    g: f64,
    dt: f64,
) -> (f64, f64, f64) {
    let mut element = ContactElement::new(law, ElementSettings::default()).unwrap();
    let (mut v, mut t, mut force) = (-v_in, 0.0, 0.0);
    loop {
        let predicted = v + (force / M - g) * dt;
        let first = element.clone().advance(dt, v, predicted).unwrap();
        let corrected = v + first.impulse / M - g * dt;
        let step = element.advance(dt, v, corrected).unwrap();
        if let Some(tau) = step.separated_at {
            // The host's velocity at the separation, on the step's line.
            let u = v + (corrected - v) * tau / dt;
            return (u, t + tau, element.absorbed());
        }
        (v, t, force) = (corrected, t + dt, step.force);
        assert!(t < 1.0, "no separation within 1 s");
    }
}

/// The library's impact of Table 4's law of `kind` at `v_in` under gravity `g`: `(e, t_s)`.
fn library(kind: ModelKind, v_in: f64, g: f64) -> (f64, f64) {
    let params = cross(kind);
    let u = Constant(-M * g);
    let settings = Settings::default();
    let cor = match kind {
        ModelKind::Shccm => impact(&Bwshccm::new(&params, M, v_in, u).unwrap(), &settings)
            .unwrap()
            .cor(),
        ModelKind::Mcm => impact(&Bwmcm::new(&params, M, v_in, u).unwrap(), &settings)
            .unwrap()
            .cor(),
    };
    (cor.e, cor.t_s.unwrap())
}

/// The host's bounce with Table 4's law of `kind`.
fn host(kind: ModelKind, v_in: f64, g: f64, dt: f64) -> (f64, f64, f64) {
    let params = cross(kind);
    match kind {
        ModelKind::Shccm => host_bounce(Bwshccl::new(&params).unwrap(), v_in, g, dt),
        ModelKind::Mcm => host_bounce(Bwmcl::new(&params).unwrap(), v_in, g, dt),
    }
}

/// The host's rebound and duration converge to the library's at second order in the host's
/// step (its predictor-corrector's order: the element itself integrates to 1e-10): below
/// 1e-6 relative at dt = 1e-6 s for a contact of about 0.7 ms, and 50 times smaller than at
/// dt = 1e-5 s.
#[test]
fn a_host_stepping_the_element_rebounds_as_the_library_impact() {
    let v_in = 2.0;
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let (e, t_s) = library(kind, v_in, 9.81);
        let errors = [1e-5, 1e-6].map(|dt| {
            let (v_out, duration, _) = host(kind, v_in, 9.81, dt);
            ((v_out / v_in - e).abs() / e, (duration - t_s).abs() / t_s)
        });
        let [(e5, t5), (e6, t6)] = errors;
        assert!(e6 < 1e-6 && t6 < 1e-6, "{kind:?}: {errors:?}");
        assert!(e6 < e5 / 50.0 && t6 < t5 / 50.0, "{kind:?}: {errors:?}");
    }
}

/// A law given by its base parameters alone (`BaseMap::physical`) rebounds as the
/// nondimensional model at those base parameters (`BaseMap::at`, no input): a different law
/// (`A = 1`) and a different path to the same `e`, to the host's 1e-6 at dt = 1e-6 s.
#[test]
fn a_law_from_base_parameters_rebounds_as_the_nondimensional_model() {
    let v_in = 2.5;
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let map = BaseMap::new(kind, base_params(&cross(kind), M).unwrap()).unwrap();
        let (params, m) = map.physical().unwrap();
        assert!((m - M).abs() < 1e-14);
        let (nd, _) = map.at(v_in).unwrap();
        let settings = Settings::default();
        let e = match kind {
            ModelKind::Shccm => {
                impact(&Ndbwshccm::new(&nd, Zero).unwrap(), &settings)
                    .unwrap()
                    .e
            }
            ModelKind::Mcm => {
                impact(&Ndbwmcm::new(&nd, Zero).unwrap(), &settings)
                    .unwrap()
                    .e
            }
        };
        let (v_out, _, _) = match kind {
            ModelKind::Shccm => host_bounce(Bwshccl::new(&params).unwrap(), v_in, 0.0, 1e-6),
            ModelKind::Mcm => host_bounce(Bwmcl::new(&params).unwrap(), v_in, 0.0, 1e-6),
        };
        assert!(
            (v_out / v_in - e).abs() < 1e-6 * e,
            "{kind:?}: {} vs {e}",
            v_out / v_in
        );
    }
}

/// Without gravity the bodies' kinetic energy lost is the work the contact absorbed:
/// `W = m (v_in² - v_out²) / 2` with `v_out = e v_in` of the library's impact. The host's
/// velocity is linear within each of its steps, the bodies' is not: the two agree at second
/// order in the host's step (below 1e-5 relative at dt = 1e-6 s, 50 times closer than at
/// 1e-5 s).
#[test]
fn the_absorbed_work_is_the_kinetic_energy_lost() {
    let v_in = 3.0;
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let (e, _) = library(kind, v_in, 0.0);
        let lost = 0.5 * M * v_in * v_in * (1.0 - e * e);
        let [coarse, fine] =
            [1e-5, 1e-6].map(|dt| (host(kind, v_in, 0.0, dt).2 - lost).abs() / lost);
        assert!(
            fine < 1e-5 && fine < coarse / 50.0,
            "{kind:?}: {coarse:.1e}, {fine:.1e}"
        );
    }
}

/// Reset starts each contact from the law at rest; carry from the state of the last
/// separation. Bad steps are errors that leave the element as it was.
#[test]
fn policies_and_bad_steps() {
    let law = Bwmcl::new(&cross(ModelKind::Mcm)).unwrap();
    let bounce = |policy| {
        let mut settings = ElementSettings::default();
        settings.policy = policy;
        let mut el = ContactElement::new(law, settings).unwrap();
        // Compression then release, until the contact ends.
        let mut u = -2.0;
        while el.contacts() == 0 {
            el.advance(1e-5, u, u + 0.05).unwrap();
            u += 0.05;
        }
        el
    };
    let (mut reset, mut carry) = (bounce(Policy::Reset), bounce(Policy::Carry));
    assert_eq!(reset.state(), carry.state());
    assert!(reset.state().norm() > 0.0 && !reset.in_contact());
    let (r, c) = (
        reset.clone().advance(1e-5, -1.0, -1.0).unwrap(),
        carry.clone().advance(1e-5, -1.0, -1.0).unwrap(),
    );
    let mut fresh = ContactElement::new(law, ElementSettings::default()).unwrap();
    assert_eq!(r, fresh.advance(1e-5, -1.0, -1.0).unwrap());
    assert_ne!(r, c);
    // Bad steps: clear errors, nothing changed.
    let before = (*carry.state(), carry.absorbed(), carry.in_contact());
    for (dt, u0, u1, name) in [
        (0.0, -1.0, -1.0, "dt"),
        (-1e-5, -1.0, -1.0, "dt"),
        (1e-5, f64::NAN, -1.0, "u_start"),
        (1e-5, -1.0, f64::INFINITY, "u_end"),
        (1e-310, -1.0, 1.0, "dt"),
    ] {
        let err = carry.advance(dt, u0, u1).unwrap_err();
        assert!(
            matches!(err, ModelError::InvalidSetting { name: n, .. } if n == name),
            "{err}"
        );
    }
    let at = |depth, rate| Penetration { depth, rate };
    for (dt, a, b, name) in [
        (f64::NAN, at(0.0, 1.0), at(1e-5, 1.0), "dt"),
        (1e-5, at(f64::NAN, 1.0), at(1e-5, 1.0), "depth_start"),
        (1e-5, at(0.0, f64::INFINITY), at(1e-5, 1.0), "rate_start"),
        (1e-5, at(0.0, 1.0), at(f64::NEG_INFINITY, 1.0), "depth_end"),
        (1e-5, at(0.0, 1.0), at(1e-5, f64::NAN), "rate_end"),
        // So short that the cubic's coefficients overflow (it was the solver's "initial value
        // not finite", naming nothing).
        (4e-306, at(-1e-6, 1.0), at(-1e-6, 1.0), "dt"),
    ] {
        let err = carry.advance_penetration(dt, a, b).unwrap_err();
        assert!(
            matches!(err, ModelError::InvalidSetting { name: n, .. } if n == name),
            "{err}"
        );
    }
    assert_eq!(
        before,
        (*carry.state(), carry.absorbed(), carry.in_contact())
    );
    reset.reset();
    assert_eq!(*reset.state(), State::<3>::zeros());
    let mut loose = ElementSettings::default();
    loose.rtol = 0.5;
    assert!(ContactElement::new(law, loose).is_err());
}

/// A host step allocates nothing on the heap.
#[test]
fn an_element_step_does_not_allocate() {
    let mut el = ContactElement::new(
        Bwshccl::new(&cross(ModelKind::Shccm)).unwrap(),
        ElementSettings::default(),
    )
    .unwrap();
    el.advance(1e-5, -2.0, -2.0).unwrap();
    let (step, allocations) = super::alloc_counter::count(|| el.advance(1e-5, -2.0, -1.99));
    assert!(step.unwrap().force > 0.0);
    assert_eq!(allocations, 0);
    // Tracking the overlap: an onset inside the step.
    let mut el = ContactElement::new(
        Bwmcl::new(&cross(ModelKind::Mcm)).unwrap(),
        ElementSettings::default(),
    )
    .unwrap();
    let (a, b) = (
        Penetration {
            depth: -1e-5,
            rate: 2.0,
        },
        Penetration {
            depth: 1e-5,
            rate: 2.0,
        },
    );
    let (step, allocations) = super::alloc_counter::count(|| el.advance_penetration(1e-5, a, b));
    let step = step.unwrap();
    assert!(step.force > 0.0 && (step.began_at.unwrap() - 5e-6).abs() < 1e-15);
    assert_eq!(allocations, 0);
}

/// A law that cannot dissipate (no dashpot, a Bouc-Wen element that never yields: `c = 0`,
/// `β = γ = 0`) gives back all the work done on it: the dissipated energy stays at rounding
/// (below 1e-12 of the largest absorbed work) while the absorbed work rises and falls through
/// a compression and its release. The Maxwell law's dashpot dissipates at `F² / c >= 0`: its
/// dissipated energy never falls.
#[test]
fn a_conservative_law_dissipates_nothing_and_a_dashpot_never_gives_back() {
    let law = |kind, c| {
        let physical = Physical::hertz_damped(1e6, c);
        PhysicalParams::new(kind, physical).unwrap()
    };
    let mut elastic = ContactElement::new(
        Bwshccl::new(&law(ModelKind::Shccm, 0.0)).unwrap(),
        ElementSettings::default(),
    )
    .unwrap();
    let mut maxwell = ContactElement::new(
        Bwmcl::new(&law(ModelKind::Mcm, 50.0)).unwrap(),
        ElementSettings::default(),
    )
    .unwrap();
    // u from -1 to 1 m/s over 2 ms: a compression of 0.5 mm and its release.
    let (dt, mut most, mut last, mut worst) = (1e-5, 0.0f64, 0.0, 0.0f64);
    for i in 0..200 {
        let (u0, u1) = (-1.0 + 0.01 * i as f64, -1.0 + 0.01 * (i + 1) as f64);
        let step = elastic.advance(dt, u0, u1).unwrap();
        most = most.max(elastic.absorbed());
        worst = worst.max(elastic.dissipated().abs());
        maxwell.advance(dt, u0, u1).unwrap();
        assert!(
            maxwell.dissipated() >= last - 1e-12 * maxwell.absorbed().abs(),
            "step {i}"
        );
        last = maxwell.dissipated();
        if step.separated_at.is_some() {
            break;
        }
    }
    // The law's dissipation rate is 0 in closed form, and its stored energy is exact: what
    // is left is rounding.
    assert!(worst < 1e-12 * most, "dissipated {worst} J of {most} J");
    assert!(most > 1e-3, "absorbed at most {most} J");
    assert!(last > 0.0);
}

/// Random admissible laws of both models driven by random host steps (1e-7 to 1e-3 s, the
/// relative velocity or the penetration and its rate): every step either succeeds with finite
/// outputs or fails with an error that leaves the element as it was, and the energy dissipated
/// never falls. Both laws dissipate at a rate `>= 0` on their admissible sets (the dashpot's
/// `c |x|^p u²` or `F² / c`, and the Bouc-Wen element's `(1-α) k / A |z|^(p+n-1) (β |z| |w| +
/// γ z w) >= 0` for `|γ| <= β`, `w` its rate), so `dissipated` may fall only by the work's
/// quadrature error and rounding (1e-6 of the work absorbed and the energy held, or 1e-15 J, is
/// a wide margin for them: a contact that separates at once leaves a work of 1e-16 J).
mod properties {
    use super::*;
    use proptest::prelude::*;

    fn law(kind: ModelKind, v: [f64; 8]) -> PhysicalParams {
        let [k, c, n, p, alpha, beta, g, a] = v;
        let law = Physical {
            k: 10f64.powf(k),
            c: 10f64.powf(c),
            n,
            p,
            alpha,
            beta: 10f64.powf(beta),
            gamma: g * 10f64.powf(beta),
            a,
        };
        PhysicalParams::new(kind, law).unwrap()
    }

    fn element(kind: ModelKind, v: [f64; 8], policy: Policy) -> AnyContactElement {
        let mut settings = ElementSettings::default();
        settings.policy = policy;
        AnyContactElement::new(&law(kind, v), settings).unwrap()
    }

    fn snapshot(e: &AnyContactElement) -> (Vec<f64>, f64, f64, bool, u64) {
        (
            e.state().to_vec(),
            e.force(),
            e.absorbed(),
            e.in_contact(),
            e.contacts(),
        )
    }

    proptest! {
        #![proptest_config(crate::lyapunov::config(48))]
        #[test]
        fn steps_succeed_or_change_nothing_and_dissipation_never_falls(
            mcm in any::<bool>(),
            carry in any::<bool>(),
            v in (4.0..8.0, 1.0..5.0, 1.0..3.0, 1.0..2.5, 0.05..0.95, 0.0..4.0, -1.0..1.0, 0.5..2.0),
            steps in prop::collection::vec((-7.0..-3.0, -5.0..5.0, -5.0..5.0, any::<bool>()), 1..24),
        ) {
            let kind = if mcm { ModelKind::Mcm } else { ModelKind::Shccm };
            let policy = if carry { Policy::Carry } else { Policy::Reset };
            let v = [v.0, v.1, v.2, v.3, v.4, v.5, v.6, v.7];
            let mut el = element(kind, v, policy);
            let (mut depth, mut last) = (0.0, 0.0);
            for (log_dt, u0, u1, by_depth) in steps {
                let (log_dt, u0, u1): (f64, f64, f64) = (log_dt, u0, u1);
                let dt = 10f64.powf(log_dt);
                let before = snapshot(&el);
                let result = if by_depth {
                    let end = depth - 0.5 * dt * (u0 + u1);
                    let r = el.advance_penetration(
                        dt,
                        Penetration { depth, rate: -u0 },
                        Penetration { depth: end, rate: -u1 },
                    );
                    depth = end;
                    r
                } else {
                    el.advance(dt, u0, u1)
                };
                match result {
                    Ok(step) => {
                        prop_assert!(step.force.is_finite() && step.impulse.is_finite());
                        prop_assert!(step.work.is_finite() && el.state().iter().all(|x| x.is_finite()));
                    }
                    Err(_) => prop_assert_eq!(snapshot(&el), before),
                }
                let (dissipated, absorbed) = (el.dissipated(), el.absorbed());
                // The springs' energy, `absorbed - dissipated`, cancels in rounding too.
                let scale = absorbed.abs() + (absorbed - dissipated).abs();
                prop_assert!(
                    dissipated >= last - 1e-12 * scale - 1e-15,
                    "dissipated {} after {}, absorbed {}, in contact {}", dissipated, last, absorbed, el.in_contact()
                );
                last = dissipated;
            }
        }
    }
}

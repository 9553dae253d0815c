//! Tests of the checked CoR evaluation and its double-double retry.

use super::*;
use crate::input::Zero;
use crate::models::nondimensional_scales;
use crate::{ModelKind, Ndbwshccm, Nondim, NondimParams, State};
use bwc_ode::System;
use std::cell::Cell;

/// The Hunt-Crossley limit (`B = Γ = 0`) whose runs at the tolerances in `failing` fail
/// (a non-finite right-hand side): it reads each run's rtol where the crate hands it its
/// settings, and keeps the Runge-Kutta path.
struct Failing {
    inner: Ndbwshccm<Zero>,
    failing: Vec<f64>,
    rtol: Cell<f64>,
    /// Every run's rtol and method, in order.
    runs: std::cell::RefCell<Vec<(f64, &'static str)>>,
    /// `V'` is scaled by `1 + skew rtol`, so that runs at different tolerances differ.
    skew: f64,
    /// The double-double runs, in turn: `e` and accepted steps, or a failure (none: no
    /// double-double path).
    dd: Vec<Result<(f64, u64), DdFailure>>,
    /// Each double-double run's rtol and step limit, in order.
    dd_runs: std::cell::RefCell<Vec<(f64, u64)>>,
}

impl Failing {
    fn new(failing: &[f64]) -> Self {
        let nd = Nondim {
            b: 0.0,
            gamma: 0.0,
            kappa: 0.5,
            sigma: 0.2,
            n: 1.5,
            p: 1.5,
        };
        Self {
            inner: Ndbwshccm::new(&NondimParams::new(ModelKind::Shccm, nd).unwrap(), Zero).unwrap(),
            failing: failing.to_vec(),
            rtol: Cell::new(0.0),
            runs: Default::default(),
            skew: 0.0,
            dd: Vec::new(),
            dd_runs: Default::default(),
        }
    }

    /// Runs that differ by about `1e4 rtol` in `e`, and the double-double runs `dd`.
    fn scripted(dd: &[Result<(f64, u64), DdFailure>]) -> Self {
        Self {
            skew: 1e4,
            dd: dd.to_vec(),
            ..Self::new(&[])
        }
    }
}

impl System<3> for Failing {
    fn rhs(&self, t: f64, y: &State<3>) -> State<3> {
        let r = self.rtol.get();
        let fails = self.failing.iter().any(|f| (r / f - 1.0).abs() < 1e-9);
        let mut dy = self.inner.rhs(t, y) * if fails { f64::NAN } else { 1.0 };
        dy[2] *= 1.0 + self.skew * r;
        dy
    }
}

impl CollisionModel<3> for Failing {
    fn initial_state(&self) -> State<3> {
        self.inner.initial_state()
    }
    fn force(&self, y: &State<3>) -> f64 {
        self.inner.force(y)
    }
    fn displacement(&self, y: &State<3>) -> f64 {
        self.inner.displacement(y)
    }
    fn velocity(&self, y: &State<3>) -> f64 {
        self.inner.velocity(y)
    }
    fn input(&self, t: f64) -> f64 {
        self.inner.input(t)
    }
    fn input_constant_after(&self) -> Option<f64> {
        self.inner.input_constant_after()
    }
    nondimensional_scales!(3);
    fn kinks(&self, t: f64, y: &State<3>) -> [f64; 2] {
        self.inner.kinks(t, y)
    }
}

impl Runs<3> for Failing {
    fn run(&self, settings: &Settings) -> Result<Impact<3>, ModelError> {
        self.rtol.set(settings.rtol);
        self.runs
            .borrow_mut()
            .push((settings.rtol, settings.method.name));
        simulate(self, settings, Sampling::None, |_, _| {})
    }
    fn double_double(
        &self,
        rtol: f64,
        settings: &Settings,
    ) -> Option<Result<Impact<3>, DdFailure>> {
        let mut runs = self.dd_runs.borrow_mut();
        let run = *self.dd.get(runs.len())?;
        runs.push((rtol, settings.max_steps));
        Some(run.map(|(e, accepted)| {
            let stats = bwc_ode::Stats {
                accepted,
                ..Default::default()
            };
            Impact::unchecked((Some(1.0), e, State::<3>::zeros()), stats, rtol)
                .with(|c| c.double_double = true)
        }))
    }
}

/// [`crate::impact`] with `model`'s runs, which it records (and scripts, in double-double).
fn impact(model: &Failing, settings: &Settings) -> Result<Impact<3>, ModelError> {
    let Some(e_tol) = settings.e_tol else {
        return model.run(settings);
    };
    settings.validate()?;
    checked(model, settings, e_tol)
}

fn checked_at(rtol: f64) -> Settings {
    Settings {
        rtol,
        atol: rtol / 100.0,
        e_tol: Some(1e-10),
        ..Settings::default()
    }
}

#[test]
fn a_cor_no_other_run_could_check_says_so() {
    // The check at 100 rtol and the tighter run at rtol / 100 both fail.
    let out = impact(&Failing::new(&[1e-6, 1e-10]), &checked_at(1e-8)).unwrap();
    assert_eq!(
        (out.check, out.e_error, out.rtol),
        (Check::Unverified, None, 1e-8)
    );
    assert!(out.separated());
    let failed = out.tighter_failed.unwrap();
    assert!((failed.rtol / 1e-10 - 1.0).abs() < 1e-9 && !failed.out_of_steps);
    // At the floor there is no tighter run to try.
    let out = impact(&Failing::new(&[1e-12]), &checked_at(1e-14)).unwrap();
    assert_eq!(
        (out.check, out.e_error, out.tighter_failed),
        (Check::Unverified, None, None)
    );
}

#[test]
fn a_tighter_run_out_of_steps_says_that_more_steps_would_help() {
    // Single runs' steps: the run at rtol 1e-5 and Verner's 7(6) at 1e-7 after it.
    let steps = |method: &'static Tableau, rtol: f64| {
        let single = Settings {
            method,
            e_tol: None,
            ..checked_at(rtol)
        };
        let out = impact(&Failing::new(&[]), &single).unwrap();
        out.stats.accepted + out.stats.rejected
    };
    let (at_rtol, tighter) = (
        steps(&bwc_ode::DOP853, 1e-5),
        steps(LADDER.tighter_method, 1e-7),
    );
    assert!(tighter > at_rtol, "{tighter} {at_rtol}");
    let settings = Settings {
        e_tol: Some(1e-30),
        max_steps: at_rtol,
        ..checked_at(1e-5)
    };
    let out = impact(&Failing::new(&[]), &settings).unwrap();
    let failed = out.tighter_failed.unwrap();
    assert!(
        (failed.rtol / 1e-7 - 1.0).abs() < 1e-9 && failed.out_of_steps,
        "{failed:?}"
    );
    assert_eq!((out.check, out.rtol), (Check::Unmet, 1e-5));
    // Met, or down to the floor: nothing failed.
    let out = impact(&Failing::new(&[]), &checked_at(1e-8)).unwrap();
    assert_eq!((out.check, out.tighter_failed), (Check::Met, None));
}

#[test]
fn the_check_and_the_tighter_runs_take_other_methods_down_to_the_floor() {
    // A target no run meets: the check at 100 rtol by Verner's 9(8), then every tighter run
    // by Verner's 7(6), down to the floor from an rtol that no power of 100 takes there.
    let model = Failing::new(&[]);
    let settings = Settings {
        e_tol: Some(1e-30),
        ..checked_at(1e-5)
    };
    let out = impact(&model, &settings).unwrap();
    let want = [
        (1e-3, "Vern9"),
        (1e-5, "DOP853"),
        (1e-7, "Vern7"),
        (1e-9, "Vern7"),
        (1e-11, "Vern7"),
        (1e-13, "Vern7"),
        (1e-14, "Vern7"),
    ];
    let runs = model.runs.take();
    assert_eq!(runs.len(), want.len(), "{runs:?}");
    for ((rtol, method), (want_rtol, want_method)) in runs.iter().zip(want) {
        assert!(
            (rtol / want_rtol - 1.0).abs() < 1e-9 && *method == want_method,
            "{runs:?}"
        );
    }
    assert_eq!((out.rtol, out.check), (LADDER.floor_rtol, Check::Unmet));
}

#[test]
fn a_check_says_whether_it_met_e_tol() {
    // Only the check fails: the tighter run checks the run at rtol instead.
    let out = impact(&Failing::new(&[1e-6]), &checked_at(1e-8)).unwrap();
    assert_eq!(out.check, Check::Met);
    assert!(out.rtol < 1e-8 && out.e_error.unwrap() <= 1e-11, "{out:?}");
    // A run that differs from its check by more than e_tol, with no tighter run possible.
    let out = impact(&Failing::new(&[1e-6]), &checked_at(1e-4)).unwrap();
    let (estimate, check) = (out.e_error.unwrap(), out.check);
    assert!(
        estimate > 1e-10 && check == Check::Unmet,
        "{estimate:e} {check:?}"
    );
    let single = impact(
        &Failing::new(&[]),
        &Settings {
            e_tol: None,
            ..checked_at(1e-8)
        },
    );
    assert_eq!(single.unwrap().check, Check::Off);
}

/// A stress case's NDBWMCM map and its input `b sin(ω t)` (`(b, ω)`, the sweep's input
/// amplitude divided by the base map's `U_factor` at `v0`, as the stress sweep scales it).
fn mcm_under_sine(
    base: crate::BaseParams,
    v0: f64,
    (b, omega): (f64, f64),
) -> (crate::BaseMap, crate::input::Sine) {
    let map = crate::BaseMap::new(ModelKind::Mcm, base).unwrap();
    let factor = map.at(v0).unwrap().1.factor;
    let u = crate::input::Sine {
        a: 0.0,
        b: b / factor,
        omega,
    };
    (map, u)
}

/// Case 7221 of the stress sweep's seed 1 (STABILITY.md, "Double-double"): an NDBWMCM
/// contact 50 time units long under a sinusoid, whose `e` double precision gets only to
/// about 1e-9. Its reference, 0.017492850063003707, is the double-double path at rtol 1e-20
/// and 1e-24 (agreeing to 1e-17); that path meets the closed forms to 1e-25
/// (`double_double/tests.rs`).
#[test]
fn double_double_settles_what_double_precision_cannot() {
    use crate::{impact_at, BaseParams};
    let base = BaseParams {
        b_b: 0.12910110765342317,
        gamma_b: -0.06155493494432533,
        kappa: 0.9999002987721985,
        sigma_b: 395.136288272385,
        n: 8.183188614474556,
        p: 10.0,
        u_b: 1.0,
        t_b: 1.0,
    };
    let v0 = 0.0030045141757612365;
    let (map, u) = mcm_under_sine(base, v0, (2.737817997146834, 2.911951122767874));
    let reference = 0.017492850063003707;
    let double = Settings {
        double_double: false,
        ..Settings::default()
    };
    let out = impact_at(&map, u, v0, &double).unwrap();
    assert_eq!((out.check, out.double_double), (Check::Unmet, false));
    assert!((out.e - reference).abs() > 1e-10, "{out:?}");
    let precise = Settings {
        double_double: true,
        ..Settings::default()
    };
    let out = impact_at(&map, u, v0, &precise).unwrap();
    assert_eq!((out.check, out.double_double), (Check::Met, true));
    assert_eq!(out.rtol, LADDER.double_double_rtols[1]);
    assert!((out.e - reference).abs() < 1e-12, "{out:?}");
    assert!(out.e_error.unwrap() < 1e-10);
    // To 1e-14, the runs at rtol 1e-16 and 1e-18 differ by 6.3e-14: the third settles it.
    let tight = Settings {
        e_tol: Some(1e-14),
        ..precise
    };
    let out = impact_at(&map, u, v0, &tight).unwrap();
    assert_eq!((out.check, out.double_double), (Check::Met, true));
    assert_eq!(out.rtol, LADDER.double_double_rtols[2]);
    assert!((out.e - reference).abs() < 1e-14, "{out:?}");
}

/// Case 15913 of the stress sweep's seed 9 (STABILITY.md, "Double-double"): an NDBWMCM contact
/// 37 time units long under a sinusoid, where rounding scatters the Runge-Kutta runs' `e` by
/// about 6e-10 at rtol 1e-12 to 3e-15. DOP853 at rtol 1e-12 and Verner's 7(6) at the floor
/// agree to 5e-11, under `e_tol`, and are both 6e-10 off. The reference, 0.0354873325102081291,
/// is the double-double path at rtol 1e-21 and 1e-23 (agreeing to all 18 digits; 1e-18 is
/// 1.5e-15 off).
#[test]
fn a_check_met_only_at_the_floor_is_retried_in_double_double() {
    use crate::{impact_at, BaseParams};
    let base = BaseParams {
        b_b: 0.017400971288875945,
        gamma_b: 0.017400971288875945,
        kappa: 0.06207319757187196,
        sigma_b: 97.76544027245326,
        n: 2.561340513089293,
        p: 10.0,
        u_b: 1.0,
        t_b: 1.0,
    };
    let v0 = 0.01179940078399802;
    let (map, u) = mcm_under_sine(base, v0, (5.108090199670192, 6.707517508526101));
    let reference = 0.035_487_332_510_208_13;
    let double = Settings {
        double_double: false,
        ..Settings::default()
    };
    let out = impact_at(&map, u, v0, &double).unwrap();
    let estimate = out.e_error.unwrap();
    assert_eq!(
        (out.check, out.rtol),
        (Check::Met, LADDER.floor_rtol),
        "{out:?}"
    );
    assert!(estimate > 1e-11 && estimate <= 1e-10, "{out:?}");
    assert!((out.e - reference).abs() > 5e-10, "{out:?}");
    let out = impact_at(&map, u, v0, &Settings::default()).unwrap();
    assert_eq!(
        (out.check, out.double_double),
        (Check::Met, true),
        "{out:?}"
    );
    assert!((out.e - reference).abs() < 1e-14, "{out:?}");
    assert!(out.e_error.unwrap() < 1e-10, "{out:?}");
}

/// Case 5523 of the stress sweep's seed 3 (STABILITY.md, "Double-double"): an NDBWMCM impact
/// without input at 507 m/s whose double-precision runs switch to RODAS4 and agree to only
/// 1.2e-10. The explicit double-double path crosses spurious kinks there (30 and 34 at rtol
/// 1e-16 and 1e-18, against 3 events of every double-precision run) and misses `e` by 5e-3
/// after 45 s, so it is not tried. The reference, 0.127578645362, is Verner's 9(8),
/// Verner's 7(6) and DOP853 at rtol 3e-15 (agreeing to 1e-14; 1e-15 moves it by 1e-12).
#[test]
fn a_stiff_run_is_not_retried_in_double_double() {
    use crate::input::Constant;
    use crate::{impact_at, BaseMap, BaseParams};
    let base = BaseParams {
        b_b: 35.85524463149488,
        gamma_b: -35.85524463149488,
        kappa: 0.2754451940192927,
        sigma_b: 0.012827185718774515,
        n: 10.0,
        p: 5.367702693104487,
        u_b: 1.0,
        t_b: 1.0,
    };
    let map = BaseMap::new(ModelKind::Mcm, base).unwrap();
    let v0 = 506.91324093318553;
    let out = impact_at(&map, Constant(0.0), v0, &Settings::default()).unwrap();
    assert_eq!((out.check, out.double_double), (Check::Unmet, false));
    assert!(matches!(
        out.double_double_declined,
        Some(DdDeclined::Stiff { from }) if Some(from) == out.stiff_from
    ));
    assert!((out.e - 0.127578645362).abs() < 1e-10, "{out:?}");
    // Nothing was spent on it: the work is the double-precision runs'.
    let double = Settings {
        double_double: false,
        ..Settings::default()
    };
    let without = impact_at(&map, Constant(0.0), v0, &double).unwrap();
    assert_eq!((without.e, without.stats), (out.e, out.stats));
}

#[test]
fn double_double_runs_go_on_until_two_agree() {
    let settings = Settings {
        e_tol: Some(1e-12),
        ..checked_at(1e-12)
    };
    let (e, steps) = (0.5, 100);
    // The first pair differs by 1e-9, the second by 1e-13: the third run is reported, with
    // every run's work.
    let model = Failing::scripted(&[
        Ok((e, steps)),
        Ok((e + 1e-9, steps)),
        Ok((e + 1e-9 + 1e-13, steps)),
    ]);
    let out = impact(&model, &settings).unwrap();
    assert_eq!((out.check, out.double_double), (Check::Met, true));
    assert_eq!(out.rtol, LADDER.double_double_rtols[2]);
    assert!((out.e_error.unwrap() - 1e-13).abs() < 1e-16, "{out:?}");
    assert_eq!(out.double_double_declined, None);
    let f64_steps = model.runs.borrow().len() as u64;
    assert!(out.stats.accepted >= 3 * steps + f64_steps, "{out:?}");
    // Each run after the first is held to the step limit of its predecessor's steps.
    let limit = LADDER.dd_step_limit(steps);
    let dd_runs = model.dd_runs.take();
    let limits: Vec<u64> = dd_runs.iter().map(|r| r.1).collect();
    assert_eq!(limits, [settings.max_steps, limit, limit]);
    // Three runs that never agree: the double-precision result, flagged, says why.
    let model = Failing::scripted(&[Ok((e, steps)), Ok((e + 1e-9, steps)), Ok((e, steps))]);
    let out = impact(&model, &settings).unwrap();
    assert_eq!((out.check, out.double_double), (Check::Unmet, false));
    assert!(
        out.rtol >= LADDER.floor_rtol && (out.e - e).abs() > 1e-6,
        "{out:?}"
    );
    match out.double_double_declined {
        Some(DdDeclined::Disagreed { e_error }) => assert!((e_error - 1e-9).abs() < 1e-15),
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_double_double_run_whose_steps_grow_past_the_limit_is_stopped() {
    let settings = Settings {
        e_tol: Some(1e-12),
        ..checked_at(1e-12)
    };
    // The second run hits its limit (growth, not the user's max_steps); a first run that
    // fails says so with its own reason.
    let model = Failing::scripted(&[Ok((0.5, 40)), Err(DdFailure::TooManySteps)]);
    let out = impact(&model, &settings).unwrap();
    assert_eq!(out.check, Check::Unmet);
    assert_eq!(
        out.double_double_declined,
        Some(DdDeclined::StepsGrew {
            rtol: LADDER.double_double_rtols[1],
            steps_before: 40
        })
    );
    assert_eq!(model.dd_runs.take()[1].1, LADDER.dd_step_limit(40));
    let model = Failing::scripted(&[Err(DdFailure::TooManySteps)]);
    let out = impact(&model, &settings).unwrap();
    let failed = DdDeclined::Failed {
        rtol: LADDER.double_double_rtols[0],
        failure: DdFailure::TooManySteps,
    };
    assert_eq!(out.double_double_declined, Some(failed));
    assert!(failed.to_string().contains("max_steps"), "{failed}");
    // No path: said so; nothing is due where the check is met or double-double is off.
    let out = impact(&Failing::scripted(&[]), &settings).unwrap();
    assert_eq!(out.double_double_declined, Some(DdDeclined::NoPath));
    let off = Settings {
        double_double: false,
        ..settings
    };
    let out = impact(&Failing::scripted(&[]), &off).unwrap();
    assert_eq!(
        (out.check, out.double_double_declined),
        (Check::Unmet, None)
    );
    let out = impact(&Failing::new(&[]), &checked_at(1e-8)).unwrap();
    assert_eq!((out.check, out.double_double_declined), (Check::Met, None));
}

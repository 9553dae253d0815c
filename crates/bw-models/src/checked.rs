//! Global error control of a CoR evaluation ([`Settings::e_tol`]): the run at `rtol` checked
//! against the same impact at `TIGHTEN rtol` by another method ([`CHECK_METHOD`]), and tighter
//! runs ([`TIGHTER_METHOD`]) down to [`FLOOR_RTOL`] until two agree to `ACCEPT e_tol`; the
//! result says what the check found ([`Check`]).

use crate::impact::{simulate, Impact, Sampling, Settings};
use crate::models::CollisionModel;
use crate::precise::DdFailure;
use crate::series::Private;
use crate::ModelError;
use bwc_ode::{Extrapolation, Tableau, VERN7, VERN9};

/// A CoR evaluation under [`Settings::e_tol`] is accepted when its `e` differs from the check's
/// by at most this fraction of `e_tol`: where the check's error is the difference, the
/// reported run's is about a hundredth of it, and the margin covers runs whose error does not
/// fall in proportion to rtol (STABILITY.md).
const ACCEPT: f64 = 0.1;

/// The factor between the tolerances of successive runs under [`Settings::e_tol`]: the check
/// runs at `TIGHTEN rtol`, a tighter run at `rtol / TIGHTEN`.
pub const TIGHTEN: f64 = 100.0;

/// The tightest rtol [`Settings::e_tol`] goes down to: below it DOP853's and the series'
/// errors are those of rounding.
pub const FLOOR_RTOL: f64 = 1e-14;

/// The Runge-Kutta method of the run that checks a CoR under [`Settings::e_tol`] (at
/// `TIGHTEN rtol`): Verner's 9(8), another method than the default DOP853, so that an error a
/// method makes at every tolerance (DOP853's in steps limited by stability, say) shows as a
/// difference instead of passing the check (STABILITY.md, "Session 21").
pub const CHECK_METHOD: &Tableau = &VERN9;

/// The Runge-Kutta method of the tighter runs under [`Settings::e_tol`] (at `rtol / TIGHTEN`
/// and below): Verner's 7(6), which of the built-in methods comes closest to the truth at
/// rtol 1e-14 on the stress sweep's hardest runs; Verner's 9(8) there spends its steps on
/// rounding noise in its error estimate (STABILITY.md, "Session 21").
pub const TIGHTER_METHOD: &Tableau = &VERN7;

/// What the check of an impact under [`Settings::e_tol`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Check {
    /// Not checked: one run at `rtol` (no `e_tol`, or a sampled run), without an estimate.
    Off,
    /// The estimate `e_error` is at most `e_tol`.
    Met,
    /// The estimate `e_error` stayed above `e_tol`: the tightest run (rtol 1e-14) still
    /// differed from the one before it, or a tighter run failed ([`Impact::tighter_failed`]).
    Unmet,
    /// No run at another tolerance finished (the check at `100 rtol` failed, and so did the
    /// run at `rtol / 100` or it was below 1e-14): `e` is one unchecked run at `rtol`.
    Unverified,
}

/// A run under [`Settings::e_tol`] tighter than the reported one that failed, so that the
/// check stopped there ([`Impact::tighter_failed`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FailedRun {
    /// Its relative tolerance.
    pub rtol: f64,
    /// Whether it needed more than [`Settings::max_steps`] steps (a larger `max_steps` lets it
    /// finish); `false` for another failure (a step size too small, a non-finite state).
    pub out_of_steps: bool,
}

impl Check {
    /// The name in outputs: `"off"`, `"met"`, `"unmet"` or `"unverified"`.
    pub fn name(self) -> &'static str {
        match self {
            Check::Off => "off",
            Check::Met => "met",
            Check::Unmet => "unmet",
            Check::Unverified => "unverified",
        }
    }
}

/// Coefficient of restitution, separation time and statistics of one impact, under
/// [`Settings::e_tol`] checked against runs at other tolerances; stores nothing and allocates
/// nothing.
///
/// # Errors
/// As [`simulate`]. Under [`Settings::e_tol`], a failure of the first run at `rtol` (the check
/// at `100 rtol` counts as a differing run); a failure of a tighter run returns the run before
/// it, with its estimate.
pub fn impact<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
) -> Result<Impact<N>, ModelError> {
    let Some(e_tol) = settings.e_tol else {
        return simulate(model, settings, Sampling::None, |_, _| {});
    };
    settings.validate()?;
    let run = |method: &'static Tableau, rtol: f64| {
        let at = Settings {
            method,
            rtol,
            atol: settings.atol * (rtol / settings.rtol),
            e_tol: None,
            ..*settings
        };
        simulate(model, &at, Sampling::None, |_, _| {})
    };
    let check = run(CHECK_METHOD, TIGHTEN * settings.rtol).ok();
    let mut out = run(settings.method, settings.rtol)?;
    let mut work = out.stats;
    if let Some(c) = &check {
        work += c.stats;
        estimate(&mut out, c);
    }
    let mut rtol = settings.rtol;
    let mut failed = None;
    while !out.e_error.is_some_and(|d| d <= ACCEPT * e_tol) && rtol > FLOOR_RTOL {
        rtol = tighter(rtol);
        let mut next = match run(TIGHTER_METHOD, rtol) {
            Ok(next) => next,
            Err(err) => {
                failed = Some(FailedRun {
                    rtol,
                    out_of_steps: out_of_steps(&err),
                });
                break;
            }
        };
        work += next.stats;
        estimate(&mut next, &out);
        out = next;
    }
    out.stats = work;
    out.tighter_failed = failed;
    out.check = verdict(out.e_error, e_tol);
    if out.check == Check::Unmet && settings.double_double {
        if let Some(precise) = double_double(model, settings, e_tol, work) {
            return Ok(precise);
        }
    }
    Ok(out)
}

/// What an estimate says against `e_tol`.
fn verdict(e_error: Option<f64>, e_tol: f64) -> Check {
    match e_error {
        None => Check::Unverified,
        Some(d) if d <= e_tol => Check::Met,
        Some(_) => Check::Unmet,
    }
}

/// The tolerances of the double-double runs ([`Settings::double_double`]): the second is
/// reported, checked against the first. On the stress sweep's runs that double precision
/// cannot settle, rtol 1e-16 gets `e` to about 1e-13 and 1e-18 to about 1e-15; at 1e-14 the
/// steps can pass over a pair of kinks and miss `e` by 7e-9 (STABILITY.md, "Session 23").
pub const DOUBLE_DOUBLE_RTOLS: [f64; 2] = [1e-16, 1e-18];

/// One run of the double-double path ([`Settings::double_double`]) at `rtol` (`atol` scaled
/// as `settings.atol / settings.rtol`), with `settings.max_steps` and `settings.t_max`; `None`
/// where `model` has no such path (the nondimensional and SI models, [`crate::Ndbwshccm`],
/// [`crate::Ndbwmcm`], [`crate::Bwshccm`] and [`crate::Bwmcm`], have it under an input with
/// [`crate::input::Input::at_dd`]). For references: its statistics are its own.
///
/// # Errors
/// [`DdFailure`] where the run does not reach the separation.
pub fn impact_double_double<M: CollisionModel<N>, const N: usize>(
    model: &M,
    rtol: f64,
    settings: &Settings,
) -> Option<Result<Impact<N>, DdFailure>> {
    let ext = Extrapolation::new(rtol, settings.atol * (rtol / settings.rtol));
    model.double_double_impact(Private(()), ext, settings)
}

/// The impact in double-double arithmetic, where the model has that path and both runs reach
/// the separation and agree to `e_tol`; `work` is the double-precision runs' cost, added to
/// the statistics.
fn double_double<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
    e_tol: f64,
    work: bwc_ode::Stats,
) -> Option<Impact<N>> {
    let run = |rtol: f64| impact_double_double(model, rtol, settings);
    let [loose, fine] = DOUBLE_DOUBLE_RTOLS;
    let loose = run(loose)?.ok()?;
    let mut out = run(fine)?.ok()?;
    estimate(&mut out, &loose);
    // The reported `e` is rounded to double precision: its error is at least that rounding,
    // even where both runs round to the same double.
    out.e_error = out.e_error.map(|d| d.max(0.5 * f64::EPSILON * out.e.abs()));
    out.check = verdict(out.e_error, e_tol);
    out.stats += work;
    out.stats += loose.stats;
    (out.check == Check::Met).then_some(out)
}

/// Whether `err` is a run that needed more than [`Settings::max_steps`] steps.
fn out_of_steps(err: &ModelError) -> bool {
    matches!(
        err,
        ModelError::Solver(bwc_events::Error::Solver(
            bwc_ode::Error::TooManySteps { .. }
        ))
    )
}

/// The tolerance of the run after one at `rtol` under [`Settings::e_tol`]: `rtol / TIGHTEN`,
/// or [`FLOOR_RTOL`] where that would pass it (so a chain of runs from any `rtol` ends on the
/// floor, not short of it).
pub fn tighter(rtol: f64) -> f64 {
    (rtol / TIGHTEN).max(FLOOR_RTOL)
}

/// Sets `out`'s error estimates from the run `before` it, at a looser tolerance. Runs that
/// differ in outcome differ by `e` itself.
fn estimate<const N: usize>(out: &mut Impact<N>, before: &Impact<N>) {
    out.e_error = Some(if out.separated() == before.separated() {
        (out.e - before.e).abs()
    } else {
        out.e.max(before.e)
    });
    out.t_s_error = before.t_s.zip(out.t_s).map(|(a, c)| (a - c).abs());
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::Zero;
    use crate::series::SeriesRun;
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
                inner: Ndbwshccm::new(&NondimParams::new(ModelKind::Shccm, nd).unwrap(), Zero)
                    .unwrap(),
                failing: failing.to_vec(),
                rtol: Cell::new(0.0),
                runs: Default::default(),
            }
        }
    }

    impl System<3> for Failing {
        fn rhs(&self, t: f64, y: &State<3>) -> State<3> {
            let r = self.rtol.get();
            let fails = self.failing.iter().any(|f| (r / f - 1.0).abs() < 1e-9);
            self.inner.rhs(t, y) * if fails { f64::NAN } else { 1.0 }
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
        fn series_impact(
            &self,
            _: crate::series::Private,
            settings: &Settings,
        ) -> Option<SeriesRun<3>> {
            self.rtol.set(settings.rtol);
            self.runs
                .borrow_mut()
                .push((settings.rtol, settings.method.name));
            None
        }
        fn impact_speed(&self) -> f64 {
            1.0
        }
        fn state_scale(&self) -> State<3> {
            State::<3>::repeat(1.0)
        }
        fn time_scale(&self) -> f64 {
            1.0
        }
        fn kinks(&self, t: f64, y: &State<3>) -> [f64; 2] {
            self.inner.kinks(t, y)
        }
    }

    fn checked(rtol: f64) -> Settings {
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
        let out = impact(&Failing::new(&[1e-6, 1e-10]), &checked(1e-8)).unwrap();
        assert_eq!(
            (out.check, out.e_error, out.rtol),
            (Check::Unverified, None, 1e-8)
        );
        assert!(out.separated());
        let failed = out.tighter_failed.unwrap();
        assert!((failed.rtol / 1e-10 - 1.0).abs() < 1e-9 && !failed.out_of_steps);
        // At the floor there is no tighter run to try.
        let out = impact(&Failing::new(&[1e-12]), &checked(1e-14)).unwrap();
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
                ..checked(rtol)
            };
            let out = impact(&Failing::new(&[]), &single).unwrap();
            out.stats.accepted + out.stats.rejected
        };
        let (at_rtol, tighter) = (steps(&bwc_ode::DOP853, 1e-5), steps(TIGHTER_METHOD, 1e-7));
        assert!(tighter > at_rtol, "{tighter} {at_rtol}");
        let settings = Settings {
            e_tol: Some(1e-30),
            max_steps: at_rtol,
            ..checked(1e-5)
        };
        let out = impact(&Failing::new(&[]), &settings).unwrap();
        let failed = out.tighter_failed.unwrap();
        assert!(
            (failed.rtol / 1e-7 - 1.0).abs() < 1e-9 && failed.out_of_steps,
            "{failed:?}"
        );
        assert_eq!((out.check, out.rtol), (Check::Unmet, 1e-5));
        // Met, or down to the floor: nothing failed.
        let out = impact(&Failing::new(&[]), &checked(1e-8)).unwrap();
        assert_eq!((out.check, out.tighter_failed), (Check::Met, None));
    }

    #[test]
    fn the_check_and_the_tighter_runs_take_other_methods_down_to_the_floor() {
        // A target no run meets: the check at 100 rtol by Verner's 9(8), then every tighter run
        // by Verner's 7(6), down to the floor from an rtol that no power of 100 takes there.
        let model = Failing::new(&[]);
        let settings = Settings {
            e_tol: Some(1e-30),
            ..checked(1e-5)
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
        assert_eq!((out.rtol, out.check), (FLOOR_RTOL, Check::Unmet));
    }

    #[test]
    fn a_check_says_whether_it_met_e_tol() {
        // Only the check fails: the tighter run checks the run at rtol instead.
        let out = impact(&Failing::new(&[1e-6]), &checked(1e-8)).unwrap();
        assert_eq!(out.check, Check::Met);
        assert!(out.rtol < 1e-8 && out.e_error.unwrap() <= 1e-11, "{out:?}");
        // A run that differs from its check by more than e_tol, with no tighter run possible.
        let out = impact(&Failing::new(&[1e-6]), &checked(1e-4)).unwrap();
        let (estimate, check) = (out.e_error.unwrap(), out.check);
        assert!(
            estimate > 1e-10 && check == Check::Unmet,
            "{estimate:e} {check:?}"
        );
        let single = impact(
            &Failing::new(&[]),
            &Settings {
                e_tol: None,
                ..checked(1e-8)
            },
        );
        assert_eq!(single.unwrap().check, Check::Off);
    }

    /// Case 7221 of the stress sweep's seed 1 (STABILITY.md, "Session 23"): an NDBWMCM
    /// contact 50 time units long under a sinusoid, whose `e` double precision gets only to
    /// about 1e-9. Its reference, 0.017492850063003707, is the double-double path at rtol 1e-20
    /// and 1e-24 (agreeing to 1e-17); that path meets the closed forms to 1e-25
    /// (`precise.rs`).
    #[test]
    fn double_double_settles_what_double_precision_cannot() {
        use crate::input::Sine;
        use crate::{impact_at, BaseMap, BaseParams};
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
        let map = BaseMap::new(ModelKind::Mcm, base).unwrap();
        let factor = map.at(v0).unwrap().1.factor;
        let u = Sine {
            a: 0.0,
            b: 2.737817997146834 / factor,
            omega: 2.911951122767874,
        };
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
        assert_eq!(out.rtol, DOUBLE_DOUBLE_RTOLS[1]);
        assert!((out.e - reference).abs() < 1e-12, "{out:?}");
        assert!(out.e_error.unwrap() < 1e-10);
    }
}

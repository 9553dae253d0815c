//! How an impact is computed ([`Settings`]): the integrator's tolerances and limits, the paths a
//! CoR evaluation may take, and the checking ladder of its error control ([`Ladder`]).

use crate::error::ModelError;
use bwc_ode::{Tableau, DOP853, VERN7, VERN9};

/// How an impact is computed, in two groups.
///
/// **The integrator** (every run): [`method`](Settings::method), [`rtol`](Settings::rtol),
/// [`atol`](Settings::atol), [`max_step`](Settings::max_step), [`t_max`](Settings::t_max),
/// [`max_steps`](Settings::max_steps), [`stop_at_kinks`](Settings::stop_at_kinks) and
/// [`stiffness`](Settings::stiffness). Tolerances, steps and the horizon are in the model's
/// natural units: nondimensional for the ND models; for SI models they are multiplied by the
/// scales of Table 1 (`atol` per component by `X_c`, `Z_c`, `v0`; times by `T_c`), so the same
/// settings give the same accuracy both ways.
///
/// **The paths and the check of a CoR evaluation** ([`impact`](crate::impact), no samples):
/// [`series`](Settings::series), [`phase`](Settings::phase) and
/// [`double_double`](Settings::double_double) switch the crate's faster or more precise paths
/// on and off, and [`e_tol`](Settings::e_tol) is the target of the checking ladder
/// ([`Ladder`]). Trajectories ([`simulate`](crate::simulate) with samples) are one Runge-Kutta
/// run whatever these say.
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// Runge-Kutta method.
    pub method: &'static Tableau,
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance (natural units).
    pub atol: f64,
    /// Largest step (natural time units; `+inf` for none).
    pub max_step: f64,
    /// Horizon: no separation by then is reported as such, with `e = 0` (natural time units).
    pub t_max: f64,
    /// Most steps.
    pub max_steps: u64,
    /// Stop exactly at the non-smooth points of the right-hand side and restart there.
    pub stop_at_kinks: bool,
    /// What to do about stiffness (a nearly rigid dashpot in the MCM, large `B` and `n`).
    pub stiffness: Stiffness,
    /// Integrate CoR evaluations under a constant input by Taylor series between the
    /// non-smooth points (the SI models [`crate::Bwshccm`] and [`crate::Bwmcm`] through their
    /// nondimensional form, Table 1), with `method` for the steps next to the points where a
    /// base vanishes and onto the separation; runs that path declines (stiff, time-varying
    /// input, ill-conditioned roots) take the Runge-Kutta path. Not with
    /// [`Stiffness::Rosenbrock`]. On by default: faster at equal error and more accurate at the
    /// same rtol than the Runge-Kutta path on the paper's cases (BENCHMARKS.md). A CoR from a
    /// trajectory run (Runge-Kutta) can differ from a CoR evaluation by about the Runge-Kutta
    /// path's error (1e-11 at rtol 1e-11).
    pub series: bool,
    /// Global error control of CoR evaluations, the target for the error in `e`.
    /// `Some(e_tol)`: each impact is computed at `rtol` and checked against the impact at
    /// `100 rtol` (`atol` scaled alike) by another method ([`Ladder::check_method`], Verner's
    /// 9(8)); where their `e` differ by more than `0.1 e_tol` (or only one separated), it is
    /// computed again at `rtol / 100` by [`Ladder::tighter_method`] (Verner's 7(6)) and checked
    /// against the run at `rtol`, and so on down to rtol 1e-14 ([`Ladder::tighter`]). The
    /// result is the tightest run, with the last difference as its error estimate
    /// ([`Impact::e_error`](crate::Impact::e_error); at most `0.1 e_tol` except where rtol
    /// 1e-14 did not get there). Validated on the stress sweep (STABILITY.md, "Global error
    /// control"). `None`: one run at `rtol`.
    pub e_tol: Option<f64>,
    /// Under [`Settings::e_tol`], where the check stays unmet after the tightest
    /// double-precision run, or is met only by an estimate above `e_tol / 10` there (where
    /// rounding decides the runs' last digits, their difference does not bound their error):
    /// compute the impact again in double-double arithmetic ([`bwc_ode::Extrapolation`] at
    /// [`Ladder::double_double_rtols`], 1e-16, 1e-18 and 1e-20 in turn, each checked against the
    /// one before it), and report the first that agrees to `e_tol`
    /// ([`Impact::double_double`](crate::Impact::double_double)). For the few long, forced
    /// contacts whose `e` double precision cannot pin down below about 1e-9; seconds to a
    /// minute per impact, and nothing where the check is met. Not tried where the tightest
    /// double-precision run went stiff (the path is explicit), and stopped where a run's steps
    /// grow far past its predecessor's; where it reports nothing,
    /// [`Impact::double_double_declined`](crate::Impact::double_double_declined) says why.
    /// Every model of the crate but the earlier BWMCM form has this path, under inputs with a
    /// double-double form ([`crate::input::Input::at_dd`]: all of the crate's but closures). On
    /// by default: on five seeds of the stress sweep (150,000 cases) it settles every unmet run
    /// that did not go stiff, and leaves no run off by more than 1e-10 (STABILITY.md,
    /// "Double-double").
    pub double_double: bool,
    /// CoR evaluations of unforced impacts of the nondimensional models (and so of
    /// [`crate::impact_at`]) by the phase path ([`crate::phase`]): `e` and `t_s` as quadratures
    /// in phase space, checked to `e_tol` (without `e_tol`, one node count chosen from `rtol`,
    /// unchecked). Where it declines or its check is not met, the impact takes the usual path.
    /// Off by default: 5.7-9x faster than plain DOP853 at equal error on the paper's fits
    /// (BENCHMARKS.md, "The phase path"), but younger than the series path, and on the stress
    /// sweep one checked result in about 15,000 was seven times its estimate off (within
    /// `e_tol`; STABILITY.md, "The phase path").
    pub phase: bool,
}

/// How a run treats stiff dynamics.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Stiffness {
    /// The explicit `method` throughout (the paper's setup; a stiff run crawls until
    /// `max_steps`).
    Ignore,
    /// The explicit `method` until Hairer's stiffness test fires, then RODAS4 (L-stable
    /// Rosenbrock, order 4) with the model's Jacobian from that point on (the default).
    Switch,
    /// RODAS4 throughout (`method` is not used).
    Rosenbrock,
}

impl Default for Settings {
    /// Taylor series for CoR evaluations, DOP853 otherwise, at rtol 1e-12, atol 1e-14,
    /// stopping at the non-smooth points, no step limit, horizon 1000, and CoR evaluations
    /// checked against a run at rtol 1e-10 for an error in `e` of at most `e_tol` = 1e-10.
    /// Chosen from the data: no single tolerance keeps the error in `e` below 1e-10 on every
    /// separated run of the stress sweep (565 of about 52,600 miss at rtol 1e-11, 55 at
    /// 1e-14); the checked runs miss about 6, by up to 1.1e-9, each with an estimate above
    /// `e_tol` (runs whose truth double precision pins down only to a few 1e-10), at about
    /// twice the cost of one run at rtol 1e-11 on the paper's cases. On the work-precision
    /// cases (BENCHMARKS.md) one run at rtol 1e-11 already keeps the error below 1e-12. Those
    /// few are computed again in double-double ([`Settings::double_double`]), which leaves no
    /// separated run of three seeds of the sweep off by more than 1e-10 (STABILITY.md,
    /// "Global error control").
    fn default() -> Self {
        Self {
            method: &DOP853,
            rtol: 1e-12,
            atol: 1e-14,
            max_step: f64::INFINITY,
            t_max: 1e3,
            max_steps: 1_000_000,
            stop_at_kinks: true,
            stiffness: Stiffness::Switch,
            series: true,
            e_tol: Some(1e-10),
            double_double: true,
            phase: false,
        }
    }
}

impl Settings {
    /// The paper's numerical setup (Appendix D): DOP853, rtol 1e-10, atol 1e-12, max_step 1e-2
    /// (nondimensional), stepping over the non-smooth points.
    pub fn paper() -> Self {
        Self {
            method: &DOP853,
            rtol: 1e-10,
            atol: 1e-12,
            max_step: 1e-2,
            stop_at_kinks: false,
            stiffness: Stiffness::Ignore,
            series: false,
            e_tol: None,
            ..Self::default()
        }
    }

    /// Checks the settings.
    ///
    /// # Errors
    /// [`ModelError::InvalidSetting`] naming the first offending setting.
    pub fn validate(&self) -> Result<(), ModelError> {
        let bad = |name, value, allowed| {
            Err(ModelError::InvalidSetting {
                name,
                value,
                allowed,
            })
        };
        if !(self.rtol.is_finite() && self.rtol > f64::EPSILON) {
            return bad("rtol", self.rtol, "finite and > 2.2e-16");
        }
        if !(self.atol.is_finite() && self.atol >= 0.0) {
            return bad("atol", self.atol, "finite and >= 0");
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return bad("max_step", self.max_step, "> 0 (may be inf)");
        }
        if !(self.t_max.is_finite() && self.t_max > 0.0) {
            return bad("t_max", self.t_max, "finite and > 0");
        }
        if self.max_steps == 0 {
            return bad("max_steps", 0.0, ">= 1");
        }
        if let Some(e_tol) = self.e_tol {
            if !(e_tol.is_finite() && e_tol > 0.0) {
                return bad(
                    "e_tol",
                    e_tol,
                    "finite and > 0 (none, or 0 in a scene, for one run at rtol)",
                );
            }
        }
        Ok(())
    }
}

/// The checking ladder of a CoR evaluation under [`Settings::e_tol`] (the crate's
/// [`impact`](crate::impact)): the run at `rtol` is checked against the same impact at
/// `tighten * rtol` by [`Ladder::check_method`]; where their `e` differ by more than
/// `accept * e_tol`, runs at `rtol / tighten`, `rtol / tighten^2`, ... by
/// [`Ladder::tighter_method`] follow down to [`Ladder::floor_rtol`] until two agree; and where
/// even the floor does not settle it, [`Settings::double_double`] computes the impact again in
/// double-double at [`Ladder::double_double_rtols`] in turn. The crate's ladder is [`LADDER`];
/// it was chosen on the stress sweep (STABILITY.md, "Global error control") and is public so
/// that tools and studies can say what was run.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct Ladder {
    /// A run is accepted when its `e` differs from the check's by at most this fraction of
    /// `e_tol`: where the check's error is the difference, the reported run's is about a
    /// hundredth of it, and the margin covers runs whose error does not fall in proportion to
    /// rtol.
    pub accept: f64,
    /// The factor between the tolerances of successive runs: the check runs at
    /// `tighten * rtol`, a tighter run at `rtol / tighten`.
    pub tighten: f64,
    /// The tightest rtol of the double-precision runs: below it DOP853's and the series'
    /// errors are those of rounding.
    pub floor_rtol: f64,
    /// The Runge-Kutta method of the check (Verner's 9(8)): another method than the default
    /// DOP853, so that an error a method makes at every tolerance (DOP853's in steps limited by
    /// stability, say) shows as a difference instead of passing the check.
    pub check_method: &'static Tableau,
    /// The Runge-Kutta method of the tighter runs (Verner's 7(6)): of the built-in methods the
    /// closest to the truth at rtol 1e-14 on the stress sweep's hardest runs, where Verner's
    /// 9(8) spends its steps on rounding noise in its error estimate.
    pub tighter_method: &'static Tableau,
    /// The tolerances of the double-double runs, in turn until one agrees with the run before
    /// it to `e_tol`; that one is reported. On the runs double precision cannot settle, rtol
    /// 1e-16 gets `e` to about 1e-13 and 1e-18 to about 1e-15, except on a few long forced
    /// contacts where 1e-16 is off by 1e-10 and the third run settles it; at 1e-14 the steps can
    /// pass over a pair of kinks and miss `e` by 7e-9.
    pub double_double_rtols: [f64; 3],
    /// A double-double run after the first may take at most this many times the accepted steps
    /// of the run before it (plus [`Ladder::dd_step_slack`]). An extrapolation of order 16 needs
    /// about `100^(1/16)` = 1.33 times the steps at a hundredth of the tolerance, and the stress
    /// sweep's runs take 1.1 to 1.6 times; a run that needs far more is not in that regime, and
    /// its result would be refused after a long wait (one took 257 steps at rtol 1e-16 and
    /// 326,460 and 45 s at 1e-18).
    pub dd_step_growth: u64,
    /// The steps a double-double run after the first may take beyond
    /// [`Ladder::dd_step_growth`] times the run before it, so that short runs are not held to a
    /// few steps.
    pub dd_step_slack: u64,
}

/// The crate's checking ladder (see [`Ladder`]).
pub const LADDER: Ladder = Ladder {
    accept: 0.1,
    tighten: 100.0,
    floor_rtol: 1e-14,
    check_method: &VERN9,
    tighter_method: &VERN7,
    double_double_rtols: [1e-16, 1e-18, 1e-20],
    dd_step_growth: 8,
    dd_step_slack: 1_000,
};

impl Ladder {
    /// The tolerance of the run after one at `rtol`: `rtol / tighten`, or `floor_rtol` where
    /// that would pass it (so a chain of runs from any `rtol` ends on the floor, not short of
    /// it).
    pub fn tighter(&self, rtol: f64) -> f64 {
        (rtol / self.tighten).max(self.floor_rtol)
    }

    /// The step limit of a double-double run after one that took `steps_before` accepted steps.
    pub fn dd_step_limit(&self, steps_before: u64) -> u64 {
        self.dd_step_growth * steps_before + self.dd_step_slack
    }
}

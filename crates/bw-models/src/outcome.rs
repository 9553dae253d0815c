//! What one impact gives ([`Impact`], [`Cor`]) and what its check found ([`Check`],
//! [`FailedRun`], [`DdDeclined`], [`DdFailure`]), in the units of the model that made it.

use crate::settings::LADDER;
use bwc_ode::{State, Stats};

/// The outcome of one impact of a model with `N` states, in the model's units: seconds and SI
/// states for [`crate::Bwshccm`] (`x, z, v`) and [`crate::Bwmcm`] (`r, y, z, v`),
/// nondimensional for the ND models. `e = v(t_s) / v0 >= 0` with the relative velocity `v`
/// positive as the bodies part. Its outcome is a [`Cor`], which it holds and derefs to
/// (`impact.e`, `impact.t_s`), and the state it ended in.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Impact<const N: usize> {
    /// The outcome: `e`, `t_s`, their error estimates and how they were found.
    pub cor: Cor,
    /// State at separation (at the horizon, or where the contact settled, without separation).
    pub state: State<N>,
}

impl<const N: usize> std::ops::Deref for Impact<N> {
    type Target = Cor;
    fn deref(&self) -> &Cor {
        &self.cor
    }
}

impl<const N: usize> std::ops::DerefMut for Impact<N> {
    fn deref_mut(&mut self) -> &mut Cor {
        &mut self.cor
    }
}

impl<const N: usize> Impact<N> {
    /// One run's outcome, unchecked ([`Check::Off`]): separated at `t_s` (or not) with `e`,
    /// ending in `state`, at `rtol`, in double precision, neither settled nor stiff, without
    /// series steps. Each path sets what differs by struct update, so that a field added to
    /// the check is added here once.
    pub(crate) fn unchecked(
        (t_s, e, state): (Option<f64>, f64, State<N>),
        stats: Stats,
        rtol: f64,
    ) -> Self {
        let cor = Cor {
            t_s,
            e,
            settled_at: None,
            stiff_from: None,
            series_steps: 0,
            stats,
            rtol,
            e_error: None,
            t_s_error: None,
            check: Check::Off,
            tighter_failed: None,
            double_double: false,
            double_double_declined: None,
            phase: false,
        };
        Impact { cor, state }
    }

    /// The impact with what differs from [`Impact::unchecked`] set on its outcome by `set`.
    pub(crate) fn with(mut self, set: impl FnOnce(&mut Cor)) -> Self {
        set(&mut self.cor);
        self
    }

    /// The outcome `cor` ending in `state`.
    pub(crate) fn from_cor(cor: Cor, state: State<N>) -> Self {
        Impact { cor, state }
    }

    /// The impact of a model's nondimensional form in the units of the model: each time (`t_s`,
    /// its error, `settled_at`, `stiff_from`) times the time scale `t_c`, each state component
    /// times its scale in `scale` (Table 1); `e = V(T_s) = v(t_s) / v0` and its error are the
    /// same both ways.
    pub(crate) fn in_units(self, scale: &State<N>, t_c: f64) -> Self {
        Impact {
            cor: self.cor.in_time_unit(t_c),
            state: self.state.component_mul(scale),
        }
    }

    /// Whether the bodies separated.
    pub fn separated(&self) -> bool {
        self.cor.t_s.is_some()
    }

    /// Contact duration `t_d = t_s - t_0 = t_s`.
    pub fn duration(&self) -> Option<f64> {
        self.cor.t_s
    }

    /// The outcome without the state.
    pub fn cor(&self) -> Cor {
        self.cor
    }
}

/// An impact's outcome without its state: what a CoR evaluation of either model gives
/// ([`crate::impact_at`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Cor {
    /// Separation time `t_s` in the model's time unit (s for SI models), `None` when the bodies
    /// had not separated by the horizon.
    pub t_s: Option<f64>,
    /// Coefficient of restitution `e = v(t_s) / v0` (0 without separation).
    pub e: f64,
    /// Without separation: the time at which the contact had settled (at rest with the force
    /// balancing a constant input, an equilibrium), if the simulation stopped there early.
    pub settled_at: Option<f64>,
    /// When the run switched to RODAS4 because it had become stiff ([`Stiffness::Switch`](crate::Stiffness::Switch)).
    pub stiff_from: Option<f64>,
    /// Steps taken by Taylor series ([`Settings::series`](crate::Settings::series); 0 on the Runge-Kutta path, and
    /// counted also where the series handed the impact over to it). The statistics count them
    /// as accepted steps, and the RHS evaluations of the start steps.
    pub series_steps: u64,
    /// Solver statistics (of every run under [`Settings::e_tol`](crate::Settings::e_tol)).
    pub stats: Stats,
    /// The relative tolerance of the reported run: [`Settings::rtol`](crate::Settings::rtol), or tighter where
    /// [`Settings::e_tol`](crate::Settings::e_tol) asked for it.
    pub rtol: f64,
    /// Under [`Settings::e_tol`](crate::Settings::e_tol): the estimate of the error in `e`, the difference from the
    /// check run at 100 times `rtol` (about a hundred times this run's own error where the
    /// error falls in proportion to rtol). `None` for a single run.
    pub e_error: Option<f64>,
    /// As `e_error`, for `t_s` (model time units), where both runs separated.
    pub t_s_error: Option<f64>,
    /// What the check under [`Settings::e_tol`](crate::Settings::e_tol) found.
    pub check: Check,
    /// Under [`Settings::e_tol`](crate::Settings::e_tol): the tighter run that failed, where one did (the check stopped
    /// there and `e` is the run before it).
    pub tighter_failed: Option<FailedRun>,
    /// Whether the reported run is the double-double one ([`Settings::double_double`](crate::Settings::double_double)); its
    /// `rtol` is then the double-double run's.
    pub double_double: bool,
    /// Where the check stayed [`Check::Unmet`] under [`Settings::double_double`](crate::Settings::double_double): why the
    /// double-double retry reported nothing (`e` is then the double-precision one). `None`
    /// otherwise.
    pub double_double_declined: Option<DdDeclined>,
    /// Whether the result is the phase path's ([`Settings::phase`](crate::Settings::phase)): no time steps, so `stats`
    /// count no work and `rtol` is the setting's; `e_error` is the phase path's own estimate.
    pub phase: bool,
}

impl Cor {
    /// The outcome with its times (`t_s`, its error, `settled_at`, `stiff_from`) multiplied by
    /// `scale`: in seconds for a nondimensional impact with `scale` its time scale (s).
    pub fn in_time_unit(self, scale: f64) -> Cor {
        Cor {
            t_s: self.t_s.map(|t| t * scale),
            t_s_error: self.t_s_error.map(|t| t * scale),
            settled_at: self.settled_at.map(|t| t * scale),
            stiff_from: self.stiff_from.map(|t| t * scale),
            ..self
        }
    }
}

impl Cor {
    /// Whether the bodies separated.
    pub fn separated(&self) -> bool {
        self.t_s.is_some()
    }
}

/// What the check of an impact under [`Settings::e_tol`](crate::Settings::e_tol) found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
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

/// A run under [`Settings::e_tol`](crate::Settings::e_tol) tighter than the reported one that failed, so that the
/// check stopped there ([`Impact::tighter_failed`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FailedRun {
    /// Its relative tolerance.
    pub rtol: f64,
    /// Whether it needed more than [`Settings::max_steps`](crate::Settings::max_steps) steps (a larger `max_steps` lets it
    /// finish); `false` for another failure (a step size too small, a non-finite state).
    pub out_of_steps: bool,
}

/// Why the double-double retry ([`Settings::double_double`](crate::Settings::double_double)) of a CoR whose check stayed
/// [`Check::Unmet`] reported nothing ([`Impact::double_double_declined`]); the reported `e` is
/// then the double-precision one, flagged.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum DdDeclined {
    /// The reported double-precision run (the tightest) switched to RODAS4 at `from` (model
    /// time units; [`Impact::stiff_from`]): the double-double path is explicit, and on such
    /// runs its error estimate does not hold (on three seeds of the stress sweep it settled
    /// none of the five, after up to 139 s; STABILITY.md, "Double-double"). Not tried.
    Stiff {
        /// When the run switched.
        from: f64,
    },
    /// The model, or its input, has no double-double form ([`impact_double_double`](crate::impact_double_double)).
    NoPath,
    /// The run at `rtol` stopped short of the separation.
    Failed {
        /// Its relative tolerance.
        rtol: f64,
        /// Why.
        failure: DdFailure,
    },
    /// The run at `rtol` needed more than [`Ladder::dd_step_limit`](crate::Ladder::dd_step_limit)
    /// of the steps of the run before it (`steps_before`): it is not in the regime where a tighter
    /// tolerance costs a few more steps, and its result would not be trusted.
    StepsGrew {
        /// Its relative tolerance.
        rtol: f64,
        /// The accepted steps of the run before it.
        steps_before: u64,
    },
    /// The last two runs (the tightest at rtol 1e-20) still differ by `e_error`, more than
    /// `e_tol`.
    Disagreed {
        /// Their difference in `e`.
        e_error: f64,
    },
}

impl DdDeclined {
    /// The name in outputs: `"stiff"`, `"no-path"`, `"failed"`, `"steps-grew"` or
    /// `"disagreed"`.
    pub fn name(self) -> &'static str {
        match self {
            DdDeclined::Stiff { .. } => "stiff",
            DdDeclined::NoPath => "no-path",
            DdDeclined::Failed { .. } => "failed",
            DdDeclined::StepsGrew { .. } => "steps-grew",
            DdDeclined::Disagreed { .. } => "disagreed",
        }
    }
}

/// A predicate of "the double-double retry", as the command-line tools print it.
impl std::fmt::Display for DdDeclined {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            DdDeclined::Stiff { .. } => write!(
                f,
                "was not tried: the tightest double-precision run went stiff (it switched to \
                 RODAS4), where the explicit double-double steps are not reliable"
            ),
            DdDeclined::NoPath => write!(
                f,
                "is not possible: the model or its input has no double-double form"
            ),
            DdDeclined::Failed { rtol, failure } => {
                write!(f, "failed at rtol {rtol:e}: {failure}")
            }
            DdDeclined::StepsGrew { rtol, steps_before } => write!(
                f,
                "was stopped: its run at rtol {rtol:e} needed more than {} times \
                 the {steps_before} steps of the run before it",
                LADDER.dd_step_growth
            ),
            DdDeclined::Disagreed { e_error } => write!(
                f,
                "did not settle it: its runs down to rtol {:e} still differ by {e_error:.1e} in e",
                LADDER.double_double_rtols[LADDER.double_double_rtols.len() - 1]
            ),
        }
    }
}

/// Why a double-double run ([`crate::impact_double_double`]) stopped short of the separation.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DdFailure {
    /// More than the step limit of accepted steps.
    #[error("more than max_steps steps; a larger [solver].max_steps lets it finish")]
    TooManySteps,
    /// The step size fell below `1e-28 max(1, T)`, at `T`.
    #[error("step size underflow at T = {0}")]
    StepSizeTooSmall(f64),
    /// No separation by the horizon.
    #[error("no separation by t_max")]
    NoSeparation,
}

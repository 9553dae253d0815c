//! Taylor-series integration of one impact of the nondimensional models under a constant input:
//! the fast path of a CoR evaluation ([`crate::Settings::series`]).
//!
//! Between the non-smooth points each right-hand side is analytic in its branch (fixed signs of
//! `X` or `Y`, of `Z` and of the rate across the hysteretic element), so the solution is
//! expanded about the start of each step in its Taylor series of order `polynomial::ORDER`, computed by
//! automatic differentiation: the coefficients of `y = b^e` (`|X|^p`, `|Z|^n`, `|Z|^p`) follow
//! from `b y' = e b' y`,
//!
//! `y_k = (1 / (k b_0)) Σ_{i<k} (e (k - i) - i) b_{k-i} y_i`,
//!
//! and products by the Cauchy rule (Jorba & Zou, Experiment. Math. 14 (2005) 99-117). The step
//! is Jorba & Zou's, `h = 0.9 min_k ρ_k` over the last `steps::ESTIMATE_TERMS` orders with
//! `ρ_k = (tol / |c_k|_∞)^(1/k)` over the state and the force and
//! `tol = TOLERANCE_SCALE (atol + rtol |y|_∞)`, growing at most `steps::MAX_GROWTH` times per step;
//! there are no rejected steps. The non-smooth points (the rate and `Z` changing sign) and the
//! separation `F <= 0 <= V` are roots of the step's polynomials, found by safeguarded Newton
//! iteration; sign changes are looked for at the middle and the end of the step and again up to
//! each root found, so that a function crossing twice inside one step is not missed.
//!
//! Where a base of a power vanishes (`X = Z = 0` at contact, `Z = 0` at its kink) the solution is
//! only finitely smooth and the recurrence divides by zero. Both there and at the roots that
//! matter most the series converge slowest (a zero of a base is their radius of convergence),
//! so the explicit method of the settings takes over: it leaves each such point with one step
//! (at `steps::START_TOLERANCE` times the tolerances), and it integrates from the start of the step
//! onto a zero of `Z` (or `X`, `Y`) and onto a separation near one (the force can vanish where
//! a base does), where one Newton step along `f` polishes the root; a separation away from the
//! zeros of the bases is the root of the step's polynomials. At contact, where the NDBWSHCCM loads as a Hunt-Crossley contact
//! (`Γ = -B`, no input: every fit of the paper), a series in `s = T^(p+1)`, in which the
//! solution is analytic, takes the first step instead (`series/contact.rs`): one step over most of the
//! compression in place of the start step and the ramp after it.
//!
//! Off a zero of a base where neither series applies (a loading with hysteresis, `B + Γ != 0`,
//! or under an input), the start step is followed by steps in `σ = ln(T - T_a)` about the time
//! `T_a` where the base vanished (`jet::Clock::Log`): the solution's terms `(T - T_a)^a` are
//! `e^(a σ)`, analytic in `σ`, so these steps are not bounded by the distance to `T_a` as the
//! steps in `T` are (which grow by at most `MAX_GROWTH` per step from the start step's span).
//! They end at the first event ahead or once a step spans less than `steps::LOG_STEP_MIN`, where the
//! solution's other singularities bound the steps and a step in time costs less. At contact
//! the start step is not the explicit method's: the loading's leading terms give the state at
//! a time where the terms they leave out are below the start tolerance (`series/onset.rs`),
//! and the logarithmic steps ramp from there.
//!
//! Off a root of `Z` into a branch without hysteresis bracket (`B + Γ = 0`, every fit of the
//! paper), a series in `D = |Z|` and `D^p`, in which the solution is analytic, takes the first
//! step instead of the start step and the ramp after it (`series/crossing.rs`).
//!
//! Where `Z` runs into the equilibrium of its branch (`|Z| = c^(-1/n)` with
//! `c = B sgn(Z) sgn(rate) + Γ > 0`, `Z` moving with the rate), it is held there once within
//! `steps::START_TOLERANCE` step tolerances of it: the exact `Z` only approaches it further, and the
//! decay towards it would otherwise cap the steps at its rate.
//!
//! A contact that comes to rest is reported as settled, as on the Runge-Kutta path. Where this
//! path cannot go on (a start step that meets an event, more than `steps::MAX_SERIES_STEPS` steps,
//! e.g. a stiff contact, a state sliding along a switching surface, an ill-conditioned root, or
//! the horizon) it hands the impact over ([`SeriesRun::HandOver`]) and the Runge-Kutta path
//! continues from the last state the series reached.
//!
//! Accuracy and cost are measured, not claimed here: BENCHMARKS.md, "One CoR: the series path" (time at equal error against plain DOP853 on the paper's DSS (1) cases) and
//! STABILITY.md (accuracy on the stress sweep's extreme parameters against the Runge-Kutta
//! path), which is why it is the default for CoR evaluations.

mod contact;
mod crossing;
mod jet;
mod onset;
mod path;
mod polynomial;
mod recurrence;
mod steps;

pub(crate) use jet::Expand;
pub(crate) use path::SeriesRun;

use crate::settings::Settings;

/// One impact by Taylor series, or `None` where this path declines (see the module docs).
pub(crate) fn impact<M: Expand<N>, const N: usize>(
    model: &M,
    settings: &Settings,
) -> Option<SeriesRun<N>> {
    path::SeriesPath::start(model, settings).map(path::SeriesPath::run)
}

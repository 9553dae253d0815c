//! The double-double path of a CoR evaluation ([`crate::Settings::double_double`]): the
//! nondimensional models in double-double arithmetic, integrated by Gragg-Bulirsch-Stoer
//! extrapolation ([`bwc_ode::Extrapolation`]), with their non-smooth points and the separation
//! located to double-double precision.
//!
//! Why: in a few long, forced, stiff contacts (STABILITY.md, "Session 23") double precision
//! gets `e` no closer than about 1e-9. Their `e` hardly depends on the parameters (1.6e-13 for a
//! change of 1e-15 in `σ`), but the same double-double integration with the right-hand side
//! evaluated from states rounded to double precision misses by 3e-9 to 2e-8; the same
//! integration in double-double throughout converges to 1e-17.
//!
//! Events are looked for at the finest midpoint sequence's states inside each step (every
//! `H / 16`, second order) and at its end, so that an excursion shorter than the step is seen
//! (a separation `F <= 0 <= V` that lasts a fraction of a step where the force is about 1e-42,
//! as in case 3144 of the stress sweep's seed 1); a sign change is confirmed by accurate states
//! at both ends of its interval and located by the Illinois method on `τ -> g(y(t + τ))`,
//! each value one extrapolation step of size `τ` from the step's start (on the branch before
//! the root, for a root of the rate: [`Frozen`]).
//! The integration stops at each non-smooth point (the zeros of [`CollisionModel::kinks`]'s
//! functions) and restarts there, and ends at the separation `F <= 0 <= V`.
//!
//! [`CollisionModel::kinks`]: crate::CollisionModel::kinks

use crate::impact::{Impact, Settings};
use crate::input::Input;
use crate::params::{ModelKind, Nondim};
use crate::{Check, State};
use bwc_ode::dd::{copysign, ln_abs, pow_abs_ln, Dd};
use bwc_ode::{DdSystem, DdTrial, Extrapolation, Stats};

/// A nondimensional model in double-double, with the equations of [`crate::Ndbwshccm`] and
/// [`crate::Ndbwmcm`], always in states `(R, Y, Z, V)`: the NDBWSHCCM's `X` is `Y`, with `R`
/// held at 0.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Model<'a, I> {
    /// Which model.
    pub kind: ModelKind,
    /// Parameters.
    pub k: Nondim,
    /// Input `U(T)`; [`Input::at_dd`] must be `Some`.
    pub u: &'a I,
}

/// A state `(R, Y, Z, V)`.
pub(crate) type DdState = [Dd; 4];

/// `|s|^(q-1) s` and `|s|^q` from `ln |s|`.
fn signed_and_abs(s: Dd, ln: Option<Dd>, q: f64) -> (Dd, Dd) {
    let a = pow_abs_ln(ln, q);
    (copysign(a, s), a)
}

/// The hysteretic rate `w - |Z|^n (B sgn(Z) |w| + Γ w)` (laws.rs's `hysteresis` with `A = 1`).
/// `abs_w` is `|w|`, or `s w` on a branch frozen to the sign `s` of `w` ([`Frozen`]).
fn hysteresis(k: &Nondim, z: Dd, zn: Dd, w: Dd, abs_w: Dd) -> Dd {
    w - zn * (copysign(abs_w * k.b, z) + w * k.gamma)
}

impl<I: Input> DdSystem<4> for Model<'_, I> {
    fn rhs(&self, t: Dd, y: &DdState) -> DdState {
        self.rhs_on(t, y, None)
    }
}

/// The model with `|w|` of the rate `w` driving `Z` replaced by `s w` for the sign `s` it had
/// before a root of `w`: the branch's analytic continuation past the root, so that the event
/// function is smooth where the root is searched for and the Illinois method converges
/// superlinearly (across the kink itself each trial step would lose its order).
struct Frozen<'m, 'a, I> {
    m: &'m Model<'a, I>,
    sign: f64,
}

impl<I: Input> DdSystem<4> for Frozen<'_, '_, I> {
    fn rhs(&self, t: Dd, y: &DdState) -> DdState {
        self.m.rhs_on(t, y, Some(self.sign))
    }
}

impl<I: Input> Model<'_, I> {
    /// The right-hand side, on the branch of the rate's sign `frozen` where given.
    fn rhs_on(&self, t: Dd, y: &DdState, frozen: Option<f64>) -> DdState {
        let abs = |w: Dd| frozen.map_or(w.abs(), |s| w * s);
        let (f, ln_z) = self.force_and_ln_z(y);
        let zn = pow_abs_ln(ln_z, self.k.n);
        let vdot = f + self.u.at_dd(t).unwrap_or(Dd::from(f64::NAN));
        match self.kind {
            ModelKind::Shccm => [
                Dd::from(0.0),
                y[3],
                hysteresis(&self.k, y[2], zn, y[3], abs(y[3])),
                vdot,
            ],
            ModelKind::Mcm => {
                let rdot = -(f * self.k.sigma);
                let ydot = y[3] - rdot;
                [
                    rdot,
                    ydot,
                    hysteresis(&self.k, y[2], zn, ydot, abs(ydot)),
                    vdot,
                ]
            }
        }
    }

    /// `(F, ln |Z|)` at `y` (the logarithm for `|Z|^n`, `None` at `Z = 0`).
    fn force_and_ln_z(&self, y: &DdState) -> (Dd, Option<Dd>) {
        let k = &self.k;
        let (ly, lz) = (ln_abs(y[1]), ln_abs(y[2]));
        let (yq, yp) = signed_and_abs(y[1], ly, k.p);
        let (zq, _) = signed_and_abs(y[2], lz, k.p);
        let kc = Dd::from(1.0) - k.kappa;
        let mut f = -(yq * k.kappa) - zq * kc;
        if self.kind == ModelKind::Shccm {
            f -= yp * y[3] * k.sigma;
        }
        (f, lz)
    }

    /// The event functions at `y`: the functions whose zeros are the non-smooth points (the
    /// rate driving `Z`, `V` or `Y'`, and `Z`, as [`crate::CollisionModel::kinks`]) and
    /// `max(F, -V)`, at most 0 exactly where `F <= 0 <= V` (separated).
    fn events(&self, y: &DdState) -> [Dd; 3] {
        let f = self.force_and_ln_z(y).0;
        let rate = match self.kind {
            ModelKind::Shccm => y[3],
            ModelKind::Mcm => y[3] + f * self.k.sigma,
        };
        let v = -y[3];
        [rate, y[2], if f > v { f } else { v }]
    }
}

/// What a double-double run made of an impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct DdRun {
    /// Separation time `T_s`.
    pub t_s: Dd,
    /// The state `(R, Y, Z, V)` at the separation: `e = V(T_s)` (`V(0) = -1`).
    pub y: DdState,
    /// Accepted steps (a located event counts as one).
    pub steps: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Right-hand-side evaluations.
    pub evals: u64,
    /// Non-smooth points crossed.
    pub kinks: u64,
}

/// Why a double-double run ([`crate::impact_double_double`]) stopped short of the separation.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
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

/// The double-double run of a nondimensional model `kind` with parameters `k` under `input`,
/// as an [`Impact`] whose state is `state_of` the run's `(R, Y, Z, V)`; `None` where the input
/// has no double-double form.
pub(crate) fn run_model<I: Input, const N: usize>(
    (kind, k, input): (ModelKind, Nondim, &I),
    ext: Extrapolation,
    settings: &Settings,
    state_of: impl Fn([f64; 4]) -> State<N>,
) -> Option<Result<Impact<N>, DdFailure>> {
    input.at_dd(Dd::from(0.0))?;
    let m = Model { kind, k, u: input };
    Some(
        impact(&m, ext, settings.max_steps, settings.t_max).map(|r| Impact {
            t_s: Some(r.t_s.hi()),
            e: r.y[3].hi().max(0.0),
            state: state_of(r.y.map(|v| v.hi())),
            settled_at: None,
            stiff_from: None,
            series_steps: 0,
            stats: Stats {
                rhs_evals: r.evals,
                accepted: r.steps,
                rejected: r.rejected,
                events: r.kinks + 1,
                jacobians: 0,
            },
            rtol: ext.rtol,
            e_error: None,
            t_s_error: None,
            check: Check::Off,
            tighter_failed: None,
            double_double: true,
        }),
    )
}

/// A located event: which function, the time from the step's start and the state there.
struct Crossing {
    /// 0 and 1: the kink functions; 2: the separation.
    which: usize,
    tau: Dd,
    y: DdState,
}

/// A run's fixed parts: the model, the method, and the counter of evaluations.
struct Run<'m, 'a, I> {
    m: &'m Model<'a, I>,
    ext: Extrapolation,
    evals: u64,
}

impl<I: Input> Run<'_, '_, I> {
    /// One extrapolation step of size `h` from `(t, y)` with `f0 = f(t, y)`, on the branch
    /// `frozen` (a sign of the rate) where given.
    fn step(
        &mut self,
        (t, y, f0): (Dd, &DdState, &DdState),
        h: Dd,
        frozen: Option<f64>,
    ) -> DdTrial<4> {
        let trial = match frozen {
            Some(sign) => self.ext.step(&Frozen { m: self.m, sign }, t, y, f0, h),
            None => self.ext.step(self.m, t, y, f0, h),
        };
        self.evals += trial.evals;
        trial
    }

    /// The event functions at the state `h` after the start `at` (one step).
    fn events_after(&mut self, at: (Dd, &DdState, &DdState), h: Dd) -> [Dd; 3] {
        let y = self.step(at, h, None).y;
        self.m.events(&y)
    }

    /// The first event inside the accepted step `[t, t + h]`, if any. `at_root[w]`: kink
    /// function `w` is at its root at `t` (its sign there is not known). The event functions
    /// are scanned at the finest midpoint sequence's states (every `h / 2k`), so that an
    /// excursion shorter than the step is seen; a sign change there is confirmed by accurate
    /// states at both ends of its interval before it is located.
    fn first_event(
        &mut self,
        (t, y, f0): (Dd, &DdState, &DdState),
        h: Dd,
        trial: &DdTrial<4>,
        at_root: [bool; 2],
    ) -> Option<Crossing> {
        let n = trial.samples.len() + 1;
        let checked = |w: usize, first: bool| w == 2 || !first || !at_root[w];
        let (mut a, mut ga, mut ga_exact) = (Dd::from(0.0), self.m.events(y), true);
        for i in 1..=n {
            let b = h * (i as f64 / n as f64);
            let last = i == n;
            let gb = self.m.events(if last {
                &trial.y
            } else {
                &trial.samples[i - 1]
            });
            let first = i == 1;
            if !(0..3).any(|w| checked(w, first) && crosses(w, ga[w], gb[w])) {
                (a, ga, ga_exact) = (b, gb, last);
                continue;
            }
            // Accurate values at both ends of the interval.
            if !ga_exact {
                ga = self.events_after((t, y, f0), a);
            }
            let gb = if last {
                gb
            } else {
                self.events_after((t, y, f0), b)
            };
            let found = (0..3)
                .filter(|&w| checked(w, first) && crosses(w, ga[w], gb[w]))
                .map(|w| self.locate((t, y, f0), (a, ga[w]), (b, gb[w]), w))
                .min_by(|p, q| p.tau.partial_cmp(&q.tau).expect("finite times"));
            if found.is_some() {
                return found;
            }
            (a, ga, ga_exact) = (b, gb, true);
        }
        None
    }

    /// The root of event function `which` in `(a, b)` by the Illinois method on the states
    /// `y(t + τ)` of single extrapolation steps; returns the state on the far side of the root
    /// (where the event has happened), within `max(rtol 1e-4, 2^-100) |b|` in `τ`.
    fn locate(
        &mut self,
        (t, y, f0): (Dd, &DdState, &DdState),
        (mut a, mut fa): (Dd, Dd),
        (mut b, mut fb): (Dd, Dd),
        which: usize,
    ) -> Crossing {
        let end = b;
        // A root of the rate (function 0) is searched for on the branch before it.
        let frozen = (which == 0).then(|| fa.hi().signum());
        let mut far = (b, self.step((t, y, f0), b, frozen).y);
        // Which end the last iteration replaced: Illinois halves the other end's value when
        // the same end is replaced twice in a row, so that regula falsi does not stall.
        let mut last_far = None;
        // The trial states carry rounding errors of about 1e-22 (the midpoint rule amplifies
        // the stiff components' rounding before the extrapolation cancels it), so the root is
        // sought to `rtol 1e-4` of the step: its error then moves the state by far less than
        // the step's tolerance, and the iteration stops before it reads that noise.
        let width = end.hi().abs() * (self.ext.rtol * 1e-4).max(2f64.powi(-100));
        for _ in 0..300 {
            if (b - a).abs().hi() <= width {
                break;
            }
            let mut c = (a * fb - b * fa) / (fb - fa);
            if (c - a).hi() * (c - b).hi() >= 0.0 || !c.hi().is_finite() {
                c = (a + b) * 0.5;
            }
            let yc = self.step((t, y, f0), c, frozen).y;
            let fc = self.m.events(&yc)[which];
            let on_far_side = crosses(which, fa, fc) || (which != 2 && fc == 0.0);
            if on_far_side {
                far = (c, yc);
                (b, fb) = (c, fc);
                if last_far == Some(true) {
                    fa *= 0.5;
                }
            } else {
                (a, fa) = (c, fc);
                if last_far == Some(false) {
                    fb *= 0.5;
                }
            }
            last_far = Some(on_far_side);
        }
        Crossing {
            which,
            tau: far.0,
            y: far.1,
        }
    }
}

/// Whether `a` and `b` lie strictly on opposite sides of 0 (for the separation, `which = 2`,
/// whether `b` has reached `<= 0` from `a > 0`).
fn crosses(which: usize, a: Dd, b: Dd) -> bool {
    if which == 2 {
        a > 0.0 && b <= 0.0
    } else {
        (a > 0.0 && b < 0.0) || (a < 0.0 && b > 0.0)
    }
}

/// Integrates one impact of `m` from contact (`V(0) = -1`, every other state 0) to the
/// separation with `ext`, in at most `max_steps` steps and by `t_max`.
///
/// # Errors
/// [`DdFailure`] where the run cannot reach the separation.
pub(crate) fn impact<I: Input>(
    m: &Model<'_, I>,
    ext: Extrapolation,
    max_steps: u64,
    t_max: f64,
) -> Result<DdRun, DdFailure> {
    let zero = Dd::from(0.0);
    let mut run = Run { m, ext, evals: 0 };
    let (mut t, mut y) = (zero, [zero, zero, zero, Dd::from(-1.0)]);
    let (mut h, mut steps, mut rejected, mut kinks) = (Dd::from(1e-6), 0, 0, 0);
    let mut at_root = [0, 1].map(|w| m.events(&y)[w] == 0.0);
    let done = |t, y, run: &Run<I>, steps, rejected, kinks| DdRun {
        t_s: t,
        y,
        steps,
        rejected,
        evals: run.evals,
        kinks,
    };
    loop {
        if steps >= max_steps {
            return Err(DdFailure::TooManySteps);
        }
        if t.hi() > t_max {
            return Err(DdFailure::NoSeparation);
        }
        let f0 = m.rhs(t, &y);
        run.evals += 1;
        let trial = run.step((t, &y, &f0), h, None);
        let factor = ext.factor(trial.err);
        if trial.err.is_nan() || trial.err > 1.0 {
            rejected += 1;
            h *= factor;
            if h.hi() < 1e-28 * t.hi().max(1.0) {
                return Err(DdFailure::StepSizeTooSmall(t.hi()));
            }
            continue;
        }
        steps += 1;
        match run.first_event((t, &y, &f0), h, &trial, at_root) {
            None => {
                (t, y) = (t + h, trial.y);
                at_root = [false; 2];
                h *= factor;
            }
            Some(c) if c.which == 2 => {
                return Ok(done(t + c.tau, c.y, &run, steps, rejected, kinks));
            }
            Some(c) => {
                (t, y) = (t + c.tau, c.y);
                at_root = [c.which == 0, c.which == 1];
                kinks += 1;
                // A kink can coincide with the separation (Z = X = 0 where an elastic
                // contact ends); the separation's own crossing starts from `> 0`.
                if m.events(&y)[2] <= 0.0 {
                    return Ok(done(t, y, &run, steps, rejected, kinks));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::Zero;
    use bwc_ode::dd;

    fn shccm(sigma: f64, p: f64) -> Model<'static, Zero> {
        Model {
            kind: ModelKind::Shccm,
            k: Nondim {
                b: 0.0,
                gamma: 0.0,
                kappa: 0.7,
                sigma,
                n: 2.5,
                p,
            },
            u: &Zero,
        }
    }

    fn rel(a: Dd, b: Dd) -> f64 {
        ((a - b) / b).hi().abs()
    }

    /// Runs at rtol 1e-28 land within about 1e-26 of these closed forms (at 1e-24, 1e-22:
    /// the separation, where `F` vanishes like `(T_s - T)^p`, costs digits).
    fn tight(m: &Model<'_, Zero>) -> DdRun {
        impact(m, Extrapolation::new(1e-28, 1e-30), 100_000, 100.0).unwrap()
    }

    /// Elastic limit, `p = 1` (REFERENCES.md): `X = -sin T`, so `T_s = π` and `e = 1`.
    #[test]
    fn elastic_linear_contact_ends_at_pi() {
        let out = tight(&shccm(0.0, 1.0));
        let pi = dd::dd(std::f64::consts::PI, 1.2246467991473532e-16);
        assert!(rel(out.t_s, pi) < 1e-28, "T_s = {:?}", out.t_s);
        assert!(rel(out.y[3], Dd::from(1.0)) < 1e-28, "e = {:?}", out.y[3]);
    }

    /// Hunt-Crossley limit (REFERENCES.md): `e` is the root in (0, 1) of
    /// `σ e + ln(1 - σ e) + σ - ln(1 + σ) = 0`, solved here by Newton's method in
    /// double-double.
    #[test]
    fn hunt_crossley_restitution_matches_its_first_integral() {
        for (sigma, p, published) in [(0.2, 1.5, 0.882189986247307), (0.9, 2.0, 0.619736466081975)]
        {
            let (s, one) = (Dd::from(sigma), Dd::from(1.0));
            let c = s - dd::ln(one + s);
            let mut e = Dd::from(published);
            for _ in 0..4 {
                let phi = s * e + dd::ln(one - s * e) + c;
                e -= phi / (s - s / (one - s * e));
            }
            assert!((e.hi() - published).abs() < 1e-15);
            let out = tight(&shccm(sigma, p));
            assert!(
                rel(out.y[3], e) < 1e-25,
                "sigma {sigma}: e = {:?}, want {e:?}",
                out.y[3]
            );
        }
    }

    #[test]
    fn a_run_out_of_steps_or_time_says_so() {
        let m = shccm(0.2, 1.5);
        let ext = Extrapolation::new(1e-20, 1e-22);
        assert_eq!(impact(&m, ext, 3, 100.0), Err(DdFailure::TooManySteps));
        assert_eq!(impact(&m, ext, 1000, 1.0), Err(DdFailure::NoSeparation));
    }
}

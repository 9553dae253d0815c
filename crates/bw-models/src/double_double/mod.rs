//! The double-double path of a CoR evaluation ([`crate::Settings::double_double`]): the
//! nondimensional models in double-double arithmetic, integrated by Gragg-Bulirsch-Stoer
//! extrapolation ([`bwc_ode::Extrapolation`]), with their non-smooth points and the separation
//! located to double-double precision.
//!
//! Why: in a few long, forced, stiff contacts (STABILITY.md, "Double-double") double precision
//! gets `e` no closer than about 1e-9. Their `e` hardly depends on the parameters (1.6e-13 for a
//! change of 1e-15 in `σ`), but the same double-double integration with the right-hand side
//! evaluated from states rounded to double precision misses by 3e-9 to 2e-8; the same
//! integration in double-double throughout converges to 1e-17.
//!
//! Events are looked for at the finest midpoint sequence's states inside each step (every
//! `H / 16`, second order) and at its end, so that an excursion shorter than the step is seen
//! (a separation `F <= 0 <= V` that lasts a fraction of a step where the force is about 1e-42,
//! as in case 3144 of the stress sweep's seed 1). A sign change is confirmed by accurate states
//! at both ends of its interval, each compared with the accurate state before it, and located
//! on `τ -> g(y(t + τ))`, each value one extrapolation step of size `τ` from the step's start
//! (on the branch before the root, for a root of the rate: [`Frozen`]), by Newton's method with
//! the Illinois method as its safeguard.
//! A step whose midpoint rule is unstable is abandoned and halved ([`Extrapolation::try_step`],
//! ODEX's stability check): past a stiff component's fast transient every midpoint sequence
//! can overshoot alike, and the error estimate then passes a wrong state (case 22932 of the
//! stress sweep's seed 10).
//! The integration stops at each non-smooth point (the zeros of [`CollisionModel::kinks`]'s
//! functions) and restarts there, and ends at the separation `F <= 0 <= V`. A step rejected
//! because it crosses a non-smooth point is not shrunk towards it: the point is located from
//! the rejected step's samples ([`Run::kink_in_rejected`]).
//!
//! [`CollisionModel::kinks`]: crate::CollisionModel::kinks

use crate::input::Input;
use crate::outcome::{DdFailure, Impact};
use crate::params::{ModelKind, Nondim};
use crate::settings::Settings;
use crate::State;
use bwc_ode::dd::{copysign, ln_abs, pow_abs_ln, Dd};
use bwc_ode::{DdSystem, DdTrial, Extrapolation, Stats};

/// A nondimensional model in double-double, with the equations of [`crate::Ndbwshccm`] and
/// [`crate::Ndbwmcm`], always in states `(R, Y, Z, V)`: the NDBWSHCCM's `X` is `Y`, with `R`
/// held at 0.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Model<'a, I: ?Sized> {
    /// Which model.
    pub kind: ModelKind,
    /// Parameters.
    pub k: Nondim,
    /// Input `U(T)`; [`Input::at_dd`] must be `Some`.
    pub u: &'a I,
}

/// A state `(R, Y, Z, V)`.
pub(crate) type DdState = [Dd; 4];

/// The event functions: the rate driving `Z` (`V` or `Y'`) and `Z`, whose zeros are the
/// non-smooth points ([`crate::CollisionModel::kinks`]); `max(F, -V)`, at most 0 exactly where
/// `F <= 0 <= V` (separated); and `F` and `V` themselves. The separated region is entered
/// through a root of `F` or of `V`, and those are seen where an excursion into it is shorter
/// than a sample interval of the scan, so that `max(F, -V)` shows no sign change (a root of
/// `F` and a root of `V` a few 1e-3 apart under a strong push: case 23291 of the stress
/// sweep's seed 1).
type Events = [Dd; EVENTS];
/// How many event functions.
const EVENTS: usize = 5;
/// The index of `max(F, -V)`, of `F` and of `V` in [`Events`].
const SEPARATED: usize = 2;
/// See [`SEPARATED`].
const FORCE: usize = 3;
/// See [`SEPARATED`].
const VELOCITY: usize = 4;

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

impl<I: Input + ?Sized> DdSystem<4> for Model<'_, I> {
    fn rhs(&self, t: Dd, y: &DdState) -> DdState {
        self.rhs_on(t, y, None)
    }
}

/// The model with `|w|` of the rate `w` driving `Z` replaced by `s w` for the sign `s` it had
/// before a root of `w`: the branch's analytic continuation past the root, so that the event
/// function is smooth where the root is searched for and the Illinois method converges
/// superlinearly (across the kink itself each trial step would lose its order).
struct Frozen<'m, 'a, I: ?Sized> {
    m: &'m Model<'a, I>,
    sign: f64,
}

impl<I: Input + ?Sized> DdSystem<4> for Frozen<'_, '_, I> {
    fn rhs(&self, t: Dd, y: &DdState) -> DdState {
        self.m.rhs_on(t, y, Some(self.sign))
    }
}

impl<I: Input + ?Sized> Model<'_, I> {
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

    /// The event functions at `y` ([`Events`]).
    fn events(&self, y: &DdState) -> Events {
        let f = self.force_and_ln_z(y).0;
        let rate = match self.kind {
            ModelKind::Shccm => y[3],
            ModelKind::Mcm => y[3] + f * self.k.sigma,
        };
        let v = -y[3];
        [rate, y[2], if f > v { f } else { v }, f, y[3]]
    }

    /// Whether a sign change of event function `w` between `ga` and `gb` can be an event: a
    /// root of `F` only where `V >= 0` at an end, a root of `V` only where `F <= 0` at an end
    /// (for the NDBWSHCCM `V` is the rate, whose roots are kinks, and the separation is checked
    /// at each kink).
    fn matters(&self, w: usize, ga: &Events, gb: &Events) -> bool {
        match w {
            FORCE => ga[VELOCITY] >= 0.0 || gb[VELOCITY] >= 0.0,
            VELOCITY => self.kind == ModelKind::Mcm && (ga[FORCE] <= 0.0 || gb[FORCE] <= 0.0),
            _ => true,
        }
    }

    /// The event functions that change sign between `ga` and `gb` and can be events.
    fn changes(&self, ga: &Events, gb: &Events) -> impl Iterator<Item = usize> + '_ {
        let (ga, gb) = (*ga, *gb);
        (0..EVENTS).filter(move |&w| crosses(w, ga[w], gb[w]) && self.matters(w, &ga, &gb))
    }

    /// The event functions' rates `dg/dT` at `(t, y)` along the flow, on the branch `frozen`
    /// where given: `V'` (NDBWSHCCM) or `V' + σ F'` (NDBWMCM), `Z'`, `F'` or `-V'` for
    /// `max(F, -V)`, `F'` and `V'`, with `F' = F_Y Y' + F_Z Z' + F_V V'`.
    fn event_rates(&self, t: Dd, y: &DdState, frozen: Option<f64>) -> Events {
        let (k, d) = (&self.k, self.rhs_on(t, y, frozen));
        // d(|s|^(p-1) s)/ds = p |s|^(p-1), 1 for p = 1 at s = 0 too.
        let slope = |s: Dd| {
            if k.p == 1.0 {
                Dd::from(1.0)
            } else {
                pow_abs_ln(ln_abs(s), k.p - 1.0) * k.p
            }
        };
        let (sy, sz) = (slope(y[1]), slope(y[2]));
        let mut f_y = -(sy * k.kappa);
        let f_z = -(sz * (1.0 - k.kappa));
        let mut f_v = Dd::from(0.0);
        if self.kind == ModelKind::Shccm {
            // F carries -σ |Y|^p V: d|Y|^p/dY = p |Y|^(p-1) sgn(Y).
            f_y -= copysign(sy, y[1]) * y[3] * k.sigma;
            f_v = -(pow_abs_ln(ln_abs(y[1]), k.p) * k.sigma);
        }
        let f_dot = f_y * d[1] + f_z * d[2] + f_v * d[3];
        let rate = match self.kind {
            ModelKind::Shccm => d[3],
            ModelKind::Mcm => d[3] + f_dot * k.sigma,
        };
        let (f, v) = (self.force_and_ln_z(y).0, -y[3]);
        [rate, d[2], if f > v { f_dot } else { -d[3] }, f_dot, d[3]]
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

/// The double-double run of a nondimensional model `kind` with parameters `k` under `input`,
/// as an [`Impact`] whose state is `state_of` the run's `(R, Y, Z, V)`; `None` where the input
/// has no double-double form.
pub(crate) fn run_model<I: Input + ?Sized, const N: usize>(
    (kind, k, input): (ModelKind, Nondim, &I),
    ext: Extrapolation,
    settings: &Settings,
    state_of: impl Fn([f64; 4]) -> State<N>,
) -> Option<Result<Impact<N>, DdFailure>> {
    input.at_dd(Dd::from(0.0))?;
    let m = Model { kind, k, u: input };
    Some(
        impact(&m, ext, settings.max_steps, settings.t_max).map(|r| {
            let stats = Stats {
                rhs_evals: r.evals,
                accepted: r.steps,
                rejected: r.rejected,
                events: r.kinks + 1,
                jacobians: 0,
            };
            let end = (
                Some(r.t_s.hi()),
                r.y[3].hi().max(0.0),
                state_of(r.y.map(|v| v.hi())),
            );
            Impact::unchecked(end, stats, ext.rtol).with(|c| c.double_double = true)
        }),
    )
}

/// A located event: which function, the time from the step's start and the state there.
struct Crossing {
    /// 0 and 1: the kink functions; [`SEPARATED`]: the separation.
    which: usize,
    tau: Dd,
    y: DdState,
    /// The sign of the event function just after the crossing.
    sign_after: f64,
}

/// A run's fixed parts: the model, the method, and the counter of evaluations.
struct Run<'m, 'a, I: ?Sized> {
    m: &'m Model<'a, I>,
    ext: Extrapolation,
    evals: u64,
}

impl<I: Input + ?Sized> Run<'_, '_, I> {
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

    /// One step as [`Self::step`] off the branch, `None` where it is abandoned as unstable
    /// ([`Extrapolation::try_step`]).
    fn try_step(&mut self, (t, y, f0): (Dd, &DdState, &DdState), h: Dd) -> Option<DdTrial<4>> {
        match self.ext.try_step(self.m, t, y, f0, h) {
            Ok(trial) => {
                self.evals += trial.evals;
                Some(trial)
            }
            Err(evals) => {
                self.evals += evals;
                None
            }
        }
    }

    /// The event functions at the state `h` after the start `at` (one step).
    fn events_after(&mut self, at: (Dd, &DdState, &DdState), h: Dd) -> Events {
        let y = self.step(at, h, None).y;
        self.m.events(&y)
    }

    /// The first event inside the accepted step `[t, t + h]`, if any. `after[w]`: kink
    /// function `w` was located at `t` and is on the side of this sign just after it (its value
    /// at `t` is rounding noise).
    ///
    /// The event functions are scanned at the finest midpoint sequence's states (every
    /// `h / 2k`), so that an excursion shorter than the step is seen. Those states are only of
    /// second order, and in a stiff step they can be off by more than a small value of the
    /// function, so a sign change is confirmed by accurate states before it is located, and
    /// each accurate value is compared with the last one before it: a sign change the samples
    /// placed in the wrong interval, or hid, is still found between two accurate values.
    fn first_event(
        &mut self,
        (t, y, f0): (Dd, &DdState, &DdState),
        h: Dd,
        trial: &DdTrial<4>,
        after: [Option<f64>; 2],
    ) -> Option<Crossing> {
        let n = trial.samples.len() + 1;
        let g0 = self.events_at_start(y, after);
        // The last accurate point, and the last sample (accurate where `exact`).
        let mut exact_at = (Dd::from(0.0), g0);
        let (mut a, mut ga, mut exact) = (exact_at.0, g0, true);
        for i in 1..=n {
            let b = h * (i as f64 / n as f64);
            let last = i == n;
            let gb = self.m.events(if last {
                &trial.y
            } else {
                &trial.samples[i - 1]
            });
            let suspect = |g: &Events| self.m.changes(g, &gb).next().is_some();
            if !(suspect(&ga) || (last && suspect(&exact_at.1))) {
                (a, ga, exact) = (b, gb, last);
                continue;
            }
            // Accurate values at both ends of the interval, each checked against the last
            // accurate value before it.
            if !exact {
                let at_a = (a, self.events_after((t, y, f0), a));
                if let Some(c) = self.first_between((t, y, f0), exact_at, at_a) {
                    return Some(c);
                }
                exact_at = at_a;
            }
            let gb = if last {
                gb
            } else {
                self.events_after((t, y, f0), b)
            };
            if let Some(c) = self.first_between((t, y, f0), exact_at, (b, gb)) {
                return Some(c);
            }
            exact_at = (b, gb);
            (a, ga, exact) = (b, gb, true);
        }
        None
    }

    /// The first event between the accurate values at `lo` and `hi` (times from the step's
    /// start), if any.
    fn first_between(
        &mut self,
        at: (Dd, &DdState, &DdState),
        lo: (Dd, Events),
        hi: (Dd, Events),
    ) -> Option<Crossing> {
        let m = self.m;
        m.changes(&lo.1, &hi.1)
            .filter_map(|w| self.event(at, (lo.0, &lo.1), (hi.0, &hi.1), w))
            .min_by(|p, q| p.tau.partial_cmp(&q.tau).expect("finite times"))
    }

    /// A kink inside a rejected step `[t, t + h]`: the first sign change of a kink function
    /// among the trial's samples (before the kink they are as good as an accepted step's),
    /// confirmed by accurate steps to both ends of its interval, each accepted by its own
    /// error estimate (to the far end on the branch before the kink, [`Frozen`], so that the
    /// step is smooth), and located as in [`Self::first_event`]. The kink spoils the error
    /// estimate of every step across it; without this the step size creeps up to the kink in
    /// a dozen rejected and shrinking steps. `None` where the samples show no kink function
    /// changing sign, or the confirmation fails: the step is then shrunk as usual.
    fn kink_in_rejected(
        &mut self,
        at: (Dd, &DdState, &DdState),
        h: Dd,
        trial: &DdTrial<4>,
        after: [Option<f64>; 2],
    ) -> Option<Crossing> {
        let n = trial.samples.len() + 1;
        let g0 = self.events_at_start(at.1, after);
        let mut ga = g0;
        // The first interval with a sign change, where it is a kink function's alone.
        let m = self.m;
        let (i, w) = (1..n).find_map(|i| {
            let gb = m.events(&trial.samples[i - 1]);
            let mut changed = m.changes(&ga, &gb);
            let first = changed.next().map(|w| (w, changed.next().is_none()));
            ga = gb;
            first.map(|w| (i, w))
        })?;
        let (w, alone) = w;
        if w >= SEPARATED || !alone {
            return None;
        }
        let (a, b) = (h * ((i - 1) as f64 / n as f64), h * (i as f64 / n as f64));
        let ga = if i == 1 {
            g0
        } else {
            let ta = self.step(at, a, None);
            let ga = self.m.events(&ta.y);
            if ta.err > 1.0 || self.m.changes(&g0, &ga).next().is_some() {
                return None;
            }
            ga
        };
        let frozen = (w == 0).then(|| ga[0].hi().signum());
        let tb = self.step(at, b, frozen);
        let gb = self.m.events(&tb.y);
        let others = self.m.changes(&ga, &gb).any(|v| v != w);
        if tb.err > 1.0 || others || !crosses(w, ga[w], gb[w]) {
            return None;
        }
        self.event(at, (a, &ga), (b, &gb), w)
    }

    /// The event where function `which` changes sign between the accurate values `lo` and
    /// `hi`: its root, located. A root of `F` or `V` is an event only where the bodies are
    /// separated past it (then it is the separation). A root where they leave the separated
    /// region (`V` falling with `F <= 0`, `F` rising with `V >= 0`) means that they entered it
    /// after `lo`, inside the same sample interval: the separation is then located between `lo`
    /// and a state just before the root (case 23291 of the stress sweep's seed 1).
    fn event(
        &mut self,
        at: (Dd, &DdState, &DdState),
        lo: (Dd, &Events),
        hi: (Dd, &Events),
        which: usize,
    ) -> Option<Crossing> {
        let c = self.locate(at, (lo.0, lo.1[which]), (hi.0, hi.1[which]), which);
        let g = self.m.events(&c.y);
        let velocity = which == VELOCITY || (which == 0 && self.m.kind == ModelKind::Shccm);
        let left = (velocity && c.sign_after < 0.0 && g[FORCE] <= 0.0)
            || (which == FORCE && c.sign_after > 0.0 && g[VELOCITY] >= 0.0);
        if left && lo.1[SEPARATED] > 0.0 {
            let before = c.tau - self.width(hi.0) * 2.0;
            let g_before = self.events_after(at, before)[SEPARATED];
            if g_before <= 0.0 {
                let sep = (lo.1[SEPARATED], g_before);
                return Some(self.locate(at, (lo.0, sep.0), (before, sep.1), SEPARATED));
            }
        }
        if which < FORCE {
            Some(c)
        } else {
            (g[SEPARATED] <= 0.0).then_some(Crossing {
                which: SEPARATED,
                ..c
            })
        }
    }

    /// How close to a root [`Self::locate`] gets in a step of length `end`: `max(rtol 1e-4,
    /// 2^-100) |end|`. The trial states carry rounding errors of about 1e-22 (the midpoint rule
    /// amplifies the stiff components' rounding before the extrapolation cancels it), so the
    /// root is sought to `rtol 1e-4` of the step: its error then moves the state by far less
    /// than the step's tolerance, and the iteration stops before it reads that noise.
    fn width(&self, end: Dd) -> f64 {
        end.hi().abs() * (self.ext.rtol * 1e-4).max(2f64.powi(-100))
    }

    /// The event functions at a step's start `y`; a kink function located there
    /// (`after[w]`) is given the sign it has just after its root (its value is noise).
    fn events_at_start(&self, y: &DdState, after: [Option<f64>; 2]) -> Events {
        let mut g = self.m.events(y);
        for (w, s) in after.iter().enumerate() {
            if let Some(s) = s {
                g[w] = Dd::from(s * f64::MIN_POSITIVE);
            }
        }
        g
    }

    /// The root of event function `which` in `(a, b)`, on the states `y(t + τ)` of single
    /// extrapolation steps, by Newton's method with the function's rate from the right-hand
    /// side ([`Model::event_rates`]) where its iterate stays inside the bracket, and by the
    /// Illinois method where not. Returns the state on the far side of the root (where the
    /// event has happened), within `max(rtol 1e-4, 2^-100) |b|` in `τ` of it.
    fn locate(
        &mut self,
        (t, y, f0): (Dd, &DdState, &DdState),
        (mut a, mut fa): (Dd, Dd),
        (mut b, mut fb): (Dd, Dd),
        which: usize,
    ) -> Crossing {
        let end = b;
        let sign_after = -fa.hi().signum();
        // A root of the rate (function 0) is searched for on the branch before it.
        let frozen = (which == 0).then(|| fa.hi().signum());
        let mut far = (b, None);
        // Which end the last Illinois iteration replaced: Illinois halves the other end's
        // value when the same end is replaced twice in a row, so that regula falsi does not
        // stall.
        let mut last_far = None;
        let width = self.width(end);
        let mut newton = None;
        // The bracket's length one and two iterations back. At a root of high multiplicity
        // (the force is `|X|^p` near `X = 0`, `p` up to 10) Newton's and the secant's steps
        // each cover a fixed small fraction of the distance, and 300 of them can stop 1e-10
        // short (case 15700 of the stress sweep's seed 4): where two iterations have not
        // halved the bracket, the next bisects it.
        let mut spans = [f64::INFINITY; 2];
        for _ in 0..300 {
            let span = (b - a).abs().hi();
            if span <= width {
                break;
            }
            let slow = span > 0.5 * spans[1];
            // After a bisection the next two iterations are judged afresh.
            spans = [span, if slow { f64::INFINITY } else { spans[0] }];
            let c = match newton {
                _ if slow => (a + b) * 0.5,
                Some(c) => c,
                None => regula_falsi((a, fa), (b, fb)),
            };
            let yc = self.step((t, y, f0), c, frozen).y;
            let fc = self.m.events(&yc)[which];
            let on_far_side = crosses(which, fa, fc) || (which != SEPARATED && fc == 0.0);
            // Newton's step from `c`, taken where it stays inside the bracket.
            let dc = fc / self.m.event_rates(t + c, &yc, frozen)[which];
            self.evals += 1;
            if on_far_side {
                far = (c, Some(yc));
                if newton.is_none() && last_far == Some(true) {
                    fa *= 0.5;
                }
                (b, fb) = (c, fc);
                if dc.hi().abs() <= 0.5 * width {
                    break;
                }
            } else {
                if newton.is_none() && last_far == Some(false) {
                    fb *= 0.5;
                }
                (a, fa) = (c, fc);
            }
            last_far = newton.is_none().then_some(on_far_side);
            newton = newton_aim(c, dc, width, (a, b));
        }
        let (tau, y) = match far {
            (tau, Some(y)) => (tau, y),
            (tau, None) => (tau, self.step((t, y, f0), tau, frozen).y),
        };
        Crossing {
            which,
            tau,
            y,
            sign_after,
        }
    }
}

/// The regula falsi iterate of the bracket `(a, b)` with values `fa`, `fb`; its midpoint
/// where the secant leaves the bracket.
fn regula_falsi((a, fa): (Dd, Dd), (b, fb): (Dd, Dd)) -> Dd {
    let c = (a * fb - b * fa) / (fb - fa);
    if (c - a).hi() * (c - b).hi() >= 0.0 || !c.hi().is_finite() {
        (a + b) * 0.5
    } else {
        c
    }
}

/// Newton's next iterate from `c` with step `dc`, where it lies inside the bracket `(a, b)`.
/// Near the root (`|dc| <= width`) it aims half a width past it, so that the iterate lands on
/// the far side.
fn newton_aim(c: Dd, dc: Dd, width: f64, (a, b): (Dd, Dd)) -> Option<Dd> {
    let past = if dc.hi().abs() <= width {
        0.5 * width
    } else {
        0.0
    };
    let aim = c - dc + past;
    let inside = (aim - a).hi() * (aim - b).hi() < 0.0 && aim.hi().is_finite();
    inside.then_some(aim)
}

/// Whether `a` and `b` lie strictly on opposite sides of 0 (for the separation, `which = 2`,
/// whether `b` has reached `<= 0` from `a > 0`).
fn crosses(which: usize, a: Dd, b: Dd) -> bool {
    if which == SEPARATED {
        a > 0.0 && b <= 0.0
    } else {
        (a > 0.0 && b < 0.0) || (a < 0.0 && b > 0.0)
    }
}

/// The step size factor after a step abandoned as unstable ([`Extrapolation::try_step`]), as
/// in ODEX.
const UNSTABLE: f64 = 0.5;

/// `h` scaled by `factor` after a rejected step at `t`.
///
/// # Errors
/// [`DdFailure::StepSizeTooSmall`] below `1e-28 max(1, T)`.
fn shrunk(h: Dd, factor: f64, t: Dd) -> Result<Dd, DdFailure> {
    let h = h * factor;
    if h.hi() < 1e-28 * t.hi().max(1.0) {
        return Err(DdFailure::StepSizeTooSmall(t.hi()));
    }
    Ok(h)
}

/// Whether a run at step `steps` and time `t` is within its budgets `max_steps` and `t_max`.
///
/// # Errors
/// [`DdFailure::TooManySteps`] or [`DdFailure::NoSeparation`] where it is not.
fn within_budget((steps, max_steps): (u64, u64), (t, t_max): (Dd, f64)) -> Result<(), DdFailure> {
    if steps >= max_steps {
        return Err(DdFailure::TooManySteps);
    }
    if t.hi() > t_max {
        return Err(DdFailure::NoSeparation);
    }
    Ok(())
}

/// Integrates one impact of `m` from contact (`V(0) = -1`, every other state 0) to the
/// separation with `ext`, in at most `max_steps` steps and by `t_max`.
///
/// # Errors
/// [`DdFailure`] where the run cannot reach the separation.
pub(crate) fn impact<I: Input + ?Sized>(
    m: &Model<'_, I>,
    ext: Extrapolation,
    max_steps: u64,
    t_max: f64,
) -> Result<DdRun, DdFailure> {
    let zero = Dd::from(0.0);
    let mut run = Run { m, ext, evals: 0 };
    let (mut t, mut y) = (zero, [zero, zero, zero, Dd::from(-1.0)]);
    let (mut h, mut steps, mut rejected, mut kinks) = (Dd::from(1e-6), 0, 0, 0);
    // The kink function located at `t`, with its sign just after (none at contact: `Z = 0`
    // there exactly, so no sign change is read from it).
    let mut after = [None; 2];
    // After a rejected step the next may not grow (Hairer, Nørsett & Wanner I, II.4): in stiff
    // stretches the step size is held by stability, and growth right after a rejection is
    // mostly rejected again.
    let mut just_rejected = false;
    loop {
        within_budget((steps, max_steps), (t, t_max))?;
        let f0 = m.rhs(t, &y);
        run.evals += 1;
        let Some(trial) = run.try_step((t, &y, &f0), h) else {
            rejected += 1;
            just_rejected = true;
            h = shrunk(h, UNSTABLE, t)?;
            continue;
        };
        let factor = ext.factor(trial.err);
        let c = if trial.err.is_nan() || trial.err > 1.0 {
            rejected += 1;
            match run.kink_in_rejected((t, &y, &f0), h, &trial, after) {
                // The step to the kink counts as one.
                Some(c) => {
                    steps += 1;
                    c
                }
                None => {
                    just_rejected = true;
                    h = shrunk(h, factor, t)?;
                    continue;
                }
            }
        } else {
            steps += 1;
            let grow = !just_rejected;
            just_rejected = false;
            match run.first_event((t, &y, &f0), h, &trial, after) {
                Some(c) => c,
                None => {
                    (t, y) = (t + h, trial.y);
                    after = [None; 2];
                    h *= if grow { factor } else { factor.min(1.0) };
                    continue;
                }
            }
        };
        (t, y) = (t + c.tau, c.y);
        if c.which == SEPARATED {
            break;
        }
        after = [0, 1].map(|w| (c.which == w).then_some(c.sign_after));
        kinks += 1;
        // A kink can coincide with the separation (Z = X = 0 where an elastic contact ends);
        // the separation's own crossing starts from `> 0`.
        if m.events(&y)[SEPARATED] <= 0.0 {
            break;
        }
    }
    Ok(DdRun {
        t_s: t,
        y,
        steps,
        rejected,
        evals: run.evals,
        kinks,
    })
}

#[cfg(test)]
mod tests;

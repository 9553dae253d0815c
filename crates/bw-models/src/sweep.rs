//! Speed sweeps by verified piecewise Chebyshev interpolation.
//!
//! Over a range of impact speeds without a change of outcome, `e(v0)` and `t_s(v0)` are smooth
//! (the base map `P(P*, u, v0)` and Table 1 are smooth in `v0 > 0`, and a transversal crossing
//! of a non-smooth point moves smoothly with the parameters), so a sweep of thousands of speeds
//! needs the impact at a few dozen. [`plan`] decides, for each speed of a sweep, whether its
//! values come from an interpolant or must be simulated:
//!
//! * The speeds are split into pieces of `u = ln v0`. On each piece the impact is evaluated at
//!   the Chebyshev-Lobatto points of degree 16, 32 and 64 in turn (nested: each degree adds
//!   only the new points).
//! * A degree is accepted when the interpolant of half that degree predicted every new point
//!   to within the tolerance (absolute in `e`, relative to the piece's largest `|t_s|` in
//!   `t_s`), and then a simulation at the sweep speed in the widest gap between the points
//!   agrees with it as well. That largest difference is the piece's error estimate.
//! * A piece that does not converge by degree 64 is halved, unless its last doubling did not
//!   halve an error within a thousand tolerances (the simulations' own noise is above the
//!   tolerance): then its speeds are simulated. Where an evaluation is not a smooth value (no separation, a failure), the
//!   piece gives way to its runs of smooth points and the gaps where the change lies.
//! * A piece must hold four times its points in speeds (136 for degree 32, 264 for 64), else
//!   its speeds are simulated one by one; and the evaluations never exceed a quarter of the
//!   sweep's speeds (the pieces still being fitted then are simulated instead), so at worst a
//!   sweep costs 1.25 times its speeds' simulations.
//! * Each range left to simulation after trials is recorded with the reason ([`GivenUp`]:
//!   noise, too few speeds for the pieces a kink needs, values that are not smooth, or the
//!   budget), so that a caller can say which setting would help.
//!
//! The error estimate is the interpolant's distance from the simulations, not from the exact
//! solution: an interpolated value carries the simulations' own error as well (measured on
//! random parameters in BENCHMARKS.md: it is as accurate as the simulations it replaces).
//!
//! ```
//! use bw_models::sweep::{plan, Row, SweepSettings};
//! // 2,000 speeds of a smooth function: a few dozen evaluations instead.
//! let speeds: Vec<f64> = (0..2000).map(|i| 0.1 + 5.9 * i as f64 / 1999.0).collect();
//! let f = |v: f64| [1.0 / (1.0 + v), v.sqrt()];
//! let mut evaluations = 0;
//! let sweep = plan(&speeds, &SweepSettings { tolerance: 1e-12 }, |vs| {
//!     evaluations += vs.len();
//!     vs.iter().map(|&v| Some(f(v))).collect()
//! });
//! assert!(evaluations < 200);
//! for (row, &v) in sweep.rows.iter().zip(&speeds) {
//!     if let Row::Interpolated { values, .. } = row {
//!         assert!((values[0] - f(v)[0]).abs() < 1e-12);
//!     }
//! }
//! ```

use std::f64::consts::PI;

/// The values a sweep interpolates for one speed: `[e, t_s]` of a separated impact.
pub type Values = [f64; 2];

/// Errors below this multiple of the tolerance that a doubling does not halve are taken for the
/// simulations' noise (at the default tolerance, the solver's rtol, the simulations' errors are
/// 1-100 times it).
const NOISE: f64 = 1e3;

/// Degrees tried on a piece, in turn.
const DEGREES: [usize; 3] = [16, 32, 64];

/// The fewest speeds for which [`plan`] tries an interpolant (a piece must pay for its points):
/// with fewer, every speed is to be simulated and `evaluate` is not called.
pub const MIN_SPEEDS: usize = pays(DEGREES[1]);

/// Settings of a sweep's interpolation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepSettings {
    /// The largest error admitted in an interpolated value: absolute in `e`, relative to the
    /// largest `|t_s|` of its piece in `t_s`.
    pub tolerance: f64,
}

impl Default for SweepSettings {
    /// A tolerance of 1e-11, a tenth of the default [`crate::Settings::e_tol`] (as a scene's
    /// `[sweep].tolerance` defaults to a tenth of its `[solver].e_tol`).
    fn default() -> Self {
        SweepSettings { tolerance: 1e-11 }
    }
}

/// Where one speed's values come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Row {
    /// From the interpolant of a piece.
    Interpolated {
        /// `[e, t_s]`.
        values: Values,
        /// The piece's error estimate (in the tolerance's terms), at most the tolerance.
        estimate: f64,
        /// Index of the piece in [`Sweep::pieces`].
        piece: usize,
    },
    /// Simulate this speed (it may have been simulated already, as a check).
    Simulate,
}

/// A piece of the sweep served by one interpolant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// Lowest and highest speed of the piece's interval (m/s or the sweep's unit).
    pub from: f64,
    /// See `from`.
    pub to: f64,
    /// Degree of the interpolant.
    pub degree: usize,
    /// Speeds of the sweep in the piece.
    pub speeds: usize,
    /// The largest difference seen between the interpolant of half the degree and the new
    /// points, and between the interpolant and the check simulation.
    pub estimate: f64,
}

/// Why [`plan`] left speeds it tried to interpolate to be simulated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum GaveUp {
    /// Doubling the degree no longer halved an error within a thousand tolerances: the values
    /// are smooth only to about the tolerance (the simulations' own error).
    Noise,
    /// The values change too sharply somewhere (a kink, a steep stretch) for the pieces the
    /// speeds pay for: halving would leave pieces of fewer than [`MIN_SPEEDS`] speeds.
    TooFewSpeeds,
    /// Points without smooth values (no separation, a failure) split the range into pieces too
    /// short to pay for their points.
    NotSmooth,
    /// The evaluations reached a quarter of the sweep's speeds first.
    Budget,
}

impl GaveUp {
    /// The name in outputs: `"noise"`, `"too-few-speeds"`, `"not-smooth"` or `"budget"`.
    pub fn name(self) -> &'static str {
        match self {
            GaveUp::Noise => "noise",
            GaveUp::TooFewSpeeds => "too-few-speeds",
            GaveUp::NotSmooth => "not-smooth",
            GaveUp::Budget => "budget",
        }
    }
}

/// A range of speeds that [`plan`] tried and left to be simulated (wholly or in part: the
/// pieces it gave way to, if any, are among [`Sweep::pieces`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GivenUp {
    /// Lowest and highest speed of the range.
    pub from: f64,
    /// See `from`.
    pub to: f64,
    /// Why.
    pub why: GaveUp,
}

/// What [`plan`] decided.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// One row per speed, in the order given.
    pub rows: Vec<Row>,
    /// The pieces served by interpolants.
    pub pieces: Vec<Piece>,
    /// Evaluations made (points and checks, including those of pieces later halved).
    pub evaluations: usize,
    /// The ranges tried and given up, in the order they were given up.
    pub given_up: Vec<GivenUp>,
}

/// Decides, for every speed in `speeds` (any order, repeats allowed; a speed that is not finite
/// and positive is left to be simulated), whether its values come from an interpolant or from
/// a simulation, calling `evaluate` with batches of
/// speeds (evaluate them in parallel if you like: the result depends only on the values).
/// `evaluate` returns `None` for a speed whose impact has no smooth values (no separation, a
/// failure); such speeds are simulated, and so are those near them.
pub fn plan<F>(speeds: &[f64], settings: &SweepSettings, evaluate: F) -> Sweep
where
    F: FnMut(&[f64]) -> Vec<Option<Values>>,
{
    let plan = plan_lazily(speeds, settings, evaluate);
    Sweep {
        rows: speeds.iter().map(|&s| plan.row(s)).collect(),
        pieces: plan.pieces,
        evaluations: plan.evaluations,
        given_up: plan.given_up,
    }
}

/// What [`plan_lazily`] decided: the pieces and their interpolants, each speed's row read when
/// it is needed ([`Plan::row`]), so that a sweep of any size holds no more than its pieces.
pub struct Plan {
    /// The pieces served by interpolants.
    pub pieces: Vec<Piece>,
    /// Evaluations made (points and checks, including those of pieces later halved).
    pub evaluations: usize,
    /// The ranges tried and given up, in the order they were given up.
    pub given_up: Vec<GivenUp>,
    fitted: Vec<Active>,
    /// The sweep's speeds that were evaluated (piece ends and checks), sorted: their rows are
    /// simulations.
    simulated: Vec<f64>,
}

impl Plan {
    /// The row of `speed`, a speed of the sweep planned: [`Row::Simulate`] where it was
    /// evaluated or no piece covers it, its piece's interpolant otherwise.
    pub fn row(&self, speed: f64) -> Row {
        if (self.simulated)
            .binary_search_by(|x| x.total_cmp(&speed))
            .is_ok()
        {
            return Row::Simulate;
        }
        let x = speed.ln();
        match self.fitted.iter().position(|p| p.covers(x)) {
            Some(k) => Row::Interpolated {
                values: self.fitted[k].at(x),
                estimate: self.fitted[k].estimate,
                piece: k,
            },
            None => Row::Simulate,
        }
    }
}

/// [`plan`], the rows left to [`Plan::row`]: nothing that grows with the sweep is kept, and
/// while it is planned only a sorted copy of speeds not given in increasing order.
pub fn plan_lazily<F>(speeds: &[f64], settings: &SweepSettings, mut evaluate: F) -> Plan
where
    F: FnMut(&[f64]) -> Vec<Option<Values>>,
{
    // The distinct speeds in increasing order: those given, where they already are.
    let increasing = (speeds.windows(2)).all(|w| w[0] < w[1])
        && speeds.iter().all(|x| x.is_finite() && *x > 0.0);
    let v: std::borrow::Cow<[f64]> = if increasing {
        speeds.into()
    } else {
        let mut v: Vec<f64> = (speeds.iter().copied())
            .filter(|x| x.is_finite() && *x > 0.0)
            .collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v.into()
    };
    let u = Logs(&v);
    let mut sweep = Plan {
        pieces: Vec::new(),
        evaluations: 0,
        given_up: Vec::new(),
        fitted: Vec::new(),
        simulated: Vec::new(),
    };
    let budget = speeds.len() / 4;
    // Sweep speeds that were evaluated (piece ends and checks): their rows are simulations.
    let mut simulated: Vec<f64> = Vec::new();
    let mut active: Vec<Active> = Active::start(u, 0, u.len()).into_iter().collect();
    let mut fitted: Vec<Active> = Vec::new();
    while !active.is_empty() {
        let requests: Vec<Vec<Request>> = active.iter().map(|p| p.requests(u)).collect();
        let batch: Vec<f64> = requests
            .iter()
            .flatten()
            .map(|r| r.sweep_index.map_or(r.u.exp(), |i| v[i]))
            .collect();
        if sweep.evaluations + batch.len() > budget {
            (sweep.given_up).extend(active.iter().map(|p| p.given_up(&v, GaveUp::Budget)));
            break;
        }
        simulated.extend(
            requests
                .iter()
                .flatten()
                .filter_map(|r| r.sweep_index.map(|i| v[i])),
        );
        let mut results = evaluate(&batch).into_iter();
        sweep.evaluations += batch.len();
        let mut next = Vec::new();
        for (mut piece, asked) in active.into_iter().zip(requests) {
            let got: Vec<Option<Values>> = results.by_ref().take(asked.len()).collect();
            match piece.absorb(u, &asked, &got, settings.tolerance) {
                Step::More => next.push(piece),
                Step::Done => {
                    sweep.pieces.push(piece.summary(&v));
                    fitted.push(piece);
                }
                Step::Replace(pieces, why) => {
                    if pieces.iter().map(|p| p.hi - p.lo).sum::<usize>() < piece.hi - piece.lo {
                        sweep.given_up.push(piece.given_up(&v, why));
                    }
                    next.extend(pieces);
                }
            }
        }
        active = next;
    }
    simulated.sort_by(f64::total_cmp);
    sweep.simulated = simulated;
    sweep.fitted = fitted;
    sweep
}

/// `u = ln v0` of the sorted speeds `v0`, computed where it is read: a sweep of any size keeps
/// no copy of them.
#[derive(Clone, Copy)]
struct Logs<'a>(&'a [f64]);

impl Logs<'_> {
    fn at(self, i: usize) -> f64 {
        self.0[i].ln()
    }

    fn len(self) -> usize {
        self.0.len()
    }

    /// The index in `lo..=hi` of the first `u` in `lo..hi` for which `before` is false
    /// (`before` true, then false, along the speeds).
    fn partition_point(self, lo: usize, hi: usize, before: impl Fn(f64) -> bool) -> usize {
        lo + self.0[lo..hi].partition_point(|&y| before(y.ln()))
    }
}

/// A speed a piece asks for: a point `u = ln v0`, or a speed of the sweep (its index in the
/// sorted speeds), which is then simulated at exactly that speed.
#[derive(Debug, Clone, Copy)]
struct Request {
    u: f64,
    sweep_index: Option<usize>,
}

/// The speeds a piece must hold to be fitted up to `degree`: four times its points and check,
/// so that interpolation saves at least three quarters of the simulations where it converges.
const fn pays(degree: usize) -> usize {
    4 * (degree + 2)
}

/// What a piece does after absorbing a batch.
enum Step {
    More,
    Done,
    /// Give way to these pieces (halves, or the runs of smooth points and the gaps); what they
    /// do not cover is simulated, for this reason.
    Replace(Vec<Active>, GaveUp),
}

/// A piece being fitted: the interval `[a, b]` of `u = ln v0` holding the sorted speeds
/// `u[lo..hi]`, its values at the Lobatto points of `degree`, and the check still to come.
struct Active {
    a: f64,
    b: f64,
    lo: usize,
    hi: usize,
    degree: usize,
    values: Vec<Values>,
    coefficients: Vec<Values>,
    scale: f64,
    estimate: f64,
    check: Option<f64>,
}

impl Active {
    /// A piece over `u[lo..hi]` if it holds enough speeds to pay for its first two degrees'
    /// points and its check four times over.
    fn start(u: Logs, lo: usize, hi: usize) -> Option<Active> {
        (hi - lo >= pays(DEGREES[1])).then(|| Active {
            a: u.at(lo),
            b: u.at(hi - 1),
            lo,
            hi,
            degree: 0,
            values: Vec::new(),
            coefficients: Vec::new(),
            scale: 0.0,
            estimate: 0.0,
            check: None,
        })
    }

    /// The speeds this piece needs next: the first degree's points (its ends are the piece's
    /// first and last speed), the points a doubling adds, or the check.
    fn requests(&self, u: Logs) -> Vec<Request> {
        let sweep = |i: usize| Request {
            u: u.at(i),
            sweep_index: Some(i),
        };
        if let Some(x) = self.check {
            return vec![sweep(self.nearest(u, x))];
        }
        let node = |k: usize, n: usize| Request {
            u: self.node(k, n),
            sweep_index: None,
        };
        match self.degree {
            0 => (0..=DEGREES[0])
                .map(|k| match k {
                    0 => sweep(self.hi - 1),
                    k if k == DEGREES[0] => sweep(self.lo),
                    k => node(k, DEGREES[0]),
                })
                .collect(),
            n => (1..=2 * n).step_by(2).map(|k| node(k, 2 * n)).collect(),
        }
    }

    /// Index of the speed of the piece nearest `x`.
    fn nearest(&self, u: Logs, x: f64) -> usize {
        let i = u.partition_point(self.lo, self.hi, |y| y < x);
        if i == self.hi || (i > self.lo && x - u.at(i - 1) < u.at(i) - x) {
            i - 1
        } else {
            i
        }
    }

    fn u_of(&self, x: f64) -> f64 {
        0.5 * (self.a + self.b) + 0.5 * (self.b - self.a) * x
    }

    fn x_of(&self, u: f64) -> f64 {
        (2.0 * u - (self.a + self.b)) / (self.b - self.a)
    }

    /// Takes the values at `asked` and decides what comes next.
    fn absorb(
        &mut self,
        u: Logs,
        asked: &[Request],
        got: &[Option<Values>],
        tolerance: f64,
    ) -> Step {
        let got: Vec<Option<Values>> = got
            .iter()
            .map(|v| v.filter(|v| v.iter().all(|x| x.is_finite())))
            .collect();
        if self.check.take().is_some() {
            let miss = got[0].map_or(f64::INFINITY, |v| self.miss(&self.at(asked[0].u), &v));
            self.estimate = self.estimate.max(miss);
            return if miss <= tolerance {
                Step::Done
            } else {
                Step::Replace(self.halves(u), GaveUp::TooFewSpeeds)
            };
        }
        let Some(got) = got.iter().copied().collect::<Option<Vec<Values>>>() else {
            return Step::Replace(self.smooth_runs(u, asked, &got), GaveUp::NotSmooth);
        };
        if self.degree == 0 {
            self.degree = DEGREES[0];
            self.values = got;
            self.refit();
            return Step::More;
        }
        // The half-degree interpolant's prediction of the new points measures its error.
        let before = self.estimate;
        self.estimate = got
            .iter()
            .zip(asked)
            .map(|(v, r)| self.miss(&self.at(r.u), v))
            .fold(0.0, f64::max);
        let old = std::mem::take(&mut self.values);
        self.degree *= 2;
        self.values = (0..=self.degree)
            .map(|k| if k % 2 == 0 { old[k / 2] } else { got[k / 2] })
            .collect();
        self.refit();
        if self.estimate <= tolerance {
            self.check = Some(self.widest_gap());
            Step::More
        } else if self.degree < DEGREES[2] && self.hi - self.lo >= pays(2 * self.degree) {
            Step::More
        } else if before > 0.0 && self.estimate > 0.5 * before && self.estimate < NOISE * tolerance
        {
            // A doubling that did not halve an error this near the tolerance has met the
            // simulations' own noise: smaller pieces would not do better. (A larger error that
            // does not halve is a kink or a jump between the points, which halving isolates.)
            Step::Replace(Vec::new(), GaveUp::Noise)
        } else {
            Step::Replace(self.halves(u), GaveUp::TooFewSpeeds)
        }
    }

    /// The pieces left when some points have no smooth values: each run of smooth points
    /// (from its first to its last point), and each gap between a smooth and a non-smooth
    /// point (its speeds strictly between them), where the change lies. Speeds under runs of
    /// non-smooth points are simulated.
    fn smooth_runs(&self, u: Logs, asked: &[Request], got: &[Option<Values>]) -> Vec<Active> {
        let mut points: Vec<(f64, bool)> = asked
            .iter()
            .zip(got)
            .map(|(r, v)| (r.u, v.is_some()))
            .collect();
        if self.degree > 0 {
            // The points of the degree reached so far, all smooth.
            let n = 2 * self.degree;
            points.extend((0..=n).step_by(2).map(|k| (self.node(k, n), true)));
        }
        points.sort_by(|p, q| p.0.total_cmp(&q.0));
        let index = |x: f64| u.partition_point(self.lo, self.hi, |y| y < x);
        let after = |x: f64| u.partition_point(self.lo, self.hi, |y| y <= x);
        let mut pieces = Vec::new();
        let mut first = 0;
        for i in 0..points.len() {
            let (x, smooth) = points[i];
            let next = points.get(i + 1);
            if next.is_some_and(|p| p.1 == smooth) {
                continue;
            }
            if smooth && i > first {
                pieces.extend(Active::start(u, index(points[first].0), after(x)));
            }
            if let Some(&(y, _)) = next {
                pieces.extend(Active::start(u, after(x), index(y)));
            }
            first = i + 1;
        }
        pieces
    }

    /// Point `k` of the Lobatto points of degree `n` (the ends exactly the piece's ends).
    fn node(&self, k: usize, n: usize) -> f64 {
        match k {
            0 => self.b,
            k if k == n => self.a,
            k => self.u_of((PI * k as f64 / n as f64).cos()),
        }
    }

    /// The difference of two values in the tolerance's terms.
    fn miss(&self, a: &Values, b: &Values) -> f64 {
        (a[0] - b[0]).abs().max((a[1] - b[1]).abs() / self.scale)
    }

    /// Chebyshev coefficients of the values at the Lobatto points (with the end terms halved,
    /// so that the interpolant is `Σ c_j T_j`).
    fn refit(&mut self) {
        let n = self.degree;
        let cosines: Vec<f64> = (0..2 * n)
            .map(|m| (PI * m as f64 / n as f64).cos())
            .collect();
        let half = |k: usize| if k == 0 || k == n { 0.5 } else { 1.0 };
        self.coefficients = (0..=n)
            .map(|j| {
                let mut c = [0.0; 2];
                for (k, v) in self.values.iter().enumerate() {
                    let w = half(k) * cosines[(j * k) % (2 * n)];
                    c[0] += w * v[0];
                    c[1] += w * v[1];
                }
                c.map(|c| c * half(j) * 2.0 / n as f64)
            })
            .collect();
        self.scale = self
            .values
            .iter()
            .map(|v| v[1].abs())
            .fold(f64::MIN_POSITIVE, f64::max);
    }

    /// The interpolant at `u` (Clenshaw's recurrence).
    fn at(&self, u: f64) -> Values {
        let x = self.x_of(u);
        let (mut b1, mut b2) = ([0.0; 2], [0.0; 2]);
        for c in self.coefficients[1..].iter().rev() {
            let b = [0, 1].map(|q| 2.0 * x * b1[q] - b2[q] + c[q]);
            b2 = b1;
            b1 = b;
        }
        [0, 1].map(|q| self.coefficients[0][q] + x * b1[q] - b2[q])
    }

    /// The middle of the widest gap between the points (next to the centre).
    fn widest_gap(&self) -> f64 {
        let n = self.degree as f64;
        self.u_of((PI * (0.5 * n + 0.5) / n).cos())
    }

    /// The two halves of the piece that hold enough speeds to be fitted.
    fn halves(&self, u: Logs) -> Vec<Active> {
        let middle = 0.5 * (self.a + self.b);
        let split = u.partition_point(self.lo, self.hi, |x| x <= middle);
        [
            Active::start(u, self.lo, split),
            Active::start(u, split, self.hi),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    fn covers(&self, u: f64) -> bool {
        self.a <= u && u <= self.b
    }

    /// The record of giving the piece up, its ends the speeds themselves (`v`, sorted).
    fn given_up(&self, v: &[f64], why: GaveUp) -> GivenUp {
        GivenUp {
            from: v[self.lo],
            to: v[self.hi - 1],
            why,
        }
    }

    /// The piece's record, its ends the speeds themselves (`v`, sorted).
    fn summary(&self, v: &[f64]) -> Piece {
        Piece {
            from: v[self.lo],
            to: v[self.hi - 1],
            degree: self.degree,
            speeds: self.hi - self.lo,
            estimate: self.estimate,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn speeds(count: usize, from: f64, to: f64) -> Vec<f64> {
        (0..count)
            .map(|i| from + (to - from) * i as f64 / (count - 1) as f64)
            .collect()
    }

    /// Runs `plan` on `f`, counting evaluations, and checks every interpolated row against
    /// `f` itself: within `tolerance` (absolute in the first value, relative to the largest
    /// second value in the second) and within its own estimate.
    fn checked(vs: &[f64], tolerance: f64, f: impl Fn(f64) -> Option<Values>) -> Sweep {
        let mut count = 0;
        let sweep = plan(vs, &SweepSettings { tolerance }, |batch| {
            count += batch.len();
            batch.iter().map(|&v| f(v)).collect()
        });
        assert_eq!(count, sweep.evaluations);
        let scale = vs
            .iter()
            .filter_map(|&v| f(v))
            .map(|x| x[1].abs())
            .fold(0.0, f64::max);
        for (row, &v) in sweep.rows.iter().zip(vs) {
            if let Row::Interpolated {
                values, estimate, ..
            } = row
            {
                let want = f(v).expect("interpolated only where smooth");
                let miss = (values[0] - want[0])
                    .abs()
                    .max((values[1] - want[1]).abs() / scale);
                assert!(miss <= tolerance, "v0 = {v}: {values:?} vs {want:?}");
                assert!(*estimate <= tolerance);
            }
        }
        sweep
    }

    fn interpolated(s: &Sweep) -> usize {
        s.rows
            .iter()
            .filter(|r| matches!(r, Row::Interpolated { .. }))
            .count()
    }

    #[test]
    fn a_smooth_sweep_takes_a_few_dozen_evaluations() {
        let vs = speeds(20_000, 0.1, 6.0);
        // Analytic in ln v0 in a strip, with a pole near v0 = 0 as e(v0) has its singularity.
        let f = |v: f64| Some([0.9 - 0.2 * v / (1.0 + v), 3.0 + (0.3 * v).sin()]);
        let s = checked(&vs, 1e-12, f);
        assert!(s.evaluations <= 3 * 65 + 3, "{}", s.evaluations);
        assert!(interpolated(&s) >= 19_900, "{}", interpolated(&s));
        assert_eq!(s.given_up, []);
    }

    #[test]
    fn a_kink_is_simulated_around_and_interpolated_away_from() {
        let vs = speeds(5_000, 0.5, 4.0);
        let f = |v: f64| Some([(v - 1.3f64).abs().powf(1.5) + v, 2.0 + v]);
        let s = checked(&vs, 1e-10, f);
        let near = vs.iter().position(|&v| v >= 1.3).unwrap();
        assert_eq!(s.rows[near], Row::Simulate);
        assert!(interpolated(&s) > 4_000, "{}", interpolated(&s));
        assert!(s.evaluations < 1_250, "{}", s.evaluations);
        // The pieces given up hold the kink, and were given up for want of speeds.
        assert!(s.given_up.iter().all(|g| g.why == GaveUp::TooFewSpeeds));
        assert!(s.given_up.iter().any(|g| g.from < 1.3 && 1.3 < g.to));
    }

    #[test]
    fn a_kink_in_a_short_sweep_is_given_up_for_want_of_speeds() {
        // 200 speeds hold one piece of degree 32, and only one half: the kink leaves all to
        // simulation, and the plan says why.
        let vs = speeds(200, 0.5, 10.0);
        let f = |v: f64| Some([(v - 2.97f64).abs().powf(2.1) + v, 2.0 + v]);
        let s = checked(&vs, 1e-11, f);
        assert_eq!(interpolated(&s), 0);
        assert_eq!(s.evaluations, 50);
        // The whole range, for want of speeds to halve it; its upper half (163 speeds) was
        // tried on until the budget ran out.
        let whole = GivenUp {
            from: 0.5,
            to: 10.0,
            why: GaveUp::TooFewSpeeds,
        };
        assert_eq!(s.given_up[0], whole);
        assert_eq!(s.given_up[1].why, GaveUp::Budget);
        assert_eq!(s.given_up.len(), 2);
    }

    #[test]
    fn speeds_without_smooth_values_are_simulated() {
        let vs = speeds(3_000, 0.1, 6.0);
        let f = |v: f64| (!(2.0..=2.5).contains(&v)).then(|| [1.0 / (1.0 + v), v]);
        let s = checked(&vs, 1e-12, f);
        for (row, &v) in s.rows.iter().zip(&vs) {
            if (2.0..=2.5).contains(&v) {
                assert_eq!(*row, Row::Simulate, "{v}");
            }
        }
        assert!(interpolated(&s) > 2_000, "{}", interpolated(&s));
        assert!(s.given_up.iter().any(|g| g.why == GaveUp::NotSmooth));
    }

    #[test]
    fn a_change_of_outcome_is_narrowed_down_and_the_rest_interpolated() {
        // 2,000 log-spaced speeds; below 1.18 no separation, as a contact that settles.
        let vs: Vec<f64> = (0..2_000)
            .map(|i| 0.05 * 60f64.powf(i as f64 / 1_999.0))
            .collect();
        let f = |v: f64| (v > 1.18).then(|| [0.5 + 0.1 * v.ln(), 3.0 - 0.2 * v]);
        let s = checked(&vs, 1e-12, f);
        let above = vs.iter().filter(|&&v| v > 1.25).count();
        assert!(
            interpolated(&s) > above * 9 / 10,
            "{} of {above}",
            interpolated(&s)
        );
        assert!(s.evaluations < 500, "{}", s.evaluations);
    }

    #[test]
    fn noise_above_the_tolerance_costs_at_most_a_quarter_more() {
        let vs = speeds(20_000, 0.1, 6.0);
        // Deterministic noise of a hundred tolerances, as a solver's error at the tolerance:
        // the piece stops at its first degree 64, without halving.
        let f = |v: f64| Some([v + 1e-10 * (1e4 * v).sin(), 1.0]);
        let s = checked(&vs, 1e-12, f);
        assert_eq!(interpolated(&s), 0);
        assert_eq!(s.evaluations, 65);
        let whole = GivenUp {
            from: 0.1,
            to: 6.0,
            why: GaveUp::Noise,
        };
        assert_eq!(s.given_up, [whole]);
        // Noise far above the tolerance, or growing with the speed, is halved; the budget
        // bounds the cost.
        for f in [
            |v: f64| Some([v + 1e-8 * (1e4 * v).sin(), 1.0]),
            |v: f64| Some([v + 1e-10 * v.powi(8) * (1e4 * v).sin(), 1.0]),
        ] {
            let s = checked(&vs, 1e-12, f);
            assert_eq!(interpolated(&s), 0);
            assert!(s.evaluations <= 20_000 / 4, "{}", s.evaluations);
            assert!(!s.given_up.is_empty());
        }
    }

    #[test]
    fn few_speeds_are_simulated_without_points() {
        let vs = speeds(135, 0.1, 6.0);
        let s = checked(&vs, 1e-12, |v| Some([v, v]));
        assert_eq!(s.evaluations, 0);
        assert!(s.rows.iter().all(|r| *r == Row::Simulate));
    }

    #[test]
    fn the_rows_do_not_depend_on_the_order_or_repeats_of_the_speeds() {
        let vs = speeds(1_000, 0.2, 5.0);
        let mut shuffled: Vec<f64> = (0..1_000).map(|i| vs[(i * 7919) % 1_000]).collect();
        shuffled.extend_from_slice(&vs[..10]);
        let odd = [0.0, -1.0, f64::NAN, f64::INFINITY];
        shuffled.extend_from_slice(&odd);
        let f = |v: f64| Some([v.sqrt(), 1.0 / v]);
        let (a, b) = (checked(&vs, 1e-12, f), checked(&shuffled, 1e-12, f));
        for (i, row) in b.rows.iter().enumerate().take(1_010) {
            let j = vs.iter().position(|&v| v == shuffled[i]).unwrap();
            assert_eq!(*row, a.rows[j]);
        }
        // Speeds that are not finite and positive are left to be simulated.
        assert!(b.rows[1_010..].iter().all(|r| *r == Row::Simulate));
        assert_eq!(a.evaluations, b.evaluations);
    }
}

//! Gragg-Bulirsch-Stoer extrapolation in double-double arithmetic, for integrations that
//! double precision cannot carry: where rounding errors of about 1e-16 in the right-hand side,
//! amplified along a long solution, decide the answer at the 1e-10 level.
//!
//! One step of size `H` runs the explicit midpoint rule with `n_j = 2, 4, ..., 2k` substeps and
//! extrapolates the results to `h = 0` in `h²` (Aitken-Neville; Hairer, Nørsett & Wanner I,
//! Sec. II.9). `T_kk` (order `2k`) is the result and `|T_kk - T_{k,k-1}|` the error estimate,
//! held below `atol + rtol max(|y|, |y_new|)` in every component. Its coefficients, the
//! substep sizes `H / n_j` and the weights `n_{j-l}² / (n_j² - n_{j-l}²)`, are computed in
//! double-double, so the method is exact to 32 digits where a Runge-Kutta tableau would be
//! limited to its coefficients' 16.
//!
//! A step whose midpoint rule is unstable is rejected whatever its error estimate says: where,
//! in the second sequence (`n = 4`), the derivative at the first Euler point differs from
//! `f(t, y)` by more than twice `f(t, y)`'s size (each scaled by the tolerance, root mean
//! square). This is ODEX's stability check (Hairer, Nørsett & Wanner I, Sec. II.9). For
//! `y' = λ y` it trips at `|λ H| = 8`, just past the extrapolated method's own stability
//! boundary at order 16 (`|T_88(λ H)| > 1` from `λ H = -7.3` on the negative real axis). ODEX
//! also checks the first sequence, which trips at `|λ H| = 4`: right for its lower orders
//! (the boundary is 2.8 at `k = 2` and 4.3 at `k = 4`), it would hold order 16's steps to half
//! their size. Without the check a step across a stiff component's fast transient can
//! overshoot in every sequence alike, and the extrapolants agree on a wrong state (case 22932
//! of the stress sweep's seed 10: `Z` from -0.3 to 2870 in one step, estimated at a third of
//! the tolerance). [`Extrapolation::try_step`] abandons such a step after its first
//! evaluations; [`Extrapolation::step`] completes it and reports its error as infinite.
//!
//! The driver (step size control, events) is the caller's: [`Extrapolation::step`] takes one
//! step and [`Extrapolation::factor`] says how to scale the next. A step also returns the
//! finest midpoint sequence's states at `t + i H / 2k` (second order), for a caller looking
//! for sign changes inside the step.

use crate::dd::Dd;

/// A right-hand side `y' = f(t, y)` in double-double.
pub trait DdSystem<const N: usize> {
    /// The derivative `f(t, y)`.
    fn rhs(&self, t: Dd, y: &[Dd; N]) -> [Dd; N];
}

impl<const N: usize, F: Fn(Dd, &[Dd; N]) -> [Dd; N]> DdSystem<N> for F {
    fn rhs(&self, t: Dd, y: &[Dd; N]) -> [Dd; N] {
        self(t, y)
    }
}

/// The method's settings: `k` midpoint sequences (order `2k`) and the tolerances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extrapolation {
    /// Number of midpoint sequences, at least 2 (order `2k`).
    pub k: usize,
    /// Relative tolerance per step.
    pub rtol: f64,
    /// Absolute tolerance per step.
    pub atol: f64,
}

/// One step's results.
#[derive(Debug, Clone, PartialEq)]
pub struct DdTrial<const N: usize> {
    /// `T_kk`, the state at `t + H`.
    pub y: [Dd; N],
    /// The finest midpoint sequence's states at `t + i H / 2k`, `i = 1, ..., 2k - 1` (second
    /// order).
    pub samples: Vec<[Dd; N]>,
    /// The error estimate in units of the tolerance: the step is accepted at `<= 1`. Infinite
    /// where the stability check failed.
    pub err: f64,
    /// Right-hand-side evaluations spent (not counting `f0`).
    pub evals: u64,
}

/// The sequence (from 0) whose first midpoint step is checked for stability (`n = 4`).
const STABILITY_SEQUENCE: usize = 1;

/// `y + h f`.
fn axpy<const N: usize>(y: &[Dd; N], h: Dd, f: &[Dd; N]) -> [Dd; N] {
    std::array::from_fn(|i| y[i] + h * f[i])
}

impl Extrapolation {
    /// Order 16 (`k = 8`) at the given tolerances.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self { k: 8, rtol, atol }
    }

    /// One step of size `h` from `(t, y)`, with `f0 = f(t, y)`, completed even where the
    /// stability check fails (its `err` is then infinite).
    ///
    /// # Panics
    /// If `k < 2` (there is no error estimate).
    pub fn step<const N: usize, S: DdSystem<N>>(
        &self,
        sys: &S,
        t: Dd,
        y: &[Dd; N],
        f0: &[Dd; N],
        h: Dd,
    ) -> DdTrial<N> {
        self.run(sys, (t, y, f0), h, false)
            .expect("a step that is not abandoned completes")
    }

    /// One step of size `h` from `(t, y)`, with `f0 = f(t, y)`; `Err` with the evaluations spent
    /// where the stability check fails: the step is abandoned there, and a caller shrinks it
    /// (ODEX halves it).
    ///
    /// # Errors
    /// The evaluations spent, where the midpoint rule is unstable at this step size.
    ///
    /// # Panics
    /// If `k < 2` (there is no error estimate).
    pub fn try_step<const N: usize, S: DdSystem<N>>(
        &self,
        sys: &S,
        t: Dd,
        y: &[Dd; N],
        f0: &[Dd; N],
        h: Dd,
    ) -> Result<DdTrial<N>, u64> {
        self.run(sys, (t, y, f0), h, true)
    }

    /// A step; `abandon`: stop where the stability check fails.
    fn run<const N: usize, S: DdSystem<N>>(
        &self,
        sys: &S,
        (t, y, f0): (Dd, &[Dd; N], &[Dd; N]),
        h: Dd,
        abandon: bool,
    ) -> Result<DdTrial<N>, u64> {
        assert!(self.k >= 2, "extrapolation needs k >= 2 sequences");
        let mut prev: Vec<[Dd; N]> = Vec::with_capacity(self.k);
        let (mut samples, mut err, mut evals) = (Vec::new(), 0.0, 0);
        let mut stable = true;
        for j in 0..self.k {
            let n = 2 * (j + 1);
            let hs = h / n as f64;
            let (mut z0, mut z1) = (*y, axpy(y, hs, f0));
            for i in 1..n {
                let f = sys.rhs(t + hs * i as f64, &z1);
                if i == 1 && j == STABILITY_SEQUENCE && !self.stable(y, f0, &f) {
                    if abandon {
                        return Err(evals + 1);
                    }
                    stable = false;
                }
                (z0, z1) = (z1, axpy(&z0, hs * 2.0, &f));
                if j + 1 == self.k {
                    samples.push(z0);
                }
            }
            evals += n as u64 - 1;
            let mut row = Vec::with_capacity(j + 1);
            row.push(z1);
            for l in 1..=j {
                let (nj, nl) = (n as f64, (2 * (j - l + 1)) as f64);
                let w = Dd::new_div(nl * nl, nj * nj - nl * nl);
                let (cur, old) = (row[l - 1], prev[l - 1]);
                row.push(std::array::from_fn(|i| cur[i] + (cur[i] - old[i]) * w));
            }
            if j + 1 == self.k {
                err = self.error_norm(y, &row[j], &row[j - 1]);
            }
            prev = row;
        }
        Ok(DdTrial {
            y: prev[self.k - 1],
            samples,
            err: if stable { err } else { f64::INFINITY },
            evals,
        })
    }

    /// ODEX's stability check: whether `f1`, the derivative at an Euler point, differs
    /// from `f0 = f(t, y)` by at most twice `f0`'s size, both scaled by `atol + rtol |y_i|`
    /// (root mean square; `f0`'s squared size taken as at least `f64::EPSILON`). A NaN is left
    /// to the error estimate.
    fn stable<const N: usize>(&self, y: &[Dd; N], f0: &[Dd; N], f1: &[Dd; N]) -> bool {
        let (mut del0, mut del1) = (0.0, 0.0);
        for i in 0..N {
            let scale = self.atol + self.rtol * y[i].hi().abs();
            del0 += (f0[i].hi() / scale).powi(2);
            del1 += ((f1[i] - f0[i]).hi() / scale).powi(2);
        }
        del1.is_nan() || del1 <= 4.0 * del0.max(f64::EPSILON)
    }

    /// The factor for the next step size after a step with error `err`: `0.9 err^(-1/(2k-1))`
    /// within [0.2, 4] (0.1 for a non-finite error).
    pub fn factor(&self, err: f64) -> f64 {
        if err.is_finite() {
            (0.9 * err.powf(-1.0 / (2 * self.k - 1) as f64)).clamp(0.2, 4.0)
        } else {
            0.1
        }
    }

    /// `max_i |a_i - b_i| / (atol + rtol max(|y_i|, |a_i|))`; infinite for a non-finite
    /// difference.
    fn error_norm<const N: usize>(&self, y: &[Dd; N], a: &[Dd; N], b: &[Dd; N]) -> f64 {
        (0..N).fold(0.0, |acc: f64, i| {
            let scale = self.atol + self.rtol * y[i].hi().abs().max(a[i].hi().abs());
            let d = (a[i] - b[i]).hi().abs() / scale;
            if d.is_nan() {
                f64::INFINITY
            } else {
                acc.max(d)
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dd::dd;

    /// Integrates to `t_end` with the method's step control.
    fn integrate<const N: usize>(
        m: &Extrapolation,
        f: impl Fn(Dd, &[Dd; N]) -> [Dd; N],
        mut y: [Dd; N],
        t_end: Dd,
    ) -> ([Dd; N], u64) {
        let (mut t, mut h, mut steps) = (Dd::from(0.0), Dd::from(0.1), 0);
        while (t_end - t).hi() > 0.0 {
            if (t + h - t_end).hi() > 0.0 {
                h = t_end - t;
            }
            let trial = m.step(&f, t, &y, &f(t, &y), h);
            if trial.err <= 1.0 {
                (t, y, steps) = (t + h, trial.y, steps + 1);
            }
            h *= m.factor(trial.err);
        }
        (y, steps)
    }

    /// The harmonic oscillator `x'' = -x` returns to `(1, 0)` after `2π`, to double-double
    /// precision.
    #[test]
    fn oscillator_closes_its_orbit_to_32_digits() {
        let two_pi = dd(std::f64::consts::TAU, 2.4492935982947064e-16);
        let f = |_t: Dd, y: &[Dd; 2]| [y[1], -y[0]];
        let m = Extrapolation::new(1e-30, 1e-32);
        let (y, steps) = integrate(&m, f, [Dd::from(1.0), Dd::from(0.0)], two_pi);
        assert!((y[0] - 1.0).hi().abs() < 1e-29, "x = {:?}", y[0]);
        assert!(y[1].hi().abs() < 1e-29, "v = {:?}", y[1]);
        assert!(steps < 200, "{steps} steps");
    }

    /// One step's error falls like `h^(2k+1)`: halving `h` divides it by about `2^(2k+1)`.
    #[test]
    fn local_error_has_order_2k() {
        // y' = y: y(h) = e^h.
        let f = |_t: Dd, y: &[Dd; 1]| [y[0]];
        let m = Extrapolation {
            k: 4,
            rtol: 1e-30,
            atol: 1e-30,
        };
        let err = |h: f64| {
            let one = [Dd::from(1.0)];
            let y = m.step(&f, Dd::from(0.0), &one, &one, Dd::from(h)).y[0];
            (y - crate::dd::exp(Dd::from(h))).hi().abs()
        };
        let ratio = err(0.2) / err(0.1);
        // 2^9 = 512 for order 8; the leading term's constant varies a little with h.
        assert!((400.0..650.0).contains(&ratio), "ratio {ratio}");
    }

    /// For `y' = λ y` the derivative at the first Euler point of the sequence with `n = 4`
    /// substeps is `f0 (1 + λ H / 4)`, so the check fails exactly where `|λ H| / 4 > 2`: a step
    /// is abandoned from `|λ H| = 8` on (after the first sequence's evaluation and its own),
    /// and completed with an infinite error by `step`.
    #[test]
    fn stability_check_trips_where_the_midpoint_rule_turns_unstable() {
        let lambda = -1e6;
        let f = move |_t: Dd, y: &[Dd; 1]| [y[0] * lambda];
        let m = Extrapolation::new(1e-20, 1e-22);
        let (one, f0) = ([Dd::from(1.0)], [Dd::from(lambda)]);
        let at = |h: f64| m.try_step(&f, Dd::from(0.0), &one, &f0, Dd::from(h));
        assert!(at(7.99e-6).is_ok());
        let spent = at(8.01e-6).expect_err("unstable");
        assert_eq!(spent, 2, "abandoned at its second evaluation");
        let full = m.step(&f, Dd::from(0.0), &one, &f0, Dd::from(8.01e-6));
        assert_eq!(full.err, f64::INFINITY);
        assert_eq!(full.evals, 64);
    }

    /// The method's own stability boundary, which places the check: `|T_88(z)|` for
    /// `y' = λ y`, `z = λ H`, stays below 1 up to `z = -7.3` and exceeds it from `z = -7.4`.
    #[test]
    fn order_16_is_stable_to_about_seven_on_the_negative_real_axis() {
        let f = |_t: Dd, y: &[Dd; 1]| [-y[0]];
        let m = Extrapolation::new(1e-20, 1e-22);
        let one = [Dd::from(1.0)];
        let r = |h: f64| (m.step(&f, Dd::from(0.0), &one, &[-one[0]], Dd::from(h)).y[0]).hi();
        assert!(
            r(7.3).abs() < 1.0 && r(7.4).abs() > 1.0,
            "{} {}",
            r(7.3),
            r(7.4)
        );
    }
}

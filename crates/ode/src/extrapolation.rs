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
    /// The error estimate in units of the tolerance: the step is accepted at `<= 1`.
    pub err: f64,
    /// Right-hand-side evaluations spent (not counting `f0`).
    pub evals: u64,
}

/// `y + h f`.
fn axpy<const N: usize>(y: &[Dd; N], h: Dd, f: &[Dd; N]) -> [Dd; N] {
    std::array::from_fn(|i| y[i] + h * f[i])
}

impl Extrapolation {
    /// Order 16 (`k = 8`) at the given tolerances.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Self { k: 8, rtol, atol }
    }

    /// One step of size `h` from `(t, y)`, with `f0 = f(t, y)`.
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
        assert!(self.k >= 2, "extrapolation needs k >= 2 sequences");
        let mut prev: Vec<[Dd; N]> = Vec::with_capacity(self.k);
        let (mut samples, mut err, mut evals) = (Vec::new(), 0.0, 0);
        for j in 0..self.k {
            let n = 2 * (j + 1);
            let hs = h / n as f64;
            let (mut z0, mut z1) = (*y, axpy(y, hs, f0));
            for i in 1..n {
                let f = sys.rhs(t + hs * i as f64, &z1);
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
        DdTrial {
            y: prev[self.k - 1],
            samples,
            err,
            evals,
        }
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
}

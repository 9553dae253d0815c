//! Chebyshev interpolants on points of the first kind: the quadratures of a panel, the
//! fixed-point iteration for `W`, and roots of a series.

use crate::ModelError;
use std::sync::OnceLock;

/// The node counts tried, in order.
pub(super) const RUNGS: [usize; 7] = [8, 12, 16, 24, 32, 48, 64];
/// The largest node count: the size of every buffer.
pub(super) const MAX_N: usize = 64;
/// Picard iterations allowed per panel; each gains about `-log10(σ)` digits on the paper's fits.
const MAX_PICARD: usize = 80;

/// Where [`picard`] starts.
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Start {
    /// From the solution without damping (`g = 0`).
    Undamped,
    /// From what `w` holds (a nearby problem's solution).
    Given,
}

/// When [`picard`] stops.
#[derive(Clone, Copy)]
pub(super) struct Settle {
    /// What may be left in `W`.
    pub(super) tol: f64,
    /// Whether what is left is estimated from the contraction, or taken to be the last
    /// change (a few times more).
    pub(super) estimated: bool,
}

/// `W = w0 + ∫ (f0 - g sqrt(2W))` on the rung's nodes by fixed-point iteration from `start`,
/// into `w`, with its integrand into `rhs`; returns an estimate of what is left in `w` (the
/// iteration contracts by about `σ |X|^p T`, a few hundredths on the paper's fits).
pub(super) fn picard(
    r: &Rung,
    half: f64,
    (w0, settle): (f64, Settle),
    (f0, g): (&[f64], &[f64]),
    (w, start): (&mut [f64], Start),
    rhs: &mut [f64],
) -> Result<f64, ModelError> {
    let n = r.n;
    let (mut next, mut g_last, mut f_last) = ([0.0; MAX_N], [0.0; MAX_N], [0.0; MAX_N]);
    if start == Start::Undamped {
        r.cumulative(f0, half, w);
        w.iter_mut().for_each(|wk| *wk += w0);
    }
    let (mut best, mut stalled) = (f64::INFINITY, 0);
    let (mut last, mut theta) = (f64::INFINITY, 0.0f64);
    for i in 0..MAX_PICARD {
        for (((rk, &fk), &gk), &wk) in rhs.iter_mut().zip(f0).zip(g).zip(w.iter()) {
            *rk = fk - gk * (2.0 * wk).max(0.0).sqrt();
        }
        r.cumulative(rhs, half, &mut next[..n]);
        next[..n].iter_mut().for_each(|x| *x += w0);
        // The residual `G(W) - W` of the map `G` and its change since the last iteration.
        let (mut change, mut size, mut dot, mut norm) = (0.0f64, 0.0f64, 0.0, 0.0);
        for k in 0..n {
            let f = next[k] - w[k];
            let df = f - f_last[k];
            (dot, norm) = (dot + f * df, norm + df * df);
            change = change.max(f.abs());
            size = size.max(next[k].abs());
            f_last[k] = f;
        }
        // What is left in the image `G(W)`: at most `θ / (1 - θ)` times the change for a map
        // that contracts by `θ`. The map is a Volterra operator, so its ratios of successive
        // changes fall from one iteration to the next (0.02, 0.015, 0.009 on DSA (1)'s fits):
        // the largest seen stands for `θ`. Where it is not well below 1 the change itself.
        if i > 0 {
            theta = theta.max(change / last);
        }
        last = change;
        let left = match theta {
            t if settle.estimated && i > 0 && t < 0.5 => change * t / (1.0 - t),
            _ => change,
        };
        // Below a few roundings of `W` the iteration only moves the last bits.
        if left <= settle.tol.max(8.0 * f64::EPSILON * size) {
            w.copy_from_slice(&next[..n]);
            return Ok(left);
        }
        // An iteration that has stopped contracting will not settle: decline after three
        // iterations without a tenth off the best residual, not after `MAX_PICARD` (the usual
        // path serves such damping).
        if change < 0.9 * best {
            (best, stalled) = (change, 0);
        } else {
            stalled += 1;
            if stalled >= 3 {
                break;
            }
        }
        // Anderson's acceleration with one previous iterate, from the fourth iteration (the
        // paper's fits settle in three or four plain ones): the combination of the last two
        // images that minimises the residual, a secant step along the slowest direction.
        let theta = if i >= 3 && norm > 0.0 {
            dot / norm
        } else {
            0.0
        };
        for k in 0..n {
            let image = next[k];
            w[k] = image - theta * (image - g_last[k]);
            g_last[k] = image;
        }
    }
    Err(ModelError::NotApplicable {
        reason: "the damping's fixed-point iteration did not settle (sigma too large for the \
                 phase path)",
    })
}

/// Chebyshev points of the first kind on `[-1, 1]` and the matrices that act on values there.
pub(super) struct Rung {
    pub(super) n: usize,
    /// The points, increasing.
    pub(super) x: Vec<f64>,
    /// Values to Chebyshev coefficients, column-major `n x n`.
    coef: Vec<f64>,
    /// Values to the integral from -1 at each point, column-major.
    int: Vec<f64>,
    /// Values to the integral over `[-1, 1]`.
    total: Vec<f64>,
}

pub(super) fn rung(n: usize) -> &'static Rung {
    static RUNG_TABLES: [OnceLock<Rung>; RUNGS.len()] = [const { OnceLock::new() }; RUNGS.len()];
    let i = RUNGS.iter().position(|&m| m == n).expect("n is a rung");
    RUNG_TABLES[i].get_or_init(|| Rung::new(n))
}

impl Rung {
    fn new(n: usize) -> Self {
        let nf = n as f64;
        let angle = |k: usize| std::f64::consts::PI * (1.0 - (k as f64 + 0.5) / nf);
        let x: Vec<f64> = (0..n).map(|k| angle(k).cos()).collect();
        // Column-major: column `k` holds what the value at node `k` adds to each coefficient.
        let mut coef = vec![0.0; n * n];
        for j in 0..n {
            let scale = if j == 0 { 1.0 / nf } else { 2.0 / nf };
            for k in 0..n {
                coef[k * n + j] = scale * (j as f64 * angle(k)).cos();
            }
        }
        // The antiderivative of T_j that vanishes at -1, at `x = cos a`.
        let anti = |j: usize, a: f64| -> f64 {
            let t = |m: usize, a: f64| (m as f64 * a).cos();
            let raw = |a: f64| match j {
                0 => t(1, a),
                1 => 0.25 * t(2, a),
                _ => t(j + 1, a) / (2.0 * (j + 1) as f64) - t(j - 1, a) / (2.0 * (j - 1) as f64),
            };
            raw(a) - raw(std::f64::consts::PI)
        };
        let at_nodes: Vec<f64> = (0..n * n).map(|i| anti(i / n, angle(i % n))).collect();
        // Column-major: column `m` holds the weights of the value at node `m`.
        let mut int = vec![0.0; n * n];
        let mut total = vec![0.0; n];
        for m in 0..n {
            for j in 0..n {
                let c = coef[m * n + j];
                total[m] += anti(j, 0.0) * c;
                for k in 0..n {
                    int[m * n + k] += at_nodes[j * n + k] * c;
                }
            }
        }
        Rung {
            n,
            x,
            coef,
            int,
            total,
        }
    }

    /// `∫_{-1}^{x_k} f`, times `scale` (the half-width of the panel), into `out`.
    pub(super) fn cumulative(&self, f: &[f64], scale: f64, out: &mut [f64]) {
        // Column by column: each pass is a vectorised `out += f_m column_m`.
        out.iter_mut().for_each(|o| *o = 0.0);
        for (column, &fm) in self.int.chunks_exact(self.n).zip(f) {
            for (o, &a) in out.iter_mut().zip(column) {
                *o += a * fm;
            }
        }
        out.iter_mut().for_each(|o| *o *= scale);
    }

    /// `∫_{-1}^{1} f`.
    pub(super) fn total(&self, f: &[f64]) -> f64 {
        self.total.iter().zip(f).map(|(a, b)| a * b).sum()
    }

    /// `∫_{-1}^{s} f` through the interpolant's coefficients.
    pub(super) fn integral_to(&self, f: &[f64], s: f64) -> f64 {
        let n = self.n;
        let c = self.coefficients(f);
        let mut ci = [0.0; MAX_N + 1];
        for j in 1..=n {
            let before = if j == 1 { 2.0 * c[0] } else { c[j - 1] };
            let after = if j + 1 < n { c[j + 1] } else { 0.0 };
            ci[j] = (before - after) / (2.0 * j as f64);
        }
        clenshaw(&ci[..=n], s) - clenshaw(&ci[..=n], -1.0)
    }

    pub(super) fn coefficients(&self, f: &[f64]) -> [f64; MAX_N] {
        let mut c = [0.0; MAX_N];
        for (column, &fk) in self.coef.chunks_exact(self.n).zip(f) {
            for (cj, &a) in c[..self.n].iter_mut().zip(column) {
                *cj += a * fk;
            }
        }
        c
    }
}

/// A root in `[lo, hi]` of `Σ c_j T_j`, which is `f_lo > 0` at `lo` and `f_hi <= 0` at `hi`:
/// Newton steps from the secant's guess, kept inside a shrinking bracket (bisection where a
/// step leaves it), to a change of `1e-15` or a value within the sum's rounding.
pub(super) fn root(c: &[f64], (mut lo, f_lo): (f64, f64), (mut hi, f_hi): (f64, f64)) -> f64 {
    // `|T_j| <= 1`: the recurrences round the sum by a few `ε Σ|c_j|`. Below that the Newton
    // steps are noise, and without this bound the bracket would be bisected down to `1e-15`
    // (some 40 evaluations).
    let noise = 4.0 * f64::EPSILON * c.iter().map(|cj| cj.abs()).sum::<f64>();
    let mut s = lo + (hi - lo) * f_lo / (f_lo - f_hi);
    for _ in 0..60 {
        let (f, df) = clenshaw_with_slope(c, s);
        if f.abs() <= noise {
            return s;
        }
        if f > 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        let newton = s - f / df;
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - s).abs() <= 1e-15 || hi - lo <= 1e-15 {
            return next;
        }
        s = next;
    }
    s
}

/// `Σ c_j T_j(s)` and its derivative (`T_j' = j U_(j-1)`), by the three-term recurrences of
/// `T` and `U` (`U_(-1) = 0`, `U_0 = 1`).
pub(super) fn clenshaw_with_slope(c: &[f64], s: f64) -> (f64, f64) {
    let (mut t0, mut t1) = (1.0, s);
    let (mut u0, mut u1) = (0.0, 1.0);
    let mut f = c[0] + c.get(1).map_or(0.0, |c1| c1 * s);
    let mut df = c.get(1).copied().unwrap_or(0.0);
    for (j, &cj) in c.iter().enumerate().skip(2) {
        let t2 = 2.0 * s * t1 - t0;
        let u2 = 2.0 * s * u1 - u0;
        f += cj * t2;
        df += cj * j as f64 * u2;
        (t0, t1, u0, u1) = (t1, t2, u1, u2);
    }
    (f, df)
}

/// `Σ c_j T_j(s)` by Clenshaw's recurrence.
pub(super) fn clenshaw(c: &[f64], s: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for &cj in c[1..].iter().rev() {
        let b0 = cj + 2.0 * s * b1 - b2;
        b2 = b1;
        b1 = b0;
    }
    c[0] + s * b1 - b2
}

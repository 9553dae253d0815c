//! The step off a root of `Z` into a branch without hysteresis bracket (`c = B + Γ = 0`, i.e.
//! `Γ = -B`: every fit of the paper), in place of a Runge-Kutta start step and the ramp of
//! series steps after it.
//!
//! After the root, `Z` moves with the rate and `Z' = rate` exactly, so `D = |Z|` grows from 0
//! and can serve as the independent variable: with `s` the sign of the rate and
//! `W = 1 / |rate|`, every state component `y` obeys `dy/dD = y' W`, where the only power that is
//! not analytic at `D = 0` is `|Z|^p = D^p`, now explicit. The solution is therefore a series in
//! the monomials `D^(a + j p)` (`a, j >= 0`, weight `a + j p` up to Jorba & Zou's order for the
//! tolerance plus two, `-ln(tol)/2 + 2`, between 6 and `ORDER`):
//!
//! * NDBWSHCCM (`X = X_c + s D`): `F = -κ sgn(X) P - (1 - κ) s D^p - σ P V` with
//!   `P = |X_c + s D|^p` (a binomial series in `D`), `dV/dD = (F + u) W`, `dT/dD = W`,
//!   `W = 1 / (s V)`;
//! * NDBWMCM (`Y = Y_c + s D`): `F = -κ sgn(Y) P - (1 - κ) s D^p`, `dV/dD = (F + u) W`,
//!   `dR/dD = -σ F W`, `dT/dD = W`, `W = 1 / (s (V + σ F))`.
//!
//! Coefficient `(a, j)` of a solution is coefficient `(a - 1, j)` of its derivative over the
//! weight `a + j p` (and 0 for `a = 0`, `j > 0`), and the products and the reciprocal `W` need
//! only coefficients of componentwise smaller index pairs, so one pass in row order (`j`, then
//! `a`) computes them all. The step in `D` is Jorba & Zou's over the last two weights of each
//! row, at [`START_TOLERANCE`] times the local tolerance, at most half the distance to the zero
//! of the other base; it ends early at a separation `F <= 0 <= V` (the root of the force's
//! series). It is declined (the Runge-Kutta start step takes over) where the rate would vanish
//! inside it, where the other base's zero is within a tenth of the step (both bases vanishing
//! together), and where its values are not finite.

use super::polynomial::{class, coarse_log2, root, ORDER};
use super::recurrence::dot2;
use super::steps::START_TOLERANCE;
use crate::models::NdCoefficients;
use crate::State;

/// Largest weight `a + j p` of the monomials, and the largest `a` and `j`.
const K: usize = ORDER;

/// Coefficients `c[j][a]` of `D^(a + j p)`.
type Lattice = [[f64; K + 1]; K + 1];

const ZERO: Lattice = [[0.0; K + 1]; K + 1];

/// The monomials up to weight `K` for the exponent `p >= 1`: row `j` holds `a = 0 ..= last[j]`.
struct Shape {
    p: f64,
    rows: usize,
    last: [usize; K + 1],
}

impl Shape {
    fn new(p: f64, tol: f64) -> Option<Self> {
        if !(1.0..=K as f64).contains(&p) {
            return None;
        }
        // Jorba & Zou's order for the tolerance, -ln(tol) / 2, and a margin.
        let top = (-0.5 * tol.ln() + 2.0).clamp(6.0, K as f64).floor();
        let mut last = [0; K + 1];
        let mut rows = 0;
        while rows <= K && rows as f64 * p <= top {
            last[rows] = (top - rows as f64 * p).floor() as usize;
            rows += 1;
        }
        Some(Self { p, rows, last })
    }

    fn weight(&self, j: usize, a: usize) -> f64 {
        a as f64 + j as f64 * self.p
    }

    /// `(Σ u[j1][a1] W[j - j1][a - a1], Σ f[j1][a1] W[j - j1][a - a1])` over the pairs
    /// `(j1, a1)` other than `(0, 0)`, with `W` stored reversed in its rows
    /// (`w_rev[j][K - a] = W[j][a]`), so that each row's sum is a forward dot product.
    fn products(u: &Lattice, f: &Lattice, w_rev: &Lattice, j: usize, a: usize) -> (f64, f64) {
        let (mut su, mut sf) = (0.0, 0.0);
        for j1 in 0..=j {
            let start = usize::from(j1 == 0);
            if start > a {
                continue;
            }
            let q = &w_rev[j - j1][K - a + start..=K];
            let (x, y) = dot2(&u[j1][start..=a], &f[j1][start..=a], q);
            su += x;
            sf += y;
        }
        (su, sf)
    }

    /// Coefficient `(j, a)` of `W = 1 / U` (stored reversed, as in [`Shape::products`]) from
    /// `U` up to `(j, a)` and `W` before it, and coefficient `(j, a)` of `F W`. `W[0][0]` is
    /// set by the caller.
    fn reciprocal_and_product(
        u: &Lattice,
        f: &Lattice,
        w_rev: &mut Lattice,
        j: usize,
        a: usize,
    ) -> f64 {
        let (su, sf) = Self::products(u, f, w_rev, j, a);
        if (j, a) != (0, 0) {
            w_rev[j][K - a] = -w_rev[0][K] * su;
        }
        sf + f[0][0] * w_rev[j][K - a]
    }

    /// The powers of `D` for evaluating a lattice at `D > 0`.
    fn powers(&self, d: f64) -> Powers {
        let mut da = [1.0; K + 1];
        for a in 1..=K {
            da[a] = da[a - 1] * d;
        }
        let dp = d.powf(self.p);
        let mut dj = [1.0; K + 1];
        for j in 1..self.rows {
            dj[j] = dj[j - 1] * dp;
        }
        Powers { d, da, dj }
    }

    /// The lattice and its derivative in `D` at the powers `w`.
    fn eval(&self, c: &Lattice, w: &Powers) -> (f64, f64) {
        let (mut value, mut slope) = (0.0, 0.0);
        for (j, (cj, &last)) in c.iter().zip(&self.last).take(self.rows).enumerate() {
            let (mut row, mut row_slope) = (0.0, 0.0);
            for (a, (c_ja, da)) in cj[..=last].iter().zip(&w.da).enumerate() {
                let term = c_ja * da;
                row += term;
                row_slope += self.weight(j, a) * term;
            }
            value += w.dj[j] * row;
            slope += w.dj[j] * row_slope;
        }
        (value, slope / w.d)
    }

    /// Jorba & Zou's step for the series `c`: `0.9 min (tol / |c_(j,a)|)^(1 / weight)` over
    /// the last two coefficients of each row.
    fn step(&self, c: &Lattice, tol: f64) -> f64 {
        let lt = coarse_log2(tol);
        let mut x = f64::INFINITY;
        for (j, (cj, &last)) in c.iter().zip(&self.last).take(self.rows).enumerate() {
            for (a, c_ja) in cj
                .iter()
                .enumerate()
                .take(last + 1)
                .skip(last.saturating_sub(1))
            {
                let (coefficient, w) = (c_ja.abs(), self.weight(j, a));
                if coefficient > 0.0 && w >= 1.0 {
                    x = x.min((lt - coarse_log2(coefficient)) / w);
                }
            }
        }
        0.9 * x.exp2()
    }
}

/// Powers of `D`: `D^a` and `D^(j p)`.
struct Powers {
    d: f64,
    da: [f64; K + 1],
    dj: [f64; K + 1],
}

/// `|b_c + s D|^p` as a series in `D` (row 0 of a lattice): the binomial series of a base whose
/// magnitude moves as `sgn(b_c) s D`.
fn binomial_row(p: f64, b_c: f64, s: f64) -> [f64; K + 1] {
    let (magnitude, slope) = (b_c.abs(), b_c.signum() * s);
    let mut row = [0.0; K + 1];
    row[0] = magnitude.powf(p);
    for a in 1..=K {
        row[a] = row[a - 1] * (p - (a - 1) as f64) / a as f64 * slope / magnitude;
    }
    row
}

/// The model's constants for a crossing step.
#[derive(Clone, Copy)]
pub(crate) struct Coefficients {
    pub(crate) kappa: f64,
    pub(crate) sigma: f64,
    pub(crate) p: f64,
    pub(crate) u: f64,
}

impl Coefficients {
    /// The constants of a model whose branch after a root of `Z` has no hysteresis bracket
    /// (`B + Γ = 0`), under the constant input `u`; `None` for any other model.
    pub(crate) fn of(k: &NdCoefficients, u: f64) -> Option<Self> {
        (k.b + k.gamma == 0.0).then(|| Self {
            kappa: k.kappa,
            sigma: k.sigma,
            p: k.p.exponent(),
            u,
        })
    }
}

/// Where a crossing step ends, `D` after the root of `Z`: the time since the root, the
/// state's increments as their series' values, and whether it ended on a separation.
pub(crate) struct Crossing {
    /// `D` at the end.
    pub(crate) d: f64,
    /// Time since the root.
    pub(crate) dt: f64,
    /// `V` at the end.
    pub(crate) v: f64,
    /// The NDBWMCM's `R - R_c` at the end (0 for the NDBWSHCCM).
    pub(crate) dr: f64,
    /// The step ended on the force's root with `V >= 0`.
    pub(crate) separated: bool,
}

/// The series of a crossing: the velocity, time, the NDBWMCM's `R`, the force and `|rate|`.
struct Solution {
    shape: Shape,
    v: Lattice,
    t: Lattice,
    r: Lattice,
    f: Lattice,
    rate: Lattice,
}

/// The NDBWSHCCM's series off a root of `Z` at `X = x_c`, `V = v_c` into the branch where the
/// rate has sign `s` (the sign of `v_c`).
fn shccm_series(k: &Coefficients, x_c: f64, v_c: f64, s: f64, sol: &mut Solution) -> Option<()> {
    let shape = &sol.shape;
    let (sx, pr) = (x_c.signum(), binomial_row(k.p, x_c, s));
    let (mut w, mut g) = (ZERO, ZERO);
    let Solution {
        v, t, f, rate: u, ..
    } = sol;
    let rate_c = s * v_c;
    if !rate_c.is_finite() || rate_c <= 0.0 {
        return None;
    }
    for j in 0..shape.rows {
        for a in 0..=shape.last[j] {
            let weight = shape.weight(j, a);
            if (j, a) == (0, 0) {
                (v[0][0], u[0][0], w[0][K]) = (v_c, rate_c, 1.0 / rate_c);
            } else if a >= 1 {
                v[j][a] = g[j][a - 1] / weight;
                t[j][a] = w[j][K + 1 - a] / weight;
            }
            u[j][a] = s * v[j][a];
            let damping: f64 = (0..=a).map(|a1| pr[a1] * v[j][a - a1]).sum();
            f[j][a] = -k.sigma * damping
                + if j == 0 { -k.kappa * sx * pr[a] } else { 0.0 }
                + if (j, a) == (1, 0) {
                    -(1.0 - k.kappa) * s
                } else {
                    0.0
                };
            g[j][a] = Shape::reciprocal_and_product(u, f, &mut w, j, a) + k.u * w[j][K - a];
        }
    }
    Some(())
}

/// The NDBWMCM's series off a root of `Z` at `Y = y_c`, `V = v_c` into the branch where the
/// rate `Y' = V + σ F` has sign `s`.
fn mcm_series(k: &Coefficients, y_c: f64, v_c: f64, s: f64, sol: &mut Solution) -> Option<()> {
    let shape = &sol.shape;
    let (sy, pr) = (y_c.signum(), binomial_row(k.p, y_c, s));
    let (mut w, mut h) = (ZERO, ZERO);
    let Solution {
        v,
        t,
        r,
        f,
        rate: u,
        ..
    } = sol;
    for (a, c) in pr.iter().enumerate() {
        f[0][a] = -k.kappa * sy * c;
    }
    if shape.rows > 1 {
        f[1][0] = -(1.0 - k.kappa) * s;
    }
    let rate_c = s * (v_c + k.sigma * f[0][0]);
    if !rate_c.is_finite() || rate_c <= 0.0 {
        return None;
    }
    for j in 0..shape.rows {
        for a in 0..=shape.last[j] {
            let weight = shape.weight(j, a);
            if (j, a) == (0, 0) {
                (v[0][0], u[0][0], w[0][K]) = (v_c, rate_c, 1.0 / rate_c);
            } else {
                if a >= 1 {
                    let w_before = w[j][K + 1 - a];
                    v[j][a] = (h[j][a - 1] + k.u * w_before) / weight;
                    r[j][a] = -k.sigma * h[j][a - 1] / weight;
                    t[j][a] = w_before / weight;
                }
                u[j][a] = s * (v[j][a] + k.sigma * f[j][a]);
            }
            h[j][a] = Shape::reciprocal_and_product(u, f, &mut w, j, a);
        }
    }
    Some(())
}

impl Solution {
    fn new(shape: Shape) -> Self {
        Self {
            shape,
            v: ZERO,
            t: ZERO,
            r: ZERO,
            f: ZERO,
            rate: ZERO,
        }
    }

    /// The step in `D` and where it ends (see the module docs), or `None` where the rate would
    /// vanish inside it. `base_c` is the other base at the root, `tol` the local tolerance.
    fn step(&self, base_c: f64, tol: f64) -> Option<Crossing> {
        let shape = &self.shape;
        let tol = START_TOLERANCE * tol;
        let mut d = [&self.v, &self.t, &self.r]
            .iter()
            .map(|c| shape.step(c, tol))
            .fold(f64::INFINITY, f64::min);
        // Within half the distance to the other base's zero; where that is far below the
        // series' own step (both bases vanishing together) the start step leaves instead.
        let cap = 0.5 * base_c.abs();
        if !(d > 0.0 && cap >= 0.1 * d) {
            return None;
        }
        d = d.min(cap);
        let value = |c: &Lattice, w: &Powers| shape.eval(c, w).0;
        // The rate must stay away from zero over the step (a turning point of D).
        let mut halvings = 0;
        let (mut at_d, mut at_half) = (shape.powers(d), shape.powers(0.5 * d));
        while !(value(&self.rate, &at_half) > 0.0 && value(&self.rate, &at_d) > 0.0) {
            d *= 0.5;
            halvings += 1;
            if halvings > 3 {
                return None;
            }
            (at_d, at_half) = (at_half, shape.powers(0.5 * d));
        }
        let separated_at = |w: &Powers| value(&self.f, w) <= 0.0 && value(&self.v, w) >= 0.0;
        let start = class(self.f[0][0]);
        let half_separated = start > 0 && separated_at(&at_half);
        let separated = half_separated || (start > 0 && separated_at(&at_d));
        if separated {
            let upto = if half_separated { 0.5 * d } else { d };
            d = root(|x| shape.eval(&self.f, &shape.powers(x)), upto, start);
            at_d = shape.powers(d);
        }
        let end = Crossing {
            d,
            dt: value(&self.t, &at_d),
            v: value(&self.v, &at_d),
            dr: value(&self.r, &at_d),
            separated,
        };
        // Overflowing coefficients (a rate near zero at the root) decline the step.
        let finite = [end.d, end.dt, end.v, end.dr].iter().all(|x| x.is_finite());
        (finite && end.dt > 0.0).then_some(end)
    }
}

/// The NDBWSHCCM's crossing step from `(X, Z = 0, V)` into the branch of rate sign `s`.
pub(crate) fn shccm(k: &Coefficients, y: &State<3>, s: f64, tol: f64) -> Option<Crossing> {
    let mut sol = Solution::new(Shape::new(k.p, START_TOLERANCE * tol)?);
    shccm_series(k, y[0], y[2], s, &mut sol)?;
    sol.step(y[0], tol)
}

/// The NDBWMCM's crossing step from `(R, Y, Z = 0, V)` into the branch of rate sign `s`.
pub(crate) fn mcm(k: &Coefficients, y: &State<4>, s: f64, tol: f64) -> Option<Crossing> {
    let mut sol = Solution::new(Shape::new(k.p, START_TOLERANCE * tol)?);
    mcm_series(k, y[1], y[3], s, &mut sol)?;
    sol.step(y[1], tol)
}

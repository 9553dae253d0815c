//! Least-squares polishing on the unit cube: Levenberg-Marquardt with a forward-difference
//! Jacobian (the model is simulated, never differentiated), steps projected onto the cube and
//! coordinates held on a face while the gradient pushes them out of it.
//!
//! Near an optimum this converges in tens of Jacobians where Nelder-Mead needs hundreds of
//! simplex moves along the curved, nearly flat valleys of non-identifiable parameters.

use crate::fit::CubeProblem;
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

/// Forward-difference step on the unit cube.
const H: f64 = 1e-5;
/// Most Jacobians per polish.
const MAX_JACOBIANS: usize = 100;

fn cost(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// The Jacobian of the residuals at `x` (`r` the residuals there), steps pointing into the cube.
fn jacobian<P: CubeProblem>(problem: &P, x: &[f64], r: &[f64]) -> Option<Vec<Vec<f64>>> {
    let mut columns = Vec::with_capacity(x.len());
    for j in 0..x.len() {
        let h = if x[j] + H > 1.0 { -H } else { H };
        let mut y = x.to_vec();
        y[j] += h;
        let ry = problem.residuals_at(&y)?;
        columns.push(ry.iter().zip(r).map(|(a, b)| (a - b) / h).collect());
    }
    Some(columns)
}

/// Solves `(JᵀJ + λ D) δ = -Jᵀr` over the coordinates in `free` (D the diagonal of JᵀJ,
/// floored), `None` if the system is singular.
fn step(columns: &[Vec<f64>], r: &[f64], free: &[usize], lambda: f64) -> Option<Vec<f64>> {
    let k = free.len();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut a = Mat::<f64>::from_fn(k, k, |i, j| dot(&columns[free[i]], &columns[free[j]]));
    let scale = (0..k).map(|i| a[(i, i)]).fold(0.0, f64::max).max(1e-300);
    for i in 0..k {
        a[(i, i)] += lambda * a[(i, i)].max(1e-12 * scale);
    }
    let g = Mat::<f64>::from_fn(k, 1, |i, _| -dot(&columns[free[i]], r));
    let delta = a.llt(Side::Lower).ok()?.solve(&g);
    let out: Vec<f64> = (0..k).map(|i| delta[(i, 0)]).collect();
    out.iter().all(|v| v.is_finite()).then_some(out)
}

/// Polishes `x` (cost `c`) by Levenberg-Marquardt; `None` if the problem has no residuals.
/// Returns the best point and its cost (never worse than the start).
pub(crate) fn polish<P: CubeProblem>(problem: &P, x: &[f64], c: f64) -> Option<(Vec<f64>, f64)> {
    let mut x: Vec<f64> = x.iter().map(|v| v.clamp(0.0, 1.0)).collect();
    let mut r = problem.residuals_at(&x)?;
    let mut c_now = cost(&r);
    if c.is_finite() && (c_now.is_nan() || c_now > c) {
        // The clamped start is worse than the caller's point: nothing to polish from.
        return None;
    }
    let mut lambda = 1e-3;
    for _ in 0..MAX_JACOBIANS {
        let columns = jacobian(problem, &x, &r)?;
        let gradient: Vec<f64> = columns
            .iter()
            .map(|col| col.iter().zip(&r).map(|(a, b)| a * b).sum())
            .collect();
        // Coordinates on a face whose gradient points out of the cube stay there.
        let free: Vec<usize> = (0..x.len())
            .filter(|&j| {
                !((x[j] <= 0.0 && gradient[j] > 0.0) || (x[j] >= 1.0 && gradient[j] < 0.0))
            })
            .collect();
        if free.is_empty() {
            break;
        }
        let mut improved = false;
        while lambda < 1e12 {
            let Some(delta) = step(&columns, &r, &free, lambda) else {
                lambda *= 10.0;
                continue;
            };
            let mut y = x.clone();
            for (i, &j) in free.iter().enumerate() {
                y[j] = (y[j] + delta[i]).clamp(0.0, 1.0);
            }
            let ry = problem.residuals_at(&y)?;
            let cy = cost(&ry);
            if cy < c_now {
                let gain = c_now - cy;
                (x, r, c_now) = (y, ry, cy);
                lambda = (lambda / 3.0).max(1e-12);
                improved = gain > 1e-9 * c_now;
                break;
            }
            lambda *= 4.0;
        }
        if !improved {
            break;
        }
    }
    Some((x, c_now))
}

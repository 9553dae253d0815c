//! Least-squares polishing on the unit cube: Levenberg-Marquardt with a forward-difference
//! Jacobian (the model is simulated, never differentiated), in two phases.
//!
//! 1. **Interior** ([`interior`]): strictly inside the cube, in the variables of Coleman and Li
//!    (SIAM J. Optim. 6, 1996) as SciPy's `least_squares(method="trf")` uses them: a coordinate
//!    whose descent direction points at a face is scaled by the square root of its distance to
//!    that face, and a step that would leave the cube is cut short of the face. A start does not
//!    stick to the first face it meets, so the other coordinates keep moving: from uniform
//!    random starts on the single-baseball fits, the interior phase reaches the best basin
//!    several times as often as the face phase alone (BENCHMARKS.md, "Identification: the
//!    global optimum on measured data").
//! 2. **Faces** ([`faces`]): geodesic acceleration (Transtrum & Sethna 2012, arXiv:1201.5885),
//!    an active set for the faces of the cube, and coordinates held on a face while the
//!    gradient pushes them out of it: the exact end on the bounds that the interior phase only
//!    approaches.
//!
//! Near an optimum this converges in tens of Jacobians where Nelder-Mead needs hundreds of
//! simplex moves along the curved, nearly flat valleys of non-identifiable parameters. The
//! acceleration bends each step along such a valley: it costs one residual evaluation per trial
//! and saves Jacobians, which cost one evaluation per parameter.

use crate::objective::TermOrder;
use crate::problem::CubeProblem;
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use rayon::prelude::*;

/// Forward-difference step on the unit cube.
const H: f64 = 1e-5;
/// Most Jacobians per polish.
const MAX_JACOBIANS: usize = 100;
/// The fraction of a step over which the residuals' second directional derivative is
/// differenced (Transtrum & Sethna's `h`).
const PROBE: f64 = 0.1;
/// The acceleration `a` is added to the velocity `v` only where `2|a| <= ALPHA |v|`: a larger
/// bend is more than the quadratic model can be trusted for.
const ALPHA: f64 = 0.75;

fn cost(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// The Jacobian of the residuals at `x` (`r` the residuals there), steps pointing into the cube;
/// its columns in parallel (each is the same on any number of threads).
fn jacobian<P: CubeProblem>(problem: &P, x: &[f64], r: &[f64]) -> Option<Vec<Vec<f64>>> {
    (0..x.len())
        .into_par_iter()
        .map(|j| {
            let h = if x[j] + H > 1.0 { -H } else { H };
            let mut y = x.to_vec();
            y[j] += h;
            let ry = problem.residuals_at(&y)?;
            Some(ry.iter().zip(r).map(|(a, b)| (a - b) / h).collect())
        })
        .collect()
}

/// Solves `(JᵀJ + λ D) δ = -Jᵀr` over the coordinates in `free` (D the diagonal of JᵀJ,
/// floored), `None` if the system is singular.
fn step(columns: &[Vec<f64>], r: &[f64], free: &[usize], lambda: f64) -> Option<Vec<f64>> {
    scaled_step(columns, r, free, lambda, None)
}

/// [`step`] with `diagonal` (indexed by coordinate) added to `JᵀJ` before the damping.
fn scaled_step(
    columns: &[Vec<f64>],
    r: &[f64],
    free: &[usize],
    lambda: f64,
    diagonal: Option<&[f64]>,
) -> Option<Vec<f64>> {
    let k = free.len();
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mut a = Mat::<f64>::from_fn(k, k, |i, j| dot(&columns[free[i]], &columns[free[j]]));
    if let Some(diagonal) = diagonal {
        for i in 0..k {
            a[(i, i)] += diagonal[free[i]];
        }
    }
    let scale = (0..k).map(|i| a[(i, i)]).fold(0.0, f64::max).max(1e-300);
    for i in 0..k {
        a[(i, i)] += lambda * a[(i, i)].max(1e-12 * scale);
    }
    let g = Mat::<f64>::from_fn(k, 1, |i, _| -dot(&columns[free[i]], r));
    let delta = a.llt(Side::Lower).ok()?.solve(&g);
    let out: Vec<f64> = (0..k).map(|i| delta[(i, 0)]).collect();
    out.iter().all(|v| v.is_finite()).then_some(out)
}

/// The Levenberg-Marquardt step of damping `lambda` from `x` over the coordinates in `free`:
/// the point reached and the coordinates that moved freely. A coordinate the step would carry
/// out of the cube is put on that face and held there, and the step is solved again for the
/// others with the held coordinate's move in the residuals. Clamping the step instead would move
/// the others as if it had gone past the face; near an optimum on or close to a face that costs
/// tens of short steps.
fn velocity(
    columns: &[Vec<f64>],
    r: &[f64],
    x: &[f64],
    free: &[usize],
    lambda: f64,
) -> Option<(Vec<f64>, Vec<usize>)> {
    let mut free = free.to_vec();
    let mut y = x.to_vec();
    let mut r = r.to_vec();
    while !free.is_empty() {
        let delta = step(columns, &r, &free, lambda)?;
        let mut held = Vec::new();
        for (&j, d) in free.iter().zip(&delta) {
            y[j] = x[j] + d;
            if !(0.0..=1.0).contains(&y[j]) {
                y[j] = y[j].clamp(0.0, 1.0);
                held.push(j);
            }
        }
        if held.is_empty() {
            break;
        }
        for &j in &held {
            let moved = y[j] - x[j];
            r.iter_mut()
                .zip(&columns[j])
                .for_each(|(ri, cj)| *ri += cj * moved);
        }
        free.retain(|j| !held.contains(j));
        // The coordinates left free are solved again from `x`.
        for &j in &free {
            y[j] = x[j];
        }
    }
    Some((y, free))
}

/// The trial point of damping `lambda`: the [`velocity`] `v`, plus half the geodesic
/// acceleration `a`, the same damped system's solution for the residuals' second directional
/// derivative along `v` (differenced over [`PROBE`] `v`). Where `2|a| > ALPHA |v|` the
/// acceleration is not trusted and the trial is `v` alone (Transtrum & Sethna reject the step
/// instead; on the baseball fits that stalls starts at large damping, 100 Jacobians at a time).
/// `None` if the damped system is singular.
fn trial<P: CubeProblem>(
    problem: &P,
    (columns, r): (&[Vec<f64>], &[f64]),
    x: &[f64],
    free: &[usize],
    lambda: f64,
) -> Option<Vec<f64>> {
    let (mut y, free) = velocity(columns, r, x, free, lambda)?;
    let v: Vec<f64> = y.iter().zip(x).map(|(a, b)| a - b).collect();
    let probe: Vec<f64> = x.iter().zip(&v).map(|(a, b)| a + PROBE * b).collect();
    let Some(r_probe) = problem.residuals_at(&probe) else {
        return Some(y);
    };
    let second: Vec<f64> = r_probe
        .iter()
        .zip(r)
        .enumerate()
        .map(|(i, (rp, r0))| {
            let along: f64 = columns.iter().zip(&v).map(|(c, vj)| c[i] * vj).sum();
            2.0 / PROBE * ((rp - r0) / PROBE - along)
        })
        .collect();
    let norm = |w: &[f64]| w.iter().map(|q| q * q).sum::<f64>().sqrt();
    match step(columns, &second, &free, lambda) {
        Some(a) if 2.0 * norm(&a) <= ALPHA * norm(&v) => {
            for (&j, aj) in free.iter().zip(&a) {
                y[j] = (y[j] + 0.5 * aj).clamp(0.0, 1.0);
            }
        }
        _ => {}
    }
    Some(y)
}

/// The end of a Levenberg-Marquardt polish.
pub(crate) struct Polished {
    /// The best point.
    pub(crate) x: Vec<f64>,
    /// Its cost (never more than the start's).
    pub(crate) cost: f64,
    /// Whether it converged: its last step gained at most 1e-9 relative, every coordinate is
    /// held on a face by its gradient, or the cost is zero. Otherwise no damping lowered the
    /// cost (a kink, noise) or the Jacobians ran out.
    pub(crate) converged: bool,
    /// Whether the face phase was stopped where it crept ([`Creep`]): near a minimum, not at it.
    pub(crate) crept: bool,
}

/// When a polish may stop where it creeps: when the last `jacobians` Jacobians of its face phase
/// together lowered the cost by at most `gain` (relative). The face phase creeps along the
/// valleys of parameters the data do not pin down, tens of Jacobians at gains of 1e-5 each. A
/// search's starts need their ends only to the agreement's tolerance (1e-2), and the best of them
/// is polished in full afterwards. A start stopped this way ends above its full polish's end
/// (on the measured fixtures by 0.01-0.2 %, and by 2 % where the valley led on to another
/// basin): it counts as agreeing less often, and a basin whose starts all stop creeping can lose
/// to another a few per cent above its minimum. On the measured fixtures every default fit still
/// ends within 1 % of the best cost known, with a quarter fewer evaluations (BENCHMARKS.md,
/// "Identification: the global optimum on measured data").
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Creep {
    /// Jacobians looked back over.
    pub(crate) jacobians: usize,
    /// The gain over them (relative) at or below which the polish stops.
    pub(crate) gain: f64,
}

/// The creep rule of a search's starts.
pub(crate) const START_CREEP: Creep = Creep {
    jacobians: 5,
    gain: 3e-4,
};

/// Where a polish stands: the point, its residuals and their cost.
struct Point {
    x: Vec<f64>,
    r: Vec<f64>,
    cost: f64,
}

impl Point {
    /// `x` evaluated; `None` if the problem has no residuals.
    fn at<P: CubeProblem>(problem: &P, x: Vec<f64>) -> Option<Self> {
        let r = problem.residuals_at(&x)?;
        Some(Self {
            cost: cost(&r),
            x,
            r,
        })
    }

    /// The end of a polish here (a zero cost cannot be lowered: converged).
    fn polished(self, converged: bool, crept: bool) -> Polished {
        Polished {
            converged: converged || self.cost == 0.0,
            crept,
            x: self.x,
            cost: self.cost,
        }
    }
}

/// How one Jacobian's damping search ended.
enum Descent {
    /// A step gained more than the tolerance: take another Jacobian.
    Gained,
    /// A step gained at most the tolerance (relative): converged.
    Settled,
    /// No damping below 1e12 lowered the cost (a kink, noise).
    Stuck,
}

/// The damping search of one Jacobian: `trial` at damping `lambda`, raised 4x per trial that
/// does not lower the cost and 10x where `trial` finds the damped system singular, until one
/// lowers it; `at` moves there and the damping falls 3x. A trial is evaluated only as far as
/// it takes to tell that it does not lower the cost ([`CubeProblem::residuals_below`], its
/// terms tried in `order`).
fn descend<P: CubeProblem>(
    problem: &P,
    (at, order): (&mut Point, &mut TermOrder),
    lambda: &mut f64,
    tolerance: f64,
    trial: impl Fn(&Point, f64) -> Option<Vec<f64>>,
) -> Descent {
    while *lambda < 1e12 {
        let Some(y) = trial(at, *lambda) else {
            *lambda *= 10.0;
            continue;
        };
        let next = problem.residuals_below(&y, at.cost, order).map(|r| Point {
            cost: cost(&r),
            x: y,
            r,
        });
        if let Some(next) = next.filter(|next| next.cost < at.cost) {
            let gain = at.cost - next.cost;
            *at = next;
            *lambda = (*lambda / 3.0).max(1e-12);
            return if gain > tolerance * at.cost {
                Descent::Gained
            } else {
                Descent::Settled
            };
        }
        *lambda *= 4.0;
    }
    Descent::Stuck
}

/// Polishes `x` (cost `c`) by Levenberg-Marquardt, the [`interior`] phase and then the
/// [`faces`] phase (stopped where it creeps if `creep` says when); `None` if the problem has
/// no residuals.
pub(crate) fn polish<P: CubeProblem>(
    problem: &P,
    x: &[f64],
    c: f64,
    creep: Option<Creep>,
) -> Option<Polished> {
    match interior(problem, x, c) {
        Some(inner) if inner.cost <= c || c.is_nan() => {
            let end = faces(problem, &inner.x, inner.cost, creep)?;
            // Where the face phase finds nothing to gain, the interior phase's end stands.
            let converged = end.converged || (inner.converged && end.cost == inner.cost);
            Some(Polished { converged, ..end })
        }
        _ => faces(problem, x, c, creep),
    }
}

/// The interior phase ends when a step gains at most this (relative): the face phase finishes
/// faster than the interior phase creeps towards a face. On the measured fixtures 1e-2 leaves
/// every default fit in the best basin, as 1e-4 and 1e-9 do, with 6 % fewer evaluations than
/// 1e-4 (BENCHMARKS.md, "Identification: the global optimum on measured data").
const INTERIOR_GAIN: f64 = 1e-2;

/// How far inside the cube the interior phase starts (on the unit cube's scale).
const INSIDE: f64 = 1e-9;

/// The interior phase: Levenberg-Marquardt steps in Coleman and Li's scaled variables, each
/// kept strictly inside the cube. At `x` with gradient `g = Jᵀr`, coordinate `j` is scaled by
/// `d_j = √v_j`, `v_j` the distance to the face that `-g_j` points at (1 where `g_j = 0`), and
/// the scaled step `p` solves `(ĴᵀĴ + diag|g| + λ D) p = -Ĵᵀr` with `Ĵ = J diag(d)`; the
/// `|g_j|` term is the curvature the scaling adds. A step `d∘p` that would leave the cube is
/// shortened to `θ` of the way to the first face it meets, `θ = max(0.995, 1 - |Ĵᵀr|∞)`.
/// `None` if the problem has no residuals or the start cannot be evaluated.
pub(crate) fn interior<P: CubeProblem>(problem: &P, x: &[f64], c: f64) -> Option<Polished> {
    let mut at = Point::at(
        problem,
        x.iter().map(|v| v.clamp(INSIDE, 1.0 - INSIDE)).collect(),
    )?;
    if at.cost.is_nan() || (c.is_finite() && at.cost > c * (1.0 + 1e-6) + 1e-300) {
        return None;
    }
    let all: Vec<usize> = (0..at.x.len()).collect();
    let mut order = TermOrder::default();
    let mut lambda = 1e-3;
    let mut converged = false;
    for _ in 0..MAX_JACOBIANS {
        let columns = jacobian(problem, &at.x, &at.r)?;
        let gradient = gradient(&columns, &at.r);
        let scale: Vec<f64> =
            at.x.iter()
                .zip(&gradient)
                .map(|(&xj, &gj)| distance_to_face(xj, gj).sqrt())
                .collect();
        let scaled: Vec<Vec<f64>> = columns
            .iter()
            .zip(&scale)
            .map(|(col, d)| col.iter().map(|a| a * d).collect())
            .collect();
        let curvature: Vec<f64> = gradient.iter().map(|g| g.abs()).collect();
        let scaled_gradient = gradient
            .iter()
            .zip(&scale)
            .map(|(g, d)| (g * d).abs())
            .fold(0.0, f64::max);
        let theta = (1.0 - scaled_gradient).max(0.995);
        let trial = |at: &Point, lambda: f64| {
            let p = scaled_step(&scaled, &at.r, &all, lambda, Some(&curvature))?;
            let step: Vec<f64> = p.iter().zip(&scale).map(|(p, d)| p * d).collect();
            Some(inside(&at.x, &step, theta))
        };
        match descend(
            problem,
            (&mut at, &mut order),
            &mut lambda,
            INTERIOR_GAIN,
            trial,
        ) {
            Descent::Gained => {}
            Descent::Settled => {
                converged = true;
                break;
            }
            Descent::Stuck => break,
        }
    }
    Some(at.polished(converged, false))
}

/// `Jᵀr`.
fn gradient(columns: &[Vec<f64>], r: &[f64]) -> Vec<f64> {
    columns
        .iter()
        .map(|col| col.iter().zip(r).map(|(a, b)| a * b).sum())
        .collect()
}

/// The distance from `x` to the face of `[0, 1]` that the descent direction `-g` points at (1
/// where `g = 0`).
fn distance_to_face(x: f64, g: f64) -> f64 {
    if g < 0.0 {
        1.0 - x
    } else if g > 0.0 {
        x
    } else {
        1.0
    }
}

/// `x + step`, or where that leaves the cube, `x` plus `theta` of the part of `step` that
/// reaches the first face it meets.
fn inside(x: &[f64], step: &[f64], theta: f64) -> Vec<f64> {
    let reach = x
        .iter()
        .zip(step)
        .map(|(&xj, &sj)| {
            if sj > 0.0 {
                (1.0 - xj) / sj
            } else if sj < 0.0 {
                -xj / sj
            } else {
                f64::INFINITY
            }
        })
        .fold(1.0, f64::min);
    let t = if reach < 1.0 { theta * reach } else { 1.0 };
    x.iter()
        .zip(step)
        .map(|(xj, sj)| (xj + t * sj).clamp(0.0, 1.0))
        .collect()
}

/// The face phase: Levenberg-Marquardt with geodesic acceleration from `x` (cost `c`), a
/// coordinate that a step carries out of the cube held on that face; stopped where it creeps if
/// `creep` says when.
pub(crate) fn faces<P: CubeProblem>(
    problem: &P,
    x: &[f64],
    c: f64,
    creep: Option<Creep>,
) -> Option<Polished> {
    let mut at = Point::at(problem, x.iter().map(|v| v.clamp(0.0, 1.0)).collect())?;
    if c.is_finite() && (at.cost.is_nan() || at.cost > c) {
        // The clamped start is worse than the caller's point: nothing to polish from.
        return None;
    }
    let mut order = TermOrder::default();
    let mut lambda = 1e-3;
    let mut converged = false;
    // The cost before each Jacobian.
    let mut costs = Vec::new();
    for _ in 0..MAX_JACOBIANS {
        if let Some(creep) = creep {
            let back = costs.len().checked_sub(creep.jacobians).map(|k| costs[k]);
            if back.is_some_and(|b: f64| b - at.cost <= creep.gain * at.cost) {
                return Some(at.polished(false, true));
            }
            costs.push(at.cost);
        }
        let columns = jacobian(problem, &at.x, &at.r)?;
        let gradient = gradient(&columns, &at.r);
        // Coordinates on a face whose gradient points out of the cube stay there.
        let x = &at.x;
        let free: Vec<usize> = (0..x.len())
            .filter(|&j| {
                !((x[j] <= 0.0 && gradient[j] > 0.0) || (x[j] >= 1.0 && gradient[j] < 0.0))
            })
            .collect();
        if free.is_empty() {
            converged = true;
            break;
        }
        let step =
            |at: &Point, lambda: f64| trial(problem, (&columns, &at.r), &at.x, &free, lambda);
        match descend(problem, (&mut at, &mut order), &mut lambda, 1e-9, step) {
            Descent::Gained => {}
            Descent::Settled => {
                converged = true;
                break;
            }
            Descent::Stuck => break,
        }
    }
    Some(at.polished(converged, false))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicU64, Ordering};

    /// A least-squares problem on the unit square with counted evaluations.
    struct Squares<F> {
        residuals: F,
        evaluations: AtomicU64,
    }

    impl<F: Fn(&[f64]) -> Vec<f64> + Sync> Squares<F> {
        fn new(residuals: F) -> Self {
            Self {
                residuals,
                evaluations: AtomicU64::new(0),
            }
        }
    }

    impl<F: Fn(&[f64]) -> Vec<f64> + Sync> CubeProblem for Squares<F> {
        fn dim(&self) -> usize {
            2
        }
        fn cost_at(&self, s: &[f64]) -> f64 {
            cost(&self.residuals_at(s).unwrap_or_default())
        }
        fn evaluations(&self) -> u64 {
            self.evaluations.load(Ordering::Relaxed)
        }
        fn residuals_at(&self, s: &[f64]) -> Option<Vec<f64>> {
            self.evaluations.fetch_add(1, Ordering::Relaxed);
            Some((self.residuals)(s))
        }
    }

    /// Rosenbrock's curved valley `s1 = s0²`, with its minimum (cost 0) at `s0 = at`.
    fn valley(at: f64) -> impl Fn(&[f64]) -> Vec<f64> + Sync {
        move |s: &[f64]| vec![10.0 * (s[1] - s[0] * s[0]), s[0] - at]
    }

    #[test]
    fn a_step_past_a_face_holds_that_coordinate_and_solves_for_the_others() {
        // r = A s - b with A = [[1, 1], [1, 2], [0, 1]], so AᵀA = [[2, 3], [3, 6]].
        let a = [[1.0, 1.0], [1.0, 2.0], [0.0, 1.0]];
        let columns: Vec<Vec<f64>> = (0..2).map(|j| (0..3).map(|i| a[i][j]).collect()).collect();
        let x = [0.5, 0.5];
        let residuals = |b: [f64; 3]| -> Vec<f64> {
            (0..3)
                .map(|i| a[i][0] * x[0] + a[i][1] * x[1] - b[i])
                .collect()
        };
        // b = (3, 4, 0): the unconstrained minimum is (3, 1/3) (Aᵀb = (7, 11)). On the face
        // s0 = 1 the minimum over s1 solves 6 s1 = 8, past the face s1 = 1 too: the corner.
        // Clamping the free step would give (1, 1/3).
        let (y, free) =
            velocity(&columns, &residuals([3.0, 4.0, 0.0]), &x, &[0, 1], 1e-14).unwrap();
        assert_eq!(y, vec![1.0, 1.0]);
        assert!(free.is_empty());
        // b = A (1.5, 0.2) = (1.7, 1.9, 0.2): on the face s0 = 1 the minimum over s1 solves
        // (s1 - 0.7) + 2 (2 s1 - 0.9) + (s1 - 0.2) = 0, s1 = 0.45. Clamping would give 0.2.
        let (y, free) =
            velocity(&columns, &residuals([1.7, 1.9, 0.2]), &x, &[0, 1], 1e-14).unwrap();
        assert_eq!(y[0], 1.0);
        assert!((y[1] - 0.45).abs() < 1e-12, "s1 = {}", y[1]);
        assert_eq!(free, vec![1]);
    }

    #[test]
    fn the_acceleration_bends_a_step_onto_a_parabola_and_is_dropped_where_it_is_large() {
        // r = (10 (s1 - s0²), s0 - 0.7) with its exact Jacobian columns (-20 s0, 1) and (10, 0): for quadratic
        // residuals the differenced second derivative is exact, r_vv = (-20 v0², 0).
        let problem = Squares::new(valley(0.7));
        let at = |x: [f64; 2]| {
            let columns = vec![vec![-20.0 * x[0], 1.0], vec![10.0, 0.0]];
            let r = valley(0.7)(&x);
            trial(&problem, (&columns, &r), &x, &[0, 1], 1e-14).unwrap()
        };
        // From (0.65, 0.4): v = (0.05, 0.0875), a = (0, 0.005) with 2|a| <= 0.75 |v|, so the
        // trial is x + v + a/2 = (0.7, 0.49), the minimum, where the straight step reaches
        // (0.7, 0.4875).
        assert_near(&at([0.65, 0.4]), [0.7, 0.49], 1e-12);
        // From (0.3, 0.5): v = (0.4, -0.17), a = (0, 0.32): 2|a| = 0.64 > 0.75 |v| = 0.33, so
        // the trial is the straight step (0.7, 0.33).
        assert_near(&at([0.3, 0.5]), [0.7, 0.33], 1e-12);
    }

    /// The polish of the valley with its minimum at `s0 = at`, from `start`.
    fn polished(at: f64, start: [f64; 2]) -> (Vec<f64>, f64) {
        let problem = Squares::new(valley(at));
        let end = polish(&problem, &start, problem.cost_at(&start), None).unwrap();
        (end.x, end.cost)
    }

    fn assert_near(x: &[f64], want: [f64; 2], tol: f64) {
        assert!(
            (x[0] - want[0]).abs() < tol && (x[1] - want[1]).abs() < tol,
            "{x:?} against {want:?}"
        );
    }

    /// A smooth minimum converges (with residuals left, and at zero cost, which nothing
    /// lowers); a minimum on a kink does not: no damping lowers the cost there and the
    /// forward-difference Jacobian straddles the kink, so the caller's Nelder-Mead takes over.
    #[test]
    fn the_polish_says_whether_it_converged() {
        type Residuals = Box<dyn Fn(&[f64]) -> Vec<f64> + Sync>;
        let cases: [(Residuals, bool); 3] = [
            (
                Box::new(|s: &[f64]| vec![10.0 * (s[1] - s[0] * s[0]), s[0] - 0.7, 0.1]),
                true,
            ),
            (Box::new(valley(0.7)), true),
            (
                Box::new(|s: &[f64]| vec![(s[0] - 0.3).abs() + 0.1, s[1] - 0.5]),
                false,
            ),
        ];
        for (i, (residuals, converges)) in cases.into_iter().enumerate() {
            let problem = Squares::new(residuals);
            let start = [0.6, 0.2];
            let end = polish(&problem, &start, problem.cost_at(&start), None).unwrap();
            assert_eq!(end.converged, converges, "case {i}: {:?}", end.x);
            assert!(end.cost < 0.0101, "case {i}: cost {}", end.cost);
        }
    }

    /// A curved valley whose floor falls by 1e-4 of the cost from end to end: the polish of a
    /// search's start stops creeping along it within a few Jacobians of the floor, above the
    /// minimum by less than the floor's whole fall; the full polish goes on to the minimum.
    #[test]
    fn a_start_stops_where_its_polish_creeps() {
        let floor = |s: &[f64]| vec![10.0 * (s[1] - s[0] * s[0]), 0.01 * (s[0] - 0.9), 1.0];
        let start = [0.1, 0.9];
        let (creeping, full) = (Squares::new(floor), Squares::new(floor));
        let stopped = faces(
            &creeping,
            &start,
            creeping.cost_at(&start),
            Some(START_CREEP),
        )
        .unwrap();
        let end = faces(&full, &start, full.cost_at(&start), None).unwrap();
        assert!(stopped.crept && !stopped.converged);
        assert!(end.converged && !end.crept);
        assert_near(&end.x, [0.9, 0.81], 1e-4);
        assert!(
            stopped.cost - end.cost < 1e-4 * end.cost,
            "{} against {}",
            stopped.cost,
            end.cost
        );
        let (a, b) = (creeping.evaluations(), full.evaluations());
        assert!(a < b, "{a} against {b} evaluations");
    }

    #[test]
    fn the_polish_follows_a_curved_valley_to_its_minimum() {
        let (x, c) = polished(0.7, [0.05, 0.9]);
        assert!(c < 1e-20, "cost {c}");
        assert_near(&x, [0.7, 0.49], 1e-10);
    }

    #[test]
    fn the_polish_stops_on_the_face_that_holds_the_constrained_minimum() {
        // The valley's minimum s0 = 1.3 lies outside; on the square the minimum is the corner
        // (1, 1), where the first residual vanishes and the second is 0.3: cost 0.09.
        let (x, c) = polished(1.3, [0.2, 0.8]);
        assert_eq!(x, vec![1.0, 1.0]);
        assert!((c - 0.09).abs() < 1e-15, "cost {c}");
    }

    #[test]
    fn a_step_that_would_leave_the_cube_stops_short_of_the_face_it_meets() {
        // From (0.5, 0.9), the step (1, 0.2) reaches s1 = 1 at half its length, before s0 = 1.
        let y = inside(&[0.5, 0.9], &[1.0, 0.2], 0.995);
        assert_near(&y, [0.5 + 0.4975, 0.9 + 0.0995], 1e-15);
        // A step inside the cube is taken whole.
        assert_eq!(inside(&[0.5, 0.5], &[0.1, -0.2], 0.995), vec![0.6, 0.3]);
        assert_eq!(distance_to_face(0.3, 2.0), 0.3);
        assert_eq!(distance_to_face(0.3, -2.0), 0.7);
        assert_eq!(distance_to_face(0.3, 0.0), 1.0);
    }

    /// The single-baseball fit of fixtures/measured_cor.toml ("Baseball 3 on wood NDBWMCM")
    /// has local minima on the faces 16-23 % above its optimum, J1 = 4.4302e-6 at `B_b` =
    /// 0.039, `Γ_b = B_b`, `n = 4`, `p = 2.4` (BENCHMARKS.md). From 16 seeded uniform starts,
    /// the face phase alone reaches it from none; both phases from six.
    #[test]
    fn the_interior_phase_reaches_the_best_basin_from_more_starts() {
        use crate::{Dataset, Objective, Param, Space, Weights};
        use bw_models::{input::Zero, ModelKind, Settings};
        use rand::{Rng, SeedableRng};
        let file = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../fixtures/data/real/baseball_ball3_v0_e.csv"
        );
        let data = Dataset::load(std::path::Path::new(file)).unwrap();
        let free = |lo, hi| Param::Free { lo, hi, log: false };
        let sigma_b = Param::Free {
            lo: 1e-5,
            hi: 1.0,
            log: true,
        };
        let params = [free(0.0, 10.0), free(-1.0, 1.0), free(0.02, 0.98), sigma_b]
            .into_iter()
            .chain([
                free(1.0, 4.0),
                free(1.0, 4.0),
                Param::Fixed(1.0),
                Param::Fixed(1.0),
            ]);
        let params: [Param; 8] = params.collect::<Vec<_>>().try_into().unwrap();
        let space = Space::new(ModelKind::Mcm, params, None).unwrap();
        let weights = Weights { j1: 1.0, j2: 0.0 };
        let objective = Objective::new(&space, &data, &Zero, Settings::default(), weights).unwrap();
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let starts: Vec<Vec<f64>> = (0..16)
            .map(|_| (0..6).map(|_| rng.random::<f64>()).collect())
            .collect();
        // The 32 polishes are independent: run them side by side.
        let reached = |phases: &(dyn Fn(&[f64], f64) -> Option<Polished> + Sync)| {
            use rayon::prelude::*;
            starts
                .par_iter()
                .filter(|s| {
                    let end = phases(s, objective.cost_at(s)).unwrap();
                    end.cost <= 1.02 * 4.4302e-6
                })
                .count()
        };
        let face_only = reached(&|s, c| faces(&objective, s, c, None));
        let both = reached(&|s, c| polish(&objective, s, c, None));
        assert!(face_only <= 1 && both >= 4, "{face_only} and {both} of 16");
    }

    #[test]
    fn the_polish_reaches_a_minimum_next_to_a_face() {
        // The minimum (0.001, 1e-6) lies 1e-3 inside a face, as the DSS NDBWSHCCM optimum of
        // kharaz.toml does in `g`: full steps overshoot it.
        let (x, c) = polished(0.001, [0.6, 0.5]);
        assert!(c < 1e-20, "cost {c}");
        assert_near(&x, [0.001, 1e-6], 1e-10);
    }
}

//! Confidence intervals of the identified parameters and confidence bands of the predicted
//! `e(v0)` and `t_d(v0)`, by linearisation at the optimum (the delta method).
//!
//! Model: each weighted residual (see [`Objective::weighted_residuals`]) is the model's error
//! plus independent noise of one variance `σ²`, so that the weights must make the CoR and
//! duration residuals equally noisy when both are fitted. `G` is the `M × k` sensitivity of the
//! weighted residuals to the `k` free cube coordinates not on a bound (central differences),
//! with singular values `s_i` and right singular vectors `v_i`; `r` counts the `s_i` above
//! 1e-6 `s_1` (the parameter combinations the data determine) and `σ̂² = Σ r² / (M - r)`. The
//! covariance of the cube coordinates is the classical `σ̂² (GᵀG)⁻¹ = Σ_i v_i v_iᵀ σ̂² / s_i²`
//! over the determined directions, and `v_i v_iᵀ / 12` (the variance of a uniform distribution
//! on the box: the bounds are all that is known) for each direction the data do not determine.
//! A prediction that depends on those (typically away from the measured speeds) gets a wide
//! band instead of a falsely narrow one. (Capping every direction's variance at 1/12, or a
//! Gaussian prior of that variance, narrowed the band near the data below its nominal coverage:
//! `BENCHMARKS.md`.)
//! A prediction `q` (a parameter, `e(v0)`, `t_d(v0)`) gets `q ± t_{0.975, M-r} sqrt(∇qᵀ C ∇q)`;
//! a parameter's interval is taken on its search scale (logarithmic where searched so) and
//! clipped to its bounds (listed in `clipped` when it reaches one). Parameters on a bound are
//! held there and get no interval. The band's coverage is validated by simulation
//! (`BENCHMARKS.md`, `bwc-identify coverage`).

use crate::data::Dataset;
use crate::error::IdentifyError;
use crate::objective::{predict, Objective, Prediction};
use crate::space::NAMES;
use bw_models::input::Input;
use statrs::distribution::{ContinuousCDF, StudentsT};

/// Confidence level of intervals and bands.
pub const LEVEL: f64 = 0.95;
/// Step of the central differences on the unit cube.
const H: f64 = 1e-4;
/// Singular values below this fraction of the largest do not count as determined directions
/// (for the residual degrees of freedom).
const RANK_TOLERANCE: f64 = 1e-6;
/// The variance of a direction the data do not determine: that of a uniform distribution on
/// `[0, 1]`, the bounds being all that is known of it.
const BOX_VARIANCE: f64 = 1.0 / 12.0;

/// Parameter intervals, and what is needed to put a band on any prediction.
#[derive(Debug, Clone, PartialEq)]
pub struct Uncertainty {
    /// How the intervals were computed.
    pub method: &'static str,
    /// Confidence level.
    pub level: f64,
    /// Standard deviation `σ̂` of the weighted residuals `sqrt(w1 / M1) (e_i - ê_i)` and
    /// `sqrt(w2 / M2) (t_i - t̂_i)` (dimensionless scale of the cost, not of the data): the
    /// noise level the intervals are built on. [`Uncertainty::sigma_e`] and
    /// [`Uncertainty::sigma_t_d`] give it in the data's units.
    pub sigma: f64,
    /// The noise standard deviation of the CoR this implies, `σ̂ sqrt(M1 / w1)` (units of `e`;
    /// `sqrt(Σ (e_i - ê_i)² / (M - r))` on a CoR-only fit), where `J1` is weighted.
    pub sigma_e: Option<f64>,
    /// The noise standard deviation of the duration, `σ̂ sqrt(M2 / w2)` (s), where `J2` is
    /// weighted.
    pub sigma_t_d: Option<f64>,
    /// Residual degrees of freedom `M - r`.
    pub dof: usize,
    /// Parameter combinations the data determine (`r`).
    pub rank: usize,
    /// Per base parameter (`B_b`, `Gamma_b`, `kappa`, `sigma_b`, `n`, `p`, `U_b`, `T_b`) that is
    /// free: its interval, or `None` when it lies on a bound.
    pub params: Vec<(&'static str, Option<[f64; 2]>)>,
    /// Parameters whose interval reaches a bound of the search (the data do not bound them).
    pub clipped: Vec<&'static str>,
    point: Vec<f64>,
    /// Covariance in cube coordinates (all free coordinates; zero where held on a bound).
    covariance: Vec<Vec<f64>>,
    quantile: f64,
}

/// A band point: the prediction at `v0` with its lower and upper confidence limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandPoint {
    /// Impact speed (m/s).
    pub v0: f64,
    /// Predicted CoR and its limits.
    pub e: [f64; 3],
    /// Predicted duration (s) and its limits (NaN where the bodies do not separate).
    pub t_d: [f64; 3],
}

/// A vector-valued function of a cube point.
type VectorFn<'a> = dyn Fn(&[f64]) -> Result<Vec<f64>, IdentifyError> + 'a;

/// Central-difference columns of `f` at `s` over the coordinates `free` (one-sided at faces).
fn columns(s: &[f64], free: &[usize], f: &VectorFn) -> Result<Vec<Vec<f64>>, IdentifyError> {
    free.iter()
        .map(|&j| {
            let (mut lo, mut hi) = (s.to_vec(), s.to_vec());
            hi[j] = (s[j] + H).min(1.0);
            lo[j] = (s[j] - H).max(0.0);
            let (a, b) = (f(&hi)?, f(&lo)?);
            let step = hi[j] - lo[j];
            Ok(a.iter().zip(&b).map(|(x, y)| (x - y) / step).collect())
        })
        .collect()
}

/// Linearised intervals at the optimum `s` of `objective` (evaluated with its settings).
/// `at_bound` holds the coordinates held on a bound (positions in the search order).
///
/// # Errors
/// [`IdentifyError::Model`] when a simulation fails; [`IdentifyError::Objectives`] when there
/// are no more data points than determined parameter combinations (no residual degrees of
/// freedom to estimate the noise from).
pub fn uncertainty<I: Input + Sync>(
    objective: &Objective<'_, I>,
    s: &[f64],
    at_bound: &[usize],
) -> Result<Uncertainty, IdentifyError> {
    let space = objective.space();
    let names = space.free_names();
    let free: Vec<usize> = (0..s.len()).filter(|j| !at_bound.contains(j)).collect();
    let (predictions, _) = objective.evaluate(s)?;
    let r = objective.weighted_residuals(&predictions);
    let residuals = |x: &[f64]| -> Result<Vec<f64>, IdentifyError> {
        let (p, _) = objective.evaluate(x)?;
        Ok(objective.weighted_residuals(&p))
    };
    if free.is_empty() {
        return Err(IdentifyError::Objectives {
            reason: "no free parameter off a bound: nothing to estimate".into(),
        });
    }
    let g = columns(s, &free, &residuals)?;
    let m = r.len();
    let Svd { values, vectors } = svd(&g, m)?;
    let largest = values.iter().copied().fold(0.0, f64::max);
    let rank = values
        .iter()
        .filter(|&&v| v > RANK_TOLERANCE * largest)
        .count();
    if rank == 0 {
        return Err(IdentifyError::Objectives {
            reason: "the data determine no parameter combination (the model's predictions do \
                     not change with any free parameter off its bound)"
                .into(),
        });
    }
    if m <= rank {
        return Err(IdentifyError::Objectives {
            reason: format!(
                "{m} data values for {rank} determined parameter combinations: no residual \
                 degrees of freedom to estimate the noise (intervals need more data points)"
            ),
        });
    }
    let dof = m - rank;
    let rss: f64 = r.iter().map(|x| x * x).sum();
    let sigma = (rss / dof as f64).sqrt();
    let covariance = covariance(&Svd { values, vectors }, &free, s.len(), sigma);
    let (scale_e, scale_t_d) = objective.residual_scales();
    let quantile = StudentsT::new(0.0, 1.0, dof as f64)
        .map_err(|e| IdentifyError::Objectives {
            reason: format!("Student-t with {dof} degrees of freedom: {e}"),
        })?
        .inverse_cdf(0.5 + LEVEL / 2.0);
    let mut u = Uncertainty {
        method:
            "linearised (delta method), Student-t; undetermined directions spread over their bounds",
        level: LEVEL,
        sigma,
        sigma_e: scale_e.map(|w| sigma / w),
        sigma_t_d: scale_t_d.map(|w| sigma / w),
        dof,
        rank,
        params: Vec::new(),
        clipped: Vec::new(),
        point: s.to_vec(),
        covariance,
        quantile,
    };
    u.parameter_intervals(objective, &names, at_bound);
    Ok(u)
}

/// The covariance (`n × n`, zero off the `free` quantities) from the singular values and
/// vectors of the weighted residuals' Jacobian over the free quantities: `σ² / s²` along a
/// determined direction, [`BOX_VARIANCE`] along one the data do not determine.
fn covariance(svd: &Svd, free: &[usize], n: usize, sigma: f64) -> Vec<Vec<f64>> {
    let largest = svd.values.iter().copied().fold(0.0, f64::max);
    let mut covariance = vec![vec![0.0; n]; n];
    for (c, &si) in svd.values.iter().enumerate() {
        let determined = si > RANK_TOLERANCE * largest;
        let variance = if determined {
            sigma * sigma / (si * si)
        } else {
            BOX_VARIANCE
        };
        for (a, &i) in free.iter().enumerate() {
            for (b, &j) in free.iter().enumerate() {
                covariance[i][j] += svd.vectors[a][c] * svd.vectors[b][c] * variance;
            }
        }
    }
    covariance
}

/// Singular values (`k`, zero beyond the `m` rows) and right singular vectors (`vectors[a][c]`:
/// component `a` of vector `c`) of the `m × k` matrix with columns `g`.
struct Svd {
    values: Vec<f64>,
    vectors: Vec<Vec<f64>>,
}

fn svd(g: &[Vec<f64>], m: usize) -> Result<Svd, IdentifyError> {
    let k = g.len();
    if k == 0 || m == 0 {
        let identity = (0..k).map(|a| (0..k).map(|c| f64::from(u8::from(a == c))).collect());
        return Ok(Svd {
            values: vec![0.0; k],
            vectors: identity.collect(),
        });
    }
    let jac = faer::Mat::<f64>::from_fn(m, k, |i, j| g[j][i]);
    let d = jac.svd().map_err(|e| IdentifyError::Optimizer {
        message: format!("SVD of the sensitivity matrix: {e:?}"),
    })?;
    Ok(Svd {
        values: (0..k)
            .map(|i| if i < m { d.S().column_vector()[i] } else { 0.0 })
            .collect(),
        vectors: (0..k)
            .map(|a| (0..k).map(|c| d.V()[(a, c)]).collect())
            .collect(),
    })
}

impl Uncertainty {
    /// Standard deviation of a linear functional `∇q` of the cube coordinates.
    fn sd(&self, grad: &[f64]) -> f64 {
        let mut v = 0.0;
        for (i, gi) in grad.iter().enumerate() {
            for (j, gj) in grad.iter().enumerate() {
                v += gi * self.covariance[i][j] * gj;
            }
        }
        v.max(0.0).sqrt()
    }

    fn parameter_intervals<I: Input + Sync>(
        &mut self,
        objective: &Objective<'_, I>,
        names: &[&'static str],
        at_bound: &[usize],
    ) {
        let space = objective.space();
        let s = self.point.clone();
        for (j, name) in names.iter().enumerate() {
            if at_bound.contains(&j) {
                self.params.push((base_name(name), None));
                continue;
            }
            let half = self.quantile * self.covariance[j][j].max(0.0).sqrt();
            let (lo, hi) = ((s[j] - half).max(0.0), (s[j] + half).min(1.0));
            if lo == 0.0 || hi == 1.0 {
                self.clipped.push(base_name(name));
            }
            // The quantity by its slot (a family's parameter has a name of its own in the slot
            // of sigma_b), at the coordinate moved to `t`.
            let slot = space.free_indices()[j];
            let at = |t: f64| {
                let mut x = s.clone();
                x[j] = t;
                space.quantities(&x)[slot]
            };
            let (a, b) = (at(lo), at(hi));
            if *name == "g" {
                // Γ_b = g B_b mixes two coordinates: its interval by the delta method.
                let grad: Vec<f64> = (0..s.len())
                    .map(|i| {
                        let (mut p, mut q) = (s.clone(), s.clone());
                        p[i] = (s[i] + H).min(1.0);
                        q[i] = (s[i] - H).max(0.0);
                        (space.decode(&p).gamma_b - space.decode(&q).gamma_b) / (p[i] - q[i])
                    })
                    .collect();
                let gamma = space.decode(&s).gamma_b;
                let h = self.quantile * self.sd(&grad);
                let bb = space.decode(&s).b_b;
                self.params
                    .push(("Gamma_b", Some([(gamma - h).max(-bb), (gamma + h).min(bb)])));
            } else {
                self.params
                    .push((base_name(name), Some([a.min(b), a.max(b)])));
            }
        }
        if space.known().is_some() {
            if let Some((_, Some([lo, hi]))) = self.params.iter().find(|(n, _)| *n == "U_b") {
                let m = space.known().expect("checked").m;
                let t = Some([m * lo, m * hi]);
                self.params.push(("T_b", t));
            }
        }
    }

    /// The band of `e(v0)` and `t_d(v0)` at `speeds` (m/s); the CoR's limits are clipped to
    /// `e >= 0`, and to `e <= 1` without input.
    ///
    /// # Errors
    /// [`IdentifyError::Model`] when a simulation fails.
    pub fn band<I: Input + Sync>(
        &self,
        objective: &Objective<'_, I>,
        speeds: &[f64],
    ) -> Result<Vec<BandPoint>, IdentifyError> {
        let grid = Dataset::at_speeds(&objective.data().path, speeds);
        let at = |x: &[f64]| -> Result<Vec<Prediction>, IdentifyError> {
            let map = objective.space().map(&objective.space().decode(x))?;
            Ok(predict(
                &map,
                objective.input(),
                &grid,
                objective.settings(),
            )?)
        };
        let centre = at(&self.point)?;
        let flat = |x: &[f64]| -> Result<Vec<f64>, IdentifyError> {
            Ok(at(x)?.iter().flat_map(|p| [p.e, p.t_d]).collect())
        };
        let all: Vec<usize> = (0..self.point.len())
            .filter(|&j| self.covariance[j][j] > 0.0)
            .collect();
        let cols = columns(&self.point, &all, &flat)?;
        let mut grad = vec![0.0; self.point.len()];
        let no_input = objective.input().is_zero();
        Ok(centre
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let mut limits = |row: usize, value: f64| {
                    grad.iter_mut().for_each(|g| *g = 0.0);
                    for (c, &j) in all.iter().enumerate() {
                        grad[j] = cols[c][row];
                    }
                    let h = self.quantile * self.sd(&grad);
                    [value, value - h, value + h]
                };
                let mut e = limits(2 * i, p.e);
                // e >= 0 always, and e <= 1 without input (the models dissipate energy).
                e[1] = e[1].max(0.0);
                if no_input {
                    e[2] = e[2].min(1.0);
                }
                BandPoint {
                    v0: p.v0,
                    e,
                    // Without separation there is no duration to predict.
                    t_d: if p.separated {
                        limits(2 * i + 1, p.t_d)
                    } else {
                        [f64::NAN; 3]
                    },
                }
            })
            .collect())
    }
}

/// The reported name of a searched quantity (`g` is reported as `Gamma_b`).
fn base_name(name: &'static str) -> &'static str {
    if name == "g" {
        "Gamma_b"
    } else {
        NAMES.iter().find(|n| **n == name).copied().unwrap_or(name)
    }
}

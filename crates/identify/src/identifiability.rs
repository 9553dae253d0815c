//! Identifiability at an optimum: the sensitivity matrix of the weighted residuals with respect
//! to the free quantities (unit-cube coordinates, i.e. relative to each bound interval, in log
//! scale where the search is), its singular values (faer), and the weakest direction.

use crate::error::IdentifyError;
use crate::objective::Objective;
use bw_models::input::Input;

/// The report.
#[derive(Debug, Clone, PartialEq)]
pub struct Identifiability {
    /// Free quantities, in column order.
    pub names: Vec<&'static str>,
    /// Singular values of the sensitivity matrix, largest first.
    pub singular_values: Vec<f64>,
    /// Ratio of the largest to the smallest singular value (`inf` when rank deficient).
    pub condition: f64,
    /// Unit vector of the least determined parameter combination, one entry per name.
    pub weakest: Vec<f64>,
    /// The right singular vectors (unit vectors of the unit cube, one entry per name), in the
    /// order of `singular_values`: moving the parameters by `δ` along `directions[i]` changes
    /// the weighted residuals by `singular_values[i] δ` to first order. With fewer residuals
    /// than free quantities there are fewer directions; the rest are undetermined.
    pub directions: Vec<Vec<f64>>,
}

/// A direction counts as weakly determined where its singular value is below `WEAK` times the
/// largest: the data determine it a hundred times less well than the best-determined one.
pub const WEAK: f64 = 1e-2;

impl Identifiability {
    /// The free quantities that dominate the weakest direction (|component| >= 0.3), for a
    /// message such as "the data cannot separate kappa and n".
    pub fn weakest_names(&self) -> Vec<&'static str> {
        self.names
            .iter()
            .zip(&self.weakest)
            .filter(|(_, w)| w.abs() >= 0.3)
            .map(|(n, _)| *n)
            .collect()
    }

    /// Whether a direction of singular value `s` is determined ([`WEAK`]).
    fn determined(&self, s: f64) -> bool {
        let largest = self.singular_values.first().copied().unwrap_or(0.0);
        s >= WEAK * largest && s > 0.0
    }

    /// How many directions are weakly determined ([`WEAK`]), counting those the data have no
    /// residual for.
    pub fn weak_count(&self) -> usize {
        let strong = self
            .singular_values
            .iter()
            .filter(|&&s| self.determined(s))
            .count();
        self.names.len() - strong
    }

    /// The share (0 to 1) of `|d|²` that lies along the weakly determined directions, for a
    /// displacement `d` of the unit cube (one entry per name); `None` for `d = 0`. A share near
    /// 1 says two points differ in what the data leave undetermined.
    pub fn weak_share(&self, d: &[f64]) -> Option<f64> {
        let norm2: f64 = d.iter().map(|x| x * x).sum();
        if norm2 == 0.0 || !norm2.is_finite() {
            return None;
        }
        let strong: f64 = self
            .singular_values
            .iter()
            .zip(&self.directions)
            .filter(|(&s, _)| self.determined(s))
            .map(|(_, v)| v.iter().zip(d).map(|(a, b)| a * b).sum::<f64>().powi(2))
            .sum();
        Some((1.0 - strong / norm2).clamp(0.0, 1.0))
    }

    /// The free quantities that dominate the weakly determined directions: those with a
    /// component of at least 0.3 in one of them.
    pub fn weak_names(&self) -> Vec<&'static str> {
        let weak: Vec<&Vec<f64>> = self
            .singular_values
            .iter()
            .zip(&self.directions)
            .filter(|(&s, _)| !self.determined(s))
            .map(|(_, v)| v)
            .collect();
        self.names
            .iter()
            .enumerate()
            .filter(|(j, _)| weak.iter().any(|v| v[*j].abs() >= 0.3))
            .map(|(_, n)| *n)
            .collect()
    }
}

fn residuals<I: Input + Sync>(
    objective: &Objective<'_, I>,
    s: &[f64],
) -> Result<Vec<f64>, IdentifyError> {
    let (predictions, _) = objective.evaluate(s)?;
    Ok(objective.weighted_residuals(&predictions))
}

/// The identifiability report at the point `s` of the unit cube (central differences with step
/// 1e-4, one-sided at the faces).
///
/// # Errors
/// [`IdentifyError::Model`] when a simulation fails; [`IdentifyError::Optimizer`] when the
/// SVD does not converge.
pub fn analyse<I: Input + Sync>(
    objective: &Objective<'_, I>,
    s: &[f64],
) -> Result<Identifiability, IdentifyError> {
    let d = s.len();
    let names = objective.space().free_names();
    if d == 0 {
        return Ok(Identifiability {
            names,
            singular_values: Vec::new(),
            condition: 1.0,
            weakest: Vec::new(),
            directions: Vec::new(),
        });
    }
    let h = 1e-4;
    let mut columns = Vec::with_capacity(d);
    for j in 0..d {
        let (mut lo, mut hi) = (s.to_vec(), s.to_vec());
        hi[j] = (s[j] + h).min(1.0);
        lo[j] = (s[j] - h).max(0.0);
        let (rh, rl) = (residuals(objective, &hi)?, residuals(objective, &lo)?);
        let step = hi[j] - lo[j];
        columns.push(
            rh.iter()
                .zip(&rl)
                .map(|(a, b)| (a - b) / step)
                .collect::<Vec<f64>>(),
        );
    }
    let m = columns[0].len();
    let jac = faer::Mat::<f64>::from_fn(m, d, |i, j| columns[j][i]);
    let svd = jac.thin_svd().map_err(|e| IdentifyError::Optimizer {
        message: format!("SVD of the sensitivity matrix: {e:?}"),
    })?;
    let sv: Vec<f64> = (0..d.min(m)).map(|i| svd.S().column_vector()[i]).collect();
    let mut order: Vec<usize> = (0..sv.len()).collect();
    order.sort_by(|a, b| sv[*b].total_cmp(&sv[*a]));
    let singular_values: Vec<f64> = order.iter().map(|&i| sv[i]).collect();
    let (largest, smallest) = (singular_values[0], *singular_values.last().expect("d >= 1"));
    let weakest_col = if m >= d {
        *order.last().expect("d >= 1")
    } else {
        d - 1
    };
    let weakest = if m >= d {
        (0..d).map(|i| svd.V()[(i, weakest_col)]).collect()
    } else {
        vec![f64::NAN; d]
    };
    let condition = if smallest > 0.0 && m >= d {
        largest / smallest
    } else {
        f64::INFINITY
    };
    let directions = order
        .iter()
        .map(|&k| (0..d).map(|i| svd.V()[(i, k)]).collect())
        .collect();
    Ok(Identifiability {
        names,
        singular_values,
        condition,
        weakest,
        directions,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two directions, the second a thousand times weaker than the first, along the axes.
    fn report(directions: Vec<Vec<f64>>) -> Identifiability {
        Identifiability {
            names: vec!["kappa", "n"],
            singular_values: vec![1.0, 1e-3],
            condition: 1e3,
            weakest: directions[1].clone(),
            directions,
        }
    }

    #[test]
    fn the_weak_share_is_the_squared_component_along_the_weak_directions() {
        let id = report(vec![vec![1.0, 0.0], vec![0.0, 1.0]]);
        assert_eq!(id.weak_count(), 1);
        assert_eq!(id.weak_names(), ["n"]);
        // |d|² = 25, 16 of it along the weak axis.
        assert!((id.weak_share(&[3.0, 4.0]).unwrap() - 0.64).abs() < 1e-15);
        assert_eq!(id.weak_share(&[0.0, 0.0]), None);
        // Rotated by 45°: d = (1, 1) lies wholly along the strong direction.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let id = report(vec![vec![h, h], vec![h, -h]]);
        assert!(id.weak_share(&[1.0, 1.0]).unwrap() < 1e-15);
        assert!((id.weak_share(&[1.0, -1.0]).unwrap() - 1.0).abs() < 1e-15);
        assert_eq!(id.weak_names(), ["kappa", "n"]);
    }

    #[test]
    fn directions_without_a_residual_count_as_weak() {
        // One residual, two quantities: one direction determined, the other not at all.
        let id = Identifiability {
            names: vec!["kappa", "n"],
            singular_values: vec![2.0],
            condition: f64::INFINITY,
            weakest: vec![f64::NAN; 2],
            directions: vec![vec![1.0, 0.0]],
        };
        assert_eq!(id.weak_count(), 1);
        assert!((id.weak_share(&[0.0, 2.0]).unwrap() - 1.0).abs() < 1e-15);
    }
}

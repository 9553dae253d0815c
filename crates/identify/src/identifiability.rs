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
}

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
    Ok(Identifiability {
        names,
        singular_values,
        condition,
        weakest,
    })
}

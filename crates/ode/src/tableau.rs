//! Butcher tableaux of explicit embedded Runge-Kutta pairs, with their continuous extensions.
//!
//! A method is pure data. For a step of size `h` from `(t, y)` with stages
//! `k_i = f(t + c_i h, y + h Σ_{j<i} a_ij k_j)`:
//!
//! * solution: `y_1 = y + h Σ_i b_i k_i`;
//! * error: `h Σ_i e_i k_i` (difference of the two embedded solutions), or Hairer's DOP853
//!   combination of a 5th- and a 3rd-order estimate ([`ErrorEstimate::Hairer853`]);
//! * dense output on `θ ∈ [0, 1]`: `y(t + θh) = y + Σ_r w_r(θ) F_r` with `F_r = h Σ_j D_rj k_j`
//!   in Hairer's nested basis `w = θ, θ(1-θ), θ²(1-θ), θ²(1-θ)², ...` (as in dopri5.f and
//!   dop853.f), evaluated as `θ (F_0 + (1-θ)(F_1 + θ (F_2 + (1-θ)(F_3 + ...))))`. `F_0` is the
//!   increment of the step and the other rows are small corrections, so the evaluation does not
//!   suffer from cancellation.
//!
//! Stages `0..stages` are evaluated in every step. Stage `fsal` (when it is not among them) is
//! `f(t + h, y_1)`, evaluated once a step is accepted and reused as the first stage of the next.
//! Stages after `fsal` are only needed by the dense output and computed lazily.

/// Most stages any built-in method needs (Verner 9 with its dense stages): the engine's stage
/// buffers hold this many.
pub const MAX_STAGES: usize = 21;
/// Most rows of any built-in interpolant: the engine's dense-output buffers hold this many.
pub(crate) const MAX_ROWS: usize = 8;

/// How the local error of a step is estimated.
#[derive(Debug, Clone, Copy)]
pub enum ErrorEstimate {
    /// `err = h Σ e_i k_i`, measured in the RMS norm scaled by `atol + rtol |y|`.
    Embedded(&'static [f64]),
    /// Hairer's DOP853 estimate: with `E5 = ‖Σ e5_i k_i‖²`, `E3 = ‖Σ e3_i k_i‖²` (scaled sums of
    /// squares), `err = |h| E5 / sqrt(N (E5 + 0.01 E3))`.
    Hairer853 {
        /// Weights of the 5th-order error estimate.
        e5: &'static [f64],
        /// Weights of the 3rd-order error estimate.
        e3: &'static [f64],
    },
}

/// A continuous extension (dense output) of a Runge-Kutta step.
#[derive(Debug, Clone, Copy)]
pub struct Interpolant {
    /// Order of the interpolant (local error `O(h^(order+1))`).
    pub order: u32,
    /// Rows `D_r` over all stages: `F_r = h Σ_j D_rj k_j`.
    pub rows: &'static [&'static [f64]],
}

/// An explicit embedded Runge-Kutta pair with a continuous extension.
#[derive(Debug, Clone, Copy)]
pub struct Tableau {
    /// Human-readable name, e.g. `"DOP853"`.
    pub name: &'static str,
    /// Order of the propagated solution.
    pub order: u32,
    /// Order used in the step-size exponent `1 / (error_order + 1)`.
    pub error_order: u32,
    /// Number of stages evaluated in every step (the first one is reused from the previous step).
    pub stages: usize,
    /// Index of the stage that equals `f(t + h, y_1)`.
    pub fsal: usize,
    /// Nodes `c_i`, for every stage including the dense-output stages.
    pub c: &'static [f64],
    /// Rows `a_i` (strictly lower triangular, row `i` has `i` entries).
    pub a: &'static [&'static [f64]],
    /// Weights `b_i` of the propagated solution (length `stages`).
    pub b: &'static [f64],
    /// Error estimate.
    pub error: ErrorEstimate,
    /// Dense output.
    pub interpolant: Interpolant,
    /// Default `β` of the PI step-size controller (Hairer's stabilisation; 0 for plain I control).
    pub default_beta: f64,
    /// Hairer's stiffness test for this method.
    pub stiffness: StiffnessTest,
}

/// Hairer's stiffness test (dopri5.f, dop853.f): after an accepted step, `h |λ|` is estimated
/// as `h ‖f(t + h, y_1) - k_s‖ / ‖y_1 - Y_s‖` from a stage `s` with `c_s = 1` evaluated at a
/// point `Y_s` other than `y_1`. Where the step size is limited by stability rather than
/// accuracy, `h |λ|` settles near the end of the stability region on the negative real axis,
/// `bound`: at 0.69-0.82 of it with the PI controller and tight tolerances (measured on
/// Prothero-Robinson problems), so a step counts as stiff beyond 0.6 `bound` (Hairer's codes use
/// 0.95-0.98 of it and miss these). 15 such steps without 6 in a row below make the problem
/// stiff ([`crate::Integrator::is_stiff`]).
#[derive(Debug, Clone, Copy)]
pub struct StiffnessTest {
    /// The stage `s` (with `c_s = 1`, not the fsal stage).
    pub stage: usize,
    /// Where the method's stability region ends on the negative real axis (`|h λ|`).
    pub bound: f64,
}

impl Tableau {
    /// Total number of stages including the dense-output stages.
    pub fn total_stages(&self) -> usize {
        self.c.len()
    }

    /// Checks that the tableau fits the engine: at most [`MAX_STAGES`] stages in all,
    /// strictly lower-triangular rows, one node per stage, `stages` weights, error and
    /// interpolant rows no longer than the stages, the fsal and stiffness stages in range,
    /// and every coefficient finite. (The built-in methods pass; their consistency as
    /// Runge-Kutta pairs is tested separately.)
    ///
    /// # Errors
    /// [`crate::Error::InvalidTableau`] naming the first problem.
    pub fn validate(&self) -> Result<(), crate::Error> {
        let bad = |reason: String| {
            Err(crate::Error::InvalidTableau {
                name: self.name,
                reason,
            })
        };
        let total = self.total_stages();
        if total == 0 || total > MAX_STAGES {
            return bad(format!(
                "{total} stages in all; the engine takes 1 to {}",
                MAX_STAGES
            ));
        }
        if self.a.len() != total {
            return bad(format!("{} rows of a for {total} nodes c", self.a.len()));
        }
        if let Some(i) = (0..total).find(|&i| self.a[i].len() != i) {
            return bad(format!(
                "row {i} of a has {} entries; an explicit method's has {i}",
                self.a[i].len()
            ));
        }
        if self.stages == 0 || self.stages > total || self.b.len() != self.stages {
            return bad(format!(
                "{} weights b for {} stages of {total}",
                self.b.len(),
                self.stages
            ));
        }
        if self.fsal >= total || self.stiffness.stage >= self.stages {
            return bad(format!(
                "fsal stage {} or stiffness stage {} out of range",
                self.fsal, self.stiffness.stage
            ));
        }
        let weights: Vec<&[f64]> = match self.error {
            ErrorEstimate::Embedded(e) => vec![e],
            ErrorEstimate::Hairer853 { e5, e3 } => vec![e5, e3],
        };
        if weights.iter().any(|e| e.len() > total) {
            return bad("error weights longer than the stages".into());
        }
        let rows = self.interpolant.rows;
        if rows.len() > MAX_ROWS || rows.iter().any(|r| r.len() > total) {
            return bad(format!(
                "{} interpolant rows (at most {}) or a row longer than the stages",
                rows.len(),
                MAX_ROWS
            ));
        }
        let all = self
            .c
            .iter()
            .chain(self.b)
            .chain(self.a.iter().copied().flatten());
        let all = all
            .chain(weights.into_iter().flatten())
            .chain(rows.iter().copied().flatten());
        if all.clone().any(|v| !v.is_finite()) {
            return bad("a coefficient is not finite".into());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Structural consistency: row sums equal the nodes, weights sum to one, error weights sum
    /// to zero, interpolant at θ = 1 reproduces the solution.
    #[test]
    fn a_tableau_the_engine_cannot_take_is_an_error() {
        for t in crate::METHODS {
            t.validate().unwrap();
        }
        // 22 stages: one more than the engine holds.
        static C: [f64; 22] = [0.0; 22];
        static ROWS: [&[f64]; 22] = [&[]; 22];
        let big: &'static Tableau = Box::leak(Box::new(Tableau {
            c: &C,
            a: &ROWS,
            ..crate::DOPRI5
        }));
        let err = big.validate().unwrap_err().to_string();
        assert!(
            err.contains("22 stages") && err.contains("1 to 21"),
            "{err}"
        );
        let f = |_t: f64, y: &crate::State<1>| *y;
        let made = crate::Integrator::new(
            f,
            big,
            0.0,
            crate::State::<1>::new(1.0),
            crate::Options::new(1e-6, 1e-9),
        );
        assert!(matches!(made, Err(crate::Error::InvalidTableau { .. })));
        // A row that is not lower-triangular.
        static A_BAD: [&[f64]; 7] = [&[], &[0.2], &[0.1, 0.1, 0.1], &[], &[], &[], &[]];
        let bad = Tableau {
            a: &A_BAD,
            ..crate::DOPRI5
        };
        assert!(bad
            .validate()
            .unwrap_err()
            .to_string()
            .contains("row 2 of a has 3 entries"));
    }

    #[test]
    fn tableaux_are_consistent() {
        for t in crate::METHODS {
            let s = t.total_stages();
            assert_eq!(t.a.len(), s, "{}", t.name);
            assert!(t.fsal < s && t.b.len() == t.stages, "{}", t.name);
            for (i, row) in t.a.iter().enumerate() {
                assert_eq!(row.len(), i, "{} row {i}", t.name);
                let sum: f64 = row.iter().sum();
                assert!(
                    (sum - t.c[i]).abs() < 1e-14,
                    "{} row {i}: {sum} vs {}",
                    t.name,
                    t.c[i]
                );
            }
            let sb: f64 = t.b.iter().sum();
            assert!((sb - 1.0).abs() < 1e-14, "{}: Σb = {sb}", t.name);
            // The fsal stage is evaluated at (t + h, y_1).
            assert_eq!(t.c[t.fsal], 1.0, "{}", t.name);
            for (j, bj) in t.b.iter().enumerate() {
                let aj = t.a[t.fsal].get(j).copied().unwrap_or(0.0);
                assert!((aj - bj).abs() < 1e-15, "{}: fsal row", t.name);
            }
            match t.error {
                ErrorEstimate::Embedded(e) => {
                    assert!(e.iter().sum::<f64>().abs() < 1e-14, "{}", t.name)
                }
                ErrorEstimate::Hairer853 { e5, e3 } => {
                    assert!(e5.iter().sum::<f64>().abs() < 1e-14);
                    assert!(e3.iter().sum::<f64>().abs() < 1e-14);
                }
            }
            assert_eq!(t.c[t.stiffness.stage], 1.0, "{}", t.name);
            assert!(t.stiffness.stage < t.stages && t.stiffness.stage != t.fsal);
            // Dense output at θ = 1 equals y_1: w_0(1) = 1 and w_r(1) = 0 otherwise, so D_0 = b.
            for j in 0..s {
                let w1 = t.interpolant.rows[0][j];
                let bj = t.b.get(j).copied().unwrap_or(0.0);
                assert!(
                    (w1 - bj).abs() < 1e-12,
                    "{} stage {j}: {w1} vs {bj}",
                    t.name
                );
            }
        }
    }

    /// The stiffness bounds are where |R(z)| first exceeds 1 on the negative real axis, R the
    /// stability polynomial `1 + z b^T (I - z A)^-1 1` (to 0.1 %).
    /// The weights integrate `c^k` exactly for `k < order` (`Σ b_j c_j^k = 1/(k+1)`), and the
    /// interpolant's weights at `θ` do for `k < its order` (`Σ b_j(θ) c_j^k = θ^(k+1)/(k+1)`):
    /// necessary order conditions that catch a mistyped coefficient.
    #[test]
    fn quadrature_conditions_hold_to_each_order() {
        for t in crate::METHODS {
            for k in 0..t.order as i32 {
                let sum: f64 = t.b.iter().zip(t.c).map(|(b, c)| b * c.powi(k)).sum();
                let want = 1.0 / f64::from(k + 1);
                assert!(
                    (sum - want).abs() < 1e-14,
                    "{} k {k}: {sum} vs {want}",
                    t.name
                );
            }
            let rows = t.interpolant.rows;
            for theta in [0.3f64, 0.7] {
                // b_j(θ) = θ (D_0j + (1-θ) (D_1j + θ (D_2j + ...))), Hairer's nested basis.
                let weight = |j: usize| {
                    let mut acc = rows[rows.len() - 1][j];
                    for r in (0..rows.len() - 1).rev() {
                        let m = if (r + 1) % 2 == 0 { theta } else { 1.0 - theta };
                        acc = rows[r][j] + acc * m;
                    }
                    acc * theta
                };
                for k in 0..t.interpolant.order as i32 {
                    let sum: f64 = (0..t.total_stages())
                        .map(|j| weight(j) * t.c[j].powi(k))
                        .sum();
                    let want = theta.powi(k + 1) / f64::from(k + 1);
                    assert!(
                        (sum - want).abs() < 1e-13,
                        "{} interpolant θ {theta} k {k}: {sum} vs {want}",
                        t.name
                    );
                }
            }
        }
    }

    #[test]
    fn stiffness_bounds_are_the_real_stability_boundaries() {
        for t in crate::METHODS {
            let r = |z: f64| {
                let mut y = vec![0.0; t.stages];
                for i in 0..t.stages {
                    y[i] = 1.0 + z * t.a[i].iter().zip(&y).map(|(a, y)| a * y).sum::<f64>();
                }
                1.0 + z * t.b.iter().zip(&y).map(|(b, y)| b * y).sum::<f64>()
            };
            let boundary = (1..200_000)
                .map(|i| i as f64 * 1e-4)
                .find(|s| r(-s).abs() > 1.0 + 1e-12)
                .unwrap();
            assert!(
                (t.stiffness.bound - boundary).abs() < 1e-3 * boundary,
                "{}: boundary {boundary} vs {}",
                t.name,
                t.stiffness.bound
            );
        }
    }
}

//! # bwc-identify: derivative-free identification of base parameters
//!
//! Given measured CoR `e` and/or contact durations `t_d` at several impact speeds (paper
//! Section 7), find the base parameters `P* = (B_b, Γ_b, κ, σ_b, n, p, U_b, T_b)` of a model
//! that minimise `w1 J1 + w2 J2`, with `J_j` the mean squared error of `Θ_1` (CoR) and `Θ_2`
//! (duration in s):
//!
//! * [`Dataset`]: measurements from CSV;
//! * [`Space`]: bounds, fixed values, `Γ_b = g B_b` with `g ∈ [-1, 1]`, and the Villegas
//!   constraints `T_b = m U_b`, `(m/k) κ / T_b^(p+1) <= 1`;
//! * [`Objective`]: the costs, evaluated in parallel over the data points;
//! * [`fit`]: independent starts from Latin-hypercube points and argmin's particle swarms
//!   (seeded, particles in parallel), polished by Levenberg-Marquardt (interior, then on the
//!   bounds; Nelder-Mead where that does not converge), until several from distinct regions
//!   agree ([`Convergence`]), the best verified by Nelder-Mead;
//!   optimum snapped onto the bounds it touches ([`at_bound`]); identical results for any
//!   thread count. A particle's evaluation stops once its cost passes the particle's best
//!   ([`CubeProblem::cost_below`], [`TermOrder`]): the same search with less work;
//! * [`analyse`]: singular values of the sensitivity matrix at the optimum (faer);
//! * [`uncertainty`]: linearised 95 % intervals of the parameters and bands of `e(v0)`,
//!   `t_d(v0)`, validated by the coverage studies of [`study`];
//! * [`LoopObjective`]: hysteresis-loop fitting of the SI contact law with known mass;
//! * [`sample`]: sequential Monte Carlo on the unit cube (tempering, resampling, Metropolis moves
//!   with differential-evolution proposals; independent runs pooled, the evidence's error their
//!   spread) of any [`Target`]; [`PosteriorProblem`] is the posterior of a [`Space`] given a
//!   [`Dataset`] under a Gaussian noise model ([`PosteriorSpec`]), summarised by [`marginals`]
//!   and [`posterior_band`], its credible band validated by [`posterior_replicate`].
//!
//! ```
//! use bw_models::{input::Zero, BaseMap, BaseParams, ModelKind, Settings};
//! use bwc_identify::{fit, Budget, Dataset, Objective, Param, Space, Weights};
//! // Synthetic data from a known NDBWSHCCM; recover it with κ and σ_b free.
//! let truth = BaseParams { b_b: 1.0, gamma_b: -1.0, kappa: 0.6, sigma_b: 0.03, n: 1.5, p: 1.5, u_b: 1.0, t_b: 1.0 };
//! let map = BaseMap::new(ModelKind::Shccm, truth)?;
//! let mut csv = String::from("v_0,e\n");
//! for v0 in [0.2, 1.0, 4.0] {
//!     csv += &format!("{v0},{}\n", bw_models::impact_at(&map, Zero, v0, &Settings::default())?.e);
//! }
//! let data = Dataset::parse(std::path::Path::new("synthetic.csv"), &csv)?;
//! let free = |lo, hi| Param::Free { lo, hi, log: false };
//! let space = Space::new(ModelKind::Shccm, [Param::Fixed(1.0), Param::Fixed(-1.0), free(0.1, 0.9), free(0.0, 0.1),
//!     Param::Fixed(1.5), Param::Fixed(1.5), Param::Fixed(1.0), Param::Fixed(1.0)], None)?;
//! let objective = Objective::new(&space, &data, &Zero, Settings::default(), Weights { j1: 1.0, j2: 0.0 })?;
//! let result = fit(&objective, &Budget { particles: 8, iterations: 10, polish_iterations: 200, ..Budget::default() }.single(), 7, None)?;
//! assert!((result.params.kappa - 0.6).abs() < 1e-4 && (result.params.sigma_b - 0.03).abs() < 1e-4);
//! # Ok::<(), bwc_identify::IdentifyError>(())
//! ```
#![deny(missing_docs)]

mod coverage;
mod csv_file;
mod data;
mod drops;
mod error;
mod fit;
mod identifiability;
mod lm;
mod loops;
mod objective;
mod posterior;
mod problem;
mod smc;
mod space;
mod uncertainty;

pub use coverage::{
    coverage, posterior_replicate, replicate, study, CoverageTask, PosteriorTask, Replicate,
};
pub use data::{Dataset, Point, PLAUSIBLE_DURATION, PLAUSIBLE_SPEED};
pub use drops::{DropData, DropKind, DropObjective, DropRow, DropSetup};
pub use error::IdentifyError;
pub use fit::{
    at_bound, fit, minimize, Budget, Convergence, FitResult, Minimum, POLISH_ROUNDS, REGION,
};
pub use identifiability::{analyse, Identifiability, WEAK};
pub use loops::{loop_cost, Curve, LawSpace, Loop, LoopObjective, LAW_NAMES};
pub use objective::{predict, Costs, Objective, Prediction, TermOrder, Weights, FAILED};
pub use posterior::{
    band as posterior_band, disagreement, marginals, run_spread, Marginal, NoiseScale,
    PosteriorBandPoint, PosteriorProblem, PosteriorSpec, Prior, RunSpread, REFERENCE_SD,
    RUN_SPREAD,
};
pub use problem::CubeProblem;
pub use smc::{
    draws, pool, run as smc_run, sample, weighted_quantiles, Pooled, SmcReference, SmcRun,
    SmcSettings, Stage, Target,
};
pub use space::{FitModel, KnownMassStiffness, Param, Space, NAMES};
pub use uncertainty::{uncertainty, BandPoint, Uncertainty, LEVEL};

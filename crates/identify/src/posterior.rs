//! The posterior of base parameters given CoR and duration data: a Gaussian likelihood of the
//! aggregate quantities `Θ_1` (CoR) and `Θ_2` (duration in s), the search bounds as a uniform
//! prior on the search scale (or truncated Gaussian priors on chosen quantities), sampled by
//! [`crate::sample`]; marginal summaries and credible bands of `e(v0)` and `t_d(v0)` from the
//! weighted sample.
//!
//! The likelihood of a point with CoR `ẽ` and prediction `e` is `N(ẽ; e, σ_e)`: `σ_e` per
//! point from the data's noise column (`e_sem`, else `e_std`), or one `σ_e` for all points,
//! sampled with a log-uniform prior. Durations have a sampled `σ_t` (s). A point where the
//! model fails has likelihood 0.

use crate::data::Dataset;
use crate::error::IdentifyError;
use crate::objective::{distinct_speeds, prediction, Costs, Prediction, Weights};
use crate::smc::{draws, weighted_quantiles, Pooled, SmcReference, Target};
use crate::space::{Param, Space, NAMES};
use bw_models::input::Input;
use bw_models::Settings;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal as Gaussian};
use rayon::prelude::*;
use statrs::distribution::{Continuous, ContinuousCDF, Normal};

/// How the noise scale of one quantity is known.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum NoiseScale {
    /// Per point, from the data's noise column (CoR only).
    Column,
    /// One scale for all points, sampled with a log-uniform prior on `[lo, hi]` (the
    /// quantity's unit: 1 for the CoR, s for durations).
    Sampled {
        /// Lower bound, `> 0`.
        lo: f64,
        /// Upper bound, `> lo`.
        hi: f64,
    },
}

/// A truncated Gaussian prior on one free quantity, on its physical value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prior {
    /// The quantity (a name of [`NAMES`]).
    pub name: &'static str,
    /// Mean.
    pub mean: f64,
    /// Standard deviation, `> 0`.
    pub sd: f64,
}

impl Prior {
    /// Checks the prior against a search space.
    ///
    /// # Errors
    /// [`IdentifyError::Posterior`] for a quantity that is not searched (or `kappa` under
    /// known mass and stiffness), a mean outside the bounds or a standard deviation that is not
    /// positive.
    pub fn validate(&self, space: &Space) -> Result<(), IdentifyError> {
        prior_of(space, self).map(|_| ())
    }
}

/// What a posterior is asked of: the data used, the noise model and the priors.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct PosteriorSpec {
    /// Which quantities enter the likelihood: the CoR where `j1 > 0`, the duration where
    /// `j2 > 0` (the weights' values are not used: the noise scales weigh the points).
    pub weights: Weights,
    /// The CoR's noise scale.
    pub e_noise: NoiseScale,
    /// The duration's noise scale (s).
    pub t_noise: NoiseScale,
    /// Priors other than uniform on the search scale.
    pub priors: Vec<Prior>,
}

impl PosteriorSpec {
    /// CoR and/or durations as `weights` say, each noise scale sampled with its default prior
    /// (see [`PosteriorSpec::default_noise`]), uniform priors.
    pub fn new(data: &Dataset, weights: Weights) -> Self {
        let (e_noise, t_noise) = Self::default_noise(data);
        Self {
            weights,
            e_noise,
            t_noise,
            priors: Vec::new(),
        }
    }

    /// The default noise scales of `data`: the CoR's from its noise column if it has one, else
    /// sampled in `[1e-4, 0.5]`; the duration's sampled in `[1e-3, 1]` times the largest
    /// measured duration.
    pub fn default_noise(data: &Dataset) -> (NoiseScale, NoiseScale) {
        let e = if data.noise_column.is_some() {
            NoiseScale::Column
        } else {
            NoiseScale::Sampled { lo: 1e-4, hi: 0.5 }
        };
        let t_max = data
            .points
            .iter()
            .filter_map(|p| p.t_d)
            .fold(0.0f64, f64::max);
        let t = NoiseScale::Sampled {
            lo: 1e-3 * t_max.max(1e-12),
            hi: t_max.max(1e-9),
        };
        (e, t)
    }
}

/// A prior as the target evaluates it: the cube coordinate, the quantity's bounds and scale
/// `(lo, hi, log)`, the Gaussian, and the log of its mass in the bounds.
type PriorTerm = (usize, (f64, f64, bool), Normal, f64);

/// The noise coordinate of a sampled scale: `(lo, hi)` and its index in the cube point.
type Sampled = Option<(f64, f64, usize)>;

/// The posterior target of a [`Space`] fitted to a [`Dataset`] (see the module's text).
pub struct PosteriorProblem<'a, I> {
    space: &'a Space,
    data: &'a Dataset,
    input: &'a I,
    settings: Settings,
    use_e: bool,
    use_t: bool,
    sigma_e: Sampled,
    sigma_t: Sampled,
    priors: Vec<PriorTerm>,
    speeds: Vec<f64>,
}

impl<'a, I: Input + Sync> PosteriorProblem<'a, I> {
    /// The posterior of `space` given `data` with input `u`, solver `settings` and `spec`.
    ///
    /// # Errors
    /// [`IdentifyError::Posterior`] for fewer than 2 data points used, a noise column with a
    /// missing, zero or negative value where a CoR is used (naming its line), noise bounds that
    /// are not `0 < lo < hi`, or a prior on a quantity that is not searched, with a mean outside
    /// its bounds or a standard deviation that is not positive; [`IdentifyError::Objectives`]
    /// where the data lack a quantity `spec` uses.
    pub fn new(
        space: &'a Space,
        data: &'a Dataset,
        u: &'a I,
        settings: Settings,
        spec: &PosteriorSpec,
    ) -> Result<Self, IdentifyError> {
        settings.validate()?;
        let (use_e, use_t) = (spec.weights.j1 > 0.0, spec.weights.j2 > 0.0);
        check_data(data, use_e, use_t, spec.e_noise)?;
        let mut next = space.dim();
        let mut sampled = |scale: NoiseScale, used: bool, name: &str| match scale {
            _ if !used => Ok(None),
            NoiseScale::Column => Ok(None),
            NoiseScale::Sampled { lo, hi } => {
                if !(lo > 0.0 && hi > lo && hi.is_finite()) {
                    return Err(IdentifyError::Posterior {
                        reason: format!(
                            "{name} = [{lo}, {hi}]: the noise scale's bounds need 0 < lo < hi"
                        ),
                    });
                }
                next += 1;
                Ok(Some((lo, hi, next - 1)))
            }
        };
        let sigma_e = sampled(spec.e_noise, use_e, "sigma_e")?;
        let sigma_t = sampled(spec.t_noise, use_t, "sigma_t")?;
        if use_t && spec.t_noise == NoiseScale::Column {
            return Err(IdentifyError::Posterior {
                reason: "durations have no noise column: sample sigma_t".into(),
            });
        }
        let priors = spec
            .priors
            .iter()
            .map(|p| prior_of(space, p))
            .collect::<Result<_, _>>()?;
        Ok(Self {
            space,
            data,
            input: u,
            settings,
            use_e,
            use_t,
            sigma_e,
            sigma_t,
            priors,
            speeds: distinct_speeds(data),
        })
    }

    /// The names of the cube's coordinates: the free quantities, then `sigma_e` and `sigma_t`
    /// where sampled.
    pub fn names(&self) -> Vec<&'static str> {
        let mut names = self.space.free_names();
        if self.sigma_e.is_some() {
            names.push("sigma_e");
        }
        if self.sigma_t.is_some() {
            names.push("sigma_t");
        }
        names
    }

    /// The physical values of a cube point's coordinates, in the order of
    /// [`PosteriorProblem::names`] (`g`, not `Γ_b`).
    pub fn values(&self, s: &[f64]) -> Vec<f64> {
        let q = self.space.quantities(&s[..self.space.dim()]);
        let mut v: Vec<f64> = self.space.free_indices().iter().map(|&i| q[i]).collect();
        for (lo, hi, j) in [self.sigma_e, self.sigma_t].into_iter().flatten() {
            v.push(log_scale(lo, hi, s[j]));
        }
        v
    }

    /// The reference the tempering starts from (see [`SmcReference`]): half uniform, half
    /// Gaussians of standard deviation [`REFERENCE_SD`] around the optimum `point` of a fit to
    /// the same data, its sampled noise scales at the fit's root-mean-square residuals `costs`.
    pub fn reference_at(&self, point: &[f64], costs: &Costs) -> SmcReference {
        let mut center = point.to_vec();
        let at = |x: Sampled, j: Option<f64>| {
            x.map(|(lo, hi, _)| {
                let rms = j.unwrap_or(lo * hi).sqrt();
                ((rms / lo).ln() / (hi / lo).ln()).clamp(0.0, 1.0)
            })
        };
        center.extend(at(self.sigma_e, costs.j1));
        center.extend(at(self.sigma_t, costs.j2));
        SmcReference::around(center, REFERENCE_SD)
    }

    /// The search space.
    pub fn space(&self) -> &Space {
        self.space
    }

    /// Whether the CoR's noise scale is sampled (else it is the data's column).
    pub fn samples_e_noise(&self) -> bool {
        self.sigma_e.is_some()
    }

    /// The noise scales at a cube point: the CoR's (NaN where it is per point) and the
    /// duration's (NaN where durations are not used).
    pub fn noise_at(&self, s: &[f64]) -> (f64, f64) {
        let at = |x: Sampled| x.map_or(f64::NAN, |(lo, hi, j)| log_scale(lo, hi, s[j]));
        (at(self.sigma_e), at(self.sigma_t))
    }

    /// The predictions at a cube point at `speeds` (sequentially: the sampler runs particles in
    /// parallel), or the first failure.
    ///
    /// # Errors
    /// [`IdentifyError::Model`] where the point is not admissible or a simulation fails.
    pub fn predict(&self, s: &[f64], speeds: &[f64]) -> Result<Vec<Prediction>, IdentifyError> {
        let map = self.space.map(&self.space.decode(&s[..self.space.dim()]))?;
        speeds
            .iter()
            .map(|&v0| Ok(prediction(&map, self.input, v0, &self.settings)?))
            .collect()
    }
}

/// The standard deviation (on the unit cube) of the Gaussians of
/// [`PosteriorProblem::reference_at`]: wide enough to hold a mode the data determine to a few
/// per cent of the bounds, narrow enough to populate one that a uniform population misses.
pub const REFERENCE_SD: f64 = 0.05;

/// `lo (hi/lo)^t`.
fn log_scale(lo: f64, hi: f64, t: f64) -> f64 {
    lo * (hi / lo).powf(t.clamp(0.0, 1.0))
}

/// Checks that `data` can carry a posterior: at least 2 points used, and a positive noise
/// value on every line with a CoR where the noise comes from the column.
fn check_data(
    data: &Dataset,
    use_e: bool,
    use_t: bool,
    e_noise: NoiseScale,
) -> Result<(), IdentifyError> {
    let used = data
        .points
        .iter()
        .filter(|p| (use_e && p.e.is_some()) || (use_t && p.t_d.is_some()))
        .count();
    if used < 2 {
        return Err(IdentifyError::Posterior {
            reason: format!(
                "{}: {used} data point(s) used: a posterior needs at least 2",
                data.path.display()
            ),
        });
    }
    if !(use_e && e_noise == NoiseScale::Column) {
        return Ok(());
    }
    let Some(column) = data.noise_column else {
        return Err(IdentifyError::Posterior {
            reason: format!(
                "{}: no column `e_sem` or `e_std` for the given noise: add one, or sample the \
                 noise (noise = \"sampled\")",
                data.path.display()
            ),
        });
    };
    for p in data.points.iter().filter(|p| p.e.is_some()) {
        if !p.noise.is_some_and(|x| x > 0.0 && x.is_finite()) {
            return Err(crate::csv_file::data_error(
                &data.path,
                p.line,
                format!(
                    "column `{column}`: {} is not a noise scale: each point with a CoR needs a \
                     finite value > 0 (or sample the noise: noise = \"sampled\")",
                    p.noise.map_or("an empty field".into(), |x| x.to_string())
                ),
            ));
        }
    }
    Ok(())
}

/// The coordinate, bounds, Gaussian and log mass in the bounds of a prior.
fn prior_of(space: &Space, p: &Prior) -> Result<PriorTerm, IdentifyError> {
    let bad = |why: String| IdentifyError::Posterior {
        reason: format!("prior on `{}`: {why}", p.name),
    };
    let i = NAMES
        .iter()
        .position(|n| *n == p.name)
        .ok_or_else(|| bad(format!("not a quantity; one of {NAMES:?}")))?;
    let j = space
        .free_indices()
        .iter()
        .position(|&f| f == i)
        .ok_or_else(|| bad("the quantity is not searched: give it bounds".into()))?;
    let Param::Free { lo, hi, log } = space.params()[i] else {
        return Err(bad("the quantity is not searched".into()));
    };
    if i == 2 && space.known().is_some() {
        return Err(bad(
            "kappa's range depends on the other quantities under [fit.known]: use its bounds"
                .into(),
        ));
    }
    if !(p.sd > 0.0 && p.sd.is_finite()) {
        return Err(bad(format!("sd = {}: needs a finite sd > 0", p.sd)));
    }
    if !(p.mean >= lo && p.mean <= hi) {
        return Err(bad(format!(
            "mean = {} lies outside the bounds [{lo}, {hi}]",
            p.mean
        )));
    }
    let g = Normal::new(p.mean, p.sd).map_err(|e| bad(e.to_string()))?;
    let mass = g.cdf(hi) - g.cdf(lo);
    Ok((j, (lo, hi, log), g, mass.ln()))
}

impl<I: Input + Sync> Target for PosteriorProblem<'_, I> {
    fn dim(&self) -> usize {
        self.space.dim() + usize::from(self.sigma_e.is_some()) + usize::from(self.sigma_t.is_some())
    }

    fn log_likelihood(&self, s: &[f64]) -> f64 {
        let d = self.space.dim();
        let params = self.space.decode(&s[..d]);
        if self.space.violation(&params) > 0.0 {
            return f64::NEG_INFINITY;
        }
        let Ok(map) = self.space.map(&params) else {
            return f64::NEG_INFINITY;
        };
        let (se, st) = self.noise_at(s);
        let half_log_2pi = 0.5 * (2.0 * std::f64::consts::PI).ln();
        let gauss = |r: f64, sigma: f64| -0.5 * (r / sigma).powi(2) - sigma.ln() - half_log_2pi;
        let mut total = 0.0;
        for &v0 in &self.speeds {
            let Ok(p) = prediction(&map, self.input, v0, &self.settings) else {
                return f64::NEG_INFINITY;
            };
            for d in self.data.points.iter().filter(|d| d.v0 == v0) {
                if let (true, Some(e)) = (self.use_e, d.e) {
                    let sigma = if se.is_nan() {
                        d.noise.unwrap_or(1.0)
                    } else {
                        se
                    };
                    total += gauss(p.e - e, sigma);
                }
                if let (true, Some(t)) = (self.use_t, d.t_d) {
                    total += gauss(p.t_d - t, st);
                }
            }
        }
        if total.is_nan() {
            f64::NEG_INFINITY
        } else {
            total
        }
    }

    fn log_prior(&self, s: &[f64]) -> f64 {
        self.priors
            .iter()
            .map(|(j, (lo, hi, log), g, log_mass)| {
                let t = s[*j].clamp(0.0, 1.0);
                let (x, jacobian) = if *log {
                    let x = lo * (hi / lo).powf(t);
                    (x, x * (hi / lo).ln())
                } else {
                    (lo + (hi - lo) * t, hi - lo)
                };
                g.ln_pdf(x) + jacobian.ln() - log_mass
            })
            .sum()
    }
}

/// A marginal summary of one coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct Marginal {
    /// The coordinate's name.
    pub name: &'static str,
    /// Weighted median.
    pub median: f64,
    /// The central 95 % credible interval.
    pub interval: [f64; 2],
    /// Weighted mean.
    pub mean: f64,
    /// Weighted standard deviation.
    pub sd: f64,
}

/// The marginal summaries of every coordinate of a pooled sample.
pub fn marginals<I: Input + Sync>(
    problem: &PosteriorProblem<'_, I>,
    post: &Pooled,
) -> Vec<Marginal> {
    let values: Vec<Vec<f64>> = post.particles.iter().map(|s| problem.values(s)).collect();
    problem
        .names()
        .into_iter()
        .enumerate()
        .map(|(j, name)| {
            let x: Vec<f64> = values.iter().map(|v| v[j]).collect();
            let q = weighted_quantiles(&x, &post.weights, &[0.5, 0.025, 0.975]);
            let mean: f64 = x.iter().zip(&post.weights).map(|(a, w)| a * w).sum();
            let var: f64 = x
                .iter()
                .zip(&post.weights)
                .map(|(a, w)| w * (a - mean).powi(2))
                .sum();
            Marginal {
                name,
                median: q[0],
                interval: [q[1], q[2]],
                mean,
                sd: var.sqrt(),
            }
        })
        .collect()
}

/// How far independent runs put a coordinate's marginal apart: a posterior with regions that
/// the tempering separates early is weighed by each run from its own few ancestors in each
/// region, and the pooled marginal, the mean of the runs', then carries a Monte Carlo error the
/// evidence's error does not show.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSpread {
    /// The coordinate's name.
    pub name: &'static str,
    /// The lowest and the highest of the runs' medians (in the coordinate's own units).
    pub medians: [f64; 2],
    /// The standard error of the mean of the runs' medians (their standard deviation over
    /// `√runs`) over the width of the pooled central 95 % interval, both on the searched scale
    /// (the unit cube): the Monte Carlo error of the pooled marginal's centre, relative to its
    /// spread. More runs lower it as `1/√runs`.
    pub error: f64,
}

/// The [`RunSpread::error`] above which the runs disagree. For a posterior with one region
/// sampled by 4 runs of 500 particles it is 0.01 (test
/// `runs_of_a_posterior_with_one_region_agree_on_its_marginals`); on the tennis drops'
/// NDBWSHCCM posterior, whose `B_b` has three regions, 0.17 for `B_b` with 4 runs and 0.08 with
/// 16.
pub const RUN_SPREAD: f64 = 0.05;

/// The warning that the runs of the posterior of fit `name` disagree on the marginals whose
/// [`RunSpread::error`] exceeds [`RUN_SPREAD`], naming each with its runs' medians and the error
/// in percent; `None` if they agree on all.
pub fn disagreement(name: &str, runs: usize, spread: &[RunSpread]) -> Option<String> {
    let apart: Vec<String> = spread
        .iter()
        .filter(|r| r.error > RUN_SPREAD)
        .map(|r| {
            format!(
                "{} (medians {:.4e} to {:.4e}; the pooled median's Monte Carlo error {:.0} % of \
                 its 95 % interval)",
                r.name,
                r.medians[0],
                r.medians[1],
                100.0 * r.error
            )
        })
        .collect();
    (!apart.is_empty()).then(|| {
        format!(
            "\"{name}\": the {runs} runs disagree on {}: the posterior has regions each run \
             weighs differently, and the pooled marginals carry that Monte Carlo error; raise runs",
            apart.join(", ")
        )
    })
}

/// The [`RunSpread`] of every coordinate of a pooled sample (empty for a single run).
pub fn run_spread<I: Input + Sync>(
    problem: &PosteriorProblem<'_, I>,
    post: &Pooled,
) -> Vec<RunSpread> {
    let runs: Vec<usize> = post.runs.iter().map(|r| r.index).collect();
    if runs.len() < 2 {
        return Vec::new();
    }
    let values: Vec<Vec<f64>> = post.particles.iter().map(|s| problem.values(s)).collect();
    let median_of = |x: &[f64], run: usize| {
        let (xs, ws): (Vec<f64>, Vec<f64>) = x
            .iter()
            .zip(&post.weights)
            .zip(&post.run)
            .filter(|(_, &r)| r == run)
            .map(|((&v, &w), _)| (v, w))
            .unzip();
        weighted_quantiles(&xs, &ws, &[0.5])[0]
    };
    problem
        .names()
        .into_iter()
        .enumerate()
        .map(|(j, name)| {
            let cube: Vec<f64> = post.particles.iter().map(|s| s[j]).collect();
            let value: Vec<f64> = values.iter().map(|v| v[j]).collect();
            let q = weighted_quantiles(&cube, &post.weights, &[0.025, 0.975]);
            let on_cube: Vec<f64> = runs.iter().map(|&r| median_of(&cube, r)).collect();
            let in_units: Vec<f64> = runs.iter().map(|&r| median_of(&value, r)).collect();
            let range = |m: &[f64]| {
                let lo = m.iter().copied().fold(f64::INFINITY, f64::min);
                [lo, m.iter().copied().fold(f64::NEG_INFINITY, f64::max)]
            };
            let r = on_cube.len() as f64;
            let mean = on_cube.iter().sum::<f64>() / r;
            let var = on_cube.iter().map(|m| (m - mean).powi(2)).sum::<f64>() / (r - 1.0);
            RunSpread {
                name,
                medians: range(&in_units),
                error: (var / r).sqrt() / (q[1] - q[0]).max(1e-12),
            }
        })
        .collect()
}

/// A point of a posterior band: the median and the central 95 % credible interval of the
/// model's curve, and the 95 % interval of a new measurement (the curve plus noise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PosteriorBandPoint {
    /// Impact speed (m/s).
    pub v0: f64,
    /// CoR: median, lower and upper limits of the curve.
    pub e: [f64; 3],
    /// CoR of a new measurement: lower and upper limits.
    pub e_new: [f64; 2],
    /// Duration (s): median, lower and upper limits of the curve (NaN where the bodies do not
    /// separate in more than 2.5 % of the draws).
    pub t_d: [f64; 3],
    /// Duration of a new measurement (s): lower and upper limits (NaN without sampled noise).
    pub t_d_new: [f64; 2],
}

/// The posterior band at `speeds` from `count` draws of the pooled sample (systematic
/// resampling with `seed`). The noise of a new CoR measurement is the draw's sampled `σ_e`,
/// or, with per-point noise, `e_noise_new`.
///
/// # Errors
/// [`IdentifyError::Model`] where a drawn point cannot be simulated.
pub fn band<I: Input + Sync>(
    problem: &PosteriorProblem<'_, I>,
    post: &Pooled,
    speeds: &[f64],
    (count, seed): (usize, u64),
    e_noise_new: f64,
) -> Result<Vec<PosteriorBandPoint>, IdentifyError> {
    let picks = draws(&post.weights, count, seed);
    let curves: Vec<(Vec<Prediction>, (f64, f64))> = picks
        .par_iter()
        .map(|&i| {
            let s = &post.particles[i];
            let (se, st) = problem.noise_at(s);
            let se = if se.is_nan() { e_noise_new } else { se };
            Ok((problem.predict(s, speeds)?, (se, st)))
        })
        .collect::<Result<_, IdentifyError>>()?;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ 0x5EED);
    let unit = Gaussian::new(0.0, 1.0).expect("unit normal");
    let w = vec![1.0; curves.len()];
    let levels = [0.5, 0.025, 0.975];
    Ok(speeds
        .iter()
        .enumerate()
        .map(|(k, &v0)| {
            let e: Vec<f64> = curves.iter().map(|(c, _)| c[k].e).collect();
            let t: Vec<f64> = curves
                .iter()
                .map(|(c, _)| if c[k].separated { c[k].t_d } else { f64::NAN })
                .collect();
            let e_new: Vec<f64> = curves
                .iter()
                .map(|(c, (se, _))| c[k].e + se * unit.sample(&mut rng))
                .collect();
            let t_new: Vec<f64> = curves
                .iter()
                .map(|(c, (_, st))| c[k].t_d + st * unit.sample(&mut rng))
                .collect();
            let q = |x: &[f64]| -> Vec<f64> {
                let nan = x.iter().filter(|v| v.is_nan()).count();
                if nan * 40 > x.len() {
                    return vec![f64::NAN; 3];
                }
                let xs: Vec<f64> = x
                    .iter()
                    .map(|v| if v.is_nan() { f64::INFINITY } else { *v })
                    .collect();
                weighted_quantiles(&xs, &w, &levels)
            };
            let (qe, qt, qen, qtn) = (q(&e), q(&t), q(&e_new), q(&t_new));
            PosteriorBandPoint {
                v0,
                e: [qe[0], qe[1], qe[2]],
                e_new: [qen[1], qen[2]],
                t_d: [qt[0], qt[1], qt[2]],
                t_d_new: [qtn[1], qtn[2]],
            }
        })
        .collect())
}

//! Sequential Monte Carlo on the unit cube: a population of particles carried from the prior to
//! the posterior through tempered targets `π_β(s) ∝ prior(s) L(s)^β`, `β` from 0 to 1.
//!
//! Each stage chooses the next `β` so that the incremental weights `L^(Δβ)` keep an effective
//! sample size of `ess` times the particles (bisection), multiplies the evidence estimate by
//! their mean, resamples (systematic), and moves every particle by random-walk Metropolis steps
//! (a Gaussian step of the particles' own covariance, or a differential-evolution step between
//! two particles), scaled pass by pass towards an acceptance of about 0.25; a stage takes as
//! many passes as make a particle move at least once with probability 0.99 at the first pass's
//! acceptance. Several independent runs are pooled: the
//! evidence is their mean and its Monte Carlo error their spread, so that the error is measured,
//! not modelled.
//!
//! A prior other than uniform on the cube is tempered with the likelihood (`β (log prior +
//! log L)`): the final target and the evidence are the same, and no sampler of the prior is
//! needed.
//!
//! Randomness comes from one stream per (run, stage, pass, particle), so a result depends on
//! its seed alone, not on the threads or the workers that computed it.

use crate::error::IdentifyError;
use faer::{Mat, Side};
use rand::{Rng, SeedableRng};
use rand_distr::StandardNormal;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// What the sampler samples: a likelihood on the unit cube `[0, 1]^d`, with a prior that is
/// uniform on the cube unless [`Target::log_prior`] says otherwise.
pub trait Target: Sync {
    /// Dimension `d`.
    fn dim(&self) -> usize;
    /// `log L(s)`; `-∞` where `s` is not admissible or the model cannot be evaluated.
    fn log_likelihood(&self, s: &[f64]) -> f64;
    /// The log of the prior density at `s` relative to the uniform density on the cube (so it
    /// integrates to 1 against it); 0 by default.
    fn log_prior(&self, s: &[f64]) -> f64 {
        let _ = s;
        0.0
    }
}

/// The distribution the tempering starts from: uniform on the cube, or a mixture of the uniform
/// and independent Gaussians (truncated to the cube) around a point where the posterior is
/// expected, such as the optimum of a global search. The targets are then
/// `reference^(1-β) (prior L)^β`: the posterior and the evidence are the same whatever the
/// reference, but a mode too narrow for a uniform population to land in (a small region of the
/// prior that holds most of the posterior) is populated from the start.
#[derive(Debug, Clone, PartialEq)]
pub struct SmcReference {
    /// Centre of the Gaussians (a point of the cube); empty for the uniform reference.
    pub center: Vec<f64>,
    /// Their standard deviation on the cube.
    pub sd: f64,
    /// The uniform's share of the mixture, in `(0, 1]`.
    pub uniform: f64,
}

impl SmcReference {
    /// The uniform reference (the prior's support).
    pub fn uniform() -> Self {
        Self {
            center: Vec::new(),
            sd: 1.0,
            uniform: 1.0,
        }
    }

    /// Half uniform, half Gaussians of standard deviation `sd` around `center`.
    pub fn around(center: Vec<f64>, sd: f64) -> Self {
        Self {
            center,
            sd,
            uniform: 0.5,
        }
    }

    fn is_uniform(&self) -> bool {
        self.center.is_empty() || self.uniform >= 1.0
    }

    /// The Gaussians of each coordinate and their mass in `[0, 1]`.
    fn gaussians(&self) -> impl Iterator<Item = (statrs::distribution::Normal, f64)> + '_ {
        use statrs::distribution::ContinuousCDF;
        self.center.iter().map(move |&c| {
            let g = statrs::distribution::Normal::new(c, self.sd).expect("sd > 0");
            let mass = g.cdf(1.0) - g.cdf(0.0);
            (g, mass)
        })
    }

    /// The log density on the cube (relative to the uniform).
    fn log_density(&self, s: &[f64]) -> f64 {
        use statrs::distribution::Continuous;
        if self.is_uniform() {
            return 0.0;
        }
        let gauss: f64 = self
            .gaussians()
            .zip(s)
            .map(|((g, mass), &x)| g.ln_pdf(x) - mass.ln())
            .sum();
        // log(u + (1 - u) e^gauss), without overflow.
        let (a, b) = (self.uniform.ln(), gauss + (1.0 - self.uniform).ln());
        a.max(b) + (-(a - b).abs()).exp().ln_1p()
    }

    /// A draw.
    fn draw(&self, d: usize, rng: &mut rand::rngs::StdRng) -> Vec<f64> {
        use statrs::distribution::ContinuousCDF;
        if self.is_uniform() || rng.random::<f64>() < self.uniform {
            return (0..d).map(|_| rng.random::<f64>()).collect();
        }
        self.gaussians()
            .map(|(g, _)| {
                let (a, b) = (g.cdf(0.0), g.cdf(1.0));
                g.inverse_cdf(a + rng.random::<f64>() * (b - a))
                    .clamp(0.0, 1.0)
            })
            .collect()
    }

    /// Checks the reference against a dimension.
    fn validate(&self, d: usize) -> Result<(), IdentifyError> {
        let bad = |reason: String| Err(IdentifyError::Posterior { reason });
        if !self.center.is_empty() && self.center.len() != d {
            return bad(format!(
                "a reference of dimension {} for {d}",
                self.center.len()
            ));
        }
        if !(self.uniform > 0.0 && self.uniform <= 1.0 && self.sd > 0.0 && self.sd.is_finite()) {
            return bad("a reference needs 0 < uniform <= 1 and sd > 0".into());
        }
        if self.center.iter().any(|c| !(0.0..=1.0).contains(c)) {
            return bad("a reference's centre lies outside the cube".into());
        }
        Ok(())
    }
}

/// Settings of [`sample`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct SmcSettings {
    /// Particles per run.
    pub particles: usize,
    /// Independent runs (at least 2: their spread is the evidence's error).
    pub runs: usize,
    /// Effective sample size kept by each tempering step, as a fraction of the particles.
    pub ess: f64,
    /// Most Metropolis steps per particle and stage.
    pub max_moves: usize,
    /// Most tempering stages per run.
    pub max_stages: usize,
}

impl Default for SmcSettings {
    fn default() -> Self {
        Self {
            particles: 500,
            runs: 4,
            ess: 0.5,
            max_moves: 60,
            max_stages: 400,
        }
    }
}

impl SmcSettings {
    /// Settings with `particles` per run and `runs` runs, the rest default.
    pub fn new(particles: usize, runs: usize) -> Self {
        Self {
            particles,
            runs,
            ..Self::default()
        }
    }

    /// Checks that the settings can run.
    ///
    /// # Errors
    /// [`IdentifyError::Posterior`] naming the inadmissible setting.
    pub fn validate(&self) -> Result<(), IdentifyError> {
        let bad = |reason: String| Err(IdentifyError::Posterior { reason });
        if self.particles < 16 {
            return bad(format!("particles = {}: need at least 16", self.particles));
        }
        if self.runs < 2 {
            return bad(format!(
                "runs = {}: need at least 2 (their spread is the evidence's error)",
                self.runs
            ));
        }
        if !(self.ess > 0.0 && self.ess < 1.0) {
            return bad(format!("ess = {}: needs 0 < ess < 1", self.ess));
        }
        if self.max_moves == 0 || self.max_stages == 0 {
            return bad("max_moves and max_stages must be >= 1".into());
        }
        Ok(())
    }
}

/// One tempering stage of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stage {
    /// The inverse temperature reached.
    pub beta: f64,
    /// Fraction of the Metropolis proposals accepted (NaN at the last stage, which does not
    /// move).
    pub acceptance: f64,
    /// Metropolis steps per particle.
    pub moves: usize,
}

/// One run's weighted particles at `β = 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct SmcRun {
    /// Which run (its random streams).
    pub index: usize,
    /// The particles (points of the cube).
    pub particles: Vec<Vec<f64>>,
    /// Their normalised weights (summing to 1).
    pub weights: Vec<f64>,
    /// Their log-likelihoods.
    pub log_likelihood: Vec<f64>,
    /// The run's estimate of the log evidence `log ∫ prior L`.
    pub log_evidence: f64,
    /// The stages.
    pub stages: Vec<Stage>,
    /// Likelihood evaluations.
    pub evaluations: u64,
}

/// Pooled runs: the weighted sample of the posterior and the evidence.
#[derive(Debug, Clone, PartialEq)]
pub struct Pooled {
    /// The particles of every run, run after run.
    pub particles: Vec<Vec<f64>>,
    /// Their weights (summing to 1; each run carries `1 / runs` of the mass).
    pub weights: Vec<f64>,
    /// Their log-likelihoods.
    pub log_likelihood: Vec<f64>,
    /// The run each particle comes from.
    pub run: Vec<usize>,
    /// `log` of the mean of the runs' evidence estimates.
    pub log_evidence: f64,
    /// Its Monte Carlo standard error: the standard deviation of the runs' evidence over their
    /// mean, divided by `sqrt(runs)` (the delta method).
    pub log_evidence_error: f64,
    /// The effective sample size of the weights, `1 / Σ w²`.
    pub ess: f64,
    /// The runs without their particles.
    pub runs: Vec<SmcRun>,
    /// Likelihood evaluations of all runs.
    pub evaluations: u64,
}

/// A stream of randomness for one (run, stage, pass, particle): SplitMix64 of the words.
fn stream(seed: u64, words: [u64; 4]) -> rand::rngs::StdRng {
    let mut h = seed;
    for w in words {
        h = splitmix(h ^ splitmix(w.wrapping_add(0x9E37_79B9_7F4A_7C15)));
    }
    rand::rngs::StdRng::seed_from_u64(h)
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// `log Σ exp(x)`, `-∞` for an empty or all `-∞` input.
fn log_sum_exp(x: impl Iterator<Item = f64> + Clone) -> f64 {
    let m = x.clone().fold(f64::NEG_INFINITY, f64::max);
    if m == f64::NEG_INFINITY {
        return m;
    }
    m + x.map(|v| (v - m).exp()).sum::<f64>().ln()
}

/// The effective sample size of the weights `exp(delta * t)`.
fn ess_of(t: &[f64], delta: f64) -> f64 {
    let m = t.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(delta * b));
    let (s1, s2) = t.iter().fold((0.0, 0.0), |(s1, s2), &v| {
        let w = (delta * v - m).exp();
        (s1 + w, s2 + w * w)
    });
    if s2 > 0.0 {
        s1 * s1 / s2
    } else {
        0.0
    }
}

/// The tempered log density `log prior + log L - log reference` of a particle (the part raised
/// to `β`), `log_reference` the reference's log density at `s`.
fn tempered<T: Target>(target: &T, s: &[f64], log_reference: f64, counter: &AtomicU64) -> f64 {
    counter.fetch_add(1, Ordering::Relaxed);
    let v = target.log_prior(s) + target.log_likelihood(s) - log_reference;
    if v.is_nan() {
        f64::NEG_INFINITY
    } else {
        v
    }
}

/// The next inverse-temperature step from `beta`: the largest (up to `1 - beta`) that keeps the
/// effective sample size of the incremental weights at `target` particles.
fn next_step(t: &[f64], beta: f64, target: f64) -> f64 {
    let rest = 1.0 - beta;
    if ess_of(t, rest) >= target {
        return rest;
    }
    let (mut lo, mut hi) = (0.0, rest);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if ess_of(t, mid) >= target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    // A step that cannot keep the target (all weight on one particle at any positive step)
    // still advances.
    lo.max(hi * 1e-3).max(1e-12 * rest)
}

/// Systematic resampling: `m` indices of `weights` (normalised here) from one uniform `u`.
fn systematic(weights: &[f64], m: usize, u: f64) -> Vec<usize> {
    let total: f64 = weights.iter().sum();
    let last = weights.len() - 1;
    let (mut cum, mut i) = (weights[0] / total, 0);
    (0..m)
        .map(|k| {
            let point = (k as f64 + u) / m as f64;
            while point > cum && i < last {
                i += 1;
                cum += weights[i] / total;
            }
            i
        })
        .collect()
}

/// The weighted covariance of `x`, with a floor on the diagonal so that a collapsed coordinate
/// still moves.
fn covariance(x: &[Vec<f64>], w: &[f64]) -> Mat<f64> {
    let d = x[0].len();
    let mean: Vec<f64> = (0..d)
        .map(|j| x.iter().zip(w).map(|(p, wi)| wi * p[j]).sum())
        .collect();
    let mut cov = Mat::<f64>::from_fn(d, d, |a, b| {
        x.iter()
            .zip(w)
            .map(|(p, wi)| wi * (p[a] - mean[a]) * (p[b] - mean[b]))
            .sum()
    });
    for j in 0..d {
        cov[(j, j)] = cov[(j, j)].max(1e-10) * (1.0 + 1e-9);
    }
    cov
}

/// The lower Cholesky factor of `cov`, times `scale` (of the diagonal where `cov` is not
/// positive definite).
fn scaled(cov: &Mat<f64>, scale: f64) -> Vec<Vec<f64>> {
    let d = cov.nrows();
    let l = match cov.llt(Side::Lower) {
        Ok(llt) => llt.L().to_owned(),
        // A degenerate population: independent coordinates.
        Err(_) => Mat::from_fn(d, d, |a, b| if a == b { cov[(a, a)].sqrt() } else { 0.0 }),
    };
    (0..d)
        .map(|a| (0..d).map(|b| scale * l[(a, b)]).collect())
        .collect()
}

/// The proposals of one Metropolis pass, symmetric so that the acceptance ratio is the
/// targets' ratio: a Gaussian step `L z` (the population's covariance), or, with probability
/// 1/2, a differential-evolution step `γ (s_a - s_b)` between two members of the population as
/// it was when the pass began (ter Braak 2006), which follows curved and separate regions of the
/// posterior where one covariance cannot; `γ = 1` one time in ten, a jump between modes.
struct Proposal<'a> {
    /// The scaled Cholesky factor of the population's covariance.
    l: &'a [Vec<f64>],
    /// The population when the pass began.
    snapshot: &'a [Vec<f64>],
    /// `γ` of the differential-evolution steps (before the jumps).
    gamma: f64,
}

impl Proposal<'_> {
    /// The proposed point from `x`.
    fn from(&self, x: &[f64], rng: &mut rand::rngs::StdRng) -> Vec<f64> {
        let d = x.len();
        if rng.random::<bool>() {
            let z: Vec<f64> = (0..d).map(|_| rng.sample(StandardNormal)).collect();
            return (0..d)
                .map(|a| x[a] + (0..=a).map(|b| self.l[a][b] * z[b]).sum::<f64>())
                .collect();
        }
        let n = self.snapshot.len();
        let a = rng.random_range(0..n);
        let b = (a + rng.random_range(1..n)) % n;
        let gamma = if rng.random_range(0..10) == 0 {
            1.0
        } else {
            self.gamma
        };
        (0..d)
            .map(|j| {
                let jitter: f64 = rng.sample(StandardNormal);
                x[j] + gamma * (self.snapshot[a][j] - self.snapshot[b][j]) + 1e-6 * jitter
            })
            .collect()
    }
}

/// One Metropolis pass over every particle: a [`Proposal`] from each, accepted with
/// probability `min(1, (r(y)/r(x)) exp(beta Δt))` for the reference `r` (rejected outside the
/// cube). Returns the accepted count.
fn metropolis<T: Target>(
    (target, reference): (&T, &SmcReference),
    (x, t): (&mut [Vec<f64>], &mut [f64]),
    proposal: &Proposal,
    beta: f64,
    rng_of: impl Fn(usize) -> rand::rngs::StdRng + Sync,
    counter: &AtomicU64,
) -> usize {
    x.par_iter_mut()
        .zip(t.par_iter_mut())
        .enumerate()
        .map(|(i, (xi, ti))| {
            let mut rng = rng_of(i);
            let y = proposal.from(xi, &mut rng);
            let u: f64 = rng.random();
            if y.iter().any(|v| !(0.0..=1.0).contains(v)) {
                return 0;
            }
            let log_ry = reference.log_density(&y);
            let ty = tempered(target, &y, log_ry, counter);
            let base = log_ry - reference.log_density(xi);
            if ty > f64::NEG_INFINITY && u.ln() < base + beta * (ty - *ti) {
                *xi = y;
                *ti = ty;
                1
            } else {
                0
            }
        })
        .sum()
}

/// Metropolis steps a stage takes at acceptance `a`: enough for a particle to move at least
/// once with probability 0.99, within `[2, max]`.
fn moves_for(a: f64, max: usize) -> usize {
    if a <= 0.0 {
        return max;
    }
    if a >= 1.0 {
        return 2;
    }
    ((0.01f64.ln() / (1.0 - a).ln()).ceil() as usize).clamp(2, max)
}

/// Runs SMC run `index` of `seed` on `target`, tempering from `reference`: drawn from the
/// reference ([`Tempering::init`]), then stage by stage the next inverse temperature and the
/// evidence's factor ([`Tempering::reweight`]), until `beta = 1` ends the run
/// ([`Tempering::finish`]), else resampling and Metropolis moves ([`Tempering::mutate`]).
///
/// # Errors
/// [`IdentifyError::Posterior`] for inadmissible settings, a prior sample with no admissible
/// point, or a run that needs more than `max_stages` stages.
pub fn run<T: Target>(
    target: &T,
    settings: &SmcSettings,
    reference: &SmcReference,
    seed: u64,
    index: usize,
) -> Result<SmcRun, IdentifyError> {
    settings.validate()?;
    reference.validate(target.dim())?;
    let mut run = Tempering::init(target, settings, reference, (seed, index))?;
    loop {
        let w = run.reweight()?;
        if run.beta >= 1.0 {
            return Ok(run.finish(w));
        }
        run.mutate(&w);
    }
}

/// A run between stages: its particles and their tempered log densities, the inverse
/// temperature, the log evidence so far and the proposal's scale.
struct Tempering<'a, T> {
    target: &'a T,
    settings: &'a SmcSettings,
    reference: &'a SmcReference,
    /// The study's seed and the run's index, which name every random stream of the run.
    seed: u64,
    index: usize,
    x: Vec<Vec<f64>>,
    t: Vec<f64>,
    beta: f64,
    log_z: f64,
    scale: f64,
    stages: Vec<Stage>,
    counter: AtomicU64,
}

impl<'a, T: Target> Tempering<'a, T> {
    /// The particles drawn from the reference, at `beta = 0`.
    fn init(
        target: &'a T,
        settings: &'a SmcSettings,
        reference: &'a SmcReference,
        (seed, index): (u64, usize),
    ) -> Result<Self, IdentifyError> {
        let (n, d) = (settings.particles, target.dim());
        let counter = AtomicU64::new(0);
        let x: Vec<Vec<f64>> = (0..n)
            .map(|i| reference.draw(d, &mut stream(seed, [index as u64, 0, 0, i as u64])))
            .collect();
        let t: Vec<f64> = x
            .par_iter()
            .map(|s| tempered(target, s, reference.log_density(s), &counter))
            .collect();
        let admissible = t.iter().filter(|v| **v > f64::NEG_INFINITY).count();
        if admissible < 2 {
            return Err(IdentifyError::Posterior {
                reason: format!(
                    "{admissible} of {n} points drawn from the prior have a finite likelihood: \
                     widen the bounds, or check the data and the input"
                ),
            });
        }
        Ok(Tempering {
            target,
            settings,
            reference,
            seed,
            index,
            x,
            t,
            beta: 0.0,
            log_z: 0.0,
            scale: 2.38 / (d.max(1) as f64).sqrt(),
            stages: Vec::new(),
            counter,
        })
    }

    /// The next stage's inverse temperature (the step that keeps the effective sample size at
    /// `ess` of the live particles, or what is left to 1) and the evidence's factor over it;
    /// the particles' normalised weights at the new temperature.
    fn reweight(&mut self) -> Result<Vec<f64>, IdentifyError> {
        if self.stages.len() >= self.settings.max_stages {
            return Err(IdentifyError::Posterior {
                reason: format!(
                    "the tempering reached beta = {:.3e} after max_stages = {} stages: \
                     raise max_stages or particles, or give the noise a larger scale",
                    self.beta, self.settings.max_stages
                ),
            });
        }
        let live = self.t.iter().filter(|v| **v > f64::NEG_INFINITY).count() as f64;
        let delta = next_step(&self.t, self.beta, self.settings.ess * live);
        let logw: Vec<f64> = self.t.iter().map(|v| delta * v).collect();
        let total = log_sum_exp(logw.iter().copied());
        self.log_z += total - (self.t.len() as f64).ln();
        self.beta = if delta >= 1.0 - self.beta {
            1.0
        } else {
            self.beta + delta
        };
        Ok(logw.iter().map(|v| (v - total).exp()).collect())
    }

    /// The run at `beta = 1`: its weighted particles, evidence and stages.
    fn finish(mut self, weights: Vec<f64>) -> SmcRun {
        self.stages.push(Stage {
            beta: self.beta,
            acceptance: f64::NAN,
            moves: 0,
        });
        SmcRun {
            index: self.index,
            particles: self.x,
            weights,
            log_likelihood: Vec::new(),
            log_evidence: self.log_z,
            stages: self.stages,
            evaluations: self.counter.load(Ordering::Relaxed),
        }
        .with_likelihoods(self.target)
    }

    /// One stage's resampling (systematic, on the weights `w`) and Metropolis passes, with
    /// proposals shaped by the weighted population's covariance: as many passes as a particle
    /// needs to move once with probability 0.99 at the first pass's acceptance.
    fn mutate(&mut self, w: &[f64]) {
        let (n, seed, run) = (self.t.len(), self.seed, self.index as u64);
        let cov = covariance(&self.x, w);
        let stage = self.stages.len() as u64 + 1;
        let u: f64 = stream(seed, [run, stage, u64::MAX, 0]).random();
        let picks = systematic(w, n, u);
        self.x = picks.iter().map(|&i| self.x[i].clone()).collect();
        self.t = picks.iter().map(|&i| self.t[i]).collect();
        let (mut moves, mut accepted, mut k) = (self.settings.max_moves, 0, 0);
        while k < moves {
            let l = scaled(&cov, self.scale);
            let snapshot = self.x.clone();
            let proposal = Proposal {
                l: &l,
                snapshot: &snapshot,
                gamma: self.scale / 2f64.sqrt(),
            };
            let rng_of = |i: usize| stream(seed, [run, stage, k as u64, i as u64]);
            let now = metropolis(
                (self.target, self.reference),
                (&mut self.x, &mut self.t),
                &proposal,
                self.beta,
                rng_of,
                &self.counter,
            );
            let a = now as f64 / n as f64;
            if k == 0 {
                moves = moves_for(a, self.settings.max_moves);
            }
            accepted += now;
            // Towards an acceptance of about 0.25 (Roberts & Rosenthal's 0.234), pass by pass:
            // the population's acceptance, not a particle's history, sets the next pass.
            self.scale = (self.scale * (a - 0.25).exp()).clamp(1e-4, 3.0);
            k += 1;
        }
        self.stages.push(Stage {
            beta: self.beta,
            acceptance: accepted as f64 / (n * moves) as f64,
            moves,
        });
    }
}

impl SmcRun {
    /// Fills [`SmcRun::log_likelihood`] (without counting: the tempered values hold the prior
    /// too).
    fn with_likelihoods<T: Target>(mut self, target: &T) -> Self {
        self.log_likelihood = self
            .particles
            .par_iter()
            .map(|s| target.log_likelihood(s))
            .collect();
        self
    }
}

/// Pools independent runs (see [`Pooled`]).
///
/// # Errors
/// [`IdentifyError::Posterior`] for fewer than 2 runs.
pub fn pool(mut runs: Vec<SmcRun>) -> Result<Pooled, IdentifyError> {
    if runs.len() < 2 {
        return Err(IdentifyError::Posterior {
            reason: format!("{} runs: need at least 2 to pool", runs.len()),
        });
    }
    runs.sort_by_key(|r| r.index);
    let r = runs.len() as f64;
    let logs: Vec<f64> = runs.iter().map(|x| x.log_evidence).collect();
    let log_evidence = log_sum_exp(logs.iter().copied()) - r.ln();
    // The runs' evidence relative to their mean: its spread is the relative error.
    let rel: Vec<f64> = logs.iter().map(|l| (l - log_evidence).exp()).collect();
    let var = rel.iter().map(|x| (x - 1.0).powi(2)).sum::<f64>() / (r - 1.0);
    let mut pooled = Pooled {
        particles: Vec::new(),
        weights: Vec::new(),
        log_likelihood: Vec::new(),
        run: Vec::new(),
        log_evidence,
        log_evidence_error: (var / r).sqrt(),
        ess: 0.0,
        runs: Vec::new(),
        evaluations: runs.iter().map(|x| x.evaluations).sum(),
    };
    for mut x in runs {
        pooled.weights.extend(x.weights.iter().map(|w| w / r));
        pooled
            .run
            .extend(std::iter::repeat_n(x.index, x.particles.len()));
        pooled.particles.append(&mut x.particles);
        pooled.log_likelihood.append(&mut x.log_likelihood);
        x.weights.clear();
        pooled.runs.push(x);
    }
    pooled.ess = 1.0 / pooled.weights.iter().map(|w| w * w).sum::<f64>();
    Ok(pooled)
}

/// Samples the posterior of `target`: `settings.runs` independent runs of `seed` (in
/// parallel) from `reference`, pooled.
///
/// # Errors
/// As [`run`].
pub fn sample<T: Target>(
    target: &T,
    settings: &SmcSettings,
    reference: &SmcReference,
    seed: u64,
) -> Result<Pooled, IdentifyError> {
    settings.validate()?;
    let runs = (0..settings.runs)
        .into_par_iter()
        .map(|k| run(target, settings, reference, seed, k))
        .collect::<Result<Vec<_>, _>>()?;
    pool(runs)
}

/// Weighted quantiles `qs` (each in `[0, 1]`) of `values` with normalised `weights`: the
/// smallest value whose cumulative weight reaches `q`.
pub fn weighted_quantiles(values: &[f64], weights: &[f64], qs: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let total: f64 = weights.iter().sum();
    qs.iter()
        .map(|&q| {
            let mut cum = 0.0;
            for &i in &order {
                cum += weights[i] / total;
                if cum >= q * (1.0 - 1e-12) {
                    return values[i];
                }
            }
            order.last().map_or(f64::NAN, |&i| values[i])
        })
        .collect()
}

/// `m` indices drawn from `weights` by systematic resampling with the stream of `seed` (for
/// bands computed on fewer points than the sample holds).
pub fn draws(weights: &[f64], m: usize, seed: u64) -> Vec<usize> {
    systematic(weights, m, stream(seed, [u64::MAX; 4]).random())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn systematic_resampling_keeps_each_weight_within_one_copy() {
        let w = [0.1, 0.45, 0.05, 0.4];
        for u in [0.0, 0.3, 0.77, 0.999] {
            let picks = systematic(&w, 4, u);
            for (i, wi) in w.iter().enumerate() {
                let copies = picks.iter().filter(|&&p| p == i).count() as f64;
                assert!((copies - 4.0 * wi).abs() < 1.0, "u {u}: {picks:?}");
            }
        }
        let d = draws(&w, 20, 3);
        for (i, wi) in w.iter().enumerate() {
            let copies = d.iter().filter(|&&p| p == i).count() as f64;
            assert!((copies - 20.0 * wi).abs() < 1.0, "{d:?}");
        }
    }

    #[test]
    fn weighted_quantiles_of_equal_weights_are_order_statistics() {
        let v = [5.0, 1.0, 3.0, 2.0, 4.0];
        let w = [0.2; 5];
        assert_eq!(
            weighted_quantiles(&v, &w, &[0.2, 0.5, 1.0]),
            vec![1.0, 3.0, 5.0]
        );
        // All the weight on one value.
        let w = [0.0, 0.0, 1.0, 0.0, 0.0];
        assert_eq!(weighted_quantiles(&v, &w, &[0.025, 0.975]), vec![3.0, 3.0]);
    }

    #[test]
    fn the_tempering_step_keeps_the_effective_sample_size() {
        let t: Vec<f64> = (0..100).map(|i| -(i as f64) * 0.7).collect();
        let step = next_step(&t, 0.0, 50.0);
        assert!(step < 1.0);
        assert!(
            (ess_of(&t, step) - 50.0).abs() < 1e-6,
            "{}",
            ess_of(&t, step)
        );
        // A flat likelihood is tempered in one step.
        assert_eq!(next_step(&[-3.0; 10], 0.25, 5.0), 0.75);
    }

    #[test]
    fn bad_settings_are_named() {
        for (s, needle) in [
            (SmcSettings::new(4, 4), "particles = 4"),
            (SmcSettings::new(100, 1), "runs = 1"),
        ] {
            let e = s.validate().unwrap_err().to_string();
            assert!(e.contains(needle), "{e}");
        }
    }
}

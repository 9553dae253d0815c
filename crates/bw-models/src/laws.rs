//! The collision laws as force elements driven by a relative-velocity input `u` (m/s), for
//! embedding in other simulators: BWSHCCL (eq:BWSHCCL, states x, z) and BWMCL (eq:BWMCL,
//! states r, y, z). Output: the contact force `F` (N), positive when pushing the bodies apart.

use crate::params::{ModelKind, PhysicalParams};
use crate::power::Pow;
use crate::{ModelError, State};

/// Bouc-Wen hysteresis `ż = A w - β |z|^(n-1) z |w| - γ |z|^n w`, given `|z|^n`.
#[inline]
pub(crate) fn hysteresis(a: f64, beta: f64, gamma: f64, z: f64, zn: f64, w: f64) -> f64 {
    // β |z|^(n-1) z |w| = β sign(z) |z|^n |w|; at z = 0 the factor |z|^n vanishes.
    a * w - zn * ((beta * w.abs()).copysign(z) + gamma * w)
}

fn expect(params: &PhysicalParams, kind: ModelKind) -> Result<(), ModelError> {
    if params.kind() == kind {
        Ok(())
    } else {
        Err(ModelError::WrongModel {
            expected: kind.name(),
            found: params.kind().name(),
        })
    }
}

/// The contact-law parameters both laws use, with the exponents classified once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Coefficients {
    pub(crate) k: f64,
    pub(crate) c: f64,
    pub(crate) alpha: f64,
    pub(crate) beta: f64,
    pub(crate) gamma: f64,
    pub(crate) a: f64,
    pub(crate) n: Pow,
    pub(crate) p: Pow,
}

impl Coefficients {
    fn new(params: &PhysicalParams, kind: ModelKind) -> Result<Self, ModelError> {
        expect(params, kind)?;
        let l = params.law();
        Ok(Self {
            k: l.k,
            c: l.c,
            alpha: l.alpha,
            beta: l.beta,
            gamma: l.gamma,
            a: l.a,
            n: Pow::new(l.n),
            p: Pow::new(l.p),
        })
    }
}

/// The Bouc-Wen-Simon-Hunt-Crossley collision law: a nonlinear dashpot in parallel with a
/// Bouc-Wen element, `ẋ = u`, `ż = A u - β|z|^(n-1) z |u| - γ|z|^n u`,
/// `F = -α k |x|^(p-1) x - (1-α) k |z|^(p-1) z - c |x|^p u`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bwshccl(pub(crate) Coefficients);

impl Bwshccl {
    /// The law with validated SHCCM parameters.
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for MCM parameters.
    pub fn new(params: &PhysicalParams) -> Result<Self, ModelError> {
        Coefficients::new(params, ModelKind::Shccm).map(Self)
    }

    /// State derivative `(ẋ, ż)` and force `F` at state `(x, z)` with input `u`.
    #[inline]
    pub fn eval(&self, s: &State<2>, u: f64) -> (State<2>, f64) {
        let c = &self.0;
        let (x, z) = (s[0], s[1]);
        let xp = c.p.of_abs(x.abs());
        let (zp, zn) = Pow::pair(z.abs(), c.p, c.n);
        let f =
            -c.alpha * c.k * xp.copysign(x) - (1.0 - c.alpha) * c.k * zp.copysign(z) - c.c * xp * u;
        (
            State::<2>::new(u, hysteresis(c.a, c.beta, c.gamma, z, zn, u)),
            f,
        )
    }
}

/// The Bouc-Wen-Maxwell collision law: a linear dashpot in series with a Bouc-Wen element,
/// `ṙ = (k/c)(α |y|^(p-1) y + (1-α) |z|^(p-1) z)`, `ẏ = u - ṙ`,
/// `ż = A ẏ - β|z|^(n-1) z |ẏ| - γ|z|^n ẏ`, `F = -c ṙ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bwmcl(pub(crate) Coefficients);

impl Bwmcl {
    /// The law with validated MCM parameters.
    ///
    /// # Errors
    /// [`ModelError::WrongModel`] for SHCCM parameters.
    pub fn new(params: &PhysicalParams) -> Result<Self, ModelError> {
        Coefficients::new(params, ModelKind::Mcm).map(Self)
    }

    /// State derivative `(ṙ, ẏ, ż)` and force `F` at state `(r, y, z)` with input `u`.
    #[inline]
    pub fn eval(&self, s: &State<3>, u: f64) -> (State<3>, f64) {
        let c = &self.0;
        let (y, z) = (s[1], s[2]);
        let (zp, zn) = Pow::pair(z.abs(), c.p, c.n);
        let f = -c.k * (c.alpha * c.p.signed(y) + (1.0 - c.alpha) * zp.copysign(z));
        let rdot = -f / c.c;
        let ydot = u - rdot;
        (
            State::<3>::new(rdot, ydot, hysteresis(c.a, c.beta, c.gamma, z, zn, ydot)),
            f,
        )
    }
}

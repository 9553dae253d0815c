//! The collision laws as force elements driven by a relative-velocity input `u` (m/s), for
//! embedding in other simulators: BWSHCCL (eq:BWSHCCL, states x, z) and BWMCL (eq:BWMCL,
//! states r, y, z). Output: the contact force `F` (N), positive when pushing the bodies apart.

use crate::params::{ModelKind, PhysicalParams};
use crate::power::{Pow, Powers};
use crate::{ModelError, State};

/// Bouc-Wen hysteresis `ż = A w - β |z|^(n-1) z |w| - γ |z|^n w`, with `zn()` giving `|z|^n`.
///
/// `β |z|^(n-1) z |w| = β sgn(z) |z|^n |w|`, so `ż = A w - |z|^n (β sgn(z) |w| + γ w)`; the
/// bracket is exactly 0 on the branch `sgn(z) = sgn(w)` when `γ = -β` (loading in all of the
/// paper's fits), and then `|z|^n` is not computed (the result is the same bit for bit).
#[inline]
pub(crate) fn hysteresis(
    a: f64,
    beta: f64,
    gamma: f64,
    z: f64,
    w: f64,
    zn: impl FnOnce() -> f64,
) -> f64 {
    let m = (beta * w.abs()).copysign(z) + gamma * w;
    if m == 0.0 {
        a * w
    } else {
        a * w - zn() * m
    }
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
        let mut zpow = Powers::of(z.abs());
        let zp = zpow.get(c.p);
        let f =
            -c.alpha * c.k * xp.copysign(x) - (1.0 - c.alpha) * c.k * zp.copysign(z) - c.c * xp * u;
        (
            State::<2>::new(u, hysteresis(c.a, c.beta, c.gamma, z, u, || zpow.get(c.n))),
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
        let mut zpow = Powers::of(z.abs());
        let zp = zpow.get(c.p);
        let f = -c.k * (c.alpha * c.p.signed(y) + (1.0 - c.alpha) * zp.copysign(z));
        let rdot = -f / c.c;
        let ydot = u - rdot;
        let zdot = hysteresis(c.a, c.beta, c.gamma, z, ydot, || zpow.get(c.n));
        (State::<3>::new(rdot, ydot, zdot), f)
    }
}

#[cfg(test)]
mod tests {
    use super::hysteresis;

    #[test]
    fn hysteresis_skips_the_power_only_where_its_factor_vanishes() {
        let (beta, gamma, zn) = (7.3, -7.3, 0.37);
        let direct = |z: f64, w: f64| -> f64 {
            let sz = z.signum();
            w - beta * zn * sz * w.abs() - gamma * zn * w
        };
        for (z, w) in [
            (-0.4, -1.2),
            (0.4, 1.2),
            (-0.4, 1.2),
            (0.4, -1.2),
            (0.0, 0.3),
        ] {
            let mut called = false;
            let got = hysteresis(1.0, beta, gamma, z, w, || {
                called = true;
                zn
            });
            assert!(
                (got - direct(z, w)).abs() <= 1e-15 * direct(z, w).abs(),
                "{z} {w}"
            );
            // Loading (sgn z = sgn w, with sgn(+0) = 1) with γ = -β: the bracket is exactly 0.
            let loading = z.signum() == w.signum();
            assert_eq!(called, !loading, "z {z} w {w}");
        }
    }
}

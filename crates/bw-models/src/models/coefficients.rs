//! The nondimensional parameters as the nondimensional models and their fast paths use them
//! ([`NdCoefficients`]): the exponents classified once.

use crate::error::ModelError;
use crate::params::{ModelKind, Nondim, NondimParams};
use crate::power::Pow;

/// The nondimensional parameters both ND models use, with the exponents classified once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NdCoefficients {
    pub(crate) b: f64,
    pub(crate) gamma: f64,
    pub(crate) kappa: f64,
    pub(crate) sigma: f64,
    pub(crate) n: Pow,
    pub(crate) p: Pow,
    /// `n - 1` and `p - 1`, for the Jacobians.
    nm1: Pow,
    pm1: Pow,
}

impl NdCoefficients {
    /// The parameters as given.
    pub(crate) fn nondim(&self) -> Nondim {
        Nondim {
            b: self.b,
            gamma: self.gamma,
            kappa: self.kappa,
            sigma: self.sigma,
            n: self.n.exponent(),
            p: self.p.exponent(),
        }
    }

    /// `(d/ds |s|^(p-1) s, d/dz ż)` pieces: `p |s|^(p-1)`.
    #[inline]
    pub(crate) fn dpow_p(&self, s: f64) -> f64 {
        self.p.exponent() * self.pm1.of_abs(s.abs())
    }

    /// `∂ż/∂w` and `∂ż/∂z` of `ż = w - |z|^n (B sgn(z) |w| + Γ w)` for the driving rate `w`.
    #[inline]
    pub(crate) fn dhysteresis(&self, z: f64, w: f64) -> (f64, f64) {
        let zn = self.n.of_abs(z.abs());
        let sz = if z == 0.0 { 0.0 } else { z.signum() };
        let sw = if w == 0.0 { 0.0 } else { w.signum() };
        let d_w = 1.0 - zn * (self.gamma + self.b * sz * sw);
        let d_z = -self.n.exponent()
            * self.nm1.of_abs(z.abs())
            * (self.b * w.abs() + self.gamma * w * sz);
        (d_w, d_z)
    }

    pub(crate) fn new(params: &NondimParams, kind: ModelKind) -> Result<Self, ModelError> {
        expect_nd(params, kind)?;
        let p = params.get();
        Ok(Self {
            b: p.b,
            gamma: p.gamma,
            kappa: p.kappa,
            sigma: p.sigma,
            n: Pow::new(p.n),
            p: Pow::new(p.p),
            nm1: Pow::new(p.n - 1.0),
            pm1: Pow::new(p.p - 1.0),
        })
    }
}

/// Which nondimensional model a parameter set belongs to.
fn expect_nd(p: &NondimParams, kind: ModelKind) -> Result<(), ModelError> {
    if p.kind() == kind {
        Ok(())
    } else {
        Err(ModelError::WrongModel {
            expected: kind.name(),
            found: p.kind().name(),
        })
    }
}

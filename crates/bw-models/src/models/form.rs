//! A model's nondimensional form ([`NdForm`]): what the crate's fast paths of a CoR evaluation
//! need of a built-in model, handed over by [`CollisionModel::nondimensional_form`].
//!
//! [`CollisionModel::nondimensional_form`]: super::CollisionModel::nondimensional_form

use super::coefficients::NdCoefficients;
use crate::input::Input;
use crate::params::ModelKind;
use crate::scaling::Scales;

/// A built-in model as its nondimensional model (eq:EBWSHCCM_nd, eq:EBWMCM_nd) with `N` states
/// sees it: its coefficients, its input in its own units, and for an SI model the Table 1
/// scales that map between the two. The type can be named and made only inside the crate.
#[derive(Clone, Copy)]
pub struct NdForm<'a, const N: usize> {
    /// Which model: the NDBWSHCCM for `N = 3`, the NDBWMCM for `N = 4`.
    pub(crate) kind: ModelKind,
    /// The nondimensional parameters, exponents classified.
    pub(crate) k: NdCoefficients,
    /// The model's input: `U(T)` of a nondimensional model, `u(t)` in N of an SI model.
    pub(crate) input: &'a dyn Input,
    /// An SI model's scales (Table 1): `U = u_factor u(T_c T)`, times `t = T_c T`; `None` for a
    /// nondimensional model.
    pub(crate) scales: Option<Scales>,
}

impl<'a> NdForm<'a, 3> {
    /// The form of an NDBWSHCCM, or of a BWSHCCM with its scales.
    pub(crate) fn shccm(k: NdCoefficients, input: &'a dyn Input, scales: Option<Scales>) -> Self {
        NdForm {
            kind: ModelKind::Shccm,
            k,
            input,
            scales,
        }
    }
}

impl<'a> NdForm<'a, 4> {
    /// The form of an NDBWMCM, or of a BWMCM with its scales.
    pub(crate) fn mcm(k: NdCoefficients, input: &'a dyn Input, scales: Option<Scales>) -> Self {
        NdForm {
            kind: ModelKind::Mcm,
            k,
            input,
            scales,
        }
    }
}

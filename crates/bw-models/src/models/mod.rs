//! The collision models with external input: BWSHCCM (eq:EBWSHCCM), BWMCM in the Lipschitz form
//! (eq:EBWMCM), their nondimensional forms (eq:EBWSHCCM_nd, eq:EBWMCM_nd), and the earlier
//! NDBWMCM form (eq:BWMCM_nd) for the equivalence the paper states; what they all are
//! ([`CollisionModel`]) and the nondimensional form through which the crate's fast paths reach
//! the built-in ones ([`form`]).

mod coefficients;
mod collision;
pub(crate) mod form;
mod nondim;
mod si;

pub(crate) use coefficients::NdCoefficients;
pub use collision::CollisionModel;
pub(crate) use collision::{at_rest, nondimensional_scales, unforced};
pub use nondim::{Ndbwmcm, NdbwmcmEarlier, Ndbwshccm};
pub use si::{Bwmcm, BwmcmEarlier, Bwshccm};

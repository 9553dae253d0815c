//! The built-in methods.
//!
//! Coefficients keep the digits of their published sources, so that they can be checked
//! against them; the compiler rounds each to the nearest `f64`.
#![allow(clippy::excessive_precision)]

use crate::Tableau;

mod dop853;
mod dopri5;
mod vern7;
mod vern9;

pub use dop853::DOP853;
pub use dopri5::DOPRI5;
pub use vern7::VERN7;
pub use vern9::VERN9;

/// All built-in methods, in order of increasing order.
pub const METHODS: [&Tableau; 4] = [&DOPRI5, &DOP853, &VERN7, &VERN9];

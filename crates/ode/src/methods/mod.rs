//! The built-in methods.

mod dop853;
mod dopri5;
mod vern7;

pub use dop853::DOP853;
pub use dopri5::DOPRI5;
pub use vern7::VERN7;

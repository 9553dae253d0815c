//! Identification: configs ([`config`]), the fits, evaluations, coverage studies, posteriors
//! and comparisons they describe ([`identify`]), the posterior's corner plot ([`corner`]) and
//! the checkpoints that let a long study resume ([`checkpoint`]).

pub mod checkpoint;
pub mod config;
pub mod corner;
pub mod identify;

//! A pair's impacts: scene files ([`scene`]), their simulation ([`simulate`], drop tests in
//! [`sequence`]), what a run gives ([`runs`], with the setting that would help one that
//! failed) and the outputs ([`output`]: the JSON summary, CSV files and figures).

pub mod notes;
pub mod output;
pub mod runs;
pub mod scene;
pub mod sequence;
pub mod simulate;

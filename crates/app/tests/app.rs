//! The application layer: the contact element of scenes ([`element`]), generated scenes and
//! configs ([`fuzz`]), scene files, output folders, summaries and charts.
//!
//! One binary: each test binary compiles the generic solver anew.

mod element;
mod fuzz;
mod materials;
mod outdir;
mod output;
mod plot;
mod scene;

//! # bwc-hack
//!
//! No code: this crate's dependencies pin the features of crates that the tests, the binaries
//! and the Python wheel share, so that one build serves all three (see its `Cargo.toml`).
//!
//! ```
//! // Nothing to call.
//! ```
#![deny(missing_docs)]

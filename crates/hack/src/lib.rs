//! # bwc-hack
//!
//! No code: this crate's dependencies pin the features of crates that the tests, the binaries
//! and the Python wheel share, so that one build serves all three (see its `Cargo.toml`). The
//! binaries and the wheel depend on it; nothing calls it.
#![deny(missing_docs)]

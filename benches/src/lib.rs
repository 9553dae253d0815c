//! Shared problems for the benchmarks.

//! The application layer: the contact element of scenes ([`element`]) and generated scenes and
//! configs ([`fuzz`]).
//!
//! One binary: each test binary compiles the generic solver anew.

mod element;
mod fuzz;

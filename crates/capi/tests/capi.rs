//! The C ABI from Rust: bad input ([`errors`]), the C example compiled and run ([`c_example`]), the
//! header against cbindgen ([`header`]).
//!
//! One binary: each test binary compiles the generic solver anew.

mod c_example;
mod errors;
mod header;
mod materials;
mod named;

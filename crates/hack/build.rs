//! Empty: the build-dependencies exist only to pin the features of the host's `syn`.
fn main() {}

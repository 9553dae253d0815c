//! How numbers read in summaries and messages.

/// `x` to 12 significant digits, so that a tolerance computed from another reads as written
/// (`1e-11`, not the `1.0000000000000001e-11` of `1e-10 / 10`) in summaries and messages.
pub fn tidy(x: f64) -> f64 {
    format!("{x:.11e}").parse().unwrap_or(x)
}

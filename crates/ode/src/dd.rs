//! Double-double numbers (about 32 significant digits), for integrations that double precision
//! cannot carry (the [`crate::Extrapolation`] method).
//!
//! The arithmetic is twofloat's (Joldes, Muller & Popescu's algorithms, with error bounds of a
//! few units in 2^-104). twofloat calls its own exp, ln, sin and powf preliminary, and measured
//! against Python's `decimal` they are off by up to 5e-15 (ln 7.77) and 8e-14 (7.77^8.18),
//! no better than `f64`. The functions here replace them, accurate to a few 1e-32 relative
//! (the tests hold them to 1e-30 against 60-digit values):
//!
//! - `exp(x) = 2^k exp(r)`, `r = x - k ln 2`, `|r| <= ln 2 / 2`; `exp(r) - 1` is summed from
//!   its Taylor series at `r / 2^10` and squared back ten times as `u (2 + u)`, which keeps the
//!   small `exp - 1` exact to the last bit.
//! - `ln(x)`: one Newton step `y + x exp(-y) - 1` from the `f64` logarithm, which squares its
//!   relative error of about 1e-16 (near `x = 1` the step works with `exp(y) - 1` and `x - 1`).
//! - `sin(x)`, `cos(x)`: reduced by a multiple of `π/2` to `|r| <= π/4`, then the Taylor
//!   series of sin or cos.
//! - `atan(x)`: two Newton steps on `tan θ = x` from the `f64` arctangent.
//! - `div(a, b)`: twofloat's quotient of two double-double numbers is off by about 1e-17
//!   relative (its reciprocal's residual `1 - b t` is rounded, not computed with a fused
//!   multiply-add), so `a / b.hi` is corrected by the residual `a - q b` instead. Division by
//!   an `f64` is twofloat's, which is accurate.

use twofloat::TwoFloat;

/// A double-double number: the unevaluated sum of two non-overlapping `f64`.
pub type Dd = TwoFloat;

/// `ln 2` as a double-double (hi, lo).
const LN_2: (f64, f64) = (std::f64::consts::LN_2, 2.3190468138462996e-17);
/// `π/2` as a double-double (hi, lo).
const FRAC_PI_2: (f64, f64) = (std::f64::consts::FRAC_PI_2, 6.123233995736766e-17);
/// Terms of a series are summed until they fall below this fraction of the sum.
const SERIES_EPS: f64 = 1e-34;

/// `π/2` in double-double.
pub fn frac_pi_2() -> Dd {
    dd(FRAC_PI_2.0, FRAC_PI_2.1)
}

/// The double-double `hi + lo`.
pub fn dd(hi: f64, lo: f64) -> Dd {
    TwoFloat::new_add(hi, lo)
}

/// `v * 2^k`, exact away from overflow and subnormals.
fn scale2(v: Dd, k: i32) -> Dd {
    let f = 2f64.powi(k);
    dd(v.hi() * f, v.lo() * f)
}

/// `e^x`; 0 below -745 and +inf above 709.7, as in `f64`.
pub fn exp(x: Dd) -> Dd {
    if x.hi() < -745.0 {
        return Dd::from(0.0);
    }
    if x.hi() > 709.7 {
        return Dd::from(f64::INFINITY);
    }
    let k = (x.hi() / LN_2.0).round();
    let r = x - dd(LN_2.0, LN_2.1) * k;
    // Split 2^k so that neither factor overflows at the ends of the range.
    let k = k as i32;
    scale2(scale2(exp_m1_reduced(r) + 1.0, k / 2), k - k / 2)
}

/// `e^r - 1` for `|r| <= ln 2 / 2`, to a few units in 2^-104 relative.
fn exp_m1_reduced(r: Dd) -> Dd {
    let s = scale2(r, -10);
    // exp(s) - 1 = s + s^2/2! + ...; |s| < 3.4e-4, so 10 terms reach 1e-40.
    let (mut term, mut sum) = (s, s);
    for i in 2..20 {
        term = term * s / i as f64;
        sum += term;
        if term.hi().abs() <= SERIES_EPS * sum.hi().abs() {
            break;
        }
    }
    for _ in 0..10 {
        sum = sum * (sum + 2.0);
    }
    sum
}

/// `ln x` for `x > 0` (NaN otherwise).
pub fn ln(x: Dd) -> Dd {
    if x.hi() <= 0.0 || x.hi().is_nan() {
        return Dd::from(f64::NAN);
    }
    if (0.75..1.4).contains(&x.hi()) {
        // Near 1 the Newton step works with exp(y) - 1 and the exact x - 1, so that the
        // small logarithm keeps its relative accuracy.
        let d = x - 1.0;
        let y = Dd::from(d.hi().ln_1p());
        let em1 = exp_m1_reduced(y);
        return y - (em1 - d) / (em1 + 1.0);
    }
    let y = Dd::from(x.hi().ln());
    y + x * exp(-y) - 1.0
}

/// `|x|^p` for `p > 0` (0 at `x = 0`).
pub fn pow_abs(x: Dd, p: f64) -> Dd {
    pow_abs_ln(ln_abs(x), p)
}

/// `ln |x|`, or `None` at `x = 0`: the shared logarithm of several powers of one base.
pub fn ln_abs(x: Dd) -> Option<Dd> {
    (x.hi() != 0.0).then(|| ln(x.abs()))
}

/// `|x|^p = exp(p ln|x|)` from `ln_abs(x)` (0 where `x = 0`, for `p > 0`).
pub fn pow_abs_ln(ln_abs: Option<Dd>, p: f64) -> Dd {
    ln_abs.map_or(Dd::from(0.0), |l| exp(l * p))
}

/// `v` with the sign of `s` (`s = 0` counts as positive, as `f64::copysign` with `+0`).
pub fn copysign(v: Dd, s: Dd) -> Dd {
    if (s.hi() < 0.0) == (v.hi() < 0.0) {
        v
    } else {
        -v
    }
}

/// `a / b` to a few 1e-32 relative: `q = a / b_hi`, then `q + (a - q b) / b_hi`.
pub fn div(a: Dd, b: Dd) -> Dd {
    let q = a / b.hi();
    q + (a - q * b) / b.hi()
}

/// `sin x`, accurate to about `max(1, |x|) 1e-31` absolute: the reduction's product `k π/2`
/// is rounded in double-double.
pub fn sin(x: Dd) -> Dd {
    quarter_turns(x, 0)
}

/// `cos x`, accurate as [`sin`].
pub fn cos(x: Dd) -> Dd {
    quarter_turns(x, 1)
}

/// `sin(x + q π/2)`, from `x = r + k π/2` with `|r| <= π/4`.
fn quarter_turns(x: Dd, q: i64) -> Dd {
    let k = (x.hi() / FRAC_PI_2.0).round();
    let r = x - frac_pi_2() * k;
    match (k as i64 + q).rem_euclid(4) {
        0 => sin_series(r),
        1 => cos_series(r),
        2 => -sin_series(r),
        _ => -cos_series(r),
    }
}

/// `arctan x` in `(-π/2, π/2)`, to about 1e-31 relative: double precision's `atan`, then two
/// Newton steps on `tan θ = x` (`θ += (x cos θ - sin θ) cos θ`), each squaring the error.
pub fn atan(x: Dd) -> Dd {
    let mut theta = Dd::from(x.hi().atan());
    for _ in 0..2 {
        let c = cos(theta);
        theta += (x * c - sin(theta)) * c;
    }
    theta
}

/// Taylor series of sin about 0 for `|r| <= π/4`.
fn sin_series(r: Dd) -> Dd {
    alternating_series(r, r, 1)
}

/// Taylor series of cos about 0 for `|r| <= π/4`.
fn cos_series(r: Dd) -> Dd {
    alternating_series(Dd::from(1.0), r, 0)
}

/// `Σ (-1)^j first r^(2j) / ((m+1)...(m+2j))` with `first = r^m / m!`.
fn alternating_series(first: Dd, r: Dd, m: usize) -> Dd {
    let r2 = r * r;
    let (mut term, mut sum) = (first, first);
    let mut k = m;
    while term.hi().abs() > SERIES_EPS * sum.hi().abs().max(f64::MIN_POSITIVE) {
        term = -term * r2 / ((k + 1) * (k + 2)) as f64;
        sum += term;
        k += 2;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative difference of `v` from the double-double `(hi, lo)`.
    fn rel(v: Dd, (hi, lo): (f64, f64)) -> f64 {
        let r = dd(hi, lo);
        ((v - r) / r).hi().abs()
    }

    // References: Python's decimal module at 60 digits (150 for the sine series at 101.3), and
    // mpmath for cos and atan, split into (hi, lo).
    #[test]
    fn elementary_functions_match_sixty_digit_values() {
        let exps = [
            (0.37, (1.4477346146633245, -8.202046215242462e-17)),
            (2.9, (18.17414536944306, -1.0319935825855902e-15)),
            (-13.25, (1.7603463121561693e-06, -4.4477459694426395e-23)),
            (55.5, (1.2686556140109568e+24, 124648300.62644248)),
        ];
        for (x, want) in exps {
            assert!(rel(exp(Dd::from(x)), want) < 1e-30, "exp({x})");
        }
        let lns = [
            (0.37, (-0.9942522733438669, -3.652349485344856e-17)),
            (7.77, (2.050270164379556, 1.4155943491569727e-17)),
            (1e-5, (-11.512925464970229, 2.790027459050308e-16)),
            (3.0e8, (19.519293032620475, 6.151727031195295e-16)),
            (0.999999, (-1.000000500029089e-06, 6.48066860222922e-23)),
        ];
        for (x, want) in lns {
            assert!(rel(ln(Dd::from(x)), want) < 1e-30, "ln({x})");
        }
        let sins = [
            (0.37f64, (0.361615431964962, -1.2480533007742616e-17)),
            (2.9, (0.23924932921398243, -1.1267666643498124e-17)),
            (-13.25, (-0.6316109877182386, 3.838735293828215e-18)),
            (101.3, (0.6954421919799202, -3.3411030051909904e-17)),
        ];
        for (x, want) in sins {
            // The reduction's product k π/2 is rounded at about |x| 2^-104.
            let err = rel(sin(Dd::from(x)), want);
            assert!(err < 1e-30 * x.abs().max(1.0), "sin({x}): {err:e}");
        }
        let coss = [
            (0.37f64, (0.9323273456060345, -4.9569278923610965e-17)),
            (2.9, (-0.9709581651495905, 4.579633153232696e-17)),
            (-13.25, (0.775285470129288, -2.5054737101750566e-17)),
            (101.3, (0.7185820465431654, -7.59059826650291e-18)),
        ];
        for (x, want) in coss {
            let err = rel(cos(Dd::from(x)), want);
            assert!(err < 1e-30 * x.abs().max(1.0), "cos({x}): {err:e}");
        }
        // mpmath at 60 digits.
        let atans = [
            (0.37, (0.3543799191234378, 2.7167638414024308e-18)),
            (-2.9, (-1.2387368592520112, 2.571119118874906e-17)),
            (1e-5, (9.999999999666668e-06, -4.575803486027043e-22)),
            (55.5, (1.5527802582408412, 6.82508897992337e-17)),
            (3.0e8, (1.5707963234615634, -1.070556332167147e-16)),
        ];
        for (x, want) in atans {
            let err = rel(atan(Dd::from(x)), want);
            assert!(err < 1e-30, "atan({x}): {err:e}");
        }
        // 1/3, 7.77/π and 0.5 = (π/4)/(π/2), mpmath at 60 digits.
        let pi = frac_pi_2() * 2.0;
        assert!(
            rel(
                div(Dd::from(1.0), Dd::from(3.0)),
                (1.0 / 3.0, 1.850371707708594e-17)
            ) < 1e-31
        );
        assert!(
            rel(
                div(Dd::from(7.77), pi),
                (2.4732678156480534, -4.2692584220805796e-17)
            ) < 1e-31
        );
        assert!(rel(div(frac_pi_2() * 0.5, frac_pi_2()), (0.5, 0.0)) < 1e-31);
        let p = pow_abs(Dd::from(-0.0123), 8.183188614474556);
        assert!(rel(p, (2.340632631448418e-16, 1.676321860368279e-32)) < 1e-30);
        assert_eq!(pow_abs(Dd::from(0.0), 2.5).hi(), 0.0);
    }

    #[test]
    fn twofloat_functions_are_not_double_double_accurate() {
        // Why this module exists: if twofloat's ln becomes accurate, use it instead.
        let want = (2.050270164379556, 1.4155943491569727e-17);
        assert!(rel(Dd::from(7.77).ln(), want) > 1e-20);
        assert!(rel(ln(Dd::from(7.77)), want) < 1e-30);
        // And its quotient of two double-double numbers.
        let half = frac_pi_2() * 0.5;
        assert!(rel(half / frac_pi_2(), (0.5, 0.0)) > 1e-20);
        assert!(rel(div(half, frac_pi_2()), (0.5, 0.0)) < 1e-31);
    }
}

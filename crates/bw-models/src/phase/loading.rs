//! The loading, from contact to the maximum compression: in closed form for the NDBWSHCCM on
//! `Γ = -B` (Hunt-Crossley), searched otherwise.

use super::chebyshev::{picard, Rung, MAX_N};
use super::{not_applicable, phi, Coefficients, Hysteretic, Loading};
use crate::power::{Pow, Powers};
use crate::{ModelError, ModelKind};
use std::f64::consts::FRAC_PI_4;

/// Newton steps allowed for the search of the maximum compression (it takes 3-6 where it
/// converges at all).
const MAX_NEWTON: usize = 12;
/// The largest `(B + Γ) |Z|^n` at the maximum compression the phase path takes: nearer the
/// saturation `dq/dZ = 1 / h` grows without bound and the loading in `Z` converges slowly.
const SATURATED: f64 = 0.5;
/// The same for the search's first guess, a little above [`SATURATED`] (the guess can be low).
const EARLY_SATURATED: f64 = 0.6;
/// Why a loading near saturation is declined.
const SATURATION: &str = "the loading nears the hysteresis' saturation, where Z is a poor variable (B + Gamma too large for the phase path)";

impl Coefficients {
    /// The NDBWSHCCM's loading in closed form, and its duration `∫ dV / F` over
    /// `V = -1 + ξ^(p+1)`, `ξ ∈ [0, 1]` (where `|X|^(p+1) = (p + 1) d (1 - d φ(σd))`,
    /// `d = (1 + V) / (1 + σ)`).
    pub(super) fn hunt_crossley(&self, r: &Rung) -> Loading {
        let p = self.p.exponent();
        let (s, q) = (self.sigma, p + 1.0);
        let u_m = (q * phi(-s)).powf(1.0 / q);
        let mut t = 0.0;
        if self.duration {
            let c_p = (q / (1.0 + s)).powf(p / q);
            let pow_q = Pow::new(q);
            let mut f = [0.0; MAX_N];
            for (fk, &x) in f.iter_mut().zip(&r.x) {
                let delta = pow_q.of_abs(0.5 * (x + 1.0));
                let d = delta / (1.0 + s);
                let shrink = (1.0 - d * phi(s * d)).powf(p / q);
                *fk = q / (c_p * shrink * (1.0 + s - s * delta));
            }
            t = 0.5 * r.total(&f[..r.n]);
        }
        Loading {
            u_m,
            q_m: -u_m,
            t,
            residual: 0.0,
        }
    }

    /// The loading on `u = -Z = u_m sin^4 φ`: `dq/du = -1 / h`, `dW/dq = F_el + c sqrt(2W)`
    /// from `W = 1/2`, with `u_m` moved by `W(u_m) h / F_el` (the slope of `W` where it
    /// vanishes) until `W(u_m) = 0`; from `|q_m|` of `h = 1` (`|q_m|^(p+1) = (p + 1) φ(-σ)` for
    /// the NDBWSHCCM, Hunt-Crossley; the undamped `(p + 1) / 2` for the NDBWMCM), moved to `Z`
    /// to first order in `B + Γ`.
    pub(super) fn searched_loading(&self, r: &Rung) -> Result<Loading, ModelError> {
        let n = r.n;
        let mut factors = LoadingFactors::default();
        for k in 0..n {
            let (s, c) = (FRAC_PI_4 * (r.x[k] + 1.0)).sin_cos();
            let unit = s * s * s * s;
            let mut pw = Powers::of(unit);
            factors.unit[k] = unit;
            factors.unit_p[k] = pw.get(self.p);
            factors.unit_n[k] = if self.beta == 0.0 {
                0.0
            } else {
                pw.get(self.n)
            };
            factors.slope[k] = 4.0 * s * s * s * c;
        }
        let p = self.p.exponent();
        let saturation = match self.beta {
            0.0 => f64::INFINITY,
            beta => beta.powf(-1.0 / self.n.exponent()),
        };
        let undamped = match self.kind {
            ModelKind::Shccm => phi(-self.sigma),
            ModelKind::Mcm => 0.5,
        };
        let x_m = ((p + 1.0) * undamped).powf(1.0 / (p + 1.0));
        // To first order in `B + Γ`, `|q| = u + (B + Γ) u^(n+1) / (n + 1)`.
        let u_guess = x_m * (1.0 - self.beta * self.n.of_abs(x_m) / (self.n.exponent() + 1.0));
        let mut u_m = u_guess.max(0.5 * x_m).min(0.9 * saturation);
        // The guess is within a few per cent of `u_m` off saturation: decline a loading that
        // will end near it before the search spends its steps.
        if self.beta * self.n.of_abs(u_m) > EARLY_SATURATED {
            return Err(not_applicable(SATURATION));
        }
        // `W` starts at 1/2: a few of its roundings are as close to 0 as it gets. `T` needs
        // more: its integrand `1 / sqrt(2W)` turns a miss `δ` at the end into about `sqrt(δ)`;
        // the Newton steps converge quadratically, so that costs one step more.
        let miss = match self.duration {
            true => self.settle * self.settle,
            false => self.settle,
        }
        .max(4.0 * f64::EPSILON);
        let mut nodes = LoadingNodes::default();
        for _ in 0..MAX_NEWTON {
            let (w_end, slope, change) = nodes.solve(self, r, u_m, &factors)?;
            if w_end.abs() <= miss {
                if self.beta * self.n.of_abs(u_m) > SATURATED {
                    return Err(not_applicable(SATURATION));
                }
                let t = if self.duration { nodes.time(r) } else { 0.0 };
                let (q_m, residual) = (nodes.q_end, change + w_end.abs());
                return Ok(Loading {
                    u_m,
                    q_m,
                    t,
                    residual,
                });
            }
            u_m = (u_m - w_end / slope).min(0.5 * (u_m + saturation));
        }
        Err(not_applicable(
            "the search for the maximum compression did not settle (sigma too large for the phase path)",
        ))
    }
}

/// What the loading's nodes on `u = u_m sin^4 φ` need whatever `u_m`: `sin^4 φ`, its `p`-th and
/// `n`-th powers (the latter where `B + Γ != 0`), and `d(sin^4 φ)/dφ`.
struct LoadingFactors {
    unit: [f64; MAX_N],
    unit_p: [f64; MAX_N],
    unit_n: [f64; MAX_N],
    slope: [f64; MAX_N],
}

impl Default for LoadingFactors {
    fn default() -> Self {
        LoadingFactors {
            unit: [0.0; MAX_N],
            unit_p: [0.0; MAX_N],
            unit_n: [0.0; MAX_N],
            slope: [0.0; MAX_N],
        }
    }
}

/// The loading's nodes at one trial `u_m`: `dq/dφ`, `W` and its integrand.
struct LoadingNodes {
    dq: [f64; MAX_N],
    w: [f64; MAX_N],
    rhs: [f64; MAX_N],
    q_end: f64,
}

impl Default for LoadingNodes {
    fn default() -> Self {
        LoadingNodes {
            dq: [0.0; MAX_N],
            w: [0.0; MAX_N],
            rhs: [0.0; MAX_N],
            q_end: 0.0,
        }
    }
}

impl LoadingNodes {
    /// `W(u_m)`, its slope in `u` there and the Picard residual.
    fn solve(
        &mut self,
        k: &Coefficients,
        r: &Rung,
        u_m: f64,
        f: &LoadingFactors,
    ) -> Result<(f64, f64, f64), ModelError> {
        let n = r.n;
        let (ump, umn) = (k.p.of_abs(u_m), k.n.of_abs(u_m));
        let mut z = [Hysteretic::default(); MAX_N];
        for (i, zi) in z[..n].iter_mut().enumerate() {
            let h = 1.0 - k.beta * umn * f.unit_n[i];
            if h <= 0.0 {
                return Err(not_applicable(
                    "the loading reaches the hysteresis' saturation (B + Gamma too large for the phase path)",
                ));
            }
            self.dq[i] = -u_m * f.slope[i] / h;
            let (z_abs, zp) = (u_m * f.unit[i], ump * f.unit_p[i]);
            *zi = Hysteretic {
                z_abs,
                zp,
                sign: -1.0,
                h,
            };
        }
        let mut q = [0.0; MAX_N];
        r.cumulative(&self.dq[..n], FRAC_PI_4, &mut q[..n]);
        let (mut f0, mut g) = ([0.0; MAX_N], [0.0; MAX_N]);
        for i in 0..n {
            let (fe, c) = if k.beta == 0.0 {
                // `q = Z` exactly (`h = 1`): its powers are `Z`'s.
                k.terms_of(-z[i].z_abs, z[i].zp, z[i])
            } else {
                k.terms(q[i], z[i])
            };
            (f0[i], g[i]) = (fe * self.dq[i], -c * self.dq[i]);
        }
        let (f0, g, w0) = (&f0[..n], &g[..n], (0.5, k.settle));
        let (w, rhs) = (&mut self.w[..n], &mut self.rhs[..n]);
        let change = picard(r, FRAC_PI_4, w0, (f0, g), w, rhs)?;
        self.q_end = FRAC_PI_4 * r.total(&self.dq[..n]);
        let h_end = 1.0 - k.beta * umn;
        let end = Hysteretic {
            z_abs: u_m,
            zp: ump,
            sign: -1.0,
            h: h_end,
        };
        let slope = -k.terms(self.q_end, end).0 / h_end;
        Ok((0.5 + FRAC_PI_4 * r.total(&self.rhs[..n]), slope, change))
    }

    /// `T` at the maximum compression: `∫ |dq| / sqrt(2W)`.
    fn time(&self, r: &Rung) -> f64 {
        let mut dt = [0.0; MAX_N];
        for (i, dti) in dt[..r.n].iter_mut().enumerate() {
            *dti = -self.dq[i] / (2.0 * self.w[i]).max(0.0).sqrt();
        }
        FRAC_PI_4 * r.total(&dt[..r.n])
    }
}

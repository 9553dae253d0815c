//! A CoR without time steps: the NDBWSHCCM and the NDBWMCM with no input, reduced to
//! quadratures in phase space.
//!
//! Without an input the clock enters the models only through `d/dT`. Write `q` for the
//! displacement that drives the hysteresis (`X` in the NDBWSHCCM, `Y` in the NDBWMCM) and
//! `W = (dq/dT)^2 / 2`. On each branch of the hysteresis (fixed signs of `dq/dT` and `Z`), `q`
//! is a function of `Z` alone, `dZ/dq = h(Z) = 1 - |Z|^n (B sgn(Z dq/dT) + Γ)`, and
//!
//! * NDBWSHCCM: `dW/dX = F_el - σ |X|^p V` with `F_el = -κ |X|^(p-1) X - (1 - κ) |Z|^(p-1) Z`;
//! * NDBWMCM (`Y' = V + σF`, `F = F_el(Y, Z)`): `dW/dY = F + σ (dF/dY) Y'`, where along a
//!   branch `dF/dY = -p (κ |Y|^(p-1) + (1 - κ) |Z|^(p-1) h)`.
//!
//! Both are `dW/dq = F_el - c(q) sqrt(2W)` with `c >= 0`, so a CoR is a few integrals over the
//! bounded phase variables, not a run in time:
//!
//! * **Loading** (`dq/dT < 0`, `h = 1 - (B + Γ)|Z|^n`). On the branch `Γ = -B` (`h = 1`,
//!   `Z = q`) the NDBWSHCCM's is the Hunt-Crossley problem `V dV / (1 - σV) = |X|^p dX`,
//!   solved in closed form: with `φ(y) = (-ln(1 - y) - y) / y^2`,
//!   `∫_0^V v dv / (1 - σv) = V^2 φ(σV)`, so the maximum compression `u_m = |X_m|` has
//!   `u_m^(p+1) = (p + 1) φ(-σ)`; its duration `∫ dV / F` is a quadrature in `ξ`,
//!   `V = -1 + ξ^(p+1)`, which takes out the contact's branch point. Otherwise (the NDBWMCM,
//!   or `Γ != -B`) `u_m = -Z_m` (where `dq/dT = 0`) is found by Newton steps on `W(u_m) = 0`,
//!   with `W` on `-Z = u_m sin^4 φ`, from a guess to first order in `B + Γ` and `σ`; each
//!   step keeps the terms of `W` near the turn to `s^2` (`s` the distance to it), so two or
//!   three steps settle. A loading that comes near the saturation of `Z`
//!   (`(B + Γ)|Z_m|^n > 1/2`, where `Z` is a poor variable) is declined.
//! * **Unloading with `Z < 0`** (`h = 1 + (B - Γ)|Z|^n`), in `θ ∈ [0, π/2]` with `-Z = u_m cos^4 θ`:
//!   `dq/dθ = 4 u_m cos^3 θ sin θ / h`, `dW/dθ = (dW/dq) dq/dθ`, `dT/dθ = (dq/dθ) / sqrt(2W)`.
//!   The map takes out the square-root branch of `dq/dT` at the maximum compression and tames
//!   the branch points of `|Z|^n`, `|Z|^p` and `|Z|^(p-1)` at the root of `Z` (fourth powers:
//!   squares leave `|Z|^(p-1)` nearly a step for `p` near 1); the blow-ups of `Z(T)` in complex
//!   time that bound every series in `T` sit at `Z = ∞` here.
//! * **Unloading with `Z >= 0`** (`h = 1 - (B + Γ)|Z|^n`, so `dq/dZ = 1/h`), in `t` with
//!   `Z = t^4`, up to the separation `F <= 0`, the first root of `F` on the interpolant. With
//!   `h = 1`, `F_el` vanishes where `κ^(1/p) |q| = (1 - κ)^(1/p) Z`; `h < 1` moves `q` on
//!   faster and the NDBWSHCCM's damping only lowers `F`, so `F <= 0` there and that point
//!   closes the panel (or, sooner, where `q` reaches 0 and `F = -(1 - κ) Z^p`). The NDBWMCM's
//!   `F` is `F_el`, and at `F = 0` its `V` is `Y'`.
//!
//! Each part is a Chebyshev interpolant on `N` points of the first kind per panel (`N` from 8
//! to 64, chosen from the tolerance; a check goes up the counts until two changes in a row are
//! small). The searched loading takes the next count up: its integrand is peaked, and on one
//! panel it converged more slowly than the unloading. The part with `Z < 0`
//! has two panels, split at the real part of the nearest root of `h`, the singularity that
//! bounds one interpolant's convergence there (one panel needs twice the points for the same
//! error). `q` is a plain quadrature; `W` depends on itself only through the damping, and is
//! found panel by panel by fixed-point (Picard) iteration from the undamped solution. For `e`
//! alone the iterations stop on the contraction's estimate of what is left, and the search's
//! last step needs no solve; `T` takes neither shortcut, as its integrand `1 / sqrt(2W)`
//! magnifies what is left in `W` near the turn.
//!
//! [`crate::impact`] takes this path for unforced CoRs under [`crate::Settings::phase`] (off
//! by default), falling back to the usual path where it declines or its check is unmet.
//!
//! On Table 3's DSS (1) and DSA (1) fits of both models this is 5.7-12 times faster than plain
//! DOP853 at equal error in `e`, from 6e-5 down to 1e-12 and beyond (BENCHMARKS.md,
//! "The phase path").
//!
//! ```
//! use bw_models::phase::{self, PhaseSettings};
//! use bw_models::{ModelKind, Nondim, NondimParams};
//! // Hunt-Crossley (B = Γ = 0): e solves e^2 φ(σe) = φ(-σ); σ = 0.5 gives 0.7484...
//! let p = NondimParams::new(ModelKind::Shccm, Nondim { b: 0.0, gamma: 0.0, kappa: 0.5, sigma: 0.5, n: 1.0, p: 1.5 })?;
//! let cor = phase::cor(&p, &PhaseSettings { tol: 1e-12, ..PhaseSettings::default() })?;
//! assert!((cor.e - 0.748434931597434).abs() < 1e-12 && cor.tolerance_met == Some(true));
//! println!("e = {} ± {:?}, T_s = {:?}, {} points a panel", cor.e, cor.e_error, cor.t_s, cor.nodes);
//! # Ok::<(), bw_models::ModelError>(())
//! ```

mod chebyshev;
mod loading;

use crate::power::{Pow, Powers};
use crate::{ModelError, ModelKind, Nondim, NondimParams};
use chebyshev::{picard, root, rung, Rung, Settle, Start, MAX_N, RUNGS};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// How much larger than the tolerance the change before the last may be in a check.
const STALL: f64 = 1e3;
/// What [`cor`] computes, and how carefully.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseSettings {
    /// The tolerance in `e` (absolute; `e` is at most 1).
    pub tol: f64,
    /// Whether to estimate the error: results on increasing node counts, the last reported with
    /// its change from the one before as its estimate, until that change meets `tol` and the
    /// change before it is at most a thousand times `tol`. Without
    /// it one node count is chosen from `tol`, where it meets `tol` on the paper's DSS (1) fit
    /// at 0.5-5 m/s (like a Runge-Kutta run at `rtol`: no estimate of the error in `e`).
    pub check: bool,
    /// Whether to compute the separation time `T_s` too (the CoR alone needs no clock).
    pub duration: bool,
}

impl Default for PhaseSettings {
    /// `tol = 1e-10`, checked, with the duration.
    fn default() -> Self {
        PhaseSettings {
            tol: 1e-10,
            check: true,
            duration: true,
        }
    }
}

/// A CoR computed in phase space (nondimensional: `V(0) = -1`, so `e` is `V` at the
/// separation, and `T_s` is in the model's time unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhaseCor {
    /// Coefficient of restitution.
    pub e: f64,
    /// Separation time `T_s`, where [`PhaseSettings::duration`] asked for it.
    pub t_s: Option<f64>,
    /// Estimate of the error in `e` where [`PhaseSettings::check`] asked for it: the change
    /// from the previous node count (an estimate of that coarser result's error, so a generous
    /// one of this result's), plus what the fixed-point iteration for the damping left.
    pub e_error: Option<f64>,
    /// The same change for `t_s`. `T_s` converges more slowly than `e` and the node count is
    /// raised for `e` alone, so this is an indication, not a bound: on the paper's fits
    /// `T_s` was within 3 times it.
    pub t_s_error: Option<f64>,
    /// Whether `e_error` met the tolerance (checked runs only); if not, `e` is the result at
    /// the largest node count.
    pub tolerance_met: Option<bool>,
    /// Chebyshev points per panel of the reported result's unloading (a searched loading
    /// takes the next count up).
    pub nodes: usize,
    /// The law's displacement at the separation: `X` (NDBWSHCCM) or `Y` (NDBWMCM).
    pub q_s: f64,
    /// The hysteretic displacement `Z` at the separation.
    pub z_s: f64,
}

impl PhaseCor {
    fn of(solved: &Solved, nodes: usize) -> Self {
        PhaseCor {
            e: solved.e,
            t_s: solved.t_s,
            e_error: None,
            t_s_error: None,
            tolerance_met: None,
            nodes,
            q_s: solved.q_s,
            z_s: solved.z_s,
        }
    }
}

/// The CoR of the NDBWSHCCM or NDBWMCM `params` with no input.
///
/// # Errors
/// [`ModelError::NotApplicable`] where the loading comes near the saturation of `Z`, and where
/// a fixed-point iteration for the damping or the search for the maximum compression does not
/// settle (large `σ`); the time-domain path [`crate::impact`] serves every case.
/// [`ModelError::InvalidSetting`] for `tol` not in `(0, 1)`.
pub fn cor(params: &NondimParams, settings: &PhaseSettings) -> Result<PhaseCor, ModelError> {
    let tol = settings.tol;
    if !(tol > 0.0 && tol < 1.0) {
        return Err(ModelError::InvalidSetting {
            name: "tol",
            value: tol,
            allowed: "0 < tol < 1",
        });
    }
    let p = params.get();
    let k = Coefficients::new(params.kind(), p, tol, settings.duration);
    let first = RUNGS.iter().position(|&n| n >= nodes_for(tol)).unwrap_or(0);
    if !settings.check {
        return Ok(PhaseCor::of(&k.solve(rung(RUNGS[first]))?, RUNGS[first]));
    }
    checked(&k, tol, first.saturating_sub(1))
}

/// The phase path's CoR for [`crate::impact`] under [`crate::Settings::phase`]: with no input,
/// checked to `e_tol` (or one node count from `rtol` without it); `None` where the path
/// declines, the settings are out of its range, or the check is not met.
pub(crate) fn for_impact<I: crate::input::Input>(
    params: &NondimParams,
    input: &I,
    settings: &crate::Settings,
) -> Option<PhaseCor> {
    if !settings.phase || !input.is_zero() {
        return None;
    }
    let phase = PhaseSettings {
        tol: settings.e_tol.unwrap_or(settings.rtol),
        check: settings.e_tol.is_some(),
        duration: true,
    };
    let cor = cor(params, &phase).ok()?;
    // A contact longer than the horizon is the usual path's to report (no separation).
    let within = cor.t_s.is_some_and(|t| t <= settings.t_max);
    (cor.tolerance_met != Some(false) && within).then_some(cor)
}

/// The impact of a phase CoR ending in `state` (see [`crate::Impact::phase`]).
pub(crate) fn impact_of<const N: usize>(
    cor: &PhaseCor,
    state: crate::State<N>,
    settings: &crate::Settings,
) -> crate::Impact<N> {
    let stats = bwc_ode::Stats::default();
    crate::Impact::unchecked((cor.t_s, cor.e, state), stats, settings.rtol).with(|c| {
        c.e_error = cor.e_error;
        c.t_s_error = cor.t_s_error;
        if cor.tolerance_met == Some(true) {
            c.check = crate::Check::Met;
        }
        c.phase = true;
    })
}

/// Results on the rungs from `first` up until two changes in a row are small: the last at most
/// `tol`, the one before at most [`STALL`] times `tol`. One small change alone can be two
/// results that are off alike: on case 18986 of the stress sweep's seed 1 (`p = 9.3`, `κ` near
/// 1) 24 and 32 points agree to 4e-11 and are both 1.1e-9 off; 16 points are 2e-5 off.
fn checked(k: &Coefficients, tol: f64, first: usize) -> Result<PhaseCor, ModelError> {
    // A coarse count's failure (a Picard iteration or search that did not settle there) only
    // leaves the next count without a predecessor.
    let mut previous: Option<Solved> = None;
    let mut before = f64::INFINITY;
    let mut out = Err(not_applicable("no node count gave a result"));
    for &n in &RUNGS[first..] {
        let solved = match k.solve(rung(n)) {
            Ok(solved) => solved,
            Err(err) => {
                (previous, before, out) = (None, f64::INFINITY, Err(err));
                continue;
            }
        };
        let Some(was) = previous else {
            previous = Some(solved);
            continue;
        };
        let change = (solved.e - was.e).abs() + solved.residual;
        let met = change <= tol && before <= STALL * tol;
        out = Ok(PhaseCor {
            e_error: Some(change),
            t_s_error: solved.t_s.zip(was.t_s).map(|(a, b)| (a - b).abs()),
            tolerance_met: Some(met),
            ..PhaseCor::of(&solved, n)
        });
        if met {
            break;
        }
        (previous, before) = (Some(solved), change);
    }
    out
}

fn not_applicable(reason: &'static str) -> ModelError {
    ModelError::NotApplicable { reason }
}

/// The node count per panel where the paper's DSS (1) and DSA (1) fits at 0.5-5 m/s are
/// within `tol` in `e` (largest errors over the fits and speeds: 7e-5 at 8 nodes, 3e-6 at 12,
/// 2e-8 at 16, 6e-12 at 24, the references' 2e-13 at 32), so that a check's next count usually
/// meets `tol` at once.
fn nodes_for(tol: f64) -> usize {
    match tol {
        t if t >= 1e-4 => 8,
        t if t >= 5e-6 => 12,
        t if t >= 3e-8 => 16,
        t if t >= 1e-11 => 24,
        t if t >= 1e-13 => 32,
        _ => 48,
    }
}

/// The loading's node count beside `n` for the unloading's panels: the next count up. The
/// loading is one panel over `Z` from the contact to the maximum compression, and its
/// integrand `F_el dq/dφ ∝ sin^(4p+3) φ cos φ` is peaked, so it converges more slowly than
/// the unloading's two panels (on 12 points the loading was 1e-6 to 2e-6 off on DSA (1) and
/// DSS (1)'s NDBWMCM, the unloading 1e-7).
fn loading_nodes(n: usize) -> usize {
    RUNGS.iter().copied().find(|&m| m > n).unwrap_or(MAX_N)
}

/// `φ(y) = (-ln(1 - y) - y) / y^2 = Σ_{k>=2} y^(k-2) / k`, by its series near 0 where the
/// closed form cancels.
fn phi(y: f64) -> f64 {
    if y.abs() < 0.1 {
        (2..20).rev().fold(0.0, |acc, k| acc * y + 1.0 / k as f64)
    } else {
        (-(-y).ln_1p() - y) / (y * y)
    }
}

/// One node count's CoR: `e`, `T_s`, the Picard iterations' residual in `e`, and `q`, `Z` at
/// the separation.
struct Solved {
    e: f64,
    t_s: Option<f64>,
    residual: f64,
    q_s: f64,
    z_s: f64,
}

/// The model's parameters.
struct Coefficients {
    kind: ModelKind,
    /// Whether `T` is wanted.
    duration: bool,
    /// `B + Γ` and `B - Γ`: `h = 1 - (B + Γ) |Z|^n` where `Z` and `dq/dT` share their sign,
    /// `1 + (B - Γ) |Z|^n` where they do not.
    beta: f64,
    alpha: f64,
    kappa: f64,
    /// `κ^(1/p)` and `(1 - κ)^(1/p)`: where `F_el` vanishes after the root of `Z`.
    kappa_roots: (f64, f64),
    sigma: f64,
    n: Pow,
    p: Pow,
    /// Where the Picard iterations and the loading's search stop (see
    /// [`Coefficients::picard_settle`]).
    settle: f64,
}

/// The maximum compression: `u_m = -Z`, `q_m`, `T` there, and what the Picard iterations
/// left.
struct Loading {
    u_m: f64,
    q_m: f64,
    t: f64,
    residual: f64,
}

/// What each part hands on.
struct Part {
    /// `q`, `W` and `T` at the part's end.
    q: f64,
    w: f64,
    t: f64,
    /// The separation, where it came within the part.
    separated: Option<Separation>,
    /// The Picard iterations' last changes in `W` so far, summed.
    residual: f64,
}

/// `W`, `T`, `q` and `Z` at the separation.
#[derive(Clone, Copy)]
struct Separation {
    w: f64,
    t: f64,
    q: f64,
    z: f64,
}

/// `|Z|`, `|Z|^p`, the sign of `Z` and `h` at a node.
#[derive(Clone, Copy, Default)]
struct Hysteretic {
    z_abs: f64,
    zp: f64,
    sign: f64,
    h: f64,
}

impl Coefficients {
    fn new(kind: ModelKind, nd: &Nondim, tol: f64, duration: bool) -> Self {
        Coefficients {
            kind,
            duration,
            beta: nd.b + nd.gamma,
            alpha: nd.b - nd.gamma,
            kappa: nd.kappa,
            kappa_roots: (nd.kappa.powf(1.0 / nd.p), (1.0 - nd.kappa).powf(1.0 / nd.p)),
            sigma: nd.sigma,
            n: Pow::new(nd.n),
            p: Pow::new(nd.p),
            // For `e` alone the stops are cheap estimates (the contraction's, the search's
            // landing) and a hundredth of `tol` costs little more than a tenth; it leaves the
            // node count, not the stops, to set the error (on DSA (1)'s NDBWSHCCM on 12 points,
            // 3e-8 to 7e-8 off at 1-5 m/s instead of up to 9e-7).
            settle: match duration {
                true => 0.1 * tol,
                false => 0.01 * tol,
            }
            .max(1e-17),
        }
    }

    /// The Picard iterations' stop at `tol`: on the contraction's estimate of what is left
    /// for `e` alone; on the change, a hundred times lower, for `T`. What the iterations leave
    /// in `W` is the same on every node count, so a check cannot see it, and `T`'s integrand
    /// `1 / sqrt(2W)` magnifies it near the turn (on DSA (1)'s fits at 2 m/s and `tol` 1e-6,
    /// the estimate at `tol / 100` left `T_s` 4.6e-10 off, ten times the check's change; a
    /// change of `tol` left it 3.4e-10 off on every count from 16 points up).
    fn picard_settle(&self, tol: f64) -> Settle {
        match self.duration {
            false => Settle {
                tol,
                estimated: true,
            },
            true => Settle {
                tol: (0.01 * tol).max(1e-17),
                estimated: false,
            },
        }
    }

    /// `F_el` and the damping's coefficient `c` of `dW/dq = F_el - c sqrt(2W)` at `q`.
    fn terms(&self, q: f64, z: Hysteretic) -> (f64, f64) {
        self.terms_of(q, self.p.of_abs(q.abs()), z)
    }

    /// [`Coefficients::terms`] from `|q|^p` (`|q|^(p-1)` and `|Z|^(p-1)` by a division: `q`
    /// and `Z` do not vanish at the nodes).
    fn terms_of(&self, q: f64, qp: f64, z: Hysteretic) -> (f64, f64) {
        let f_el = -self.kappa * qp.copysign(q) - (1.0 - self.kappa) * z.zp * z.sign;
        let c = match self.kind {
            ModelKind::Shccm => self.sigma * qp,
            ModelKind::Mcm => {
                let slope = self.kappa * qp / q.abs() + (1.0 - self.kappa) * z.zp / z.z_abs * z.h;
                self.sigma * self.p.exponent() * slope
            }
        };
        (f_el, c)
    }

    /// The contact force `F` at `q`, `Z` and `W` while `dq/dT >= 0`.
    fn force(&self, q: f64, z: f64, w: f64) -> f64 {
        let qp = self.p.of_abs(q.abs());
        let f_el = -self.kappa * qp.copysign(q) - (1.0 - self.kappa) * self.p.signed(z);
        match self.kind {
            ModelKind::Shccm => f_el - self.sigma * qp * (2.0 * w).max(0.0).sqrt(),
            ModelKind::Mcm => f_el,
        }
    }

    /// A function with the sign and the root of `F` at `q <= 0`, `Z` and `W`, smooth at
    /// `q = 0`, to locate the separation on its interpolant. With `q <= 0`,
    /// `F = a^p - b^p` for `a = (-q) (κ - σV)^(1/p)` and `b = (1 - κ)^(1/p) Z` (signed powers;
    /// `σ = 0` in the NDBWMCM's `F = F_el`), so `a - b` has `F`'s sign and root without the
    /// branch point of `|q|^p` at `q = 0`, next to which a CoR with `κ` near 1 separates. That
    /// needs `κ - σV` away from 0: `σ <= κ / 2` does (`V <= 1`); otherwise `F` itself. With
    /// `κ <= 1/2` the root is at `|q| >= Z (κ - σV)^(-1/p)`, away from `q = 0`, and `F`
    /// serves without the powers.
    fn crossing(&self, q: f64, z: f64, w: f64) -> f64 {
        if self.kappa <= 0.5 {
            return self.force(q, z, w);
        }
        let (ka, kb) = self.kappa_roots;
        let a = match self.kind {
            ModelKind::Shccm if self.sigma <= 0.5 * self.kappa => {
                let damped = self.kappa - self.sigma * (2.0 * w).max(0.0).sqrt();
                damped.powf(1.0 / self.p.exponent())
            }
            ModelKind::Shccm => return self.force(q, z, w),
            ModelKind::Mcm => ka,
        };
        -q * a - kb * z
    }

    /// The CoR on `r`'s nodes, unchecked.
    fn solve(&self, r: &Rung) -> Result<Solved, ModelError> {
        let up = rung(loading_nodes(r.n));
        let loading = match self.kind {
            ModelKind::Shccm if self.beta == 0.0 => self.hunt_crossley(up),
            _ => self.searched_loading(up)?,
        };
        let one = self.unloading_before_root(r, &loading)?;
        let (at, residual) = match one.separated {
            Some(at) => (at, one.residual),
            None => self.unloading_after_root(r, &one)?,
        };
        let e = (2.0 * at.w.max(0.0)).sqrt();
        Ok(Solved {
            e,
            t_s: self.duration.then_some(at.t),
            // `de = dW / e`.
            residual: residual / e.max(f64::MIN_POSITIVE),
            q_s: at.q,
            z_s: at.z,
        })
    }

    /// The part with `Z < 0`, in `θ` with `-Z = u_m cos^4 θ`, from the maximum compression, in
    /// two panels split at `θ_split`.
    fn unloading_before_root(&self, r: &Rung, loading: &Loading) -> Result<Part, ModelError> {
        let u_m = loading.u_m;
        let split = self.theta_split(u_m);
        let start = Part {
            q: loading.q_m,
            w: 0.0,
            t: loading.t,
            separated: None,
            residual: loading.residual,
        };
        let first = self.theta_panel(r, u_m, (0.0, split), &start)?;
        if first.separated.is_some() {
            return Ok(first);
        }
        self.theta_panel(r, u_m, (split, FRAC_PI_2), &first)
    }

    /// Where the first panel in `θ` ends: at the real part of the nearest root of
    /// `h = 1 + (B - Γ) u^n` (`u = (B - Γ)^(-1/n) e^(±iπ/n)`), which bounds the convergence of one
    /// interpolant over the whole part; at `π/4` where `h` has no roots (`B = Γ`).
    fn theta_split(&self, u_m: f64) -> f64 {
        if self.alpha == 0.0 {
            return FRAC_PI_4;
        }
        let n = self.n.exponent();
        // cos θ = (|u| / u_m)^(1/4) e^(±iπ/(4n)); θ's real part by `acos` of the real part, a
        // fair stand-in for the split.
        let modulus = (self.alpha.powf(-1.0 / n) / u_m).sqrt().sqrt();
        let real = modulus * (std::f64::consts::PI / (4.0 * n)).cos();
        real.clamp(0.2, 0.98).acos().clamp(0.3, FRAC_PI_2 - 0.2)
    }

    /// One panel `θ ∈ [a, b]` of the part with `Z < 0`, from the state `from`.
    fn theta_panel(
        &self,
        r: &Rung,
        u_m: f64,
        (a, b): (f64, f64),
        from: &Part,
    ) -> Result<Part, ModelError> {
        let (n, half) = (r.n, 0.5 * (b - a));
        let (mut dq, mut z) = ([0.0; MAX_N], [Hysteretic::default(); MAX_N]);
        for k in 0..n {
            let (s, c) = (a + half * (r.x[k] + 1.0)).sin_cos();
            let c2 = c * c;
            let mut pw = Powers::of(u_m * c2 * c2);
            let h = 1.0 + self.alpha * pw.get(self.n);
            dq[k] = 4.0 * u_m * c2 * c * s / h;
            let (z_abs, zp, sign) = (u_m * c2 * c2, pw.get(self.p), -1.0);
            z[k] = Hysteretic { z_abs, zp, sign, h };
        }
        let z_at = |s: f64| -u_m * (a + half * (s + 1.0)).cos().powi(4);
        let panel = Panel { r, half, from };
        panel.solve(self, (&dq[..n], &z[..n]), &z_at)
    }

    /// `t` at `s ∈ [-1, 1]` on `[0, t_end]`: `t_end u` with `u = (s + 1) / 2`, or, where the
    /// panel ends at `q = 0`, `t_end (1 - (1 - u)^4)`, which makes `q` vanish like `(1 - u)^4`
    /// there: the branch points of `|q|^p` and of the NDBWMCM's `|q|^(p-1)` at that end become
    /// four times milder, as the map `Z = t^4` does at the other.
    fn after_root_t(s: f64, (t_end, squeeze): (f64, bool)) -> f64 {
        let u = 0.5 * (s + 1.0);
        match squeeze {
            false => t_end * u,
            true => t_end * (1.0 - (1.0 - u).powi(4)),
        }
    }

    /// `dq/ds` and the hysteretic element at the nodes of the panel `t ∈ [0, t_end]`
    /// ([`Coefficients::after_root_t`]), `Z = t^4`.
    fn after_root_nodes(
        &self,
        r: &Rung,
        (t_end, squeeze): (f64, bool),
        dq: &mut [f64; MAX_N],
        z: &mut [Hysteretic; MAX_N],
    ) {
        for k in 0..r.n {
            let t = Self::after_root_t(r.x[k], (t_end, squeeze));
            let dt = match squeeze {
                false => 0.5 * t_end,
                true => 2.0 * t_end * (1.0 - 0.5 * (r.x[k] + 1.0)).powi(3),
            };
            let mut pw = Powers::of(t * t * t * t);
            let h = 1.0 - self.beta * pw.get(self.n);
            dq[k] = 4.0 * t * t * t / h * dt;
            let (z_abs, zp, sign) = (t * t * t * t, pw.get(self.p), 1.0);
            z[k] = Hysteretic { z_abs, zp, sign, h };
        }
    }

    /// The part with `Z >= 0`, in `t` with `Z = t^4`, up to the separation: there, `W`, `T`,
    /// `q` and `Z`, and the Picard residual.
    fn unloading_after_root(&self, r: &Rung, one: &Part) -> Result<(Separation, f64), ModelError> {
        let (n, q0) = (r.n, one.q);
        let (ka, kb) = self.kappa_roots;
        // Where `F_el` would vanish with `h = 1` (`q = q_0 + Z`); `h <= 1` only moves `q` on
        // faster, so `F_el <= 0` there.
        let mut z_end = (-ka * q0 / (ka + kb)).max(0.0);
        if self.beta * self.n.of_abs(z_end) >= 0.99 {
            return Err(not_applicable(
                "the unloading nears the hysteresis' saturation (B + Gamma too large for the phase path)",
            ));
        }
        let (mut dq, mut z) = ([0.0; MAX_N], [Hysteretic::default(); MAX_N]);
        let mut map = (z_end.sqrt().sqrt(), false);
        self.after_root_nodes(r, map, &mut dq, &mut z);
        let q_end = q0 + r.total(&dq[..n]);
        if q_end > 0.0 {
            // With `h < 1`, `q` passes 0 first, a branch point of `|q|^p` inside the panel:
            // the panel ends there instead, where `F = -(1 - κ) Z^p < 0` still brackets the
            // separation, on a map that makes the branch point milder. (`dq` does not depend
            // on `q`, so its interpolant locates the point.)
            let mut minus_q = [0.0; MAX_N];
            r.cumulative(&dq[..n], 1.0, &mut minus_q[..n]);
            minus_q[..n].iter_mut().for_each(|m| *m = -(*m + q0));
            let c = r.coefficients(&minus_q[..n]);
            let s = root(&c[..n], (-1.0, -q0), (1.0, -q_end));
            map = (Self::after_root_t(s, map), true);
            z_end = map.0.powi(4);
            self.after_root_nodes(r, map, &mut dq, &mut z);
        }
        let z_at = |s: f64| Self::after_root_t(s, map).powi(4);
        let panel = Panel {
            r,
            half: 1.0,
            from: one,
        };
        let end = panel.solve(self, (&dq[..n], &z[..n]), &z_at)?;
        let at = end.separated.unwrap_or(Separation {
            w: end.w,
            t: end.t,
            q: end.q,
            z: z_end,
        });
        Ok((at, end.residual))
    }
}

/// One panel of the unloading: its nodes, half-width and the state it starts from.
struct Panel<'a> {
    r: &'a Rung,
    half: f64,
    from: &'a Part,
}

impl Panel<'_> {
    /// `q`, `W` and `T` over the panel from `dq` (`dq/ds` at the nodes) and the hysteretic
    /// element there; `z_at(s)` is `Z` at `s ∈ [-1, 1]`. Where `F` turns non-positive by the
    /// end, the separation is located on the interpolant of `F`.
    fn solve(
        &self,
        k: &Coefficients,
        (dq, z): (&[f64], &[Hysteretic]),
        z_at: &dyn Fn(f64) -> f64,
    ) -> Result<Part, ModelError> {
        let (r, n, half, from) = (self.r, self.r.n, self.half, self.from);
        let mut q = [0.0; MAX_N];
        r.cumulative(dq, half, &mut q[..n]);
        let (mut f0, mut g) = ([0.0; MAX_N], [0.0; MAX_N]);
        for i in 0..n {
            q[i] += from.q;
            let (fe, c) = k.terms(q[i], z[i]);
            (f0[i], g[i]) = (fe * dq[i], c * dq[i]);
        }
        let (mut w, mut w_rhs) = ([0.0; MAX_N], [0.0; MAX_N]);
        let (f0, g) = (&f0[..n], &g[..n]);
        let change = picard(
            r,
            half,
            (from.w, k.picard_settle(k.settle)),
            (f0, g),
            (&mut w[..n], Start::Undamped),
            &mut w_rhs[..n],
        )?;
        let mut dt = [0.0; MAX_N];
        if k.duration {
            for i in 0..n {
                dt[i] = dq[i] / (2.0 * w[i]).max(0.0).sqrt();
            }
        }
        let q_end = from.q + half * r.total(dq);
        let w_end = from.w + half * r.total(&w_rhs[..n]);
        let z_end = z_at(1.0);
        let f_end = k.force(q_end, z_end, w_end);
        // `T` at `s` (`None`: the panel's end), only where asked for: each reading away from
        // the end is a transform of its integrand.
        let t_at = |s: Option<f64>| match (k.duration, s) {
            (false, _) => 0.0,
            (true, None) => from.t + half * r.total(&dt[..n]),
            (true, Some(s)) => from.t + half * r.integral_to(&dt[..n], s),
        };
        let separated = (f_end <= 0.0).then(|| {
            let w_rhs = &w_rhs[..n];
            if f_end == 0.0 {
                let (w, t, q, z) = (w_end, t_at(None), q_end, z_end);
                return Separation { w, t, q, z };
            }
            // The first crossing: bracketed by the first node where `F <= 0` (a tiny `F`
            // near the end can carry the interpolant's own roots), on the smooth stand-in
            // for `F`.
            let mut force = [0.0; MAX_N];
            for i in 0..n {
                force[i] = k.crossing(q[i], z[i].sign * z[i].z_abs, w[i]);
            }
            let first = force[..n].iter().position(|&f| f <= 0.0);
            let end = k.crossing(q_end, z_end, w_end);
            let hi = first.map_or((1.0, end), |i| (r.x[i], force[i]));
            let lo = match first {
                Some(0) => (-1.0, k.crossing(from.q, z_at(-1.0), from.w)),
                Some(i) => (r.x[i - 1], force[i - 1]),
                None => (r.x[n - 1], force[n - 1]),
            };
            let s = root(&r.coefficients(&force[..n])[..n], lo, hi);
            Separation {
                w: from.w + half * r.integral_to(w_rhs, s),
                t: t_at(Some(s)),
                q: from.q + half * r.integral_to(dq, s),
                z: z_at(s),
            }
        });
        Ok(Part {
            q: q_end,
            w: w_end,
            t: t_at(None),
            separated,
            residual: from.residual + change,
        })
    }
}

#[cfg(test)]
mod tests;

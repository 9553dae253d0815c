//! Where in the last step a pair's contact begins, ends or meets a kink of its law: each
//! located on the step's dense output down to adjacent floating-point numbers
//! ([`bwc_events::find_crossing`]).

use super::system::{ChainSystem, NONE};
use crate::input::Input;
use crate::separated;
use bwc_events::{class, find_crossing};
use bwc_ode::FlatIntegrator;

/// What happens to a pair at an event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    /// Its gap closes through its onset gap: a contact begins.
    Onset,
    /// `F <= 0 <= u`: its contact ends.
    Separation,
    /// A non-smooth point of its law: the integration stops and restarts there.
    Kink,
}

/// The first event of the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Event {
    pub(super) t: f64,
    pub(super) pair: usize,
    pub(super) kind: Kind,
}

type Chain<'a, I> = FlatIntegrator<ChainSystem<'a, I>>;

/// Body `i`'s displacement (m) and velocity (m/s) at `t` inside the last step: on the dense
/// output where it is integrated, in closed form where it flies free.
fn body_at<I: Input>(it: &mut Chain<'_, I>, i: usize, t: f64) -> (f64, f64) {
    let sys = it.system();
    match sys.local(i) {
        NONE => sys.motion[i].at(t),
        k => {
            let e = sys.integrated.len();
            (it.dense_component(k, t), it.dense_component(e + k, t))
        }
    }
}

/// Pair `j`'s gap less its onset gap, at `t` inside the last step.
fn gap_at<I: Input>(it: &mut Chain<'_, I>, j: usize, onset: f64, t: f64) -> f64 {
    let p = it.system().pairs[j];
    let r = p.right.map_or(0.0, |r| body_at(it, r, t).0);
    let l = p.left.map_or(0.0, |l| body_at(it, l, t).0);
    p.gap0 + r - l - onset
}

/// Pair `j`'s relative velocity (m/s) at `t` inside the last step.
fn velocity_at<I: Input>(it: &mut Chain<'_, I>, j: usize, t: f64) -> f64 {
    let p = it.system().pairs[j];
    p.right.map_or(0.0, |r| body_at(it, r, t).1) - p.left.map_or(0.0, |l| body_at(it, l, t).1)
}

/// Active pair `j`'s force (N) and relative velocity (m/s) at `t` inside the last step.
fn contact_at<I: Input>(it: &mut Chain<'_, I>, j: usize, t: f64) -> (f64, f64) {
    let o = it.system().slot(j);
    let s = [0, 1, 2].map(|c| it.dense_component(o + c, t));
    let u = velocity_at(it, j, t);
    (it.system().pairs[j].law.force(&s, u), u)
}

/// Active pair `j`'s force (N) at `t` inside the last step, on the dense output.
fn force_at<I: Input>(it: &mut Chain<'_, I>, j: usize, t: f64) -> f64 {
    contact_at(it, j, t).0
}

/// The largest force of active pair `j` inside the last step and when (golden-section search
/// on the dense output, to a 1e-12 part of the step or the doubles' spacing): for a step that
/// brackets a maximum.
pub(super) fn peak_in_step<I: Input>(it: &mut Chain<'_, I>, j: usize) -> (f64, f64) {
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    let (mut a, mut b) = (it.t_prev(), it.t());
    // 58 golden sections shrink the step by 1e-12 (0.618^58), or to the spacing of the
    // doubles near `t`, whichever comes first.
    let resolution = 4.0 * f64::EPSILON * b.abs().max(a.abs());
    let mut c = b - INV_PHI * (b - a);
    let mut d = a + INV_PHI * (b - a);
    let (mut fc, mut fd) = (force_at(it, j, c), force_at(it, j, d));
    for _ in 0..58 {
        if b - a <= resolution {
            break;
        }
        if fc >= fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - INV_PHI * (b - a);
            fc = force_at(it, j, c);
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + INV_PHI * (b - a);
            fd = force_at(it, j, d);
        }
    }
    if fc >= fd {
        (fc, c)
    } else {
        (fd, d)
    }
}

/// Active pair `j`'s kink functions at `t` inside the last step.
fn kinks_at<I: Input>(it: &mut Chain<'_, I>, j: usize, t: f64) -> [f64; 2] {
    let u = velocity_at(it, j, t);
    let o = it.system().slot(j);
    let s = [0, 1, 2].map(|c| it.dense_component(o + c, t));
    it.system().pairs[j].law.kinks(&s, u)
}

/// The first event of the last accepted step `[t0, t1]` over the watched pairs (those with
/// an integrated body), `onsets` the pairs' onset gaps; `None` if there is none. An event at
/// `t0` itself (a gap that leaves zero downwards at the step's start) has `t == t0`.
pub(super) fn first<I: Input>(it: &mut Chain<'_, I>, onsets: &[f64]) -> Option<Event> {
    let mut best: Option<Event> = None;
    for w in 0..it.system().watched.len() {
        let j = it.system().watched[w];
        let horizon = best.map_or(it.t(), |e| e.t);
        let found = if it.system().is_active(j) {
            contact_event(it, j, horizon)
        } else {
            onset_event(it, j, onsets[j], horizon)
        };
        if let Some(e) = found.filter(|e| best.is_none_or(|b| e.t < b.t)) {
            best = Some(e);
        }
    }
    best
}

/// Where pair `j`'s gap closes through `onset` in the last step, before `horizon`: a sign
/// change of the gap over the step, or a dip below it inside the step that the cubic Hermite
/// model of the gap (from its values and rates at both ends) predicts and the dense output
/// confirms.
fn onset_event<I: Input>(
    it: &mut Chain<'_, I>,
    j: usize,
    onset: f64,
    horizon: f64,
) -> Option<Event> {
    let (t0, t1) = (it.t_prev(), it.t());
    let sys = it.system();
    let (g0, g1) = (
        sys.gap(j, t0, it.y_prev()) - onset,
        sys.gap(j, t1, it.y()) - onset,
    );
    let event = |t| {
        Some(Event {
            t,
            pair: j,
            kind: Kind::Onset,
        })
    };
    if t1 <= t0 {
        return None;
    }
    let (r0, r1) = (
        sys.relative_velocity(j, t0, it.y_prev()),
        sys.relative_velocity(j, t1, it.y()),
    );
    if g0 < 0.0 {
        // Below the onset gap and not in contact (it opened there): a contact begins where
        // the pair turns to closing.
        return match (r0 < 0.0 || r0 == 0.0 && r1 < 0.0, r1 < 0.0) {
            (true, _) => event(t0),
            (false, true) => {
                let b = find_crossing(|t| velocity_at(it, j, t), t0, t1, r0, r1);
                (b.hi <= horizon).then(|| event(b.hi)).flatten()
            }
            (false, false) => None,
        };
    }
    if g1 < 0.0 {
        if g0 == 0.0 {
            return event(t0);
        }
        let b = find_crossing(|t| gap_at(it, j, onset, t), t0, t1, g0, g1);
        return (b.hi <= horizon).then(|| event(b.hi)).flatten();
    }
    let dip = hermite_minimum(t1 - t0, g0, g1, r0, r1)?;
    let tm = t0 + dip;
    if tm >= horizon {
        return None;
    }
    let gm = gap_at(it, j, onset, tm);
    if gm >= 0.0 {
        return None;
    }
    let b = find_crossing(|t| gap_at(it, j, onset, t), t0, tm, g0, gm);
    event(b.hi)
}

/// Where the cubic through `(0, g0)`, `(h, g1)` with slopes `r0`, `r1` has an interior minimum
/// below zero (its offset from 0), if it has one.
fn hermite_minimum(h: f64, g0: f64, g1: f64, r0: f64, r1: f64) -> Option<f64> {
    if r0 >= 0.0 || r1 <= 0.0 {
        // A minimum inside needs the gap falling at the start and rising at the end.
        return None;
    }
    // g(s) = g0 + r0 s + c2 s² + c3 s³ on [0, h].
    let slope = (g1 - g0) / h;
    let c2 = (3.0 * slope - 2.0 * r0 - r1) / h;
    let c3 = (r0 + r1 - 2.0 * slope) / (h * h);
    // The minimum is the zero of g'(s) = r0 + 2 c2 s + 3 c3 s² where g''(s) = 2 c2 + 6 c3 s > 0.
    let (a, b) = (3.0 * c3, 2.0 * c2);
    let roots = if a == 0.0 {
        [-r0 / b, f64::NAN]
    } else {
        let disc = b * b - 4.0 * a * r0;
        if disc < 0.0 {
            return None;
        }
        let q = -0.5 * (b + disc.sqrt().copysign(b));
        [q / a, r0 / q]
    };
    let s = roots
        .into_iter()
        .find(|s| *s > 0.0 && *s < h && b + 2.0 * a * s > 0.0)?;
    let g = g0 + s * (r0 + s * (c2 + s * c3));
    (s > 0.0 && s < h && g < 0.0).then_some(s)
}

/// The first separation or kink of active pair `j` in the last step, before `horizon`.
fn contact_event<I: Input>(it: &mut Chain<'_, I>, j: usize, horizon: f64) -> Option<Event> {
    let (t0, t1) = (it.t_prev(), it.t());
    if t1 <= t0 {
        return None;
    }
    let sys = it.system();
    let o = sys.slot(j);
    let law = sys.pairs[j].law;
    let (u0, u1) = (
        sys.relative_velocity(j, t0, it.y_prev()),
        sys.relative_velocity(j, t1, it.y()),
    );
    let (s0, s1) = (&it.y_prev()[o..o + 3], &it.y()[o..o + 3]);
    let (k0, k1) = (law.kinks(s0, u0), law.kinks(s1, u1));
    let f1 = law.force(s1, u1);
    let mut best = if separated(f1, u1) {
        Some(Event {
            t: separation_time(it, j),
            pair: j,
            kind: Kind::Separation,
        })
    } else {
        None
    };
    for c in 0..2 {
        let (a, b) = (k0[c], k1[c]);
        if class(a) == 0 || class(a) == class(b) {
            continue;
        }
        let limit = best.map_or(horizon, |e| e.t.min(horizon));
        let crossing = find_crossing(|t| kinks_at(it, j, t)[c], t0, t1, a, b);
        if crossing.hi < limit {
            best = Some(Event {
                t: crossing.hi,
                pair: j,
                kind: Kind::Kink,
            });
        }
    }
    best.filter(|e| e.t < horizon || e.t == t1 && horizon == t1)
}

/// `inf{t in (t0, t1] : F <= 0 <= u}` for active pair `j`, where the condition holds at `t1`:
/// the later of the first instants where `F <= 0` and where `u >= 0`, moved on until the
/// condition holds there (at most four times; otherwise `t1`).
fn separation_time<I: Input>(it: &mut Chain<'_, I>, j: usize) -> f64 {
    let (t0, t1) = (it.t_prev(), it.t());
    let (f1, u1) = contact_at(it, j, t1);
    let mut a = t0;
    for _ in 0..4 {
        let (fa, ua) = contact_at(it, j, a);
        let tf = if fa <= 0.0 {
            a
        } else {
            find_crossing(|t| contact_at(it, j, t).0, a, t1, fa, f1).hi
        };
        let tu = if ua >= 0.0 {
            a
        } else {
            find_crossing(|t| contact_at(it, j, t).1, a, t1, ua, u1).hi
        };
        let tau = tf.max(tu);
        let (f, u) = contact_at(it, j, tau);
        if separated(f, u) {
            return tau;
        }
        if tau <= a {
            break;
        }
        a = tau;
    }
    t1
}

#[cfg(test)]
mod tests {
    use super::hermite_minimum;

    #[test]
    fn the_hermite_model_finds_a_dip_and_only_a_dip() {
        // g = (s - 0.5)² - 0.01 on [0, 1]: g0 = g1 = 0.24, slopes -1 and 1, minimum at 0.5.
        let s = hermite_minimum(1.0, 0.24, 0.24, -1.0, 1.0).unwrap();
        assert!((s - 0.5).abs() < 1e-12, "{s}");
        // Shifted up: the minimum stays above zero.
        assert_eq!(hermite_minimum(1.0, 0.26, 0.26, -1.0, 1.0), None);
        // Falling throughout: no interior minimum.
        assert_eq!(hermite_minimum(1.0, 0.5, 0.1, -1.0, -0.1), None);
    }
}

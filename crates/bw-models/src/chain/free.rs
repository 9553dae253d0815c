//! Bodies in free flight. Under inputs constant in time a body in no contact moves on a
//! parabola, `d(t) = d_0 + v_0 τ + a τ² / 2` with `τ = t - t_0` and `a = u / m`, so it needs no
//! integration; and the next onset of a pair of two such bodies (or of one and a wall) is known
//! in closed form when the pair's bodies change state. Those onsets wait in an [`Onsets`] queue,
//! each stamped with its pair's version so that a later change of either body voids it.

use bwc_events::find_crossing;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A body's motion in free flight from `(t0, d0, v0)` with constant acceleration `a` (m/s²).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Motion {
    /// Start (s).
    pub(super) t0: f64,
    /// Displacement at `t0` (m).
    pub(super) d0: f64,
    /// Velocity at `t0` (m/s).
    pub(super) v0: f64,
    /// Acceleration (m/s²).
    pub(super) a: f64,
}

impl Motion {
    /// Displacement (m) and velocity (m/s) at `t`.
    #[inline]
    pub(super) fn at(&self, t: f64) -> (f64, f64) {
        let tau = t - self.t0;
        (
            self.d0 + tau * (self.v0 + 0.5 * self.a * tau),
            self.v0 + self.a * tau,
        )
    }
}

/// A predicted onset.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Entry {
    t: f64,
    pair: usize,
    version: u64,
}

impl Eq for Entry {}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.t
            .total_cmp(&other.t)
            .then(self.pair.cmp(&other.pair))
            .then(self.version.cmp(&other.version))
    }
}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

/// The predicted onsets of pairs in free flight, earliest first (ties by pair), with lazy
/// invalidation: [`Onsets::void`] raises a pair's version, and entries of an older version are
/// dropped when they reach the front.
#[derive(Debug, Clone, Default)]
pub(super) struct Onsets {
    heap: BinaryHeap<Reverse<Entry>>,
    version: Vec<u64>,
}

impl Onsets {
    /// An empty queue for `pairs` pairs.
    pub(super) fn new(pairs: usize) -> Self {
        Self {
            heap: BinaryHeap::with_capacity(pairs),
            version: vec![0; pairs],
        }
    }

    /// Voids pair `j`'s prediction.
    pub(super) fn void(&mut self, j: usize) {
        self.version[j] += 1;
    }

    /// Predicts pair `j`'s onset at `t` (replacing any earlier prediction). Voided entries are
    /// swept out once they outnumber the pairs, so the queue stays `O(pairs)` long.
    pub(super) fn push(&mut self, j: usize, t: f64) {
        self.void(j);
        if self.heap.len() > 2 * self.version.len() + 64 {
            let version = &self.version;
            self.heap.retain(|Reverse(e)| e.version == version[e.pair]);
        }
        self.heap.push(Reverse(Entry {
            t,
            pair: j,
            version: self.version[j],
        }));
    }

    /// The earliest valid prediction `(t, pair)`, if any.
    pub(super) fn first(&mut self) -> Option<(f64, usize)> {
        while let Some(Reverse(e)) = self.heap.peek() {
            if e.version == self.version[e.pair] {
                return Some((e.t, e.pair));
            }
            self.heap.pop();
        }
        None
    }

    /// Removes the earliest valid prediction.
    pub(super) fn pop(&mut self) {
        if let Some((_, j)) = self.first() {
            self.heap.pop();
            self.void(j);
        }
    }
}

/// A pair in free flight: the [`Motion`] of its gap less its onset gap, `h` (m), from `t0`
/// with relative velocity `v0` (m/s) and relative acceleration `a` (m/s²).
#[derive(Debug, Clone, Copy)]
pub(super) struct Flight(pub(super) Motion);

impl Flight {
    fn h(&self, t: f64) -> f64 {
        self.0.at(t).0
    }

    fn velocity(&self, t: f64) -> f64 {
        self.0.at(t).1
    }

    /// When the pair's contact begins, by the rules of a step's onset test: at once where the
    /// gap is at or below the onset gap and closing (or turning to closing from rest);
    /// below it and opening, where the relative velocity turns negative; above it, where
    /// `h` first falls below zero. Each instant is located on the closed form down to adjacent
    /// floating-point numbers ([`find_crossing`]'s `hi`). `None` if it never begins.
    pub(super) fn onset(&self) -> Option<f64> {
        let Motion {
            t0: t,
            d0: h0,
            v0: u,
            a,
        } = self.0;
        let closing_now = u < 0.0 || u == 0.0 && a < 0.0;
        if h0 <= 0.0 && closing_now {
            return Some(t);
        }
        if h0 < 0.0 {
            // Opening below the onset gap: it begins where it turns to closing.
            if a >= 0.0 {
                return None;
            }
            let turn = -u / a;
            let hi = t + 2.0 * turn.max(f64::MIN_POSITIVE);
            return Some(find_crossing(|s| self.velocity(s), t, hi, u, self.velocity(hi)).hi);
        }
        // Above the onset gap (or on it and opening): the first zero where h falls.
        let (lo, hi) = self.bracket()?;
        Some(find_crossing(|s| self.h(s), lo, hi, self.h(lo), self.h(hi)).hi)
    }

    /// A bracket `[lo, hi]` with `h(lo) > 0 > h(hi)` around the first fall of `h` through
    /// zero, where there is one.
    fn bracket(&self) -> Option<(f64, f64)> {
        let Motion {
            t0: t,
            d0: h0,
            v0: u,
            a,
        } = self.0;
        if a == 0.0 {
            return (u < 0.0 && h0 > 0.0).then(|| (t, t + 2.0 * h0 / -u));
        }
        let vertex = -u / a;
        let lo = if h0 == 0.0 {
            // Opening from the onset gap: from the top of the arc (a < 0 here, or never).
            if a > 0.0 || vertex <= 0.0 {
                return None;
            }
            t + vertex
        } else {
            t
        };
        let disc = u * u - 2.0 * a * h0;
        if disc < 0.0 {
            return None;
        }
        if a > 0.0 {
            // Opens upwards: the gap dips below the onset gap between two roots, if at all;
            // h is least at the vertex.
            let hi = t + vertex;
            return (vertex > 0.0 && self.h(hi) < 0.0).then_some((lo, hi));
        }
        // Opens downwards: past its positive root h falls for ever.
        let root = (-u - disc.sqrt()) / a;
        let mut hi = t + 2.0 * root.max(vertex).max(f64::MIN_POSITIVE);
        while self.h(hi) >= 0.0 {
            hi = t + 2.0 * (hi - t);
        }
        (self.h(lo) > 0.0).then_some((lo, hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn onsets_come_out_earliest_first_and_voided_ones_not_at_all() {
        let mut q = Onsets::new(3);
        q.push(0, 2.0);
        q.push(1, 1.0);
        q.push(2, 3.0);
        q.void(1);
        assert_eq!(q.first(), Some((2.0, 0)));
        q.pop();
        q.push(2, 0.5);
        assert_eq!(q.first(), Some((0.5, 2)));
        q.pop();
        assert_eq!(q.first(), None);
    }

    #[test]
    fn a_closing_pair_begins_at_the_root_of_its_parabola() {
        // h = 1 - 2 τ from t = 1: begins at 1.5.
        let f = Flight(Motion {
            t0: 1.0,
            d0: 1.0,
            v0: -2.0,
            a: 0.0,
        });
        assert!((f.onset().unwrap() - 1.5).abs() <= 1e-15);
        // Under gravity from rest 0.05 m above: h = 0.05 - 9.81 τ² / 2.
        let f = Flight(Motion {
            t0: 0.0,
            d0: 0.05,
            v0: 0.0,
            a: -9.81,
        });
        let expected = (2.0f64 * 0.05 / 9.81).sqrt();
        assert!((f.onset().unwrap() - expected).abs() <= 4.0 * f64::EPSILON * expected);
        // Thrown up from the onset gap: back at it after 2 u / g.
        let f = Flight(Motion {
            t0: 0.0,
            d0: 0.0,
            v0: 1.0,
            a: -9.81,
        });
        assert!((f.onset().unwrap() - 2.0 / 9.81).abs() <= 1e-15);
        // Closing but braked before it closes: never.
        let f = Flight(Motion {
            t0: 0.0,
            d0: 1.0,
            v0: -1.0,
            a: 1.0,
        });
        assert_eq!(f.onset(), None);
        // Closing and braked, but not enough: at the first root, 1 - sqrt(1 - 2 * 0.3).
        let f = Flight(Motion {
            t0: 0.0,
            d0: 0.3,
            v0: -1.0,
            a: 1.0,
        });
        let expected = 1.0 - (1.0f64 - 0.6).sqrt();
        assert!((f.onset().unwrap() - expected).abs() <= 1e-15);
        // Touching and closing: at once; opening with nothing to turn it: never.
        let f = Flight(Motion {
            t0: 3.0,
            d0: 0.0,
            v0: -1.0,
            a: 0.0,
        });
        assert_eq!(f.onset(), Some(3.0));
        let f = Flight(Motion { v0: 1.0, ..f.0 });
        assert_eq!(f.onset(), None);
        // Below the onset gap and opening, pulled back: where it turns.
        let f = Flight(Motion {
            t0: 0.0,
            d0: -1e-6,
            v0: 0.5,
            a: -2.0,
        });
        assert!((f.onset().unwrap() - 0.25).abs() <= 1e-15);
    }
}

//! The chain's equations of motion on one flat state, and what each pair's events look at.
//!
//! Layout of the state (`N` bodies, `P` pairs): the displacements `d_i = x_i - x_i(0)` (m) at
//! `0..N`, the velocities (m/s) at `N..2N`, then per pair `j` a slot of four at
//! `2N + 4j`: the law's displacements (m; the first two of the BWSHCCL's) and the energy it
//! has dissipated (J); last, the work of the inputs (J).

use super::PairLaw;
use crate::input::Input;
use crate::laws::ContactLaw;
use crate::State;
use bwc_ode::FlatSystem;

/// Slot length of a pair's law in the state.
pub(super) const SLOT: usize = 4;
/// Where the dissipated energy sits in a slot.
pub(super) const DISSIPATED: usize = 3;

impl PairLaw {
    /// The law's state rate, force (N) and dissipation rate (W) at `s` with input `u`.
    #[inline]
    pub(super) fn eval(&self, s: &[f64], u: f64) -> ([f64; 3], f64, f64) {
        match self {
            PairLaw::Shccm(law) => {
                let st = State::<2>::new(s[0], s[1]);
                let (rate, f) = law.eval(&st, u);
                let d = ContactLaw::dissipation(law, &st, u, &rate, f);
                ([rate[0], rate[1], 0.0], f, d)
            }
            PairLaw::Mcm(law) => {
                let st = State::<3>::new(s[0], s[1], s[2]);
                let (rate, f) = law.eval(&st, u);
                let d = ContactLaw::dissipation(law, &st, u, &rate, f);
                ([rate[0], rate[1], rate[2]], f, d)
            }
        }
    }

    /// The force (N) at `s` with input `u`.
    #[inline]
    pub(super) fn force(&self, s: &[f64], u: f64) -> f64 {
        self.eval(s, u).1
    }

    /// The energy stored at `s` (J).
    pub(super) fn stored(&self, s: &[f64]) -> f64 {
        match self {
            PairLaw::Shccm(law) => ContactLaw::stored(law, &State::<2>::new(s[0], s[1])),
            PairLaw::Mcm(law) => ContactLaw::stored(law, &State::<3>::new(s[0], s[1], s[2])),
        }
    }

    /// The law's non-smooth points at `s` with input `u` ([`ContactLaw::kinks`]).
    pub(super) fn kinks(&self, s: &[f64], u: f64) -> [f64; 2] {
        match self {
            PairLaw::Shccm(law) => ContactLaw::kinks(law, &State::<2>::new(s[0], s[1]), u),
            PairLaw::Mcm(law) => ContactLaw::kinks(law, &State::<3>::new(s[0], s[1], s[2]), u),
        }
    }
}

/// One pair as the equations see it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pair {
    /// The bodies (left, right); `None` for a wall.
    pub(super) left: Option<usize>,
    pub(super) right: Option<usize>,
    pub(super) law: PairLaw,
    /// The gap at `t = 0` (m).
    pub(super) gap0: f64,
}

/// The chain's right-hand side: bodies, pairs, and which pairs are in contact.
#[derive(Debug, Clone)]
pub(super) struct ChainSystem<'a, I> {
    pub(super) inverse_mass: Vec<f64>,
    pub(super) inputs: Vec<&'a I>,
    /// Whether any input is not identically zero.
    pub(super) forced: bool,
    pub(super) pairs: Vec<Pair>,
    /// The pairs in contact, in increasing order.
    pub(super) active: Vec<usize>,
}

impl<I: Input> ChainSystem<'_, I> {
    /// Number of bodies.
    pub(super) fn bodies(&self) -> usize {
        self.inverse_mass.len()
    }

    /// Offset of pair `j`'s slot.
    pub(super) fn slot(&self, j: usize) -> usize {
        2 * self.bodies() + SLOT * j
    }

    /// Index of the work of the inputs.
    pub(super) fn work(&self) -> usize {
        2 * self.bodies() + SLOT * self.pairs.len()
    }

    /// Pair `j`'s relative velocity `u_j = v_right - v_left` (m/s) in `y`.
    #[inline]
    pub(super) fn relative_velocity(&self, j: usize, y: &[f64]) -> f64 {
        let n = self.bodies();
        let p = &self.pairs[j];
        p.right.map_or(0.0, |r| y[n + r]) - p.left.map_or(0.0, |l| y[n + l])
    }

    /// Pair `j`'s gap (m) in `y`.
    #[inline]
    pub(super) fn gap(&self, j: usize, y: &[f64]) -> f64 {
        let p = &self.pairs[j];
        p.gap0 + p.right.map_or(0.0, |r| y[r]) - p.left.map_or(0.0, |l| y[l])
    }

    /// Pair `j`'s law state in `y`.
    #[inline]
    pub(super) fn law_state<'y>(&self, j: usize, y: &'y [f64]) -> &'y [f64] {
        let o = self.slot(j);
        &y[o..o + 3]
    }

    /// Pair `j`'s force (N) in `y` (0 when not in contact).
    pub(super) fn force(&self, j: usize, y: &[f64]) -> f64 {
        if self.active.binary_search(&j).is_ok() {
            let u = self.relative_velocity(j, y);
            self.pairs[j].law.force(self.law_state(j, y), u)
        } else {
            0.0
        }
    }

    /// The relative acceleration of pair `j` (m/s²) without its own force, from the derivative
    /// `dy` of the state.
    pub(super) fn relative_acceleration(&self, j: usize, dy: &[f64]) -> f64 {
        self.relative_velocity(j, dy)
    }
}

impl<I: Input> FlatSystem for ChainSystem<'_, I> {
    fn len(&self) -> usize {
        self.work() + 1
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.bodies();
        let (positions, rest) = dy.split_at_mut(n);
        let (accelerations, laws) = rest.split_at_mut(n);
        positions.copy_from_slice(&y[n..2 * n]);
        let mut power = 0.0;
        if self.forced {
            for (i, a) in accelerations.iter_mut().enumerate() {
                let u = self.inputs[i].at(t);
                *a = u * self.inverse_mass[i];
                power += u * y[n + i];
            }
        } else {
            accelerations.fill(0.0);
        }
        laws.fill(0.0);
        laws[SLOT * self.pairs.len()] = power;
        for &j in &self.active {
            let p = &self.pairs[j];
            let u = self.relative_velocity(j, y);
            let o = SLOT * j;
            let (rate, force, dissipation) = p.law.eval(&y[2 * n + o..2 * n + o + 3], u);
            laws[o..o + 3].copy_from_slice(&rate);
            laws[o + DISSIPATED] = dissipation;
            if let Some(l) = p.left {
                accelerations[l] -= force * self.inverse_mass[l];
            }
            if let Some(r) = p.right {
                accelerations[r] += force * self.inverse_mass[r];
            }
        }
    }
}

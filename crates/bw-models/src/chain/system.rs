//! The chain's equations of motion on the part of it that is integrated, and what each pair's
//! events look at.
//!
//! Under inputs constant in time only the bodies in contact are integrated: a body in no
//! contact flies on a parabola in closed form ([`Motion`]), so a step costs `O(1)` per body in
//! contact and per active contact, whatever the chain's length. Under inputs that vary in time
//! (or when asked, [`super::Scheme::Whole`]) every body is integrated.
//!
//! Layout of the integrated state (`E` integrated bodies, `A` active pairs): the displacements
//! `d_i = x_i - x_i(0)` (m) at `0..E`, the velocities (m/s) at `E..2E`, then per active pair a
//! slot of four at `2E + 4k`: the law's displacements (m; the first two of the BWSHCCL's) and
//! the energy it has dissipated (J); last, the work of the integrated bodies' inputs (J). A
//! pair out of contact keeps its law's state and dissipated energy aside ([`ChainSystem::parked`]).

use super::free::Motion;
use super::PairLaw;
use crate::input::Input;
use bwc_ode::FlatSystem;

/// Slot length of a pair's law in the state.
pub(super) const SLOT: usize = 4;
/// Where the dissipated energy sits in a slot.
pub(super) const DISSIPATED: usize = 3;
/// The place of a body that is not integrated, or of a pair not in contact.
pub(super) const NONE: usize = usize::MAX;

impl PairLaw {
    /// The force (N) at `s` with input `u`.
    #[inline]
    pub(super) fn force(&self, s: &[f64], u: f64) -> f64 {
        self.eval(s, u).1
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

/// Absolute tolerances of the integrated state: lengths (m, and m/s for velocities) and
/// energies (J).
#[derive(Debug, Clone, Copy)]
pub(super) struct Tolerances {
    pub(super) length: f64,
    pub(super) energy: f64,
}

/// The chain's right-hand side: bodies, pairs, which pairs are in contact and which bodies are
/// integrated.
#[derive(Debug, Clone)]
pub(super) struct ChainSystem<'a, I> {
    pub(super) inverse_mass: Vec<f64>,
    pub(super) inputs: Vec<&'a I>,
    /// Whether any input is not identically zero.
    pub(super) forced: bool,
    /// Whether every body is integrated; otherwise only those in contact.
    pub(super) whole: bool,
    pub(super) pairs: Vec<Pair>,
    /// Each body's pairs (left, right).
    pub(super) body_pairs: Vec<[Option<usize>; 2]>,
    /// The integrated bodies, in increasing order.
    pub(super) integrated: Vec<usize>,
    /// Each body's place among the integrated ([`NONE`] if it flies free).
    local: Vec<usize>,
    /// The pairs in contact, in increasing order.
    pub(super) active: Vec<usize>,
    /// Each pair's place among the active ([`NONE`] out of contact).
    place: Vec<usize>,
    /// The pairs whose events are sought step by step: those with an integrated body.
    pub(super) watched: Vec<usize>,
    /// The motion of each body in free flight (where it is not integrated).
    pub(super) motion: Vec<Motion>,
    /// The law state and dissipated energy of each pair out of contact.
    pub(super) parked: Vec<[f64; SLOT]>,
    /// Bodies integrated or freed by the last [`ChainSystem::relayout`].
    pub(super) changed: Vec<usize>,
    tolerances: Tolerances,
    scratch: Vec<usize>,
}

impl<'a, I: Input> ChainSystem<'a, I> {
    /// The system of `pairs` between bodies of `masses`, `velocities` and `inputs`, at
    /// `t = 0` with no contact (every body integrated if `whole`, else none), with its
    /// integrated state and absolute tolerances.
    pub(super) fn new(
        bodies: (&[f64], &[f64], Vec<&'a I>),
        pairs: Vec<Pair>,
        whole: bool,
        tolerances: Tolerances,
    ) -> (Self, Vec<f64>, Vec<f64>) {
        let (masses, velocities, inputs) = bodies;
        let n = masses.len();
        let mut body_pairs = vec![[None, None]; n];
        for (j, p) in pairs.iter().enumerate() {
            if let Some(l) = p.left {
                body_pairs[l][1] = Some(j);
            }
            if let Some(r) = p.right {
                body_pairs[r][0] = Some(j);
            }
        }
        let inverse_mass: Vec<f64> = masses.iter().map(|m| 1.0 / m).collect();
        let motion = (0..n)
            .map(|i| Motion {
                t0: 0.0,
                d0: 0.0,
                v0: velocities[i],
                a: inputs[i].at(0.0) * inverse_mass[i],
            })
            .collect();
        let p = pairs.len();
        let mut sys = Self {
            forced: inputs.iter().any(|u| !u.is_zero()),
            inverse_mass,
            inputs,
            whole,
            pairs,
            body_pairs,
            integrated: Vec::new(),
            local: vec![NONE; n],
            active: Vec::new(),
            place: vec![NONE; p],
            watched: Vec::new(),
            motion,
            parked: vec![[0.0; SLOT]; p],
            changed: Vec::new(),
            tolerances,
            scratch: Vec::new(),
        };
        let (mut y, mut atol) = (Vec::new(), Vec::new());
        sys.relayout(0.0, &[0.0], &[], (&mut y, &mut atol));
        (sys, y, atol)
    }

    /// Number of bodies.
    pub(super) fn bodies(&self) -> usize {
        self.inverse_mass.len()
    }

    /// Body `i`'s place in the integrated state ([`NONE`] if it flies free).
    #[inline]
    pub(super) fn local(&self, i: usize) -> usize {
        self.local[i]
    }

    /// Whether pair `j` is in contact.
    #[inline]
    pub(super) fn is_active(&self, j: usize) -> bool {
        self.place[j] != NONE
    }

    /// Offset of active pair `j`'s slot.
    #[inline]
    pub(super) fn slot(&self, j: usize) -> usize {
        2 * self.integrated.len() + SLOT * self.place[j]
    }

    /// Index of the work of the integrated bodies' inputs.
    pub(super) fn work(&self) -> usize {
        2 * self.integrated.len() + SLOT * self.active.len()
    }

    /// Body `i`'s displacement (m) and velocity (m/s) at `t`, `y` the integrated state at `t`.
    #[inline]
    pub(super) fn body(&self, i: usize, t: f64, y: &[f64]) -> (f64, f64) {
        match self.local[i] {
            NONE => self.motion[i].at(t),
            k => (y[k], y[self.integrated.len() + k]),
        }
    }

    /// Pair `j`'s relative velocity `u_j = v_right - v_left` (m/s) at `t`.
    #[inline]
    pub(super) fn relative_velocity(&self, j: usize, t: f64, y: &[f64]) -> f64 {
        let p = &self.pairs[j];
        p.right.map_or(0.0, |r| self.body(r, t, y).1) - p.left.map_or(0.0, |l| self.body(l, t, y).1)
    }

    /// Pair `j`'s gap (m) at `t`.
    #[inline]
    pub(super) fn gap(&self, j: usize, t: f64, y: &[f64]) -> f64 {
        let p = &self.pairs[j];
        p.gap0 + p.right.map_or(0.0, |r| self.body(r, t, y).0)
            - p.left.map_or(0.0, |l| self.body(l, t, y).0)
    }

    /// Pair `j`'s law state and dissipated energy in `y` (active) or aside.
    #[inline]
    pub(super) fn law_slot<'y>(&'y self, j: usize, y: &'y [f64]) -> &'y [f64] {
        if self.is_active(j) {
            let o = self.slot(j);
            &y[o..o + SLOT]
        } else {
            &self.parked[j]
        }
    }

    /// Pair `j`'s force (N) at `t` (0 when not in contact).
    pub(super) fn force(&self, j: usize, t: f64, y: &[f64]) -> f64 {
        if self.is_active(j) {
            let u = self.relative_velocity(j, t, y);
            self.pairs[j].law.force(self.law_slot(j, y), u)
        } else {
            0.0
        }
    }

    /// Whether active pair `j`'s force is falling at `t`: the sign of its rate along the
    /// derivative `dy`, by a central difference over `e` (s) on the law's state and the
    /// relative velocity (two law evaluations, no dense output).
    pub(super) fn force_falling(
        &self,
        j: usize,
        t: f64,
        (y, dy): (&[f64], &[f64]),
        e: f64,
    ) -> bool {
        let o = self.slot(j);
        let (u, du) = (
            self.relative_velocity(j, t, y),
            self.relative_acceleration(j, dy),
        );
        let at = |sign: f64| {
            let s = [0, 1, 2].map(|c| y[o + c] + sign * e * dy[o + c]);
            self.pairs[j].law.force(&s, u + sign * e * du)
        };
        at(1.0) < at(-1.0)
    }

    /// The relative acceleration of pair `j` (m/s²) from the derivative `dy` of the
    /// integrated state.
    pub(super) fn relative_acceleration(&self, j: usize, dy: &[f64]) -> f64 {
        let e = self.integrated.len();
        let a = |i: usize| match self.local[i] {
            NONE => self.motion[i].a,
            k => dy[e + k],
        };
        let p = &self.pairs[j];
        p.right.map_or(0.0, a) - p.left.map_or(0.0, a)
    }

    /// Changes the active pairs to `next` (increasing) at `t`, the integrated state there
    /// being `y`: writes the new integrated state and its absolute tolerances into `out`, and
    /// the bodies that were integrated or freed into [`ChainSystem::changed`]. Pairs leaving
    /// contact keep their slots aside; freed bodies fly on from their state at `t`.
    pub(super) fn relayout(
        &mut self,
        t: f64,
        y: &[f64],
        next: &[usize],
        out: (&mut Vec<f64>, &mut Vec<f64>),
    ) {
        let (state, atol) = out;
        for &j in &self.active {
            if next.binary_search(&j).is_err() {
                let o = self.slot(j);
                self.parked[j].copy_from_slice(&y[o..o + SLOT]);
            }
        }
        // The new integrated bodies.
        let mut bodies = std::mem::take(&mut self.scratch);
        bodies.clear();
        if self.whole {
            bodies.extend(0..self.bodies());
        } else {
            for &j in next {
                bodies.extend(self.pairs[j].left);
                bodies.extend(self.pairs[j].right);
            }
            bodies.dedup();
        }
        let e_old = self.integrated.len();
        self.changed.clear();
        for &i in &self.integrated {
            if bodies.binary_search(&i).is_err() {
                let k = self.local[i];
                self.motion[i] = Motion {
                    t0: t,
                    d0: y[k],
                    v0: y[e_old + k],
                    a: self.inputs[i].at(t) * self.inverse_mass[i],
                };
                self.changed.push(i);
            }
        }
        let Tolerances { length, energy } = self.tolerances;
        state.clear();
        atol.clear();
        for part in [0, 1] {
            for &i in &bodies {
                let (d, v) = self.body(i, t, y);
                state.push(if part == 0 { d } else { v });
                atol.push(length);
            }
        }
        for &j in next {
            state.extend_from_slice(self.law_slot(j, y));
            atol.extend_from_slice(&[length, length, length, energy]);
        }
        state.push(y[self.work()]);
        atol.push(energy);
        self.adopt(bodies, next);
    }

    /// Makes `bodies` the integrated bodies and `next` the active pairs: their places, the
    /// bodies newly integrated (added to [`ChainSystem::changed`]) and the watched pairs.
    fn adopt(&mut self, bodies: Vec<usize>, next: &[usize]) {
        for &i in &self.integrated {
            self.local[i] = NONE;
        }
        for (k, &i) in bodies.iter().enumerate() {
            if self.integrated.binary_search(&i).is_err() {
                self.changed.push(i);
            }
            self.local[i] = k;
        }
        for &j in &self.active {
            self.place[j] = NONE;
        }
        for (k, &j) in next.iter().enumerate() {
            self.place[j] = k;
        }
        self.active.clear();
        self.active.extend_from_slice(next);
        self.scratch = std::mem::replace(&mut self.integrated, bodies);
        self.watched.clear();
        for &i in &self.integrated {
            self.watched.extend(self.body_pairs[i].iter().flatten());
        }
        self.watched.dedup();
    }
}

impl<I: Input> FlatSystem for ChainSystem<'_, I> {
    fn len(&self) -> usize {
        self.work() + 1
    }

    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let e = self.integrated.len();
        let (positions, rest) = dy.split_at_mut(e);
        let (accelerations, laws) = rest.split_at_mut(e);
        positions.copy_from_slice(&y[e..2 * e]);
        let mut power = 0.0;
        if self.forced {
            for (k, a) in accelerations.iter_mut().enumerate() {
                let i = self.integrated[k];
                let u = self.inputs[i].at(t);
                *a = u * self.inverse_mass[i];
                power += u * y[e + k];
            }
        } else {
            accelerations.fill(0.0);
        }
        laws[SLOT * self.active.len()] = power;
        for (k, &j) in self.active.iter().enumerate() {
            let p = &self.pairs[j];
            let left = p.left.map(|l| self.local[l]);
            let right = p.right.map(|r| self.local[r]);
            let u = right.map_or(0.0, |r| y[e + r]) - left.map_or(0.0, |l| y[e + l]);
            let o = SLOT * k;
            let (rate, force, dissipation) = p.law.eval(&y[2 * e + o..2 * e + o + 3], u);
            laws[o..o + 3].copy_from_slice(&rate);
            laws[o + DISSIPATED] = dissipation;
            if let Some(l) = left {
                accelerations[l] -= force * self.inverse_mass[self.integrated[l]];
            }
            if let Some(r) = right {
                accelerations[r] += force * self.inverse_mass[self.integrated[r]];
            }
        }
    }
}

//! A chain's run: the integration from event to event, the contacts it records, the energy
//! ledger and the samples in time.

use super::events::{self, Event, Kind};
use super::system::{ChainSystem, Pair, DISSIPATED, SLOT};
use super::{Chain, Stop};
use crate::input::Input;
use crate::sequence::Policy;
use crate::ModelError;
use bwc_ode::{FlatIntegrator, FlatOptions, Stats, DOP853};

/// Events in a row at one instant before a run gives up on it: contacts that open and close
/// again without time passing.
const SAME_INSTANT: usize = 64;

/// A body at the end of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FinalBody {
    /// Position of the centre (m).
    pub position: f64,
    /// Velocity (m/s).
    pub velocity: f64,
}

/// One contact of a pair, from its onset to its separation.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ContactRecord {
    /// The pair (0 is the leftmost: the left wall's pair where there is one).
    pub pair: usize,
    /// Onset (s).
    pub onset: f64,
    /// The relative velocity at the onset (m/s, `<= 0`).
    pub onset_velocity: f64,
    /// Separation (s); `None` if the run ended during the contact.
    pub separation: Option<f64>,
    /// The relative velocity at the separation (m/s, `>= 0`).
    pub separation_velocity: Option<f64>,
    /// Energy dissipated by the contact (J), a reset law's stored energy at the separation
    /// included.
    pub dissipated: f64,
    /// The largest force of the contact (N) at the ends of the integration's steps, which
    /// include every stop at a kink of the law: exact at the maximal compression of a law
    /// without damping (`u = 0`), within a step elsewhere.
    pub peak_force: f64,
    /// When the contact's force was at `peak_force` (s).
    pub peak_at: f64,
}

impl ContactRecord {
    /// The rebound ratio `-u(t_s) / u(onset)`: the pair's own coefficient of restitution
    /// (`None` before the separation, or for a contact that began at rest).
    pub fn rebound(&self) -> Option<f64> {
        let after = self.separation_velocity?;
        (self.onset_velocity < 0.0).then(|| -after / self.onset_velocity)
    }
}

/// The energy ledger at one instant (J).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Ledger {
    /// `Σ m_i v_i² / 2`.
    pub kinetic: f64,
    /// Stored in the laws.
    pub stored: f64,
    /// Dissipated by the laws so far.
    pub dissipated: f64,
    /// Work of the inputs so far, `∫ Σ u_i v_i dt`.
    pub work: f64,
    /// Kinetic energy at `t = 0` (nothing is stored then).
    pub initial: f64,
}

impl Ledger {
    /// `kinetic + stored + dissipated - work - initial`: zero but for the integration error.
    pub fn imbalance(&self) -> f64 {
        self.kinetic + self.stored + self.dissipated - self.work - self.initial
    }
}

/// The chain at a sampling instant.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub struct Sample<'a> {
    /// Time (s).
    pub t: f64,
    /// Positions of the centres (m).
    pub positions: &'a [f64],
    /// Velocities (m/s).
    pub velocities: &'a [f64],
    /// Each pair's gap (m; negative while compressed).
    pub gaps: &'a [f64],
    /// Each pair's force (N; 0 out of contact).
    pub forces: &'a [f64],
    /// The energy ledger.
    pub ledger: Ledger,
}

/// The outcome of a chain's run.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ChainRun {
    /// When the run ended (s).
    pub t_end: f64,
    /// Whether it ended settled ([`Stop::settled`]) rather than at the horizon.
    pub settled: bool,
    /// The bodies at the end.
    pub bodies: Vec<FinalBody>,
    /// Every contact, in order of onset.
    pub contacts: Vec<ContactRecord>,
    /// The ledger at the end.
    pub ledger: Ledger,
    /// Integration statistics (events include onsets, separations and kinks).
    pub stats: Stats,
}

/// Where a run stands beyond the integrator: each pair's onset gap and open contact.
struct Book {
    onsets: Vec<f64>,
    open: Vec<Option<usize>>,
    contacts: Vec<ContactRecord>,
    /// Dissipated energy in a pair's slot at its contact's onset.
    dissipated_at_onset: Vec<f64>,
    initial: f64,
    masses: Vec<f64>,
    policy: Policy,
}

impl<I: Input> Chain<I> {
    /// Runs the chain until `stop`, calling `observer` at `t = 0, dt, 2 dt, ...` where `dt`
    /// (s) is given.
    ///
    /// # Errors
    /// [`ModelError::InvalidSetting`] for a horizon or `dt` that is not positive and finite;
    /// [`ModelError::Solver`] if the integration fails (with the time and state);
    /// [`ModelError::NotApplicable`] if contacts keep opening and closing at one instant.
    pub fn run(
        &self,
        stop: Stop,
        dt: Option<f64>,
        mut observer: impl FnMut(&Sample<'_>),
    ) -> Result<ChainRun, ModelError> {
        check_stop(stop, dt)?;
        let system = self.system();
        let y0 = vec![0.0; bwc_ode::FlatSystem::len(&system)];
        let mut y0 = y0;
        let n = self.bodies.len();
        for (i, b) in self.bodies.iter().enumerate() {
            y0[n + i] = b.velocity;
        }
        let initial: f64 = self
            .bodies
            .iter()
            .map(|b| 0.5 * b.mass * b.velocity * b.velocity)
            .sum();
        let options = self.options(&system, initial);
        let mut it = FlatIntegrator::new(system, &DOP853, 0.0, &y0, options)
            .map_err(|e| ModelError::Solver(e.into()))?;
        let mut book = Book {
            onsets: vec![0.0; self.pairs()],
            open: vec![None; self.pairs()],
            contacts: Vec::new(),
            dissipated_at_onset: vec![0.0; self.pairs()],
            initial,
            masses: self.bodies.iter().map(|b| b.mass).collect(),
            policy: self.settings.policy,
        };
        let mut sampler = dt.map(|dt| Sampler::new(dt, &it));
        take_up_touching(&mut it, &mut book)?;
        if let Some(s) = sampler.as_mut() {
            s.emit_current(self, &it, &book, &mut observer);
        }
        let mut same_instant = 0;
        let settled = loop {
            if stop.settled && is_settled(&it) {
                break true;
            }
            if it.t() >= stop.horizon {
                break false;
            }
            it.step(stop.horizon)
                .map_err(|e| ModelError::Solver(e.into()))?;
            let event = events::first(&mut it, &book.onsets);
            if let Some(e) = event.filter(|e| e.t < it.t()) {
                if e.t > it.t_prev() {
                    it.retake_to(e.t)
                        .map_err(|e| ModelError::Solver(e.into()))?;
                } else {
                    it.undo();
                }
            }
            if let Some(s) = sampler.as_mut() {
                s.emit_step(self, &mut it, &book, &mut observer);
            }
            record_peaks(&it, &mut book);
            if let Some(e) = event {
                same_instant = if it.t() == it.t_prev() {
                    same_instant + 1
                } else {
                    0
                };
                if same_instant > SAME_INSTANT {
                    return Err(ModelError::NotApplicable {
                        reason: "contacts keep opening and closing at one instant; \
                                 tighten rtol or give the touching bodies a small gap",
                    });
                }
                apply(&mut it, &mut book, e)?;
                take_up_touching(&mut it, &mut book)?;
            }
        };
        Ok(self.finish(&it, book, settled))
    }

    fn system(&self) -> ChainSystem<'_, I> {
        let pairs = (0..self.pairs())
            .map(|j| {
                let (left, right) = self.pair_bodies(j);
                Pair {
                    left,
                    right,
                    law: self.laws[j],
                    gap0: self.initial_gap(j),
                }
            })
            .collect();
        ChainSystem {
            inverse_mass: self.bodies.iter().map(|b| 1.0 / b.mass).collect(),
            inputs: self.bodies.iter().map(|b| &b.input).collect(),
            forced: self.bodies.iter().any(|b| !b.input.is_zero()),
            pairs,
            active: Vec::with_capacity(self.pairs()),
        }
    }

    /// Tolerances: `atol` (m) for positions and law displacements, `atol / (1 s)` for
    /// velocities, and for the energies the relative tolerance of the initial kinetic energy
    /// (1 J where that is zero), so that the ledger closes to the integration's tolerance.
    fn options(&self, system: &ChainSystem<'_, I>, initial: f64) -> FlatOptions {
        let len = bwc_ode::FlatSystem::len(system);
        let mut atol = vec![self.settings.atol; len];
        let energy = self.settings.rtol * if initial > 0.0 { initial } else { 1.0 };
        for j in 0..self.pairs() {
            atol[system.slot(j) + DISSIPATED] = energy;
        }
        atol[system.work()] = energy;
        FlatOptions::new(self.settings.rtol, atol)
    }

    fn finish(
        &self,
        it: &FlatIntegrator<ChainSystem<'_, I>>,
        book: Book,
        settled: bool,
    ) -> ChainRun {
        let n = self.bodies.len();
        let y = it.y();
        let bodies = self
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| FinalBody {
                position: b.position + y[i],
                velocity: y[n + i],
            })
            .collect();
        let mut contacts = book.contacts.clone();
        for (j, open) in book.open.iter().enumerate() {
            if let Some(k) = open {
                contacts[*k].dissipated =
                    y[it.system().slot(j) + DISSIPATED] - book.dissipated_at_onset[j];
            }
        }
        ChainRun {
            t_end: it.t(),
            settled,
            bodies,
            contacts,
            ledger: ledger(it.system(), y, &book),
            stats: it.stats(),
        }
    }
}

fn check_stop(stop: Stop, dt: Option<f64>) -> Result<(), ModelError> {
    if !(stop.horizon > 0.0 && stop.horizon.is_finite()) {
        return Err(ModelError::InvalidSetting {
            name: "horizon",
            value: stop.horizon,
            allowed: "> 0 and finite (s)",
        });
    }
    if let Some(dt) = dt.filter(|dt| !(*dt > 0.0 && dt.is_finite())) {
        return Err(ModelError::InvalidSetting {
            name: "dt",
            value: dt,
            allowed: "> 0 and finite (s)",
        });
    }
    Ok(())
}

/// The ledger of state `y`.
fn ledger<I: Input>(system: &ChainSystem<'_, I>, y: &[f64], book: &Book) -> Ledger {
    let n = system.bodies();
    let kinetic = (0..n)
        .map(|i| 0.5 * book.masses[i] * y[n + i] * y[n + i])
        .sum();
    let (mut stored, mut dissipated) = (0.0, 0.0);
    for (j, p) in system.pairs.iter().enumerate() {
        let o = system.slot(j);
        stored += p.law.stored(&y[o..o + 3]);
        dissipated += y[o + DISSIPATED];
    }
    Ledger {
        kinetic,
        stored,
        dissipated,
        work: y[system.work()],
        initial: book.initial,
    }
}

/// Whether no contact is active and no gap is closing: every relative velocity `>= 0`, and
/// under constant inputs every relative acceleration too.
fn is_settled<I: Input>(it: &FlatIntegrator<ChainSystem<'_, I>>) -> bool {
    let sys = it.system();
    if !sys.active.is_empty() {
        return false;
    }
    let constant = sys.inputs.iter().all(|i| i.is_constant());
    (0..sys.pairs.len()).all(|j| {
        sys.relative_velocity(j, it.y()) >= 0.0
            && constant
            && sys.relative_acceleration(j, it.derivative()) >= 0.0
    })
}

/// Raises the open contacts' peak forces to their forces at the current point.
fn record_peaks<I: Input>(it: &FlatIntegrator<ChainSystem<'_, I>>, book: &mut Book) {
    let sys = it.system();
    for &j in &sys.active {
        let Some(k) = book.open[j] else { continue };
        let f = sys.force(j, it.y());
        let c = &mut book.contacts[k];
        if f > c.peak_force {
            c.peak_force = f;
            c.peak_at = it.t();
        }
    }
}

/// Takes up the contacts of pairs whose gap is closed (at or below the onset gap) and closing
/// at the current point: a contact that begins exactly at a restart (bodies placed touching,
/// or pushed together by another contact's event).
fn take_up_touching<I: Input>(
    it: &mut FlatIntegrator<ChainSystem<'_, I>>,
    book: &mut Book,
) -> Result<(), ModelError> {
    let mut began = false;
    for j in 0..book.onsets.len() {
        let sys = it.system();
        let closing = book.open[j].is_none()
            && sys.gap(j, it.y()) <= book.onsets[j]
            && sys.relative_velocity(j, it.y()) < 0.0;
        if closing {
            // Beginning a contact changes no state, so the next pairs' tests stand.
            begin(it, book, j);
            began = true;
        }
    }
    if !began {
        return Ok(());
    }
    let t = it.t();
    it.restart(t).map_err(|e| ModelError::Solver(e.into()))
}

/// Begins pair `j`'s contact at the current point (the integrator restarts after).
fn begin<I: Input>(it: &mut FlatIntegrator<ChainSystem<'_, I>>, book: &mut Book, j: usize) {
    let t = it.t();
    let (sys, y) = it.system_and_state_mut();
    let u = sys.relative_velocity(j, y);
    if let Err(k) = sys.active.binary_search(&j) {
        sys.active.insert(k, j);
    }
    book.dissipated_at_onset[j] = y[sys.slot(j) + DISSIPATED];
    book.open[j] = Some(book.contacts.len());
    book.contacts.push(ContactRecord {
        pair: j,
        onset: t,
        onset_velocity: u.min(0.0),
        separation: None,
        separation_velocity: None,
        dissipated: 0.0,
        peak_force: 0.0,
        peak_at: t,
    });
}

/// Ends pair `j`'s contact at the current point: records it, moves its onset gap to where it
/// separated and, under [`Policy::Reset`], puts its law at rest (what it stored counted as
/// dissipated).
fn end<I: Input>(it: &mut FlatIntegrator<ChainSystem<'_, I>>, book: &mut Book, j: usize) {
    let t = it.t();
    let (sys, y) = it.system_and_state_mut();
    let u = sys.relative_velocity(j, y);
    if let Ok(k) = sys.active.binary_search(&j) {
        sys.active.remove(k);
    }
    let o = sys.slot(j);
    if book.policy == Policy::Reset {
        y[o + DISSIPATED] += sys.pairs[j].law.stored(&y[o..o + 3]);
        y[o..o + SLOT - 1].fill(0.0);
    }
    book.onsets[j] = sys.gap(j, y);
    if let Some(k) = book.open[j].take() {
        let c = &mut book.contacts[k];
        c.separation = Some(t);
        c.separation_velocity = Some(u.max(0.0));
        c.dissipated = y[o + DISSIPATED] - book.dissipated_at_onset[j];
    }
}

/// Applies `event` at the current point and restarts the integration there.
fn apply<I: Input>(
    it: &mut FlatIntegrator<ChainSystem<'_, I>>,
    book: &mut Book,
    event: Event,
) -> Result<(), ModelError> {
    it.record_event();
    match event.kind {
        Kind::Onset => begin(it, book, event.pair),
        Kind::Separation => end(it, book, event.pair),
        Kind::Kink => {}
    }
    let t = it.t();
    it.restart(t).map_err(|e| ModelError::Solver(e.into()))
}

/// Samples at `t = k dt` from the dense output of each step.
struct Sampler {
    dt: f64,
    next: u64,
    y: Vec<f64>,
    positions: Vec<f64>,
    velocities: Vec<f64>,
    gaps: Vec<f64>,
    forces: Vec<f64>,
}

impl Sampler {
    fn new<I: Input>(dt: f64, it: &FlatIntegrator<ChainSystem<'_, I>>) -> Self {
        let sys = it.system();
        let (n, p) = (sys.bodies(), sys.pairs.len());
        Self {
            dt,
            next: 0,
            y: it.y().to_vec(),
            positions: vec![0.0; n],
            velocities: vec![0.0; n],
            gaps: vec![0.0; p],
            forces: vec![0.0; p],
        }
    }

    /// The sample at the current point if it is due (`t = 0`).
    fn emit_current<I: Input>(
        &mut self,
        chain: &Chain<I>,
        it: &FlatIntegrator<ChainSystem<'_, I>>,
        book: &Book,
        observer: &mut impl FnMut(&Sample<'_>),
    ) {
        self.y.copy_from_slice(it.y());
        self.emit(chain, it.system(), it.t(), book, observer);
        self.next = 1;
    }

    /// The samples due inside the last step `(t_prev, t]`.
    fn emit_step<I: Input>(
        &mut self,
        chain: &Chain<I>,
        it: &mut FlatIntegrator<ChainSystem<'_, I>>,
        book: &Book,
        observer: &mut impl FnMut(&Sample<'_>),
    ) {
        loop {
            let t = self.next as f64 * self.dt;
            if t > it.t() || it.t() <= it.t_prev() {
                return;
            }
            if t == it.t() {
                self.y.copy_from_slice(it.y());
            } else {
                for c in 0..self.y.len() {
                    self.y[c] = it.dense_component(c, t);
                }
            }
            self.emit(chain, it.system(), t, book, observer);
            self.next += 1;
        }
    }

    fn emit<I: Input>(
        &mut self,
        chain: &Chain<I>,
        sys: &ChainSystem<'_, I>,
        t: f64,
        book: &Book,
        observer: &mut impl FnMut(&Sample<'_>),
    ) {
        let n = sys.bodies();
        for (i, b) in chain.bodies.iter().enumerate() {
            self.positions[i] = b.position + self.y[i];
            self.velocities[i] = self.y[n + i];
        }
        for j in 0..sys.pairs.len() {
            self.gaps[j] = sys.gap(j, &self.y);
            self.forces[j] = sys.force(j, &self.y);
        }
        observer(&Sample {
            t,
            positions: &self.positions,
            velocities: &self.velocities,
            gaps: &self.gaps,
            forces: &self.forces,
            ledger: ledger(sys, &self.y, book),
        });
    }
}

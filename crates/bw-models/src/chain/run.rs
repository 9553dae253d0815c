//! A chain's run: the integration from event to event, the contacts it records, the energy
//! ledger and the samples in time.

use super::events::{self, peak_in_step, Event, Kind};
use super::free::{Flight, Motion, Onsets};
use super::system::{ChainSystem, Pair, Tolerances, DISSIPATED, NONE, SLOT};
use super::{Chain, Scheme, Stop};
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
    /// The largest force of the contact (N): at the ends of the integration's steps, which
    /// include every stop at a kink of the law (the maximal compression of a law without
    /// damping, `u = 0`), and inside a step where the force rises into it and falls at its end
    /// (a damped law's maximum before the maximal compression), located on the dense output to
    /// a 1e-12 part of the step.
    pub peak_force: f64,
    /// When the contact's force was at `peak_force` (s).
    pub peak_at: f64,
    /// Whether the contact began without approach: a pair touching at rest from `t = 0` (its
    /// onset then reads 0 s and its onset velocity 0, whenever rounding in its neighbours'
    /// motion took it up), or an approach speed below [`REST_SPEED`] times the chain's speed
    /// scale (bodies that re-touch at rounding level).
    pub began_at_rest: bool,
}

/// The chain's speed scale: its largest initial speed, 1 m/s where every body starts at rest.
fn speed_scale(velocities: &[f64]) -> f64 {
    let largest = velocities.iter().fold(0.0, |a: f64, v| a.max(v.abs()));
    if largest > 0.0 {
        largest
    } else {
        1.0
    }
}

/// Approach speeds up to this fraction of the chain's speed scale (its largest initial speed,
/// 1 m/s where all bodies start at rest) are rest: the integration's rounding, not an impact.
pub const REST_SPEED: f64 = 1e-12;

impl ContactRecord {
    /// The rebound ratio `-u(t_s) / u(onset)`: the pair's own coefficient of restitution
    /// (`None` before the separation, or for a contact that [began at rest](Self::began_at_rest),
    /// which has none).
    pub fn rebound(&self) -> Option<f64> {
        let after = self.separation_velocity?;
        (self.onset_velocity < 0.0 && !self.began_at_rest).then(|| -after / self.onset_velocity)
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

/// Where a run stands beyond the integrator: each pair's onset gap and open contact, the
/// onsets predicted for pairs in free flight, and the switches of the active set at the
/// current point.
struct Book {
    onsets: Vec<f64>,
    open: Vec<Option<usize>>,
    contacts: Vec<ContactRecord>,
    /// Dissipated energy in a pair's slot at its contact's onset.
    dissipated_at_onset: Vec<f64>,
    initial: f64,
    masses: Vec<f64>,
    policy: Policy,
    queue: Onsets,
    /// Pairs touching at rest since `t = 0`, not separated since.
    at_rest: Vec<bool>,
    /// Whether an open contact's force was rising at the last step's end.
    rising: Vec<bool>,
    /// Approach speeds up to this are rest (m/s, [`REST_SPEED`] of the speed scale).
    rest_speed: f64,
    /// Pairs beginning and ending contact at the current point.
    began: Vec<usize>,
    ended: Vec<usize>,
    /// Scratch: the next active set, its integrated state and tolerances.
    next: Vec<usize>,
    y_next: Vec<f64>,
    atol_next: Vec<f64>,
}

/// What a stretch of free flight (nothing integrated) ended at.
enum Landing {
    /// A predicted onset.
    Event(Event),
    /// The instant the chain settled.
    Settled,
    /// The horizon.
    Horizon,
}

type It<'a, I> = FlatIntegrator<ChainSystem<'a, I>>;

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
        let solver = |e: bwc_ode::Error| ModelError::Solver(e.into());
        let (mut it, mut book) = self.start()?;
        let mut sampler = dt.map(|dt| Sampler::new(dt, &it));
        take_up_touching(&mut it, &mut book)?;
        if let Some(s) = sampler.as_mut() {
            s.emit(self, &mut it, &book, &mut observer);
        }
        let mut same_instant = 0;
        let settled = loop {
            if stop.settled && is_settled(&it, &mut book) {
                break true;
            }
            if it.t() >= stop.horizon {
                break false;
            }
            let event = if it.system().integrated.is_empty() {
                match fly(&mut it, &mut book, stop)? {
                    Landing::Event(e) => Some(e),
                    Landing::Settled => {
                        if let Some(s) = sampler.as_mut() {
                            s.emit(self, &mut it, &book, &mut observer);
                        }
                        break true;
                    }
                    Landing::Horizon => None,
                }
            } else {
                step(&mut it, &mut book, stop.horizon).map_err(solver)?
            };
            if let Some(s) = sampler.as_mut() {
                s.emit(self, &mut it, &book, &mut observer);
            }
            record_peaks(&mut it, &mut book);
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

    /// The integration and the book at `t = 0`, before any contact; in free flight, every
    /// pair's onset predicted.
    fn start(&self) -> Result<(It<'_, I>, Book), ModelError> {
        let initial: f64 = self
            .bodies
            .iter()
            .map(|b| 0.5 * b.mass * b.velocity * b.velocity)
            .sum();
        let whole = self.settings.scheme == Scheme::Whole
            || !self.bodies.iter().all(|b| b.input.is_constant());
        // Tolerances: `atol` (m) for positions and law displacements, `atol / (1 s)` for
        // velocities, and for the energies the relative tolerance of the initial kinetic
        // energy (1 J where that is zero), so that the ledger closes to the tolerance.
        let tolerances = Tolerances {
            length: self.settings.atol,
            energy: self.settings.rtol * if initial > 0.0 { initial } else { 1.0 },
        };
        let masses: Vec<f64> = self.bodies.iter().map(|b| b.mass).collect();
        let velocities: Vec<f64> = self.bodies.iter().map(|b| b.velocity).collect();
        let inputs = self.bodies.iter().map(|b| &b.input).collect();
        let (system, y0, atol) = ChainSystem::new(
            (&masses, &velocities, inputs),
            self.pairs_of(),
            whole,
            tolerances,
        );
        let options = FlatOptions::new(self.settings.rtol, atol);
        let it = FlatIntegrator::new(system, &DOP853, 0.0, &y0, options)
            .map_err(|e| ModelError::Solver(e.into()))?;
        let pairs = self.pairs();
        let mut book = Book {
            onsets: vec![0.0; pairs],
            open: vec![None; pairs],
            contacts: Vec::new(),
            dissipated_at_onset: vec![0.0; pairs],
            initial,
            masses,
            policy: self.settings.policy,
            queue: Onsets::new(pairs),
            at_rest: vec![false; pairs],
            rising: vec![true; pairs],
            rest_speed: REST_SPEED * speed_scale(&velocities),
            began: Vec::new(),
            ended: Vec::new(),
            next: Vec::new(),
            y_next: Vec::new(),
            atol_next: Vec::new(),
        };
        for j in 0..pairs {
            let sys = it.system();
            book.at_rest[j] =
                sys.gap(j, 0.0, it.y()) <= 0.0 && sys.relative_velocity(j, 0.0, it.y()) == 0.0;
        }
        if !whole {
            for j in 0..pairs {
                predict(&it, &mut book, j);
            }
        }
        Ok((it, book))
    }

    fn pairs_of(&self) -> Vec<Pair> {
        (0..self.pairs())
            .map(|j| {
                let (left, right) = self.pair_bodies(j);
                Pair {
                    left,
                    right,
                    law: self.laws[j],
                    gap0: self.initial_gap(j),
                }
            })
            .collect()
    }

    fn finish(&self, it: &It<'_, I>, book: Book, settled: bool) -> ChainRun {
        let (sys, t, y) = (it.system(), it.t(), it.y());
        let bodies = self
            .bodies
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let (d, v) = sys.body(i, t, y);
                FinalBody {
                    position: b.position + d,
                    velocity: v,
                }
            })
            .collect();
        let mut contacts = book.contacts.clone();
        for (j, open) in book.open.iter().enumerate() {
            if let Some(k) = open {
                contacts[*k].dissipated =
                    sys.law_slot(j, y)[DISSIPATED] - book.dissipated_at_onset[j];
            }
        }
        ChainRun {
            t_end: t,
            settled,
            bodies,
            contacts,
            ledger: ledger(sys, t, y, &book),
            stats: it.stats(),
        }
    }
}

/// One step of the integrated bodies, back to its first event if it has one: an event of a
/// watched pair on the dense output, or a predicted onset of a pair in free flight.
fn step<I: Input>(
    it: &mut It<'_, I>,
    book: &mut Book,
    horizon: f64,
) -> Result<Option<Event>, bwc_ode::Error> {
    it.step(horizon)?;
    let mut event = events::first(it, &book.onsets);
    if let Some((t, pair)) = book.queue.first() {
        if t <= it.t() && event.is_none_or(|e| t < e.t) {
            event = Some(Event {
                t,
                pair,
                kind: Kind::Onset,
            });
        }
    }
    if let Some(e) = event.filter(|e| e.t < it.t()) {
        if e.t > it.t_prev() {
            it.retake_to(e.t)?;
        } else {
            it.undo();
        }
    }
    Ok(event)
}

/// Free flight with nothing integrated: on to the next predicted onset, the horizon, or (when
/// the run stops once settled and no onset is ahead) the instant every gap stops closing.
fn fly<I: Input>(it: &mut It<'_, I>, book: &mut Book, stop: Stop) -> Result<Landing, ModelError> {
    let next = book.queue.first();
    let settle = match next {
        None if stop.settled => settling_time(it),
        _ => f64::INFINITY,
    };
    let (to, landing) = match next {
        Some((t, pair)) if t <= stop.horizon => (
            t,
            Landing::Event(Event {
                t,
                pair,
                kind: Kind::Onset,
            }),
        ),
        _ if settle <= stop.horizon => (settle, Landing::Settled),
        _ => (stop.horizon, Landing::Horizon),
    };
    it.restart(to).map_err(|e| ModelError::Solver(e.into()))?;
    Ok(landing)
}

/// With every body in free flight and no onset ahead: when the last closing gap stops closing
/// (each pair's relative velocity and acceleration then `>= 0`), `∞` if one never does.
fn settling_time<I: Input>(it: &It<'_, I>) -> f64 {
    let (sys, t, y) = (it.system(), it.t(), it.y());
    let mut at = t;
    for j in 0..sys.pairs.len() {
        let (u, a) = (
            sys.relative_velocity(j, t, y),
            sys.relative_acceleration(j, it.derivative()),
        );
        if a < 0.0 || u < 0.0 && a == 0.0 {
            return f64::INFINITY;
        }
        if u < 0.0 {
            at = at.max(t - u / a);
        }
    }
    at
}

/// Predicts pair `j`'s onset if both its sides fly free (a wall counts as free).
fn predict<I: Input>(it: &It<'_, I>, book: &mut Book, j: usize) {
    let (sys, t, y) = (it.system(), it.t(), it.y());
    let p = &sys.pairs[j];
    let free = |b: Option<usize>| b.is_none_or(|i| sys.local(i) == NONE);
    if sys.is_active(j) || !free(p.left) || !free(p.right) {
        return;
    }
    let flight = Flight(Motion {
        t0: t,
        d0: sys.gap(j, t, y) - book.onsets[j],
        v0: sys.relative_velocity(j, t, y),
        a: sys.relative_acceleration(j, it.derivative()),
    });
    if let Some(at) = flight.onset() {
        book.queue.push(j, at);
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

/// The ledger at `t`, `y` the integrated state there. The work of constant inputs is
/// `Σ u_i d_i` exactly; that of inputs varying in time is integrated (every body is then).
fn ledger<I: Input>(system: &ChainSystem<'_, I>, t: f64, y: &[f64], book: &Book) -> Ledger {
    let (mut kinetic, mut work) = (0.0, 0.0);
    for (i, m) in book.masses.iter().enumerate() {
        let (d, v) = system.body(i, t, y);
        kinetic += 0.5 * m * v * v;
        if !system.whole {
            work += system.inputs[i].at(t) * d;
        }
    }
    if system.whole {
        work = y[system.work()];
    }
    let (mut stored, mut dissipated) = (0.0, 0.0);
    for (j, p) in system.pairs.iter().enumerate() {
        let s = system.law_slot(j, y);
        stored += p.law.stored(s);
        dissipated += s[DISSIPATED];
    }
    Ledger {
        kinetic,
        stored,
        dissipated,
        work,
        initial: book.initial,
    }
}

/// Whether no contact is active and no gap is closing: every relative velocity `>= 0`, and
/// under constant inputs every relative acceleration too. In free flight a predicted onset
/// means a gap is closing.
fn is_settled<I: Input>(it: &It<'_, I>, book: &mut Book) -> bool {
    let (sys, t, y) = (it.system(), it.t(), it.y());
    if !sys.active.is_empty() {
        return false;
    }
    // A pair closing at the rounding level of the speeds (an elastic chain's beads drifting at
    // 1e-12 of the impact speed, meeting in years) is at rest, as its predicted onset is.
    let constant = sys.inputs.iter().all(|i| i.is_constant());
    (0..sys.pairs.len()).all(|j| {
        sys.relative_velocity(j, t, y) >= -book.rest_speed
            && constant
            && sys.relative_acceleration(j, it.derivative()) >= 0.0
    })
}

/// Raises the open contacts' peak forces to their forces at the current point.
fn record_peaks<I: Input>(it: &mut It<'_, I>, book: &mut Book) {
    let (t, t_prev) = (it.t(), it.t_prev());
    for a in 0..it.system().active.len() {
        let j = it.system().active[a];
        let Some(k) = book.open[j] else { continue };
        let f = it.system().force(j, t, it.y());
        let mut peak = (f, t);
        // A maximum inside the step (a damped law's, away from the kinks the steps stop at):
        // the force rose into the step and falls at its end.
        if t > t_prev {
            let falling =
                it.system()
                    .force_falling(j, t, (it.y(), it.derivative()), 1e-6 * (t - t_prev));
            if falling && book.rising[j] {
                let inside = peak_in_step(it, j);
                if inside.0 > peak.0 {
                    peak = inside;
                }
            }
            book.rising[j] = !falling;
        }
        let c = &mut book.contacts[k];
        if peak.0 > c.peak_force {
            c.peak_force = peak.0;
            c.peak_at = peak.1;
        }
    }
}

/// Takes up the contacts of pairs whose gap is closed (at or below the onset gap) and closing
/// at the current point: a contact that begins exactly at a restart (bodies placed touching,
/// or pushed together by another contact's event). Watched pairs are tested here; pairs in
/// free flight have their onset predicted at this instant.
fn take_up_touching<I: Input>(it: &mut It<'_, I>, book: &mut Book) -> Result<(), ModelError> {
    let t = it.t();
    for w in 0..it.system().watched.len() {
        let sys = it.system();
        let j = sys.watched[w];
        let closing = !sys.is_active(j)
            && sys.gap(j, t, it.y()) <= book.onsets[j]
            && sys.relative_velocity(j, t, it.y()) < 0.0;
        if closing {
            begin(it, book, j);
        }
    }
    // Onsets are predicted no earlier than the instant they are predicted at, and a step ends
    // at the first of them: those due now are the only ones not after now.
    while let Some((_, j)) = book.queue.first().filter(|(at, _)| *at <= t) {
        book.queue.pop();
        begin(it, book, j);
    }
    if book.began.is_empty() {
        return Ok(());
    }
    switch(it, book)
}

/// Begins pair `j`'s contact at the current point ([`switch`] follows).
fn begin<I: Input>(it: &It<'_, I>, book: &mut Book, j: usize) {
    let (sys, t) = (it.system(), it.t());
    let u = sys.relative_velocity(j, t, it.y());
    book.dissipated_at_onset[j] = sys.parked[j][DISSIPATED];
    book.open[j] = Some(book.contacts.len());
    let touching = book.at_rest[j];
    book.rising[j] = true;
    book.contacts.push(ContactRecord {
        pair: j,
        onset: if touching { 0.0 } else { t },
        onset_velocity: if touching { 0.0 } else { u.min(0.0) },
        began_at_rest: touching || -u <= book.rest_speed,
        separation: None,
        separation_velocity: None,
        dissipated: 0.0,
        peak_force: 0.0,
        peak_at: t,
    });
    book.began.push(j);
}

/// Ends pair `j`'s contact at the current point: records it, moves its onset gap to where it
/// separated and, under [`Policy::Reset`], puts its law at rest (what it stored counted as
/// dissipated); [`switch`] follows.
fn end<I: Input>(it: &mut It<'_, I>, book: &mut Book, j: usize) {
    let t = it.t();
    let (sys, y) = it.system_and_state_mut();
    let u = sys.relative_velocity(j, t, y);
    let o = sys.slot(j);
    if book.policy == Policy::Reset {
        y[o + DISSIPATED] += sys.pairs[j].law.stored(&y[o..o + 3]);
        y[o..o + SLOT - 1].fill(0.0);
    }
    book.onsets[j] = sys.gap(j, t, y);
    book.at_rest[j] = false;
    if let Some(k) = book.open[j].take() {
        let c = &mut book.contacts[k];
        c.separation = Some(t);
        c.separation_velocity = Some(u.max(0.0));
        c.dissipated = y[o + DISSIPATED] - book.dissipated_at_onset[j];
    }
    book.ended.push(j);
}

/// Applies the contacts begun and ended at the current point: the new active set, the bodies
/// it integrates, and the onsets of the pairs whose bodies changed between integrated and
/// free; the integration restarts there.
fn switch<I: Input>(it: &mut It<'_, I>, book: &mut Book) -> Result<(), ModelError> {
    let t = it.t();
    book.next.clear();
    let (ended, began) = (&book.ended, &book.began);
    book.next.extend(
        it.system()
            .active
            .iter()
            .filter(|j| !ended.contains(j))
            .chain(began.iter()),
    );
    book.next.sort_unstable();
    let (sys, y) = it.system_and_state_mut();
    sys.relayout(t, y, &book.next, (&mut book.y_next, &mut book.atol_next));
    it.restart_with(t, &book.y_next, &book.atol_next)
        .map_err(|e| ModelError::Solver(e.into()))?;
    book.began.clear();
    book.ended.clear();
    if !it.system().whole {
        for c in 0..it.system().changed.len() {
            let i = it.system().changed[c];
            for j in it.system().body_pairs[i].into_iter().flatten() {
                book.queue.void(j);
                predict(it, book, j);
            }
        }
    }
    Ok(())
}

/// Applies `event` at the current point and restarts the integration there.
fn apply<I: Input>(it: &mut It<'_, I>, book: &mut Book, event: Event) -> Result<(), ModelError> {
    it.record_event();
    match event.kind {
        Kind::Onset => begin(it, book, event.pair),
        Kind::Separation => end(it, book, event.pair),
        Kind::Kink => {}
    }
    if !book.began.is_empty() || !book.ended.is_empty() {
        return switch(it, book);
    }
    let t = it.t();
    it.restart(t).map_err(|e| ModelError::Solver(e.into()))
}

/// Samples at `t = k dt`: integrated bodies and laws from the last step's dense output, bodies
/// in free flight in closed form.
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
    fn new<I: Input>(dt: f64, it: &It<'_, I>) -> Self {
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

    /// The samples due up to the current point (inside the last step, or the last stretch of
    /// free flight).
    fn emit<I: Input>(
        &mut self,
        chain: &Chain<I>,
        it: &mut It<'_, I>,
        book: &Book,
        observer: &mut impl FnMut(&Sample<'_>),
    ) {
        loop {
            let t = self.next as f64 * self.dt;
            if t > it.t() {
                return;
            }
            self.y.resize(it.y().len(), 0.0);
            if t == it.t() || it.t() <= it.t_prev() {
                self.y.copy_from_slice(it.y());
            } else {
                for c in 0..self.y.len() {
                    self.y[c] = it.dense_component(c, t);
                }
            }
            self.sample(chain, it.system(), t, book, observer);
            self.next += 1;
        }
    }

    fn sample<I: Input>(
        &mut self,
        chain: &Chain<I>,
        sys: &ChainSystem<'_, I>,
        t: f64,
        book: &Book,
        observer: &mut impl FnMut(&Sample<'_>),
    ) {
        for (i, b) in chain.bodies.iter().enumerate() {
            let (d, v) = sys.body(i, t, &self.y);
            self.positions[i] = b.position + d;
            self.velocities[i] = v;
        }
        for j in 0..sys.pairs.len() {
            self.gaps[j] = sys.gap(j, t, &self.y);
            self.forces[j] = sys.force(j, t, &self.y);
        }
        observer(&Sample {
            t,
            positions: &self.positions,
            velocities: &self.velocities,
            gaps: &self.gaps,
            forces: &self.forces,
            ledger: ledger(sys, t, &self.y, book),
        });
    }
}

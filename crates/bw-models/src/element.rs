//! A contact element: one contact law with its state, carried between the steps of a host
//! simulator.
//!
//! The host integrates its bodies; per step it gives the element the step `dt` (s) and the
//! relative motion over it, in one of two forms:
//!
//! * [`ContactElement::advance`]: the relative velocity `u` (m/s, negative while the bodies
//!   approach) at the step's start and end, taken as linear in between. A contact is under way
//!   from the first such step: the host calls it only while its bodies touch.
//! * [`ContactElement::advance_penetration`]: the penetration `δ` (m, positive while the
//!   bodies overlap) and its rate `δ̇ = -u` (m/s) at the step's start and end, taken as the
//!   cubic Hermite interpolant in between. The element finds the onset itself: a contact
//!   begins where `δ` rises through the onset depth ([`ContactElement::onset_depth`]: 0 at
//!   first, then the depth of the last separation, which is where a `[sequence]` scene starts
//!   its next contact).
//!
//! The element integrates its law's stiff internal states over the step with its own adaptive
//! steps (DOP853 to [`ElementSettings::rtol`], stopping exactly at the law's kinks), locates
//! the separation `F <= 0 <= u` inside the step, and returns the force at the step's end, the
//! impulse `∫ F dt` over the step (N s: what a host's momentum balance needs) and the work the
//! contact absorbed, `∫ -F u dt` (J).
//!
//! A new contact starts from the law at rest under [`Policy::Reset`], from the state of the
//! last separation under [`Policy::Carry`] (as a `[sequence]` scene does).

use crate::error::ModelError;
use crate::laws::ContactLaw;
use crate::separation::Separation;
use crate::sequence::Policy;
use bwc_events::{Locator, Outcome, SwitchAt};
use bwc_ode::{Integrator, Options, State, DOP853};

/// The integrated state: the law's `N <= 3` displacements, then the energy dissipated (J) and
/// the impulse (N s) since the step's start, in components 3 and 4. The work absorbed is the
/// dissipated energy plus the change of the stored energy ([`ContactLaw::stored`], exact):
/// only the dissipation is a quadrature, and its integrand is smooth where the work's is not
/// (`F² / c` against `-F u` at the onset of a Maxwell law).
type Augmented = State<5>;
const WORK: usize = 3;
const IMPULSE: usize = 4;

/// Contact phases one host step may hold before the element gives up on it: a contact, a
/// separation, a new onset and so on. Only a step far longer than a contact reaches it.
const MAX_PHASES: usize = 8;

/// How an element integrates and what a new contact starts from.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ElementSettings {
    /// Relative tolerance of the internal steps.
    pub rtol: f64,
    /// Absolute tolerance of the law's displacements (m).
    pub atol: f64,
    /// What a new contact starts from.
    pub policy: Policy,
}

impl Default for ElementSettings {
    /// `rtol` 1e-10, `atol` 1e-16 m, [`Policy::Reset`].
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-16,
            policy: Policy::Reset,
        }
    }
}

/// The penetration at one instant: what a host that tracks overlaps gives the element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Penetration {
    /// The overlap `δ` of the bodies (m), positive while they overlap.
    pub depth: f64,
    /// Its rate `δ̇` (m/s), positive while the bodies approach: `δ̇ = -u`.
    pub rate: f64,
}

/// What one host step gave.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ElementStep {
    /// The force at the step's end (N, positive pushing the bodies apart; 0 once separated).
    pub force: f64,
    /// `∫ F dt` over the step (N s).
    pub impulse: f64,
    /// `∫ -F u dt` over the step (J): the work the bodies did on the contact.
    pub work: f64,
    /// Where the contact ended inside the step (s from its start), if it did (the last
    /// separation where the step holds several).
    pub separated_at: Option<f64>,
    /// Where a contact began inside the step (s from its start), if one did
    /// ([`ContactElement::advance_penetration`] only; the first onset where the step holds
    /// several).
    pub began_at: Option<f64>,
}

/// The relative velocity over a host step, `u(t) = c0 + c1 t + c2 t²` (m/s) with `t` (s) from
/// the step's start, and the penetration `δ(t) = d0 - ∫ u` (m) that goes with it.
#[derive(Debug, Clone, Copy)]
struct Motion {
    c: [f64; 3],
    d0: f64,
}

impl Motion {
    /// Linear velocity from `u0` to `u1` over `dt`.
    fn linear(dt: f64, u0: f64, u1: f64) -> Self {
        Self {
            c: [u0, (u1 - u0) / dt, 0.0],
            d0: 0.0,
        }
    }

    /// The cubic Hermite penetration through `a` at 0 and `b` at `dt`.
    fn hermite(dt: f64, a: Penetration, b: Penetration) -> Self {
        let slope = (b.depth - a.depth) / dt;
        let c2 = (3.0 * slope - 2.0 * a.rate - b.rate) / dt;
        let c3 = (a.rate + b.rate - 2.0 * slope) / (dt * dt);
        // δ = d0 + r0 t + c2 t² + c3 t³, u = -δ̇.
        Self {
            c: [-a.rate, -2.0 * c2, -3.0 * c3],
            d0: a.depth,
        }
    }

    fn u(&self, t: f64) -> f64 {
        let [c0, c1, c2] = self.c;
        c0 + t * (c1 + t * c2)
    }

    fn du(&self, t: f64) -> f64 {
        let [_, c1, c2] = self.c;
        c1 + 2.0 * c2 * t
    }

    fn depth(&self, t: f64) -> f64 {
        let [c0, c1, c2] = self.c;
        self.d0 - t * (c0 + t * (c1 / 2.0 + t * c2 / 3.0))
    }

    /// The first time in `[from, to]` where a contact begins: where `δ` rises through
    /// `level`, or starts to rise while above it. Found on the pieces where `δ` is monotone,
    /// by bisection.
    fn rise_through(&self, level: f64, from: f64, to: f64) -> Option<f64> {
        let g = |t: f64| self.depth(t) - level;
        let mut cuts = [from, to, to, to];
        for (slot, t) in cuts[1..3].iter_mut().zip(self.turning_points()) {
            // NaN (no turning point) fails the test and leaves `to`.
            if t > from && t < to {
                *slot = t;
            }
        }
        cuts[1..3].sort_by(f64::total_cmp);
        cuts.windows(2)
            .filter(|w| w[0] < w[1] && self.u(0.5 * (w[0] + w[1])) < 0.0)
            .find_map(|w| {
                if g(w[0]) > 0.0 {
                    Some(w[0])
                } else if g(w[1]) > 0.0 {
                    Some(bisect(g, w[0], w[1]))
                } else {
                    None
                }
            })
    }

    /// The zeros of `u` (where `δ` may turn), `NaN` where there are none.
    fn turning_points(&self) -> [f64; 2] {
        let [c0, c1, c2] = self.c;
        if c2 == 0.0 {
            return [if c1 == 0.0 { f64::NAN } else { -c0 / c1 }, f64::NAN];
        }
        let disc = c1 * c1 - 4.0 * c2 * c0;
        if disc < 0.0 {
            return [f64::NAN; 2];
        }
        let q = -0.5 * (c1 + disc.sqrt().copysign(c1));
        [q / c2, if q == 0.0 { f64::NAN } else { c0 / q }]
    }
}

/// The point in `[a, b]` where `g` goes from `<= 0` to `> 0`, to the last bit.
fn bisect(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    loop {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            return b;
        }
        if g(m) > 0.0 {
            b = m;
        } else {
            a = m;
        }
    }
}

/// What changes over a step, kept apart so that a failed step changes nothing.
#[derive(Debug, Clone, Copy)]
struct Status<const N: usize> {
    state: State<N>,
    in_contact: bool,
    force: f64,
    absorbed: f64,
    contacts: u64,
    onset_depth: f64,
}

/// One contact's law and state (see the module's documentation).
#[derive(Debug, Clone)]
pub struct ContactElement<L, const N: usize> {
    law: L,
    settings: ElementSettings,
    status: Status<N>,
}

/// One contact phase's end: the time, the augmented state there and whether it separated.
struct PhaseEnd {
    t: f64,
    y: Augmented,
    separated: bool,
}

impl<L: ContactLaw<N>, const N: usize> ContactElement<L, N> {
    const FITS: () = assert!(N <= 3, "a contact law has at most three states");

    /// An element of `law`, out of contact, at rest.
    ///
    /// # Errors
    /// [`ModelError::InvalidSetting`] for `rtol` outside `[1e-14, 1e-2]` or `atol <= 0`.
    pub fn new(law: L, settings: ElementSettings) -> Result<Self, ModelError> {
        let () = Self::FITS;
        if !(1e-14..=1e-2).contains(&settings.rtol) {
            return Err(invalid("rtol", settings.rtol, "1e-14 <= rtol <= 1e-2"));
        }
        if !(settings.atol > 0.0 && settings.atol.is_finite()) {
            return Err(invalid("atol", settings.atol, "atol > 0 (m)"));
        }
        let status = Status {
            state: law.onset(),
            in_contact: false,
            force: 0.0,
            absorbed: 0.0,
            contacts: 0,
            onset_depth: 0.0,
        };
        Ok(Self {
            law,
            settings,
            status,
        })
    }

    /// Advances the contact over a host step of `dt` (s) in which the relative velocity goes
    /// linearly from `u_start` to `u_end` (m/s). The step starts a contact if none is under
    /// way; after a separation inside the step the force is 0 for the rest of it.
    ///
    /// # Errors
    /// [`ModelError::InvalidSetting`] for `dt <= 0` or a non-finite velocity, and
    /// [`ModelError::Solver`] where the law's integration fails; the element is then
    /// unchanged.
    pub fn advance(
        &mut self,
        dt: f64,
        u_start: f64,
        u_end: f64,
    ) -> Result<ElementStep, ModelError> {
        check_dt(dt)?;
        check_finite("u_start", u_start, "a finite relative velocity (m/s)")?;
        check_finite("u_end", u_end, "a finite relative velocity (m/s)")?;
        self.commit(dt, &Motion::linear(dt, u_start, u_end), false)
    }

    /// Advances the element over a host step of `dt` (s) from the penetration `start` to
    /// `end` (cubic Hermite in between). Out of contact, a contact begins where the
    /// penetration rises through [`ContactElement::onset_depth`] (or starts to rise while
    /// above it); it ends at `F <= 0 <= u`, and the element waits for the next rise. A step
    /// may hold several contacts.
    ///
    /// # Errors
    /// [`ModelError::InvalidSetting`] for `dt <= 0` or a non-finite depth or rate (named
    /// `depth_start`, `rate_start`, `depth_end`, `rate_end`, as the bindings call them),
    /// [`ModelError::Solver`] where the law's integration fails and
    /// [`ModelError::NotApplicable`] for a step that holds more than 8 contacts; the element
    /// is then unchanged.
    pub fn advance_penetration(
        &mut self,
        dt: f64,
        start: Penetration,
        end: Penetration,
    ) -> Result<ElementStep, ModelError> {
        check_dt(dt)?;
        let finite = "a finite penetration (m) and rate (m/s)";
        check_finite("depth_start", start.depth, finite)?;
        check_finite("rate_start", start.rate, finite)?;
        check_finite("depth_end", end.depth, finite)?;
        check_finite("rate_end", end.rate, finite)?;
        self.commit(dt, &Motion::hermite(dt, start, end), true)
    }

    /// Runs a step and keeps its result only if it succeeded.
    fn commit(
        &mut self,
        dt: f64,
        motion: &Motion,
        onsets: bool,
    ) -> Result<ElementStep, ModelError> {
        // A step so short that the motion's coefficients (differences over `dt`, `dt²`)
        // overflow has no motion to integrate: say so, naming the step.
        if !motion.c.iter().all(|c| c.is_finite()) {
            return Err(invalid(
                "dt",
                dt,
                "a step long enough for the velocities (and depths) at its ends: their \
                 differences over dt overflow; a longer step, or ends that agree",
            ));
        }
        let (status, step) = self.step(dt, motion, onsets)?;
        self.status = status;
        Ok(step)
    }

    /// A host step as contact phases: an onset (found where `onsets`, else at the step's
    /// start), a contact to the step's end or to a separation, and again after a separation
    /// where `onsets`.
    fn step(
        &self,
        dt: f64,
        motion: &Motion,
        onsets: bool,
    ) -> Result<(Status<N>, ElementStep), ModelError> {
        let mut s = self.status;
        let mut step = ElementStep {
            force: 0.0,
            impulse: 0.0,
            work: 0.0,
            separated_at: None,
            began_at: None,
        };
        let mut t = 0.0;
        for _ in 0..MAX_PHASES {
            if !s.in_contact {
                let onset = if onsets {
                    motion.rise_through(s.onset_depth, t, dt)
                } else {
                    Some(t)
                };
                let Some(t_on) = onset.filter(|&t_on| t_on < dt) else {
                    s.force = 0.0;
                    return Ok((s, step));
                };
                self.begin(&mut s);
                if onsets {
                    // An onset located to the float above the step's start (a penetration
                    // rising through the onset depth at t = 0) is at the start.
                    let at = if t_on <= 4.0 * f64::EPSILON * dt {
                        0.0
                    } else {
                        t_on
                    };
                    step.began_at.get_or_insert(at);
                }
                t = t_on;
            }
            // A contact at whose start the bodies are parting and the law pushes nothing (at
            // rest, or a carried state without compression) ends there: the condition holds
            // from the start, and the event location looks for where it begins to hold.
            let end = if self.parted(&s.state, motion, t) {
                PhaseEnd {
                    t,
                    y: augmented(&s.state),
                    separated: true,
                }
            } else {
                self.contact(&s.state, motion, t, dt)?
            };
            let held = self.law.stored(&s.state);
            s.state = law_state::<N>(&end.y);
            let work = end.y[WORK] + self.law.stored(&s.state) - held;
            s.absorbed += work;
            step.work += work;
            step.impulse += end.y[IMPULSE];
            if !end.separated {
                s.force = self.law.eval(&s.state, motion.u(dt)).1;
                step.force = s.force;
                return Ok((s, step));
            }
            (s.in_contact, s.force, t) = (false, 0.0, end.t);
            s.contacts += 1;
            step.separated_at = Some(end.t);
            if !onsets {
                return Ok((s, step));
            }
            s.onset_depth = motion.depth(end.t);
        }
        Err(ModelError::NotApplicable {
            reason: "more than 8 contacts began and ended within one host step: take shorter \
                     host steps",
        })
    }

    /// Whether the law at `state` pushes nothing while the bodies part at `t`: `F <= 0` and
    /// `u > 0`, or `u = 0` and not falling.
    fn parted(&self, state: &State<N>, motion: &Motion, t: f64) -> bool {
        let u = motion.u(t);
        let parting = u > 0.0 || (u == 0.0 && motion.du(t) >= 0.0);
        parting && self.law.eval(state, u).1 <= 0.0
    }

    /// A new contact: the law at rest, or as the last contact left it under
    /// [`Policy::Carry`].
    fn begin(&self, s: &mut Status<N>) {
        if self.settings.policy == Policy::Reset {
            s.state = self.law.onset();
        }
        s.in_contact = true;
    }

    /// Integrates a contact from the law's `start` at `t0` to `t1` or to its separation, with
    /// the work and the impulse since `t0`.
    fn contact(
        &self,
        start: &State<N>,
        motion: &Motion,
        t0: f64,
        t1: f64,
    ) -> Result<PhaseEnd, ModelError> {
        let law = &self.law;
        let rhs = move |t: f64, y: &Augmented| {
            let (u, s) = (motion.u(t), law_state::<N>(y));
            let (d, f) = law.eval(&s, u);
            let mut dy = augmented(&d);
            dy[WORK] = law.dissipation(&s, u, &d, f);
            dy[IMPULSE] = f;
            dy
        };
        let force = move |t: f64, y: &Augmented| {
            let u = motion.u(t);
            (law.eval(&law_state::<N>(y), u).1, u)
        };
        let kinks =
            SwitchAt(move |t: f64, y: &Augmented| law.kinks(&law_state::<N>(y), motion.u(t)));
        let y0 = augmented(start);
        let mut options = Options::new(self.settings.rtol, self.settings.atol);
        // The dissipation and the impulse are quadratures of the state: they follow its steps
        // and take no part in choosing them (tests/support/element.rs measures how well).
        options.atol[WORK] = 1e300;
        options.atol[IMPULSE] = 1e300;
        let mut it = Integrator::new(rhs, &DOP853, t0, y0, options)
            .map_err(|e| ModelError::Solver(e.into()))?;
        Ok(
            match Locator::new(Separation(force), kinks).run(&mut it, t1)? {
                Outcome::Event { t, y } => PhaseEnd {
                    t,
                    y,
                    separated: true,
                },
                Outcome::Horizon { t, y } => PhaseEnd {
                    t,
                    y,
                    separated: false,
                },
            },
        )
    }

    /// The law.
    pub fn law(&self) -> &L {
        &self.law
    }

    /// The settings.
    pub fn settings(&self) -> &ElementSettings {
        &self.settings
    }

    /// The force at the end of the last step (N).
    pub fn force(&self) -> f64 {
        self.status.force
    }

    /// The law's state (m): the displacements of its elements.
    pub fn state(&self) -> &State<N> {
        &self.status.state
    }

    /// Whether a contact is under way (it began and has not separated).
    pub fn in_contact(&self) -> bool {
        self.status.in_contact
    }

    /// The penetration (m) at which the next contact of
    /// [`ContactElement::advance_penetration`] begins: 0 until a contact has separated, then
    /// the penetration at that separation (as a `[sequence]` scene measures its heights from
    /// the point of the last separation, under both policies).
    pub fn onset_depth(&self) -> f64 {
        self.status.onset_depth
    }

    /// The work the bodies did on the contact over all steps so far, `∫ -F u dt` (J).
    pub fn absorbed(&self) -> f64 {
        self.status.absorbed
    }

    /// The energy dissipated so far (J): the work absorbed less what the law's springs hold
    /// now ([`ContactLaw::stored`]). A new contact under [`Policy::Reset`] starts the law at
    /// rest, so what its springs held at the last separation counts as dissipated.
    pub fn dissipated(&self) -> f64 {
        let s = &self.status;
        let held = if s.in_contact || self.settings.policy == Policy::Carry {
            self.law.stored(&s.state)
        } else {
            0.0
        };
        s.absorbed - held
    }

    /// Contacts that have ended.
    pub fn contacts(&self) -> u64 {
        self.status.contacts
    }

    /// Back to the law at rest, out of contact, with nothing absorbed and the onset depth 0.
    pub fn reset(&mut self) {
        self.status = Status {
            state: self.law.onset(),
            in_contact: false,
            force: 0.0,
            absorbed: 0.0,
            contacts: 0,
            onset_depth: 0.0,
        };
    }
}

/// An augmented state with the law's `state`, no work and no impulse.
fn augmented<const N: usize>(state: &State<N>) -> Augmented {
    let mut y = Augmented::zeros();
    y.fixed_rows_mut::<N>(0).copy_from(state);
    y
}

/// The law's state in an augmented state.
fn law_state<const N: usize>(y: &Augmented) -> State<N> {
    State::<N>::from_fn(|i, _| y[i])
}

/// What a host can change when a step of an element failed in its integration, by how it
/// failed; each host words it in its own names (the C ABI's `dt`, the FMU's
/// `communicationStepSize`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Remedy {
    /// The state overflowed: the velocities (or penetration rates) or the law's parameters are
    /// beyond what the law can be integrated at.
    CheckVelocities,
    /// The solver took its most steps inside one host step: a shorter host step, or a looser
    /// `rtol`.
    ShorterStep,
    /// The solver's step fell below the resolution of its time: a shorter host step (a long one
    /// reaches times where the state is huge), looser `rtol` and `atol`, or a less stiff law.
    LooserTolerances,
}

impl Remedy {
    /// The remedy of a failed step's error, if its integration failed.
    pub fn of(e: &ModelError) -> Option<Self> {
        use bwc_ode::Error as Ode;
        match e {
            ModelError::Solver(bwc_events::Error::Solver(ode)) => match ode {
                Ode::NonFiniteInitialValue { .. } | Ode::NonFiniteState { .. } => {
                    Some(Self::CheckVelocities)
                }
                Ode::TooManySteps { .. } => Some(Self::ShorterStep),
                Ode::StepSizeTooSmall { .. } => Some(Self::LooserTolerances),
                _ => None,
            },
            _ => None,
        }
    }
}

fn invalid(name: &'static str, value: f64, allowed: &'static str) -> ModelError {
    ModelError::InvalidSetting {
        name,
        value,
        allowed,
    }
}

/// `dt > 0` and finite.
fn check_dt(dt: f64) -> Result<(), ModelError> {
    if dt > 0.0 && dt.is_finite() {
        Ok(())
    } else {
        Err(invalid("dt", dt, "dt > 0 (s), finite"))
    }
}

fn check_finite(name: &'static str, value: f64, allowed: &'static str) -> Result<(), ModelError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(invalid(name, value, allowed))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Hermite motion interpolates the ends and their rates, and `u = -δ̇`.
    #[test]
    fn the_hermite_motion_meets_its_ends() {
        let (a, b) = (
            Penetration {
                depth: -1e-3,
                rate: 2.0,
            },
            Penetration {
                depth: 4e-3,
                rate: -1.0,
            },
        );
        let m = Motion::hermite(1e-2, a, b);
        assert!((m.depth(0.0) - a.depth).abs() < 1e-18);
        assert!((m.depth(1e-2) - b.depth).abs() < 1e-15);
        assert!((m.u(0.0) + a.rate).abs() < 1e-14);
        assert!((m.u(1e-2) + b.rate).abs() < 1e-12);
        let h = 1e-7;
        let t = 3e-3;
        let rate = (m.depth(t + h) - m.depth(t - h)) / (2.0 * h);
        assert!((rate + m.u(t)).abs() < 1e-7);
    }

    /// `δ(t) = t (1 - t)` on [0, 1] rises through 0.09 at t = 0.1 (the smaller root of
    /// t² - t + 0.09), and never rises through 0.3 (its maximum is 0.25).
    #[test]
    fn a_rise_is_found_on_the_rising_piece() {
        let m = Motion {
            c: [-1.0, 2.0, 0.0],
            d0: 0.0,
        };
        let t = m.rise_through(0.09, 0.0, 1.0).unwrap();
        assert!((t - 0.1).abs() < 1e-15, "{t}");
        assert_eq!(m.rise_through(0.3, 0.0, 1.0), None);
        // Above the level and rising at the start: at once. Falling: not at all.
        assert_eq!(m.rise_through(-0.1, 0.0, 1.0), Some(0.0));
        assert_eq!(m.rise_through(0.0, 0.6, 1.0), None);
    }
}

//! A contact element: one contact law with its state, carried between the steps of a host
//! simulator.
//!
//! The host integrates its bodies; per step it gives the element the step `dt` (s) and the
//! relative velocity `u` (m/s, negative while the bodies approach) at the step's start and end,
//! taken as linear in between. The element integrates its law's stiff internal states over the
//! step with its own adaptive steps (DOP853 to [`ElementSettings::rtol`], stopping exactly at
//! the law's kinks), locates the separation `F <= 0 <= u` inside the step, and returns the
//! force at the step's end, the impulse `∫ F dt` over the step (N s: what a host's momentum
//! balance needs) and the work the contact absorbed, `∫ -F u dt` (J).
//!
//! A contact begins with the first step the host gives after the element was created or had
//! separated: from the law at rest under [`Policy::Reset`], from the state of the last
//! separation under [`Policy::Carry`] (as a `[sequence]` scene does).

use crate::error::ModelError;
use crate::laws::ContactLaw;
use crate::separation::Separation;
use crate::sequence::Policy;
use bwc_events::{Locator, Outcome, SwitchAt};
use bwc_ode::{Integrator, Options, State, DOP853};

/// The integrated state: the law's `N <= 3` displacements, then the absorbed work (J) and the
/// impulse (N s) since the step's start, in components 3 and 4.
type Augmented = State<5>;
const WORK: usize = 3;
const IMPULSE: usize = 4;

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
    /// Where the contact ended inside the step (s from its start), if it did.
    pub separated_at: Option<f64>,
}

/// One contact's law and state (see the module's documentation).
#[derive(Debug, Clone)]
pub struct ContactElement<L, const N: usize> {
    law: L,
    settings: ElementSettings,
    state: State<N>,
    in_contact: bool,
    force: f64,
    absorbed: f64,
    contacts: u64,
}

impl<L: ContactLaw<N>, const N: usize> ContactElement<L, N> {
    const FITS: () = assert!(N <= 3, "a contact law has at most three states");

    /// An element of `law`, out of contact, at rest.
    ///
    /// # Errors
    /// [`ModelError::InvalidSetting`] for `rtol` outside `[1e-14, 1e-2]` or `atol <= 0`.
    pub fn new(law: L, settings: ElementSettings) -> Result<Self, ModelError> {
        let () = Self::FITS;
        let bad = |name, value, allowed| ModelError::InvalidSetting {
            name,
            value,
            allowed,
        };
        if !(1e-14..=1e-2).contains(&settings.rtol) {
            return Err(bad("rtol", settings.rtol, "1e-14 <= rtol <= 1e-2"));
        }
        if !(settings.atol > 0.0 && settings.atol.is_finite()) {
            return Err(bad("atol", settings.atol, "atol > 0 (m)"));
        }
        let state = law.onset();
        Ok(Self {
            law,
            settings,
            state,
            in_contact: false,
            force: 0.0,
            absorbed: 0.0,
            contacts: 0,
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
        check_step(dt, u_start, u_end)?;
        let start = if self.in_contact || self.settings.policy == Policy::Carry {
            self.state
        } else {
            self.law.onset()
        };
        let rate = (u_end - u_start) / dt;
        let law = &self.law;
        let u = move |t: f64| u_start + rate * t;
        let rhs = move |t: f64, y: &Augmented| {
            let (d, f) = law.eval(&law_state::<N>(y), u(t));
            let mut dy = Augmented::zeros();
            dy.fixed_rows_mut::<N>(0).copy_from(&d);
            dy[WORK] = -f * u(t);
            dy[IMPULSE] = f;
            dy
        };
        let force = move |t: f64, y: &Augmented| (law.eval(&law_state::<N>(y), u(t)).1, u(t));
        let kinks = SwitchAt(move |t: f64, y: &Augmented| law.kinks(&law_state::<N>(y), u(t)));
        let mut y0 = Augmented::zeros();
        y0.fixed_rows_mut::<N>(0).copy_from(&start);
        let mut options = Options::new(self.settings.rtol, self.settings.atol);
        // The work and the impulse are quadratures of the state: they follow its steps and
        // take no part in choosing them. Those steps do not resolve the onset's `|x|^p`, so
        // the quadratures are good to about 1e-8 of a contact's work, not to `rtol`
        // (tests/support/element.rs).
        options.atol[WORK] = 1e300;
        options.atol[IMPULSE] = 1e300;
        let mut it = Integrator::new(rhs, &DOP853, 0.0, y0, options)
            .map_err(|e| ModelError::Solver(e.into()))?;
        let outcome = Locator::new(Separation(force), kinks).run(&mut it, dt)?;
        let (t_end, y, separated_at) = match outcome {
            Outcome::Event { t, y } => (t, y, Some(t)),
            Outcome::Horizon { t, y } => (t, y, None),
        };
        self.state = law_state::<N>(&y);
        self.in_contact = separated_at.is_none();
        self.force = if self.in_contact {
            self.law.eval(&self.state, u(t_end)).1
        } else {
            0.0
        };
        self.contacts += u64::from(separated_at.is_some());
        self.absorbed += y[WORK];
        Ok(ElementStep {
            force: self.force,
            impulse: y[IMPULSE],
            work: y[WORK],
            separated_at,
        })
    }

    /// The force at the end of the last step (N).
    pub fn force(&self) -> f64 {
        self.force
    }

    /// The law's state (m): the displacements of its elements.
    pub fn state(&self) -> &State<N> {
        &self.state
    }

    /// Whether a contact is under way (it began and has not separated).
    pub fn in_contact(&self) -> bool {
        self.in_contact
    }

    /// The work the bodies did on the contact over all steps so far, `∫ -F u dt` (J).
    pub fn absorbed(&self) -> f64 {
        self.absorbed
    }

    /// The energy dissipated so far (J): the work absorbed less what the law's springs hold
    /// now ([`ContactLaw::stored`]). A new contact under [`Policy::Reset`] starts the law at
    /// rest, so what its springs held at the last separation counts as dissipated.
    pub fn dissipated(&self) -> f64 {
        let held = if self.in_contact || self.settings.policy == Policy::Carry {
            self.law.stored(&self.state)
        } else {
            0.0
        };
        self.absorbed - held
    }

    /// Contacts that have ended.
    pub fn contacts(&self) -> u64 {
        self.contacts
    }

    /// Back to the law at rest, out of contact, with nothing absorbed.
    pub fn reset(&mut self) {
        self.state = self.law.onset();
        self.in_contact = false;
        self.force = 0.0;
        self.absorbed = 0.0;
        self.contacts = 0;
    }
}

/// The law's state in an augmented state.
fn law_state<const N: usize>(y: &Augmented) -> State<N> {
    State::<N>::from_fn(|i, _| y[i])
}

/// `dt > 0` and finite velocities.
fn check_step(dt: f64, u_start: f64, u_end: f64) -> Result<(), ModelError> {
    let bad = |name, value, allowed| {
        Err(ModelError::InvalidSetting {
            name,
            value,
            allowed,
        })
    };
    if !(dt > 0.0 && dt.is_finite()) {
        return bad("dt", dt, "dt > 0 (s), finite");
    }
    if !u_start.is_finite() {
        return bad("u_start", u_start, "a finite relative velocity (m/s)");
    }
    if !u_end.is_finite() {
        return bad("u_end", u_end, "a finite relative velocity (m/s)");
    }
    Ok(())
}

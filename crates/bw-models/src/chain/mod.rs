//! Chains of bodies on a line: `N` bodies, one contact law per neighbouring pair, either end
//! optionally a fixed wall, integrated as one system.
//!
//! Body `i` (mass `m_i`, kg) has its centre at `x_i(t)` (m), velocity `v_i` (m/s) and external
//! force `u_i(t)` (N); its length along the line is `l_i` (m), so the gap of pair `j` between
//! bodies `j` and `j + 1` is `g_j = (x_{j+1} - l_{j+1}/2) - (x_j + l_j/2)`, and a wall's pair
//! measures from the wall's face. A pair's law sees the relative velocity
//! `u_j = v_{j+1} - v_j` (negative while the gap closes) and gives the force `F_j` (N,
//! positive pushing the bodies apart):
//!
//! `m_i v̇_i = u_i(t) + F_{i-1} - F_i`, `ẋ_i = v_i`, `ṡ_j = f_j(s_j, u_j)` (active pairs only).
//!
//! A contact begins when its gap closes through its onset gap (0 at first, then the gap where
//! the pair last separated, as a `[sequence]` scene's next contact) and ends at
//! `t_s = inf{t : F_j <= 0 <= u_j}` ([`crate::separated`]); its law starts at rest
//! ([`Policy::Reset`]) or from the state it separated with ([`Policy::Carry`]). A pair may
//! touch many times, and any number of contacts may be active at once. The system is one
//! adaptive integration ([`bwc_ode::FlatIntegrator`], DOP853) that stops exactly at every onset,
//! separation and kink of a law (its `z = 0` and the zero of the rate across its hysteretic
//! element), so no step straddles a point where the right-hand side is not smooth.
//!
//! Under inputs constant in time the integration carries only the bodies in contact
//! ([`Scheme::Contacts`]): a body in no contact flies on a parabola in closed form, and the
//! onset of a pair of two such bodies (or of one and a wall) is predicted in closed form and
//! waits in a queue, so a step costs `O(1)` per body in contact and per active contact,
//! whatever the chain's length, and allocates nothing. Inputs that vary in time integrate every
//! body ([`Scheme::Whole`], `O(N)` per step).
//!
//! The energy ledger is exact bookkeeping, not an estimate: kinetic `Σ m_i v_i² / 2`, stored
//! in the laws ([`crate::ContactLaw::stored`]), dissipated (the integral of each law's closed
//! form dissipation rate, plus the energy a reset law had stored at its separation), and the
//! work of the inputs `∫ Σ u_i v_i dt`; `kinetic + stored + dissipated - work` stays equal to
//! the initial kinetic energy to the integration's tolerance.
//!
//! ```
//! use bw_models::chain::{Chain, ChainBody, ChainSettings, Stop, Walls, PairLaw};
//! use bw_models::{input::Zero, ModelKind, Physical, PhysicalParams};
//! // Two equal balls, the first at 1 m/s: a Hertz contact with a little hysteresis.
//! let law = PhysicalParams::new(ModelKind::Shccm, Physical {
//!     k: 1e7, c: 0.0, n: 1.0, p: 1.5, alpha: 0.9, beta: 50.0, gamma: -50.0, a: 1.0,
//! })?;
//! let bodies = vec![ChainBody::new(0.1, 0.0, 1.0, 0.02, Zero), ChainBody::new(0.1, 0.021, 0.0, 0.02, Zero)];
//! let chain = Chain::new(bodies, vec![PairLaw::new(&law)?], Walls::default(), ChainSettings::default())?;
//! let run = chain.run(Stop::settled(1.0), None, |_| {})?;
//! let momentum: f64 = run.bodies.iter().map(|b| 0.1 * b.velocity).sum();
//! assert!((momentum - 0.1).abs() < 1e-12);
//! assert!(run.bodies[1].velocity > run.bodies[0].velocity);
//! # Ok::<(), bw_models::ModelError>(())
//! ```

mod events;
mod free;
mod run;
mod system;

pub use crate::error::ChainPart;
use crate::input::Input;

use crate::sequence::Policy;
use crate::ModelError;

pub use run::{ChainRun, ContactRecord, FinalBody, Ledger, Sample};

/// One body of a chain.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ChainBody<I> {
    /// Mass (kg), positive and finite.
    pub mass: f64,
    /// Position of the centre at `t = 0` (m).
    pub position: f64,
    /// Velocity at `t = 0` (m/s).
    pub velocity: f64,
    /// Length along the line (m, `>= 0`): the centre is `length / 2` from either face.
    pub length: f64,
    /// External force (N).
    pub input: I,
}

impl<I> ChainBody<I> {
    /// A body of `mass` (kg) centred at `position` (m) moving at `velocity` (m/s), `length`
    /// (m) long, driven by `input` (N).
    pub fn new(mass: f64, position: f64, velocity: f64, length: f64, input: I) -> Self {
        Self {
            mass,
            position,
            velocity,
            length,
            input,
        }
    }
}

/// The contact law of one pair, in SI units: any registered law ([`crate::AnyLaw`]); a
/// Bouc-Wen law from validated parameters by [`PairLaw::new`].
pub type PairLaw = crate::AnyLaw;

/// Fixed walls at the ends of a chain: the position of each wall's face (m), if there is one.
/// A wall does not move.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[non_exhaustive]
pub struct Walls {
    /// The face of a wall left of body 0.
    pub left: Option<f64>,
    /// The face of a wall right of the last body.
    pub right: Option<f64>,
}

impl Walls {
    /// Walls with faces at `left` and `right` (m), where given.
    pub fn new(left: Option<f64>, right: Option<f64>) -> Self {
        Self { left, right }
    }
}

/// How a chain is integrated and what a new contact starts from.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ChainSettings {
    /// Relative tolerance of the integration.
    pub rtol: f64,
    /// Absolute tolerance of positions and law displacements (m); velocities get
    /// `atol / 1 s`, energies `atol` times the largest force scale (see the source).
    pub atol: f64,
    /// What a law's state is at the onset of its pair's next contact.
    pub policy: Policy,
    /// Which bodies are integrated.
    pub scheme: Scheme,
}

/// Which bodies a chain's integration carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Scheme {
    /// Only the bodies in contact, under inputs constant in time: a body in no contact flies
    /// on a parabola in closed form, and the onsets of pairs in free flight are predicted in
    /// closed form, so a step costs `O(1)` per body in contact whatever the chain's length.
    /// Inputs that vary in time fall back to [`Scheme::Whole`].
    #[default]
    Contacts,
    /// Every body, at every step: `O(N)` per step (the reference the other scheme is checked
    /// against).
    Whole,
}

impl Default for ChainSettings {
    /// `rtol` 1e-10, `atol` 1e-14 m, [`Policy::Reset`], [`Scheme::Contacts`].
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-14,
            policy: Policy::Reset,
            scheme: Scheme::Contacts,
        }
    }
}

impl ChainSettings {
    /// The settings with `policy`.
    pub fn with_policy(self, policy: Policy) -> Self {
        Self { policy, ..self }
    }

    /// The settings with `scheme`.
    pub fn with_scheme(self, scheme: Scheme) -> Self {
        Self { scheme, ..self }
    }

    /// The settings with tolerances `rtol` and `atol` (m).
    pub fn with_tolerances(self, rtol: f64, atol: f64) -> Self {
        Self { rtol, atol, ..self }
    }
}

/// When a chain's run ends.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Stop {
    /// The run ends at this time (s) at the latest.
    pub horizon: f64,
    /// Whether it ends earlier, once no contact is active and no gap is closing: every pair's
    /// relative velocity and (under inputs constant in time) relative acceleration are `>= 0`.
    pub settled: bool,
}

impl Stop {
    /// At `horizon` (s).
    pub fn at(horizon: f64) -> Self {
        Self {
            horizon,
            settled: false,
        }
    }

    /// Once settled, or at `horizon` (s) at the latest.
    pub fn settled(horizon: f64) -> Self {
        Self {
            horizon,
            settled: true,
        }
    }
}

/// A validated chain, ready to run.
#[derive(Debug, Clone)]
pub struct Chain<I> {
    bodies: Vec<ChainBody<I>>,
    laws: Vec<PairLaw>,
    walls: Walls,
    settings: ChainSettings,
}

fn invalid(part: ChainPart, name: &'static str, value: f64, allowed: &'static str) -> ModelError {
    ModelError::InvalidChain {
        part,
        name,
        value,
        allowed,
    }
}

/// `ChainPart::Body(i)` (a chain of more than 2^32 bodies is not a use case).
fn body(i: usize) -> ChainPart {
    ChainPart::Body(i as u32)
}

/// At least two bodies (walls counted), each with a positive finite mass, a finite position
/// and velocity and a length `>= 0`; finite wall faces.
fn check_bodies<I>(
    bodies: &[ChainBody<I>],
    walls: Walls,
    walls_count: usize,
) -> Result<(), ModelError> {
    if bodies.is_empty() || bodies.len() + walls_count < 2 {
        let n = bodies.len() as f64;
        return Err(invalid(
            ChainPart::Chain,
            "bodies",
            n,
            "at least 2 bodies, walls counted",
        ));
    }
    for (i, b) in bodies.iter().enumerate() {
        if !(b.mass > 0.0 && b.mass.is_finite()) {
            return Err(invalid(body(i), "mass", b.mass, "> 0 and finite (kg)"));
        }
        for (name, value) in [("position", b.position), ("velocity", b.velocity)] {
            if !value.is_finite() {
                return Err(invalid(body(i), name, value, "finite"));
            }
        }
        if !(b.length >= 0.0 && b.length.is_finite()) {
            return Err(invalid(body(i), "length", b.length, ">= 0 and finite (m)"));
        }
    }
    for (part, wall) in [
        (ChainPart::LeftWall, walls.left),
        (ChainPart::RightWall, walls.right),
    ] {
        if let Some(w) = wall.filter(|w| !w.is_finite()) {
            return Err(invalid(part, "face", w, "finite (m)"));
        }
    }
    Ok(())
}

/// Tolerances positive and finite.
fn check_settings(settings: &ChainSettings) -> Result<(), ModelError> {
    for (name, value, allowed) in [
        ("rtol", settings.rtol, "> 0 and finite"),
        ("atol", settings.atol, "> 0 and finite (m)"),
    ] {
        if !(value > 0.0 && value.is_finite()) {
            return Err(ModelError::InvalidSetting {
                name,
                value,
                allowed,
            });
        }
    }
    Ok(())
}

impl<I: Input> Chain<I> {
    /// A chain of `bodies` (left to right) with `laws` for its pairs: one per neighbouring
    /// pair, the left wall's pair first and the right wall's last where there are walls, or a
    /// single law for every pair.
    ///
    /// # Errors
    /// [`ModelError::InvalidChain`] naming the body, pair or wall: fewer than two bodies
    /// (counting walls), a mass that is not positive and finite, a non-finite position,
    /// velocity or length, a negative length, overlapping neighbours (a negative gap), a
    /// number of laws that is neither 1 nor the number of pairs;
    /// [`ModelError::InvalidSetting`] for tolerances that are not positive and finite.
    pub fn new(
        bodies: Vec<ChainBody<I>>,
        laws: Vec<PairLaw>,
        walls: Walls,
        settings: ChainSettings,
    ) -> Result<Self, ModelError> {
        let walls_count = usize::from(walls.left.is_some()) + usize::from(walls.right.is_some());
        check_bodies(&bodies, walls, walls_count)?;
        let pairs = bodies.len() - 1 + walls_count;
        let laws = match laws.len() {
            1 => vec![laws[0]; pairs],
            n if n == pairs => laws,
            n => {
                return Err(invalid(
                    ChainPart::Chain,
                    "laws",
                    n as f64,
                    "one law for every pair, or one law per neighbouring pair (walls included)",
                ))
            }
        };
        check_settings(&settings)?;
        let chain = Self {
            bodies,
            laws,
            walls,
            settings,
        };
        for j in 0..pairs {
            let gap = chain.initial_gap(j);
            if gap.is_nan() || gap < 0.0 {
                return Err(invalid(
                    ChainPart::Pair(j as u32),
                    "gap",
                    gap,
                    ">= 0 (m): neighbours may touch but not overlap",
                ));
            }
        }
        Ok(chain)
    }

    /// The bodies, left to right.
    pub fn bodies(&self) -> &[ChainBody<I>] {
        &self.bodies
    }

    /// The law of every pair, left to right (the left wall's pair first).
    pub fn laws(&self) -> &[PairLaw] {
        &self.laws
    }

    /// The walls.
    pub fn walls(&self) -> Walls {
        self.walls
    }

    /// The settings.
    pub fn settings(&self) -> ChainSettings {
        self.settings
    }

    /// Number of pairs (neighbouring bodies, and a wall with its body).
    pub fn pairs(&self) -> usize {
        self.laws.len()
    }

    /// The bodies of pair `j` (left, right); `None` for a wall.
    pub fn pair_bodies(&self, j: usize) -> (Option<usize>, Option<usize>) {
        let shift = usize::from(self.walls.left.is_some());
        let left = (j >= shift).then(|| j - shift);
        let right = (j + 1 - shift < self.bodies.len()).then_some(j + 1 - shift);
        (left, right)
    }

    /// The gap of pair `j` at `t = 0` (m). A gap within the rounding of the faces' positions
    /// (8 ulps of the larger) is 0: bodies placed touching at `x_i = i d` stay touching.
    pub fn initial_gap(&self, j: usize) -> f64 {
        let face = |b: &ChainBody<I>, side: f64| b.position + side * b.length / 2.0;
        let (left, right) = self.pair_bodies(j);
        let l = left.map_or_else(
            || self.walls.left.unwrap_or(f64::NAN),
            |i| face(&self.bodies[i], 1.0),
        );
        let r = right.map_or_else(
            || self.walls.right.unwrap_or(f64::NAN),
            |i| face(&self.bodies[i], -1.0),
        );
        let gap = r - l;
        if gap.abs() <= 8.0 * f64::EPSILON * l.abs().max(r.abs()) {
            0.0
        } else {
            gap
        }
    }
}

//! Impact sequences: a body dropped onto a fixed surface bounces under gravity, free flight
//! between contacts and one impact of a collision model per contact.
//!
//! Heights are in m above the point where the last contact separated (positive up), speeds in
//! m/s, times in s from release. In flight the body obeys `h'' = -g - drag |h'| h'` (quadratic
//! air drag, `drag` in 1/m), whose rise and fall have closed forms ([`Flight`]). Each contact is
//! the caller's: a function of the impact speed (and, under [`Policy::Carry`], of the state the
//! last contact left) that simulates one impact with gravity as its input `u = -m g` and
//! returns a [`Contact`].
//!
//! ```
//! use bw_models::sequence::{drop_sequence, Contact, Flight, Policy, SequenceSettings, Start};
//! // A contact that returns 80 % of the speed after 1 ms.
//! let contact = |v_in: f64, _: Option<&()>| {
//!     Ok(Contact { t_s: Some(1e-3), v_out: 0.8 * v_in, settled: false, state: () })
//! };
//! let settings = SequenceSettings {
//!     flight: Flight { g: 9.81, drag: 0.0 },
//!     bounces: 3,
//!     policy: Policy::Reset,
//! };
//! let bounces = drop_sequence(Start::Height(1.0), &settings, contact)?;
//! // The first flight rises to e^2 h0.
//! assert!((bounces[0].apex - 0.64).abs() < 1e-12);
//! # Ok::<(), bw_models::ModelError>(())
//! ```

use crate::models::CollisionModel;
use crate::params::check;
use crate::{ModelError, State};
use bwc_ode::{Matrix, System};

/// Free flight under gravity `g` (m/s²) with quadratic air drag `drag` (1/m): acceleration
/// `-g - drag |v| v`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flight {
    /// Gravitational acceleration (m/s²), > 0.
    pub g: f64,
    /// Quadratic drag coefficient (1/m), >= 0.
    pub drag: f64,
}

/// One flight from the surface and back: rise to the apex, fall to the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// Height of the apex above the take-off point (m).
    pub apex: f64,
    /// Time from take-off to the apex (s).
    pub t_up: f64,
    /// Time from the apex back to the take-off height (s).
    pub t_down: f64,
    /// Speed on return (m/s).
    pub v_land: f64,
}

impl Default for Flight {
    /// Standard gravity, 9.81 m/s², and no drag (as a `[sequence]` scene's defaults).
    fn default() -> Self {
        Flight { g: 9.81, drag: 0.0 }
    }
}

impl Flight {
    /// `sqrt(g drag)` (1/s) and `sqrt(drag / g)` (s/m), the scales of the drag solutions.
    fn rates(&self) -> (f64, f64) {
        ((self.g * self.drag).sqrt(), (self.drag / self.g).sqrt())
    }

    /// The fall from rest through `h` (m): its time (s) and the speed reached (m/s).
    /// With drag: `t = acosh(e^(drag h)) / sqrt(g drag)`, `v = sqrt(g/drag) tanh(sqrt(g drag) t)`.
    pub fn fall(&self, h: f64) -> (f64, f64) {
        if self.drag == 0.0 {
            let t = (2.0 * h / self.g).sqrt();
            return (t, self.g * t);
        }
        let (w, _) = self.rates();
        let t = (self.drag * h).exp().acosh() / w;
        (t, (self.g / self.drag).sqrt() * (w * t).tanh())
    }

    /// The rise from the surface at speed `v` (m/s) to the apex and the fall back. With drag:
    /// `t_up = atan(v sqrt(drag/g)) / sqrt(g drag)`, apex `ln(1 + drag v²/g) / (2 drag)`.
    pub fn arc(&self, v: f64) -> Arc {
        if self.drag == 0.0 {
            let t = v / self.g;
            return Arc {
                apex: 0.5 * v * v / self.g,
                t_up: t,
                t_down: t,
                v_land: v,
            };
        }
        let (w, s) = self.rates();
        let apex = (self.drag * v * v / self.g).ln_1p() / (2.0 * self.drag);
        let (t_down, v_land) = self.fall(apex);
        Arc {
            apex,
            t_up: (v * s).atan() / w,
            t_down,
            v_land,
        }
    }

    /// Height (m) above the take-off point at time `t` (s) after leaving it at speed `v` on
    /// the arc `arc` (`t` within `[0, t_up + t_down]`).
    pub fn height(&self, v: f64, arc: &Arc, t: f64) -> f64 {
        if self.drag == 0.0 {
            return v * t - 0.5 * self.g * t * t;
        }
        let (w, _) = self.rates();
        if t <= arc.t_up {
            // h = ln(cos(w (t_up - t)) / cos(w t_up)) / drag
            ((w * (arc.t_up - t)).cos() / (w * arc.t_up).cos()).ln() / self.drag
        } else {
            arc.apex - (w * (t - arc.t_up)).cosh().ln() / self.drag
        }
    }

    fn validate(&self) -> Result<(), ModelError> {
        check("g", self.g, self.g > 0.0, "g > 0 (m/s^2)")?;
        check("drag", self.drag, self.drag >= 0.0, "drag >= 0 (1/m)")
    }
}

/// What the law's state is at the onset of the next contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Policy {
    /// At rest: each contact starts from `x = z = 0` where the last one separated.
    Reset,
    /// Carried over: the residual deformation and `z` of the last separation, the contact
    /// resuming when the body returns to the separation point.
    Carry,
}

/// Settings of a sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SequenceSettings {
    /// Gravity and drag in flight.
    pub flight: Flight,
    /// Most contacts to simulate (the sequence ends earlier when the body comes to rest).
    pub bounces: usize,
    /// The law's state at each new contact.
    pub policy: Policy,
}

impl Default for SequenceSettings {
    /// A `[sequence]` scene's defaults: [`Flight::default`], 10 bounces, [`Policy::Reset`].
    fn default() -> Self {
        SequenceSettings {
            flight: Flight::default(),
            bounces: 10,
            policy: Policy::Reset,
        }
    }
}

/// How the body starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Start {
    /// Dropped from rest at this height (m) above the surface.
    Height(f64),
    /// Arriving at the surface with this speed (m/s) at `t = 0`.
    Speed(f64),
}

/// What one contact gave: the caller's simulation of an impact, with the state `S` it hands to
/// the next contact under [`Policy::Carry`] (`()` where nothing carries over).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact<S> {
    /// Contact duration (s), `None` without separation (settled, or the horizon).
    pub t_s: Option<f64>,
    /// Speed at separation (m/s, upwards), 0 without separation.
    pub v_out: f64,
    /// Without separation: whether the contact came to rest (else its horizon came first).
    pub settled: bool,
    /// The law's state at separation, carried to the next contact under [`Policy::Carry`].
    pub state: S,
}

/// How a bounce ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BounceEnd {
    /// The body left the surface again.
    Separated,
    /// The body came to rest on the surface (no separation, or a rebound too small to fly).
    Settled,
    /// The contact's simulation reached its horizon without separation.
    Horizon,
}

/// One contact of a sequence and the flight after it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounce {
    /// Number of the contact, from 1.
    pub n: usize,
    /// Onset of the contact (s from release).
    pub t_contact: f64,
    /// Impact speed (m/s).
    pub v_in: f64,
    /// Rebound speed (m/s), 0 without separation.
    pub v_out: f64,
    /// Coefficient of restitution `v_out / v_in`.
    pub e: f64,
    /// Contact duration (s), `None` without separation.
    pub t_s: Option<f64>,
    /// Height (m) of the next flight's top above the separation point (0 without one).
    pub apex: f64,
    /// Time (s) from this contact's onset to the next one's; `None` for the last contact.
    pub interval: Option<f64>,
    /// How the contact ended.
    pub end: BounceEnd,
}

/// A rebound slower than this fraction of the first impact speed does not fly: the body has
/// come to rest (the next contact would start at rest, where `v0 > 0` fails).
pub const REST_FRACTION: f64 = 1e-9;

/// Simulates the sequence: the first contact after `start`, then flights and contacts until
/// `settings.bounces` contacts or rest. `contact(v_in, carried)` simulates one impact at speed
/// `v_in` (m/s), from the state `carried` of the last separation under [`Policy::Carry`]
/// (`None` for the first contact and under [`Policy::Reset`]).
///
/// # Errors
/// [`ModelError::InvalidParameter`] / [`ModelError::InvalidSetting`] for a non-positive height,
/// speed or `g`, a negative or non-finite drag, or no bounces; the first error of `contact`.
pub fn drop_sequence<S>(
    start: Start,
    settings: &SequenceSettings,
    mut contact: impl FnMut(f64, Option<&S>) -> Result<Contact<S>, ModelError>,
) -> Result<Vec<Bounce>, ModelError> {
    let flight = settings.flight;
    flight.validate()?;
    if settings.bounces == 0 {
        return Err(ModelError::InvalidSetting {
            name: "bounces",
            value: 0.0,
            allowed: "bounces >= 1",
        });
    }
    let (mut t, mut v_in) = match start {
        Start::Height(h0) => {
            check("h0", h0, h0 > 0.0, "h0 > 0 (m)")?;
            flight.fall(h0)
        }
        Start::Speed(v0) => {
            check("v0", v0, v0 > 0.0, "v0 > 0 (m/s)")?;
            (0.0, v0)
        }
    };
    let rest = REST_FRACTION * v_in;
    let mut carried: Option<S> = None;
    let mut out: Vec<Bounce> = Vec::with_capacity(settings.bounces);
    for n in 1..=settings.bounces {
        let c = contact(v_in, carried.as_ref())?;
        let (t_s, v_out) = (c.t_s, c.v_out);
        let flies = t_s.is_some() && v_out > rest;
        let end = match t_s {
            Some(_) if flies => BounceEnd::Separated,
            None if !c.settled => BounceEnd::Horizon,
            _ => BounceEnd::Settled,
        };
        let arc = flies.then(|| flight.arc(v_out));
        let last = n == settings.bounces || !flies;
        let interval = match (&arc, last) {
            (Some(a), false) => Some(t_s.unwrap_or(0.0) + a.t_up + a.t_down),
            _ => None,
        };
        out.push(Bounce {
            n,
            t_contact: t,
            v_in,
            v_out,
            e: v_out / v_in,
            t_s,
            apex: arc.map_or(0.0, |a| a.apex),
            interval,
            end,
        });
        let (Some(a), Some(dt)) = (arc, interval) else {
            break;
        };
        t += dt;
        v_in = a.v_land;
        if settings.policy == Policy::Carry {
            carried = Some(c.state);
        }
    }
    Ok(out)
}

/// A model whose contact starts from a given state instead of the unloaded one: the next
/// contact of a [`Policy::Carry`] sequence (residual deformation and `z` of the last
/// separation, velocity `-v0`). Everything else is the inner model's.
#[derive(Debug, Clone, Copy)]
pub struct Resumed<M, const N: usize> {
    /// The model.
    pub model: M,
    /// The state at the onset of contact, in the model's variables.
    pub start: State<N>,
}

impl<M: CollisionModel<N>, const N: usize> System<N> for Resumed<M, N> {
    fn rhs(&self, t: f64, y: &State<N>) -> State<N> {
        self.model.rhs(t, y)
    }
}

impl<M: CollisionModel<N>, const N: usize> CollisionModel<N> for Resumed<M, N> {
    fn initial_state(&self) -> State<N> {
        self.start
    }
    fn force(&self, y: &State<N>) -> f64 {
        self.model.force(y)
    }
    fn displacement(&self, y: &State<N>) -> f64 {
        self.model.displacement(y)
    }
    fn velocity(&self, y: &State<N>) -> f64 {
        self.model.velocity(y)
    }
    fn input(&self, t: f64) -> f64 {
        self.model.input(t)
    }
    fn input_constant_after(&self) -> Option<f64> {
        self.model.input_constant_after()
    }
    fn impact_speed(&self) -> f64 {
        self.model.impact_speed()
    }
    fn state_scale(&self) -> State<N> {
        self.model.state_scale()
    }
    fn time_scale(&self) -> f64 {
        self.model.time_scale()
    }
    fn kinks(&self, t: f64, y: &State<N>) -> [f64; 2] {
        self.model.kinks(t, y)
    }
    fn clearance(&self, y: &State<N>, f: &State<N>, rtol: f64) -> f64 {
        self.model.clearance(y, f, rtol)
    }
    fn jacobian(&self, t: f64, y: &State<N>) -> Matrix<N> {
        self.model.jacobian(t, y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flights_with_drag_match_their_differential_equation() {
        let f = Flight {
            g: 9.81,
            drag: 0.05,
        };
        let v = 7.0;
        let arc = f.arc(v);
        // Integrate h'' = -g - drag |h'| h' by small explicit steps (RK4) as an independent check.
        let steps = 200_000;
        let (mut h, mut w, dt) = (0.0f64, v, (arc.t_up + arc.t_down) / f64::from(steps));
        let acc = |w: f64| -f.g - f.drag * w.abs() * w;
        let mut t = 0.0;
        let mut apex = 0.0f64;
        for _ in 0..steps {
            let k1 = (w, acc(w));
            let k2 = (w + 0.5 * dt * k1.1, acc(w + 0.5 * dt * k1.1));
            let k3 = (w + 0.5 * dt * k2.1, acc(w + 0.5 * dt * k2.1));
            let k4 = (w + dt * k3.1, acc(w + dt * k3.1));
            h += dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            w += dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            t += dt;
            apex = apex.max(h);
            let closed = f.height(v, &arc, t);
            assert!((closed - h).abs() < 1e-9, "t {t}: {closed} vs {h}");
        }
        assert!(
            (apex - arc.apex).abs() < 1e-7 && h.abs() < 1e-9,
            "{apex} {h}"
        );
        assert!((w + arc.v_land).abs() < 1e-9, "{w} vs {}", arc.v_land);
        // Without drag the arc is the parabola.
        let a = Flight { g: 9.81, drag: 0.0 }.arc(v);
        assert_eq!(a.apex, 0.5 * v * v / 9.81);
        assert_eq!((a.t_up, a.v_land), (v / 9.81, v));
    }

    #[test]
    fn a_body_at_rest_ends_the_sequence() {
        let settings = SequenceSettings {
            flight: Flight { g: 9.81, drag: 0.0 },
            bounces: 10,
            policy: Policy::Reset,
        };
        let contact = |v: f64, _: Option<&()>| {
            Ok(Contact {
                t_s: if v > 1.0 { Some(1e-3) } else { None },
                v_out: if v > 1.0 { 0.5 * v } else { 0.0 },
                settled: false,
                state: (),
            })
        };
        let b = drop_sequence(Start::Speed(3.0), &settings, contact).unwrap();
        assert_eq!(b.len(), 3);
        assert_eq!(b[2].end, BounceEnd::Horizon);
        assert!(b[2].interval.is_none() && b[1].interval.is_some());
        let bad = drop_sequence(Start::Height(-1.0), &settings, contact);
        assert!(matches!(
            bad,
            Err(ModelError::InvalidParameter { name: "h0", .. })
        ));
    }
}

//! The runs of `[sequence]` scenes: repeated impacts of a `[physical]` body on a fixed surface
//! under gravity ([`bw_models::sequence`]), each contact an impact with input `u = -m g`.

use crate::impact::runs::{hint, scaling, Bounced, Outcome, Run};
use crate::impact::scene::{SequenceSpec, System, SystemSpec};
use bw_models::input::{Constant, Scaled};
use bw_models::sequence::{drop_sequence, BounceEnd, Contact, Resumed};
use bw_models::{
    impact, Bwmcm, Bwshccm, CollisionModel, ModelError, ModelKind, Ndbwmcm, Ndbwshccm, Settings,
    State,
};

/// How a contact's model units map to SI at an impact speed: seconds per time unit and metres
/// per displacement unit (1 and 1 for `[physical]` models; `T_c` and `X_c = v0 T_c` for
/// `[base]` models at that speed).
type Units<'a> = dyn Fn(f64) -> (f64, f64) + 'a;

/// One contact of `model` from its unloaded state, or from `carried` (the state of the last
/// separation at the speed it had, its displacements rescaled to this contact's units and the
/// velocity set to the impact's); the contact in SI units (s, m/s) and the displacement (m)
/// at separation.
fn contact<M: CollisionModel<N>, const N: usize>(
    model: M,
    v_in: f64,
    carried: Option<&(State<N>, f64)>,
    settings: &Settings,
    units: &Units<'_>,
) -> Result<(Contact<(State<N>, f64)>, f64), ModelError> {
    let (to_s, to_m) = units(v_in);
    let (out, x_s) = match carried {
        None => {
            let out = impact(&model, settings)?;
            (out, model.displacement(&out.state))
        }
        Some((s, v_old)) => {
            let ratio = units(*v_old).1 / to_m;
            let mut start = *s * ratio;
            start[N - 1] = model.initial_state()[N - 1];
            let resumed = Resumed { model, start };
            let out = impact(&resumed, settings)?;
            (out, resumed.displacement(&out.state))
        }
    };
    let contact = Contact {
        t_s: out.t_s.map(|t| t * to_s),
        v_out: out.e * v_in,
        settled: out.settled_at.is_some(),
        state: (out.state, v_in),
    };
    Ok((contact, x_s * to_m))
}

/// The sequence of contacts made by `make(v_in)` in `units`.
fn sequence_of<M: CollisionModel<N>, const N: usize>(
    seq: &SequenceSpec,
    settings: &Settings,
    units: &Units<'_>,
    make: impl Fn(f64) -> Result<M, ModelError>,
) -> Result<Vec<Bounced>, ModelError> {
    let mut displacements = Vec::new();
    let one = |v_in: f64, carried: Option<&(State<N>, f64)>| {
        let (c, x_s) = contact(make(v_in)?, v_in, carried, settings, units)?;
        displacements.push(x_s);
        Ok(c)
    };
    let list = drop_sequence(seq.start, &seq.settings, one)?;
    Ok(list.into_iter().zip(displacements).collect())
}

/// The sequence of `spec` (a `[physical]` system, or `[base]` with `[sequence].m`; the scene's
/// parsing guarantees it).
///
/// # Errors
/// The first failed contact's [`ModelError`].
pub fn bounces(
    spec: &SystemSpec,
    seq: &SequenceSpec,
    settings: &Settings,
) -> Result<Vec<Bounced>, ModelError> {
    let g = seq.settings.flight.g;
    match &spec.system {
        System::Physical { params, m, .. } => {
            let input = Constant(-m * g);
            let si = |_: f64| (1.0, 1.0);
            match spec.kind {
                ModelKind::Shccm => {
                    sequence_of(seq, settings, &si, |v| Bwshccm::new(params, *m, v, input))
                }
                ModelKind::Mcm => {
                    sequence_of(seq, settings, &si, |v| Bwmcm::new(params, *m, v, input))
                }
            }
        }
        System::Base { map, .. } => {
            let m = seq.m.expect("[base] sequences have a mass");
            let units = |v: f64| {
                let t_c = map.time_scale(v);
                (t_c, v * t_c)
            };
            let input = |v: f64| -> Result<_, ModelError> {
                let (nd, s) = map.at(v)?;
                let u = Scaled {
                    inner: Constant(-m * g),
                    factor: s.factor,
                    time_scale: s.time_scale,
                };
                Ok((nd, u))
            };
            match spec.kind {
                ModelKind::Shccm => sequence_of(seq, settings, &units, |v| {
                    let (nd, u) = input(v)?;
                    Ndbwshccm::new(&nd, u)
                }),
                ModelKind::Mcm => sequence_of(seq, settings, &units, |v| {
                    let (nd, u) = input(v)?;
                    Ndbwmcm::new(&nd, u)
                }),
            }
        }
        _ => unreachable!("[sequence] scenes have a [physical] or [base] system"),
    }
}

/// The run of a `[sequence]` scene: its first contact's `e`, `t_s` and scales, the outcome of
/// its last contact, and every bounce.
pub fn run(spec: &SystemSpec, seq: &SequenceSpec, settings: &Settings) -> Run {
    let mut run = Run::new(spec, None, "s");
    match bounces(spec, seq, settings) {
        Ok(list) => {
            let (first, last) = (list[0].0, list[list.len() - 1].0);
            run.v0 = Some(first.v_in);
            run.e = first.e;
            run.t_s = first.t_s;
            run.t_d = first.t_s;
            run.outcome = match last.end {
                BounceEnd::Separated => Outcome::Separated,
                BounceEnd::Settled => Outcome::Settled,
                BounceEnd::Horizon => Outcome::Horizon,
            };
            if let Ok(s) = scaling(spec, Some(first.v_in)) {
                run.t_c = s.t_c;
                run.nondimensional = Some(s.nondimensional);
            }
            run.bounces = list;
        }
        Err(e) => {
            run.outcome = Outcome::Failed;
            run.error = Some(format!("{e}; {}", hint(&e, settings)));
        }
    }
    run
}

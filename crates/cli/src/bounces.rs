//! The runs of `[sequence]` scenes: repeated impacts of a `[physical]` body on a fixed surface
//! under gravity ([`bw_models::sequence`]), each contact an impact with input `u = -m g`.

use crate::scene::{SequenceSpec, System, SystemSpec};
use crate::simulate::{Outcome, Run};
use bw_models::input::Constant;
use bw_models::sequence::{drop_sequence, Bounce, BounceEnd, Contact, Resumed};
use bw_models::{
    impact, nondimensionalize, Bwmcm, Bwshccm, CollisionModel, ModelError, ModelKind,
    PhysicalParams, Settings, State,
};

/// One contact of `model` from its unloaded state, or from `carried` (the state of the last
/// separation, the velocity set to the impact's), and the displacement (m) at separation.
fn contact<M: CollisionModel<N>, const N: usize>(
    model: M,
    carried: Option<&State<N>>,
    settings: &Settings,
) -> Result<(Contact<State<N>>, f64), ModelError> {
    let v_in = model.impact_speed();
    let (out, x_s) = match carried {
        None => {
            let out = impact(&model, settings)?;
            (out, model.displacement(&out.state))
        }
        Some(s) => {
            let mut start = *s;
            start[N - 1] = model.initial_state()[N - 1];
            let resumed = Resumed { model, start };
            let out = impact(&resumed, settings)?;
            (out, resumed.displacement(&out.state))
        }
    };
    let contact = Contact {
        t_s: out.t_s,
        v_out: out.e * v_in,
        settled: out.settled_at.is_some(),
        state: out.state,
    };
    Ok((contact, x_s))
}

/// A bounce and the displacement (m) at its separation.
pub type Bounced = (Bounce, f64);

/// The sequence of contacts made by `make(v_in)`.
fn sequence_of<M: CollisionModel<N>, const N: usize>(
    seq: &SequenceSpec,
    settings: &Settings,
    make: impl Fn(f64) -> Result<M, ModelError>,
) -> Result<Vec<Bounced>, ModelError> {
    let mut displacements = Vec::new();
    let one = |v_in: f64, carried: Option<&State<N>>| {
        let (c, x_s) = contact(make(v_in)?, carried, settings)?;
        displacements.push(x_s);
        Ok(c)
    };
    let list = drop_sequence(seq.start, &seq.settings, one)?;
    Ok(list.into_iter().zip(displacements).collect())
}

/// The sequence of `spec` (a `[physical]` system; the scene's parsing guarantees it).
///
/// # Errors
/// The first failed contact's [`ModelError`].
pub fn bounces(
    spec: &SystemSpec,
    seq: &SequenceSpec,
    settings: &Settings,
) -> Result<Vec<Bounced>, ModelError> {
    let System::Physical { params, m, .. } = &spec.system else {
        unreachable!("[sequence] scenes have a [physical] system");
    };
    let input = Constant(-m * seq.settings.flight.g);
    match spec.kind {
        ModelKind::Shccm => sequence_of(seq, settings, |v| Bwshccm::new(params, *m, v, input)),
        ModelKind::Mcm => sequence_of(seq, settings, |v| Bwmcm::new(params, *m, v, input)),
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
            if let System::Physical { params, m, .. } = &spec.system {
                scales(&mut run, params, *m, first.v_in);
            }
            run.bounces = list;
        }
        Err(e) => {
            run.outcome = Outcome::Failed;
            run.error = Some(format!("{e}; {}", crate::simulate::hint(&e, settings)));
        }
    }
    run
}

/// `T_c` and the nondimensional parameters of the first contact.
fn scales(run: &mut Run, params: &PhysicalParams, m: f64, v0: f64) {
    if let Ok((nd, s)) = nondimensionalize(params, m, v0) {
        run.t_c = Some(s.t_c);
        run.nondimensional = Some(*nd.get());
    }
}

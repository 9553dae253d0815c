//! The crate's fast paths of a CoR evaluation, taken through a built-in model's nondimensional
//! form ([`NdForm`](crate::models::form::NdForm)): the Taylor series ([`Settings::series`]), the phase path
//! ([`Settings::phase`]) and the double-double path ([`Settings::double_double`]). Each runs
//! the nondimensional model (eq:EBWSHCCM_nd, eq:EBWMCM_nd) and returns its result in the units
//! of the model it was asked for ([`Impact::in_units`]): an SI model's input `u(t)` enters as
//! `U(T) = u(T_c T) T_c² / (m X_c)` and its times and states leave scaled by Table 1.

use crate::double_double;
use crate::input::{Constant, Scaled, Zero};
use crate::models::{CollisionModel, Ndbwmcm, Ndbwshccm};
use crate::outcome::DdFailure;
use crate::outcome::Impact;
use crate::params::{ModelKind, NondimParams};
use crate::phase;
use crate::series::{self, SeriesRun};
use crate::settings::Settings;
use bwc_ode::{Extrapolation, State};

/// The series path of `model` under a constant input; `None` where the model has no
/// nondimensional form, its input varies, or the series decline at contact.
pub(crate) fn series<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
) -> Option<SeriesRun<N>> {
    let form = model.nondimensional_form()?;
    if !form.input.is_constant() {
        return None;
    }
    let u = form.input.at(0.0);
    let u = Constant(form.scales.map_or(u, |s| u * s.u_factor));
    Some(match form.kind {
        ModelKind::Shccm => {
            series_in_units(model, series::impact(&Ndbwshccm::of(form.k, u), settings)?)
        }
        ModelKind::Mcm => {
            series_in_units(model, series::impact(&Ndbwmcm::of(form.k, u), settings)?)
        }
    })
}

/// The phase path of `model` with no input ([`phase`]): the impact where the path applies and
/// its check (if any) is met, `None` otherwise.
pub(crate) fn phase<M: CollisionModel<N>, const N: usize>(
    model: &M,
    settings: &Settings,
) -> Option<Impact<N>> {
    let form = model.nondimensional_form()?;
    if !form.input.is_zero() {
        return None;
    }
    let params = NondimParams::new(form.kind, form.k.nondim()).ok()?;
    let cor = phase::for_impact(&params, &Zero, settings)?;
    // The state `(R, Y, Z, V)` (the NDBWSHCCM's `(X, Z, V)` is its last three): with no input
    // `R' = -σF = -σV'`, so `R = -σ (V + 1)` from `V(0) = -1`.
    let r = -form.k.sigma * (cor.e + 1.0);
    let state = restate(&[r, cor.q_s, cor.z_s, cor.e]);
    Some(in_units(model, phase::impact_of(&cor, state, settings)))
}

/// One run of the double-double path of `model` at `ext`'s tolerances, with
/// `settings.max_steps` and `settings.t_max`; `None` where the model has no nondimensional
/// form or its input no double-double form ([`Input::at_dd`](crate::input::Input::at_dd)).
pub(crate) fn double_double<M: CollisionModel<N>, const N: usize>(
    model: &M,
    ext: Extrapolation,
    settings: &Settings,
) -> Option<Result<Impact<N>, DdFailure>> {
    let form = model.nondimensional_form()?;
    let (kind, k) = (form.kind, form.k.nondim());
    let state_of = |y: [f64; 4]| restate(&y);
    let run = match form.scales {
        None => double_double::run_model((kind, k, form.input), ext, settings, state_of)?,
        Some(s) => {
            let u = Scaled {
                inner: form.input,
                factor: s.u_factor,
                time_scale: s.t_c,
            };
            double_double::run_model((kind, k, &u), ext, settings, state_of)?
        }
    };
    Some(run.map(|out| in_units(model, out)))
}

/// A nondimensional form's impact in `model`'s units (for a nondimensional model the scales
/// are ones, and the products exact).
fn in_units<M: CollisionModel<N>, const N: usize>(model: &M, out: Impact<N>) -> Impact<N> {
    out.in_units(&model.state_scale(), model.time_scale())
}

/// The last `N` of the components `(R, Y, Z, V)`: the state of the model with `N` states (the
/// NDBWSHCCM's `(X, Z, V)`, the NDBWMCM's `(R, Y, Z, V)`).
fn restate<const N: usize>(y: &[f64]) -> State<N> {
    State::<N>::from_column_slice(&y[y.len() - N..])
}

/// A series run of the nondimensional model with `A` states as the run of `model`, with `N`
/// states (`A = N`: an NDBWSHCCM form has 3 states, an NDBWMCM form 4), in `model`'s units.
fn series_in_units<M: CollisionModel<N>, const A: usize, const N: usize>(
    model: &M,
    run: SeriesRun<A>,
) -> SeriesRun<N> {
    match run {
        SeriesRun::Done(out) => {
            let out = Impact::from_cor(out.cor(), restate(out.state.as_slice()));
            SeriesRun::Done(in_units(model, out))
        }
        SeriesRun::HandOver {
            t,
            state,
            stats,
            series_steps,
        } => SeriesRun::HandOver {
            t: t * model.time_scale(),
            state: restate::<N>(state.as_slice()).component_mul(&model.state_scale()),
            stats,
            series_steps,
        },
    }
}

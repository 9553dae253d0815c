//! Contact that never ends: under an input that pushes the bodies together and is constant
//! (from some time on), the run stops once the state is at rest, an equilibrium with the force
//! balancing the input, and reports no separation.

use bw_models::input::{Arctan, Constant, Scaled, Table};
use bw_models::{impact, ModelKind, Ndbwshccm, Nondim, NondimParams, Settings};

fn params() -> NondimParams {
    let p = Nondim {
        b: 1.0,
        gamma: -0.5,
        kappa: 0.6,
        sigma: 0.8,
        n: 1.5,
        p: 1.5,
    };
    NondimParams::new(ModelKind::Shccm, p).unwrap()
}

/// A constant push U = -2 (stronger than the rebound): the contact settles at V = 0 with
/// F = -U = 2, long before the horizon.
#[test]
fn constant_push_settles_at_the_force_balance() {
    let m = Ndbwshccm::new(&params(), Constant(-2.0)).unwrap();
    let out = impact(&m, &Settings::default()).unwrap();
    let t = out.settled_at.expect("settled");
    assert!(out.t_s.is_none() && out.e == 0.0);
    assert!(t < 200.0, "settled only at {t}");
    let (x, z, v) = (out.state[0], out.state[1], out.state[2]);
    assert!(v.abs() < 1e-10, "V = {v}");
    let force = -0.6 * x.abs().powf(1.5).copysign(x) - 0.4 * z.abs().powf(1.5).copysign(z);
    assert!((force - 2.0).abs() < 1e-9, "F = {force}");
}

/// A table that ramps the push up over T in [0, 5] and then holds it: the settling check starts
/// at the table's last time (the input is constant from there on); an arctan ramp never
/// becomes exactly constant, so that run goes to the horizon.
#[test]
fn inputs_constant_from_some_time_settle_too() {
    let ramp = Table::new(&[(0.0, 0.0), (5.0, -2.0)]).unwrap();
    let m = Ndbwshccm::new(&params(), ramp).unwrap();
    let out = impact(&m, &Settings::default()).unwrap();
    let t = out.settled_at.expect("settled after the ramp");
    assert!((5.0..200.0).contains(&t), "settled at {t}");
    // The same through a time scale (as a physical input is seen by a nondimensional model).
    let table = Table::new(&[(0.0, 0.0), (0.05, -2.0)]).unwrap();
    let scaled = Scaled {
        inner: table,
        factor: 1.0,
        time_scale: 0.01,
    };
    let out = impact(
        &Ndbwshccm::new(&params(), scaled).unwrap(),
        &Settings::default(),
    )
    .unwrap();
    assert!(out.settled_at.expect("settled") >= 5.0);
    let arctan = Arctan {
        m: 1.0,
        d: -2.0,
        omega: 1.0,
    };
    let settings = Settings {
        t_max: 300.0,
        e_tol: None,
        ..Settings::default()
    };
    let out = impact(&Ndbwshccm::new(&params(), arctan).unwrap(), &settings).unwrap();
    assert!(out.t_s.is_none() && out.settled_at.is_none());
}

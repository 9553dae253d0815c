//! The SI models (BWSHCCM, BWMCM): agreement with their nondimensional forms through Table 1,
//! the published Cross loops (Table 4), two bodies under constant forces, and Section 6's two
//! balls.

use super::*;

/// Peak force over a grid of `samples` points per unit of natural time.
fn run_with_peak<M: CollisionModel<N>, const N: usize>(m: &M, s: &Settings, dt: f64) -> (Cor, f64) {
    let mut peak = f64::NEG_INFINITY;
    let out = simulate(m, s, Sampling::Grid { dt }, |_t, y| {
        peak = peak.max(m.force(y))
    })
    .unwrap();
    (out.cor(), peak)
}

/// SI vs nondimensional: the same t_s, e and peak force both ways (to 1e-9 relative).
#[test]
fn si_and_nondimensional_agree_on_cross_parameters() {
    let s = Settings::default();
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let params = cross(kind);
        for v0 in CROSS_SPEEDS {
            let (ndp, sc) = nondimensionalize(&params, BASEBALL_MASS, v0).unwrap();
            let ((si, si_peak), (nd_out, nd_peak)) = match kind {
                ModelKind::Shccm => (
                    run_with_peak(
                        &Bwshccm::new(&params, BASEBALL_MASS, v0, Zero).unwrap(),
                        &s,
                        0.01 * sc.t_c,
                    ),
                    run_with_peak(&Ndbwshccm::new(&ndp, Zero).unwrap(), &s, 0.01),
                ),
                ModelKind::Mcm => (
                    run_with_peak(
                        &Bwmcm::new(&params, BASEBALL_MASS, v0, Zero).unwrap(),
                        &s,
                        0.01 * sc.t_c,
                    ),
                    run_with_peak(&Ndbwmcm::new(&ndp, Zero).unwrap(), &s, 0.01),
                ),
            };
            let (ts_si, ts_nd) = (si.t_s.unwrap(), nd_out.t_s.unwrap() * sc.t_c);
            assert!(
                (ts_si - ts_nd).abs() < 1e-9 * ts_nd,
                "{kind:?} {v0}: t_s {ts_si} vs {ts_nd}"
            );
            assert!(
                (si.e - nd_out.e).abs() < 1e-9,
                "{kind:?} {v0}: e {} vs {}",
                si.e,
                nd_out.e
            );
            let nd_peak_si = nd_peak * sc.force();
            assert!(
                (si_peak - nd_peak_si).abs() < 1e-9 * nd_peak_si,
                "{kind:?} {v0}: F {si_peak} vs {nd_peak_si}"
            );
            // Plausibility against the published loops (Fig. 7 / fixtures): hundreds of N to kN,
            // contact lasting a few hundred microseconds.
            assert!(
                si_peak > 500.0 && si_peak < 5000.0 && ts_si > 1e-4 && ts_si < 2e-3,
                "{kind:?} {v0}: {si_peak} N, {ts_si} s"
            );
        }
    }
}

/// `e`, `t_s` and the series steps of a separated impact.
fn brief<const N: usize>(out: Result<Impact<N>, ModelError>) -> (f64, f64, u64) {
    let out = out.unwrap();
    (out.e, out.t_s.expect("separated"), out.series_steps)
}

/// A CoR of an SI model under a constant input is the series run of its nondimensional model
/// (Table 1): the same `e` bit for bit and `t_s = T_c T_s`; it agrees with the Runge-Kutta path
/// at tight tolerances; under an input that varies, the Runge-Kutta path runs as before.
#[test]
fn si_cor_evaluations_take_the_series_path_of_their_nondimensional_model() {
    let s = Settings::default();
    let rk = Settings {
        rtol: 1e-13,
        atol: 1e-15,
        series: false,
        e_tol: None,
        ..Settings::default()
    };
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let params = cross(kind);
        for (v0, u) in CROSS_SPEEDS.iter().zip([0.0, -20.0, 5.0, -50.0]) {
            let (ndp, sc) = nondimensionalize(&params, BASEBALL_MASS, *v0).unwrap();
            let input = Constant(u);
            let nd_input = Constant(u * sc.u_factor);
            let (si, nd, reference) = match kind {
                ModelKind::Shccm => {
                    let m = Bwshccm::new(&params, BASEBALL_MASS, *v0, input).unwrap();
                    let n = Ndbwshccm::new(&ndp, nd_input).unwrap();
                    (
                        brief(impact(&m, &s)),
                        brief(impact(&n, &s)),
                        brief(impact(&m, &rk)),
                    )
                }
                ModelKind::Mcm => {
                    let m = Bwmcm::new(&params, BASEBALL_MASS, *v0, input).unwrap();
                    let n = Ndbwmcm::new(&ndp, nd_input).unwrap();
                    (
                        brief(impact(&m, &s)),
                        brief(impact(&n, &s)),
                        brief(impact(&m, &rk)),
                    )
                }
            };
            assert!(si.2 > 0, "{kind:?} {v0}: no series steps");
            assert_eq!(si.0, nd.0, "{kind:?} {v0}");
            assert_eq!(si.1, nd.1 * sc.t_c, "{kind:?} {v0}");
            assert!(
                (si.0 - reference.0).abs() < 1e-10,
                "{kind:?} {v0}: {si:?} vs {reference:?}"
            );
            assert!(
                (si.1 - reference.1).abs() < 1e-10 * reference.1,
                "{kind:?} {v0}"
            );
        }
    }
    let varying = Arctan {
        m: BASEBALL_MASS,
        d: 10.0,
        omega: 1e4,
    };
    let params = cross(ModelKind::Shccm);
    let m = Bwshccm::new(&params, BASEBALL_MASS, 3.0, varying).unwrap();
    let out = impact(&m, &s).unwrap();
    assert_eq!(out.series_steps, 0);
    assert!(out.separated());
}

/// Two bodies under constant forces: the relative input is constant (from the later of the
/// two inputs' constant times), so their CoR takes the series path and agrees with the
/// Runge-Kutta path; a ramp on either body makes it vary.
#[test]
fn two_bodies_under_constant_forces_take_the_series_path() {
    let (m1, m2) = (0.4, 0.2);
    let bodies = Bodies::new(m1, m2, -0.5, 1.5, 0.05, 0.05, Constant(-3.0), Constant(2.0)).unwrap();
    let u = bodies.relative_input();
    assert!(
        input::Input::is_constant(&u)
            && input::Input::constant_after(&u) == Some(f64::NEG_INFINITY)
    );
    let ramp = Arctan {
        m: m2,
        d: 250.0,
        omega: 1e3,
    };
    let ramped = Bodies::new(m1, m2, -0.5, 1.5, 0.05, 0.05, Constant(-3.0), ramp).unwrap();
    assert!(!input::Input::is_constant(&ramped.relative_input()));
    let rk = Settings {
        rtol: 1e-13,
        atol: 1e-15,
        series: false,
        e_tol: None,
        ..Settings::default()
    };
    let params = cross(ModelKind::Shccm);
    let m = Bwshccm::new(&params, bodies.effective_mass(), bodies.impact_speed(), u).unwrap();
    let (fast, reference) = (
        brief(impact(&m, &Settings::default())),
        brief(impact(&m, &rk)),
    );
    assert!(fast.2 > 0, "no series steps");
    assert!(
        (fast.0 - reference.0).abs() < 1e-10,
        "{fast:?} vs {reference:?}"
    );
}

/// The Cross loops in fixtures/ were produced with the BWSHCCM at the published parameters:
/// the force at the loop's maximum compression and the compression itself must match.
#[test]
fn cross_fixture_loops_match_the_bwshccm() {
    let params = cross(ModelKind::Shccm);
    for (v0, file) in [
        (2.15, "cross_2_15.csv"),
        (3.03, "cross_3_03.csv"),
        (4.18, "cross_4_18.csv"),
        (5.02, "cross_5_02.csv"),
    ] {
        let path = format!("{}/../../fixtures/data/{file}", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).unwrap();
        let rows: Vec<(f64, f64)> = text
            .lines()
            .filter(|l| !l.starts_with('#') && !l.starts_with('x'))
            .map(|l| {
                let mut it = l.split(',').map(|v| v.trim().parse::<f64>().unwrap());
                (it.next().unwrap(), it.next().unwrap())
            })
            .collect();
        let (xmax_mm, fmax) = rows
            .iter()
            .fold((0.0f64, 0.0f64), |a, r| (a.0.max(r.0), a.1.max(r.1)));
        let m = Bwshccm::new(&params, BASEBALL_MASS, v0, Zero).unwrap();
        let mut peak_f = 0.0f64;
        let mut peak_x = 0.0f64;
        let out = simulate(
            &m,
            &Settings::default(),
            Sampling::Grid { dt: 1e-7 },
            |_t, y| {
                peak_f = peak_f.max(m.force(y));
                peak_x = peak_x.max(-y[0] * 1e3);
            },
        )
        .unwrap();
        assert!(out.separated());
        assert!(
            (peak_x - xmax_mm).abs() < 2e-3 * xmax_mm,
            "{file}: max compression {peak_x} mm vs {xmax_mm}"
        );
        assert!(
            (peak_f - fmax).abs() < 2e-3 * fmax,
            "{file}: peak force {peak_f} N vs {fmax}"
        );
    }
}

/// Section 3, Table 2 (tab:AE): two balls in a pipe; effective mass, relative input, impact
/// speed, and the per-body motion conserving momentum under the external forces.
#[test]
fn two_balls_section_6() {
    let a: f64 = 0.05;
    let vol = 4.0 / 3.0 * std::f64::consts::PI * a.powi(3);
    let (m1, m2, g, d, omega) = (3e3 * vol, 1e3 * vol, 9.81, 250.0, 1e3);
    let ramp = Arctan { m: m2, d, omega };
    let bodies = Bodies::new(m1, m2, -0.5, 1.5, a, a, input::gravity(m1, g), ramp).unwrap();
    let m = bodies.effective_mass();
    assert!((m - m1 * m2 / (m1 + m2)).abs() < 1e-15);
    assert_eq!(bodies.impact_speed(), 2.0);
    let u = bodies.relative_input();
    for t in [0.0, 1e-4, 1e-3, 1e-2] {
        // u = (m2 u1 - m1 u2) / (m1 + m2) = -m (g + (2/π) D arctan(ω t))
        let expected = -m * (g + std::f64::consts::FRAC_2_PI * d * (omega * t).atan());
        assert!((input::Input::at(&u, t) - expected).abs() < 1e-12 * expected.abs());
    }
    let law = Physical {
        k: 1e6,
        c: 1e3,
        n: 1.5,
        p: 1.5,
        alpha: 0.5,
        beta: 1e4,
        gamma: -5e3,
        a: 1.0,
    };
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let params = PhysicalParams::new(kind, law).unwrap();
        let mut rows = Vec::new();
        let s = Settings::default();
        let out = match kind {
            ModelKind::Shccm => {
                let model = Bwshccm::new(&params, m, 2.0, bodies.relative_input()).unwrap();
                simulate(&model, &s, Sampling::Steps, |t, y| {
                    rows.push((t, model.displacement(y), model.velocity(y)))
                })
                .unwrap()
                .cor()
            }
            ModelKind::Mcm => {
                let model = Bwmcm::new(&params, m, 2.0, bodies.relative_input()).unwrap();
                simulate(&model, &s, Sampling::Steps, |t, y| {
                    rows.push((t, model.displacement(y), model.velocity(y)))
                })
                .unwrap()
                .cor()
            }
        };
        let ts = out.t_s.expect("the balls separate");
        assert!(ts > 1e-3 && ts < 5e-2, "{kind:?}: t_s = {ts}");
        assert!(out.e > 0.0 && out.e < 1.0, "{kind:?}: e = {}", out.e);
        let mut motion = bodies.motion().unwrap();
        for &(t, x, v) in &rows {
            let b = motion.at(t, x, v).unwrap();
            // Geometry: x = x_1 - x_2 with x_1 = x_m1 - l1, x_2 = x_m2 + l2.
            assert!(((b.x_m_1 - a) - (b.x_m_2 + a) - x).abs() < 1e-12);
            // Momentum: m1 v1 + m2 v2 changes only by the impulse of the external forces,
            // ∫ u1 + u2 = -m1 g t + (2/π) m2 D (t atan(ωt) - ln(1 + ω²t²) / (2ω)).
            let p0 = m1 * -0.5 + m2 * 1.5;
            let impulse = -m1 * g * t
                + std::f64::consts::FRAC_2_PI
                    * m2
                    * d
                    * (t * (omega * t).atan() - (1.0 + (omega * t).powi(2)).ln() / (2.0 * omega));
            let p = m1 * b.v_m_1 + m2 * b.v_m_2;
            assert!(
                (p - (p0 + impulse)).abs() < 1e-9,
                "{kind:?} t {t}: momentum {p} vs {}",
                p0 + impulse
            );
            assert!((b.v_m_1 - b.v_m_2 - v).abs() < 1e-12);
        }
    }
}

/// Section 3 with a fixed body 2 (`m2 = inf`): the effective mass is `m1`, the relative input
/// `u1`, and body 2 does not move; bodies moving apart are rejected.
#[test]
fn a_fixed_body_takes_the_whole_impact() {
    let fixed = Bodies::new(
        2.0,
        f64::INFINITY,
        -1.0,
        0.0,
        0.1,
        0.0,
        Constant(-3.0),
        Constant(5.0),
    )
    .unwrap();
    assert_eq!(fixed.effective_mass(), 2.0);
    assert_eq!(input::Input::at(&fixed.relative_input(), 0.3), -3.0);
    let mut motion = fixed.motion().unwrap();
    let b = motion.at(0.5, -0.01, 0.2).unwrap();
    assert_eq!((b.v_m_2, b.x_m_2), (0.0, 0.0));
    assert!(
        Bodies::new(1.0, 1.0, 1.0, 0.5, 0.0, 0.0, Zero, Zero).is_err(),
        "bodies moving apart"
    );
    assert!(Bodies::new(1.0, -1.0, -1.0, 0.0, 0.0, 0.0, Zero, Zero).is_err());
}

/// The SI BWSHCCM's clearance from a root of a base is its nondimensional model's, in
/// seconds: Table 1 scales the state, its rate and the time alike.
#[test]
fn si_clearance_is_the_nondimensional_one_in_seconds() {
    use bwc_ode::System;
    let params = cross(ModelKind::Shccm);
    let v0 = 20.0;
    let si = Bwshccm::new(&params, BASEBALL_MASS, v0, Zero).unwrap();
    let (ndp, sc) = nondimensionalize(&params, BASEBALL_MASS, v0).unwrap();
    let nd = Ndbwshccm::new(&ndp, Zero).unwrap();
    // Unloading, both bases approaching 0: X = -0.01, Z = -0.002, V = 0.8.
    let y_nd = State::<3>::new(-0.01, -0.002, 0.8);
    let y_si = State::<3>::new(y_nd[0] * sc.x_c, y_nd[1] * sc.z_c, y_nd[2] * v0);
    let (f_nd, f_si) = (nd.rhs(0.0, &y_nd), si.rhs(0.0, &y_si));
    let (c_nd, c_si) = (
        nd.clearance(&y_nd, &f_nd, 1e-12),
        si.clearance(&y_si, &f_si, 1e-12),
    );
    assert!(c_nd.is_finite() && c_nd > 0.0, "{c_nd}");
    assert!(
        (c_si / sc.t_c - c_nd).abs() <= 1e-12 * c_nd,
        "{c_si} s vs {c_nd} T_c"
    );
    // Receding from both roots there is none.
    let back = State::<3>::new(-0.01, -0.002, -0.8);
    assert_eq!(
        nd.clearance(&back, &nd.rhs(0.0, &back), 1e-12),
        f64::INFINITY
    );
}

/// The SI models' double-double path (the nondimensional model's, scaled by Table 1): the
/// linear elastic contact (`p = 1`, `c = β = γ = 0`, `A = 1`, so `z = x` and `m v' = -k x`)
/// lasts `π sqrt(m / k)` with `e = 1`; under the arctan ramp both models agree with the
/// double-precision path at tight tolerances.
#[test]
fn si_models_have_the_double_double_path() {
    let s = Settings::default();
    let (m, k) = (0.2, 4.0e5);
    let linear = Physical {
        k,
        c: 0.0,
        n: 1.5,
        p: 1.0,
        alpha: 0.3,
        beta: 0.0,
        gamma: 0.0,
        a: 1.0,
    };
    let params = PhysicalParams::new(ModelKind::Shccm, linear).unwrap();
    let model = Bwshccm::new(&params, m, 1.5, Zero).unwrap();
    let out = impact_double_double(&model, 1e-20, &s).unwrap().unwrap();
    let t_s = std::f64::consts::PI * (m / k).sqrt();
    assert!((out.t_s.unwrap() - t_s).abs() < 1e-15 * t_s, "{out:?}");
    assert!((out.e - 1.0).abs() < 1e-15 && out.double_double, "{out:?}");
    // x(t_s) = 0 and v(t_s) = 1.5 m/s, in SI units.
    assert!(out.state[0].abs() < 1e-15 && (out.state[2] - 1.5).abs() < 1e-14);

    let ramp = Arctan {
        m: BASEBALL_MASS,
        d: -300.0,
        omega: 2e3,
    };
    let fine = tight();
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let (dd, double) = match kind {
            ModelKind::Shccm => {
                let model = Bwshccm::new(&cross(kind), BASEBALL_MASS, 3.03, ramp).unwrap();
                let dd = impact_double_double(&model, 1e-18, &s).unwrap().unwrap();
                (dd.cor(), impact(&model, &fine).unwrap().cor())
            }
            ModelKind::Mcm => {
                let model = Bwmcm::new(&cross(kind), BASEBALL_MASS, 3.03, ramp).unwrap();
                let dd = impact_double_double(&model, 1e-18, &s).unwrap().unwrap();
                (dd.cor(), impact(&model, &fine).unwrap().cor())
            }
        };
        assert!(
            (dd.e - double.e).abs() < 1e-11,
            "{kind:?}: {dd:?} {double:?}"
        );
        let (a, b) = (dd.t_s.unwrap(), double.t_s.unwrap());
        assert!((a - b).abs() < 1e-11 * b, "{kind:?}: t_s {a} vs {b}");
    }
}

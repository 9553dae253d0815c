//! The stiff regime: analytic Jacobians, RODAS4 against the explicit methods and known answers,
//! and the automatic switch on a case that an explicit method cannot finish.

use bw_models::input::Zero;
use bw_models::{
    impact, impact_at, BaseMap, CollisionModel, ModelError, ModelKind, Ndbwmcm, Ndbwshccm,
    Settings, State, Stiffness,
};
use bwc_ode::{Matrix, VERN7};

use super::{base, nd};

/// Central differences with steps 1e-6: error about 1e-12 times the third derivative.
fn central<M: CollisionModel<N>, const N: usize>(m: &M, y: &State<N>) -> Matrix<N> {
    let mut j = Matrix::<N>::zeros();
    for c in 0..N {
        let d = 1e-6;
        let (mut yp, mut ym) = (*y, *y);
        yp[c] += d;
        ym[c] -= d;
        j.set_column(c, &((m.rhs(0.0, &yp) - m.rhs(0.0, &ym)) / (2.0 * d)));
    }
    j
}

fn assert_close<const N: usize>(a: &Matrix<N>, b: &Matrix<N>, what: &str) {
    let scale = b.amax().max(1.0);
    assert!(
        (a - b).amax() <= 1e-7 * scale,
        "{what}:\n{a}\nvs central differences\n{b}"
    );
}

/// The analytic Jacobians of both nondimensional models equal central differences away from
/// the non-smooth points, for integer, half-integer and general exponents (the fast paths).
#[test]
fn analytic_jacobians_match_finite_differences() {
    let exps = [
        (1.0, 1.0),
        (2.0, 1.5),
        (2.93, 2.62),
        (1.57, 1.75),
        (10.0, 3.5),
    ];
    let states3 = [[-0.7, -0.4, 0.3], [-1.2, 0.5, -0.8], [0.2, -0.9, 0.05]];
    let states4 = [
        [0.1, -0.7, -0.4, 0.3],
        [-0.3, -1.2, 0.5, -0.8],
        [0.0, 0.2, -0.9, 0.05],
    ];
    for (n, p) in exps {
        let m = Ndbwshccm::new(&nd(ModelKind::Shccm, 2.4, -1.3, 0.677, 0.35, n, p), Zero).unwrap();
        for s in states3 {
            let y = State::<3>::from(s);
            assert_close(
                &m.jacobian(0.0, &y),
                &central(&m, &y),
                &format!("SHCCM n {n} p {p}"),
            );
        }
        let m = Ndbwmcm::new(&nd(ModelKind::Mcm, 0.97, 0.4, 0.531, 2.5, n, p), Zero).unwrap();
        for s in states4 {
            let y = State::<4>::from(s);
            assert_close(
                &m.jacobian(0.0, &y),
                &central(&m, &y),
                &format!("MCM n {n} p {p}"),
            );
        }
    }
}

/// RODAS4 throughout gives the known answers: the elastic limit (e = 1, T_s of `crate::ELASTIC`)
/// and Table 3's DSS (1) against a tight explicit run, both models, to 1e-9.
#[test]
fn rosenbrock_reproduces_known_answers() {
    let rodas = Settings {
        stiffness: Stiffness::Rosenbrock,
        rtol: 1e-11,
        atol: 1e-13,
        e_tol: None,
        ..Settings::default()
    };
    let elastic =
        Ndbwshccm::new(&nd(ModelKind::Shccm, 0.0, 0.0, 0.5, 0.0, 1.0, 2.5), Zero).unwrap();
    let r = impact(&elastic, &rodas).unwrap();
    assert!((r.e - 1.0).abs() < 1e-9, "elastic e = {}", r.e);
    assert!(
        (r.t_s.unwrap() - crate::ELASTIC[3].1).abs() < 1e-9,
        "{:?}",
        r.t_s
    );
    assert!(r.stats.jacobians > 0 && r.stiff_from.is_none());
    let tight = Settings {
        method: &VERN7,
        rtol: 1e-14,
        atol: 1e-16,
        stiffness: Stiffness::Ignore,
        e_tol: None,
        ..Settings::default()
    };
    let dss1 = [
        (
            ModelKind::Shccm,
            base(2.38, -2.38, 0.677, 0.0348, 2.93, 2.62),
        ),
        (
            ModelKind::Mcm,
            base(0.966, -0.966, 0.531, 2.22e-16, 1.57, 1.75),
        ),
    ];
    for (kind, base) in dss1 {
        let map = BaseMap::new(kind, base).unwrap();
        for v0 in [0.5, 2.0, 5.0] {
            let a = impact_at(&map, Zero, v0, &rodas).unwrap();
            let b = impact_at(&map, Zero, v0, &tight).unwrap();
            assert!(
                (a.e - b.e).abs() < 1e-9,
                "{kind:?} v0 {v0}: {} vs {}",
                a.e,
                b.e
            );
            let (ta, tb) = (a.t_s.unwrap(), b.t_s.unwrap());
            assert!(
                (ta - tb).abs() < 1e-9 * tb,
                "{kind:?} v0 {v0}: {ta} vs {tb}"
            );
        }
    }
}

/// A case of the stress sweep's "too many steps" class (MCM, n = 8.7, kappa = 9e-4, v0 = 124
/// m/s): DOP853 alone exhausts 200,000 steps at T = 0.84, where the dynamics turn stiff; with
/// the default switch, Hairer's test fires there and RODAS4 finishes the impact, agreeing with
/// RODAS4 throughout.
#[test]
fn stiff_impact_switches_to_rosenbrock_and_finishes() {
    let base = base(
        0.7701717736752235,
        -0.7701717736752235,
        0.0009339372916279058,
        2.468383259716545,
        8.731291903102164,
        1.5573680392509233,
    );
    let map = BaseMap::new(ModelKind::Mcm, base).unwrap();
    let v0 = 123.65181439237939;
    let with = |stiffness| Settings {
        stiffness,
        max_steps: 200_000,
        rtol: 1e-11,
        atol: 1e-13,
        e_tol: None,
        ..Settings::default()
    };
    let explicit = impact_at(&map, Zero, v0, &with(Stiffness::Ignore));
    assert!(
        matches!(explicit, Err(ModelError::Solver(_))),
        "{explicit:?}"
    );
    let switched = impact_at(&map, Zero, v0, &with(Stiffness::Switch)).unwrap();
    let rodas = impact_at(&map, Zero, v0, &with(Stiffness::Rosenbrock)).unwrap();
    let from = switched.stiff_from.expect("switched");
    assert!((0.5..1.0).contains(&from), "switched at {from}");
    assert!(switched.separated() && rodas.separated());
    assert!(
        (switched.e - rodas.e).abs() < 1e-9,
        "{} vs {}",
        switched.e,
        rodas.e
    );
    assert!(switched.stats.accepted + switched.stats.rejected < 20_000);
}

/// The test does not fire on the non-stiff published cases: Table 3's DSS (1), both models, at
/// every tolerance from 1e-4 to 1e-13 and three speeds (the default would switch otherwise).
#[test]
fn published_cases_are_not_called_stiff() {
    let dss1 = [
        (
            ModelKind::Shccm,
            base(2.38, -2.38, 0.677, 0.0348, 2.93, 2.62),
        ),
        (
            ModelKind::Mcm,
            base(0.966, -0.966, 0.531, 2.22e-16, 1.57, 1.75),
        ),
    ];
    for (kind, b) in dss1 {
        let map = BaseMap::new(kind, b).unwrap();
        for k in 4..=13 {
            let rtol = 10f64.powi(-k);
            let s = Settings {
                rtol,
                atol: rtol / 100.0,
                e_tol: None,
                ..Settings::default()
            };
            for v0 in [0.5, 2.0, 5.0] {
                let out = impact_at(&map, Zero, v0, &s).unwrap();
                assert!(out.stiff_from.is_none(), "{kind:?} rtol {rtol:e} v0 {v0}");
            }
        }
    }
}

/// RODAS4 on the SI models (forward-difference Jacobians, scaled to the state) agrees with the
/// explicit nondimensional runs on Cross's parameters: e to 1e-8, t_s to 1e-8 relative.
#[test]
fn rosenbrock_on_si_models_with_finite_difference_jacobians() {
    use super::{cross, BASEBALL_MASS};
    use bw_models::{nondimensionalize, Bwmcm, Bwshccm};
    let rodas = Settings {
        stiffness: Stiffness::Rosenbrock,
        e_tol: None,
        ..Settings::default()
    };
    for kind in [ModelKind::Shccm, ModelKind::Mcm] {
        let params = cross(kind);
        let v0 = 3.03;
        let (ndp, sc) = nondimensionalize(&params, BASEBALL_MASS, v0).unwrap();
        let (si, nd) = match kind {
            ModelKind::Shccm => (
                impact(
                    &Bwshccm::new(&params, BASEBALL_MASS, v0, Zero).unwrap(),
                    &rodas,
                )
                .map(|i| i.cor()),
                impact(&Ndbwshccm::new(&ndp, Zero).unwrap(), &Settings::default()).map(|i| i.cor()),
            ),
            ModelKind::Mcm => (
                impact(
                    &Bwmcm::new(&params, BASEBALL_MASS, v0, Zero).unwrap(),
                    &rodas,
                )
                .map(|i| i.cor()),
                impact(&Ndbwmcm::new(&ndp, Zero).unwrap(), &Settings::default()).map(|i| i.cor()),
            ),
        };
        let (si, nd) = (si.unwrap(), nd.unwrap());
        assert!(si.stats.jacobians > 0);
        assert!(
            (si.e - nd.e).abs() < 1e-8,
            "{kind:?}: e {} vs {}",
            si.e,
            nd.e
        );
        let (ts_si, ts_nd) = (si.t_s.unwrap(), nd.t_s.unwrap() * sc.t_c);
        assert!(
            (ts_si - ts_nd).abs() < 1e-8 * ts_nd,
            "{kind:?}: t_s {ts_si} vs {ts_nd}"
        );
    }
}

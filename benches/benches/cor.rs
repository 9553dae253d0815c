//! One CoR evaluation of the NDBWSHCCM at Table 3's DSS (1), v0 = 2 m/s, side by side:
//! bwc's default settings (the Taylor-series path, `Settings::series`), the Runge-Kutta path
//! (DOP853 with stops at the kinks, `series = false`), DOP853 stepping over the kinks, the paper's setup in bwc
//! (DOP853, max_step 1e-2), and the `ode_solvers` crate's DOP853 on the same right-hand side
//! (no event location: it stops at the end of the first step where F <= 0 <= v); then the
//! NDBWMCM at its DSS (1) fit (default, series at rtol 1e-8, DOP853 stepping over the kinks).
//! `cargo bench -p bwc-benches --bench cor`

use bw_models::{CollisionModel, ModelKind, Ndbwshccm, Settings};
use bwc_benches::cor;
use bwc_ode::DOP853;
use criterion::{criterion_group, criterion_main, Criterion};
use ode_solvers::{Dop853, System, Vector3};

struct Peer<'a>(&'a Ndbwshccm<bw_models::input::Zero>);

impl System<f64, Vector3<f64>> for Peer<'_> {
    fn system(&self, t: f64, y: &Vector3<f64>, dy: &mut Vector3<f64>) {
        *dy = bwc_ode::System::rhs(self.0, t, y);
    }
    fn solout(&mut self, _t: f64, y: &Vector3<f64>, _dy: &Vector3<f64>) -> bool {
        self.0.force(y) <= 0.0 && y[2] >= 0.0
    }
}

fn peer(model: &Ndbwshccm<bw_models::input::Zero>) -> (f64, u32) {
    let mut s = Dop853::new(
        Peer(model),
        0.0,
        1e3,
        0.0,
        Vector3::new(0.0, 0.0, -1.0),
        1e-10,
        1e-12,
    );
    let stats = s.integrate().expect("ode_solvers integrates");
    (s.y_out().last().expect("output")[2], stats.num_eval)
}

fn cor_evaluation(c: &mut Criterion) {
    let map = cor::dss1(ModelKind::Shccm);
    let v0 = 2.0;
    let reference = cor::evaluate(
        &map,
        v0,
        &Settings {
            rtol: 1e-14,
            atol: 1e-16,
            series: false,
            ..Settings::default()
        },
    )
    .unwrap()
    .e;
    let settings = [
        (
            "bwc default (Taylor series, order 16, rtol 1e-11)",
            Settings::default(),
        ),
        (
            "bwc DOP853 rtol 1e-11, stops at kinks (series = false)",
            Settings {
                series: false,
                ..Settings::default()
            },
        ),
        (
            "bwc Taylor series (order 16) rtol 1e-9",
            Settings {
                rtol: 1e-9,
                atol: 1e-11,
                series: true,
                ..Settings::default()
            },
        ),
        (
            "bwc Taylor series (order 16) rtol 1e-8",
            Settings {
                rtol: 1e-8,
                atol: 1e-10,
                series: true,
                ..Settings::default()
            },
        ),
        (
            "bwc DOP853 rtol 1e-10, stops at kinks",
            Settings {
                rtol: 1e-10,
                atol: 1e-12,
                series: false,
                ..Settings::default()
            },
        ),
        (
            "bwc DOP853 rtol 1e-11, stepping over kinks",
            Settings {
                method: &DOP853,
                rtol: 1e-11,
                atol: 1e-13,
                stop_at_kinks: false,
                series: false,
                ..Settings::default()
            },
        ),
        (
            "bwc DOP853 rtol 1e-10, stepping over kinks",
            Settings {
                method: &DOP853,
                rtol: 1e-10,
                atol: 1e-12,
                stop_at_kinks: false,
                series: false,
                ..Settings::default()
            },
        ),
        (
            "bwc paper setup (DOP853, rtol 1e-10, max_step 1e-2)",
            Settings::paper(),
        ),
    ];
    let mut group = c.benchmark_group("cor_dss1_v0_2");
    for (name, s) in settings {
        let out = cor::evaluate(&map, v0, &s).unwrap();
        eprintln!(
            "{name}: {} RHS evaluations, {} steps ({} series), |e - e_ref| = {:.2e}",
            out.stats.rhs_evals,
            out.stats.accepted + out.stats.rejected,
            out.series_steps,
            (out.e - reference).abs()
        );
        group.bench_function(name, |b| b.iter(|| cor::evaluate(&map, v0, &s).unwrap()));
    }
    let (nd, _) = map.at(v0).unwrap();
    let model = Ndbwshccm::new(&nd, bw_models::input::Zero).unwrap();
    let (e, evals) = peer(&model);
    eprintln!("ode_solvers DOP853 rtol 1e-10 (stops at a step end): {evals} RHS evaluations, |e - e_ref| = {:.2e}", (e - reference).abs());
    group.bench_function("ode_solvers DOP853 rtol 1e-10", |b| b.iter(|| peer(&model)));
    group.finish();
    // One right-hand-side evaluation (non-integer n and p: the general powf path).
    let y = bwc_ode::State::<3>::new(-0.8, -0.7, 0.3);
    c.bench_function("ndbwshccm_rhs_dss1", |b| {
        b.iter(|| bwc_ode::System::rhs(&model, 0.0, std::hint::black_box(&y)))
    });
    // The NDBWMCM at its DSS (1) fit, same speed: the default, the series at rtol 1e-8 and
    // DOP853 stepping over the kinks at the rtol where it meets about the series' error.
    let mcm = cor::dss1(ModelKind::Mcm);
    let tight = Settings {
        rtol: 1e-14,
        atol: 1e-16,
        series: false,
        ..Settings::default()
    };
    let reference = cor::evaluate(&mcm, v0, &tight).unwrap().e;
    let mut group = c.benchmark_group("mcm_dss1_v0_2");
    for (name, s) in [
        (
            "bwc default (Taylor series, rtol 1e-11)",
            Settings::default(),
        ),
        (
            "bwc Taylor series rtol 1e-8",
            Settings {
                rtol: 1e-8,
                atol: 1e-10,
                ..Settings::default()
            },
        ),
        (
            "bwc DOP853 rtol 1e-10, stepping over kinks",
            Settings {
                method: &DOP853,
                rtol: 1e-10,
                atol: 1e-12,
                stop_at_kinks: false,
                series: false,
                ..Settings::default()
            },
        ),
    ] {
        let out = cor::evaluate(&mcm, v0, &s).unwrap();
        eprintln!(
            "NDBWMCM {name}: {} RHS evaluations, {} steps ({} series), |e - e_ref| = {:.2e}",
            out.stats.rhs_evals,
            out.stats.accepted + out.stats.rejected,
            out.series_steps,
            (out.e - reference).abs()
        );
        group.bench_function(name, |b| b.iter(|| cor::evaluate(&mcm, v0, &s).unwrap()));
    }
    group.finish();
}

criterion_group!(benches, cor_evaluation);
criterion_main!(benches);

//! One CoR evaluation of the NDBWSHCCM at Table 3's DSS (1), v0 = 2 m/s, side by side:
//! bwc's default settings (the Taylor-series path, `Settings::series`), the Runge-Kutta path
//! (DOP853 with stops at the kinks, `series = false`), DOP853 stepping over the kinks, the paper's setup in bwc
//! (DOP853, max_step 1e-2), and the `ode_solvers` crate's DOP853 on the same right-hand side
//! (no event location: it stops at the end of the first step where F <= 0 <= v); then the
//! NDBWMCM at its DSS (1) fit (default, series at rtol 1e-8, DOP853 stepping over the kinks).
//! `cargo bench -p bwc-benches --bench cor`

use bw_models::{BaseMap, CollisionModel, ModelKind, Ndbwshccm, Settings};
use bwc_benches::cor;
use bwc_ode::DOP853;
use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion};
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

/// The default settings at `rtol` (atol = rtol / 100): the Taylor series for CoR evaluations.
fn at(rtol: f64) -> Settings {
    Settings {
        rtol,
        atol: rtol / 100.0,
        e_tol: None,
        ..Settings::default()
    }
}

/// DOP853 at `rtol`, stopping at the kinks or stepping over them.
fn dop853(rtol: f64, stop_at_kinks: bool) -> Settings {
    Settings {
        method: &DOP853,
        stop_at_kinks,
        series: false,
        ..at(rtol)
    }
}

/// One benchmark group of CoR evaluations at `v0` on `map`, one row per setting, each first
/// printed with its work and its error against a Runge-Kutta run at rtol 1e-14; the group is
/// returned open for more rows. Returns the reference `e` too.
fn rows<'a>(
    c: &'a mut Criterion,
    group: &str,
    map: &'a BaseMap,
    v0: f64,
    settings: Vec<(&str, Settings)>,
) -> (BenchmarkGroup<'a, WallTime>, f64) {
    let reference = cor::evaluate(map, v0, &dop853(1e-14, true)).unwrap().e;
    let mut g = c.benchmark_group(group);
    for (name, s) in settings {
        let out = cor::evaluate(map, v0, &s).unwrap();
        eprintln!(
            "{group} {name}: {} RHS evaluations, {} steps ({} series), |e - e_ref| = {:.2e}",
            out.stats.rhs_evals,
            out.stats.accepted + out.stats.rejected,
            out.series_steps,
            (out.e - reference).abs()
        );
        g.bench_function(name, |b| b.iter(|| cor::evaluate(map, v0, &s).unwrap()));
    }
    (g, reference)
}

fn cor_evaluation(c: &mut Criterion) {
    let v0 = 2.0;
    let map = cor::dss1(ModelKind::Shccm);
    let settings = vec![
        (
            "bwc default (Taylor series, order 16, rtol 1e-11)",
            Settings::default(),
        ),
        (
            "bwc DOP853 rtol 1e-11, stops at kinks (series = false)",
            dop853(1e-11, true),
        ),
        ("bwc Taylor series (order 16) rtol 1e-9", at(1e-9)),
        ("bwc Taylor series (order 16) rtol 1e-8", at(1e-8)),
        ("bwc DOP853 rtol 1e-10, stops at kinks", dop853(1e-10, true)),
        (
            "bwc DOP853 rtol 1e-11, stepping over kinks",
            dop853(1e-11, false),
        ),
        (
            "bwc DOP853 rtol 1e-10, stepping over kinks",
            dop853(1e-10, false),
        ),
        (
            "bwc paper setup (DOP853, rtol 1e-10, max_step 1e-2)",
            Settings::paper(),
        ),
    ];
    let (mut group, reference) = rows(c, "cor_dss1_v0_2", &map, v0, settings);
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
    // The NDBWMCM at its DSS (1) fit, same speed.
    let mcm = cor::dss1(ModelKind::Mcm);
    let settings = vec![
        (
            "bwc default (Taylor series, rtol 1e-11)",
            Settings::default(),
        ),
        ("bwc Taylor series rtol 1e-8", at(1e-8)),
        (
            "bwc DOP853 rtol 1e-10, stepping over kinks",
            dop853(1e-10, false),
        ),
    ];
    rows(c, "mcm_dss1_v0_2", &mcm, v0, settings).0.finish();
}

criterion_group!(benches, cor_evaluation);
criterion_main!(benches);

//! The figures of a chain's run, from its samples: the bodies' displacements in time
//! (space-time: the bodies move micrometres in a contact and metres in flight, so each is drawn
//! from where it started), their velocities (where a wave shows as a pulse handed on), and the
//! energy ledger in time.

use super::{ChainOutcome, ChainScene};
use crate::plot::{chart, Axis, Series, Style};

/// Most bodies drawn in the space-time figure: a longer chain shows every k-th body.
const MOST_DRAWN: usize = 40;

/// `(file name, SVG or the drawing backend's message)` of every figure.
pub(super) fn all(scene: &ChainScene, out: &ChainOutcome) -> Vec<(String, Result<String, String>)> {
    vec![
        ("chain_space_time.svg".into(), space_time(scene, out)),
        ("chain_velocities.svg".into(), velocities(scene, out)),
        ("chain_ledger.svg".into(), ledger(out)),
    ]
}

/// The factor and unit that put the largest of `values` (in `unit`, "s" or "m") between 1 and
/// 1000: a contact's microseconds read as µs, not as 2e-4 s.
fn prefixed(values: impl Iterator<Item = f64>, unit: &str) -> (f64, String) {
    let largest = values
        .filter(|v| v.is_finite())
        .fold(0.0f64, |a, v| a.max(v.abs()));
    let prefixes = [(1.0, ""), (1e3, "m"), (1e6, "µ"), (1e9, "n")];
    let (factor, prefix) = prefixes
        .iter()
        .copied()
        .find(|(f, _)| largest * f >= 1.0)
        .unwrap_or(prefixes[3]);
    (factor, format!("{prefix}{unit}"))
}

/// `series` with their x (time, s) and y scaled by `(ft, fy)`.
fn scaled(series: Vec<Series>, (ft, fy): (f64, f64)) -> Vec<Series> {
    series
        .into_iter()
        .map(|s| Series {
            points: s.points.iter().map(|&(t, y)| (t * ft, y * fy)).collect(),
            ..s
        })
        .collect()
}

/// The time axis's factor and label for the samples of `out`.
fn time_axis(out: &ChainOutcome) -> (f64, String) {
    let (f, unit) = prefixed(out.samples.iter().map(|s| s.t), "s");
    (f, format!("t ({unit})"))
}

/// Every `k`-th body's series of `value(sample, body)`, labelled where there are few.
fn per_body(
    scene: &ChainScene,
    out: &ChainOutcome,
    value: impl Fn(&super::ChainSample, usize) -> f64,
) -> (Vec<Series>, usize) {
    let n = scene.bodies.len();
    let every = n.div_ceil(MOST_DRAWN);
    let series: Vec<Series> = (0..n)
        .step_by(every)
        .map(|i| Series {
            label: format!("body {}", scene.body_number(i)),
            points: out.samples.iter().map(|s| (s.t, value(s, i))).collect(),
            style: Style::Line,
            color: i / every,
        })
        .collect();
    let series = if series.len() <= 10 {
        series
    } else {
        unlabelled(series)
    };
    (series, every)
}

/// The title of a per-body figure: `what`, and which bodies where not all are drawn.
fn title(what: &str, every: usize, n: usize) -> String {
    if every > 1 {
        format!("{what} (every {every}th of {n} bodies)")
    } else {
        what.to_string()
    }
}

fn velocities(scene: &ChainScene, out: &ChainOutcome) -> Result<String, String> {
    let (series, every) = per_body(scene, out, |s, i| s.velocities[i]);
    let (ft, t_label) = time_axis(out);
    chart(
        &title("Velocities of the bodies", every, scene.bodies.len()),
        Axis::linear(&t_label),
        Axis::linear("v (m/s)"),
        &scaled(series, (ft, 1.0)),
    )
}

fn space_time(scene: &ChainScene, out: &ChainOutcome) -> Result<String, String> {
    let (series, every) = per_body(scene, out, |s, i| s.positions[i] - scene.bodies[i].position);
    let (ft, t_label) = time_axis(out);
    let (fx, unit) = prefixed(
        series.iter().flat_map(|s| s.points.iter().map(|p| p.1)),
        "m",
    );
    chart(
        &title("Displacements of the bodies", every, scene.bodies.len()),
        Axis::linear(&t_label),
        Axis::linear(&format!("x - x(0) ({unit})")),
        &scaled(series, (ft, fx)),
    )
}

/// Series without legend entries (a long chain's legend would cover the figure).
fn unlabelled(series: Vec<Series>) -> Vec<Series> {
    series
        .into_iter()
        .map(|s| Series {
            label: String::new(),
            ..s
        })
        .collect()
}

fn ledger(out: &ChainOutcome) -> Result<String, String> {
    let line = |label: &str, color: usize, f: &dyn Fn(&bw_models::chain::Ledger) -> f64| Series {
        label: label.into(),
        points: out.samples.iter().map(|s| (s.t, f(&s.ledger))).collect(),
        style: Style::Line,
        color,
    };
    let series = [
        line("kinetic", 0, &|l| l.kinetic),
        line("stored in the laws", 1, &|l| l.stored),
        line("dissipated", 2, &|l| l.dissipated),
        line("work of the inputs", 3, &|l| l.work),
    ];
    let (ft, t_label) = time_axis(out);
    chart(
        "Energy ledger: kinetic + stored + dissipated - work = initial",
        Axis::linear(&t_label),
        Axis::linear("energy (J)"),
        &scaled(series.to_vec(), (ft, 1.0)),
    )
}

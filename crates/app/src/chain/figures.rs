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
    chart(
        &title("Velocities of the bodies", every, scene.bodies.len()),
        Axis::linear("t (s)"),
        Axis::linear("v (m/s)"),
        &series,
    )
}

fn space_time(scene: &ChainScene, out: &ChainOutcome) -> Result<String, String> {
    let (series, every) = per_body(scene, out, |s, i| s.positions[i] - scene.bodies[i].position);
    chart(
        &title("Displacements of the bodies", every, scene.bodies.len()),
        Axis::linear("t (s)"),
        Axis::linear("x - x(0) (m)"),
        &series,
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
    chart(
        "Energy ledger: kinetic + stored + dissipated - work = initial",
        Axis::linear("t (s)"),
        Axis::linear("energy (J)"),
        &series,
    )
}

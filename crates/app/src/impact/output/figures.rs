//! The SVG figures of a scene: CoR and duration against the impact speed, force-compression
//! loops, and the time histories of the paper's Figs. 3-5, with quantities and units on every
//! axis and legends in words.

use super::si_states;
use crate::impact::runs::{Run, Sample};
use crate::impact::scene::Scene;
use crate::plot::{self, Axis, Series, Style};

/// A figure: its file name and SVG text, or the file name and the drawing error.
type Figure = Result<(String, Vec<u8>), (String, String)>;

fn figure(name: &str, svg: Result<String, String>) -> Figure {
    svg.map(|s| (name.to_string(), s.into_bytes()))
        .map_err(|m| (name.to_string(), m))
}

/// The figure `name` (`cor.svg`, ...) drawn with the scene's own title, axis labels and style
/// where `[output.figures.NAME]` gives them, its own otherwise.
fn drawn(
    scene: &Scene,
    name: &str,
    title: &str,
    (x, y): (Axis, Axis),
    series: &[Series],
) -> Figure {
    let Some(own) = scene.figures.get(name.trim_end_matches(".svg")) else {
        return figure(name, plot::chart(title, x, y, series));
    };
    let title = own.title.as_deref().unwrap_or(title);
    let x = Axis {
        label: own.x_label.as_deref().unwrap_or(x.label),
        ..x
    };
    let y = Axis {
        label: own.y_label.as_deref().unwrap_or(y.label),
        ..y
    };
    let series: Vec<Series> = series
        .iter()
        .map(|s| Series {
            style: own.style.unwrap_or(s.style),
            ..s.clone()
        })
        .collect();
    figure(name, plot::chart(title, x, y, &series))
}

/// Models computed at few speeds show their points; dense sweeps are lines.
fn sweep_style(points: usize) -> Style {
    if points <= 20 {
        Style::LineAndMarkers
    } else {
        Style::Line
    }
}

/// One series per system of `f(run)` over its runs (failed runs skipped).
fn by_system(runs: &[Run], f: impl Fn(&Run) -> (f64, f64)) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    for r in runs.iter().filter(|r| r.e.is_finite()) {
        let label = r.name.clone().unwrap_or_else(|| r.model.title().into());
        match out.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push(f(r)),
            None => out.push(Series {
                color: out.len(),
                label,
                points: vec![f(r)],
                style: Style::Line,
            }),
        }
    }
    for s in &mut out {
        s.style = sweep_style(s.points.len());
    }
    out
}

/// `cor.svg` and, where durations have a time scale, `duration.svg`: against v0 on a log axis
/// where the speeds span more than a decade.
pub(super) fn sweep(scene: &Scene, runs: &[Run]) -> Vec<Figure> {
    let speeds = || scene.speeds.iter().copied();
    let x = Axis::log_if_spanning("impact speed v0 (m/s)", speeds(), 1.0);
    let mut out = vec![drawn(
        scene,
        "cor.svg",
        "Coefficient of restitution",
        (x, Axis::linear("coefficient of restitution e (-)")),
        &by_system(runs, |r| (r.v0.unwrap_or(f64::NAN), r.e)),
    )];
    if runs.iter().any(|r| r.t_d.is_some()) {
        let series = by_system(runs, |r| {
            (r.v0.unwrap_or(f64::NAN), r.t_d.unwrap_or(f64::NAN))
        });
        let y = Axis::log_if_spanning(
            "contact duration t_d (s)",
            runs.iter().filter_map(|r| r.t_d),
            1.0,
        );
        out.push(drawn(
            scene,
            "duration.svg",
            "Contact duration",
            (x, y),
            &series,
        ));
    }
    out
}

/// `loops.svg`: force against compression, one line per run.
pub(super) fn loops(scene: &Scene, runs: &[Run]) -> Figure {
    let si = si_states(scene);
    let (x, y, scale) = if si {
        ("compression |x| (mm)", "contact force F (N)", 1e3)
    } else {
        (
            "compression |X| (nondimensional)",
            "contact force F (nondimensional)",
            1.0,
        )
    };
    let series: Vec<Series> = runs
        .iter()
        .enumerate()
        .map(|(i, r)| Series {
            label: r.label(),
            points: r.trajectory.iter().map(|s| (-s.x * scale, s.f)).collect(),
            style: Style::Line,
            color: i,
        })
        .collect();
    drawn(
        scene,
        "loops.svg",
        "Force-compression loops",
        (Axis::linear(x), Axis::linear(y)),
        &series,
    )
}

/// A quantity of a time history: its legend words and how to read it from a sample.
type Quantity = (&'static str, fn(&Sample) -> f64);

const BODY_POSITIONS: [Quantity; 3] = [
    ("ball 1 position x_m,1", |s| {
        s.bodies.map_or(f64::NAN, |b| b.x_m_1)
    }),
    ("ball 2 position x_m,2", |s| {
        s.bodies.map_or(f64::NAN, |b| b.x_m_2)
    }),
    ("centre of mass x_m", |s| {
        s.bodies.map_or(f64::NAN, |b| b.x_m)
    }),
];
const BODY_VELOCITIES: [Quantity; 3] = [
    ("ball 1 velocity v_m,1", |s| {
        s.bodies.map_or(f64::NAN, |b| b.v_m_1)
    }),
    ("ball 2 velocity v_m,2", |s| {
        s.bodies.map_or(f64::NAN, |b| b.v_m_2)
    }),
    ("centre of mass velocity v_m", |s| {
        s.bodies.map_or(f64::NAN, |b| b.v_m)
    }),
];
const BODY_FORCES: [Quantity; 2] = [
    ("force on ball 1 u_1", |s| {
        s.bodies.map_or(f64::NAN, |b| b.u_1)
    }),
    ("force on ball 2 u_2", |s| {
        s.bodies.map_or(f64::NAN, |b| b.u_2)
    }),
];

/// The paper's Figs. 3-5: displacements, velocities and forces against time.
pub(super) fn time_histories(scene: &Scene, runs: &[Run], bodies: bool) -> Vec<Figure> {
    let si = si_states(scene);
    let t = if runs.iter().all(|r| r.time_unit == "s") {
        "time t (s)"
    } else {
        "time T (nondimensional)"
    };
    let unit = |si_unit: &'static str| if si { si_unit } else { "nondimensional" };
    let panels: [(&str, &str, Vec<Quantity>); 3] = [
        (
            "displacements.svg",
            "Displacements",
            [
                if bodies { &BODY_POSITIONS[..] } else { &[] },
                &[("relative displacement x", |s: &Sample| s.x)],
            ]
            .concat(),
        ),
        (
            "velocities.svg",
            "Velocities",
            [
                if bodies { &BODY_VELOCITIES[..] } else { &[] },
                &[("relative velocity v", |s: &Sample| s.v)],
            ]
            .concat(),
        ),
        (
            "forces.svg",
            "Forces",
            [
                if bodies { &BODY_FORCES[..] } else { &[] },
                &[
                    ("relative input u", |s: &Sample| s.u),
                    ("contact force F", |s: &Sample| s.f),
                ],
            ]
            .concat(),
        ),
    ];
    let y_labels = [
        format!("position, displacement ({})", unit("m")),
        format!("velocity ({})", unit("m/s")),
        format!("force ({})", unit("N")),
    ];
    panels
        .iter()
        .zip(&y_labels)
        .map(|((name, title, quantities), y)| {
            let mut series = Vec::new();
            for r in runs {
                let tag = if runs.len() > 1 {
                    format!(" ({})", r.label())
                } else {
                    String::new()
                };
                for (words, read) in quantities {
                    series.push(Series {
                        label: format!("{words}{tag}"),
                        points: r.trajectory.iter().map(|s| (s.t, read(s))).collect(),
                        style: Style::Line,
                        color: series.len(),
                    });
                }
            }
            drawn(
                scene,
                name,
                title,
                (Axis::linear(t), Axis::linear(y)),
                &series,
            )
        })
        .collect()
}

/// `height.svg`: the height of the body's contact point above the surface (m) from release,
/// the flights drawn from their closed forms and each contact as the step from the touchdown
/// height to the separation height.
pub(super) fn height(scene: &Scene, runs: &[Run]) -> Figure {
    use bw_models::sequence::{Arc, Policy, Start};
    let Some(seq) = scene.sequence else {
        return Err(("height.svg".into(), "not a sequence".into()));
    };
    let flight = seq.settings.flight;
    let mut series = Vec::new();
    for (i, r) in runs.iter().enumerate() {
        let mut points = Vec::new();
        if let (Start::Height(h0), Some((first, _))) = (seq.start, r.bounces.first()) {
            let drop = Arc {
                apex: 0.0,
                t_up: 0.0,
                t_down: first.t_contact,
                v_land: first.v_in,
            };
            points.extend(arc_points(first.t_contact, |t| {
                h0 + flight.height(0.0, &drop, t)
            }));
        }
        // Under "reset" each contact starts where the last one separated; under "carry" the
        // displacement is counted from the first contact's surface.
        let mut base = 0.0;
        for (b, x_s) in &r.bounces {
            let t0 = b.t_contact;
            let top = match seq.settings.policy {
                Policy::Reset => base + x_s,
                Policy::Carry => *x_s,
            };
            points.push((t0, base));
            let Some(t_s) = b.t_s else { continue };
            points.push((t0 + t_s, top));
            if let Some(interval) = b.interval {
                let arc = flight.arc(b.v_out);
                let offset = |(t, h): (f64, f64)| (t0 + t_s + t, top + h);
                points.extend(
                    arc_points(interval - t_s, |t| flight.height(b.v_out, &arc, t))
                        .into_iter()
                        .map(offset),
                );
            }
            base = top;
        }
        series.push(Series {
            label: r.label(),
            points,
            style: Style::Line,
            color: i,
        });
    }
    drawn(
        scene,
        "height.svg",
        "Height of the body above the surface",
        (
            Axis::linear("time from release t (s)"),
            Axis::linear("height (m)"),
        ),
        &series,
    )
}

/// `(t, h(t))` at 60 points of `[0, span]`.
fn arc_points(span: f64, h: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
    (0..=60)
        .map(|k| {
            let t = span * f64::from(k) / 60.0;
            (t, h(t))
        })
        .collect()
}

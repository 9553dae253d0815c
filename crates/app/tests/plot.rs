//! Charts: tick labels that read, a log axis labelling each decade once, a legend where it hides
//! no line, and the drawn size.

use bwc_app::plot::{chart, legend_corner, log_tick, tick, Axis, Series, Style};
use plotters::chart::SeriesLabelPosition;

#[test]
fn tick_labels_read() {
    assert_eq!(tick(6.94e-18, 0.1), "0");
    assert_eq!(tick(0.25, 1.0), "0.25");
    assert_eq!(tick(0.5, 1.0), "0.5");
    assert_eq!(tick(350.0, 450.0), "350");
    assert_eq!(tick(2.5e-5, 3e-5), "2.5e-5");
    assert_eq!(tick(1e-10, 1e-5), "1e-10");
    assert_eq!(log_tick(3e-5, 1.0, true), "");
    assert_eq!(log_tick(5e-5, 1.0, true), "5e-5");
    assert_eq!(log_tick(0.2, 1.0, true), "0.2");
}

#[test]
fn a_log_axis_labels_each_decade_once() {
    let series = [Series {
        label: "e".into(),
        points: (0..50)
            .map(|i| (0.5 * 1.07f64.powi(i), 0.7 - 0.01 * i as f64))
            .collect(),
        style: Style::Line,
        color: 0,
    }];
    let x = Axis::log_if_spanning("v0 (m/s)", series[0].points.iter().map(|p| p.0), 0.5);
    assert!(x.log);
    let svg = chart("t", x, Axis::linear("e (-)"), &series).unwrap();
    let texts: Vec<&str> = svg.split("<text").skip(1).collect();
    for label in [">1<", ">10<", ">2<", ">5<"] {
        let n = texts
            .iter()
            .filter(|t| t.replace(['\n', ' '], "").contains(label))
            .count();
        assert_eq!(n, 1, "{label} drawn {n} times");
    }
}

#[test]
fn the_legend_goes_where_it_covers_no_line() {
    // A line along the top from the middle on and along the bottom: the upper left and
    // every corner on the right hold some of it, the middle of the right side none.
    let top: Vec<(f64, f64)> = (0..=50).map(|i| (0.5 + 0.01 * i as f64, 1.0)).collect();
    let bottom: Vec<(f64, f64)> = vec![(0.0, 0.0), (1.0, 0.0)];
    let drop: Vec<(f64, f64)> = vec![(0.0, 1.0), (0.05, 0.5), (0.5, 0.5), (0.5, 1.0)];
    let corner = legend_corner(
        &[&top, &bottom, &drop],
        &["kinetic", "stored"],
        (0.0, 1.0),
        (0.0, 1.0),
        (false, false),
    );
    assert_eq!(corner, SeriesLabelPosition::MiddleRight);
}

#[test]
fn charts_are_drawn_large_and_shown_at_their_size() {
    let series = [Series {
        label: "line".into(),
        points: vec![(0.0, 0.0), (1.0, 1e-3)],
        style: Style::Line,
        color: 0,
    }];
    let svg = chart("t", Axis::linear("x (m)"), Axis::linear("y (N)"), &series).unwrap();
    assert!(
        svg.starts_with("<svg width=\"900\" height=\"560\" viewBox=\"0 0 3600 2240\""),
        "{}",
        &svg[..80]
    );
    assert!(svg.contains("x (m)") && svg.contains("y (N)"));
}

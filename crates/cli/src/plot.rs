//! SVG line charts (plotters, SVG backend, no system fonts needed).

use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
pub use plotters::prelude::SeriesLabelPosition;
use plotters::prelude::*;

/// A named polyline.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points `(x, y)`; non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
}

/// Draws `series` on one chart and returns the SVG text. `markers` also draws the points;
/// `legend` places the legend where the data leaves room.
///
/// # Errors
/// The drawing backend's message.
pub fn chart(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
    markers: bool,
    legend: SeriesLabelPosition,
) -> Result<String, String> {
    let finite = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let pts = series.iter().flat_map(|s| s.points.iter().filter(finite));
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = |a: f64, b: f64| {
        if b > a {
            0.05 * (b - a)
        } else {
            0.5 * a.abs().max(1e-12)
        }
    };
    let (px, py) = (pad(x0, x1), pad(y0, y1));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 24))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d((x0 - px)..(x1 + px), (y0 - py)..(y1 + py))
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .draw()
            .map_err(|e| e.to_string())?;
        for (i, s) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let points: Vec<(f64, f64)> = s.points.iter().filter(finite).copied().collect();
            chart
                .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label(s.label.clone())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            if markers {
                chart
                    .draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))
                    .map_err(|e| e.to_string())?;
            }
        }
        if series.len() > 1 || series.first().is_some_and(|s| !s.label.is_empty()) {
            chart
                .configure_series_labels()
                .position(legend)
                .background_style(WHITE.mix(0.8))
                .border_style(BLACK)
                .draw()
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// Measured points of a fit chart: `(x, y, spread)`, the spread drawn as an error bar.
pub type Measured = [(f64, f64, Option<f64>)];

/// A model line with its confidence band: `(x, value, lower, upper)`.
pub type Banded = [(f64, f64, f64, f64)];

/// What a fit chart shows.
struct FitLayers<'a> {
    x_label: &'a str,
    y_label: &'a str,
    data: (&'a str, &'a Measured),
    model: (&'a str, &'a Banded),
    band_label: &'a str,
    corner: SeriesLabelPosition,
}

/// A fit chart: the data as markers (with error bars where they carry a spread), the model as
/// a line with its confidence band shaded (unless `band_label` is empty); a logarithmic x axis
/// when `log_x`; the legend in the corner that hides the least.
///
/// # Errors
/// The drawing backend's message.
pub fn fit_chart(
    title: &str,
    x_label: &str,
    y_label: &str,
    data: (&str, &Measured),
    model: (&str, &Banded),
    band_label: &str,
    log_x: bool,
) -> Result<String, String> {
    let xs: Vec<f64> = data
        .1
        .iter()
        .map(|p| p.0)
        .chain(model.1.iter().map(|p| p.0))
        .filter(|x| x.is_finite() && (!log_x || *x > 0.0))
        .collect();
    let ys: Vec<f64> = data
        .1
        .iter()
        .flat_map(|p| [p.1 - p.2.unwrap_or(0.0), p.1 + p.2.unwrap_or(0.0)])
        .chain(model.1.iter().flat_map(|p| [p.1, p.2, p.3]))
        .filter(|y| y.is_finite())
        .collect();
    let range = |v: &[f64]| {
        v.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(*x), b.max(*x))
            })
    };
    let ((x0, x1), (y0, y1)) = (range(&xs), range(&ys));
    if !(x0.is_finite() && y0.is_finite()) {
        return Err("nothing finite to draw".into());
    }
    let py = if y1 > y0 {
        0.05 * (y1 - y0)
    } else {
        0.05 * y0.abs().max(1e-3)
    };
    let (y0, y1) = (y0 - py, y1 + py);
    let drawn: Vec<(f64, f64)> = data
        .1
        .iter()
        .map(|p| (p.0, p.1))
        .chain(
            model
                .1
                .iter()
                .flat_map(|p| [(p.0, p.1), (p.0, p.2), (p.0, p.3)]),
        )
        .collect();
    let layers = FitLayers {
        x_label,
        y_label,
        data,
        model,
        band_label,
        corner: legend_corner(&drawn, (x0, x1), (y0, y1), log_x),
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut builder = ChartBuilder::on(&root);
        builder
            .caption(title, ("sans-serif", 24))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(72);
        if log_x {
            let chart = builder
                .build_cartesian_2d((x0 / 1.1..x1 * 1.1).log_scale(), y0..y1)
                .map_err(|e| e.to_string())?;
            draw_fit(chart, &layers)?;
        } else {
            let px = if x1 > x0 {
                0.05 * (x1 - x0)
            } else {
                0.5 * x0.abs().max(1e-12)
            };
            let chart = builder
                .build_cartesian_2d((x0 - px)..(x1 + px), y0..y1)
                .map_err(|e| e.to_string())?;
            draw_fit(chart, &layers)?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// Draws the layers of a fit chart on a chart with either x axis.
fn draw_fit<'a, X>(
    mut chart: ChartContext<'a, SVGBackend<'a>, Cartesian2d<X, RangedCoordf64>>,
    l: &FitLayers,
) -> Result<(), String>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let e = |e: DrawingAreaErrorKind<std::io::Error>| e.to_string();
    chart
        .configure_mesh()
        .x_desc(l.x_label)
        .y_desc(l.y_label)
        .draw()
        .map_err(e)?;
    let line = RGBColor(31, 119, 180);
    let shade = line.mix(0.2).filled();
    let ok = |p: &&(f64, f64, f64, f64)| p.2.is_finite() && p.3.is_finite();
    let mut outline: Vec<(f64, f64)> = l.model.1.iter().filter(ok).map(|p| (p.0, p.3)).collect();
    if !l.band_label.is_empty() && !outline.is_empty() {
        outline.extend(l.model.1.iter().rev().filter(ok).map(|p| (p.0, p.2)));
        chart
            .draw_series(std::iter::once(Polygon::new(outline, shade)))
            .map_err(e)?
            .label(l.band_label)
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], shade));
    }
    let curve = l
        .model
        .1
        .iter()
        .filter(|p| p.1.is_finite())
        .map(|p| (p.0, p.1));
    chart
        .draw_series(LineSeries::new(curve, line.stroke_width(2)))
        .map_err(e)?
        .label(l.model.0)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], line.stroke_width(2)));
    let mark = RGBColor(214, 39, 40);
    let bars = l.data.1.iter().filter_map(|p| {
        p.2.filter(|s| *s > 0.0)
            .map(|s| PathElement::new(vec![(p.0, p.1 - s), (p.0, p.1 + s)], mark.stroke_width(1)))
    });
    chart.draw_series(bars).map_err(e)?;
    chart
        .draw_series(
            l.data
                .1
                .iter()
                .map(|p| Circle::new((p.0, p.1), 3, mark.filled())),
        )
        .map_err(e)?
        .label(l.data.0)
        .legend(move |(x, y)| Circle::new((x + 10, y), 3, mark.filled()));
    chart
        .configure_series_labels()
        .position(l.corner.clone())
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    Ok(())
}

/// The corner of the plot whose quarter holds the fewest drawn points: where the legend hides
/// the least.
fn legend_corner(
    points: &[(f64, f64)],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    log_x: bool,
) -> SeriesLabelPosition {
    let fx = |x: f64| {
        if log_x {
            (x / x0).ln() / (x1 / x0).ln()
        } else {
            (x - x0) / (x1 - x0)
        }
    };
    let fy = |y: f64| (y - y0) / (y1 - y0);
    let count = |right: bool, upper: bool| {
        points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .filter(|p| {
                let (u, v) = (fx(p.0), fy(p.1));
                (if right { u > 0.55 } else { u < 0.45 }) && (if upper { v > 0.6 } else { v < 0.4 })
            })
            .count()
    };
    [
        (SeriesLabelPosition::UpperRight, count(true, true)),
        (SeriesLabelPosition::LowerRight, count(true, false)),
        (SeriesLabelPosition::UpperLeft, count(false, true)),
        (SeriesLabelPosition::LowerLeft, count(false, false)),
    ]
    .into_iter()
    .min_by_key(|c| c.1)
    .map_or(SeriesLabelPosition::UpperRight, |c| c.0)
}

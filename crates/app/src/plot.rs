//! SVG charts (plotters, SVG backend, no system fonts needed), drawn the way a paper's figures
//! are: every axis with its quantity and unit, logarithmic axes where the values span decades,
//! data as markers (with error bars where they carry a spread), models as lines, readable tick
//! labels, the legend in the corner that hides the least.
//!
//! plotters' SVG backend places everything on integer pixels, which turns a nearly flat line
//! into a staircase: charts are drawn [`SCALE`] times larger and shown at their nominal size
//! through the SVG `viewBox`, so the steps are a fraction of a pixel.

use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;

/// Supersampling factor of every chart.
pub const SCALE: i32 = 4;
/// Nominal size of a chart (px).
const SIZE: (u32, u32) = (900, 560);

/// Distinct colours (Tableau 10, then black), picked by index: the work-precision charts draw
/// eleven series.
const COLORS: [RGBColor; 11] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(0, 0, 0),
];

/// Colour number `i` (cycling).
pub fn color(i: usize) -> RGBColor {
    COLORS[i % COLORS.len()]
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A line (a model).
    Line,
    /// Markers (data).
    Markers,
    /// A line with markers at its points (a model computed at few points).
    LineAndMarkers,
}

/// A named series.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label, in words.
    pub label: String,
    /// Points `(x, y)`; non-finite points (and, on a log axis, non-positive ones) are skipped.
    pub points: Vec<(f64, f64)>,
    /// Line, markers or both.
    pub style: Style,
    /// Colour number ([`color`]): series that belong together share one.
    pub color: usize,
}

/// An axis: its label with the unit, and its scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axis<'a> {
    /// Quantity and unit, e.g. `"v0 (m/s)"`.
    pub label: &'a str,
    /// Logarithmic scale.
    pub log: bool,
}

impl<'a> Axis<'a> {
    /// A linear axis.
    pub fn linear(label: &'a str) -> Self {
        Axis { label, log: false }
    }

    /// A logarithmic axis where `values` are positive and span more than `decades`
    /// (a log-spaced sweep, costs over orders of magnitude); linear otherwise.
    pub fn log_if_spanning(
        label: &'a str,
        values: impl IntoIterator<Item = f64>,
        decades: f64,
    ) -> Self {
        let (mut lo, mut hi, mut positive) = (f64::INFINITY, 0.0f64, true);
        for v in values.into_iter().filter(|v| v.is_finite()) {
            positive &= v > 0.0;
            lo = lo.min(v);
            hi = hi.max(v);
        }
        Axis {
            label,
            log: positive && lo > 0.0 && (hi / lo).log10() > decades,
        }
    }
}

/// The label of the tick at `v` on an axis spanning `span`: plain decimals with as many digits
/// as the tick spacing needs, or scientific notation for very small or large values.
pub fn tick(v: f64, span: f64) -> String {
    // Ticks are multiples of a step computed in floating point: zero can come out as 1e-18.
    if v == 0.0 || v.abs() < 1e-9 * span {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.2e}");
        // 2.50e-5 -> 2.5e-5
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        return format!("{m}e{e}");
    }
    let digits = (-(span / 20.0).log10()).ceil().clamp(0.0, 6.0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// [`tick`], and on a log axis (`log`) only the ticks at 1, 2 and 5 times a power of ten (the
/// others crowd each other near the top of a decade), the others unlabelled.
pub fn log_tick(v: f64, span: f64, log: bool) -> String {
    if log && v > 0.0 {
        let mantissa = v / 10f64.powf(v.log10().floor());
        let shown = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .any(|m| (mantissa - m).abs() < 1e-6 * m);
        if !shown {
            return String::new();
        }
        return tick(v, v);
    }
    tick(v, span)
}

/// The range of the finite values (positive ones on a log axis), padded by 5 % (a factor 1.1
/// on a log axis); `None` without any.
fn padded(values: impl Iterator<Item = f64>, log: bool) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return None;
    }
    Some(if log {
        (lo / 1.1, hi * 1.1)
    } else if hi > lo {
        let p = 0.05 * (hi - lo);
        (lo - p, hi + p)
    } else {
        let p = 0.5 * lo.abs().max(1e-12);
        (lo - p, hi + p)
    })
}

/// Shows the supersampled SVG at its nominal size, each text drawn once.
fn nominal_size(svg: String) -> String {
    let (w, h) = SIZE;
    let big = format!(
        "<svg width=\"{}\" height=\"{}\" ",
        w * SCALE as u32,
        h * SCALE as u32
    );
    let svg = svg.replacen(&big, &format!("<svg width=\"{w}\" height=\"{h}\" "), 1);
    once_each(&svg)
}

/// `svg` without repeats of a `<text>` element at the same place with the same words: a log
/// axis's key points hold each power of ten twice (as `10^k` and as `1 × 10^k`), and the label
/// drawn twice on itself reads bold.
fn once_each(svg: &str) -> String {
    let mut seen = std::collections::HashSet::new();
    let mut out = String::with_capacity(svg.len());
    let mut rest = svg;
    while let Some(start) = rest.find("<text") {
        let Some(len) = rest[start..].find("</text>") else {
            break;
        };
        let end = start + len + "</text>".len();
        out.push_str(&rest[..start]);
        let element = &rest[start..end];
        if seen.insert(element.to_string()) {
            out.push_str(element);
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// Builds the chart of `$builder` over the ranges with the axes' scales and calls the generic
/// `$draw(&mut chart, args...)` on it.
macro_rules! with_axes {
    ($builder:expr, $x:expr, $y:expr, $xr:expr, $yr:expr, $draw:ident($($arg:expr),*)) => {{
        let ((x0, x1), (y0, y1)) = ($xr, $yr);
        let e = |e: DrawingAreaErrorKind<std::io::Error>| e.to_string();
        match ($x.log, $y.log) {
            (false, false) => {
                $draw(&mut $builder.build_cartesian_2d(x0..x1, y0..y1).map_err(e)?, $($arg),*)
            }
            (true, false) => $draw(
                &mut $builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1).map_err(e)?,
                $($arg),*
            ),
            (false, true) => $draw(
                &mut $builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale()).map_err(e)?,
                $($arg),*
            ),
            (true, true) => $draw(
                &mut $builder
                    .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
                    .map_err(e)?,
                $($arg),*
            ),
        }
    }};
}

/// The caption, margins and label areas of every chart, at [`SCALE`].
fn builder<'a, 'b>(
    root: &'a DrawingArea<SVGBackend<'b>, plotters::coord::Shift>,
    title: &str,
) -> ChartBuilder<'a, 'b, SVGBackend<'b>> {
    let mut b = ChartBuilder::on(root);
    b.caption(title, ("sans-serif", 24 * SCALE))
        .margin(16 * SCALE)
        .x_label_area_size(52 * SCALE)
        .y_label_area_size(84 * SCALE);
    b
}

/// The mesh, tick labels and axis descriptions, at [`SCALE`].
fn mesh<'a, X, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'a>, Cartesian2d<X, Y>>,
    x: &Axis,
    y: &Axis,
    (xs, ys): (f64, f64),
) -> Result<(), String>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (xlog, ylog) = (x.log, y.log);
    let fx = move |v: &f64| log_tick(*v, xs, xlog);
    let fy = move |v: &f64| log_tick(*v, ys, ylog);
    chart
        .configure_mesh()
        .x_desc(x.label)
        .y_desc(y.label)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style(("sans-serif", 13 * SCALE))
        .axis_desc_style(("sans-serif", 15 * SCALE))
        .bold_line_style(BLACK.mix(0.15).stroke_width(SCALE as u32))
        .light_line_style(BLACK.mix(0.03).stroke_width(SCALE as u32))
        .axis_style(BLACK.stroke_width(SCALE as u32))
        .set_all_tick_mark_size(5 * SCALE)
        .draw()
        .map_err(|e| e.to_string())
}

/// The legend, at [`SCALE`], in `corner`.
fn legend<'a, X, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'a>, Cartesian2d<X, Y>>,
    corner: SeriesLabelPosition,
) -> Result<(), String>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    chart
        .configure_series_labels()
        .position(corner)
        .label_font(("sans-serif", 13 * SCALE))
        .margin(10 * SCALE)
        .legend_area_size(26 * SCALE)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.stroke_width(SCALE as u32))
        .draw()
        .map_err(|e| e.to_string())
}

/// Draws `series` on one chart with the axes `x` and `y` and returns the SVG text.
///
/// # Errors
/// The drawing backend's message.
pub fn chart(title: &str, x: Axis, y: Axis, series: &[Series]) -> Result<String, String> {
    let keep = |p: &(f64, f64)| {
        p.0.is_finite() && p.1.is_finite() && (!x.log || p.0 > 0.0) && (!y.log || p.1 > 0.0)
    };
    let points: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied().filter(keep))
        .collect();
    let xr = padded(points.iter().map(|p| p.0), x.log).unwrap_or((0.1, 1.0));
    let yr = padded(points.iter().map(|p| p.1), y.log).unwrap_or((0.1, 1.0));
    let kept: Vec<Vec<(f64, f64)>> = series
        .iter()
        .map(|s| s.points.iter().copied().filter(keep).collect())
        .collect();
    let paths: Vec<&[(f64, f64)]> = (series.iter().zip(&kept))
        .flat_map(|(s, k)| {
            // Markers are points, lines are followed between them.
            let k: &[(f64, f64)] = k;
            if s.style == Style::Markers {
                k.chunks(1).collect::<Vec<_>>()
            } else {
                vec![k]
            }
        })
        .collect();
    let labels: Vec<&str> = series
        .iter()
        .filter(|s| !s.label.is_empty())
        .map(|s| s.label.as_str())
        .collect();
    let corner = legend_corner(&paths, &labels, xr, yr, (x.log, y.log));
    let spans = (xr.1 - xr.0, yr.1 - yr.0);
    svg(title, |b| {
        with_axes!(
            b,
            x,
            y,
            xr,
            yr,
            draw_chart((&x, &y), spans, series, &keep, corner)
        )
    })
}

/// A chart's SVG text: `draw` builds and draws it on a [`builder`] at [`SCALE`], shown at its
/// nominal size.
fn svg(
    title: &str,
    draw: impl FnOnce(&mut ChartBuilder<'_, '_, SVGBackend<'_>>) -> Result<(), String>,
) -> Result<String, String> {
    let mut text = String::new();
    {
        let (w, h) = SIZE;
        let root = SVGBackend::with_string(&mut text, (w * SCALE as u32, h * SCALE as u32))
            .into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        draw(&mut builder(&root, title))?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(nominal_size(text))
}

/// The mesh, the series and the legend of [`chart`].
fn draw_chart<'a, X, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'a>, Cartesian2d<X, Y>>,
    (x, y): (&Axis, &Axis),
    spans: (f64, f64),
    series: &[Series],
    keep: &dyn Fn(&(f64, f64)) -> bool,
    corner: SeriesLabelPosition,
) -> Result<(), String>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    mesh(chart, x, y, spans)?;
    for s in series {
        draw_series(chart, s, keep)?;
    }
    // A legend only where some series has a label (one unlabelled series, or many lines
    // drawn without labels, have none).
    if series.iter().any(|s| !s.label.is_empty()) {
        legend(chart, corner)?;
    }
    Ok(())
}

/// A legend entry with room after its words: plotters sizes the legend's box from a width
/// estimate of the font that falls short of what viewers draw, so the words ran into the box.
fn padded_label(label: &str) -> String {
    format!("{label}\u{a0}\u{a0}\u{a0}")
}

/// Most markers of one series: a dense measured curve is thinned to these, evenly.
const MOST_MARKERS: usize = 160;

/// One series in its style and colour, with its legend entry.
fn draw_series<'a, X, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'a>, Cartesian2d<X, Y>>,
    s: &Series,
    keep: &dyn Fn(&(f64, f64)) -> bool,
) -> Result<(), String>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let e = |e: DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let c = color(s.color);
    let points: Vec<(f64, f64)> = s.points.iter().copied().filter(|p| keep(p)).collect();
    let width = 2 * SCALE as u32;
    let r = 3 * SCALE;
    let legend_line = move |(x, y): (i32, i32)| {
        PathElement::new(vec![(x, y), (x + 20 * SCALE, y)], c.stroke_width(width))
    };
    let legend_marker = move |(x, y): (i32, i32)| Circle::new((x + 10 * SCALE, y), r, c.filled());
    if s.style != Style::Markers {
        let drawn = chart
            .draw_series(LineSeries::new(points.clone(), c.stroke_width(width)))
            .map_err(e)?;
        if !s.label.is_empty() {
            drawn.label(padded_label(&s.label)).legend(legend_line);
        }
    }
    if s.style != Style::Line {
        let every = points.len().div_ceil(MOST_MARKERS).max(1);
        let drawn = chart
            .draw_series(
                points
                    .iter()
                    .step_by(every)
                    .map(|&p| Circle::new(p, r, c.filled())),
            )
            .map_err(e)?;
        if s.style == Style::Markers && !s.label.is_empty() {
            drawn.label(padded_label(&s.label)).legend(legend_marker);
        }
    }
    Ok(())
}

/// Measured points of a fit chart: `(x, y, spread)`, the spread drawn as an error bar.
pub type Measured = [(f64, f64, Option<f64>)];

/// A model line with its confidence band: `(x, value, lower, upper)`.
pub type Banded = [(f64, f64, f64, f64)];

/// A labelled line: `(label, points)`.
pub type Line<'a> = (&'a str, &'a [(f64, f64)]);

/// What a fit chart shows.
struct FitLayers<'a> {
    data: (&'a str, &'a Measured),
    model: (&'a str, &'a Banded),
    reference: Option<Line<'a>>,
    band_label: &'a str,
    corner: SeriesLabelPosition,
}

/// A fit chart: the data as markers (with error bars where they carry a spread), the model as
/// a line with its confidence band shaded (unless `band_label` is empty), a reference model as
/// a dashed line where given; a logarithmic x axis when `log_x`; the legend in the corner that
/// hides the least.
///
/// # Errors
/// The drawing backend's message.
pub fn fit_chart(
    title: &str,
    (x_label, y_label): (&str, &str),
    data: (&str, &Measured),
    model: (&str, &Banded),
    reference: Option<Line>,
    band_label: &str,
    log_x: bool,
) -> Result<String, String> {
    let xs: Vec<f64> = data
        .1
        .iter()
        .map(|p| p.0)
        .chain(model.1.iter().map(|p| p.0))
        .chain(reference.iter().flat_map(|r| r.1.iter().map(|p| p.0)))
        .filter(|x| x.is_finite() && (!log_x || *x > 0.0))
        .collect();
    let ys: Vec<f64> = data
        .1
        .iter()
        .flat_map(|p| [p.1 - p.2.unwrap_or(0.0), p.1 + p.2.unwrap_or(0.0)])
        .chain(model.1.iter().flat_map(|p| [p.1, p.2, p.3]))
        .chain(reference.iter().flat_map(|r| r.1.iter().map(|p| p.1)))
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
    let measured: Vec<(f64, f64)> = data.1.iter().map(|p| (p.0, p.1)).collect();
    let band = |f: fn(&(f64, f64, f64, f64)) -> f64| -> Vec<(f64, f64)> {
        model.1.iter().map(|p| (p.0, f(p))).collect()
    };
    let (middle, lower, upper) = (band(|p| p.1), band(|p| p.2), band(|p| p.3));
    let mut drawn: Vec<&[(f64, f64)]> = measured.chunks(1).collect();
    drawn.extend([&middle[..], &lower[..], &upper[..]]);
    drawn.extend(reference.iter().map(|r| r.1));
    let layers = FitLayers {
        data,
        model,
        reference,
        band_label,
        corner: legend_corner(
            &drawn,
            &[data.0, model.0, band_label, reference.map_or("", |r| r.0)],
            (x0, x1),
            (y0, y1),
            (log_x, false),
        ),
    };
    let xr = padded([x0, x1].into_iter(), log_x).expect("finite");
    let (x, y) = (
        Axis {
            label: x_label,
            log: log_x,
        },
        Axis::linear(y_label),
    );
    let spans = (xr.1 - xr.0, y1 - y0);
    svg(title, |b| {
        with_axes!(b, x, y, xr, (y0, y1), draw_fit((&x, &y), spans, &layers))
    })
}

/// Draws the layers of a fit chart on a chart with either x axis.
fn draw_fit<'a, X, Y>(
    chart: &mut ChartContext<'a, SVGBackend<'a>, Cartesian2d<X, Y>>,
    (x, y): (&Axis, &Axis),
    spans: (f64, f64),
    l: &FitLayers,
) -> Result<(), String>
where
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    mesh(chart, x, y, spans)?;
    let e = |e: DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let (width, r) = (2 * SCALE as u32, 3 * SCALE);
    let line = color(0);
    let shade = line.mix(0.2).filled();
    let ok = |p: &&(f64, f64, f64, f64)| p.2.is_finite() && p.3.is_finite();
    let mut outline: Vec<(f64, f64)> = l.model.1.iter().filter(ok).map(|p| (p.0, p.3)).collect();
    if !l.band_label.is_empty() && !outline.is_empty() {
        outline.extend(l.model.1.iter().rev().filter(ok).map(|p| (p.0, p.2)));
        chart
            .draw_series(std::iter::once(Polygon::new(outline, shade)))
            .map_err(e)?
            .label(padded_label(l.band_label))
            .legend(move |(x, y)| {
                Rectangle::new([(x, y - 5 * SCALE), (x + 20 * SCALE, y + 5 * SCALE)], shade)
            });
    }
    let curve = l
        .model
        .1
        .iter()
        .filter(|p| p.1.is_finite())
        .map(|p| (p.0, p.1));
    chart
        .draw_series(LineSeries::new(curve, line.stroke_width(width)))
        .map_err(e)?
        .label(padded_label(l.model.0))
        .legend(move |(x, y)| {
            PathElement::new(vec![(x, y), (x + 20 * SCALE, y)], line.stroke_width(width))
        });
    if let Some((label, points)) = l.reference {
        let other = color(1).stroke_width(width);
        let finite = points.iter().copied().filter(|p| p.1.is_finite());
        chart
            .draw_series(DashedLineSeries::new(finite, 6 * SCALE, 4 * SCALE, other))
            .map_err(e)?
            .label(padded_label(label))
            .legend(move |(x, y)| {
                plotters::element::DashedPathElement::new(
                    vec![(x, y), (x + 20 * SCALE, y)],
                    4 * SCALE,
                    3 * SCALE,
                    other,
                )
            });
    }
    let mark = color(3);
    let bars = l.data.1.iter().filter_map(|p| {
        p.2.filter(|s| *s > 0.0).map(|s| {
            PathElement::new(
                vec![(p.0, p.1 - s), (p.0, p.1 + s)],
                mark.stroke_width(SCALE as u32),
            )
        })
    });
    chart.draw_series(bars).map_err(e)?;
    chart
        .draw_series(
            l.data
                .1
                .iter()
                .map(|p| Circle::new((p.0, p.1), r, mark.filled())),
        )
        .map_err(e)?
        .label(padded_label(l.data.0))
        .legend(move |(x, y)| Circle::new((x + 10 * SCALE, y), r, mark.filled()));
    legend(chart, l.corner.clone())
}

/// The corner of the plot whose legend box would cover the fewest drawn points: where the
/// legend hides the least. The box is estimated from the entries (26 px each) and the longest
/// label (7.5 px a character, 60 px for the key), and the lines are followed between their
/// points, so that a curve crossing the box counts though few of its points lie in it. `paths`
/// are the drawn lines and marks in data coordinates, `labels` the legend's entries; then the
/// axes' ranges and whether each is logarithmic.
pub fn legend_corner(
    paths: &[&[(f64, f64)]],
    labels: &[&str],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    (log_x, log_y): (bool, bool),
) -> SeriesLabelPosition {
    let along = |v: f64, a: f64, b: f64, log: bool| {
        if log {
            (v / a).ln() / (b / a).ln()
        } else {
            (v - a) / (b - a)
        }
    };
    // The plot area in px, less the label areas and margins of `builder`.
    let (w, h) = (
        f64::from(SIZE.0) - 84.0 - 32.0,
        f64::from(SIZE.1) - 52.0 - 32.0 - 30.0,
    );
    let labels: Vec<&&str> = labels.iter().filter(|l| !l.is_empty()).collect();
    let longest = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0) as f64;
    let bw = ((longest + 3.0) * 7.5 + 60.0 + 10.0) / w;
    let bh = (labels.len() as f64 * 26.0 + 20.0 + 10.0) / h;
    let mut fractions: Vec<(f64, f64)> = Vec::new();
    for path in paths {
        let f: Vec<(f64, f64)> = path
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|p| (along(p.0, x0, x1, log_x), along(p.1, y0, y1, log_y)))
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect();
        fractions.extend(f.first().copied());
        for pair in f.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let steps = (((b.0 - a.0).abs() + (b.1 - a.1).abs()) * 100.0)
                .ceil()
                .min(200.0);
            let steps = steps.max(1.0) as usize;
            fractions.extend((1..=steps).map(|k| {
                let t = k as f64 / steps as f64;
                (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
            }));
        }
    }
    // Where the box's lower left corner lies, in fractions of the plot, at each position
    // (the corners first: of equals, the first wins).
    let (left, right, middle_x) = (0.0, 1.0 - bw, 0.5 - bw / 2.0);
    let (lower, upper, middle_y) = (0.0, 1.0 - bh, 0.5 - bh / 2.0);
    let count = |(u0, v0): (f64, f64)| {
        fractions
            .iter()
            .filter(|&&(u, v)| u >= u0 && u <= u0 + bw && v >= v0 && v <= v0 + bh)
            .count()
    };
    [
        (SeriesLabelPosition::UpperRight, (right, upper)),
        (SeriesLabelPosition::UpperLeft, (left, upper)),
        (SeriesLabelPosition::LowerRight, (right, lower)),
        (SeriesLabelPosition::LowerLeft, (left, lower)),
        (SeriesLabelPosition::MiddleRight, (right, middle_y)),
        (SeriesLabelPosition::MiddleLeft, (left, middle_y)),
        (SeriesLabelPosition::UpperMiddle, (middle_x, upper)),
        (SeriesLabelPosition::LowerMiddle, (middle_x, lower)),
    ]
    .into_iter()
    .map(|(position, at)| (position, count(at)))
    .min_by_key(|c| c.1)
    .map_or(SeriesLabelPosition::UpperRight, |c| c.0)
}

//! Corner plots of a weighted sample (plotters, SVG): the weighted histogram of each quantity on
//! the diagonal, the pairs as weighted two-dimensional histograms below it (shaded by the
//! weight in each cell). Quantities sampled on a log scale are drawn as their base-10
//! logarithm.

use crate::plot::SCALE;
use plotters::prelude::*;

/// Nominal size of one cell (px).
const CELL: u32 = 200;
/// Histogram bins.
const BINS: usize = 30;

/// One quantity of a corner plot.
#[derive(Debug, Clone, PartialEq)]
pub struct CornerColumn {
    /// Axis label with the unit.
    pub label: String,
    /// The values, one per sample.
    pub values: Vec<f64>,
    /// Drawn as `log10` of the values.
    pub log: bool,
}

/// The corner plot of `columns` with sample `weights` (normalised or not).
///
/// # Errors
/// The drawing backend's message; no columns.
pub fn corner(title: &str, columns: &[CornerColumn], weights: &[f64]) -> Result<String, String> {
    let d = columns.len();
    if d == 0 {
        return Err("no quantities to draw".into());
    }
    let shown: Vec<Vec<f64>> = columns
        .iter()
        .map(|c| {
            c.values
                .iter()
                .map(|&v| if c.log { v.log10() } else { v })
                .collect()
        })
        .collect();
    let ranges: Vec<(f64, f64)> = shown.iter().map(|v| range_of(v)).collect();
    let labels: Vec<String> = columns
        .iter()
        .map(|c| {
            if c.log {
                format!("log10 {}", c.label)
            } else {
                c.label.clone()
            }
        })
        .collect();
    let side = CELL * d as u32 + 60;
    let mut text = String::new();
    {
        let root =
            SVGBackend::with_string(&mut text, (side * SCALE as u32, (side + 40) * SCALE as u32))
                .into_drawing_area();
        let e = |e: DrawingAreaErrorKind<std::io::Error>| e.to_string();
        root.fill(&WHITE).map_err(e)?;
        let root = root.titled(title, ("sans-serif", 20 * SCALE)).map_err(e)?;
        let cells = root.split_evenly((d, d));
        for (k, area) in cells.iter().enumerate() {
            let (row, col) = (k / d, k % d);
            if col > row {
                continue;
            }
            let x_label = if row == d - 1 {
                labels[col].as_str()
            } else {
                ""
            };
            let y_label = if col == 0 && row > 0 {
                labels[row].as_str()
            } else {
                ""
            };
            if row == col {
                histogram(area, &shown[col], weights, ranges[col], x_label)?;
            } else {
                let pair = (&shown[col][..], &shown[row][..]);
                density(
                    area,
                    pair,
                    weights,
                    (ranges[col], ranges[row]),
                    (x_label, y_label),
                )?;
            }
        }
        root.present().map_err(e)?;
    }
    let big = format!(
        "<svg width=\"{}\" height=\"{}\" ",
        side * SCALE as u32,
        (side + 40) * SCALE as u32
    );
    Ok(text.replacen(
        &big,
        &format!("<svg width=\"{side}\" height=\"{}\" ", side + 40),
        1,
    ))
}

/// The finite range of `v`, padded by 2 % (or around a single value).
fn range_of(v: &[f64]) -> (f64, f64) {
    let (lo, hi) = v
        .iter()
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi > lo {
        let p = 0.02 * (hi - lo);
        (lo - p, hi + p)
    } else {
        let p = 0.05 * lo.abs().max(1e-6);
        (lo - p, hi + p)
    }
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// A cell's chart builder: small margins, label areas only where the cell carries a label.
fn cell<'a, 'b>(
    area: &'a Area<'b>,
    labelled: (bool, bool),
) -> ChartBuilder<'a, 'b, SVGBackend<'b>> {
    let mut b = ChartBuilder::on(area);
    b.margin(4 * SCALE)
        .x_label_area_size(if labelled.0 { 38 * SCALE } else { 14 * SCALE })
        .y_label_area_size(if labelled.1 { 52 * SCALE } else { 14 * SCALE });
    b
}

fn tick(v: &f64) -> String {
    let a = v.abs();
    if a != 0.0 && !(1e-2..1e4).contains(&a) {
        format!("{v:.1e}")
    } else {
        format!("{v:.3}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    }
}

/// The weighted histogram of `v` on the diagonal.
fn histogram(
    area: &Area,
    v: &[f64],
    w: &[f64],
    (lo, hi): (f64, f64),
    label: &str,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let width = (hi - lo) / BINS as f64;
    let mut bins = [0.0; BINS];
    for (x, wi) in v.iter().zip(w) {
        if x.is_finite() {
            let k = (((x - lo) / width) as usize).min(BINS - 1);
            bins[k] += wi;
        }
    }
    let top = bins.iter().fold(0.0f64, |a, &b| a.max(b)).max(1e-300) * 1.1;
    let mut chart = cell(area, (!label.is_empty(), false))
        .build_cartesian_2d(lo..hi, 0.0..top)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_y_axis()
        .disable_mesh()
        .x_desc(label)
        .x_labels(4)
        .x_label_formatter(&tick)
        .label_style(("sans-serif", 10 * SCALE))
        .axis_desc_style(("sans-serif", 12 * SCALE))
        .axis_style(BLACK.stroke_width(SCALE as u32))
        .draw()
        .map_err(e)?;
    let fill = crate::plot::color(0).mix(0.6).filled();
    chart
        .draw_series(bins.iter().enumerate().map(|(k, &h)| {
            let x0 = lo + k as f64 * width;
            Rectangle::new([(x0, 0.0), (x0 + width, h)], fill)
        }))
        .map_err(e)?;
    Ok(())
}

/// Cells per axis of the two-dimensional histograms.
const CELLS: usize = 24;

/// The weighted two-dimensional histogram of a pair below the diagonal, each cell shaded by its
/// share of the largest cell's weight.
fn density(
    area: &Area,
    (x, y): (&[f64], &[f64]),
    w: &[f64],
    ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
    (x_label, y_label): (&str, &str),
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let mut chart = cell(area, (!x_label.is_empty(), !y_label.is_empty()))
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .x_labels(4)
        .y_labels(4)
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style(("sans-serif", 10 * SCALE))
        .axis_desc_style(("sans-serif", 12 * SCALE))
        .axis_style(BLACK.stroke_width(SCALE as u32))
        .draw()
        .map_err(e)?;
    let (dx, dy) = ((x1 - x0) / CELLS as f64, (y1 - y0) / CELLS as f64);
    let mut grid = vec![0.0; CELLS * CELLS];
    for ((a, b), wi) in x.iter().zip(y).zip(w) {
        if a.is_finite() && b.is_finite() {
            let i = (((a - x0) / dx) as usize).min(CELLS - 1);
            let j = (((b - y0) / dy) as usize).min(CELLS - 1);
            grid[i * CELLS + j] += wi;
        }
    }
    let top = grid.iter().fold(0.0f64, |a, &b| a.max(b)).max(1e-300);
    let base = crate::plot::color(0);
    chart
        .draw_series(
            grid.iter()
                .enumerate()
                .filter(|(_, &g)| g > 0.0)
                .map(|(k, &g)| {
                    let (i, j) = (k / CELLS, k % CELLS);
                    let (xa, ya) = (x0 + i as f64 * dx, y0 + j as f64 * dy);
                    // At least a faint shade, so that a cell with any weight shows.
                    let shade = base.mix(0.08 + 0.92 * (g / top).sqrt()).filled();
                    Rectangle::new([(xa, ya), (xa + dx, ya + dy)], shade)
                }),
        )
        .map_err(e)?;
    Ok(())
}

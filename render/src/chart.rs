//! Line charts (optionally on a logarithmic y axis, several in a grid) and grouped bar charts
//! for experiment reports, written as PNG and SVG.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::RenderError;
use crate::font::{self, FONT_FAMILY};
use meshio::outfile::write_atomic;

/// Width and height of one chart cell in pixels.
const CELL: (u32, u32) = (560, 420);
/// Height of a figure title band.
const TITLE_BAND: u32 = 44;

/// Series colours, distinguishable in print and for common colour-vision deficiencies
/// (Okabe–Ito palette).
const PALETTE: [RGBColor; 6] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
];

/// One named sequence of `(x, y)` points.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
}

/// A line chart.
#[derive(Clone, Debug, PartialEq)]
pub struct LineChart {
    /// Title above the plot.
    pub title: String,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// The series.
    pub series: Vec<Series>,
    /// Logarithmic y axis: non-positive and non-finite values are skipped and counted in a note.
    pub log_y: bool,
}

/// A grouped bar chart (a histogram per group over shared categories).
#[derive(Clone, Debug, PartialEq)]
pub struct Histogram {
    /// Title.
    pub title: String,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// Category names along x.
    pub categories: Vec<String>,
    /// `(label, value per category)` for each group.
    pub groups: Vec<(String, Vec<f64>)>,
}

fn font(size: f64) -> FontDesc<'static> {
    (FONT_FAMILY, size).into_font()
}

/// Points of a series that can be drawn, and how many could not.
fn drawable(points: &[(f64, f64)], log_y: bool) -> (Vec<(f64, f64)>, usize) {
    let ok: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && (!log_y || *y > 0.0))
        .collect();
    let skipped = points.len() - ok.len();
    (ok, skipped)
}

/// Integers without a decimal point (iteration counts), other values with at most three
/// decimals and no trailing zeros (`-1.2`, not `-1.200`).
fn fmt_x(v: &f64) -> String {
    if (v - v.round()).abs() < 1e-9 {
        format!("{:.0}", v)
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// Tick labels along x in a chart cell: more overlap at the cell's width.
const X_TICKS: usize = 6;

/// The series of a line chart (with point markers if asked) and the legend, on either axis kind.
fn draw_series<'a, DB: DrawingBackend + 'a, X, Y>(
    c: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    prepared: &[(Vec<(f64, f64)>, usize)],
    chart: &LineChart,
    markers: bool,
) -> Result<(), String>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    let e = |x: &dyn std::fmt::Display| x.to_string();
    for (k, (pts, _)) in prepared.iter().enumerate() {
        let col = PALETTE[k % PALETTE.len()];
        c.draw_series(LineSeries::new(pts.iter().copied(), col.stroke_width(2)))
            .map_err(|x| e(&x))?
            .label(&chart.series[k].label)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], col.stroke_width(3)));
        if markers {
            c.draw_series(pts.iter().map(|&p| Circle::new(p, 3, col.filled())))
                .map_err(|x| e(&x))?;
        }
    }
    c.configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(font(14.0))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|x| e(&x))?;
    Ok(())
}

fn draw_line_chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &LineChart,
) -> Result<(), String> {
    let e = |x: &dyn std::fmt::Display| x.to_string();
    let prepared: Vec<(Vec<(f64, f64)>, usize)> = chart
        .series
        .iter()
        .map(|s| drawable(&s.points, chart.log_y))
        .collect();
    let skipped: usize = prepared.iter().map(|p| p.1).sum();
    let all = prepared.iter().flat_map(|p| p.0.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in all {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, if chart.log_y { 0.1 } else { 0.0 }, 1.0);
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    let (area, note_area) = area.split_vertically(area.dim_in_pixel().1.saturating_sub(26));
    let mut builder = ChartBuilder::on(&area);
    builder
        .caption(&chart.title, font(17.0))
        .margin(10)
        .x_label_area_size(42)
        .y_label_area_size(72);
    if chart.log_y {
        if y1 <= y0 {
            y1 = y0 * 10.0;
        }
        let (lo, hi) = (y0 / 3.0, y1 * 3.0);
        let mut c = builder
            .build_cartesian_2d(x0..x1, (lo..hi).log_scale())
            .map_err(|x| e(&x))?;
        c.configure_mesh()
            .max_light_lines(1)
            .x_desc(&chart.x_label)
            .y_desc(&chart.y_label)
            .label_style(font(14.0))
            .axis_desc_style(font(15.0))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .x_label_formatter(&fmt_x)
            .x_labels(X_TICKS)
            .draw()
            .map_err(|x| e(&x))?;
        draw_series(&mut c, &prepared, chart, true)?;
    } else {
        if y1 <= y0 {
            y1 = y0 + 1.0;
        }
        let pad = 0.05 * (y1 - y0);
        let mut c = builder
            .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + pad))
            .map_err(|x| e(&x))?;
        c.configure_mesh()
            .max_light_lines(1)
            .x_desc(&chart.x_label)
            .y_desc(&chart.y_label)
            .label_style(font(14.0))
            .axis_desc_style(font(15.0))
            .x_label_formatter(&fmt_x)
            .x_labels(X_TICKS)
            .draw()
            .map_err(|x| e(&x))?;
        draw_series(&mut c, &prepared, chart, false)?;
    }
    if skipped > 0 {
        note_area
            .draw_text(
                &format!("{skipped} point(s) not drawn (zero or non-finite on this axis)"),
                &font(13.0).color(&BLACK),
                (12, 4),
            )
            .map_err(|x| e(&x))?;
    }
    Ok(())
}

fn draw_histogram<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    h: &Histogram,
) -> Result<(), String> {
    let e = |x: &dyn std::fmt::Display| x.to_string();
    let n = h.categories.len().max(1);
    let g = h.groups.len().max(1);
    let ymax = h
        .groups
        .iter()
        .flat_map(|(_, v)| v.iter().copied())
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max)
        .max(1.0);
    let mut c = ChartBuilder::on(area)
        .caption(&h.title, font(18.0))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(-0.5..n as f64 - 0.5, 0.0..ymax * 1.12)
        .map_err(|x| e(&x))?;
    let cats = h.categories.clone();
    c.configure_mesh()
        .disable_x_mesh()
        .x_desc(&h.x_label)
        .y_desc(&h.y_label)
        .label_style(font(14.0))
        .axis_desc_style(font(15.0))
        .x_labels(n.min(30))
        .x_label_formatter(&move |v| {
            let i = v.round();
            if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < cats.len() {
                cats[i as usize].clone()
            } else {
                String::new()
            }
        })
        .y_label_formatter(&fmt_x)
        .draw()
        .map_err(|x| e(&x))?;
    let width = 0.8 / g as f64;
    for (k, (label, values)) in h.groups.iter().enumerate() {
        let col = PALETTE[k % PALETTE.len()];
        c.draw_series(
            values
                .iter()
                .enumerate()
                .filter(|(_, v)| v.is_finite() && **v > 0.0)
                .map(|(i, &v)| {
                    let x = i as f64 - 0.4 + k as f64 * width;
                    Rectangle::new([(x, 0.0), (x + width, v)], col.filled())
                }),
        )
        .map_err(|x| e(&x))?
        .label(label)
        .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 14, y + 6)], col.filled()));
    }
    c.configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(font(14.0))
        .draw()
        .map_err(|x| e(&x))?;
    Ok(())
}

/// Draws the same picture into an RGB buffer and an SVG string, then writes both atomically.
fn write_both(
    png: &Path,
    svg: &Path,
    size: (u32, u32),
    draw_png: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
    draw_svg: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<(), RenderError> {
    if !font::ensure_registered() {
        return Err(RenderError::Font {
            path: png.to_path_buf(),
        });
    }
    let (w, h) = size;
    let mut rgb = vec![0_u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|x| RenderError::Draw {
            path: png.to_path_buf(),
            message: x.to_string(),
        })?;
        draw_png(&root).map_err(|message| RenderError::Draw {
            path: png.to_path_buf(),
            message,
        })?;
    }
    let png_bytes = crate::curveplot::encode_png(&rgb, w, h).map_err(|e| RenderError::Encode {
        path: png.to_path_buf(),
        message: e.to_string(),
    })?;
    let mut svg_text = String::new();
    {
        let root = SVGBackend::with_string(&mut svg_text, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|x| RenderError::Draw {
            path: svg.to_path_buf(),
            message: x.to_string(),
        })?;
        draw_svg(&root).map_err(|message| RenderError::Draw {
            path: svg.to_path_buf(),
            message,
        })?;
    }
    write_atomic(png, &png_bytes)?;
    Ok(write_atomic(svg, svg_text.as_bytes())?)
}

fn grid<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    charts: &[LineChart],
    columns: usize,
    title: &str,
) -> Result<(), String> {
    let (body, head) = {
        let (t, b) = root.split_vertically(TITLE_BAND);
        (b, t)
    };
    head.draw_text(title, &font(20.0).color(&BLACK), (14, 10))
        .map_err(|x| x.to_string())?;
    let rows = charts.len().div_ceil(columns);
    let cells = body.split_evenly((rows, columns));
    for (cell, chart) in cells.iter().zip(charts) {
        draw_line_chart(cell, chart)?;
    }
    Ok(())
}

/// Several line charts in a grid of `columns` columns under a figure title, as PNG and SVG.
pub fn write_line_charts(
    charts: &[LineChart],
    columns: usize,
    title: &str,
    png: &Path,
    svg: &Path,
) -> Result<(), RenderError> {
    if charts.is_empty() {
        return Err(RenderError::EmptyFigure {
            path: png.to_path_buf(),
        });
    }
    let columns = columns.clamp(1, charts.len());
    let rows = charts.len().div_ceil(columns);
    let size = (CELL.0 * columns as u32, CELL.1 * rows as u32 + TITLE_BAND);
    write_both(
        png,
        svg,
        size,
        |r| grid(r, charts, columns, title),
        |r| grid(r, charts, columns, title),
    )
}

/// One line chart as PNG and SVG.
pub fn write_line_chart(chart: &LineChart, png: &Path, svg: &Path) -> Result<(), RenderError> {
    if chart.series.is_empty() {
        return Err(RenderError::EmptyFigure {
            path: png.to_path_buf(),
        });
    }
    let size = (900, 600);
    write_both(
        png,
        svg,
        size,
        |r| draw_line_chart(r, chart),
        |r| draw_line_chart(r, chart),
    )
}

/// A grouped bar chart as PNG and SVG.
pub fn write_histogram(h: &Histogram, png: &Path, svg: &Path) -> Result<(), RenderError> {
    if h.groups.is_empty() || h.categories.is_empty() {
        return Err(RenderError::EmptyFigure {
            path: png.to_path_buf(),
        });
    }
    write_both(
        png,
        svg,
        (900, 560),
        |r| draw_histogram(r, h),
        |r| draw_histogram(r, h),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_axis_skips_what_it_cannot_draw() {
        let (ok, skipped) = drawable(
            &[(0.0, 1.0), (1.0, 0.0), (2.0, f64::NAN), (3.0, 1e-30)],
            true,
        );
        assert_eq!(ok, vec![(0.0, 1.0), (3.0, 1e-30)]);
        assert_eq!(skipped, 2);
        let (ok, skipped) = drawable(&[(0.0, -1.0), (1.0, 0.0)], false);
        assert_eq!((ok.len(), skipped), (2, 0));
    }
}

//! Boundary-curve figures in the style of Mann (1994), *Using local optimization in surface
//! fitting*, Figure 2.
//!
//! A [`CurveFigure`] is a grid of [`CurvePanel`]s: one row per boundary-curve problem, one column
//! per construction method. Each panel shows
//!
//! * on top, the cubic with its control polygon (thin dashed grey) and its control points
//!   (crosses). All curve plots of a figure share one scale, with x and y units of the same
//!   length on screen, so shapes can be compared across methods and problems;
//! * below, the signed curvature against normalized arc length `s/L ∈ [0, 1]`, with the zero
//!   line and, as in the paper, the straight line joining the target end curvatures
//!   (`k0` at `s = 0`, `k1` at `s = L`). The curvature plots of a row share a y-range chosen by
//!   [`curvature_y_range`], which clips spikes (a short end tangent makes curvature reach the
//!   hundreds); clipped stretches are drawn along the plot border with a marker and the true
//!   extreme value;
//! * under both, notes: the end curvatures against their targets, the true curvature range, the
//!   arc length, then the caller's own notes.
//!
//! [`write_curve_figure`] writes the figure as PNG and as SVG (text kept as text), each
//! atomically.

use std::path::Path;

use curves::CubicBez2;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::font::{self, FONT_FAMILY};
use crate::RenderError;
use meshio::outfile::write_atomic;

/// One curve of a figure: a method's answer to one boundary-curve problem.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvePanel {
    /// Panel title, normally the construction method's name ("chord", "dbhs", "optimized").
    pub title: String,
    /// The cubic to draw.
    pub curve: CubicBez2,
    /// Target signed curvatures `[k0, k1]` at the start and end of the curve.
    pub targets: [f64; 2],
    /// Extra caption lines printed under the panel (for example `"α = (0.83, 1.21)"`); long
    /// lines are wrapped at spaces.
    pub notes: Vec<String>,
}

/// A grid of curve panels: each row is one problem, each column one method.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveFigure {
    /// Title printed above the figure.
    pub title: String,
    /// Rows of panels; rows may differ in length. Curvature plots share a y-range within a row,
    /// curve plots share their scale across the whole figure.
    pub rows: Vec<Vec<CurvePanel>>,
}

/// A y-axis range `[lo, hi]` with `lo < hi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct YRange {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
}

impl YRange {
    /// Whether `v` lies in the closed range.
    pub fn contains(&self, v: f64) -> bool {
        self.lo <= v && v <= self.hi
    }
}

// ---------------------------------------------------------------------------------------------
// Range selection (pure functions).

/// Fraction of samples trimmed at each end to find the "bulk" of a curvature plot: a spike from
/// a short tangent occupies only a few percent of equally spaced parameter samples.
pub const BULK_TRIM: f64 = 0.05;
/// How far beyond the core range (targets, zero and the bulk of the samples) the plot may extend
/// to show excursions in full, in units of the core's span. Values further out are clipped.
pub const EXCURSION_ALLOWANCE: f64 = 1.0;
/// Empty space added at both ends of a y-range, as a fraction of its span, so that lines along
/// the extremes stay clear of the frame.
pub const RANGE_MARGIN: f64 = 0.08;
/// Span used when all values coincide (a straight line aimed at zero curvature).
const FALLBACK_SPAN: f64 = 1.0;

/// The y-range of a row's curvature plots.
///
/// The *core* range is the hull of zero (the zero line is always shown), the finite `targets`
/// and the bulk of the finite `samples` (their [`BULK_TRIM`] to `1 − BULK_TRIM` quantiles).
/// Sample values beyond the core are shown while they stay within [`EXCURSION_ALLOWANCE`] core
/// spans of it; beyond that the range is cut, so a spike 1000 times the targets does not flatten
/// everything else. Finally [`RANGE_MARGIN`] of the span is added at both ends. Non-finite values
/// are ignored. The result always contains every finite target and zero.
pub fn curvature_y_range(targets: &[f64], samples: &[f64]) -> YRange {
    let mut finite: Vec<f64> = samples.iter().copied().filter(|v| v.is_finite()).collect();
    finite.sort_by(f64::total_cmp);
    let targets = targets.iter().copied().filter(|v| v.is_finite());

    let (mut core_lo, mut core_hi) = (0.0_f64, 0.0_f64);
    for t in targets.clone() {
        core_lo = core_lo.min(t);
        core_hi = core_hi.max(t);
    }
    let (mut data_lo, mut data_hi) = (core_lo, core_hi);
    if let (Some(&first), Some(&last)) = (finite.first(), finite.last()) {
        core_lo = core_lo.min(quantile(&finite, BULK_TRIM));
        core_hi = core_hi.max(quantile(&finite, 1.0 - BULK_TRIM));
        data_lo = data_lo.min(first);
        data_hi = data_hi.max(last);
    }
    let core_span = core_hi - core_lo;
    let allowance = EXCURSION_ALLOWANCE * core_span;
    let mut lo = data_lo.max(core_lo - allowance);
    let mut hi = data_hi.min(core_hi + allowance);
    let mut span = hi - lo;
    // A degenerate or overflowing span (all zero, or targets near f64::MAX).
    if span.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) || !span.is_finite() {
        let mid = if (0.5 * (lo + hi)).is_finite() {
            0.5 * (lo + hi)
        } else {
            0.0
        };
        lo = mid - 0.5 * FALLBACK_SPAN;
        hi = mid + 0.5 * FALLBACK_SPAN;
        span = FALLBACK_SPAN;
    }
    YRange {
        lo: lo - RANGE_MARGIN * span,
        hi: hi + RANGE_MARGIN * span,
    }
}

/// Nearest-rank quantile of sorted, non-empty `v`.
fn quantile(v: &[f64], q: f64) -> f64 {
    let i = ((v.len() - 1) as f64 * q).round() as usize;
    v[i.min(v.len() - 1)]
}

/// Axis-aligned bounding box `(x_lo, x_hi, y_lo, y_hi)`.
type BBox = (f64, f64, f64, f64);

/// Ranges for a plotting area of `pixels = (width, height)` that contain `bbox`, centred on it,
/// with one data unit the same number of pixels along x and along y (equal aspect ratio).
pub fn equal_aspect_ranges(bbox: BBox, pixels: (u32, u32)) -> ((f64, f64), (f64, f64)) {
    let (x0, x1, y0, y1) = bbox;
    let pw = f64::from(pixels.0.max(1));
    let ph = f64::from(pixels.1.max(1));
    let units_per_pixel = ((x1 - x0) / pw).max((y1 - y0) / ph);
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let (hw, hh) = (0.5 * units_per_pixel * pw, 0.5 * units_per_pixel * ph);
    ((cx - hw, cx + hw), (cy - hh, cy + hh))
}

/// Bounding box of the finite points, padded by [`RANGE_MARGIN`] of the larger side; a unit box
/// around the origin if there are none, and at least [`FALLBACK_SPAN`] wide if they coincide.
fn padded_bbox<'a>(points: impl Iterator<Item = &'a (f64, f64)>) -> BBox {
    let mut b = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in points.filter(|(x, y)| x.is_finite() && y.is_finite()) {
        b = (b.0.min(x), b.1.max(x), b.2.min(y), b.3.max(y));
    }
    if b.0 > b.1 {
        b = (0.0, 0.0, 0.0, 0.0);
    }
    let mut side = (b.1 - b.0).max(b.3 - b.2);
    if !(side.is_finite() && side > 0.0) {
        side = FALLBACK_SPAN;
    }
    let pad = RANGE_MARGIN * side;
    let (cx, cy) = (0.5 * (b.0 + b.1), 0.5 * (b.2 + b.3));
    let hw = 0.5 * (b.1 - b.0).max(side * 1e-3) + pad;
    let hh = 0.5 * (b.3 - b.2).max(side * 1e-3) + pad;
    (cx - hw, cx + hw, cy - hh, cy + hh)
}

// ---------------------------------------------------------------------------------------------
// Layout and styling.

/// Pixel width of one column (one method).
const COLUMN_WIDTH: u32 = 420;
/// Height of a panel's title strip.
const PANEL_TITLE_HEIGHT: u32 = 40;
/// Height of the curve plot including its axis labels.
const CURVE_HEIGHT: u32 = 290;
/// Height of the curvature plot including its axis labels.
const KAPPA_HEIGHT: u32 = 290;
/// Height of one caption line.
const NOTE_LINE_HEIGHT: u32 = 24;
/// Space between the last caption line and the next row.
const ROW_GAP: u32 = 16;
/// Space above the figure title.
const FIGURE_TOP: u32 = 12;
/// Height of one line of the figure title (long titles are wrapped).
const FIGURE_TITLE_LINE_HEIGHT: u32 = 38;
/// Height of one legend line.
const LEGEND_LINE_HEIGHT: u32 = 28;
/// Horizontal padding of captions and legend inside their column or the figure.
const TEXT_PAD: u32 = 14;

/// Font sizes as plotters' size parameter. With the bundled font this is the glyph cell height in
/// PNG pixels; SVG output writes `size / 1.24` as its `font-size`, so 18 gives at least 14.5 px
/// text in both.
const TEXT_SIZE: f64 = 18.0;
const PANEL_TITLE_SIZE: f64 = 24.0;
const FIGURE_TITLE_SIZE: f64 = 28.0;

/// Samples along each curve for drawing its shape.
const CURVE_SAMPLES: usize = 300;
/// Curvature samples per curve (equally spaced in the parameter; a spike at a short tangent,
/// where the speed is small, is thereby sampled densely in arc length).
const KAPPA_SAMPLES: usize = 401;

/// Stroke width of curves and curvature lines (the bitmap backend draws wider strokes with
/// ragged joins between short segments).
const CURVE_STROKE: u32 = 2;
/// Normalized arc length is plotted over `[−KAPPA_X_PAD, 1 + KAPPA_X_PAD]`, so that behaviour
/// at the ends (and the target markers there) stays clear of the frame.
const KAPPA_X_PAD: f64 = 0.03;

const CURVE_COLOR: RGBColor = RGBColor(31, 94, 180);
const POLYGON_COLOR: RGBColor = RGBColor(130, 130, 130);
const POINT_COLOR: RGBColor = RGBColor(20, 20, 20);
const TARGET_COLOR: RGBColor = RGBColor(200, 30, 40);
const CLIP_COLOR: RGBColor = RGBColor(240, 130, 0);
const GRID_COLOR: RGBColor = RGBColor(228, 228, 228);
const ZERO_COLOR: RGBColor = RGBColor(70, 70, 70);
const SEPARATOR_COLOR: RGBColor = RGBColor(190, 190, 190);

/// Axis label areas and margin of both plots of a panel.
const PLOT_MARGIN: u32 = 12;
const X_LABEL_AREA: u32 = 44;
const Y_LABEL_AREA: u32 = 66;

fn text_font(size: f64) -> FontDesc<'static> {
    (FONT_FAMILY, size).into_font()
}

/// Width of `text` in pixels; a generous estimate if the font cannot lay it out.
fn text_width(text: &str, size: f64) -> u32 {
    text_font(size)
        .box_size(text)
        .map(|(w, _)| w)
        .unwrap_or_else(|_| (text.chars().count() as f64 * size * 0.65) as u32)
}

/// Greedy word wrap of `text` into lines of at most `width` pixels (a single word wider than the
/// line is kept whole).
fn wrap(text: &str, size: f64, width: u32) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if !line.is_empty() && text_width(&candidate, size) > width {
            lines.push(std::mem::take(&mut line));
            line = word.to_string();
        } else {
            line = candidate;
        }
    }
    lines.push(line);
    lines
}

/// The panel title size, reduced (down to the caption size) for a title wider than a column.
fn panel_title_size(title: &str) -> f64 {
    let available = f64::from(COLUMN_WIDTH - 2 * TEXT_PAD);
    let wide = f64::from(text_width(title, PANEL_TITLE_SIZE));
    if wide <= available {
        PANEL_TITLE_SIZE
    } else {
        (PANEL_TITLE_SIZE * available / wide).max(TEXT_SIZE)
    }
}

/// A number with about four significant digits, for captions.
fn fmt_num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    let s = if a >= 1e5 || (a < 1e-3 && a > 0.0) {
        format!("{v:.3e}")
    } else if a >= 1000.0 {
        format!("{v:.0}")
    } else if a >= 100.0 {
        format!("{v:.1}")
    } else if a >= 10.0 {
        format!("{v:.2}")
    } else {
        format!("{v:.3}")
    };
    if s.parse::<f64>() == Ok(0.0) {
        "0".to_string()
    } else {
        s
    }
}

/// Tick label with as many decimals as a tick spacing of about `span / 5` needs.
fn fmt_tick(v: f64, span: f64) -> String {
    let decimals = if span > 0.0 && span.is_finite() {
        (1.0 - (span / 5.0).log10().floor()).clamp(0.0, 6.0) as usize
    } else {
        2
    };
    let s = format!("{v:.decimals$}");
    // Trailing zeros carry nothing on an axis whose ticks are round numbers: "0.40" → "0.4".
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s.parse::<f64>() == Ok(0.0) {
        "0".to_string()
    } else {
        s
    }
}

// ---------------------------------------------------------------------------------------------
// Data preparation, shared by the PNG and SVG renderings.

/// A run of clipped curvature samples along one border.
struct ClipRun {
    /// Normalized arc lengths of the run's samples.
    us: Vec<f64>,
    /// Position and true value of the run's extreme.
    extreme: (f64, f64),
    /// Clipped at the top (true) or bottom.
    top: bool,
}

struct PreparedPanel<'a> {
    panel: &'a CurvePanel,
    /// The curve, split where it is not finite.
    curve_runs: Vec<Vec<(f64, f64)>>,
    control_points: Vec<(f64, f64)>,
    /// Curvature against normalized arc length (or `t` if the length is degenerate), split where
    /// the curvature is not finite.
    kappa_runs: Vec<Vec<(f64, f64)>>,
    clip_runs: Vec<ClipRun>,
    /// Caption lines, wrapped.
    notes: Vec<String>,
}

struct PreparedRow<'a> {
    panels: Vec<PreparedPanel<'a>>,
    y: YRange,
    note_lines: usize,
}

struct Prepared<'a> {
    /// The figure title, wrapped to the figure width.
    title_lines: Vec<String>,
    rows: Vec<PreparedRow<'a>>,
    columns: usize,
    curve_bbox: BBox,
    legend: Vec<Vec<LegendItem>>,
}

impl Prepared<'_> {
    fn width(&self) -> u32 {
        COLUMN_WIDTH * self.columns as u32
    }
    fn header_height(&self) -> u32 {
        self.title_height() + LEGEND_LINE_HEIGHT * self.legend.len() as u32 + 8
    }
    fn title_height(&self) -> u32 {
        FIGURE_TOP + FIGURE_TITLE_LINE_HEIGHT * self.title_lines.len() as u32
    }
    fn row_height(row: &PreparedRow<'_>) -> u32 {
        PANEL_TITLE_HEIGHT
            + CURVE_HEIGHT
            + KAPPA_HEIGHT
            + NOTE_LINE_HEIGHT * row.note_lines as u32
            + ROW_GAP
    }
    fn height(&self) -> u32 {
        self.header_height() + self.rows.iter().map(Self::row_height).sum::<u32>()
    }
}

/// Split a sequence at non-finite points into runs of finite points.
fn finite_runs(points: impl Iterator<Item = (f64, f64)>) -> Vec<Vec<(f64, f64)>> {
    let mut runs = vec![Vec::new()];
    for p in points {
        if p.0.is_finite() && p.1.is_finite() {
            if let Some(run) = runs.last_mut() {
                run.push(p);
            }
        } else if runs.last().is_some_and(|r| !r.is_empty()) {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// Curvature samples of one panel before the row's range is known.
struct KappaData {
    points: Vec<(f64, f64)>,
    skipped: usize,
    degenerate_length: bool,
}

fn kappa_data(curve: &CubicBez2) -> KappaData {
    let samples = curve.curvature_samples(KAPPA_SAMPLES);
    let length = samples.last().map_or(f64::NAN, |s| s.s);
    let degenerate_length = !(length.is_finite() && length > 0.0);
    let points = samples
        .iter()
        .map(|s| {
            let u = if degenerate_length { s.t } else { s.s / length };
            (u, s.kappa)
        })
        .collect::<Vec<_>>();
    let skipped = points.iter().filter(|p| !p.1.is_finite()).count();
    KappaData {
        points,
        skipped,
        degenerate_length,
    }
}

fn clip_runs(points: &[(f64, f64)], y: YRange) -> Vec<ClipRun> {
    let mut runs: Vec<ClipRun> = Vec::new();
    let mut current: Option<ClipRun> = None;
    for &(u, k) in points {
        let side = if !k.is_finite() {
            None
        } else if k > y.hi {
            Some(true)
        } else if k < y.lo {
            Some(false)
        } else {
            None
        };
        match (side, current.as_mut()) {
            (Some(top), Some(run)) if run.top == top => {
                run.us.push(u);
                if (top && k > run.extreme.1) || (!top && k < run.extreme.1) {
                    run.extreme = (u, k);
                }
            }
            (Some(top), _) => {
                runs.extend(current.take());
                current = Some(ClipRun {
                    us: vec![u],
                    extreme: (u, k),
                    top,
                });
            }
            (None, _) => runs.extend(current.take()),
        }
    }
    runs.extend(current);
    runs
}

fn prepare(fig: &CurveFigure) -> Prepared<'_> {
    let columns = fig.rows.iter().map(Vec::len).max().unwrap_or(0).max(1);
    let note_width = COLUMN_WIDTH - 2 * TEXT_PAD;
    let mut all_points = Vec::new();
    let mut rows = Vec::new();
    for row in &fig.rows {
        let data: Vec<KappaData> = row.iter().map(|p| kappa_data(&p.curve)).collect();
        let targets: Vec<f64> = row.iter().flat_map(|p| p.targets).collect();
        let samples: Vec<f64> = data
            .iter()
            .flat_map(|d| d.points.iter().map(|p| p.1))
            .collect();
        let y = curvature_y_range(&targets, &samples);
        let mut panels = Vec::new();
        for (panel, d) in row.iter().zip(data) {
            let c = &panel.curve;
            let curve_pts: Vec<(f64, f64)> = (0..CURVE_SAMPLES)
                .map(|i| {
                    let p = c.eval(i as f64 / (CURVE_SAMPLES - 1) as f64);
                    (p.x, p.y)
                })
                .collect();
            let control_points: Vec<(f64, f64)> = c.points.iter().map(|p| (p.x, p.y)).collect();
            all_points.extend(curve_pts.iter().copied());
            all_points.extend(control_points.iter().copied());
            let clip = clip_runs(&d.points, y);
            let notes = panel_notes(panel, &d, !clip.is_empty());
            let notes = notes
                .iter()
                .flat_map(|n| wrap(n, TEXT_SIZE, note_width))
                .collect();
            panels.push(PreparedPanel {
                panel,
                curve_runs: finite_runs(curve_pts.into_iter()),
                control_points,
                kappa_runs: finite_runs(d.points.iter().copied()),
                clip_runs: clip,
                notes,
            });
        }
        let note_lines = panels.iter().map(|p| p.notes.len()).max().unwrap_or(0);
        rows.push(PreparedRow {
            panels,
            y,
            note_lines,
        });
    }
    let text_width = COLUMN_WIDTH * columns as u32 - 2 * TEXT_PAD;
    let legend = legend_lines(text_width);
    Prepared {
        title_lines: wrap(&fig.title, FIGURE_TITLE_SIZE, text_width),
        rows,
        columns,
        curve_bbox: padded_bbox(all_points.iter()),
        legend,
    }
}

/// Automatic caption lines (end curvatures against targets, true curvature range, arc length)
/// followed by the caller's notes.
fn panel_notes(panel: &CurvePanel, d: &KappaData, clipped: bool) -> Vec<String> {
    let c = &panel.curve;
    let [k0, k1] = panel.targets;
    let mut notes = vec![
        format!(
            "κ(0) = {}, target {}",
            fmt_num(c.curvature(0.0)),
            fmt_num(k0)
        ),
        format!(
            "κ(1) = {}, target {}",
            fmt_num(c.curvature(1.0)),
            fmt_num(k1)
        ),
    ];
    let finite = d.points.iter().map(|p| p.1).filter(|k| k.is_finite());
    let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), k| {
        (lo.min(k), hi.max(k))
    });
    if lo <= hi {
        let mut line = format!("κ from {} to {}", fmt_num(lo), fmt_num(hi));
        if clipped {
            line.push_str(" (clipped in plot)");
        }
        notes.push(line);
    } else {
        notes.push("κ undefined at every sample".to_string());
    }
    if d.skipped > 0 {
        notes.push(format!("{} non-finite κ samples skipped", d.skipped));
    }
    let length = c.arc_length();
    if d.degenerate_length {
        notes.push(format!(
            "arc length {}: κ plotted against t",
            fmt_num(length)
        ));
    } else {
        notes.push(format!("arc length L = {}", fmt_num(length)));
    }
    notes.extend(panel.notes.iter().cloned());
    notes
}

/// One legend entry: a swatch and its text.
#[derive(Clone, Copy)]
enum Swatch {
    Curve,
    Polygon,
    Target,
    Clipped,
}

struct LegendItem {
    swatch: Swatch,
    text: &'static str,
}

const LEGEND: [(Swatch, &str); 4] = [
    (Swatch::Curve, "curve; its signed curvature κ over s/L"),
    (Swatch::Polygon, "control polygon and points"),
    (Swatch::Target, "line joining target end curvatures"),
    (
        Swatch::Clipped,
        "κ beyond plot range (true extreme printed)",
    ),
];
const SWATCH_WIDTH: u32 = 36;
const LEGEND_ITEM_GAP: u32 = 30;

fn legend_item_width(text: &str) -> u32 {
    SWATCH_WIDTH + 8 + text_width(text, TEXT_SIZE) + LEGEND_ITEM_GAP
}

/// Flow the legend items into lines of at most `width` pixels.
fn legend_lines(width: u32) -> Vec<Vec<LegendItem>> {
    let mut lines: Vec<Vec<LegendItem>> = vec![Vec::new()];
    let mut used = 0;
    for (swatch, text) in LEGEND {
        let w = legend_item_width(text);
        if used > 0 && used + w > width {
            lines.push(Vec::new());
            used = 0;
        }
        if let Some(line) = lines.last_mut() {
            line.push(LegendItem { swatch, text });
        }
        used += w;
    }
    lines
}

// ---------------------------------------------------------------------------------------------
// Drawing, generic over the plotters backend.

fn draw_figure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    prep: &Prepared<'_>,
) -> Result<(), String> {
    let e = |err: DrawingAreaErrorKind<DB::ErrorType>| err.to_string();
    root.fill(&WHITE).map_err(e)?;
    let width = prep.width();
    let left_top = Pos::new(HPos::Left, VPos::Top);
    let center_top = Pos::new(HPos::Center, VPos::Top);

    // Figure title and legend.
    for (i, line) in prep.title_lines.iter().enumerate() {
        root.draw(&Text::new(
            line.clone(),
            (
                (width / 2) as i32,
                (FIGURE_TOP + FIGURE_TITLE_LINE_HEIGHT * i as u32) as i32,
            ),
            text_font(FIGURE_TITLE_SIZE).color(&BLACK).pos(center_top),
        ))
        .map_err(e)?;
    }
    for (i, line) in prep.legend.iter().enumerate() {
        let y =
            (prep.title_height() + LEGEND_LINE_HEIGHT * i as u32 + LEGEND_LINE_HEIGHT / 2) as i32;
        let line_width: u32 = line
            .iter()
            .map(|it| legend_item_width(it.text))
            .sum::<u32>()
            .saturating_sub(LEGEND_ITEM_GAP);
        let mut x = (width.saturating_sub(line_width) / 2) as i32;
        for item in line {
            draw_swatch(root, item.swatch, x, y).map_err(e)?;
            let tx = x + SWATCH_WIDTH as i32 + 8;
            root.draw(&Text::new(
                item.text,
                (tx, y),
                text_font(TEXT_SIZE)
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Left, VPos::Center)),
            ))
            .map_err(e)?;
            x += legend_item_width(item.text) as i32;
        }
    }

    let mut y0 = prep.header_height();
    for row in &prep.rows {
        let h = Prepared::row_height(row);
        root.draw(&PathElement::new(
            vec![(0, y0 as i32), (width as i32, y0 as i32)],
            SEPARATOR_COLOR.stroke_width(1),
        ))
        .map_err(e)?;
        for (col, panel) in row.panels.iter().enumerate() {
            let area = root
                .clone()
                .shrink((COLUMN_WIDTH * col as u32, y0), (COLUMN_WIDTH, h));
            area.draw(&Text::new(
                panel.panel.title.clone(),
                ((COLUMN_WIDTH / 2) as i32, 10),
                text_font(panel_title_size(&panel.panel.title))
                    .color(&BLACK)
                    .pos(center_top),
            ))
            .map_err(e)?;
            let curve_area = area
                .clone()
                .shrink((0, PANEL_TITLE_HEIGHT), (COLUMN_WIDTH, CURVE_HEIGHT));
            draw_curve_plot(&curve_area, panel, prep.curve_bbox).map_err(e)?;
            let kappa_area = area.clone().shrink(
                (0, PANEL_TITLE_HEIGHT + CURVE_HEIGHT),
                (COLUMN_WIDTH, KAPPA_HEIGHT),
            );
            draw_kappa_plot(&kappa_area, panel, row.y).map_err(e)?;
            for (i, note) in panel.notes.iter().enumerate() {
                let y = PANEL_TITLE_HEIGHT
                    + CURVE_HEIGHT
                    + KAPPA_HEIGHT
                    + 4
                    + NOTE_LINE_HEIGHT * i as u32;
                area.draw(&Text::new(
                    note.clone(),
                    (TEXT_PAD as i32, y as i32),
                    text_font(TEXT_SIZE).color(&BLACK).pos(left_top),
                ))
                .map_err(e)?;
            }
        }
        y0 += h;
    }
    root.present().map_err(e)?;
    Ok(())
}

fn draw_swatch<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    swatch: Swatch,
    x: i32,
    y: i32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let w = SWATCH_WIDTH as i32;
    let line = vec![(x, y), (x + w, y)];
    match swatch {
        Swatch::Curve => root.draw(&PathElement::new(
            line,
            CURVE_COLOR.stroke_width(CURVE_STROKE + 1),
        )),
        Swatch::Polygon => {
            root.draw(&DashedPathElement::new(
                line,
                6,
                4,
                POLYGON_COLOR.stroke_width(1),
            ))?;
            root.draw(&Cross::new((x + 4, y), 5, POINT_COLOR.stroke_width(2)))?;
            root.draw(&Cross::new((x + w - 4, y), 5, POINT_COLOR.stroke_width(2)))
        }
        Swatch::Target => root.draw(&DashedPathElement::new(
            line,
            8,
            5,
            TARGET_COLOR.stroke_width(2),
        )),
        Swatch::Clipped => {
            root.draw(&PathElement::new(line, CLIP_COLOR.stroke_width(5)))?;
            root.draw(&Polygon::new(
                vec![
                    (x + w / 2, y - 12),
                    (x + w / 2 - 6, y - 2),
                    (x + w / 2 + 6, y - 2),
                ],
                CLIP_COLOR.filled(),
            ))
        }
    }
}

fn draw_curve_plot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &PreparedPanel<'_>,
    bbox: BBox,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let builder = || {
        let mut b = ChartBuilder::on(area);
        b.margin(PLOT_MARGIN)
            .x_label_area_size(X_LABEL_AREA)
            .y_label_area_size(Y_LABEL_AREA);
        b
    };
    // The plotting area's pixel size does not depend on the ranges: build once to measure it.
    let probe = builder().build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
    let pixels = probe.plotting_area().dim_in_pixel();
    let ((x0, x1), (y0, y1)) = equal_aspect_ranges(bbox, pixels);
    let mut chart = builder().build_cartesian_2d(x0..x1, y0..y1)?;
    let (xs, ys) = (x1 - x0, y1 - y0);
    let x_fmt = |v: &f64| fmt_tick(*v, xs);
    let y_fmt = |v: &f64| fmt_tick(*v, ys);
    chart
        .configure_mesh()
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style(text_font(TEXT_SIZE))
        .axis_desc_style(text_font(TEXT_SIZE))
        .x_desc("x")
        .y_desc("y")
        .bold_line_style(GRID_COLOR.stroke_width(1))
        .light_line_style(TRANSPARENT)
        .draw()?;
    let pts = &panel.control_points;
    chart.draw_series(DashedLineSeries::new(
        pts.iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite()),
        6,
        4,
        POLYGON_COLOR.stroke_width(1),
    ))?;
    for run in &panel.curve_runs {
        chart.draw_series(LineSeries::new(
            run.iter().copied(),
            CURVE_COLOR.stroke_width(CURVE_STROKE),
        ))?;
    }
    chart.draw_series(
        pts.iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&p| Cross::new(p, 6, POINT_COLOR.stroke_width(2))),
    )?;
    Ok(())
}

fn draw_kappa_plot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &PreparedPanel<'_>,
    y: YRange,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(area)
        .margin(PLOT_MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(-KAPPA_X_PAD..1.0 + KAPPA_X_PAD, y.lo..y.hi)?;
    let span = y.hi - y.lo;
    let y_fmt = |v: &f64| fmt_tick(*v, span);
    let x_fmt = |v: &f64| fmt_tick(*v, 1.0);
    chart
        .configure_mesh()
        .x_labels(6)
        .y_labels(6)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style(text_font(TEXT_SIZE))
        .axis_desc_style(text_font(TEXT_SIZE))
        .x_desc("s / L")
        .y_desc("κ")
        .bold_line_style(GRID_COLOR.stroke_width(1))
        .light_line_style(TRANSPARENT)
        .draw()?;
    chart.draw_series(LineSeries::new(
        [(-KAPPA_X_PAD, 0.0), (1.0 + KAPPA_X_PAD, 0.0)],
        ZERO_COLOR.stroke_width(1),
    ))?;
    // Clipped stretches along the border, under the curve.
    for run in &panel.clip_runs {
        let border = if run.top { y.hi } else { y.lo };
        chart.draw_series(LineSeries::new(
            run.us.iter().map(|&u| (u, border)),
            CLIP_COLOR.stroke_width(5),
        ))?;
    }
    // Target line, as in the paper: straight from k0 at s = 0 to k1 at s = L.
    let [k0, k1] = panel.panel.targets;
    if k0.is_finite() && k1.is_finite() {
        chart.draw_series(DashedLineSeries::new(
            [(0.0, k0), (1.0, k1)],
            8,
            5,
            TARGET_COLOR.stroke_width(2),
        ))?;
    }
    for run in &panel.kappa_runs {
        chart.draw_series(LineSeries::new(
            run.iter().map(|&(u, k)| (u, k.clamp(y.lo, y.hi))),
            CURVE_COLOR.stroke_width(CURVE_STROKE),
        ))?;
    }
    // The targets' end points, on top of the curve so a match is visible.
    chart.draw_series(
        [(0.0, k0), (1.0, k1)]
            .into_iter()
            .filter(|p| y.contains(p.1))
            .map(|p| Circle::new(p, 5, TARGET_COLOR.stroke_width(2))),
    )?;
    // A marker and the true value at the extreme of each clipped stretch.
    for run in &panel.clip_runs {
        let (u, k) = run.extreme;
        let (border, dir) = if run.top { (y.hi, 1) } else { (y.lo, -1) };
        let anchor_left = u < 0.5;
        let label_pos = Pos::new(
            if anchor_left { HPos::Left } else { HPos::Right },
            if run.top { VPos::Top } else { VPos::Bottom },
        );
        let dx = if anchor_left { 12 } else { -12 };
        chart.plotting_area().draw(
            &(EmptyElement::at((u, border))
                + Polygon::new(
                    vec![(0, 0), (-7, 13 * dir), (7, 13 * dir)],
                    CLIP_COLOR.filled(),
                )
                + Text::new(
                    format!("{} {}", if run.top { "max" } else { "min" }, fmt_num(k)),
                    (dx, 4 * dir),
                    text_font(TEXT_SIZE)
                        .color(&CLIP_COLOR.mix(1.0))
                        .pos(label_pos),
                )),
        )?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Output.

/// Width and height in pixels of the PNG (and SVG) [`write_curve_figure`] writes for `fig`:
/// 420 px per column and, per row, about 600 px of plots plus the caption lines.
pub fn figure_size(fig: &CurveFigure) -> (u32, u32) {
    let prep = prepare(fig);
    (prep.width(), prep.height())
}

/// Draw `fig` and write it as a PNG at `png` and an SVG at `svg`, each atomically (an existing
/// file is replaced only by a complete new one). The figure is rendered fully before either file
/// is written.
///
/// Degenerate curves do not panic: non-finite curvature samples (a cusp) are skipped, and a
/// curve of zero length has its curvature plotted against the parameter. A figure without any
/// panel is an error.
pub fn write_curve_figure(fig: &CurveFigure, png: &Path, svg: &Path) -> Result<(), RenderError> {
    if fig.rows.iter().all(Vec::is_empty) {
        return Err(RenderError::EmptyFigure {
            path: png.to_path_buf(),
        });
    }
    if !font::ensure_registered() {
        return Err(RenderError::Font {
            path: png.to_path_buf(),
        });
    }
    let prep = prepare(fig);
    let (w, h) = (prep.width(), prep.height());

    let mut rgb = vec![0_u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        draw_figure(&root, &prep).map_err(|message| RenderError::Draw {
            path: png.to_path_buf(),
            message,
        })?;
    }
    let png_bytes = encode_png(&rgb, w, h).map_err(|e| RenderError::Encode {
        path: png.to_path_buf(),
        message: e.to_string(),
    })?;

    let mut svg_text = String::new();
    {
        let root = SVGBackend::with_string(&mut svg_text, (w, h)).into_drawing_area();
        draw_figure(&root, &prep).map_err(|message| RenderError::Draw {
            path: svg.to_path_buf(),
            message,
        })?;
    }

    write_atomic(png, &png_bytes)?;
    Ok(write_atomic(svg, svg_text.as_bytes())?)
}

pub(crate) fn encode_png(rgb: &[u8], w: u32, h: u32) -> std::io::Result<Vec<u8>> {
    let mut out = Vec::new();
    crate::shade::write_rgb_png(rgb, w, h, &mut out)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative agreement expected of quantities computed by a few floating-point operations on
    /// values of order one.
    const ROUNDING: f64 = 1e-12;

    /// Smooth curvature samples between `lo` and `hi`, like those of a fair cubic.
    fn smooth(n: usize, lo: f64, hi: f64) -> Vec<f64> {
        (0..n)
            .map(|i| {
                let u = i as f64 / (n - 1) as f64;
                lo + (hi - lo) * (std::f64::consts::PI * u).sin()
            })
            .collect()
    }

    #[test]
    fn range_of_fair_samples_shows_everything_with_margins() {
        let samples = smooth(401, -0.9, -0.72);
        let y = curvature_y_range(&[-0.8, -0.8], &samples);
        assert!(y.contains(-0.8) && y.contains(0.0));
        assert!(samples.iter().all(|&k| y.contains(k)));
        // Hull of {0, −0.9} plus RANGE_MARGIN of its span at each end.
        assert!((y.lo - (-0.9 - RANGE_MARGIN * 0.9)).abs() < ROUNDING);
        assert!((y.hi - RANGE_MARGIN * 0.9).abs() < ROUNDING);
    }

    #[test]
    fn range_clips_a_thousandfold_spike() {
        // 401 samples around the target with the first 8 (2 %, a short tangent's spike) at
        // 1000 times the target's size.
        let mut samples = smooth(401, -0.95, -0.7);
        for k in samples.iter_mut().take(8) {
            *k = 800.0;
        }
        let y = curvature_y_range(&[-0.8, -0.8], &samples);
        assert!(y.contains(-0.8) && y.contains(0.0));
        // The core is [−0.95, 0]; one core span of excursion plus margins caps the top below 1.2.
        assert!(y.hi < 1.2, "{y:?}");
        assert!(y.lo > -2.1, "{y:?}");
        assert!(!y.contains(800.0));
        // Negative spikes likewise.
        let flipped: Vec<f64> = samples.iter().map(|k| -k).collect();
        let y = curvature_y_range(&[0.8, 0.8], &flipped);
        assert!(
            y.contains(0.8) && y.lo > -1.2 && !y.contains(-800.0),
            "{y:?}"
        );
    }

    #[test]
    fn range_shows_moderate_excursions_in_full() {
        let mut samples = smooth(401, -1.0, -0.5);
        // The core is [q, 0] with q ≈ −0.96 the 5 % quantile: 0.9 lies within one core
        // span above it and is shown, 1.5 lies beyond and is clipped there.
        samples[0] = 1.5;
        samples[1] = 0.9;
        let mut sorted = samples.clone();
        sorted.sort_by(f64::total_cmp);
        let q = quantile(&sorted, BULK_TRIM);
        assert!(q > -1.0 && q < -0.95, "{q}");
        let y = curvature_y_range(&[-0.8, -0.8], &samples);
        assert!(y.contains(0.9) && y.contains(-1.0));
        assert!(!y.contains(1.5));
        let (lo, hi) = (-1.0, -q);
        assert!(
            (y.hi - (hi + RANGE_MARGIN * (hi - lo))).abs() < ROUNDING,
            "{y:?}"
        );
        assert!(
            (y.lo - (lo - RANGE_MARGIN * (hi - lo))).abs() < ROUNDING,
            "{y:?}"
        );
    }

    #[test]
    fn range_contains_targets_far_from_the_samples() {
        let samples = smooth(101, 0.1, 0.2);
        let y = curvature_y_range(&[-30.0, 45.0], &samples);
        assert!(y.contains(-30.0) && y.contains(45.0));
    }

    #[test]
    fn range_ignores_non_finite_values_and_survives_empty_input() {
        let y = curvature_y_range(
            &[f64::NAN, -0.5],
            &[f64::NAN, f64::INFINITY, -1.0, f64::NEG_INFINITY, -0.25],
        );
        assert!(y.lo.is_finite() && y.hi.is_finite());
        assert!(y.contains(-1.0) && y.contains(0.0) && y.contains(-0.5));
        // Nothing at all, or only zeros: a unit range around zero plus margins.
        for y in [
            curvature_y_range(&[], &[]),
            curvature_y_range(&[0.0, 0.0], &[0.0; 10]),
        ] {
            assert!((y.lo + 0.5 + RANGE_MARGIN).abs() < ROUNDING, "{y:?}");
            assert!((y.hi - 0.5 - RANGE_MARGIN).abs() < ROUNDING, "{y:?}");
        }
    }

    #[test]
    fn equal_aspect_ranges_have_equal_units_and_contain_the_box() {
        let bbox = (-0.1, 1.1, -0.2, 0.3);
        for pixels in [(330, 220), (200, 400), (1, 1)] {
            let ((x0, x1), (y0, y1)) = equal_aspect_ranges(bbox, pixels);
            let ux = (x1 - x0) / f64::from(pixels.0);
            let uy = (y1 - y0) / f64::from(pixels.1);
            assert!((ux - uy).abs() < ROUNDING * ux, "{pixels:?}");
            assert!(x0 <= bbox.0 && x1 >= bbox.1 && y0 <= bbox.2 && y1 >= bbox.3);
            // Centred on the box.
            assert!((x0 + x1 - (bbox.0 + bbox.1)).abs() < ROUNDING);
            assert!((y0 + y1 - (bbox.2 + bbox.3)).abs() < ROUNDING);
        }
    }

    #[test]
    fn padded_bbox_handles_empty_and_coincident_points() {
        let b = padded_bbox([(f64::NAN, 0.0)].iter());
        assert!(b.0 < 0.0 && b.1 > 0.0 && b.2 < 0.0 && b.3 > 0.0);
        let b = padded_bbox([(2.0, 3.0), (2.0, 3.0)].iter());
        assert!(b.0 < 2.0 && b.1 > 2.0 && b.2 < 3.0 && b.3 > 3.0);
        let b = padded_bbox([(0.0, 0.0), (1.0, 0.0), (0.5, 0.1)].iter());
        assert!((b.0 + RANGE_MARGIN).abs() < ROUNDING);
        assert!((b.1 - 1.0 - RANGE_MARGIN).abs() < ROUNDING);
    }

    #[test]
    fn runs_split_at_non_finite_points_and_clipping() {
        let pts = [
            (0.0, 5.0),
            (0.1, 3.0),
            (0.2, 0.5),
            (0.3, f64::NAN),
            (0.4, -0.5),
            (0.5, -4.0),
            (0.6, -6.0),
            (0.7, 0.0),
        ];
        let runs = finite_runs(pts.iter().copied());
        assert_eq!(runs.iter().map(Vec::len).collect::<Vec<_>>(), vec![3, 4]);
        let clip = clip_runs(&pts, YRange { lo: -2.0, hi: 2.0 });
        assert_eq!(clip.len(), 2);
        assert!(clip[0].top && clip[0].extreme == (0.0, 5.0) && clip[0].us == vec![0.0, 0.1]);
        assert!(!clip[1].top && clip[1].extreme == (0.6, -6.0) && clip[1].us == vec![0.5, 0.6]);
    }

    #[test]
    fn numbers_are_formatted_compactly() {
        assert_eq!(fmt_num(-0.8), "-0.800");
        assert_eq!(fmt_num(10.932), "10.93");
        assert_eq!(fmt_num(312.44), "312.4");
        assert_eq!(fmt_num(-1234.5), "-1234");
        assert_eq!(fmt_num(-1e-9), "-1.000e-9");
        assert_eq!(fmt_num(-0.0), "0");
        assert_eq!(fmt_tick(0.4, 0.8), "0.4");
        assert_eq!(fmt_tick(-0.0, 0.8), "0");
        assert_eq!(fmt_tick(1.0, 2.0), "1");
        assert_eq!(fmt_tick(0.25, 0.5), "0.25");
        assert_eq!(fmt_tick(300.0, 1000.0), "300");
    }

    #[test]
    fn wrapped_lines_fit_the_column() {
        assert!(font::ensure_registered());
        let text = "a long note that has to be wrapped because it does not fit into one column";
        let lines = wrap(text, TEXT_SIZE, 200);
        assert!(lines.len() >= 3, "{lines:?}");
        assert!(lines.iter().all(|l| text_width(l, TEXT_SIZE) <= 200));
        assert_eq!(lines.join(" "), text);
        // A single over-long word stays whole.
        assert_eq!(wrap("abcdefghijklmnopqrstuvwxyz", TEXT_SIZE, 20).len(), 1);
    }
}

//! Composite pictures: rendered images in a grid with a label above each, a figure title, and a
//! colour bar legend, written as PNG.

use std::path::Path;

use plotters::prelude::*;

use crate::colors::{diverging, sequential};
use crate::error::RenderError;
use crate::font::{self, FONT_FAMILY};
use crate::shade::{to_srgb8, Image};
use meshio::outfile::write_atomic;

/// Height of the title band, of each label band and of the legend band, in pixels.
const TITLE_H: u32 = 40;
const LABEL_H: u32 = 24;
const LEGEND_H: u32 = 70;

/// One picture of a composite with its label.
#[derive(Clone, Debug, PartialEq)]
pub struct Tile {
    /// The picture.
    pub image: Image,
    /// Text above it.
    pub label: String,
}

/// The colour scale of a composite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LegendKind {
    /// [`diverging`] from `−limit` to `limit`.
    Diverging {
        /// Saturation value.
        limit: f64,
    },
    /// [`sequential`] from `lo` to `hi`.
    Sequential {
        /// Low end.
        lo: f64,
        /// High end.
        hi: f64,
    },
}

/// A colour bar under a composite.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    /// Caption of the bar.
    pub title: String,
    /// Its scale.
    pub kind: LegendKind,
}

/// Writes `tiles` in a grid of `columns` columns (all tiles the size of the first) under
/// `title`, with `legend` below if given.
pub fn write_composite(
    tiles: &[Tile],
    columns: usize,
    title: &str,
    legend: Option<&Legend>,
    png: &Path,
) -> Result<(), RenderError> {
    let Some(first) = tiles.first() else {
        return Err(RenderError::EmptyFigure {
            path: png.to_path_buf(),
        });
    };
    if !font::ensure_registered() {
        return Err(RenderError::Font {
            path: png.to_path_buf(),
        });
    }
    let (tw, th) = (first.image.width, first.image.height);
    let columns = columns.clamp(1, tiles.len()) as u32;
    let rows = (tiles.len() as u32).div_ceil(columns);
    let w = tw * columns;
    let h = TITLE_H + rows * (LABEL_H + th) + if legend.is_some() { LEGEND_H } else { 0 };
    let mut rgb = vec![255u8; (w * h * 3) as usize];
    for (k, t) in tiles.iter().enumerate() {
        let (col, row) = (k as u32 % columns, k as u32 / columns);
        let (x0, y0) = (col * tw, TITLE_H + row * (LABEL_H + th) + LABEL_H);
        for y in 0..th.min(t.image.height) {
            let src = (y * t.image.width * 3) as usize;
            let dst = (((y0 + y) * w + x0) * 3) as usize;
            let n = (tw.min(t.image.width) * 3) as usize;
            rgb[dst..dst + n].copy_from_slice(&t.image.rgb[src..src + n]);
        }
    }
    let draw_err = |e: &dyn std::fmt::Display| RenderError::Draw {
        path: png.to_path_buf(),
        message: e.to_string(),
    };
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        let text = |size: f64| (FONT_FAMILY, size).into_font().color(&BLACK);
        root.draw_text(title, &text(22.0), (12, 9))
            .map_err(|e| draw_err(&e))?;
        for (k, t) in tiles.iter().enumerate() {
            let (col, row) = (k as u32 % columns, k as u32 / columns);
            let (x0, y0) = (col * tw, TITLE_H + row * (LABEL_H + th));
            root.draw_text(&t.label, &text(14.0), (x0 as i32 + 6, y0 as i32 + 5))
                .map_err(|e| draw_err(&e))?;
            root.draw(&Rectangle::new(
                [
                    (x0 as i32, y0 as i32 + LABEL_H as i32),
                    ((x0 + tw) as i32 - 1, (y0 + LABEL_H + th) as i32 - 1),
                ],
                RGBColor(210, 210, 210),
            ))
            .map_err(|e| draw_err(&e))?;
        }
        if let Some(l) = legend {
            let y0 = (TITLE_H + rows * (LABEL_H + th)) as i32 + 8;
            let (bx0, bx1) = ((w as f64 * 0.2) as i32, (w as f64 * 0.8) as i32);
            let (lo, hi) = match l.kind {
                LegendKind::Diverging { limit } => (-limit, limit),
                LegendKind::Sequential { lo, hi } => (lo, hi),
            };
            for x in bx0..bx1 {
                let v = lo + (hi - lo) * f64::from(x - bx0) / f64::from(bx1 - bx0 - 1).max(1.0);
                let c = match l.kind {
                    LegendKind::Diverging { limit } => diverging(v, limit),
                    LegendKind::Sequential { lo, hi } => sequential(v, lo, hi),
                };
                let c = RGBColor(to_srgb8(c[0]), to_srgb8(c[1]), to_srgb8(c[2]));
                root.draw(&Rectangle::new([(x, y0), (x + 1, y0 + 18)], c.filled()))
                    .map_err(|e| draw_err(&e))?;
            }
            for (frac, v) in [(0.0, lo), (0.5, 0.5 * (lo + hi)), (1.0, hi)] {
                let x = bx0 + (f64::from(bx1 - bx0) * frac) as i32;
                let label = if v != 0.0 && v.abs() < 0.01 {
                    format!("{v:.2e}")
                } else {
                    format!("{v:.3}")
                };
                root.draw_text(&label, &text(14.0), (x - 18, y0 + 22))
                    .map_err(|e| draw_err(&e))?;
            }
            root.draw_text(&l.title, &text(15.0), (bx1 + 12, y0 + 1))
                .map_err(|e| draw_err(&e))?;
        }
        root.present().map_err(|e| draw_err(&e))?;
    }
    let bytes = crate::curveplot::encode_png(&rgb, w, h).map_err(|e| RenderError::Encode {
        path: png.to_path_buf(),
        message: e.to_string(),
    })?;
    Ok(write_atomic(png, &bytes)?)
}

//! The principal-direction picture of the ring study: short line glyphs on the shaded surface
//! along each sample's principal directions, `d1` of the larger principal curvature `κ1` in
//! red and `d2` of `κ2` in blue (libigl's convention, `κ1 ≥ κ2`, `estimate::principal_frame`
//! from the tessellation's exact shape tensors). On the true torus they run along the meridians
//! (κ1 = 1/r) and the parallels; on a fit they show how far its curvature field turns from the
//! torus's; on the sphere, an umbilic surface, every direction is principal, so the fit's
//! glyphs point wherever its small departures from the sphere send them.
//!
//! Each glyph is a thin quad (two triangles) through the sample, lifted off the surface by a
//! small fraction of its length along the normal so the z-buffer keeps it in front, and drawn
//! by the same rasterizer as the surface: no second drawing pass, and hidden glyphs stay
//! hidden.

use std::path::Path;

use nalgebra::{Point3, Vector3};
use render::colors as colormap;
use render::{write_composite, Camera, RenderMesh, RenderOptions, Tile};
use surface::Tessellation;

use crate::error::ExperimentError;

/// Glyph crosses drawn per surface (every `⌈n / GLYPHS⌉`-th sample).
pub const GLYPHS: usize = 700;
/// A glyph's length, in units of the mean distance between glyphs (`√(area / GLYPHS)`).
const LENGTH: f64 = 0.7;
/// Its width, as a share of its length.
const WIDTH: f64 = 0.12;
/// Its lift off the surface along the normal, as a share of its length.
const LIFT: f64 = 0.06;
/// Colour of the `d1` glyphs (direction of the larger principal curvature).
const D1: [f32; 3] = [0.75, 0.05, 0.05];
/// Colour of the `d2` glyphs.
const D2: [f32; 3] = [0.05, 0.15, 0.8];
/// Size of one picture.
const TILE: (u32, u32) = (520, 400);
/// The view (azimuth°, elevation°).
const VIEW: (f64, f64) = (35.0, 35.0);

/// The shaded surface of `t` with its principal-direction glyphs.
pub fn glyph_mesh(t: &Tessellation) -> RenderMesh {
    let mut m = RenderMesh {
        positions: t.positions.clone(),
        normals: t.normals.clone(),
        colors: vec![colormap::MATERIAL; t.positions.len()],
        faces: t.faces.clone(),
    };
    let area: f64 = t
        .faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|i| t.positions[i]);
            0.5 * (b - a).cross(&(c - a)).norm()
        })
        .sum();
    let len = LENGTH * (area / GLYPHS as f64).sqrt();
    let stride = t.positions.len().div_ceil(GLYPHS).max(1);
    for i in (0..t.positions.len()).step_by(stride) {
        let n = t.normals[i].normalize();
        let p = estimate::principal_frame(&t.shapes[i], &n);
        if !(p.d1.iter().all(|x| x.is_finite()) && n.iter().all(|x| x.is_finite())) {
            continue;
        }
        let centre = t.positions[i] + n * (LIFT * len);
        for (d, across, colour) in [(p.d1, p.d2, D1), (p.d2, p.d1, D2)] {
            quad(
                &mut m,
                centre,
                d * (0.5 * len),
                across * (0.5 * WIDTH * len),
                n,
                colour,
            );
        }
    }
    m
}

/// Appends the quad `c ± a ± b` facing `n` in `colour`.
fn quad(
    m: &mut RenderMesh,
    c: Point3<f64>,
    a: Vector3<f64>,
    b: Vector3<f64>,
    n: Vector3<f64>,
    colour: [f32; 3],
) {
    let base = m.positions.len();
    for p in [c - a - b, c + a - b, c + a + b, c - a + b] {
        m.positions.push(p);
        m.normals.push(n);
        m.colors.push(colour);
    }
    m.faces.push([base, base + 1, base + 2]);
    m.faces.push([base, base + 2, base + 3]);
}

/// Writes `principal-directions.png` into `out`: one picture per `(label, tessellation)`.
pub fn write(out: &Path, surfaces: &[(String, &Tessellation)]) -> Result<String, ExperimentError> {
    let options = RenderOptions {
        width: TILE.0,
        height: TILE.1,
        ..RenderOptions::default()
    };
    let mut tiles = Vec::new();
    for (label, t) in surfaces {
        let cam = Camera::framing_points(
            &t.positions,
            VIEW.0,
            VIEW.1,
            f64::from(TILE.0) / f64::from(TILE.1),
        );
        tiles.push(Tile {
            image: render::render(&glyph_mesh(t), &cam, &options)?,
            label: label.clone(),
        });
    }
    let file = "principal-directions.png".to_string();
    write_composite(
        &tiles,
        tiles.len().clamp(1, 3),
        "Principal directions: red along κ1 (the larger principal curvature), blue along κ2",
        None,
        &out.join(&file),
    )?;
    Ok(file)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The median share of a d1 glyph along the torus's parallel on the 16 × 8 ring's chord
    /// fit (measured 0.033): κ1 = 1/r runs round the tube, so the red glyphs cross the parallels;
    /// a glyph along the wrong direction would give a share near 1.
    const ALONG_PARALLEL: f64 = 0.15;

    /// On a fit of the torus, the red glyphs (d1, κ1 = 1/r the larger) run round the tube,
    /// perpendicular to the parallel direction `(−sin u, cos u, 0)`; every sample past the
    /// stride gets a cross of two quads.
    #[test]
    fn the_torus_glyphs_run_along_meridians() {
        let set = surface::dataset_by_name("ring", Some(16)).unwrap();
        let params = surface::InteriorParameters::default();
        let fit = surface::fit::fit(&set.mesh, &curves::Chord, &|_| params).unwrap();
        let t = surface::tessellate_fit(&set.mesh, &fit, 4).unwrap();
        let m = glyph_mesh(&t);
        let glyphs = (m.faces.len() - t.faces.len()) / 4;
        assert!(
            glyphs > GLYPHS / 2 && glyphs <= GLYPHS + 1,
            "{glyphs} glyph crosses"
        );
        assert_eq!(m.positions.len(), t.positions.len() + 8 * glyphs);
        let mut shares: Vec<f64> = (t.positions.len()..m.positions.len())
            .step_by(4)
            .filter(|&b| m.colors[b] == D1)
            .map(|b| {
                let axis = (m.positions[b + 1] - m.positions[b]).normalize();
                let c = m.positions[b];
                let u = c.y.atan2(c.x);
                axis.dot(&Vector3::new(-u.sin(), u.cos(), 0.0)).abs()
            })
            .collect();
        shares.sort_by(f64::total_cmp);
        let median = shares[shares.len() / 2];
        assert!(median < ALONG_PARALLEL, "median {median}");
    }
}

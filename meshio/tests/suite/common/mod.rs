//! Meshes and checks shared by the format tests.
#![allow(dead_code)]

use meshio::{Polygons, RawMesh};
use nalgebra::{Point3, Vector3};

/// Colours stored as sRGB bytes (OFF) move by at most half a byte step in sRGB, which is at
/// most `2.4 / 1.055` times as much in linear (the slope of the sRGB decoding, largest at 1),
/// plus `f32` rounding.
pub const COLOR_QUANTUM: f32 = 0.5 / 255.0 * (2.4 / 1.055) + 1e-6;

/// Colours stored as sRGB-encoded floats (PLY, OBJ) come back within the `f32` rounding of
/// the encoding and decoding (two `powf`, a few ulps of values at most 1).
pub const COLOR_FLOAT_ROUND_TRIP: f32 = 1e-6;

/// True when two colour lists agree within `tolerance` in every component.
pub fn colors_close(a: Option<&[[f32; 3]]>, b: Option<&[[f32; 3]]>, tolerance: f32) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(x, y)| (0..3).all(|k| (x[k] - y[k]).abs() <= tolerance))
        }
        (None, None) => true,
        _ => false,
    }
}

/// A unit cube of 8 vertices and 6 quads (outward, counter-clockwise), coordinates, normals and
/// properties exact in f32 so that every format round-trips them exactly.
pub fn cube() -> RawMesh {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for i in 0..8 {
        let p = Point3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64);
        normals.push((p.coords - Vector3::repeat(0.5)) * 2.0);
        positions.push(p);
    }
    let quads: [[usize; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut polygons = Polygons::new();
    for q in &quads {
        polygons.push(q);
    }
    let mut mesh = RawMesh {
        positions,
        normals: Some(normals),
        polygons,
        ..RawMesh::default()
    };
    mesh.colors = Some((0..8).map(|i| [i as f32 / 7.0, 0.5, 1.0]).collect());
    mesh.properties
        .insert("quality".into(), (0..8).map(|i| i as f64 * 0.25).collect());
    mesh
}

/// The cube with positions and faces only.
pub fn bare_cube() -> RawMesh {
    let c = cube();
    RawMesh {
        positions: c.positions,
        polygons: c.polygons,
        ..RawMesh::default()
    }
}

/// A triangle grid of `n × n` cells on a wavy surface (2n² triangles).
pub fn grid(n: usize) -> RawMesh {
    let mut positions = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            positions.push(Point3::new(x, y, 0.1 * (6.0 * x).sin() * (5.0 * y).cos()));
        }
    }
    let mut tris = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 1, a + n + 2);
            tris.push([a, b, d]);
            tris.push([a, d, c]);
        }
    }
    RawMesh::from_triangles(positions, &tris)
}

/// The polygons as vectors.
pub fn polys(m: &RawMesh) -> Vec<Vec<usize>> {
    m.polygons.iter().map(<[usize]>::to_vec).collect()
}

/// True when some note contains `text`.
pub fn has_note(m: &RawMesh, text: &str) -> bool {
    m.notes.iter().any(|n| n.contains(text))
}

/// True when some of `notes` contains `text`.
pub fn has_note_vec(notes: &[String], text: &str) -> bool {
    notes.iter().any(|n| n.contains(text))
}

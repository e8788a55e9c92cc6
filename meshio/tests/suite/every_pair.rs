//! Every format to every format: for every readable format A and every writable format B of
//! [`FORMATS`] (and each of their write variants: PLY binary, text and double precision, STL
//! binary and text), a mesh written as A and read back is written as B and read back again
//! (glTF binary through `meshio`'s own reader; `glb.rs` checks the writer against the
//! independent `gltf` crate), and the result is compared with the original mesh: vertex positions within the precision of the
//! formats passed through, the faces (count and corners, through the vertices' positions, so a
//! format that renumbers vertices — STL welds them — is compared by what it means), and the
//! vertex normals where both formats carry them (and none invented where one does not).

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use meshio::{MeshFormat, RawMesh, WriteOptions, FORMATS};
use nalgebra::{Point3, Vector3};

/// A float format stores each coordinate as the nearest `f32`: off by at most half an ulp,
/// 2^-24 relative. A text float format (PLY and STL text) writes the shortest decimal that reads
/// back as that `f32`, which a reader may keep as the `f64` it parses — up to another half ulp
/// away. One `f32` ulp, 2^-23 relative (`f32::EPSILON`), bounds both, and a second float format
/// stores the first one's value exactly (it is an `f32`, or the decimal of one). Measured on the
/// wavy grid over every pair: 0.58 of it at most.
const F32_RELATIVE: f64 = f32::EPSILON as f64;

/// A float store moves each component of a normal by at most [`F32_RELATIVE`] of itself, so the
/// vector by at most that fraction of its length and its direction by at most that many
/// radians; twice that leaves room for the normalizations (readers and writers that make the
/// normals unit, in `f64`) and the rounding of the angle's own computation.
const F32_NORMAL_ANGLE: f64 = 2.0 * F32_RELATIVE;

/// Formats that write `f64` exactly (shortest round-trip decimals; PLY `double` for positions,
/// not normals) change positions not at all, and the directions of normals only by the
/// normalization of a reader that makes them unit (a few `f64` ulps; 1e-14 rad is a hundred).
/// Measured: 0 — the test meshes' normals are unit already, and stay bit for bit.
const F64_NORMAL_ANGLE: f64 = 1e-14;

/// One way of writing a format.
#[derive(Clone, Copy)]
struct Variant {
    format: &'static dyn MeshFormat,
    options: WriteOptions,
}

impl Variant {
    fn name(&self) -> String {
        let o = self.options;
        let mut s = self.format.name().to_string();
        if o.ascii {
            s.push_str(" (text)");
        }
        if o.double_precision {
            s.push_str(" (double)");
        }
        s
    }

    /// Positions stored as `f32`: PLY unless written with double precision, STL, glTF.
    fn is_f32(&self) -> bool {
        match self.format.name() {
            "ply" => !self.options.double_precision,
            "stl" | "glb" => true,
            _ => false,
        }
    }

    /// Normals stored as `f32`: PLY (`float nx`, also when positions are `double`), glTF.
    fn normals_f32(&self) -> bool {
        matches!(self.format.name(), "ply" | "glb")
    }

    /// Polygons become fans of triangles: STL and glTF hold only triangles.
    fn triangulates(&self) -> bool {
        matches!(self.format.name(), "stl" | "glb")
    }

    /// Per-vertex normals are part of the format (STL has facet normals only, which its reader
    /// ignores).
    fn carries_normals(&self) -> bool {
        self.format.name() != "stl"
    }

    fn write(&self, mesh: &RawMesh) -> Vec<u8> {
        self.format
            .write(mesh, &self.options)
            .unwrap_or_else(|e| panic!("{}: {e}", self.name()))
    }

    /// Reads `bytes` back with the format's reader.
    fn read(&self, bytes: &[u8]) -> RawMesh {
        self.format
            .read(bytes)
            .unwrap_or_else(|e| panic!("{}: {e}", self.name()))
    }
}

/// Every write variant of every writable format, in registry order.
fn variants() -> Vec<Variant> {
    let mut out = Vec::new();
    for &format in FORMATS.iter().filter(|f| f.can_write()) {
        let options: &[WriteOptions] = match format.name() {
            "ply" => &[
                WriteOptions::new(),
                WriteOptions::new().ascii(),
                WriteOptions::new().double_precision(),
            ],
            "stl" => &[WriteOptions::new(), WriteOptions::new().ascii()],
            _ => &[WriteOptions::new()],
        };
        out.extend(options.iter().map(|&options| Variant { format, options }));
    }
    out
}

/// A wavy grid of 7 × 7 cells (98 triangles, 64 vertices) with the surface's unit normals:
/// coordinates like 1/7 and sines that no `f32` holds, so the float formats' rounding shows.
fn wavy() -> RawMesh {
    let mut m = common::grid(7);
    let normals = m
        .positions
        .iter()
        .map(|p| {
            // z = 0.1 sin(6x) cos(5y): n ∝ (−z_x, −z_y, 1).
            let zx = 0.6 * (6.0 * p.x).cos() * (5.0 * p.y).cos();
            let zy = -0.5 * (6.0 * p.x).sin() * (5.0 * p.y).sin();
            Vector3::new(-zx, -zy, 1.0).normalize()
        })
        .collect();
    m.normals = Some(normals);
    m
}

/// The unit cube of six quads with its (not unit) corner normals: polygons that STL and glTF
/// turn into fans.
fn cube() -> RawMesh {
    let c = common::cube();
    RawMesh {
        positions: c.positions,
        normals: c.normals,
        polygons: c.polygons,
        ..RawMesh::default()
    }
}

/// The faces `want` expects after the chain: the polygons, or their fans (`[p0, pk, pk+1]`).
fn expected_faces(mesh: &RawMesh, triangulated: bool) -> Vec<Vec<usize>> {
    if !triangulated {
        return common::polys(mesh);
    }
    let mut out = Vec::new();
    for p in mesh.polygons.iter() {
        for k in 1..p.len() - 1 {
            out.push(vec![p[0], p[k], p[k + 1]]);
        }
    }
    out
}

fn angle(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    let (a, b) = (a.normalize(), b.normalize());
    a.cross(&b).norm().atan2(a.dot(&b))
}

/// Compares `got` (after A then B) with `want` (the original).
fn check(want: &RawMesh, got: &RawMesh, a: &Variant, b: &Variant, what: &str) {
    let f32_chain = a.is_f32() || b.is_f32();
    let close = |g: &Point3<f64>, w: &Point3<f64>| {
        if f32_chain {
            (0..3).all(|k| (g[k] - w[k]).abs() <= F32_RELATIVE * w[k].abs())
        } else {
            g == w
        }
    };
    // Every vertex read back is one original vertex, by position (the vertices are far apart
    // next to the tolerance), each original vertex exactly once.
    assert_eq!(got.num_vertices(), want.num_vertices(), "{what}: vertices");
    let mut seen = vec![false; want.num_vertices()];
    let original: Vec<usize> = got
        .positions
        .iter()
        .enumerate()
        .map(|(i, g)| {
            let matches: Vec<usize> = (0..want.num_vertices())
                .filter(|&j| close(g, &want.positions[j]))
                .collect();
            assert_eq!(
                matches.len(),
                1,
                "{what}: vertex {i} at {g:?} matches original vertices {matches:?}"
            );
            assert!(!seen[matches[0]], "{what}: vertex {} twice", matches[0]);
            seen[matches[0]] = true;
            matches[0]
        })
        .collect();
    // Faces: the same count, and each the same corners in the same order.
    let faces = expected_faces(want, a.triangulates() || b.triangulates());
    assert_eq!(got.num_faces(), faces.len(), "{what}: faces");
    for (k, (g, w)) in got.polygons.iter().zip(&faces).enumerate() {
        let mapped: Vec<usize> = g.iter().map(|&i| original[i]).collect();
        assert_eq!(&mapped, w, "{what}: face {k}");
    }
    // Normals where both formats carry them, and none made up where one does not.
    let want_normals = want.normals.as_ref().expect("the test meshes have normals");
    if a.carries_normals() && b.carries_normals() {
        let ns = got
            .normals
            .as_ref()
            .unwrap_or_else(|| panic!("{what}: normals lost"));
        let tol = if a.normals_f32() || b.normals_f32() {
            F32_NORMAL_ANGLE
        } else {
            F64_NORMAL_ANGLE
        };
        assert_eq!(ns.len(), got.num_vertices(), "{what}: normals");
        for (i, n) in ns.iter().enumerate() {
            let d = angle(n, &want_normals[original[i]]);
            assert!(d <= tol, "{what}: normal of vertex {i} turned by {d:e} rad");
        }
    } else {
        assert!(got.normals.is_none(), "{what}: normals from nowhere");
    }
}

#[test]
fn every_readable_format_to_every_writable_format() {
    let all = variants();
    let readable: Vec<Variant> = all
        .iter()
        .copied()
        .filter(|v| v.format.can_read())
        .collect();
    // The registry as this test knows it: a new format is covered by the loops, but its
    // precision, polygons and normals need a word in `Variant`.
    let names: Vec<&str> = FORMATS.iter().map(|f| f.name()).collect();
    assert_eq!(names, ["ply", "glb", "off", "stl", "testbed", "obj"]);
    let mut pairs = 0;
    for (mesh_name, mesh) in [("wavy grid", wavy()), ("cube", cube())] {
        for a in &readable {
            let as_a = a.read(&a.write(&mesh));
            for b in &all {
                let what = format!("{mesh_name}: {} → {}", a.name(), b.name());
                let got = b.read(&b.write(&as_a));
                check(&mesh, &got, a, b, &what);
                pairs += 1;
            }
        }
    }
    // 9 readable and writable variants (PLY ×3, glTF, STL ×2, OFF, testbed, OBJ), each to
    // each, for each of the two meshes.
    assert_eq!(pairs, 2 * 9 * 9);
}

/// The float formats do round: the wavy grid through binary PLY is not the original, so the
/// tolerance above is used, not idle.
#[test]
fn float_formats_round_and_text_formats_do_not() {
    let mesh = wavy();
    let v = variants();
    let by = |name: &str, double: bool| {
        *v.iter()
            .find(|x| x.format.name() == name && x.options.double_precision == double)
            .unwrap()
    };
    let ply = by("ply", false);
    let back = ply.read(&ply.write(&mesh));
    let moved = back
        .positions
        .iter()
        .zip(&mesh.positions)
        .filter(|(g, w)| g != w)
        .count();
    assert!(moved > mesh.num_vertices() / 2, "{moved} vertices rounded");
    for exact in [
        by("obj", false),
        by("off", false),
        by("testbed", false),
        by("ply", true),
    ] {
        let back = exact.read(&exact.write(&mesh));
        assert_eq!(back.positions, mesh.positions, "{}", exact.name());
    }
}

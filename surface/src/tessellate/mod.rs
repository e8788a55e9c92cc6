//! Tessellation of triangular Bézier patches with differential geometry: the testbed's `Tess`
//! (Lounsbery et al. 1990, §3.2: `Tess -s 8` samples each patch with 8 segments per edge, and
//! `-kg` adds Gaussian curvature at the vertices).
//!
//! Each patch is sampled at the barycentric grid `(i, j, k)/s`, `i + j + k = s`:
//! `(s + 1)(s + 2)/2` samples and `s²` triangles per patch, oriented like the patch (the
//! triangle `(u-ward, v-ward, w-ward)` corners, so a triangle's geometric normal agrees with the
//! patch normal `r_u × r_v`). Every sample carries position, unit normal, Gaussian and mean
//! curvature and the shape tensor (see [`crate::beztri`] for the formulas and signs).
//!
//! **Welding.** Samples on patch boundaries are merged by position (the library's one weld,
//! [`crate::weld`]): two boundary samples closer than [`WELD_RELATIVE`] times the diagonal of
//! the patches' control-net bounding box are one vertex. Interior samples of a patch are never
//! welded. Patches that share a boundary curve (same end points, same control points, in
//! either direction) produce bit-identical or nearly identical samples along it, so the
//! welded mesh has no duplicated seams; patches that merely come close are not merged unless
//! within the tolerance. [`Tessellation::welds`] counts merged samples. A welded vertex keeps
//! the normal and curvature of the first patch that produced it;
//! [`Tessellation::max_weld_normal_angle`] reports the largest angle between the normals
//! merged (a G1 defect measure along seams, in radians).
//!
//! Welding can make two corners of a sample triangle one vertex when a patch edge collapses to
//! a point; such triangles are dropped and counted ([`Tessellation::collapsed_faces`]).
//!
//! **Singular points** (a collapsed patch edge, `r_u × r_v = 0`): the differential geometry is
//! taken a small step ([`SINGULAR_NUDGE`]) towards the patch centre, and counted in
//! [`Tessellation::singular_samples`] — never NaN. A patch singular even there (a net collapsed
//! to a curve or a point, as a zero-area face's fallback can be) gets the normal of its corner
//! triangle (or `+z` if that has no area either) and zero curvature, counted the same way:
//! one bad patch never stops a tessellation.

pub mod tessellate_fit;
pub mod weld;

use std::collections::HashMap;

use curves::VertexData;
use meshio::MeshFormat;
use nalgebra::{Matrix3, Point3, Vector3};

use crate::beztri::{BezierTriangle, Curvature, SampleWeights};
use crate::mesh::{bounding_size, Mesh, MeshError, Vertex};
use crate::weld::PositionWeld;

/// Boundary samples closer than this fraction of the model size are welded: far above the
/// rounding of de Casteljau evaluation (1e-15 relative), far below any sampling step (1/s ≥
/// 1e-4 for practical `s`).
pub const WELD_RELATIVE: f64 = 1e-9;

/// Barycentric step towards the patch centre used to evaluate differential geometry at a
/// singular sample.
pub const SINGULAR_NUDGE: f64 = 1e-6;

/// Why tessellation failed.
#[derive(Debug, thiserror::Error)]
pub enum TessError {
    /// The sampling density must be at least 1.
    #[error("sampling density must be at least 1 segment per edge")]
    ZeroDensity,
    /// Converting to a [`Mesh`] failed (degenerate or non-manifold output).
    #[error("tessellation is not a valid mesh: {0}")]
    Mesh(#[from] MeshError),
    /// A tessellation that builds the nets again ([`crate::tessellate_fit::tessellate_fit_rebuilt`])
    /// could not: the layout is not welded by topology, or a face could not be built.
    #[error("tessellating without the nets: {0}")]
    Rebuild(String),
}

/// One welded triangle mesh with per-vertex differential geometry.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tessellation {
    /// Vertex positions.
    pub positions: Vec<Point3<f64>>,
    /// Unit normals.
    pub normals: Vec<Vector3<f64>>,
    /// Gaussian curvature `K`.
    pub gaussian: Vec<f64>,
    /// Mean curvature `H`.
    pub mean: Vec<f64>,
    /// Shape tensors (empty when not asked for: [`crate::tessellate_fit::Keep`]).
    pub shapes: Vec<Matrix3<f64>>,
    /// Unit principal directions `[d1, d2]` (of `κ1 ≥ κ2`) per vertex, in world coordinates,
    /// where asked for instead of the shape tensors ([`crate::tessellate_fit::Keep`]); empty
    /// otherwise.
    pub directions: Vec<[Vector3<f64>; 2]>,
    /// Triangles, oriented like their patches.
    pub faces: Vec<[usize; 3]>,
    /// Patch of each triangle (empty when not asked for: [`crate::tessellate_fit::Keep`]).
    pub patch_of_face: Vec<usize>,
    /// Number of boundary samples merged into an existing vertex.
    pub welds: usize,
    /// Largest angle (radians) between the normals of merged samples.
    pub max_weld_normal_angle: f64,
    /// Samples whose geometry was taken at a nudged point.
    pub singular_samples: usize,
    /// Triangles dropped because welding made two of their corners one vertex (a patch edge
    /// collapsed to a point, as at the pole of a degenerate patch).
    pub collapsed_faces: usize,
}

impl Tessellation {
    /// The tessellation as a [`Mesh`] (curvature known at every vertex), for adjacency queries
    /// and writers.
    pub fn to_mesh(&self) -> Result<Mesh, MeshError> {
        let vertices = (0..self.positions.len())
            .map(|i| {
                Vertex::new(VertexData::new(
                    self.positions[i],
                    self.normals[i],
                    self.shapes[i],
                ))
            })
            .collect();
        Mesh::new(vertices, self.faces.clone())
    }

    /// The tessellation mapped back from a working frame to world coordinates in place
    /// (positions, `K / scale²`, `H / scale`, shape tensors `/ scale`).
    pub fn to_world(&mut self, frame: &mesh::Frame) {
        frame.points_to_world(&mut self.positions);
        let s = frame.scale;
        for k in &mut self.gaussian {
            *k /= s * s;
        }
        for h in &mut self.mean {
            *h /= s;
        }
        for m in &mut self.shapes {
            *m /= s;
        }
    }

    /// The tessellation as a raw mesh for `meshio`'s writers: positions, normals, triangles, and
    /// the Gaussian and mean curvature as vertex properties `gaussian`, `mean`.
    pub fn to_raw(&self) -> meshio::RawMesh {
        let mut raw = meshio::RawMesh::from_triangles(self.positions.clone(), &self.faces);
        raw.normals = Some(self.normals.clone());
        raw.properties
            .insert("gaussian".into(), self.gaussian.clone());
        raw.properties.insert("mean".into(), self.mean.clone());
        raw
    }

    /// Writes positions, normals and triangles as OBJ (curvatures are not part of OBJ; PLY
    /// carries them: [`Tessellation::to_raw`]).
    pub fn write_obj<W: std::io::Write>(&self, mut out: W) -> std::io::Result<()> {
        let bytes = meshio::obj::Obj
            .write(&self.to_raw(), &meshio::WriteOptions::new())
            .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()))?;
        out.write_all(&bytes)
    }
}

fn geometry(
    patch: &BezierTriangle,
    weights: Option<&SampleWeights>,
    (u, v, _w): (f64, f64, f64),
) -> (Curvature, bool) {
    let fast = weights
        .and_then(|wt| patch.derivatives_with(wt))
        .and_then(|d| crate::beztri::curvature_of(&d));
    if let Some(c) = fast.or_else(|| patch.curvature(u, v)) {
        return (c, false);
    }
    (nudged_geometry(patch, u, v), true)
}

/// The geometry of a singular sample: a small step towards the centre, or where the patch is
/// singular there too, the normal of its corner triangle (`+z` if that has no area) with zero
/// curvature (module docs).
pub(crate) fn nudged_geometry(patch: &BezierTriangle, u: f64, v: f64) -> Curvature {
    let third = 1.0 / 3.0;
    let t = SINGULAR_NUDGE;
    let (nu, nv) = (u + t * (third - u), v + t * (third - v));
    patch.curvature(nu, nv).unwrap_or_else(|| {
        let n = patch.degree();
        let corner = |i, j, k| patch.point(i, j, k).unwrap_or_else(Point3::origin);
        let (a, b, c) = (corner(n, 0, 0), corner(0, n, 0), corner(0, 0, n));
        flat_curvature((b - a).cross(&(c - a)))
    })
}

/// Zero curvature with the normal along `n` (`+z` where it has no direction): the geometry of
/// a sample that is singular even a step inside.
pub(crate) fn flat_curvature(n: Vector3<f64>) -> Curvature {
    Curvature {
        normal: n.try_normalize(0.0).unwrap_or_else(Vector3::z),
        gaussian: 0.0,
        mean: 0.0,
        principal: [0.0, 0.0],
        shape: Matrix3::zeros(),
    }
}

/// Tessellates `patches` at `s` segments per patch edge into one welded mesh (module docs).
pub fn tessellate(patches: &[BezierTriangle], s: usize) -> Result<Tessellation, TessError> {
    if s == 0 {
        return Err(TessError::ZeroDensity);
    }
    let size = bounding_size(patches.iter().flat_map(|p| p.points().iter()));
    let tol = WELD_RELATIVE * size.max(f64::MIN_POSITIVE);
    let mut welder = PositionWeld::new(tol);
    let mut out = Tessellation::default();
    let local = |i: usize, j: usize| -> usize {
        // Position of sample (i, j, s − i − j) in the per-patch table, rows by j.
        j * (s + 1) - j * j.saturating_sub(1) / 2 + i
    };
    // Bernstein weights of every sample, per degree present, computed once and shared by all
    // patches (the patches of one scheme share a degree).
    let mut tables: HashMap<usize, Vec<SampleWeights>> = HashMap::new();
    for patch in patches {
        tables
            .entry(patch.degree())
            .or_insert_with(|| SampleWeights::grid(patch.degree(), s));
    }
    let mut ids = vec![0usize; (s + 1) * (s + 2) / 2];
    for (pi, patch) in patches.iter().enumerate() {
        let table = tables.get(&patch.degree());
        for j in 0..=s {
            for i in 0..=s - j {
                let k = s - i - j;
                let (u, v, w) = (
                    i as f64 / s as f64,
                    j as f64 / s as f64,
                    k as f64 / s as f64,
                );
                let weights = table.and_then(|t| t.get(local(i, j)));
                let p = weights
                    .and_then(|wt| patch.derivatives_with(wt))
                    .map_or_else(|| patch.eval(u, v, w), |d| d.p);
                let (c, nudged) = geometry(patch, weights, (u, v, w));
                out.singular_samples += usize::from(nudged);
                let on_boundary = i == 0 || j == 0 || k == 0;
                let existing = if on_boundary {
                    welder.find(&p, &out.positions)
                } else {
                    None
                };
                let id = match existing {
                    Some(id) => {
                        out.welds += 1;
                        let angle = out.normals[id].angle(&c.normal);
                        out.max_weld_normal_angle = out.max_weld_normal_angle.max(angle);
                        id
                    }
                    None => {
                        let id = out.positions.len();
                        out.positions.push(p);
                        out.normals.push(c.normal);
                        out.gaussian.push(c.gaussian);
                        out.mean.push(c.mean);
                        out.shapes.push(c.shape);
                        if on_boundary {
                            welder.insert(&p, id);
                        }
                        id
                    }
                };
                ids[local(i, j)] = id;
            }
        }
        for j in 0..s {
            for i in 0..s - j {
                // Upward triangle: corners towards u, v, w; then the downward one.
                let mut tris = vec![[ids[local(i + 1, j)], ids[local(i, j + 1)], ids[local(i, j)]]];
                if i + j + 2 <= s {
                    tris.push([
                        ids[local(i + 1, j)],
                        ids[local(i + 1, j + 1)],
                        ids[local(i, j + 1)],
                    ]);
                }
                for [a, b, c] in tris {
                    if a == b || b == c || c == a {
                        out.collapsed_faces += 1;
                    } else {
                        out.faces.push([a, b, c]);
                        out.patch_of_face.push(pi);
                    }
                }
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::datasets::octa;

    /// Curvature of a patch tessellated at its exact samples: rounding only.
    const EXACT: f64 = 1e-12;

    fn flat(a: [f64; 3], b: [f64; 3], c: [f64; 3], n: usize) -> BezierTriangle {
        let (a, b, c) = (Vector3::from(a), Vector3::from(b), Vector3::from(c));
        BezierTriangle::from_fn(n, |i, j, k| {
            Point3::from((a * i as f64 + b * j as f64 + c * k as f64) / n as f64)
        })
    }

    #[test]
    fn one_patch_counts() {
        let p = flat([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 2);
        for s in 1..6 {
            let t = tessellate(std::slice::from_ref(&p), s).unwrap();
            assert_eq!(t.positions.len(), (s + 1) * (s + 2) / 2);
            assert_eq!(t.faces.len(), s * s);
            assert_eq!(t.welds, 0);
            // Orientation: corners (u, v, w) = (a, b, c) counter-clockwise about +z... the
            // patch normal r_u × r_v = (a − c) × (b − c) = +z here, and every face agrees.
            for f in &t.faces {
                let [x, y, z] = f.map(|i| t.positions[i]);
                assert!((y - x).cross(&(z - x)).z > 0.0);
            }
            assert!(t.normals.iter().all(|n| (n - Vector3::z()).norm() < EXACT));
            assert!(t.gaussian.iter().chain(&t.mean).all(|k| k.abs() < EXACT));
        }
        assert!(matches!(tessellate(&[p], 0), Err(TessError::ZeroDensity)));
    }

    #[test]
    fn collapsed_edge_is_nudged_and_dropped() {
        // Edge 0 (u to v) collapsed to the apex: a cone-like quadratic.
        let apex = Point3::new(0.0, 0.0, 1.0);
        let p = BezierTriangle::from_fn(2, |i, j, k| match (i, j, k) {
            (_, _, 0) => apex,
            (1, 0, 1) => Point3::new(1.0, -0.5, 0.5),
            (0, 1, 1) => Point3::new(1.0, 0.5, 0.5),
            _ => Point3::new(1.0, 0.0, 0.0),
        });
        let s = 4;
        let t = tessellate(&[p], s).unwrap();
        // The s + 1 samples of edge 0 are one vertex: s of them welded, the s triangles along
        // that edge dropped.
        assert_eq!(t.welds, s);
        assert_eq!(t.collapsed_faces, s);
        assert_eq!(t.faces.len(), s * s - s);
        assert_eq!(t.singular_samples, s + 1);
        assert!(t.normals.iter().all(|n| (n.norm() - 1.0).abs() < EXACT));
        assert!(t.gaussian.iter().chain(&t.mean).all(|k| k.is_finite()));
    }

    #[test]
    fn shared_edge_is_welded_once() {
        // Two patches on the square sharing the diagonal b–c, traversed in opposite directions.
        let (a, b, c, d) = (
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        );
        let patches = [flat(a, b, c, 3), flat(d, c, b, 3)];
        for s in [1, 2, 5, 8] {
            let t = tessellate(&patches, s).unwrap();
            let per = (s + 1) * (s + 2) / 2;
            assert_eq!(t.welds, s + 1);
            assert_eq!(t.positions.len(), 2 * per - (s + 1));
            assert_eq!(t.faces.len(), 2 * s * s);
            let m = t.to_mesh().unwrap();
            assert_eq!(m.boundary_edges().len(), 4 * s);
            assert_eq!(m.euler_characteristic(), 1);
        }
    }

    #[test]
    fn sphere_like_patch_set_is_watertight() {
        // Quadratic patches on the octahedron's faces, edge control points pushed out: shared
        // boundary curves are computed from the same two corners in either direction.
        let data = octa().unwrap();
        let m = &data.mesh;
        let mid = |a: usize, b: usize| {
            let (p, q) = (
                m.vertex(a).unwrap().data.p.coords,
                m.vertex(b).unwrap().data.p.coords,
            );
            Point3::from((p + q).normalize() * 1.2)
        };
        let patches: Vec<BezierTriangle> = m
            .faces()
            .iter()
            .map(|&[a, b, c]| {
                BezierTriangle::from_fn(2, |i, j, k| match (i, j, k) {
                    (2, 0, 0) => m.vertex(a).unwrap().data.p,
                    (0, 2, 0) => m.vertex(b).unwrap().data.p,
                    (0, 0, 2) => m.vertex(c).unwrap().data.p,
                    (1, 1, 0) => mid(a, b),
                    (0, 1, 1) => mid(b, c),
                    _ => mid(c, a),
                })
            })
            .collect();
        let s = 6;
        let t = tessellate(&patches, s).unwrap();
        let mesh = t.to_mesh().unwrap();
        assert!(mesh.is_closed());
        assert_eq!(mesh.euler_characteristic(), 2);
        // 12 shared edges with s − 1 interior samples each, welded once; 6 corners shared by 4
        // patches, welded 3 times each.
        assert_eq!(t.welds, 12 * (s - 1) + 6 * 3);
        assert_eq!(t.faces.len(), 8 * s * s);
        // Outward: every face normal points away from the origin.
        for f in mesh.faces() {
            let [x, y, z] = f.map(|i| t.positions[i]);
            let n = (y - x).cross(&(z - x));
            assert!(n.dot(&(x.coords + y.coords + z.coords)) > 0.0);
        }
        // The octahedron-based surface is convex: both curvatures negative wherever regular.
        assert!(t.mean.iter().all(|&h| h < 0.0));
        assert_eq!(t.singular_samples, 0);
        // The OBJ output reads back as the same mesh.
        let mut buf = Vec::new();
        t.write_obj(&mut buf).unwrap();
        let back = meshio::obj::Obj.read(&buf).unwrap();
        let faces: Vec<[usize; 3]> = back.polygons.iter().map(|f| [f[0], f[1], f[2]]).collect();
        assert_eq!(faces, t.faces);
        assert_eq!(back.num_vertices(), t.positions.len());
    }
}

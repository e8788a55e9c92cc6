//! [`RawMesh`]: a polygon mesh exactly as a file gave it, before any validation or repair.
//!
//! Readers fill it and writers read it; turning it into a validated triangle mesh (and repairing
//! what a file got wrong) is the `surface` crate's job, so every reader stays a pure parser.

use std::borrow::Cow;
use std::collections::BTreeMap;

use nalgebra::{Matrix3, Point3, Vector3};

use crate::convention::{ColorMap, Curvature};

/// Named per-vertex scalar properties a reader found and did not interpret (PLY `quality`,
/// `red`, `u`, …), each with one value per vertex, in file order; writers put them back where
/// their format can carry them.
pub type VertexProperties = BTreeMap<String, Vec<f64>>;

/// Faces as polygons of any size, stored flat: polygon `f` has the corners
/// `indices[offsets[f]..offsets[f + 1]]` (vertex indices, 0-based), counter-clockwise seen from
/// the side its normal points to. `offsets` starts with 0 and has one more entry than there are
/// polygons. Flat storage keeps a million faces in two allocations.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Polygons {
    indices: Vec<usize>,
    offsets: Vec<usize>,
}

impl Default for Polygons {
    fn default() -> Self {
        Polygons {
            indices: Vec::new(),
            offsets: vec![0],
        }
    }
}

impl Polygons {
    /// No polygons.
    pub fn new() -> Self {
        Self::default()
    }

    /// Room for `faces` polygons with `corners` corners in all.
    pub fn with_capacity(faces: usize, corners: usize) -> Self {
        let mut offsets = Vec::with_capacity(faces + 1);
        offsets.push(0);
        Polygons {
            indices: Vec::with_capacity(corners),
            offsets,
        }
    }

    /// Triangles as polygons.
    pub fn from_triangles(tris: &[[usize; 3]]) -> Self {
        let mut p = Self::with_capacity(tris.len(), 3 * tris.len());
        for t in tris {
            p.push(t);
        }
        p
    }

    /// Triangles as polygons, taking their storage: the corner list is the triangles' own
    /// buffer reinterpreted (`Vec::into_flattened`, no copy), so a large mesh is not held twice
    /// while it becomes polygons; only the offsets are new.
    pub fn from_triangle_vec(tris: Vec<[usize; 3]>) -> Self {
        let offsets = (0..=tris.len()).map(|k| 3 * k).collect();
        Polygons {
            indices: tris.into_flattened(),
            offsets,
        }
    }

    /// Appends one polygon.
    pub fn push(&mut self, corners: &[usize]) {
        self.indices.extend_from_slice(corners);
        self.offsets.push(self.indices.len());
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// True when there are no polygons.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The corners of polygon `f` (empty when `f` is out of range).
    pub fn get(&self, f: usize) -> &[usize] {
        match (self.offsets.get(f), self.offsets.get(f + 1)) {
            (Some(&a), Some(&b)) => &self.indices[a..b],
            _ => &[],
        }
    }

    /// The polygons in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[usize]> + '_ {
        self.offsets.windows(2).map(|w| &self.indices[w[0]..w[1]])
    }

    /// True when every polygon is a triangle.
    pub fn all_triangles(&self) -> bool {
        self.offsets.windows(2).all(|w| w[1] - w[0] == 3)
    }

    /// Total number of corners.
    pub fn corner_count(&self) -> usize {
        self.indices.len()
    }

    /// Every polygon's corners, one polygon after the other (what [`Polygons::iter`] gives,
    /// joined).
    pub(crate) fn all_corners(&self) -> &[usize] {
        &self.indices
    }
}

/// A mesh as read from a file: positions, whatever per-vertex data the file had, polygons, and
/// notes about what the reader did (a fan triangulation, a welded STL, ignored statements).
///
/// Invariants a reader guarantees: every optional per-vertex array has one entry per position;
/// every face index and every index of [`RawMesh::crease_edges`] is `< positions.len()` (a
/// reader reports an out-of-range index as an error naming the line or element, it never
/// stores it), and the crease pairs are sorted as that field says; every number is finite unless a note says
/// otherwise (readers refuse NaN and infinities with an error). Nothing else is guaranteed:
/// faces may be degenerate, repeated, non-manifold or inconsistently oriented, and vertices may
/// be unused. `surface` validates and repairs.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawMesh {
    /// Vertex positions.
    pub positions: Vec<Point3<f64>>,
    /// Per-vertex normals as the file gave them (not necessarily unit), if it gave them for
    /// every vertex.
    pub normals: Option<Vec<Vector3<f64>>>,
    /// Per-vertex shape tensors `S` (`κn(d) = dᵀ S d`, positive where the surface bends towards
    /// the normal), if the file gave them (the testbed format's `shape` field).
    pub shapes: Option<Vec<Matrix3<f64>>>,
    /// Per-vertex colours, linear 0–1 RGB, if the file had them (PLY, OBJ and OFF store them
    /// sRGB-encoded: readers decode, writers encode; [`crate::srgb`]).
    pub colors: Option<Vec<[f32; 3]>>,
    /// What the colours show (a colour map of a quantity over a range), written where a format
    /// has a place for it ([`crate::convention::ColorMap`]).
    pub color_map: Option<ColorMap>,
    /// Per-vertex Gaussian and mean curvature in the exported convention (libigl's, trimesh's
    /// and MeshLab's: `H > 0` on a sphere with outward normals; [`crate::convention`]), if the
    /// mesh has them. Written by the formats that store curvature
    /// ([`crate::MeshFormat::writes_curvature`]: PLY `quality`, `gaussian_curvature`,
    /// `mean_curvature`, `k1`, `k2`; glTF `_GAUSSIAN_CURVATURE`, `_MEAN_CURVATURE`) and read
    /// back by their readers.
    pub curvature: Option<Curvature>,
    /// Per-vertex names (the testbed format names its points), if the file had them and they
    /// are not all implied ([`RawMesh::implied_vertex_names`]); read them through
    /// [`RawMesh::vertex_name`].
    pub vertex_names: Option<Vec<String>>,
    /// The file named every vertex `v<i>` by its position `i` (what the testbed writer emits
    /// for a mesh without names): the names are implied, not stored (`vertex_names` is `None`),
    /// and [`RawMesh::vertex_name`] gives them. A million points then cost no million strings;
    /// writing the mesh back gives the same names.
    pub implied_vertex_names: bool,
    /// Other per-vertex properties, kept.
    pub properties: VertexProperties,
    /// The faces.
    pub polygons: Polygons,
    /// The edges the file marks as sharp (creases), as unordered pairs of vertex indices: each
    /// pair `[a, b]` with `a < b`, the list sorted and without repeats; empty when the file
    /// says nothing about sharp edges. The OBJ reader finds them from per-corner normals and
    /// smoothing groups, and they are sides of its polygons ([`crate::obj`]); the PLY reader
    /// takes them from an `edge` element as listed ([`crate::ply`]), so they need not be sides
    /// of a polygon there. Writers ignore them except PLY's, which writes them back as such an
    /// element.
    pub crease_edges: Vec<[usize; 2]>,
    /// Per-face names (the testbed format names its faces), if the file had them and they are
    /// not all implied ([`RawMesh::implied_face_names`]); read them through
    /// [`RawMesh::face_name`].
    pub face_names: Option<Vec<String>>,
    /// The file named every face `f<k>` by its position `k` in the mesh (as the testbed writer
    /// does): implied, not stored (`face_names` is `None`); [`RawMesh::face_name`] gives them.
    pub implied_face_names: bool,
    /// Per-mesh numeric fields a reader kept (the testbed format's extra top-level fields).
    pub mesh_fields: BTreeMap<String, Vec<f64>>,
    /// What the reader did that a user should know (one line each).
    pub notes: Vec<String>,
}

impl RawMesh {
    /// A mesh of positions and triangles only.
    pub fn from_triangles(positions: Vec<Point3<f64>>, tris: &[[usize; 3]]) -> Self {
        RawMesh {
            positions,
            polygons: Polygons::from_triangles(tris),
            ..RawMesh::default()
        }
    }

    /// [`RawMesh::from_triangles`] taking the triangles' storage ([`Polygons::from_triangle_vec`]).
    pub fn from_triangle_vec(positions: Vec<Point3<f64>>, tris: Vec<[usize; 3]>) -> Self {
        RawMesh {
            positions,
            polygons: Polygons::from_triangle_vec(tris),
            ..RawMesh::default()
        }
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of polygons.
    pub fn num_faces(&self) -> usize {
        self.polygons.len()
    }

    /// The name of vertex `i`: stored, implied (`v<i>`), or none.
    pub fn vertex_name(&self, i: usize) -> Option<Cow<'_, str>> {
        match &self.vertex_names {
            Some(names) => names.get(i).map(|n| Cow::Borrowed(n.as_str())),
            None if self.implied_vertex_names && i < self.positions.len() => {
                Some(Cow::Owned(format!("v{i}")))
            }
            None => None,
        }
    }

    /// The name of face `k`: stored, implied (`f<k>`), or none.
    pub fn face_name(&self, k: usize) -> Option<Cow<'_, str>> {
        match &self.face_names {
            Some(names) => names.get(k).map(|n| Cow::Borrowed(n.as_str())),
            None if self.implied_face_names && k < self.polygons.len() => {
                Some(Cow::Owned(format!("f{k}")))
            }
            None => None,
        }
    }

    /// Whether the vertices have names, stored or implied.
    pub fn has_vertex_names(&self) -> bool {
        self.vertex_names.is_some() || self.implied_vertex_names
    }

    /// Whether the faces have names, stored or implied.
    pub fn has_face_names(&self) -> bool {
        self.face_names.is_some() || self.implied_face_names
    }
}

//! [`PolyMesh`]: a validated manifold polygon mesh (open or closed) with its adjacency, and
//! the crease tags subdivision carries from level to level.
//!
//! # Storage
//!
//! Faces are stored flat, as in [`meshio::Polygons`]: face `f` has the corners
//! `indices[offsets[f]..offsets[f + 1]]`, counter-clockwise seen from the side its normal points
//! to. Corner `h` is also the **half-edge** from `indices[h]` to the next corner of its face, so
//! the adjacency is a handful of flat `u32` arrays indexed by corner (twin, edge, face) and by
//! edge (endpoints, first half-edge, flags), built once per mesh without per-element
//! allocation. Indices are 32-bit: a mesh of more than `u32::MAX − 1` vertices or corners is
//! refused ([`SubdivError::IndexOverflow`]).
//!
//! # What is refused
//!
//! Construction checks, in this order, and names the first offender: non-finite positions,
//! faces of fewer than three corners, indices out of range, a vertex repeated in a face, an
//! edge shared by more than two faces, an edge traversed twice in the same direction
//! (inconsistent orientation or a duplicate face), a vertex whose faces form more than one fan
//! (bowtie), a crease that is not an edge. Boundaries (open meshes), several components and
//! isolated vertices (used by no face) are accepted.
//!
//! # Vertex classes
//!
//! An edge is **sharp** if it is a boundary edge (one face) or tagged as a crease. A vertex is
//! classified by its number of sharp edges `s` ([`VertexKind`]): no face → isolated; `s = 0` →
//! smooth; `s = 1` → dart (smooth rule); `s = 2` → crease (a boundary vertex is a crease
//! vertex, including a valence-2 boundary corner such as the corner of a quad grid); `s > 2` →
//! corner, which stays fixed.

use meshio::{Polygons, RawMesh};
use nalgebra::{Point3, Vector3};

use crate::error::SubdivError;

/// "No half-edge": the twin of a boundary half-edge, the start of an isolated vertex's fan.
pub(crate) const NONE: u32 = u32::MAX;

/// How a vertex is treated by the subdivision rules (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VertexKind {
    /// Used by no face: copied unchanged.
    Isolated,
    /// Interior, no sharp edge: the smooth rule.
    Smooth,
    /// Interior with exactly one crease edge: the smooth rule (Hoppe et al. 1994).
    Dart,
    /// Exactly two sharp edges (a boundary vertex, or a vertex on a crease line): the curve
    /// rule `(1/8, 3/4, 1/8)` along the two sharp edges.
    Crease,
    /// More than two sharp edges: fixed.
    Corner,
}

/// Adjacency of a [`PolyMesh`], all flat arrays (see the module documentation).
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Topology {
    /// Face of each half-edge.
    pub(crate) face_of: Vec<u32>,
    /// Opposite half-edge, or [`NONE`] on the boundary.
    pub(crate) twin: Vec<u32>,
    /// Edge of each half-edge.
    pub(crate) edge: Vec<u32>,
    /// A half-edge of each edge: the one with the smaller index (the only one on the boundary).
    pub(crate) edge_half: Vec<u32>,
    /// Per edge: boundary or crease.
    pub(crate) sharp: Vec<bool>,
    /// Per edge: tagged as a crease (boundary edges are not tagged).
    pub(crate) crease: Vec<bool>,
    /// Per vertex: the outgoing half-edge its counter-clockwise fan walk starts from (on the
    /// boundary, the outgoing boundary half-edge), or [`NONE`] for an isolated vertex.
    pub(crate) vertex_out: Vec<u32>,
    /// Per vertex: its class.
    pub(crate) kind: Vec<VertexKind>,
}

/// A validated manifold polygon mesh with boundaries allowed, its adjacency, and crease tags.
#[derive(Clone, Debug, PartialEq)]
pub struct PolyMesh {
    positions: Vec<Point3<f64>>,
    indices: Vec<u32>,
    offsets: Vec<u32>,
    pub(crate) topo: Topology,
}

fn to_u32(count: usize, what: &'static str) -> Result<u32, SubdivError> {
    u32::try_from(count)
        .ok()
        .filter(|&c| c != NONE)
        .ok_or(SubdivError::IndexOverflow { what, count })
}

impl PolyMesh {
    /// A mesh from positions and polygons (any number of corners each), without creases.
    pub fn new(positions: Vec<Point3<f64>>, polygons: &Polygons) -> Result<Self, SubdivError> {
        Self::with_creases(positions, polygons, &[])
    }

    /// A mesh from positions, polygons and crease edges (unordered vertex pairs; each must be
    /// an edge of the mesh; repeats are harmless). Creases on boundary edges change nothing.
    pub fn with_creases(
        positions: Vec<Point3<f64>>,
        polygons: &Polygons,
        creases: &[[usize; 2]],
    ) -> Result<Self, SubdivError> {
        let nv = positions.len();
        to_u32(nv, "vertices")?;
        to_u32(polygons.corner_count(), "corners")?;
        if let Some(vertex) = positions
            .iter()
            .position(|p| !p.coords.iter().all(|c| c.is_finite()))
        {
            return Err(SubdivError::NonFinitePosition { vertex });
        }
        let mut indices = Vec::with_capacity(polygons.corner_count());
        let mut offsets = Vec::with_capacity(polygons.len() + 1);
        offsets.push(0u32);
        for (face, corners) in polygons.iter().enumerate() {
            if corners.len() < 3 {
                return Err(SubdivError::FaceTooSmall {
                    face,
                    corners: corners.len(),
                });
            }
            for (i, &index) in corners.iter().enumerate() {
                if index >= nv {
                    return Err(SubdivError::IndexOutOfRange {
                        face,
                        index,
                        vertices: nv,
                    });
                }
                if corners[..i].contains(&index) {
                    return Err(SubdivError::RepeatedVertex {
                        face,
                        vertex: index,
                    });
                }
                indices.push(index as u32);
            }
            offsets.push(indices.len() as u32);
        }
        let mut tagged = Vec::with_capacity(creases.len());
        for &[a, b] in creases {
            if a >= nv || b >= nv || a == b {
                return Err(SubdivError::CreaseNotAnEdge { a, b });
            }
            tagged.push([a as u32, b as u32]);
        }
        Self::from_parts(positions, indices, offsets, &tagged)
    }

    /// A triangle mesh.
    pub fn from_triangles(
        positions: Vec<Point3<f64>>,
        triangles: &[[usize; 3]],
    ) -> Result<Self, SubdivError> {
        Self::new(positions, &Polygons::from_triangles(triangles))
    }

    /// The positions and polygons of a file's raw mesh (other per-vertex data is not carried).
    pub fn from_raw(raw: &RawMesh) -> Result<Self, SubdivError> {
        Self::new(raw.positions.clone(), &raw.polygons)
    }

    /// Positions and polygons as a raw mesh, for the writers of `meshio`.
    pub fn to_raw(&self) -> RawMesh {
        let mut polygons = Polygons::with_capacity(self.num_faces(), self.indices.len());
        let mut corners = Vec::new();
        for f in 0..self.num_faces() {
            corners.clear();
            corners.extend(self.face(f).iter().map(|&v| v as usize));
            polygons.push(&corners);
        }
        RawMesh {
            positions: self.positions.clone(),
            polygons,
            ..RawMesh::default()
        }
    }

    /// Builds the adjacency of already range-checked flat faces. Crease pairs are in range.
    pub(crate) fn from_parts(
        positions: Vec<Point3<f64>>,
        indices: Vec<u32>,
        offsets: Vec<u32>,
        creases: &[[u32; 2]],
    ) -> Result<Self, SubdivError> {
        let topo = build_topology(positions.len(), &indices, &offsets, creases)?;
        Ok(PolyMesh {
            positions,
            indices,
            offsets,
            topo,
        })
    }

    /// No vertices, no faces.
    pub fn empty() -> Self {
        PolyMesh {
            positions: Vec::new(),
            indices: Vec::new(),
            offsets: vec![0],
            topo: Topology::default(),
        }
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[Point3<f64>] {
        &self.positions
    }

    /// Number of vertices (isolated ones included).
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Number of edges.
    pub fn num_edges(&self) -> usize {
        self.topo.edge_half.len()
    }

    /// Total number of corners (= half-edges).
    pub fn num_corners(&self) -> usize {
        self.indices.len()
    }

    /// The corners of face `f`, counter-clockwise. Panics if `f` is out of range.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.indices[self.offsets[f] as usize..self.offsets[f + 1] as usize]
    }

    /// The faces in order.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.offsets
            .windows(2)
            .map(|w| &self.indices[w[0] as usize..w[1] as usize])
    }

    /// True when every face is a triangle.
    pub fn all_triangles(&self) -> bool {
        self.indices.len() == 3 * self.num_faces()
    }

    /// True when every face is a quadrilateral.
    pub fn all_quads(&self) -> bool {
        self.indices.len() == 4 * self.num_faces()
            && self.offsets.windows(2).all(|w| w[1] - w[0] == 4)
    }

    /// The first face that is not a triangle, with its number of corners.
    pub fn first_non_triangle(&self) -> Option<(usize, usize)> {
        self.offsets
            .windows(2)
            .position(|w| w[1] - w[0] != 3)
            .map(|f| (f, (self.offsets[f + 1] - self.offsets[f]) as usize))
    }

    /// The crease edges (tagged by the user or inherited from a coarser level), each as
    /// `[a, b]` with `a < b`, in edge order.
    pub fn creases(&self) -> Vec<[usize; 2]> {
        (0..self.num_edges())
            .filter(|&e| self.topo.crease[e])
            .map(|e| {
                let [a, b] = self.edge_ends(e);
                [a.min(b) as usize, a.max(b) as usize]
            })
            .collect()
    }

    /// The edges as `[a, b]` (direction of their first half-edge), in edge order.
    pub fn edges(&self) -> Vec<[usize; 2]> {
        (0..self.num_edges())
            .map(|e| self.edge_ends(e).map(|v| v as usize))
            .collect()
    }

    /// How vertex `v` is treated by the rules. Panics if `v` is out of range.
    pub fn vertex_kind(&self, v: usize) -> VertexKind {
        self.topo.kind[v]
    }

    /// True if edge `e` (in the order of [`Self::edges`]) is a boundary edge.
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.topo.twin[self.topo.edge_half[e] as usize] == NONE
    }

    /// The same connectivity and creases with other positions (one per vertex).
    pub fn with_positions(&self, positions: Vec<Point3<f64>>) -> Result<Self, SubdivError> {
        if positions.len() != self.positions.len() {
            return Err(SubdivError::IndexOutOfRange {
                face: 0,
                index: positions.len(),
                vertices: self.positions.len(),
            });
        }
        if let Some(vertex) = positions
            .iter()
            .position(|p| !p.coords.iter().all(|c| c.is_finite()))
        {
            return Err(SubdivError::NonFinitePosition { vertex });
        }
        Ok(PolyMesh {
            positions,
            indices: self.indices.clone(),
            offsets: self.offsets.clone(),
            topo: self.topo.clone(),
        })
    }

    // ---- half-edge navigation (crate-internal) -------------------------------------------

    pub(crate) fn indices(&self) -> &[u32] {
        &self.indices
    }

    pub(crate) fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// Start vertex of half-edge `h`.
    #[inline]
    pub(crate) fn tail(&self, h: u32) -> u32 {
        self.indices[h as usize]
    }

    /// Next half-edge in the same face.
    #[inline]
    pub(crate) fn next(&self, h: u32) -> u32 {
        let f = self.topo.face_of[h as usize] as usize;
        if h + 1 == self.offsets[f + 1] {
            self.offsets[f]
        } else {
            h + 1
        }
    }

    /// Previous half-edge in the same face.
    #[inline]
    pub(crate) fn prev(&self, h: u32) -> u32 {
        let f = self.topo.face_of[h as usize] as usize;
        if h == self.offsets[f] {
            self.offsets[f + 1] - 1
        } else {
            h - 1
        }
    }

    /// End vertex of half-edge `h`.
    #[inline]
    pub(crate) fn head(&self, h: u32) -> u32 {
        self.indices[self.next(h) as usize]
    }

    /// Endpoints of edge `e` along its first half-edge.
    #[inline]
    pub(crate) fn edge_ends(&self, e: usize) -> [u32; 2] {
        let h = self.topo.edge_half[e];
        [self.tail(h), self.head(h)]
    }

    /// The outgoing half-edges of `v` in counter-clockwise order (on the boundary starting at
    /// the outgoing boundary half-edge), appended to `out`.
    pub(crate) fn outgoing(&self, v: usize, out: &mut Vec<u32>) {
        let start = self.topo.vertex_out[v];
        if start == NONE {
            return;
        }
        let mut h = start;
        loop {
            out.push(h);
            let t = self.topo.twin[self.prev(h) as usize];
            if t == NONE || t == start {
                break;
            }
            h = t;
        }
    }

    /// The neighbours of `v` in counter-clockwise order, appended to `out`: for an interior
    /// vertex one per edge, starting anywhere; for a boundary vertex from the far end of the
    /// outgoing boundary edge round to the far end of the incoming one.
    pub(crate) fn ring(&self, v: usize, out: &mut Vec<u32>) {
        let mut hs = Vec::new();
        self.outgoing(v, &mut hs);
        for &h in &hs {
            out.push(self.head(h));
        }
        if let Some(&last) = hs.last() {
            let p = self.prev(last);
            if self.topo.twin[p as usize] == NONE {
                out.push(self.tail(p));
            }
        }
    }

    /// Sum of the positions of the vertices joined to `v` by sharp edges.
    pub(crate) fn sharp_neighbour_sum(&self, v: usize) -> Vector3<f64> {
        let mut hs = Vec::new();
        self.outgoing(v, &mut hs);
        let mut s = Vector3::zeros();
        for &h in &hs {
            if self.topo.sharp[self.topo.edge[h as usize] as usize] {
                s += self.positions[self.head(h) as usize].coords;
            }
        }
        if let Some(&last) = hs.last() {
            let p = self.prev(last);
            if self.topo.twin[p as usize] == NONE {
                s += self.positions[self.tail(p) as usize].coords;
            }
        }
        s
    }
}

/// Builds the adjacency; see the module documentation for what is refused.
fn build_topology(
    nv: usize,
    indices: &[u32],
    offsets: &[u32],
    creases: &[[u32; 2]],
) -> Result<Topology, SubdivError> {
    let nh = indices.len();
    let nf = offsets.len() - 1;
    let mut face_of = vec![0u32; nh];
    let mut to = vec![0u32; nh];
    for f in 0..nf {
        let (s, e) = (offsets[f] as usize, offsets[f + 1] as usize);
        for h in s..e {
            face_of[h] = f as u32;
            to[h] = indices[if h + 1 == e { s } else { h + 1 }];
        }
    }
    // Outgoing half-edges per vertex, compressed rows.
    let mut start = vec![0u32; nv + 1];
    for &v in indices {
        start[v as usize + 1] += 1;
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut out = vec![0u32; nh];
    for (h, &v) in indices.iter().enumerate() {
        out[fill[v as usize] as usize] = h as u32;
        fill[v as usize] += 1;
    }
    drop(fill);
    let row = |v: u32| &out[start[v as usize] as usize..start[v as usize + 1] as usize];
    // Twins, and the refusal of edges used twice in one direction or by more than two faces.
    let mut twin = vec![NONE; nh];
    for h in 0..nh {
        let (a, b) = (indices[h], to[h]);
        let same = row(a).iter().filter(|&&g| to[g as usize] == b).count();
        let mut opposite = 0;
        let mut found = NONE;
        for &g in row(b) {
            if to[g as usize] == a {
                opposite += 1;
                found = g;
            }
        }
        if same + opposite > 2 {
            return Err(SubdivError::NonManifoldEdge {
                a: a.min(b) as usize,
                b: a.max(b) as usize,
                faces: same + opposite,
            });
        }
        if same > 1 {
            return Err(SubdivError::InconsistentOrientation {
                a: a as usize,
                b: b as usize,
            });
        }
        twin[h] = found;
    }
    // Edges.
    let mut edge = vec![0u32; nh];
    let mut edge_half = Vec::with_capacity(nh / 2 + nh / 8 + 1);
    for h in 0..nh {
        let t = twin[h];
        if t == NONE || (h as u32) < t {
            let e = edge_half.len() as u32;
            edge[h] = e;
            if t != NONE {
                edge[t as usize] = e;
            }
            edge_half.push(h as u32);
        }
    }
    let ne = edge_half.len();
    let mut sharp: Vec<bool> = edge_half
        .iter()
        .map(|&h| twin[h as usize] == NONE)
        .collect();
    let mut crease = vec![false; ne];
    for &[a, b] in creases {
        let h = row(a)
            .iter()
            .copied()
            .find(|&g| to[g as usize] == b)
            .or_else(|| row(b).iter().copied().find(|&g| to[g as usize] == a))
            .ok_or(SubdivError::CreaseNotAnEdge {
                a: a as usize,
                b: b as usize,
            })?;
        let e = edge[h as usize] as usize;
        if !sharp[e] {
            crease[e] = true;
            sharp[e] = true;
        }
    }
    let mut sharp_count = vec![0u8; nv];
    for (e, &h) in edge_half.iter().enumerate() {
        if sharp[e] {
            for v in [indices[h as usize], to[h as usize]] {
                let c = &mut sharp_count[v as usize];
                *c = c.saturating_add(1);
            }
        }
    }
    // Fans: one per vertex, walked counter-clockwise from the outgoing boundary half-edge.
    let prev = |h: u32| {
        let f = face_of[h as usize] as usize;
        if h == offsets[f] {
            offsets[f + 1] - 1
        } else {
            h - 1
        }
    };
    let mut vertex_out = vec![NONE; nv];
    let mut kind = vec![VertexKind::Isolated; nv];
    for v in 0..nv {
        let hs = row(v as u32);
        if hs.is_empty() {
            continue;
        }
        let mut boundary = hs.iter().copied().filter(|&g| twin[g as usize] == NONE);
        let first = boundary.next();
        if boundary.next().is_some() {
            return Err(SubdivError::NonManifoldVertex { vertex: v });
        }
        let s = first.unwrap_or(hs[0]);
        let mut h = s;
        let mut count = 1;
        loop {
            let t = twin[prev(h) as usize];
            if t == NONE || t == s {
                break;
            }
            h = t;
            count += 1;
            if count > hs.len() {
                break;
            }
        }
        if count != hs.len() {
            return Err(SubdivError::NonManifoldVertex { vertex: v });
        }
        vertex_out[v] = s;
        kind[v] = match sharp_count[v] {
            0 => VertexKind::Smooth,
            1 => VertexKind::Dart,
            2 => VertexKind::Crease,
            _ => VertexKind::Corner,
        };
    }
    Ok(Topology {
        face_of,
        twin,
        edge,
        edge_half,
        sharp,
        crease,
        vertex_out,
        kind,
    })
}

/// New crease pairs after a step that puts the point of edge `e` at index `edge_base + e`:
/// each crease edge `(a, b)` becomes `(a, m)` and `(m, b)`.
pub(crate) fn split_creases(mesh: &PolyMesh, edge_base: u32) -> Vec<[u32; 2]> {
    let mut out = Vec::new();
    for e in 0..mesh.num_edges() {
        if mesh.topo.crease[e] {
            let [a, b] = mesh.edge_ends(e);
            let m = edge_base + e as u32;
            out.push([a, m]);
            out.push([m, b]);
        }
    }
    out
}

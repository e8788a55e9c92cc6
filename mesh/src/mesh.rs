//! Triangle meshes with half-edge adjacency and per-vertex data.
//!
//! The testbed's mesh library (Lounsbery et al. 1990, §4.1) stores meshes in a modified
//! winged-edge structure and offers iterators over faces, over the vertices of a face, data
//! attached to vertices, and "a command to walk along a user-specified path through the mesh".
//! [`Mesh`] offers the same on an array-based half-edge structure.
//!
//! # Conventions
//!
//! * Faces are triangles `[a, b, c]` of vertex indices; their orientation (counter-clockwise
//!   seen from the side the normals point to) is kept as given and checked to be consistent.
//! * **Local edge** `l ∈ {0, 1, 2}` of a face runs from corner `l` to corner `(l + 1) % 3`;
//!   it is opposite corner `(l + 2) % 3`. This matches the edges of a triangular Bézier patch in
//!   [`crate::beztri`] (edge 0 is `w = 0`, from the `u` corner to the `v` corner).
//! * Half-edge `h = 3 f + l` is local edge `l` of face `f`.
//! * Undirected edges get a stable index: numbered in the order of their first half-edge
//!   (faces in order, local edges in order), each edge once ([`Mesh::edge_index`]).
//! * The faces around a vertex ([`Mesh::faces_around_vertex`]) come counter-clockwise (seen
//!   from the side of the normals) as one unbroken fan; at a boundary vertex the fan starts at
//!   the face reached by turning clockwise until a boundary edge is met, and ends at the other
//!   boundary edge.
//!
//! # Validation
//!
//! [`Mesh::new`] rejects faces that reference a missing vertex, degenerate faces (a repeated
//! vertex, or zero area relative to the face's size, [`DEGENERATE_FACE_SINE`]), non-finite vertex
//! data, edges used by more than two faces or twice in the same direction (inconsistent
//! orientation), and non-manifold vertices (two fans of faces touching at one vertex), each with
//! the index of the face, edge or vertex at fault.

use std::collections::BTreeMap;

use crate::sectors::{SectorError, Sectors};
use crate::vertex::VertexData;
use nalgebra::{Matrix3, Point3, Vector3};
use rayon::prelude::*;

use crate::edge_groups::{ends, key, EdgeGroups};
use crate::vertex_pieces::for_each_half_edge_by_vertex;

/// A face whose doubled area is below this fraction of the product of its two longest edges
/// (the sine of its largest angle, in effect) is degenerate: below `1e-12` a face normal has lost
/// most of its digits to cancellation.
pub const DEGENERATE_FACE_SINE: f64 = 1e-12;

/// Extra named per-vertex (or per-mesh) fields a reader found and did not interpret, kept so that
/// a writer can put them back (the testbed's extensibility rule).
pub type ExtraFields = BTreeMap<String, Vec<f64>>;

/// The twin of a boundary half-edge in the construction's `usize` arrays.
pub(crate) const NO_TWIN: usize = usize::MAX;

/// "None" in [`Mesh`]'s stored `u32` half-edge and edge arrays: the twin of a boundary half-edge,
/// the outgoing half-edge of an isolated vertex.
const NONE32: u32 = u32::MAX;

/// The most faces a [`Mesh`] holds: its half-edge and edge arrays store `u32` indices (half the
/// memory of `usize`: 36 MB less at 10⁶ faces), and every half-edge `3f + l` must be below
/// `u32::MAX`, their "none" value.
pub const MAX_FACES: usize = (u32::MAX as usize - 1) / 3;

/// The most vertices a [`Mesh`] holds, so that every face and vertex index of a mesh is a `u32`
/// (the estimators' adjacency lists store them so: `estimate::Topology`).
pub const MAX_VERTICES: usize = u32::MAX as usize;

/// A stored half-edge index and its "none" value: `usize` in the construction's arrays
/// ([`NO_TWIN`]), `u32` in the mesh's ([`NONE32`]), so that the fan walks serve both.
pub(crate) trait HalfEdgeSlot: Copy + Send + Sync {
    /// The index, `None` for the "none" value.
    fn get(self) -> Option<usize>;
}

impl HalfEdgeSlot for usize {
    fn get(self) -> Option<usize> {
        (self != NO_TWIN).then_some(self)
    }
}

impl HalfEdgeSlot for u32 {
    fn get(self) -> Option<usize> {
        (self != NONE32).then_some(self as usize)
    }
}

impl HalfEdgeSlot for Option<usize> {
    fn get(self) -> Option<usize> {
        self
    }
}

/// `h` (below `3 ·` [`MAX_FACES`], or `None`) as a stored `u32`.
fn slot32(h: Option<usize>) -> u32 {
    h.map_or(NONE32, |h| h as u32)
}

/// One vertex: position, normal and shape tensor, whether the curvature is known, a name and
/// extra fields.
///
/// The name and the extra fields, which few files have, live behind one optional box
/// ([`Vertex::name`], [`Vertex::extra`]): a vertex is 136 bytes instead of the 176 it took with
/// both inline (20 MB at 500 000 vertices).
#[derive(Clone, Debug)]
pub struct Vertex {
    /// Position, normal and shape tensor `S` (`κn(d) = dᵀ S d`).
    pub data: VertexData,
    /// False when the source gave no curvature: `data.shape` is then the zero matrix and a
    /// method that needs curvature must say so rather than use it.
    pub curvature_known: bool,
    /// The name and the extra fields; `None` when it has neither.
    labels: Option<Box<VertexLabels>>,
}

/// A vertex's name in its source file and the fields a reader kept without interpreting them.
#[derive(Clone, Debug, Default, PartialEq)]
struct VertexLabels {
    name: Option<String>,
    extra: ExtraFields,
}

/// The extra fields of a vertex that has none.
static NO_EXTRA: ExtraFields = ExtraFields::new();

impl PartialEq for Vertex {
    /// Equal data, curvature flag, name and extra fields (however the labels are stored).
    fn eq(&self, other: &Self) -> bool {
        self.data == other.data
            && self.curvature_known == other.curvature_known
            && self.name() == other.name()
            && self.extra() == other.extra()
    }
}

impl Vertex {
    /// A vertex with known position, normal and shape tensor.
    pub fn new(data: VertexData) -> Self {
        Vertex {
            data,
            curvature_known: true,
            labels: None,
        }
    }

    /// A vertex whose curvature is unknown: shape tensor zero and flagged.
    pub fn without_curvature(p: Point3<f64>, n: Vector3<f64>) -> Self {
        Vertex {
            data: VertexData::new(p, n, Matrix3::zeros()),
            curvature_known: false,
            labels: None,
        }
    }

    /// The same vertex with a name.
    pub fn named(mut self, name: impl Into<String>) -> Self {
        self.set_name(Some(name.into()));
        self
    }

    /// The vertex's name in its source file, if it had one.
    pub fn name(&self) -> Option<&str> {
        self.labels.as_ref()?.name.as_deref()
    }

    /// Sets (or, with `None`, removes) the vertex's name.
    pub fn set_name(&mut self, name: Option<String>) {
        match (&mut self.labels, name) {
            (Some(labels), name) => labels.name = name,
            (None, None) => {}
            (None, name) => {
                self.labels = Some(Box::new(VertexLabels {
                    name,
                    ..VertexLabels::default()
                }))
            }
        }
    }

    /// Fields the reader kept without interpreting them (empty when there are none).
    pub fn extra(&self) -> &ExtraFields {
        self.labels.as_ref().map_or(&NO_EXTRA, |l| &l.extra)
    }

    /// [`Vertex::extra`], to change.
    pub fn extra_mut(&mut self) -> &mut ExtraFields {
        &mut self.labels.get_or_insert_with(Box::default).extra
    }
}

/// Why a mesh could not be built or a query could not be answered.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A face refers to a vertex index that does not exist.
    #[error("face {face}: corner {corner} refers to vertex {vertex}, but there are only {count} vertices")]
    MissingVertex {
        /// The face.
        face: usize,
        /// Which corner (0, 1, 2).
        corner: usize,
        /// The missing index.
        vertex: usize,
        /// How many vertices there are.
        count: usize,
    },
    /// A face uses the same vertex twice.
    #[error("face {face}: vertex {vertex} appears twice")]
    RepeatedVertex {
        /// The face.
        face: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// A face has (relatively) zero area.
    #[error("face {face} (vertices {vertices:?}) has zero area")]
    ZeroArea {
        /// The face.
        face: usize,
        /// Its vertices.
        vertices: [usize; 3],
    },
    /// A vertex has a NaN or infinite coordinate.
    #[error("vertex {vertex}: non-finite {what}")]
    NonFinite {
        /// The vertex.
        vertex: usize,
        /// `"position"`, `"normal"` or `"shape tensor"`.
        what: &'static str,
    },
    /// An edge is used by more than two faces.
    #[error("edge {}–{} is used by more than two faces ({faces:?})", vertices[0], vertices[1])]
    NonManifoldEdge {
        /// The edge's vertices.
        vertices: [usize; 2],
        /// The faces using it.
        faces: Vec<usize>,
    },
    /// Two faces traverse an edge in the same direction: their orientations disagree.
    #[error("edge {}→{} is used in the same direction by faces {} and {}: inconsistent orientation", vertices[0], vertices[1], faces[0], faces[1])]
    InconsistentOrientation {
        /// The directed edge.
        vertices: [usize; 2],
        /// The two faces.
        faces: [usize; 2],
    },
    /// The faces around a vertex form more than one fan.
    #[error("vertex {vertex} is non-manifold: its faces form more than one fan")]
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
    },
    /// A face index out of range in a query.
    #[error("face {face} does not exist (there are {count} faces)")]
    NoSuchFace {
        /// The index asked for.
        face: usize,
        /// How many faces there are.
        count: usize,
    },
    /// A local edge index other than 0, 1, 2.
    #[error("local edge {0} does not exist (local edges are 0, 1, 2)")]
    NoSuchLocalEdge(usize),
    /// More faces than a mesh holds ([`MAX_FACES`]: its half-edges are `u32` indices).
    #[error("{faces} faces: a mesh holds at most {MAX_FACES}")]
    TooLarge {
        /// How many faces were given.
        faces: usize,
    },
    /// More vertices than a mesh holds ([`MAX_VERTICES`]: the estimators index them as `u32`).
    #[error("{vertices} vertices: a mesh holds at most {MAX_VERTICES}")]
    TooManyVertices {
        /// How many vertices were given.
        vertices: usize,
    },
    /// A walk tried to cross a boundary edge.
    #[error("walk step {step}: local edge {local_edge} of face {face} is a boundary edge")]
    WalkOffBoundary {
        /// Index of the step in the walk.
        step: usize,
        /// The face the walk was on.
        face: usize,
        /// The edge it tried to cross.
        local_edge: usize,
    },
}

/// An undirected edge: its vertices and the one or two (face, local edge) pairs using it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// The vertices in the direction of the first face using the edge.
    pub vertices: [usize; 2],
    /// The first face using the edge and its local edge index there.
    pub first: (usize, usize),
    /// The second face and local edge, `None` on a boundary edge.
    pub second: Option<(usize, usize)>,
}

impl Edge {
    /// True when only one face uses the edge.
    pub fn is_boundary(&self) -> bool {
        self.second.is_none()
    }
}

/// A validated triangle mesh with half-edge adjacency.
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    vertices: Vec<Vertex>,
    faces: Vec<[usize; 3]>,
    /// Face names, empty when no face has one (8 bytes a face saved on the common case).
    face_names: Vec<Option<String>>,
    /// Twin of each half-edge, [`NONE32`] on the boundary.
    twin: Vec<u32>,
    /// Undirected edge of each half-edge.
    edge_of: Vec<u32>,
    /// The first half-edge of each undirected edge: the edge's [`Edge`] is read from it and its
    /// twin ([`Mesh::edge`]), 4 bytes an edge instead of the 56 of a stored `Edge`.
    edge_first: Vec<u32>,
    /// One outgoing half-edge per vertex, [`NONE32`] for an isolated vertex.
    outgoing: Vec<u32>,
    /// Per-mesh fields a reader kept.
    pub extra: ExtraFields,
    /// Per-sector data at the creases ([`crate::sectors`]); `None`: one normal and shape tensor
    /// per vertex.
    sectors: Option<Box<Sectors>>,
}

/// The twin of every half-edge of valid faces ([`NO_TWIN`] on the boundary), or the first
/// error in half-edge order (the one a half-edge-by-half-edge construction meets first): a
/// second half-edge running the same way along an edge, or a third half-edge on it.
fn twins(faces: &[[usize; 3]]) -> Result<Vec<usize>, MeshError> {
    let groups = EdgeGroups::new(faces);
    let dir = |h: usize| faces[h / 3][h % 3];
    let mut first_error: Option<(usize, MeshError)> = None;
    for hs in groups.iter() {
        let trigger = if hs.len() >= 2 && dir(hs[0]) == dir(hs[1]) {
            let (a, b) = ends(faces, hs[1]);
            Some((
                hs[1],
                MeshError::InconsistentOrientation {
                    vertices: [a, b],
                    faces: [hs[0] / 3, hs[1] / 3],
                },
            ))
        } else if hs.len() >= 3 {
            let (lo, hi) = key(faces, hs[0]);
            Some((
                hs[2],
                MeshError::NonManifoldEdge {
                    vertices: [lo, hi],
                    faces: hs[..3].iter().map(|h| h / 3).collect(),
                },
            ))
        } else {
            None
        };
        if let Some((h, e)) = trigger {
            if first_error.as_ref().is_none_or(|(h0, _)| h < *h0) {
                first_error = Some((h, e));
            }
        }
    }
    if let Some((_, e)) = first_error {
        return Err(e);
    }
    let mut twin = vec![NO_TWIN; 3 * faces.len()];
    for hs in groups.iter() {
        if let [h0, h1] = *hs {
            twin[h0] = h1;
            twin[h1] = h0;
        }
    }
    Ok(twin)
}

/// [`MeshError::TooManyVertices`] for more than [`MAX_VERTICES`] vertices.
fn check_vertex_count(vertices: usize) -> Result<(), MeshError> {
    if vertices > MAX_VERTICES {
        return Err(MeshError::TooManyVertices { vertices });
    }
    Ok(())
}

/// [`MeshError::TooLarge`] for more than [`MAX_FACES`] faces.
fn check_size(faces: usize) -> Result<(), MeshError> {
    if faces > MAX_FACES {
        return Err(MeshError::TooLarge { faces });
    }
    Ok(())
}

/// A mesh's half-edge arrays, built from its faces and twins.
struct Adjacency {
    twin: Vec<u32>,
    edge_of: Vec<u32>,
    edge_first: Vec<u32>,
    outgoing: Vec<u32>,
}

impl Adjacency {
    /// From valid faces and a twin array pairing half-edges that run along the same edge in
    /// opposite directions ([`NO_TWIN`] on the boundary): numbers the edges in the order of
    /// their first half-edge ([`number_edges`]) and picks each vertex's outgoing half-edge
    /// ([`outgoing_half_edges`]), side by side.
    /// The stored arrays are `u32`: `faces` has at most [`MAX_FACES`] faces (checked by the
    /// callers).
    fn new(faces: &[[usize; 3]], twin: Vec<usize>, vertex_count: usize) -> Self {
        debug_assert!(faces.len() <= MAX_FACES);
        let ((edge_of, edge_first), outgoing) = rayon::join(
            || number_edges(&twin),
            || {
                outgoing_half_edges(faces, &twin, vertex_count)
                    .into_iter()
                    .map(slot32)
                    .collect()
            },
        );
        let twin = twin.par_iter().map(|&t| slot32(t.get())).collect();
        Adjacency {
            twin,
            edge_of,
            edge_first,
            outgoing,
        }
    }
}

/// The undirected edges of valid faces with twins `twin`, numbered in the order of their first
/// half-edge: the edge of every half-edge and the first half-edge of every edge.
///
/// Walking the half-edges in order, a half-edge starts an edge unless its twin came before
/// it; an edge's number is then the count of starting half-edges before it. That count is
/// taken per block of half-edges in parallel, summed, and each block then numbers its own
/// starting half-edges and their twins (every half-edge is written once, by the block of its
/// edge's first half-edge, hence the atomics, which cost nothing uncontended) and notes the
/// half-edge each edge starts at.
fn number_edges(twin: &[usize]) -> (Vec<u32>, Vec<u32>) {
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let nh = twin.len();
    let starts = |h: usize| twin[h] == NO_TWIN || twin[h] > h;
    let block = (nh / (8 * rayon::current_num_threads().max(1))).max(1 << 14);
    let blocks = nh.div_ceil(block);
    let range = |b: usize| b * block..((b + 1) * block).min(nh);
    let counts: Vec<usize> = (0..blocks)
        .into_par_iter()
        .map(|b| range(b).filter(|&h| starts(h)).count())
        .collect();
    let mut offsets = Vec::with_capacity(blocks);
    let mut total = 0;
    for c in counts {
        offsets.push(total);
        total += c;
    }
    // (Every half-edge and edge index is below 3 · MAX_FACES: the casts are exact.)
    let edge_of: Vec<AtomicU32> = (0..nh).into_par_iter().map(|_| AtomicU32::new(0)).collect();
    let first: Vec<AtomicU32> = (0..total)
        .into_par_iter()
        .map(|_| AtomicU32::new(0))
        .collect();
    offsets.into_par_iter().enumerate().for_each(|(b, mut e)| {
        for h in range(b).filter(|&h| starts(h)) {
            edge_of[h].store(e as u32, Relaxed);
            if let Some(t) = twin.get(h).copied().filter(|&t| t != NO_TWIN) {
                edge_of[t].store(e as u32, Relaxed);
            }
            first[e].store(h as u32, Relaxed);
            e += 1;
        }
    });
    let edge_of = edge_of.into_iter().map(AtomicU32::into_inner).collect();
    let first = first.into_iter().map(AtomicU32::into_inner).collect();
    (edge_of, first)
}

/// One half-edge leaving each of `vertex_count` vertices (`None` for a vertex in no face):
/// the last one on the boundary, else the first. Preferring the boundary is not needed for
/// correctness (queries rotate to the boundary), but makes the common case cheap.
pub(crate) fn outgoing_half_edges(
    faces: &[[usize; 3]],
    twin: &[usize],
    vertex_count: usize,
) -> Vec<Option<usize>> {
    let mut outgoing = vec![None; vertex_count];
    for_each_half_edge_by_vertex(
        faces,
        &mut outgoing,
        |t, l| t[l],
        |slot, h| {
            if slot.is_none() || twin[h] == NO_TWIN {
                *slot = Some(h);
            }
        },
    );
    outgoing
}

/// Walks the fan of half-edge `start`'s vertex across `twin` ([`NO_TWIN`] on the boundary):
/// first clockwise (`h → next(twin(h))`) until a boundary or back at the start, then
/// counter-clockwise (`h → twin(prev(h))`), calling `visit` with each half-edge of that second
/// pass (one per face, in order).
fn walk_fan<T: HalfEdgeSlot>(twin: &[T], start: usize, mut visit: impl FnMut(usize)) {
    let nh = twin.len();
    let twin_of = |h: usize| twin.get(h).and_then(|t| t.get());
    let mut h = start;
    for _ in 0..nh {
        match twin_of(h) {
            Some(t) if Mesh::next(t) != start => h = Mesh::next(t),
            _ => break,
        }
    }
    let first = h;
    visit(h);
    for _ in 0..nh {
        match twin_of(Mesh::prev(h)) {
            Some(t) if t != first => {
                h = t;
                visit(h);
            }
            _ => break,
        }
    }
}

/// The lowest vertex whose faces form more than one fan across `twin`, in parallel: one
/// whose fan walk from `outgoing[v]` ([`outgoing_half_edges`]) does not meet every half-edge
/// leaving it. `None` when every vertex is manifold.
pub(crate) fn first_vertex_with_several_fans<T: HalfEdgeSlot, O: HalfEdgeSlot>(
    faces: &[[usize; 3]],
    twin: &[T],
    outgoing: &[O],
) -> Option<usize> {
    let mut incident = vec![0usize; outgoing.len()];
    for_each_half_edge_by_vertex(faces, &mut incident, |t, l| t[l], |c, _| *c += 1);
    let fan_len = |v: usize| {
        let mut len = 0;
        if let Some(start) = outgoing[v].get() {
            walk_fan(twin, start, |_| len += 1);
        }
        len
    };
    (0..outgoing.len())
        .into_par_iter()
        .find_first(|&v| fan_len(v) != incident[v])
}

/// The zero-area test of [`Mesh::new`]: doubled area at most [`DEGENERATE_FACE_SINE`] times
/// the product of the two longest edges. Coordinates are finite (checked before), so no NaN
/// reaches the comparison; a face with a NaN area (overflow) counts as degenerate.
pub(crate) fn is_degenerate([a, b, c]: [Point3<f64>; 3]) -> bool {
    let (e1, e2, e3) = (b - a, c - a, c - b);
    let mut lengths = [e1.norm(), e2.norm(), e3.norm()];
    lengths.sort_by(f64::total_cmp);
    let area2 = e1.cross(&e2).norm();
    let limit = DEGENERATE_FACE_SINE * lengths[1] * lengths[2];
    area2.partial_cmp(&limit) != Some(std::cmp::Ordering::Greater)
}

/// The first vertex with non-finite data, in parallel (`find_first`: the lowest index, as a
/// loop finds).
fn check_vertices(vertices: &[Vertex]) -> Result<(), MeshError> {
    match vertices
        .par_iter()
        .enumerate()
        .map(|(i, v)| check_vertex(i, v))
        .find_first(Result::is_err)
    {
        Some(Err(e)) => Err(e),
        _ => Ok(()),
    }
}

fn check_vertex(i: usize, v: &Vertex) -> Result<(), MeshError> {
    let bad = |what| Err(MeshError::NonFinite { vertex: i, what });
    if !v.data.p.iter().all(|c| c.is_finite()) {
        return bad("position");
    }
    if !v.data.n.iter().all(|c| c.is_finite()) {
        return bad("normal");
    }
    if !v.data.shape.iter().all(|c| c.is_finite()) {
        return bad("shape tensor");
    }
    Ok(())
}

impl Mesh {
    /// Builds and validates a mesh (see the module docs for what is rejected).
    pub fn new(vertices: Vec<Vertex>, faces: Vec<[usize; 3]>) -> Result<Self, MeshError> {
        Self::build(vertices, faces, false)
    }

    /// [`Mesh::new`], but faces of (relatively) zero area are accepted: the repair of user files
    /// ([`crate::repair`]) keeps them so that the mesh has no hole, and the fit gives them a
    /// stated fallback patch. Everything else is validated as in [`Mesh::new`].
    pub fn new_allowing_degenerate(
        vertices: Vec<Vertex>,
        faces: Vec<[usize; 3]>,
    ) -> Result<Self, MeshError> {
        Self::build(vertices, faces, true)
    }

    /// True when face `f` has (relatively) zero area: its doubled area is at most
    /// [`DEGENERATE_FACE_SINE`] times the product of its two longest edges (false for a face
    /// that does not exist).
    pub fn is_degenerate_face(&self, f: usize) -> bool {
        self.faces
            .get(f)
            .is_some_and(|face| is_degenerate(face.map(|i| self.vertices[i].data.p)))
    }

    fn build(
        vertices: Vec<Vertex>,
        faces: Vec<[usize; 3]>,
        allow_degenerate: bool,
    ) -> Result<Self, MeshError> {
        check_size(faces.len())?;
        check_vertex_count(vertices.len())?;
        let count = vertices.len();
        check_vertices(&vertices)?;
        for (f, face) in faces.iter().enumerate() {
            for (corner, &vertex) in face.iter().enumerate() {
                if vertex >= count {
                    return Err(MeshError::MissingVertex {
                        face: f,
                        corner,
                        vertex,
                        count,
                    });
                }
            }
            for l in 0..3 {
                if face[l] == face[(l + 1) % 3] {
                    return Err(MeshError::RepeatedVertex {
                        face: f,
                        vertex: face[l],
                    });
                }
            }
            if !allow_degenerate && is_degenerate(face.map(|i| vertices[i].data.p)) {
                return Err(MeshError::ZeroArea {
                    face: f,
                    vertices: *face,
                });
            }
        }

        let twin = twins(&faces)?;
        let adjacency = Adjacency::new(&faces, twin, count);
        let mesh = Self::assemble(vertices, faces, adjacency);
        match mesh.first_non_manifold_vertex() {
            Some(vertex) => Err(MeshError::NonManifoldVertex { vertex }),
            None => Ok(mesh),
        }
    }

    /// The mesh of faces whose adjacency the repair ([`crate::repair`]) has established: every
    /// corner a vertex of `vertices`, no repeated vertex in a face, `twin` pairing the
    /// half-edges of every edge with two faces running opposite ways ([`NO_TWIN`] on the
    /// boundary), no edge with a third face, and the faces around every vertex one fan across
    /// these twins. The validation of [`Mesh::new_allowing_degenerate`] would find exactly these
    /// twins and nothing to reject, so only the vertex data is checked (the same
    /// [`MeshError::NonFinite`] as there); debug builds check the rest too.
    pub(crate) fn from_twins(
        vertices: Vec<Vertex>,
        faces: Vec<[usize; 3]>,
        twin: Vec<usize>,
    ) -> Result<Self, MeshError> {
        check_size(faces.len())?;
        check_vertex_count(vertices.len())?;
        debug_assert_eq!(twins(&faces).as_ref(), Ok(&twin));
        // The vertex check and the adjacency side by side (they share nothing).
        let (checked, adjacency) = rayon::join(
            || check_vertices(&vertices),
            || Adjacency::new(&faces, twin, vertices.len()),
        );
        checked?;
        let mesh = Self::assemble(vertices, faces, adjacency);
        debug_assert_eq!(mesh.first_non_manifold_vertex(), None);
        Ok(mesh)
    }

    /// The mesh of valid vertices and faces with their adjacency. Nothing is checked.
    fn assemble(vertices: Vec<Vertex>, faces: Vec<[usize; 3]>, adjacency: Adjacency) -> Self {
        let Adjacency {
            twin,
            edge_of,
            edge_first,
            outgoing,
        } = adjacency;
        Mesh {
            face_names: Vec::new(),
            vertices,
            faces,
            twin,
            edge_of,
            edge_first,
            outgoing,
            extra: ExtraFields::new(),
            sectors: None,
        }
    }

    /// The lowest vertex whose faces form more than one fan (in parallel).
    fn first_non_manifold_vertex(&self) -> Option<usize> {
        first_vertex_with_several_fans(&self.faces, &self.twin, &self.outgoing)
    }

    /// The same mesh with face names (for writers and messages); `names` shorter than the face
    /// list leaves the remaining faces unnamed.
    pub fn with_face_names(mut self, names: Vec<String>) -> Self {
        if self.face_names.is_empty() {
            self.face_names = vec![None; self.faces.len()];
        }
        for (slot, name) in self.face_names.iter_mut().zip(names) {
            *slot = Some(name);
        }
        if self.face_names.iter().all(Option::is_none) {
            self.face_names = Vec::new();
        }
        self
    }

    /// Number of vertices `V`.
    pub fn num_vertices(&self) -> usize {
        self.vertices.len()
    }

    /// Number of faces `F`.
    pub fn num_faces(&self) -> usize {
        self.faces.len()
    }

    /// Number of undirected edges `E`.
    pub fn num_edges(&self) -> usize {
        self.edge_first.len()
    }

    /// Euler characteristic `V − E + F` (2 for a sphere, 0 for a torus).
    pub fn euler_characteristic(&self) -> i64 {
        self.num_vertices() as i64 - self.num_edges() as i64 + self.num_faces() as i64
    }

    /// All vertices.
    pub fn vertices(&self) -> &[Vertex] {
        &self.vertices
    }

    /// Vertex `v`, `None` when there is no such vertex.
    pub fn vertex(&self, v: usize) -> Option<&Vertex> {
        self.vertices.get(v)
    }

    /// Mutable access to the vertex data (positions, normals, shape tensors, extra fields); the
    /// connectivity cannot change. Degenerate faces created this way are not re-checked.
    pub fn vertices_mut(&mut self) -> &mut [Vertex] {
        &mut self.vertices
    }

    /// All faces as vertex triples.
    pub fn faces(&self) -> &[[usize; 3]] {
        &self.faces
    }

    /// The vertices of face `f`, in its orientation.
    pub fn face(&self, f: usize) -> Result<[usize; 3], MeshError> {
        self.faces.get(f).copied().ok_or(MeshError::NoSuchFace {
            face: f,
            count: self.faces.len(),
        })
    }

    /// The name of face `f`, if its source named it.
    pub fn face_name(&self, f: usize) -> Option<&str> {
        self.face_names.get(f).and_then(|n| n.as_deref())
    }

    /// Vertex data of the three corners of face `f`.
    pub fn face_data(&self, f: usize) -> Result<[&VertexData; 3], MeshError> {
        let [a, b, c] = self.face(f)?;
        Ok([
            &self.vertices[a].data,
            &self.vertices[b].data,
            &self.vertices[c].data,
        ])
    }

    /// The data of corner `c` of face `f` as the fit reads it: the vertex's position with the
    /// normal and shape tensor of its sector ([`crate::sectors`]), or of the vertex when the
    /// mesh has no sectors. `None` for a missing face or corner.
    pub fn corner_data(&self, f: usize, c: usize) -> Option<VertexData> {
        let v = *self.faces.get(f)?.get(c)?;
        let data = self.vertices[v].data;
        match &self.sectors {
            None => Some(data),
            Some(s) => {
                let slot = s.slot(f, c)?;
                Some(VertexData::new(data.p, *s.normal(slot)?, *s.shape(slot)?))
            }
        }
    }

    /// Whether the shape tensor of corner `c` of face `f` is known (see [`Mesh::corner_data`]).
    pub fn corner_curvature_known(&self, f: usize, c: usize) -> bool {
        let Some(&v) = self.faces.get(f).and_then(|face| face.get(c)) else {
            return false;
        };
        match &self.sectors {
            None => self.vertices[v].curvature_known,
            Some(s) => s.slot(f, c).is_some_and(|slot| s.curvature_known(slot)),
        }
    }

    /// The sectors and their data, when the mesh has creases.
    pub fn sectors(&self) -> Option<&Sectors> {
        self.sectors.as_deref()
    }

    /// The sectors, to set their data.
    pub fn sectors_mut(&mut self) -> Option<&mut Sectors> {
        self.sectors.as_deref_mut()
    }

    /// Attaches sectors made for this mesh ([`Sectors::new`]), or removes them (`None`).
    pub fn set_sectors(&mut self, sectors: Option<Sectors>) -> Result<(), SectorError> {
        if let Some(s) = &sectors {
            s.check(self)?;
        }
        self.sectors = sectors.map(Box::new);
        Ok(())
    }

    /// True when edge `e` is a crease the data is split at ([`Sectors::is_crease`]); false
    /// without sectors.
    pub fn is_crease(&self, e: usize) -> bool {
        self.sectors.as_ref().is_some_and(|s| s.is_crease(e))
    }

    /// The unit normal of face `f`; `None` for a missing face or one of zero (or non-finite)
    /// area.
    pub fn face_unit_normal(&self, f: usize) -> Option<Vector3<f64>> {
        let n = self.face_area_normal(f).ok()?;
        let len = n.norm();
        (len > 0.0 && len.is_finite()).then(|| n / len)
    }

    /// The geometric normal of face `f`: `(p1 − p0) × (p2 − p0)`, twice the area in length.
    pub fn face_area_normal(&self, f: usize) -> Result<Vector3<f64>, MeshError> {
        let [a, b, c] = self.face_data(f)?;
        Ok((b.p - a.p).cross(&(c.p - a.p)))
    }

    fn check_local(&self, f: usize, l: usize) -> Result<usize, MeshError> {
        self.face(f)?;
        if l > 2 {
            return Err(MeshError::NoSuchLocalEdge(l));
        }
        Ok(3 * f + l)
    }

    /// The face across local edge `l` of face `f` and the local index of the same edge in that
    /// face; `None` on a boundary edge.
    pub fn neighbour(&self, f: usize, l: usize) -> Result<Option<(usize, usize)>, MeshError> {
        let h = self.check_local(f, l)?;
        Ok(self.twin_of(h).map(|t| (t / 3, t % 3)))
    }

    /// The stable undirected index of local edge `l` of face `f`.
    pub fn edge_index(&self, f: usize, l: usize) -> Result<usize, MeshError> {
        let h = self.check_local(f, l)?;
        Ok(self.edge_of[h] as usize)
    }

    /// Undirected edge `e`: its vertices in the direction of its first face, and its one or two
    /// (face, local edge) pairs, read from its first half-edge and that half-edge's twin.
    ///
    /// # Panics
    /// When `e` is not below [`Mesh::num_edges`] (as indexing a slice of the edges would).
    pub fn edge(&self, e: usize) -> Edge {
        let h = self.edge_first[e] as usize;
        let (f, l) = (h / 3, h % 3);
        Edge {
            vertices: [self.faces[f][l], self.faces[f][(l + 1) % 3]],
            first: (f, l),
            second: self.twin[h].get().map(|t| (t / 3, t % 3)),
        }
    }

    /// All undirected edges, in index order ([`Mesh::edge`] of each).
    pub fn edges(&self) -> impl ExactSizeIterator<Item = Edge> + DoubleEndedIterator + Clone + '_ {
        (0..self.num_edges()).map(|e| self.edge(e))
    }

    /// [`Mesh::edges`] as a parallel iterator.
    pub fn par_edges(&self) -> impl IndexedParallelIterator<Item = Edge> + '_ {
        (0..self.num_edges()).into_par_iter().map(|e| self.edge(e))
    }

    /// The undirected edge between vertices `a` and `b`, if there is one.
    pub fn find_edge(&self, a: usize, b: usize) -> Option<usize> {
        let h = self.outgoing.get(a)?.get()?;
        // Every edge at `a` is the edge of an outgoing or an incoming half-edge of a face in
        // the fan around `a`.
        self.faces_around_vertex_from(a, h)
            .into_iter()
            .find_map(|f| {
                (0..3).find_map(|l| {
                    let (x, y) = (self.faces[f][l], self.faces[f][(l + 1) % 3]);
                    ((x == a && y == b) || (x == b && y == a))
                        .then_some(self.edge_of[3 * f + l] as usize)
                })
            })
    }

    /// Indices of the boundary edges (used by one face), in index order; empty for a closed mesh.
    pub fn boundary_edges(&self) -> Vec<usize> {
        (0..self.num_edges())
            .filter(|&e| self.twin[self.edge_first[e] as usize] == NONE32)
            .collect()
    }

    /// True when every edge has two faces.
    pub fn is_closed(&self) -> bool {
        self.twin.iter().all(|&t| t != NONE32)
    }

    /// The undirected edge of half-edge `h` (which must exist).
    pub(crate) fn edge_of_half_edge(&self, h: usize) -> usize {
        self.edge_of[h] as usize
    }

    /// Number of half-edges (three a face).
    pub(crate) fn num_half_edges(&self) -> usize {
        self.twin.len()
    }

    /// The twin of half-edge `h`, `None` on the boundary.
    pub(crate) fn twin_of(&self, h: usize) -> Option<usize> {
        self.twin.get(h)?.get()
    }

    fn next(h: usize) -> usize {
        3 * (h / 3) + (h % 3 + 1) % 3
    }

    fn prev(h: usize) -> usize {
        3 * (h / 3) + (h % 3 + 2) % 3
    }

    /// [`walk_fan`] on this mesh's twins.
    fn walk_fan(&self, start: usize, visit: impl FnMut(usize)) {
        walk_fan(&self.twin, start, visit);
    }

    fn faces_around_vertex_from(&self, v: usize, start: usize) -> Vec<usize> {
        let mut out = Vec::new();
        self.walk_fan(start, |h| out.push(h / 3));
        debug_assert!(out.iter().all(|&f| self.faces[f].contains(&v)));
        out
    }

    /// The faces around vertex `v`, counter-clockwise (seen from the side of the normals) as one
    /// fan; at a boundary vertex the fan starts at a boundary edge. Empty for an isolated or
    /// missing vertex.
    pub fn faces_around_vertex(&self, v: usize) -> Vec<usize> {
        match self.outgoing.get(v).and_then(|h| h.get()) {
            Some(h) => self.faces_around_vertex_from(v, h),
            None => Vec::new(),
        }
    }

    /// The vertices adjacent to `v` in the same counter-clockwise order as
    /// [`Mesh::faces_around_vertex`] (the one-ring; at a boundary vertex one more vertex than
    /// faces).
    pub fn vertex_ring(&self, v: usize) -> Vec<usize> {
        let fan = self.faces_around_vertex(v);
        let mut out = Vec::with_capacity(fan.len() + 1);
        for (i, &f) in fan.iter().enumerate() {
            let face = self.faces[f];
            let Some(c) = face.iter().position(|&x| x == v) else {
                continue;
            };
            // In face (v, a, b) counter-clockwise the ring runs a, then b.
            if i == 0 {
                out.push(face[(c + 1) % 3]);
            }
            let b = face[(c + 2) % 3];
            if i + 1 < fan.len() || self.twin_of(3 * f + (c + 2) % 3).is_none() {
                out.push(b);
            }
        }
        out
    }

    /// Walks across the mesh like the testbed's path command: from `start_face`, each step names
    /// a local edge (0, 1, 2) of the current face to cross. Returns every face visited, the start
    /// first (`steps.len() + 1` faces). Crossing a boundary edge is an error naming the step.
    pub fn walk(&self, start_face: usize, steps: &[usize]) -> Result<Vec<usize>, MeshError> {
        self.face(start_face)?;
        let mut out = Vec::with_capacity(steps.len() + 1);
        out.push(start_face);
        let mut f = start_face;
        for (step, &l) in steps.iter().enumerate() {
            match self.neighbour(f, l)? {
                Some((g, _)) => {
                    f = g;
                    out.push(g);
                }
                None => {
                    return Err(MeshError::WalkOffBoundary {
                        step,
                        face: f,
                        local_edge: l,
                    })
                }
            }
        }
        Ok(out)
    }

    /// The diagonal of the vertices' bounding box ([`bounding_size`]), the scale for relative
    /// tolerances (0 for an empty mesh).
    pub fn size(&self) -> f64 {
        bounding_size(self.vertices.iter().map(|v| &v.data.p))
    }
}

/// The diagonal of the bounding box of some points (0 for none): the workbench's one bounding
/// box, `meshio::BoundingBox`, re-exported here where the mesh's users look for it.
pub use meshio::bounds::bounding_size;

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> Vertex {
        Vertex::without_curvature(Point3::new(x, y, z), Vector3::z())
    }

    /// A unit square split into two triangles, plus a third triangle on its right.
    fn strip() -> Mesh {
        let verts = vec![
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(1.0, 1.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(2.0, 0.5, 0.0),
        ];
        Mesh::new(verts, vec![[0, 1, 2], [0, 2, 3], [1, 4, 2]]).unwrap()
    }

    #[test]
    fn counts_and_adjacency_of_a_strip() {
        let m = strip();
        assert_eq!((m.num_vertices(), m.num_edges(), m.num_faces()), (5, 7, 3));
        assert_eq!(m.euler_characteristic(), 1);
        // Local edge 2 of face 0 is 2→0, shared with face 1's local edge 0 (0→2).
        assert_eq!(m.neighbour(0, 2).unwrap(), Some((1, 0)));
        assert_eq!(m.neighbour(0, 1).unwrap(), Some((2, 2)));
        assert_eq!(m.neighbour(0, 0).unwrap(), None);
        assert_eq!(m.edge_index(0, 2).unwrap(), m.edge_index(1, 0).unwrap());
        assert_eq!(m.boundary_edges().len(), 5);
        assert!(!m.is_closed());
        // Vertex 2 is touched by all three faces: fan counter-clockwise 2, 0, 1.
        assert_eq!(m.faces_around_vertex(2), vec![1, 0, 2]);
        assert_eq!(m.vertex_ring(2), vec![3, 0, 1, 4]);
        assert_eq!(m.find_edge(3, 2), Some(m.edge_index(1, 1).unwrap()));
        assert_eq!(m.find_edge(3, 4), None);
        assert_eq!(m.walk(1, &[0, 1]).unwrap(), vec![1, 0, 2]);
        assert_eq!(
            m.walk(1, &[0, 0]),
            Err(MeshError::WalkOffBoundary {
                step: 1,
                face: 0,
                local_edge: 0
            })
        );
        assert_eq!(m.neighbour(0, 3), Err(MeshError::NoSuchLocalEdge(3)));
    }

    #[test]
    fn a_mesh_beyond_u32_half_edges_is_refused_and_the_largest_fits() {
        assert_eq!(
            check_size(MAX_FACES + 1),
            Err(MeshError::TooLarge {
                faces: MAX_FACES + 1
            })
        );
        assert_eq!(check_size(MAX_FACES), Ok(()));
        // The last half-edge of the largest mesh is a u32 other than the "none" value.
        let last = 3 * MAX_FACES - 1;
        assert!(u32::try_from(last).is_ok_and(|h| h != NONE32));
        assert_eq!(slot32(Some(last)).get(), Some(last));
        assert_eq!(slot32(None).get(), None);
    }

    #[test]
    fn a_mesh_beyond_u32_vertices_is_refused() {
        assert_eq!(
            check_vertex_count(MAX_VERTICES + 1),
            Err(MeshError::TooManyVertices {
                vertices: MAX_VERTICES + 1
            })
        );
        assert_eq!(check_vertex_count(MAX_VERTICES), Ok(()));
        assert!(u32::try_from(MAX_VERTICES - 1).is_ok());
    }

    #[test]
    fn a_vertex_keeps_its_name_and_fields_and_compares_by_them_alone() {
        let plain = v(1.0, 2.0, 3.0);
        assert_eq!((plain.name(), plain.extra().len()), (None, 0));
        let mut labelled = plain.clone().named("tip");
        labelled
            .extra_mut()
            .insert("temperature".into(), vec![21.5]);
        assert_eq!(labelled.name(), Some("tip"));
        assert_eq!(labelled.extra()["temperature"], vec![21.5]);
        assert_ne!(labelled, plain);
        // Emptied labels (a box with nothing in it) equal none at all.
        labelled.set_name(None);
        labelled.extra_mut().clear();
        assert_eq!(labelled, plain);
        assert_eq!(std::mem::size_of::<Vertex>(), 136);
    }

    #[test]
    fn edges_have_stable_indices_each_once() {
        let m = strip();
        let mut seen = std::collections::BTreeSet::new();
        for (e, edge) in m.edges().enumerate() {
            let [a, b] = edge.vertices;
            assert!(seen.insert((a.min(b), a.max(b))));
            assert_eq!(m.edge_index(edge.first.0, edge.first.1).unwrap(), e);
            if let Some((f, l)) = edge.second {
                assert_eq!(m.edge_index(f, l).unwrap(), e);
            }
        }
        // First appearance order: face 0's edges are 0, 1, 2.
        assert_eq!(
            (0..3)
                .map(|l| m.edge_index(0, l).unwrap())
                .collect::<Vec<_>>(),
            vec![0, 1, 2]
        );
    }

    #[test]
    fn invalid_meshes_are_named() {
        let quad = || {
            vec![
                v(0.0, 0.0, 0.0),
                v(1.0, 0.0, 0.0),
                v(1.0, 1.0, 0.0),
                v(0.0, 1.0, 0.0),
            ]
        };
        assert_eq!(
            Mesh::new(quad(), vec![[0, 1, 2], [0, 2, 7]]),
            Err(MeshError::MissingVertex {
                face: 1,
                corner: 2,
                vertex: 7,
                count: 4
            })
        );
        assert_eq!(
            Mesh::new(quad(), vec![[0, 1, 1]]),
            Err(MeshError::RepeatedVertex { face: 0, vertex: 1 })
        );
        let mut collinear = quad();
        collinear[2].data.p = Point3::new(2.0, 0.0, 0.0);
        assert_eq!(
            Mesh::new(collinear, vec![[0, 1, 3], [0, 1, 2]]),
            Err(MeshError::ZeroArea {
                face: 1,
                vertices: [0, 1, 2]
            })
        );
        assert_eq!(
            Mesh::new(quad(), vec![[0, 1, 2], [0, 3, 2]]),
            Err(MeshError::InconsistentOrientation {
                vertices: [2, 0],
                faces: [0, 1]
            })
        );
        let mut five = quad();
        five.push(v(0.5, -1.0, 0.3));
        five.push(v(0.5, -1.0, -0.3));
        assert_eq!(
            Mesh::new(five, vec![[0, 1, 2], [1, 0, 4], [0, 5, 1]]),
            Err(MeshError::NonManifoldEdge {
                vertices: [0, 1],
                faces: vec![0, 1, 2]
            })
        );
        let mut nan = quad();
        nan[3].data.n.x = f64::NAN;
        assert_eq!(
            Mesh::new(nan, vec![[0, 1, 2]]),
            Err(MeshError::NonFinite {
                vertex: 3,
                what: "normal"
            })
        );
        // Two triangles touching only at vertex 0: a bow tie.
        let bow = vec![
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(1.0, 1.0, 0.0),
            v(-1.0, 0.0, 0.0),
            v(-1.0, -1.0, 0.0),
        ];
        assert_eq!(
            Mesh::new(bow, vec![[0, 1, 2], [0, 3, 4]]),
            Err(MeshError::NonManifoldVertex { vertex: 0 })
        );
    }

    #[test]
    fn three_faces_on_one_edge_is_non_manifold() {
        let verts = vec![
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(0.5, 1.0, 0.0),
            v(0.5, -1.0, 0.0),
            v(0.5, 0.0, 1.0),
        ];
        let err = Mesh::new(verts.clone(), vec![[0, 1, 2], [1, 0, 3], [1, 0, 4]]).unwrap_err();
        // The third face on edge 0–1 is reported, whatever its direction.
        assert_eq!(
            err,
            MeshError::NonManifoldEdge {
                vertices: [0, 1],
                faces: vec![0, 1, 2]
            }
        );
        let err = Mesh::new(verts, vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]).unwrap_err();
        assert_eq!(
            err,
            MeshError::NonManifoldEdge {
                vertices: [0, 1],
                faces: vec![0, 1, 2]
            }
        );
        assert!(err.to_string().contains("more than two faces"));
    }
}

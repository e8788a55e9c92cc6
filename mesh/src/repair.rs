//! From a file's [`RawMesh`] to a validated [`Mesh`], repairing what real files get wrong by
//! stated rules, each counted in a [`RepairReport`]: one bad face never sinks a mesh.
//!
//! # The rules, in the order they are applied
//!
//! 0. **Coincident vertices** (exactly the same position, data that agree) are welded into one
//!    ([`crate::weld`]; [`RepairOptions::weld`], on by default): pieces a file stores apart
//!    (the teapot's patches, per-face exports) are joined at their seams.
//! 1. **Polygons** with more than three corners are split into a fan around their first corner
//!    (right for convex and star-shaped polygons, which is what exporters write), or refused
//!    ([`PolygonRule::Refuse`]) with the polygon's index.
//! 2. **Faces repeating a vertex** (`[a, a, b]`) are skipped: they have no interior to fit.
//! 3. **Duplicate faces** (the same three vertices, in either orientation) are skipped but the
//!    first.
//! 4. **Orientation** is made consistent within each component by a breadth-first walk across
//!    edges with exactly two faces (a face is reversed when it runs along a shared edge in the
//!    same direction as its neighbour). Each component then keeps the orientation of the
//!    majority of its faces as given, and is reversed as a whole when (a) the file gave normals
//!    and the faces' area normals disagree with them on the whole (`Σ_f A_f n̂_f · (n_a + n_b +
//!    n_c) < 0`: "winding against normals"), or (b) without normals, when it is closed and
//!    its signed volume is negative (inward-facing). A surface that cannot be oriented (a
//!    Möbius band) keeps one edge unshared: the walk's conflicting edge.
//! 5. **Non-manifold edges** (three or more faces): the first face running each way along the
//!    edge stay joined, the others are detached from that edge.
//! 6. **Non-manifold vertices** (the faces around a vertex forming several fans, joined only
//!    through the vertex, or separated by a detached edge of rule 4 or 5) are split: each fan
//!    beyond the first gets its own copy of the vertex, with the same data.
//! 7. **Unused vertices** (in no face) are dropped.
//! 8. **Zero-area faces** (collinear corners, [`crate::mesh::DEGENERATE_FACE_SINE`]) are kept, so
//!    the mesh has no hole there; they are listed, and the fit gives them a fallback patch.
//! 9. Should the mesh still not validate (a configuration the rules above do not foresee), the
//!    face named by the validation error is dropped and listed, at most
//!    [`MAX_DROPPED_FACES`] times.
//!
//! Several components and open boundaries are kept as they are (counted).
//!
//! Normals given by the file are normalized; if any is zero or not finite, all are discarded
//! (a note says so) and the caller estimates them. Shape tensors given by the file (the testbed
//! format) are kept and make the curvature known.
//!
//! **Crease edges** the file marks ([`RawMesh::crease_edges`], pairs of file vertices) are
//! carried to the mesh ([`Repaired::crease_edges`]): a mesh edge is a crease when the file
//! vertices its two ends come from ([`Repaired::vertex_source`]) are a file crease pair. So
//! every copy of a split vertex keeps the creases of the file vertex along the edges it still
//! has, and dropped vertices take none with them; a diagonal of a fanned polygon is a crease
//! only if the file marked that very pair (an OBJ reader never marks one: its creases are
//! sides of polygons). A file pair that is no edge of the mesh (its faces skipped or dropped,
//! or never a side of a face) is dropped; the report counts the pairs kept and dropped.

use std::borrow::Cow;

use meshio::RawMesh;
use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

use crate::edge_groups::{ends, key, EdgeGroups};
use crate::mesh::{
    first_vertex_with_several_fans, is_degenerate, outgoing_half_edges, ExtraFields, Mesh,
    MeshError, Vertex, NO_TWIN,
};

/// Rule 9's bound: a mesh that still fails validation after this many faces were dropped is
/// refused (each drop costs a full validation, so the bound keeps the work linear in practice).
pub const MAX_DROPPED_FACES: usize = 64;

/// What to do with faces of more than three corners.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PolygonRule {
    /// Split into a fan around the first corner (counted in the report).
    #[default]
    Fan,
    /// Refuse the mesh, naming the first polygon.
    Refuse,
}

/// Options of [`repair`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RepairOptions {
    /// Faces of more than three corners.
    pub polygons: PolygonRule,
    /// Vertices at the same position (rule 0).
    pub weld: crate::weld::WeldRule,
}

/// Why a raw mesh could not be made into a mesh at all.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RepairError {
    /// A polygon with more than three corners, with [`PolygonRule::Refuse`].
    #[error("face {face} has {corners} corners and polygons are refused (triangulate the mesh first, or allow fan triangulation)")]
    Polygon {
        /// The face (polygon) index in the file.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// No face is left to build a mesh from.
    #[error("nothing to fit: {0}")]
    Empty(String),
    /// The mesh did not validate even after dropping [`MAX_DROPPED_FACES`] faces.
    #[error("the mesh is still invalid after dropping {dropped} faces: {source}")]
    Invalid {
        /// Faces dropped before giving up.
        dropped: usize,
        /// The last validation error.
        source: MeshError,
    },
}

/// Why a component was reversed as a whole (rule 4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reversal {
    /// Its winding disagreed with the normals the file gave.
    AgainstNormals,
    /// It is closed and its signed volume was negative (the faces faced inward).
    Inward,
}

/// What [`repair`] did, rule by rule. Face indices are those of the file (polygon index), vertex
/// indices those of the file, unless a field says otherwise.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RepairReport {
    /// Vertices welded into another at the same position (rule 0).
    pub welded_vertices: usize,
    /// Groups of vertices at one position left apart because their file data disagree (rule 0).
    pub weld_kept_apart: usize,
    /// Polygons of more than three corners split into fans (rule 1).
    pub fanned_polygons: usize,
    /// Faces skipped for repeating a vertex (rule 2).
    pub repeated_vertex_faces: Vec<usize>,
    /// Faces skipped as duplicates of an earlier face (rule 3).
    pub duplicate_faces: Vec<usize>,
    /// Faces reversed to agree with their neighbours (rule 4, before whole-component reversals).
    pub reoriented_faces: usize,
    /// Components reversed as a whole, with the reason (component numbers in order of first face).
    pub reversed_components: Vec<(usize, Reversal)>,
    /// Edges (file vertex pairs) along which a face was detached (rules 4 and 5).
    pub detached_edges: Vec<[usize; 2]>,
    /// Vertices (file index) split into several copies, with the number of extra copies (rule 6).
    pub split_vertices: Vec<(usize, usize)>,
    /// Vertices in no face, dropped (rule 7).
    pub unused_vertices: usize,
    /// Faces of zero area kept (rule 8), as **mesh** face indices.
    pub degenerate_faces: Vec<usize>,
    /// Faces dropped because the mesh still did not validate (rule 9), file indices.
    pub dropped_faces: Vec<usize>,
    /// Connected components of the result.
    pub components: usize,
    /// Boundary edges of the result (0 for closed meshes).
    pub boundary_edges: usize,
    /// The file's crease edges (distinct pairs) that are edges of the result, on one or more
    /// mesh edges ([`Repaired::crease_edges`]).
    pub file_creases_kept: usize,
    /// The file's crease edges (distinct pairs) that are not edges of the result.
    pub file_creases_dropped: usize,
    /// Things a user should know that are not counted above (discarded normals, …).
    pub notes: Vec<String>,
}

impl RepairReport {
    /// True when the file's faces were used exactly as given (no face skipped, reversed,
    /// detached, split or dropped; polygons and unused vertices aside).
    pub fn is_clean(&self) -> bool {
        self.welded_vertices == 0
            && self.repeated_vertex_faces.is_empty()
            && self.duplicate_faces.is_empty()
            && self.reoriented_faces == 0
            && self.reversed_components.is_empty()
            && self.detached_edges.is_empty()
            && self.split_vertices.is_empty()
            && self.dropped_faces.is_empty()
    }

    /// One line per rule that did something, for a terminal.
    pub fn summary_lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        let list = |v: &[usize]| {
            let mut s: Vec<String> = v.iter().take(8).map(|x| x.to_string()).collect();
            if v.len() > 8 {
                s.push(format!("… ({} in all)", v.len()));
            }
            s.join(", ")
        };
        if self.welded_vertices > 0 {
            out.push(format!(
                "welded {} vertices into others at exactly the same position (the file's pieces joined at their seams)",
                self.welded_vertices
            ));
        }
        if self.weld_kept_apart > 0 {
            out.push(format!(
                "kept {} groups of vertices at one position apart: their normals or shape tensors in the file differ",
                self.weld_kept_apart
            ));
        }
        if self.fanned_polygons > 0 {
            out.push(format!(
                "{} polygons split into triangle fans",
                self.fanned_polygons
            ));
        }
        if !self.repeated_vertex_faces.is_empty() {
            out.push(format!(
                "skipped {} faces repeating a vertex: {}",
                self.repeated_vertex_faces.len(),
                list(&self.repeated_vertex_faces)
            ));
        }
        if !self.duplicate_faces.is_empty() {
            out.push(format!(
                "skipped {} duplicate faces: {}",
                self.duplicate_faces.len(),
                list(&self.duplicate_faces)
            ));
        }
        if self.reoriented_faces > 0 {
            out.push(format!(
                "reversed {} faces to agree with their neighbours",
                self.reoriented_faces
            ));
        }
        for (c, why) in &self.reversed_components {
            out.push(format!(
                "reversed component {c}: {}",
                match why {
                    Reversal::AgainstNormals => "its winding disagreed with the file's normals",
                    Reversal::Inward => "it is closed and faced inward",
                }
            ));
        }
        if !self.detached_edges.is_empty() {
            let e: Vec<String> = self
                .detached_edges
                .iter()
                .take(8)
                .map(|[a, b]| format!("{a}–{b}"))
                .collect();
            out.push(format!(
                "detached faces along {} non-manifold or non-orientable edges: {}{}",
                self.detached_edges.len(),
                e.join(", "),
                if self.detached_edges.len() > 8 {
                    ", …"
                } else {
                    ""
                }
            ));
        }
        if !self.split_vertices.is_empty() {
            let v: Vec<usize> = self.split_vertices.iter().map(|(v, _)| *v).collect();
            out.push(format!(
                "split {} non-manifold vertices: {}",
                v.len(),
                list(&v)
            ));
        }
        if self.unused_vertices > 0 {
            out.push(format!("dropped {} unused vertices", self.unused_vertices));
        }
        if !self.degenerate_faces.is_empty() {
            out.push(format!(
                "{} zero-area faces kept (fitted by the fallback): mesh faces {}",
                self.degenerate_faces.len(),
                list(&self.degenerate_faces)
            ));
        }
        if !self.dropped_faces.is_empty() {
            out.push(format!(
                "dropped {} faces that still did not validate: {}",
                self.dropped_faces.len(),
                list(&self.dropped_faces)
            ));
        }
        if self.file_creases_kept + self.file_creases_dropped > 0 {
            out.push(format!(
                "{} of the file's {} crease edges kept, {} dropped (not edges of the mesh)",
                self.file_creases_kept,
                self.file_creases_kept + self.file_creases_dropped,
                self.file_creases_dropped
            ));
        }
        if self.components > 1 || self.boundary_edges > 0 {
            out.push(format!(
                "{} components, {} boundary edges",
                self.components, self.boundary_edges
            ));
        }
        out.extend(self.notes.iter().cloned());
        out
    }
}

/// A repaired mesh with the maps back to the file.
#[derive(Clone, Debug)]
pub struct Repaired {
    /// The mesh. Its vertices carry the file's normals (unit) when [`Repaired::normals_given`],
    /// zero vectors otherwise, and the file's shape tensors when it had them.
    pub mesh: Mesh,
    /// True when every vertex's normal came from the file.
    pub normals_given: bool,
    /// For each mesh face, the file's face (polygon) it came from.
    pub face_source: Vec<usize>,
    /// For each mesh vertex, the file's vertex it came from (copies of a split vertex repeat it).
    pub vertex_source: Vec<usize>,
    /// The mesh edges the file marks as creases, in **mesh** vertex indices (module docs):
    /// each pair smaller index first, the list sorted; empty when the file marks none.
    pub crease_edges: Vec<[usize; 2]>,
    /// What was done.
    pub report: RepairReport,
}

/// Union–find for components and fans (the crate's one, [`crate::disjoint`]).
type Dsu = crate::disjoint::DisjointSets;

/// Rule 3 on faces without a repeated vertex: the faces (indices, possibly repeated) with the
/// same three vertices as an earlier face.
///
/// Found in the edge groups rather than by sorting the faces: two faces with the same three
/// vertices are together in the group of each of their edges with the same third vertex, and
/// two faces in one edge's group with the same third vertex have the same three vertices. So
/// within every group, each face whose third vertex an earlier (lower) face of the group has
/// too is a duplicate, and these are exactly all but the first face of every set of faces with
/// the same vertices, which is what the sort kept.
fn duplicate_faces(faces: &[[usize; 3]], groups: &EdgeGroups) -> Vec<usize> {
    let third = |h: usize| faces[h / 3][(h % 3 + 2) % 3];
    groups
        .par_iter()
        .flat_map_iter(|g| -> Vec<usize> {
            match *g {
                [_] => Vec::new(),
                [h0, h1] => {
                    if third(h0) == third(h1) {
                        vec![h1 / 3]
                    } else {
                        Vec::new()
                    }
                }
                _ => {
                    let mut by_third: Vec<(usize, usize)> =
                        g.iter().map(|&h| (third(h), h / 3)).collect();
                    by_third.sort_unstable();
                    by_third
                        .windows(2)
                        .filter(|w| w[0].0 == w[1].0)
                        .map(|w| w[1].1)
                        .collect()
                }
            }
        })
        .collect()
}

/// The faces across the edges of face `f` that have exactly two faces (`mate`, [`NO_TWIN`]
/// elsewhere), each with whether it runs that edge the same way as `f`: in the order of the
/// edges' keys (the order of the edge groups, which the orientation walk visited them in).
fn neighbours<'a>(
    faces: &'a [[usize; 3]],
    mate: &'a [usize],
    f: usize,
) -> impl Iterator<Item = (usize, bool)> + 'a {
    let t = faces[f];
    let mut ls = [0, 1, 2];
    ls.sort_unstable_by_key(|&l| key(faces, 3 * f + l));
    ls.into_iter().filter_map(move |l| {
        let m = mate[3 * f + l];
        (m != NO_TWIN).then(|| (m / 3, t[l] == faces[m / 3][m % 3]))
    })
}

/// The components of the faces joined across their mates (`mate[h]`, [`NO_TWIN`] where none),
/// numbered in the order of their lowest face, and how many there are: what the orientation
/// walk finds, since it starts each component at its lowest face not yet reached and crosses
/// exactly the mates. The union–find keeps the smaller root, so a root is its set's lowest face,
/// met before the set's other faces in face order.
fn components_of_mates(n_faces: usize, mate: &[usize]) -> (Vec<usize>, usize) {
    let mut dsu = Dsu::new(n_faces);
    for (h, &m) in mate.iter().enumerate() {
        if m != NO_TWIN && h < m {
            dsu.union(h / 3, m / 3);
        }
    }
    let mut component = vec![0usize; n_faces];
    let mut n = 0;
    for f in 0..n_faces {
        let root = dsu.find(f);
        component[f] = if root == f {
            n += 1;
            n - 1
        } else {
            component[root]
        };
    }
    (component, n)
}

fn flip(t: &mut [usize; 3]) {
    t.swap(1, 2);
}

/// Builds a mesh from a file's raw mesh by the rules of the module docs.
///
/// The work is that of applying the rules one after the other, done with fewer passes: the
/// half-edges are grouped by edge once ([`EdgeGroups`]) for rules 3 to 6, the joins that
/// rules 4 to 6 establish are handed to the mesh as its twins ([`Mesh::from_twins`]) instead
/// of being found and checked again, and what does not depend on the faces' orientation or on
/// which vertices get split (the vertex data, rule 8's zero-area faces) is computed on another
/// thread meanwhile. Each shortcut states why it gives the same result; whenever one does not
/// apply (an edge with three faces, a non-orientable component, a face cut loose) the rules run
/// as written.
pub fn repair(raw: &RawMesh, options: &RepairOptions) -> Result<Repaired, RepairError> {
    let mut report = RepairReport::default();
    let nv = raw.positions.len();

    // Rules 1–3: triangles, without repeated vertices or duplicates.
    let (mut faces, mut source) = triangles(raw, options, &mut report)?;
    // Rule 0, applied to the triangles: corners renumbered to the first vertex at their
    // position; a triangle that then repeats a vertex is skipped as rule 2 says.
    let welded = crate::weld::weld_map(raw, options.weld);
    report.welded_vertices = welded.welded;
    report.weld_kept_apart = welded.kept_apart;
    if !welded.map.is_empty() {
        let map = &welded.map;
        let mut repeats = vec![false; faces.len()];
        for (t, r) in faces.iter_mut().zip(repeats.iter_mut()) {
            *t = t.map(|v| map[v]);
            *r = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
        }
        let removed = remove_faces(&mut faces, &mut source, &repeats);
        report.repeated_vertex_faces.extend(removed);
        report.repeated_vertex_faces.sort_unstable();
        report.repeated_vertex_faces.dedup();
    }
    let mut edge_groups = EdgeGroups::new(&faces);
    let dup = duplicate_faces(&faces, &edge_groups);
    if !dup.is_empty() {
        let mut is_dup = vec![false; faces.len()];
        for f in dup {
            is_dup[f] = true;
        }
        report.duplicate_faces = remove_faces(&mut faces, &mut source, &is_dup);
        report.duplicate_faces.dedup();
        edge_groups = EdgeGroups::new(&faces);
    }
    if faces.is_empty() {
        return Err(RepairError::Empty(format!(
            "{} faces in the file, none with three distinct vertices{}",
            raw.polygons.len(),
            if report.welded_vertices > 0 {
                format!(
                    " once the {} vertices at the same position as another were welded into it (repair rule 0)",
                    report.welded_vertices
                )
            } else {
                String::new()
            }
        )));
    }
    // (Its notes are the only notes, so reading the normals before rule 4 keeps their order.)
    let given_normals = file_normals(raw, &mut report);

    // Rules 4–6 on this thread; meanwhile, on another, the data of every file vertex and the
    // zero-area faces (rule 8), which the orientation, the splits and the renumbering do not
    // change (a split vertex's copies have its data; reversing a face permutes its edges and
    // negates its area normal, exactly, so the test of `Mesh::is_degenerate_face` gives the
    // same answer).
    let (joined, (file_vertices, degenerate)) = rayon::join(
        || {
            let oriented = orient(
                &faces,
                edge_groups,
                raw,
                given_normals.as_deref(),
                &mut report,
            );
            join_faces(&faces, oriented, nv, &mut report)
        },
        || {
            let vertices: Vec<Vertex> = (0..nv)
                .into_par_iter()
                .map(|s| file_vertex(raw, given_normals.as_deref(), s))
                .collect();
            let degenerate: Vec<usize> = (0..faces.len())
                .into_par_iter()
                .filter(|&f| is_degenerate(faces[f].map(|v| raw.positions[v])))
                .collect();
            (vertices, degenerate)
        },
    );
    let Joined {
        tris,
        vertex_source,
        twin,
        components,
    } = joined;
    let mut tris: Vec<[usize; 3]> = match tris {
        Cow::Owned(tris) => tris,
        // Unchanged: the faces themselves (no copy).
        Cow::Borrowed(_) => faces,
    };

    // Rule 7: drop unused vertices, renumber.
    let mut used = vec![false; vertex_source.len()];
    for t in &tris {
        for &v in t {
            used[v] = true;
        }
    }
    let mut renumber = vec![usize::MAX; vertex_source.len()];
    let mut kept_source = Vec::with_capacity(vertex_source.len());
    for (v, &u) in used.iter().enumerate() {
        if u {
            renumber[v] = kept_source.len();
            kept_source.push(vertex_source[v]);
        }
    }
    report.unused_vertices = (0..nv).filter(|&v| !used[v]).count();
    if kept_source.len() < vertex_source.len() {
        // (Otherwise `renumber` is the identity.)
        tris.par_iter_mut()
            .for_each(|t| *t = t.map(|v| renumber[v]));
    }
    drop((used, renumber));
    let vertex_source = kept_source;
    // The mesh's vertices: the file's, or copies of them where some were dropped or split
    // (built again should rule 9 need them a second time after taking them whole).
    let mut file_vertices = Some(file_vertices);
    let mut vertices_of = |vertex_source: &[usize]| -> Vec<Vertex> {
        match file_vertices.take() {
            Some(all)
                if vertex_source.len() == all.len()
                    && vertex_source.iter().enumerate().all(|(v, &s)| v == s) =>
            {
                all
            }
            Some(all) => {
                let copies = vertex_source.par_iter().map(|&s| all[s].clone()).collect();
                file_vertices = Some(all);
                copies
            }
            None => vertex_source
                .par_iter()
                .map(|&s| file_vertex(raw, given_normals.as_deref(), s))
                .collect(),
        }
    };

    // Rule 9: validate; drop what still fails, boundedly (the vertices are copied again for a
    // retry: a clean mesh is built once).
    let mut face_source = source;
    let (mesh, degenerate, components) = if let Some(twin) = twin {
        // The last round joined every edge with two faces and cut nothing: the validation
        // would find these twins and nothing to drop (see `Mesh::from_twins`), so rule 9 has
        // nothing to do but check the vertex data, as the validation does first. No face was
        // dropped, so the zero-area faces found above keep their numbers.
        match Mesh::from_twins(vertices_of(&vertex_source), tris, twin) {
            Ok(m) => (m, Some(degenerate), components),
            Err(e) => {
                return Err(RepairError::Invalid {
                    dropped: 0,
                    source: e,
                })
            }
        }
    } else {
        let mesh = {
            loop {
                match Mesh::new_allowing_degenerate(vertices_of(&vertex_source), tris.clone()) {
                    Ok(m) => break m,
                    Err(e) => {
                        let culprit = match &e {
                            MeshError::NonManifoldEdge { faces, .. } => faces.last().copied(),
                            MeshError::InconsistentOrientation { faces, .. } => Some(faces[1]),
                            MeshError::NonManifoldVertex { vertex } => {
                                tris.iter().rposition(|t| t.contains(vertex))
                            }
                            MeshError::RepeatedVertex { face, .. }
                            | MeshError::ZeroArea { face, .. }
                            | MeshError::MissingVertex { face, .. } => Some(*face),
                            _ => None,
                        };
                        match culprit {
                            Some(f)
                                if report.dropped_faces.len() < MAX_DROPPED_FACES
                                    && f < tris.len() =>
                            {
                                report.dropped_faces.push(face_source[f]);
                                tris.remove(f);
                                face_source.remove(f);
                                if tris.is_empty() {
                                    return Err(RepairError::Empty(
                                        "every face had to be dropped".into(),
                                    ));
                                }
                            }
                            _ => {
                                return Err(RepairError::Invalid {
                                    dropped: report.dropped_faces.len(),
                                    source: e,
                                })
                            }
                        }
                        // Vertices left unused by a drop stay: an isolated vertex is harmless to a
                        // mesh, and the numbering stays that of `vertex_source`.
                    }
                }
            }
        };
        (mesh, None, None)
    };
    let mut mesh = mesh;
    if raw.has_face_names() {
        let n: Vec<String> = face_source
            .iter()
            .map(|&s| raw.face_name(s).map(|n| n.into_owned()).unwrap_or_default())
            .collect();
        mesh = mesh.with_face_names(n);
    }
    mesh.extra = raw.mesh_fields.clone();
    report.degenerate_faces = degenerate.unwrap_or_else(|| {
        (0..mesh.num_faces())
            .into_par_iter()
            .filter(|&f| mesh.is_degenerate_face(f))
            .collect()
    });
    report.components = components.unwrap_or_else(|| count_components(&mesh));
    report.boundary_edges = mesh.par_edges().filter(|e| e.is_boundary()).count();
    let crease_edges = mesh_creases(raw, &mesh, &vertex_source, &welded.map, &mut report);
    Ok(Repaired {
        normals_given: given_normals.is_some(),
        mesh,
        face_source,
        vertex_source,
        crease_edges,
        report,
    })
}

/// Removes the triangles `remove` marks from `faces` and their file faces from `source`
/// (kept in step, order kept); returns the removed ones' file faces, in order.
fn remove_faces(
    faces: &mut Vec<[usize; 3]>,
    source: &mut Vec<usize>,
    remove: &[bool],
) -> Vec<usize> {
    let removed = source
        .iter()
        .zip(remove)
        .filter(|(_, &r)| r)
        .map(|(&s, _)| s)
        .collect();
    let mut k = 0;
    faces.retain(|_| {
        k += 1;
        !remove[k - 1]
    });
    let mut k = 0;
    source.retain(|_| {
        k += 1;
        !remove[k - 1]
    });
    removed
}

/// The file's crease pairs on the mesh (module docs): every mesh edge whose ends come from a
/// file crease pair, sorted pairs, sorted; counts the distinct file pairs kept and dropped.
/// The file's list is taken as it is (a hand-built [`RawMesh`] may have it unsorted, reversed
/// or with repeats); a pair naming no vertex, or one vertex twice, matches no edge.
fn mesh_creases(
    raw: &RawMesh,
    mesh: &Mesh,
    vertex_source: &[usize],
    weld: &[usize],
    report: &mut RepairReport,
) -> Vec<[usize; 2]> {
    if raw.crease_edges.is_empty() {
        return Vec::new();
    }
    // A welded vertex's creases are its group's first vertex's (rule 0).
    let welded = |v: usize| weld.get(v).copied().unwrap_or(v);
    let mut file: Vec<[usize; 2]> = raw
        .crease_edges
        .iter()
        .map(|&[a, b]| {
            let (a, b) = (welded(a), welded(b));
            [a.min(b), a.max(b)]
        })
        .collect();
    file.sort_unstable();
    file.dedup();
    let mut kept = vec![false; file.len()];
    let mut out: Vec<[usize; 2]> = Vec::new();
    for e in mesh.edges() {
        let [a, b] = e.vertices;
        let (sa, sb) = (vertex_source[a], vertex_source[b]);
        if let Ok(k) = file.binary_search(&[sa.min(sb), sa.max(sb)]) {
            kept[k] = true;
            out.push([a.min(b), a.max(b)]);
        }
    }
    out.sort_unstable();
    // (A validated mesh has one edge per vertex pair; this keeps the list's promise whatever.)
    out.dedup();
    report.file_creases_kept = kept.iter().filter(|&&k| k).count();
    report.file_creases_dropped = file.len() - report.file_creases_kept;
    out
}

/// Rules 1 and 2: the file's polygons as triangles (fans), without those repeating a vertex,
/// with the polygon each came from.
fn triangles(
    raw: &RawMesh,
    options: &RepairOptions,
    report: &mut RepairReport,
) -> Result<(Vec<[usize; 3]>, Vec<usize>), RepairError> {
    let nv = raw.positions.len();
    // The common case first, in parallel: every polygon a triangle of three distinct existing
    // vertices, kept as it is (what the loop below does with such polygons).
    let n = raw.polygons.len();
    let triangle = |f: usize| match *raw.polygons.get(f) {
        [a, b, c] if a != b && b != c && a != c && a.max(b).max(c) < nv => Some([a, b, c]),
        _ => None,
    };
    if raw.polygons.all_triangles() && (0..n).into_par_iter().all(|f| triangle(f).is_some()) {
        let faces = (0..n)
            .into_par_iter()
            .map(|f| triangle(f).unwrap_or_default())
            .collect();
        return Ok((faces, (0..n).collect()));
    }
    let mut faces: Vec<[usize; 3]> = Vec::with_capacity(raw.polygons.corner_count() / 3 + 1);
    let mut source: Vec<usize> = Vec::with_capacity(faces.capacity());
    for (pi, poly) in raw.polygons.iter().enumerate() {
        if poly.len() < 3 || poly.iter().any(|&v| v >= nv) {
            // Readers guarantee neither happens; a hand-built RawMesh might.
            report.repeated_vertex_faces.push(pi);
            continue;
        }
        if poly.len() > 3 {
            if options.polygons == PolygonRule::Refuse {
                return Err(RepairError::Polygon {
                    face: pi,
                    corners: poly.len(),
                });
            }
            report.fanned_polygons += 1;
        }
        let mut repeated = false;
        for k in 1..poly.len() - 1 {
            let t = [poly[0], poly[k], poly[k + 1]];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                repeated = true;
                continue;
            }
            faces.push(t);
            source.push(pi);
        }
        if repeated {
            report.repeated_vertex_faces.push(pi);
        }
    }
    Ok((faces, source))
}

/// The file's normals, normalized, when it gave a usable one for every vertex (a note says why
/// they were discarded otherwise).
fn file_normals(raw: &RawMesh, report: &mut RepairReport) -> Option<Vec<Vector3<f64>>> {
    let nv = raw.positions.len();
    match &raw.normals {
        Some(ns) if ns.len() == nv => {
            let unit: Vec<Vector3<f64>> = ns
                .iter()
                .map(|n| {
                    let len = n.norm();
                    if len > 0.0 && len.is_finite() {
                        n / len
                    } else {
                        Vector3::zeros()
                    }
                })
                .collect();
            let bad = unit.iter().filter(|n| n.norm_squared() == 0.0).count();
            if bad > 0 {
                report.notes.push(format!(
                    "{bad} of the file's normals are zero or not finite: all normals discarded (to be estimated)"
                ));
                None
            } else {
                Some(unit)
            }
        }
        Some(_) => {
            report
                .notes
                .push("the file's normals do not match its vertices: discarded".into());
            None
        }
        None => None,
    }
}

/// The mesh vertex of file vertex `s`: its position, its normal (unit, or zero when the file's
/// were not used), its shape tensor (symmetrized) when the file gave them, name and properties.
fn file_vertex(raw: &RawMesh, given_normals: Option<&[Vector3<f64>]>, s: usize) -> Vertex {
    let nv = raw.positions.len();
    let p = raw.positions[s];
    let n = given_normals
        .as_ref()
        .map_or_else(Vector3::zeros, |ns| ns[s]);
    let mut v = match &raw.shapes {
        Some(shapes) if shapes.len() == nv => Vertex::new(crate::VertexData::new(p, n, shapes[s])),
        _ => Vertex::without_curvature(p, n),
    };
    if v.curvature_known {
        v.data.shape = symmetric(&v.data.shape);
    }
    if let Some(name) = raw.vertex_name(s) {
        v.set_name(Some(name.into_owned()));
    }
    if !raw.properties.is_empty() {
        let mut extra = ExtraFields::new();
        for (k, vals) in &raw.properties {
            if let Some(x) = vals.get(s) {
                extra.insert(k.clone(), vec![*x]);
            }
        }
        *v.extra_mut() = extra;
    }
    v
}

/// The faces after rule 4, and what the walk found.
struct Oriented<'a> {
    /// The faces, each reversed or not (borrowed while none is).
    tris: Cow<'a, [[usize; 3]]>,
    /// Each half-edge's mate across an edge with exactly two faces, [`NO_TWIN`] elsewhere (as
    /// given, before reversals).
    mate: Vec<usize>,
    /// Whether some edge has three or more faces.
    several: bool,
    /// Pairs of faces `(f, h)`, `f < h`, the walk could not make agree.
    conflicts: Vec<(usize, usize)>,
    /// Number of components of the walk.
    components: usize,
}

/// Rule 4: consistent orientation by a walk across two-face edges, then whole components by
/// the majority, the normals or the volume.
fn orient<'a>(
    faces: &'a [[usize; 3]],
    edge_groups: EdgeGroups,
    raw: &RawMesh,
    given_normals: Option<&[Vector3<f64>]>,
    report: &mut RepairReport,
) -> Oriented<'a> {
    // Each half-edge's mate across an edge with exactly two faces (the walk's neighbour).
    let mut mate = vec![NO_TWIN; 3 * faces.len()];
    let mut several = false;
    for g in edge_groups.iter() {
        match *g {
            [h0, h1] if h0 / 3 != h1 / 3 => {
                mate[h0] = h1;
                mate[h1] = h0;
            }
            [_, _, _, ..] => several = true,
            _ => {}
        }
    }
    // Whether the faces already agree across every two-face edge: then the walk reverses no
    // face and meets no conflict, whatever order it visits the faces in, so only its
    // components are needed, and a union–find over the mates gives the same ones, numbered the
    // same way ([`components_of_mates`]).
    let consistent = mate
        .par_iter()
        .enumerate()
        .all(|(h, &m)| m == NO_TWIN || ends(faces, h).0 != ends(faces, m).0);
    let (flipped, component, conflicts, n_components) = if consistent {
        let (component, n_components) = components_of_mates(faces.len(), &mate);
        (None, component, Vec::new(), n_components)
    } else {
        let mut flipped: Vec<Option<bool>> = vec![None; faces.len()];
        let mut component = vec![0usize; faces.len()];
        let mut conflicts: Vec<(usize, usize)> = Vec::new();
        let mut n_components = 0;
        // Breadth first: a queue in a vector (each face enters once), read from `head`.
        let mut queue: Vec<usize> = Vec::with_capacity(faces.len());
        for seed in 0..faces.len() {
            if flipped[seed].is_some() {
                continue;
            }
            flipped[seed] = Some(false);
            component[seed] = n_components;
            queue.clear();
            queue.push(seed);
            let mut head = 0;
            while let Some(&f) = queue.get(head) {
                head += 1;
                let ff = flipped[f].unwrap_or(false);
                for (h, same) in neighbours(faces, &mate, f) {
                    // Consistent when, after flips, the two run the edge in opposite directions.
                    let want = ff ^ same;
                    match flipped[h] {
                        None => {
                            flipped[h] = Some(want);
                            component[h] = n_components;
                            queue.push(h);
                        }
                        Some(got) if got != want && f < h => conflicts.push((f, h)),
                        Some(_) => {}
                    }
                }
            }
            n_components += 1;
        }
        drop(queue);
        (Some(flipped), component, conflicts, n_components)
    };
    // Majority orientation per component, then the whole-component rules.
    // The faces as given until one is reversed.
    let mut oriented: Cow<'_, [[usize; 3]]> = Cow::Borrowed(faces);
    if let Some(flipped) = flipped {
        let mut votes = vec![(0usize, 0usize); n_components];
        for (f, fl) in flipped.iter().enumerate() {
            if fl.unwrap_or(false) {
                votes[component[f]].1 += 1;
            } else {
                votes[component[f]].0 += 1;
            }
        }
        let majority_flip: Vec<bool> = votes.iter().map(|(keep, fl)| fl > keep).collect();
        for (f, t) in oriented.to_mut().iter_mut().enumerate() {
            if flipped[f].unwrap_or(false) ^ majority_flip[component[f]] {
                flip(t);
                report.reoriented_faces += 1;
            }
        }
    }
    {
        let mut agreement = vec![0.0f64; n_components];
        let mut volume = vec![0.0f64; n_components];
        let mut closed = vec![true; n_components];
        for (f, t) in oriented.iter().enumerate() {
            let [a, b, c] = t.map(|i| raw.positions[i]);
            let an = (b - a).cross(&(c - a));
            if let Some(ns) = given_normals {
                agreement[component[f]] += an.dot(&(ns[t[0]] + ns[t[1]] + ns[t[2]]));
            }
            volume[component[f]] += a.coords.dot(&b.coords.cross(&c.coords));
        }
        for g in edge_groups.iter() {
            if g.len() != 2 {
                closed[component[g[0] / 3]] = false;
            }
        }
        let mut reverse = vec![false; n_components];
        for c in 0..n_components {
            if given_normals.is_some() {
                if agreement[c] < 0.0 {
                    reverse[c] = true;
                    report
                        .reversed_components
                        .push((c, Reversal::AgainstNormals));
                }
            } else if closed[c] && volume[c] < 0.0 {
                reverse[c] = true;
                report.reversed_components.push((c, Reversal::Inward));
            }
        }
        if reverse.contains(&true) {
            for (f, t) in oriented.to_mut().iter_mut().enumerate() {
                if reverse[component[f]] {
                    flip(t);
                }
            }
        }
    }
    Oriented {
        tris: oriented,
        mate,
        several,
        conflicts,
        components: n_components,
    }
}

/// The faces after rules 4–6, with what the mesh can take over.
struct Joined<'a> {
    /// The faces, on the vertices of `vertex_source` (borrowed while unchanged).
    tris: Cow<'a, [[usize; 3]]>,
    /// The file vertex of each vertex (copies of split vertices at the end).
    vertex_source: Vec<usize>,
    /// The joins, when the last round cut nothing ([`join_and_split`]).
    twin: Option<Vec<usize>>,
    /// The number of components of the mesh, when known already.
    components: Option<usize>,
}

/// Rules 4–6 after the orientation: which faces are joined across which edges, then fans
/// around each vertex; repeated while an edge still has more than two faces (a detached face
/// whose fans did not separate from the others is then cut loose along that edge with its own
/// vertex copies). `faces` are the faces before the orientation.
fn join_faces<'a>(
    faces: &'a [[usize; 3]],
    oriented: Oriented<'a>,
    nv: usize,
    report: &mut RepairReport,
) -> Joined<'a> {
    let Oriented {
        mut tris,
        mate,
        several,
        conflicts,
        components,
    } = oriented;
    let mut vertex_source: Vec<usize> = (0..nv).collect();
    let mut extra_copies: std::collections::BTreeMap<usize, usize> = Default::default();
    let mut detached: std::collections::BTreeSet<[usize; 2]> = Default::default();
    let (twin, components) = if !several && conflicts.is_empty() {
        // What the first round of `join_and_split` finds, without grouping the half-edges
        // again: every edge has one face, or two that the walk made run opposite ways (a pair
        // that it could not is a conflict), so every such pair is joined and none is cut. Their
        // half-edges are the mates' with the local edges of reversed faces renumbered (`[a, b,
        // c]` → `[a, c, b]` turns local edge `l` into `2 − l`); splitting the fans then leaves
        // nothing to cut, so there is no second round. The mesh's faces are then joined across
        // exactly the edges the walk crossed, so its components are the walk's.
        let mut twin = mate;
        if let Cow::Owned(turned_tris) = &tris {
            let turned = |f: usize| turned_tris[f] != faces[f];
            twin.par_chunks_mut(3).enumerate().for_each(|(f, hs)| {
                for h in hs.iter_mut().filter(|h| **h != NO_TWIN) {
                    if turned(*h / 3) {
                        *h = 3 * (*h / 3) + 2 - *h % 3;
                    }
                }
                if turned(f) {
                    hs.swap(0, 2);
                }
            });
        }
        if several_fans(&tris, &twin, vertex_source.len()) {
            split_fans(tris.to_mut(), &twin, &mut vertex_source, &mut extra_copies);
        }
        (Some(twin), Some(components))
    } else {
        drop(mate);
        let conflict_set: std::collections::HashSet<(usize, usize)> =
            conflicts.iter().copied().collect();
        let mut twin = None;
        for _round in 0..MAX_SPLIT_ROUNDS {
            let (forced, joined) = join_and_split(
                tris.to_mut(),
                &mut vertex_source,
                &conflict_set,
                &mut detached,
                &mut extra_copies,
            );
            twin = joined;
            if !forced {
                break;
            }
        }
        (twin, None)
    };
    report.detached_edges = detached.into_iter().collect();
    report.split_vertices = extra_copies.into_iter().collect();
    Joined {
        tris,
        vertex_source,
        twin,
        components,
    }
}

/// Rounds of [`join_and_split`] before the remaining defects are left to rule 9: each round
/// cuts every face that is still a third face on an edge loose, so two rounds suffice for
/// everything the tests and the corpus show; the bound keeps the work linear.
const MAX_SPLIT_ROUNDS: usize = 4;

/// One round of rules 4–6 on `tris` (vertex indices into `vertex_source`, which maps them to
/// the file's vertices): join the first face running each way along every edge, split every
/// vertex into one copy per fan of joined faces ([`split_fans`]), then cut loose (own copies of
/// the edge's two vertices) every face that still shares an edge with two others. Returns
/// whether a face was cut loose (another round is needed), and the joins as a twin array
/// ([`NO_TWIN`] where none) when nothing had to be cut: then the faces after the split are
/// exactly what the mesh validation accepts with these twins (see [`Mesh::from_twins`]): a
/// joined pair shares its fans at both ends, so keeps its edge, and every other edge keeps its
/// one face.
fn join_and_split(
    tris: &mut [[usize; 3]],
    vertex_source: &mut Vec<usize>,
    conflict_set: &std::collections::HashSet<(usize, usize)>,
    detached: &mut std::collections::BTreeSet<[usize; 2]>,
    extra_copies: &mut std::collections::BTreeMap<usize, usize>,
) -> (bool, Option<Vec<usize>>) {
    let groups = EdgeGroups::new(tris);
    let mut twin = vec![NO_TWIN; 3 * tris.len()];
    // Whether some edge has more than two faces or two running the same way: only then can a
    // face still be a third one after the split (splitting vertices only separates groups).
    let mut any_cut = false;
    for members in groups.iter() {
        let edge = key(tris, members[0]);
        let mut fwd: Option<usize> = None;
        let mut bwd: Option<usize> = None;
        for &h in members {
            let slot = if ends(tris, h).0 == edge.0 {
                &mut fwd
            } else {
                &mut bwd
            };
            if slot.is_none() {
                *slot = Some(h);
            }
        }
        let mut cut = members.len() > 2;
        match (fwd, bwd) {
            (Some(a), Some(b)) => {
                let (f, h) = (a / 3, b / 3);
                if !conflict_set.is_empty() && conflict_set.contains(&(f.min(h), f.max(h))) {
                    cut = true;
                } else {
                    twin[a] = b;
                    twin[b] = a;
                }
            }
            // Two faces the same way: the walk's conflict of a non-orientable surface.
            _ => cut |= members.len() == 2,
        }
        if cut {
            detached.insert([vertex_source[edge.0], vertex_source[edge.1]]);
        }
        any_cut |= cut;
    }
    drop(groups);
    if several_fans(tris, &twin, vertex_source.len()) {
        split_fans(tris, &twin, vertex_source, extra_copies);
    }
    // Faces still a third (or same-direction second) face on an edge: cut loose.
    if !any_cut {
        return (false, Some(twin));
    }
    let groups = EdgeGroups::new(tris);
    let mut forced = false;
    for members in groups.iter() {
        let same_direction =
            members.len() == 2 && ends(tris, members[0]).0 == ends(tris, members[1]).0;
        if members.len() <= 2 && !same_direction {
            continue;
        }
        // Keep the joined pair (or the first face), cut the others loose.
        let keep: Vec<usize> = members
            .iter()
            .copied()
            .filter(|&h| twin[h] != NO_TWIN)
            .collect();
        let keep = if keep.len() == 2 {
            keep
        } else {
            vec![members[0]]
        };
        for &h in members {
            if keep.contains(&h) {
                continue;
            }
            let (f, l) = (h / 3, h % 3);
            let (a, b) = (tris[f][l], tris[f][(l + 1) % 3]);
            let (ca, cb) = (
                copy_vertex(a, vertex_source, extra_copies),
                copy_vertex(b, vertex_source, extra_copies),
            );
            tris[f][l] = ca;
            tris[f][(l + 1) % 3] = cb;
            forced = true;
        }
    }
    (forced, None)
}

/// A new copy of vertex `v` (same file vertex), counted in `extra_copies`.
fn copy_vertex(
    v: usize,
    vertex_source: &mut Vec<usize>,
    extra_copies: &mut std::collections::BTreeMap<usize, usize>,
) -> usize {
    let s = vertex_source[v];
    vertex_source.push(s);
    *extra_copies.entry(s).or_insert(0) += 1;
    vertex_source.len() - 1
}

/// Whether some vertex's corners form several fans across the joins `twin`, so that
/// [`split_fans`] has something to do. Faster than its union–find, and in parallel: the fan
/// walk around each vertex across the twins meets all its corners exactly when they are one
/// class of that union–find, because a corner is joined to at most two others, across its
/// face's two edges at that vertex, which is what the walk follows.
fn several_fans(tris: &[[usize; 3]], twin: &[usize], vertex_count: usize) -> bool {
    let outgoing = outgoing_half_edges(tris, twin, vertex_count);
    first_vertex_with_several_fans(tris, twin, &outgoing).is_some()
}

/// Rule 6: every vertex whose corners form several fans across the joins `twin` keeps the
/// first fan (in face order) and gives each other fan a copy of its own, numbered in the order
/// the fans first appear. The fans are the classes of a union–find over corners (the two
/// corners at each end of a joined edge are one); only these classes matter, not the order of
/// the unions. (Nothing changes when [`several_fans`] is false.)
fn split_fans(
    tris: &mut [[usize; 3]],
    twin: &[usize],
    vertex_source: &mut Vec<usize>,
    extra_copies: &mut std::collections::BTreeMap<usize, usize>,
) {
    // Edge l of f runs a → b and its twin, edge m of h, runs b → a: vertex a is corner l of f
    // and corner m + 1 of h, vertex b is corner l + 1 of f and corner m of h.
    let mut dsu = Dsu::new(3 * tris.len());
    for (x, &y) in twin.iter().enumerate() {
        if y != NO_TWIN && x < y {
            let (f, l, h, m) = (x / 3, x % 3, y / 3, y % 3);
            dsu.union(3 * f + l, 3 * h + (m + 1) % 3);
            dsu.union(3 * f + (l + 1) % 3, 3 * h + m);
        }
    }
    // The first fan of each vertex keeps it; others get copies.
    let mut fan_vertex: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    let mut first_fan: Vec<Option<usize>> = vec![None; vertex_source.len()];
    for (f, tri) in tris.iter_mut().enumerate() {
        for (c, slot) in tri.iter_mut().enumerate() {
            let v = *slot;
            let fan = dsu.find(3 * f + c);
            match first_fan[v] {
                None => first_fan[v] = Some(fan),
                Some(first) if first == fan => {}
                Some(_) => {
                    *slot = match fan_vertex.get(&fan) {
                        Some(&c) => c,
                        None => {
                            let c = copy_vertex(v, vertex_source, extra_copies);
                            fan_vertex.insert(fan, c);
                            c
                        }
                    };
                }
            }
        }
    }
}

fn symmetric(s: &Matrix3<f64>) -> Matrix3<f64> {
    (s + s.transpose()) * 0.5
}

/// Connected components of a mesh's faces (across shared edges).
pub fn count_components(mesh: &Mesh) -> usize {
    let mut dsu = Dsu::new(mesh.num_faces());
    for e in mesh.edges() {
        if let Some((g, _)) = e.second {
            dsu.union(e.first.0, g);
        }
    }
    (0..mesh.num_faces()).filter(|&f| dsu.find(f) == f).count()
}

/// A mesh back to a file's raw form, for writers: positions, unit normals (when `with_normals`),
/// shape tensors (when every vertex's curvature is known), vertex and face names, extra fields
/// with one value per vertex as properties, the mesh's own fields.
pub fn mesh_to_raw(mesh: &Mesh, with_normals: bool) -> RawMesh {
    mesh_to_raw_with(mesh, with_normals, true)
}

/// [`mesh_to_raw`], the shape tensors only when `with_shapes` (a writer that does not store
/// them need not hold a copy: 72 bytes a vertex).
pub fn mesh_to_raw_with(mesh: &Mesh, with_normals: bool, with_shapes: bool) -> RawMesh {
    let vs = mesh.vertices();
    let mut raw = RawMesh::from_triangles(vs.iter().map(|v| v.data.p).collect(), mesh.faces());
    if with_normals {
        raw.normals = Some(vs.iter().map(|v| v.data.n).collect());
    }
    if with_shapes && !vs.is_empty() && vs.iter().all(|v| v.curvature_known) {
        raw.shapes = Some(vs.iter().map(|v| v.data.shape).collect());
    }
    if vs.iter().any(|v| v.name().is_some()) {
        raw.vertex_names = Some(
            vs.iter()
                .enumerate()
                .map(|(i, v)| v.name().map_or_else(|| format!("v{i}"), str::to_string))
                .collect(),
        );
    }
    if (0..mesh.num_faces()).any(|f| mesh.face_name(f).is_some()) {
        raw.face_names = Some(
            (0..mesh.num_faces())
                .map(|f| {
                    mesh.face_name(f)
                        .map_or_else(|| format!("f{f}"), str::to_string)
                })
                .collect(),
        );
    }
    // A property is written only when every vertex has it with exactly one value.
    if let Some(first) = vs.first() {
        for key in first.extra().keys() {
            let values: Option<Vec<f64>> = vs
                .iter()
                .map(|v| match v.extra().get(key).map(Vec::as_slice) {
                    Some([x]) => Some(*x),
                    _ => None,
                })
                .collect();
            if let Some(values) = values {
                raw.properties.insert(key.clone(), values);
            }
        }
    }
    raw.mesh_fields = mesh.extra.clone();
    raw
}

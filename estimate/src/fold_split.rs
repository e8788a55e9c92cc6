//! Sectors split where the data folds: a sector whose face normals lie in no open hemisphere
//! (no normal faces all its faces, [`crate::facing`]) is cut into sectors that each have one.
//!
//! # Why
//!
//! Every split-domain patch interpolates its corners' normals, so a face at 90° or more from a
//! corner's normal folds there, and the G1 schemes give it the C0 fallback
//! (`surface::shirman_sequin::SchemeError::NormalAgainstFace`). Where the faces round a vertex
//! lie in no open hemisphere (a decimated scan's fin seen from both sides, a claw folded over
//! itself, a non-manifold spot the repair opened), no normal faces them all: the data has a
//! crease there that the crease rule did not see (scans get no geometric creases by default,
//! docs/conventions.md). Turning the vertex into a crease vertex at its sharpest edges gives
//! each side its own normal, as a crease does: the surface is C0 along those edges (as the data
//! is) and G1 on each side, where the fallback left C0 faces kinked on every side.
//!
//! # The cut
//!
//! The sector's faces round its vertex, in order, are joined through its smooth edges there
//! (a path, or a cycle round an interior vertex). Those edges are taken by decreasing dihedral
//! angle (between the two faces' normals) and made creases one after the other, until every
//! piece the cut edges leave has a normal facing all its faces (its face normals in an open
//! hemisphere: a positive [`crate::facing::widest_margin`]) that is also perpendicular to the
//! chords of the cut edges bounding it (so that the crease tangent there, the line both
//! sides' tangent planes share, can run along the edge). A piece of one face always has one
//! (its own normal), so the cut ends. The cut edges become crease edges of the mesh
//! ([`mesh::Sectors::new`]); at their other end, where nothing else cuts, they are darts (one
//! sector there, unchanged). Where the cut edges of two folds meet at a vertex they split it
//! too; its pieces are checked the same way, and cut further where one has no such normal,
//! for at most [`MAX_ROUNDS`] rounds.
//!
//! Every new sector starts from its old sector's normal and shape tensor. A piece at the cut
//! vertex then gets the normal nearest it that faces its faces and is perpendicular to the
//! chords of its cut edges ([`crate::facing::facing_normal_across`]): both sectors' tangent
//! planes then hold the chord, and the crease tangent (their intersection,
//! `curves::crease_end`) runs along the edge, as on a CAD part's crease. Where no such normal
//! exists the facing rule ([`crate::facing::face_the_faces`], run again) turns it, as little as
//! it can, to face its faces only. Sectors without a fold are not touched, bit for bit.

use std::collections::HashSet;

use mesh::disjoint::DisjointSets;
use mesh::{Mesh, Sectors};
use nalgebra::Vector3;

use crate::facing::{facing_normal_across, project_shape};

/// What [`split_folds`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct FoldSplit {
    /// Sectors with no facing normal that the cuts split (by their own cuts, or by a
    /// neighbouring fold's cut edges that pass through them).
    pub sectors_cut: usize,
    /// Edges made creases by the cuts.
    pub edges_cut: usize,
}

/// The slot of corner `(f, c)` under `sectors` (its vertex without sectors).
fn slot_in(mesh: &Mesh, sectors: Option<&Sectors>, f: usize, c: usize) -> Option<usize> {
    match sectors {
        Some(s) => s.slot(f, c),
        None => mesh.faces().get(f).map(|face| face[c]),
    }
}

/// The vertex of slot `s` under `sectors`.
fn vertex_in(sectors: Option<&Sectors>, s: usize) -> Option<usize> {
    match sectors {
        Some(sec) => sec.slot_vertex(s),
        None => Some(s),
    }
}

/// The chord of edge `e` from its end `v`.
fn chord(mesh: &Mesh, e: usize, v: usize) -> Vector3<f64> {
    let ev = mesh.edge(e).vertices;
    let other = if ev[0] == v { ev[1] } else { ev[0] };
    mesh.vertices()[other].data.p - mesh.vertices()[v].data.p
}

/// Whether a piece with face normals `normals` and cut chords `lines` has a normal facing its
/// faces and perpendicular to the chords (a piece of zero-area faces only has nothing to face).
fn piece_fits(normals: &[Vector3<f64>], lines: &[Vector3<f64>]) -> bool {
    normals.is_empty() || facing_normal_across(&Vector3::z(), normals, lines).is_some()
}

/// The further edges to cut in slot `s` of `sectors` (module docs), given the edges `cut`
/// already (made creases, or to be): none when every piece the cut edges leave at its vertex
/// fits ([`piece_fits`]) already, or when its faces cannot be read.
fn cut_slot(mesh: &Mesh, sectors: Option<&Sectors>, s: usize, cut: &HashSet<usize>) -> Vec<usize> {
    let Some(v) = vertex_in(sectors, s) else {
        return Vec::new();
    };
    // The slot's faces round v, in the star's order, with their normals.
    let star: Vec<(usize, usize)> = mesh
        .faces_around_vertex(v)
        .into_iter()
        .filter_map(|g| Some((g, mesh.faces()[g].iter().position(|&x| x == v)?)))
        .filter(|&(g, gc)| slot_in(mesh, sectors, g, gc) == Some(s))
        .collect();
    let normals: Vec<Option<Vector3<f64>>> = star
        .iter()
        .map(|&(g, _)| mesh.face_unit_normal(g))
        .collect();
    let k = star.len();
    // Links between faces of the slot across an edge at v: (i, j, edge, dihedral cosine).
    let mut links: Vec<(usize, usize, usize, f64)> = Vec::new();
    for i in 0..k {
        let (g, gc) = star[i];
        let Ok(e) = mesh.edge_index(g, (gc + 2) % 3) else {
            continue;
        };
        for (j, &(h, hc)) in star.iter().enumerate() {
            if j != i && mesh.edge_index(h, hc).ok() == Some(e) {
                let cos = match (normals[i], normals[j]) {
                    (Some(a), Some(b)) => a.dot(&b),
                    _ => 1.0,
                };
                links.push((i, j, e, cos));
            }
        }
    }
    // Links already cut (darts at v so far) come first; the others sharpest first (least
    // cosine), ties by edge, so the cut does not depend on the order the star was walked in.
    links.sort_by(|a, b| {
        let (ca, cb) = (cut.contains(&a.2), cut.contains(&b.2));
        cb.cmp(&ca).then(a.3.total_cmp(&b.3)).then(a.2.cmp(&b.2))
    });
    let pre = links.iter().filter(|l| cut.contains(&l.2)).count();
    // Cut edges that bound the slot at v (between one of its faces and another sector's): the
    // piece holding that face must be perpendicular to their chords too.
    let bounding: Vec<Vec<Vector3<f64>>> = star
        .iter()
        .map(|&(g, gc)| {
            [gc, (gc + 2) % 3]
                .into_iter()
                .filter_map(|l| mesh.edge_index(g, l).ok())
                .filter(|e| cut.contains(e) && !links.iter().any(|link| link.2 == *e))
                .filter(|&e| mesh.edge(e).second.is_some())
                .map(|e| chord(mesh, e, v))
                .collect()
        })
        .collect();
    let fits = |removed: usize| -> bool {
        // Pieces: faces joined by the links not removed (the first `removed` are).
        let mut piece = DisjointSets::new(k);
        for &(i, j, _, _) in &links[removed..] {
            piece.union(i, j);
        }
        // Per piece: its face normals and the chords of the removed edges bounding it (an
        // edge whose two faces are still one piece is a dart: no crease at v).
        type Piece = (Vec<Vector3<f64>>, Vec<Vector3<f64>>);
        let mut groups: std::collections::BTreeMap<usize, Piece> = Default::default();
        for (i, normal) in normals.iter().enumerate() {
            let entry = groups.entry(piece.find(i)).or_default();
            entry.0.extend(*normal);
            entry.1.extend(bounding[i].iter().copied());
        }
        for &(i, j, e, _) in &links[..removed] {
            let (a, b) = (piece.find(i), piece.find(j));
            if a != b {
                for r in [a, b] {
                    if let Some(entry) = groups.get_mut(&r) {
                        entry.1.push(chord(mesh, e, v));
                    }
                }
            }
        }
        groups.values().all(|(ns, lines)| piece_fits(ns, lines))
    };
    let removed = (pre..=links.len())
        .find(|&removed| fits(removed))
        .unwrap_or(links.len());
    links[pre..removed].iter().map(|l| l.2).collect()
}

/// At most this many rounds of cuts at the vertices the previous round split (module docs):
/// each round cuts at least one more edge, and the cascade measured on the dragons and on
/// tori crumpled by noise of up to the edge length ends in at most 7 (the rounds after the
/// last cut only check).
pub const MAX_ROUNDS: usize = 16;

/// The slots at vertex `v` under `sectors`, each once.
fn slots_at(mesh: &Mesh, sectors: &Sectors, v: usize) -> Vec<usize> {
    let mut out: Vec<usize> = mesh
        .faces_around_vertex(v)
        .into_iter()
        .filter_map(|g| {
            let gc = mesh.faces()[g].iter().position(|&x| x == v)?;
            sectors.slot(g, gc)
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Cuts each slot of `slots` (sectors with no facing normal) at its sharpest edges until every
/// piece has a normal facing its faces and perpendicular to its cut chords, then cuts again at
/// every vertex those cuts split where a piece has none (module docs), and gives the mesh the
/// sectors of its creases and the cuts: each new sector with its old sector's data, each piece
/// at a split vertex with the normal nearest it that faces its faces across its cut chords.
/// The mesh is left as it was when nothing is cut or the sectors cannot be made.
pub fn split_folds(mesh: &mut Mesh, slots: &[usize]) -> FoldSplit {
    let mut cut: HashSet<usize> = HashSet::new();
    for &s in slots {
        cut.extend(cut_slot(mesh, mesh.sectors(), s, &cut));
    }
    if cut.is_empty() {
        return FoldSplit::default();
    }
    let original: Vec<bool> = match mesh.sectors() {
        Some(s) => s.creases().to_vec(),
        None => vec![false; mesh.num_edges()],
    };
    let before = original.iter().filter(|&&c| c).count();
    let slots_before = match mesh.sectors() {
        Some(sec) => sec.slots_per_vertex(mesh.num_vertices()),
        None => vec![1; mesh.num_vertices()],
    };
    let make = |cut: &HashSet<usize>| {
        let mut flags = original.clone();
        for &e in cut {
            if let Some(flag) = flags.get_mut(e) {
                *flag = true;
            }
        }
        Sectors::new(mesh, &flags).ok()
    };
    // The vertices a cut splits: its own, and an end of cut edges from two folds (two darts
    // make a crease line there).
    let split_vertices = |sectors: &Sectors, cut: &HashSet<usize>| {
        let after = sectors.slots_per_vertex(mesh.num_vertices());
        let mut vertices: Vec<usize> = cut.iter().flat_map(|&e| mesh.edge(e).vertices).collect();
        vertices.retain(|&v| after.get(v) > slots_before.get(v));
        vertices.sort_unstable();
        vertices.dedup();
        vertices
    };
    let Some(mut sectors) = make(&cut) else {
        return FoldSplit::default();
    };
    for _ in 0..MAX_ROUNDS {
        let mut more: Vec<usize> = Vec::new();
        for v in split_vertices(&sectors, &cut) {
            for s in slots_at(mesh, &sectors, v) {
                more.extend(cut_slot(mesh, Some(&sectors), s, &cut));
            }
        }
        if more.is_empty() {
            break;
        }
        cut.extend(more);
        let Some(next) = make(&cut) else {
            return FoldSplit::default();
        };
        sectors = next;
    }
    let vertices = split_vertices(&sectors, &cut);
    // Each new slot's data from the old slot of its first corner.
    let mut done = vec![false; sectors.num_slots()];
    for f in 0..mesh.num_faces() {
        for c in 0..3 {
            let (Some(new), Some(old)) = (sectors.slot(f, c), slot_in(mesh, mesh.sectors(), f, c))
            else {
                continue;
            };
            if done[new] {
                continue;
            }
            done[new] = true;
            let data = match mesh.sectors() {
                Some(sec) => sec
                    .normal(old)
                    .zip(sec.shape(old))
                    .map(|(n, sh)| (*n, *sh, sec.curvature_known(old))),
                None => mesh
                    .vertices()
                    .get(old)
                    .map(|v| (v.data.n, v.data.shape, v.curvature_known)),
            };
            if let Some((n, shape, known)) = data {
                sectors.set_slot(new, n, shape, known);
            }
        }
    }
    let edges_cut = sectors.num_creases().saturating_sub(before);
    // The sectors asked for that the cuts split (by their own cuts or a neighbour's).
    let sectors_cut = slots
        .iter()
        .filter(|&&s| {
            let Some(v) = vertex_in(mesh.sectors(), s) else {
                return false;
            };
            let mut new: Vec<usize> = mesh
                .faces_around_vertex(v)
                .into_iter()
                .filter_map(|g| {
                    let gc = mesh.faces()[g].iter().position(|&x| x == v)?;
                    (slot_in(mesh, mesh.sectors(), g, gc) == Some(s))
                        .then(|| sectors.slot(g, gc))
                        .flatten()
                })
                .collect();
            new.sort_unstable();
            new.dedup();
            new.len() > 1
        })
        .count();
    if mesh.set_sectors(Some(sectors)).is_err() {
        return FoldSplit::default();
    }
    // Each piece's normal at a split vertex: facing its faces and perpendicular to the chords
    // of its cut edges there, so the crease tangents run along them (else the facing rule's,
    // in its second pass).
    for v in vertices {
        let mut pieces: std::collections::BTreeMap<usize, (Vec<Vector3<f64>>, Vec<usize>)> =
            Default::default();
        for g in mesh.faces_around_vertex(v) {
            let Some(gc) = mesh.faces()[g].iter().position(|&x| x == v) else {
                continue;
            };
            let Some(slot) = slot_in(mesh, mesh.sectors(), g, gc) else {
                continue;
            };
            let mut edges = Vec::new();
            for l in [gc, (gc + 2) % 3] {
                let Ok(e) = mesh.edge_index(g, l) else {
                    continue;
                };
                // A cut edge that separates two sectors at v.
                let edge = mesh.edge(e);
                let other = match edge.second {
                    Some((h, _)) if edge.first.0 == g => Some(h),
                    Some(_) => Some(edge.first.0),
                    None => None,
                };
                let separates = other.is_some_and(|h| {
                    let hc = mesh.faces()[h].iter().position(|&x| x == v);
                    hc.and_then(|hc| slot_in(mesh, mesh.sectors(), h, hc)) != Some(slot)
                });
                if cut.contains(&e) && separates {
                    edges.push(e);
                }
            }
            let entry = pieces.entry(slot).or_default();
            if let Some(n) = mesh.face_unit_normal(g) {
                entry.0.push(n);
            }
            for e in edges {
                if !entry.1.contains(&e) {
                    entry.1.push(e);
                }
            }
        }
        for (slot, (faces, edges)) in pieces {
            let lines: Vec<Vector3<f64>> = edges.iter().map(|&e| chord(mesh, e, v)).collect();
            let Some(sec) = mesh.sectors_mut() else {
                continue;
            };
            let (Some(&n0), Some(&shape)) = (sec.normal(slot), sec.shape(slot)) else {
                continue;
            };
            let known = sec.curvature_known(slot);
            if let Some(n) = facing_normal_across(&n0, &faces, &lines) {
                sec.set_slot(slot, n, project_shape(&shape, &n), known);
            }
        }
    }
    FoldSplit {
        sectors_cut,
        edges_cut,
    }
}

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
//! hemisphere: a positive [`crate::facing::widest_margin`]). A piece of one face always has one,
//! so the cut ends. The cut edges become crease edges of the mesh ([`mesh::Sectors::new`]); at
//! their other end, where nothing else cuts, they are darts (one sector there, unchanged).
//!
//! Every new sector starts from its old sector's normal and shape tensor. A piece at the cut
//! vertex then gets the normal nearest it that faces its faces and is perpendicular to the
//! chords of its cut edges ([`crate::facing::facing_normal_across`]): both sectors' tangent
//! planes then hold the chord, and the crease tangent (their intersection,
//! `curves::crease_end`) runs along the edge, as on a CAD part's crease. Where no such normal
//! exists the facing rule ([`crate::facing::face_the_faces`], run again) turns it, as little as
//! it can, to face its faces only. Sectors without a fold are not touched, bit for bit.

use mesh::{Mesh, Sectors};
use nalgebra::Vector3;

use crate::facing::{facing_normal_across, project_shape, widest_margin};

/// What [`split_folds`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct FoldSplit {
    /// Sectors with no facing normal that were cut.
    pub sectors_cut: usize,
    /// Edges made creases by the cuts.
    pub edges_cut: usize,
}

/// The slot of corner `(f, c)`: its sector's, or its vertex where the mesh has no sectors.
fn slot_of(mesh: &Mesh, f: usize, c: usize) -> Option<usize> {
    match mesh.sectors() {
        Some(s) => s.slot(f, c),
        None => mesh.faces().get(f).map(|face| face[c]),
    }
}

/// The vertex of slot `s`.
fn vertex_of(mesh: &Mesh, s: usize) -> Option<usize> {
    match mesh.sectors() {
        Some(sec) => sec.slot_vertex(s),
        None => Some(s),
    }
}

/// The edges to cut in slot `s` (module docs), or none when its faces cannot be read.
fn cut_of(mesh: &Mesh, s: usize) -> Vec<usize> {
    let Some(v) = vertex_of(mesh, s) else {
        return Vec::new();
    };
    // The slot's faces round v, in the star's order, with their normals.
    let star: Vec<(usize, usize)> = mesh
        .faces_around_vertex(v)
        .into_iter()
        .filter_map(|g| Some((g, mesh.faces()[g].iter().position(|&x| x == v)?)))
        .filter(|&(g, gc)| slot_of(mesh, g, gc) == Some(s))
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
    // Sharpest first (least cosine); ties by edge, so the cut does not depend on the order
    // the star was walked in.
    links.sort_by(|a, b| a.3.total_cmp(&b.3).then(a.2.cmp(&b.2)));
    let p = mesh.vertices()[v].data.p;
    let chord = |e: usize| {
        let ev = mesh.edge(e).vertices;
        let other = if ev[0] == v { ev[1] } else { ev[0] };
        mesh.vertices()[other].data.p - p
    };
    let n0 = match mesh.sectors() {
        Some(sec) => sec.normal(s).copied(),
        None => mesh.vertices().get(v).map(|x| x.data.n),
    }
    .unwrap_or_else(Vector3::z);
    let feasible = |cut: usize| -> bool {
        // Pieces: faces joined by the links not cut (the first `cut` are).
        let mut piece: Vec<usize> = (0..k).collect();
        fn root(p: &mut [usize], mut x: usize) -> usize {
            while p[x] != x {
                p[x] = p[p[x]];
                x = p[x];
            }
            x
        }
        for &(i, j, _, _) in &links[cut..] {
            let (a, b) = (root(&mut piece, i), root(&mut piece, j));
            piece[a] = b;
        }
        // Per piece: its face normals and the chords of the cut edges bounding it.
        type Piece = (Vec<Vector3<f64>>, Vec<Vector3<f64>>);
        let mut groups: std::collections::BTreeMap<usize, Piece> = Default::default();
        for (i, normal) in normals.iter().enumerate() {
            let r = root(&mut piece, i);
            let entry = groups.entry(r).or_default();
            entry.0.extend(*normal);
        }
        for &(i, j, e, _) in &links[..cut] {
            for x in [i, j] {
                let r = root(&mut piece, x);
                if let Some(entry) = groups.get_mut(&r) {
                    entry.1.push(chord(e));
                }
            }
        }
        groups.values().all(|(ns, lines)| {
            ns.is_empty()
                || if lines.is_empty() {
                    widest_margin(ns).is_some()
                } else {
                    facing_normal_across(&n0, ns, lines).is_some()
                }
        })
    };
    (1..=links.len())
        .find(|&cut| feasible(cut))
        .map(|cut| links[..cut].iter().map(|l| l.2).collect())
        .unwrap_or_default()
}

/// Cuts each slot of `slots` (sectors with no facing normal) at its sharpest edges until every
/// piece has one (module docs), and gives the mesh the sectors of its creases and the cuts,
/// each new sector with its old sector's data. The mesh is left as it was when nothing is cut
/// or the sectors cannot be made.
pub fn split_folds(mesh: &mut Mesh, slots: &[usize]) -> FoldSplit {
    let mut cut: Vec<usize> = Vec::new();
    let mut cut_vertices: Vec<usize> = Vec::new();
    let mut sectors_cut = 0;
    for &s in slots {
        let edges = cut_of(mesh, s);
        if !edges.is_empty() {
            sectors_cut += 1;
            cut.extend(edges);
            cut_vertices.extend(vertex_of(mesh, s));
        }
    }
    if cut.is_empty() {
        return FoldSplit::default();
    }
    let mut flags: Vec<bool> = match mesh.sectors() {
        Some(s) => s.creases().to_vec(),
        None => vec![false; mesh.num_edges()],
    };
    let before = flags.iter().filter(|&&c| c).count();
    for &e in &cut {
        if let Some(flag) = flags.get_mut(e) {
            *flag = true;
        }
    }
    let Ok(mut sectors) = Sectors::new(mesh, &flags) else {
        return FoldSplit::default();
    };
    // The vertices the cuts split: the cut vertices, and an end of cut edges from two folds
    // (two darts make a crease line there).
    let slots_before = match mesh.sectors() {
        Some(sec) => sec.slots_per_vertex(mesh.num_vertices()),
        None => vec![1; mesh.num_vertices()],
    };
    let slots_after = sectors.slots_per_vertex(mesh.num_vertices());
    let mut vertices: Vec<usize> = cut_vertices;
    for &e in &cut {
        vertices.extend(mesh.edge(e).vertices);
    }
    vertices.retain(|&v| slots_after.get(v) > slots_before.get(v));
    vertices.sort_unstable();
    vertices.dedup();
    // Each new slot's data from the old slot of its first corner.
    let mut done = vec![false; sectors.num_slots()];
    for f in 0..mesh.num_faces() {
        for c in 0..3 {
            let (Some(new), Some(old)) = (sectors.slot(f, c), slot_of(mesh, f, c)) else {
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
    if mesh.set_sectors(Some(sectors)).is_err() {
        return FoldSplit::default();
    }
    // Each piece's normal at a split vertex: facing its faces and perpendicular to the chords
    // of its cut edges, so the crease tangents run along them (else the facing rule's, in its
    // second pass).
    let cut_set: std::collections::HashSet<usize> = cut.iter().copied().collect();
    for v in vertices {
        let mut pieces: std::collections::BTreeMap<usize, (Vec<Vector3<f64>>, Vec<usize>)> =
            Default::default();
        for g in mesh.faces_around_vertex(v) {
            let Some(gc) = mesh.faces()[g].iter().position(|&x| x == v) else {
                continue;
            };
            let Some(slot) = slot_of(mesh, g, gc) else {
                continue;
            };
            let entry = pieces.entry(slot).or_default();
            if let Some(n) = mesh.face_unit_normal(g) {
                entry.0.push(n);
            }
            for l in [gc, (gc + 2) % 3] {
                if let Ok(e) = mesh.edge_index(g, l) {
                    if cut_set.contains(&e) && !entry.1.contains(&e) {
                        entry.1.push(e);
                    }
                }
            }
        }
        let p = mesh.vertices()[v].data.p;
        for (slot, (faces, edges)) in pieces {
            let lines: Vec<Vector3<f64>> = edges
                .iter()
                .map(|&e| {
                    let ev = mesh.edge(e).vertices;
                    let other = if ev[0] == v { ev[1] } else { ev[0] };
                    mesh.vertices()[other].data.p - p
                })
                .collect();
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

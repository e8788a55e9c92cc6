//! The file's crease edges through `mesh::repair`: mapped to mesh vertices through vertex drops,
//! vertex splits and fans, and counted.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use mesh::repair::{repair, RepairOptions, Repaired};
use meshio::{Polygons, RawMesh};
use nalgebra::Point3;

fn p(x: f64, y: f64, z: f64) -> Point3<f64> {
    Point3::new(x, y, z)
}

/// Every mesh crease is a mesh edge whose ends come from a file crease pair, and the list is
/// sorted pairs, sorted, without repeats.
fn check_mapping(raw: &RawMesh, r: &Repaired) {
    let src = &r.vertex_source;
    for &[a, b] in &r.crease_edges {
        assert!(a < b, "{a} {b}");
        assert!(r.mesh.find_edge(a, b).is_some(), "{a}–{b} is no mesh edge");
        let (sa, sb) = (src[a], src[b]);
        let file = [sa.min(sb), sa.max(sb)];
        assert!(
            raw.crease_edges
                .iter()
                .any(|&[x, y]| [x.min(y), x.max(y)] == file),
            "{a}–{b} comes from {file:?}, no file crease"
        );
    }
    assert!(r.crease_edges.windows(2).all(|w| w[0] < w[1]));
}

#[test]
fn the_face_normal_cube_keeps_its_twelve_creases_and_no_fan_diagonal() {
    // The OBJ cube with one normal per face: 12 creases among the 18 edges of its 12 fanned
    // triangles; the 6 diagonals are not creases.
    let mut text = String::new();
    for i in 0..8 {
        text.push_str(&format!("v {} {} {}\n", i & 1, (i >> 1) & 1, (i >> 2) & 1));
    }
    text.push_str("vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n");
    let quads = [
        [1, 3, 4, 2],
        [5, 6, 8, 7],
        [1, 2, 6, 5],
        [3, 7, 8, 4],
        [1, 5, 7, 3],
        [2, 4, 8, 6],
    ];
    for (k, q) in quads.iter().enumerate() {
        let n = k + 1;
        text.push_str(&format!(
            "f {}//{n} {}//{n} {}//{n} {}//{n}\n",
            q[0], q[1], q[2], q[3]
        ));
    }
    let raw = meshio::format_by_name("obj")
        .expect("obj")
        .read(text.as_bytes())
        .expect("read");
    assert_eq!(raw.crease_edges.len(), 12);
    let r = repair(&raw, &RepairOptions::default()).expect("repair");
    assert_eq!(r.mesh.num_faces(), 12);
    assert_eq!(r.mesh.num_edges(), 18);
    // No vertex was dropped or split: the numbering is the file's.
    assert_eq!(r.vertex_source, (0..8).collect::<Vec<_>>());
    assert_eq!(r.crease_edges, raw.crease_edges);
    for [a, b] in &r.crease_edges {
        assert_eq!((a ^ b).count_ones(), 1, "{a}–{b} is a diagonal");
    }
    assert_eq!(
        (r.report.file_creases_kept, r.report.file_creases_dropped),
        (12, 0)
    );
    assert!(r.report.summary_lines().contains(
        &"12 of the file's 12 crease edges kept, 0 dropped (not edges of the mesh)".into()
    ));
    check_mapping(&raw, &r);
}

#[test]
fn creases_follow_a_split_vertex_and_skip_a_dropped_one() {
    // Vertex 0 is the pinch of two fans, A = (0 2 3), (0 3 4) and B = (0 5 6), (0 6 7), that
    // share nothing else; vertex 1 is in no face.
    let pos = vec![
        p(0., 0., 0.),
        p(5., 5., 5.),
        p(1., 0., 0.),
        p(1., 1., 0.),
        p(0., 1., 0.),
        p(-1., 0., 0.),
        p(-1., -1., 0.),
        p(0., -1., 0.),
    ];
    let mut raw = RawMesh::from_triangles(pos, &[[0, 2, 3], [0, 3, 4], [0, 5, 6], [0, 6, 7]]);
    // Creases inside each fan (0–3, 0–6, the last given reversed and twice), a boundary edge
    // (3–4), a pair that is no edge (2–5) and one naming no vertex (7–100).
    raw.crease_edges = vec![[0, 3], [6, 0], [0, 6], [3, 4], [2, 5], [7, 100]];
    let r = repair(&raw, &RepairOptions::default()).expect("repair");
    assert_eq!(r.report.split_vertices, vec![(0, 1)]);
    assert_eq!(r.report.unused_vertices, 1);
    // Vertex 1 dropped, the others renumbered down by one, fan B's copy of vertex 0 last.
    assert_eq!(r.vertex_source, vec![0, 2, 3, 4, 5, 6, 7, 0]);
    // File 0–3 → mesh 0–2 (fan A keeps vertex 0), 3–4 → 2–3, 0–6 → the copy 7 and 6 → 5: 5–7.
    assert_eq!(r.crease_edges, vec![[0, 2], [2, 3], [5, 7]]);
    // Five distinct file pairs: 0–3, 0–6, 3–4 kept; 2–5 and 7–100 dropped.
    assert_eq!(
        (r.report.file_creases_kept, r.report.file_creases_dropped),
        (3, 2)
    );
    // The copy is not joined to the other fan's vertices: no 0–5 crease (file 0–6 through the
    // kept vertex 0).
    assert!(!r.crease_edges.contains(&[0, 5]));
    check_mapping(&raw, &r);
}

#[test]
fn a_crease_on_a_detached_fin_edge_marks_both_copies() {
    // Two triangles on edge 0–1 and a third (the fin) on it too: the fin is detached with its
    // own copies of 0 and 1, so the file's crease 0–1 lies on two mesh edges.
    let pos = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(0.5, 1., 0.),
        p(0.5, -1., 0.),
        p(0.5, 0., 1.),
    ];
    let mut raw = RawMesh::from_triangles(pos, &[[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    raw.crease_edges = vec![[0, 1]];
    let r = repair(&raw, &RepairOptions::default()).expect("repair");
    assert_eq!(r.report.detached_edges, vec![[0, 1]]);
    assert_eq!(r.mesh.num_vertices(), 7);
    assert_eq!(r.vertex_source, vec![0, 1, 2, 3, 4, 0, 1]);
    assert_eq!(r.crease_edges, vec![[0, 1], [5, 6]]);
    assert_eq!(
        (r.report.file_creases_kept, r.report.file_creases_dropped),
        (1, 0)
    );
    check_mapping(&raw, &r);
}

#[test]
fn a_marked_fan_diagonal_is_kept_and_skipped_faces_drop_their_creases() {
    // A quad 0 1 2 3 fanned around 0: its diagonal 0–2 becomes a mesh edge, and a file that
    // marks that pair (a hand-built mesh; no reader does) keeps it. The face 1 4 4 repeats a
    // vertex and is skipped: its side 1–4 is no edge.
    let pos = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(1., 1., 0.),
        p(0., 1., 0.),
        p(2., 0., 0.),
    ];
    let mut polygons = Polygons::new();
    polygons.push(&[0, 1, 2, 3]);
    polygons.push(&[1, 4, 4]);
    let raw = RawMesh {
        positions: pos,
        polygons,
        crease_edges: vec![[0, 2], [1, 4]],
        ..RawMesh::default()
    };
    let r = repair(&raw, &RepairOptions::default()).expect("repair");
    assert_eq!(r.report.repeated_vertex_faces, vec![1]);
    assert_eq!(r.crease_edges, vec![[0, 2]]);
    assert_eq!(
        (r.report.file_creases_kept, r.report.file_creases_dropped),
        (1, 1)
    );
    check_mapping(&raw, &r);
}

#[test]
fn no_file_creases_no_mesh_creases_and_no_line() {
    let raw = RawMesh::from_triangles(
        vec![p(0., 0., 0.), p(1., 0., 0.), p(0., 1., 0.)],
        &[[0, 1, 2]],
    );
    let r = repair(&raw, &RepairOptions::default()).expect("repair");
    assert!(r.crease_edges.is_empty());
    assert_eq!(
        (r.report.file_creases_kept, r.report.file_creases_dropped),
        (0, 0)
    );
    assert!(!r
        .report
        .summary_lines()
        .iter()
        .any(|l| l.contains("crease")));
}

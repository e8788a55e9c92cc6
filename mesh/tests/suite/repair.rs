//! The repair rules of `mesh::repair`, one broken configuration each, plus a property test:
//! whatever faces are thrown at it (random triangles over a few vertices), the result is a valid
//! mesh or a named refusal, never a panic.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use mesh::repair::{repair, PolygonRule, RepairError, RepairOptions, Reversal};
use meshio::{Polygons, RawMesh};
use nalgebra::{Point3, Vector3};
use proptest::prelude::*;

fn p(x: f64, y: f64, z: f64) -> Point3<f64> {
    Point3::new(x, y, z)
}

/// The octahedron (outward, counter-clockwise seen from outside).
fn octa() -> RawMesh {
    let pos = vec![
        p(1., 0., 0.),
        p(0., 1., 0.),
        p(0., 0., 1.),
        p(-1., 0., 0.),
        p(0., -1., 0.),
        p(0., 0., -1.),
    ];
    let tris = [
        [0, 1, 2],
        [1, 3, 2],
        [3, 4, 2],
        [4, 0, 2],
        [1, 0, 5],
        [3, 1, 5],
        [4, 3, 5],
        [0, 4, 5],
    ];
    RawMesh::from_triangles(pos, &tris)
}

fn default() -> RepairOptions {
    RepairOptions::default()
}

#[test]
fn a_clean_mesh_is_kept_as_is() {
    let raw = octa();
    let r = repair(&raw, &default()).unwrap();
    assert!(r.report.is_clean(), "{:?}", r.report);
    assert_eq!(r.mesh.num_faces(), 8);
    assert_eq!(r.mesh.num_vertices(), 6);
    assert_eq!(r.report.components, 1);
    assert_eq!(r.report.boundary_edges, 0);
    assert_eq!(r.face_source, (0..8).collect::<Vec<_>>());
    assert!(!r.normals_given);
}

#[test]
fn an_inward_closed_mesh_is_reversed() {
    let mut raw = octa();
    let tris: Vec<[usize; 3]> = raw.polygons.iter().map(|t| [t[0], t[2], t[1]]).collect();
    raw.polygons = Polygons::from_triangles(&tris);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.reversed_components, vec![(0, Reversal::Inward)]);
    // Every face now has a positive outward orientation.
    for f in 0..8 {
        let n = r.mesh.face_area_normal(f).unwrap();
        let c = r.mesh.face_data(f).unwrap()[0].p;
        assert!(n.dot(&c.coords) > 0.0);
    }
}

#[test]
fn one_reversed_face_is_turned_back() {
    let mut raw = octa();
    let mut tris: Vec<[usize; 3]> = raw.polygons.iter().map(|t| [t[0], t[1], t[2]]).collect();
    tris[3] = [tris[3][0], tris[3][2], tris[3][1]];
    raw.polygons = Polygons::from_triangles(&tris);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.reoriented_faces, 1);
    assert!(r.report.reversed_components.is_empty());
    assert_eq!(r.mesh.faces()[3], [4, 0, 2]);
}

#[test]
fn winding_against_the_files_normals_is_reversed() {
    let mut raw = octa();
    let tris: Vec<[usize; 3]> = raw.polygons.iter().map(|t| [t[0], t[2], t[1]]).collect();
    raw.polygons = Polygons::from_triangles(&tris);
    // Inward normals *and* inward winding: consistent, so nothing is reversed.
    raw.normals = Some(raw.positions.iter().map(|q| -q.coords).collect());
    let r = repair(&raw, &default()).unwrap();
    assert!(r.report.reversed_components.is_empty());
    assert!(r.normals_given);
    // Outward normals with inward winding: the winding follows the normals.
    raw.normals = Some(raw.positions.iter().map(|q| q.coords * 2.0).collect());
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(
        r.report.reversed_components,
        vec![(0, Reversal::AgainstNormals)]
    );
    let n0 = r.mesh.vertices()[0].data.n;
    assert!((n0.norm() - 1.0).abs() < 1e-15, "normals are normalized");
}

#[test]
fn zero_normals_are_discarded_with_a_note() {
    let mut raw = octa();
    let mut ns: Vec<Vector3<f64>> = raw.positions.iter().map(|q| q.coords).collect();
    ns[2] = Vector3::zeros();
    raw.normals = Some(ns);
    let r = repair(&raw, &default()).unwrap();
    assert!(!r.normals_given);
    assert_eq!(r.report.notes.len(), 1);
}

#[test]
fn polygons_are_fanned_or_refused() {
    // A unit square and a pentagon beside it.
    let pos = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(1., 1., 0.),
        p(0., 1., 0.),
        p(2., 0., 0.),
        p(2.5, 0.5, 0.),
        p(2., 1., 0.),
    ];
    let mut polys = Polygons::new();
    polys.push(&[0, 1, 2, 3]);
    polys.push(&[1, 4, 5, 6, 2]);
    let raw = RawMesh {
        positions: pos,
        polygons: polys,
        ..RawMesh::default()
    };
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.fanned_polygons, 2);
    assert_eq!(r.mesh.num_faces(), 2 + 3);
    assert_eq!(r.face_source, vec![0, 0, 1, 1, 1]);
    let refuse = RepairOptions {
        polygons: PolygonRule::Refuse,
        ..RepairOptions::default()
    };
    match repair(&raw, &refuse) {
        Err(
            e @ RepairError::Polygon {
                face: 0,
                corners: 4,
            },
        ) => {
            assert!(e.to_string().contains("face 0 has 4 corners"));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn repeated_and_duplicate_faces_and_unused_vertices_are_skipped() {
    let mut raw = octa();
    raw.positions.push(p(5., 5., 5.)); // unused
    let mut tris: Vec<[usize; 3]> = raw.polygons.iter().map(|t| [t[0], t[1], t[2]]).collect();
    tris.push([0, 0, 1]); // face 8: repeated vertex
    tris.push([2, 1, 0]); // face 9: duplicate of face 0, other orientation
    raw.polygons = Polygons::from_triangles(&tris);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.repeated_vertex_faces, vec![8]);
    assert_eq!(r.report.duplicate_faces, vec![9]);
    assert_eq!(r.report.unused_vertices, 1);
    assert_eq!(r.mesh.num_faces(), 8);
    assert_eq!(r.mesh.num_vertices(), 6);
}

#[test]
fn a_fin_on_an_edge_is_detached() {
    // Octahedron plus a third face on edge 0–1 pointing away.
    let mut raw = octa();
    raw.positions.push(p(1., 1., -0.3));
    let mut tris: Vec<[usize; 3]> = raw.polygons.iter().map(|t| [t[0], t[1], t[2]]).collect();
    tris.push([0, 1, 6]);
    raw.polygons = Polygons::from_triangles(&tris);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.detached_edges, vec![[0, 1]]);
    assert_eq!(r.mesh.num_faces(), 9);
    assert!(r.report.dropped_faces.is_empty(), "{:?}", r.report);
    // The fin got its own copies of vertices 0 and 1.
    assert_eq!(r.mesh.num_vertices(), 7 + 2);
    assert_eq!(r.report.components, 2);
}

#[test]
fn a_bowtie_vertex_is_split() {
    // Two triangles touching only at vertex 0.
    let pos = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(1., 1., 0.),
        p(-1., 0., 0.),
        p(-1., -1., 0.),
    ];
    let raw = RawMesh::from_triangles(pos, &[[0, 1, 2], [0, 3, 4]]);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.split_vertices, vec![(0, 1)]);
    assert_eq!(r.mesh.num_vertices(), 6);
    assert_eq!(r.vertex_source, vec![0, 1, 2, 3, 4, 0]);
    assert_eq!(r.report.components, 2);
    assert_eq!(r.report.boundary_edges, 6);
}

#[test]
fn a_moebius_band_is_cut_open() {
    // A Möbius band of 5 quads (10 triangles): the last quad joins the first with a half twist.
    let n = 5;
    let mut pos = Vec::new();
    for i in 0..n {
        let t = std::f64::consts::TAU * i as f64 / n as f64;
        let half = t / 2.0;
        for s in [-0.3, 0.3] {
            let r = 1.0 + s * half.cos();
            pos.push(p(r * t.cos(), r * t.sin(), s * half.sin()));
        }
    }
    let mut tris = Vec::new();
    for i in 0..n {
        let (a, b) = (2 * i, 2 * i + 1);
        let (c, d) = if i + 1 < n {
            (2 * i + 2, 2 * i + 3)
        } else {
            (1, 0) // the twist
        };
        tris.push([a, c, d]);
        tris.push([a, d, b]);
    }
    let raw = RawMesh::from_triangles(pos, &tris);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.mesh.num_faces(), 10);
    assert!(!r.report.detached_edges.is_empty());
    assert!(r.report.dropped_faces.is_empty());
}

#[test]
fn a_zero_area_face_is_kept_and_listed() {
    // A flat fan with one collinear triangle (vertices 0, 1, 4 on a line).
    let pos = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(1., 1., 0.),
        p(0., 1., 0.),
        p(2., 0., 0.),
    ];
    let raw = RawMesh::from_triangles(pos, &[[0, 1, 2], [0, 2, 3], [0, 4, 1]]);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.degenerate_faces, vec![2]);
    assert!(r.mesh.is_degenerate_face(2));
    assert!(!r.mesh.is_degenerate_face(0));
}

#[test]
fn nothing_to_fit_is_an_error() {
    let raw = RawMesh::from_triangles(vec![p(0., 0., 0.), p(1., 0., 0.)], &[[0, 0, 1]]);
    assert!(matches!(
        repair(&raw, &default()),
        Err(RepairError::Empty(_))
    ));
    let empty = RawMesh::default();
    assert!(matches!(
        repair(&empty, &default()),
        Err(RepairError::Empty(_))
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Random faces over a handful of random points: a valid mesh or a named refusal.
    #[test]
    fn any_face_soup_gives_a_mesh_or_a_refusal(
        pts in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 3..9),
        faces in prop::collection::vec((0usize..9, 0usize..9, 0usize..9), 1..24),
    ) {
        let n = pts.len();
        let pos: Vec<Point3<f64>> = pts.iter().map(|&(x, y, z)| p(x, y, z)).collect();
        let tris: Vec<[usize; 3]> = faces.iter().map(|&(a, b, c)| [a % n, b % n, c % n]).collect();
        let raw = RawMesh::from_triangles(pos, &tris);
        match repair(&raw, &default()) {
            Ok(r) => {
                prop_assert_eq!(r.mesh.num_faces(), r.face_source.len());
                prop_assert_eq!(r.mesh.num_vertices(), r.vertex_source.len());
                prop_assert!(r.report.dropped_faces.len() <= mesh::repair::MAX_DROPPED_FACES);
            }
            Err(RepairError::Empty(_)) => {}
            Err(e) => prop_assert!(false, "unexpected refusal: {e}"),
        }
    }
}

/// The octahedron stored as eight separate triangles (24 vertices, three at each position),
/// as a per-face export writes it.
fn octa_in_pieces() -> RawMesh {
    let whole = octa();
    let mut pos = Vec::new();
    let mut tris = Vec::new();
    for t in whole.polygons.iter() {
        let base = pos.len();
        for &v in t {
            pos.push(whole.positions[v]);
        }
        tris.push([base, base + 1, base + 2]);
    }
    RawMesh::from_triangles(pos, &tris)
}

#[test]
fn pieces_at_the_same_positions_are_welded_into_one_closed_mesh() {
    let raw = octa_in_pieces();
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.welded_vertices, 18);
    assert_eq!(r.mesh.num_vertices(), 6);
    assert_eq!(r.report.components, 1);
    assert_eq!(r.report.boundary_edges, 0);
    assert!(!r.report.is_clean());
    assert!(r
        .report
        .summary_lines()
        .iter()
        .any(|l| l.contains("welded 18 vertices")));
    // Every mesh vertex comes from the first file vertex at its position.
    for (v, &s) in r.vertex_source.iter().enumerate() {
        assert_eq!(r.mesh.vertices()[v].data.p, raw.positions[s]);
        assert!(raw.positions[..s].iter().all(|q| *q != raw.positions[s]));
    }
    // Without the weld the pieces stay eight components.
    let apart = repair(
        &raw,
        &RepairOptions {
            weld: mesh::weld::WeldRule::Never,
            ..default()
        },
    )
    .unwrap();
    assert_eq!(apart.report.components, 8);
    assert_eq!(apart.report.welded_vertices, 0);
}

#[test]
fn split_normals_keep_a_seam_open_and_are_counted() {
    let mut raw = octa_in_pieces();
    // Each piece's vertices carry its face's normal: a faceted export with sharp edges.
    let normals = raw
        .polygons
        .iter()
        .flat_map(|t| {
            let [a, b, c] = [t[0], t[1], t[2]].map(|v| raw.positions[v]);
            let n = (b - a).cross(&(c - a)).normalize();
            [n, n, n]
        })
        .collect();
    raw.normals = Some(normals);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.welded_vertices, 0);
    assert_eq!(r.report.weld_kept_apart, 6);
    assert_eq!(r.report.components, 8);
}

#[test]
fn a_sliver_whose_corners_coincide_collapses_and_its_neighbours_join() {
    // Two triangles of a square, and a sliver (0, 4, 1) whose corner 4 is at vertex 0's place,
    // stored with its own copy: welded, it repeats a vertex and is skipped.
    let pos = vec![
        p(0., 0., 0.),
        p(1., 0., 0.),
        p(1., 1., 0.),
        p(0., 1., 0.),
        p(0., 0., 0.),
    ];
    let raw = RawMesh::from_triangles(pos, &[[0, 1, 2], [0, 2, 3], [4, 1, 0]]);
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.welded_vertices, 1);
    assert_eq!(r.report.repeated_vertex_faces, vec![2]);
    assert_eq!(r.mesh.num_faces(), 2);
}

#[test]
fn file_creases_follow_their_welded_vertices() {
    let mut raw = octa_in_pieces();
    // A crease named by the second copies of the ends of the octahedron's edge 0–1.
    let at = |q: Point3<f64>| {
        raw.positions
            .iter()
            .enumerate()
            .filter(|(_, x)| **x == q)
            .map(|(i, _)| i)
            .nth(1)
            .unwrap()
    };
    let (a, b) = (at(p(1., 0., 0.)), at(p(0., 1., 0.)));
    raw.crease_edges = vec![[a, b]];
    let r = repair(&raw, &default()).unwrap();
    assert_eq!(r.report.file_creases_kept, 1);
    assert_eq!(r.crease_edges.len(), 1);
    let [u, v] = r.crease_edges[0];
    let ends = [r.mesh.vertices()[u].data.p, r.mesh.vertices()[v].data.p];
    assert!(ends.contains(&p(1., 0., 0.)) && ends.contains(&p(0., 1., 0.)));
}

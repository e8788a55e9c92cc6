//! `estimate::fold_split`: a sector whose faces lie in no open hemisphere (the data folds over
//! itself at the vertex) is cut at its sharpest edges into sectors that each have a normal
//! facing all their faces, perpendicular to the chords of the edges cut; sectors without a
//! fold keep their data bit for bit. On a star built to fold (four faces whose normals are a
//! regular tetrahedron's) and on the committed decimated scans.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use estimate::{prepare, EstimateChoice};
use meshio::RawMesh;
use nalgebra::{Point3, Vector3};

/// A normal perpendicular to a chord is so to rounding.
const PERPENDICULAR: f64 = 1e-12;

/// Every sector's faces, by slot: the unit normals of the faces whose corner is in it.
fn faces_by_slot(mesh: &mesh::Mesh) -> Vec<Vec<Vector3<f64>>> {
    let sec = mesh.sectors().expect("sectors");
    let mut out = vec![Vec::new(); sec.num_slots()];
    for f in 0..mesh.num_faces() {
        let Some(n) = mesh.face_unit_normal(f) else {
            continue;
        };
        for c in 0..3 {
            out[sec.slot(f, c).unwrap()].push(n);
        }
    }
    out
}

/// An umbrella of four faces round the origin whose face normals point to the corners of a
/// regular tetrahedron: no normal at the origin faces all four (the sheet folds through
/// itself there), and the ring vertices each see two faces.
fn folded_umbrella() -> RawMesh {
    let ring = [
        Point3::new(-1.0, 1.0, 0.0),
        Point3::new(0.0, -1.0, 1.0),
        Point3::new(-1.0, -1.0, 0.0),
        Point3::new(0.0, 1.0, 1.0),
    ];
    let mut positions = vec![Point3::origin()];
    positions.extend(ring);
    let tris: Vec<[usize; 3]> = (0..4).map(|i| [0, 1 + i, 1 + (i + 1) % 4]).collect();
    RawMesh::from_triangles(positions, &tris)
}

#[test]
fn a_star_folded_through_itself_is_cut_into_sectors_that_face_their_faces() {
    let raw = folded_umbrella();
    // The premise: the four face normals are in no open hemisphere.
    let normals: Vec<Vector3<f64>> = (0..4)
        .map(|i| {
            let (a, b) = (raw.positions[1 + i], raw.positions[1 + (i + 1) % 4]);
            a.coords.cross(&b.coords).normalize()
        })
        .collect();
    assert!(estimate::facing::widest_margin(&normals).is_none());
    let choice = EstimateChoice::parse(estimate::DEFAULT_ESTIMATOR).unwrap();
    let p = prepare(&raw, choice, false).expect("prepared");
    let f = p.facing;
    assert_eq!(f.fold_sectors_cut, 1, "{f:?}");
    assert!(f.fold_edges_cut >= 2, "a closed star needs two cuts: {f:?}");
    assert_eq!(f.no_facing_normal, 0, "{f:?}");
    let mesh = &p.mesh;
    let sec = mesh.sectors().expect("the cuts are creases");
    assert_eq!(sec.num_creases(), f.fold_edges_cut);
    // The centre has one sector per piece; every sector faces its faces.
    let centre = sec.slots_per_vertex(mesh.num_vertices())[0];
    assert!(centre >= 2, "{centre}");
    for (s, faces) in faces_by_slot(mesh).iter().enumerate() {
        let n = sec.normal(s).unwrap();
        assert!(faces.iter().all(|a| a.dot(n) > 0.0), "slot {s}: {n:?}");
    }
    // Each piece at the centre is perpendicular to the chords of its cut edges where it can
    // be (the summary counts the crease ends off the line otherwise): here every piece can.
    for e in 0..mesh.num_edges() {
        if !sec.is_crease(e) {
            continue;
        }
        let edge = mesh.edge(e);
        let chord =
            mesh.vertices()[edge.vertices[1]].data.p - mesh.vertices()[edge.vertices[0]].data.p;
        let centre_end = if edge.vertices[0] == 0 { 0 } else { 1 };
        assert_eq!(
            edge.vertices[centre_end], 0,
            "cuts are at the folded vertex"
        );
        let mut faces = vec![edge.first];
        faces.extend(edge.second);
        for (g, _) in faces {
            let c = mesh.faces()[g].iter().position(|&x| x == 0).unwrap();
            let n = sec.normal(sec.slot(g, c).unwrap()).unwrap();
            assert!(
                n.dot(&chord).abs() < PERPENDICULAR * chord.norm(),
                "edge {e}: {n:?}"
            );
        }
    }
}

/// A mesh without a fold is not touched: no sectors made, the data as before, bit for bit.
#[test]
fn a_mesh_without_a_fold_is_not_cut() {
    let raw = meshio::read_file(fixtures::corpus::corpus_dir().join("bunny.ply")).unwrap();
    let choice = EstimateChoice::parse(estimate::DEFAULT_ESTIMATOR).unwrap();
    let p = prepare(&raw, choice, false).expect("prepared");
    assert_eq!(p.facing.fold_sectors_cut, 0);
    assert!(p.mesh.sectors().is_none());
}

/// The committed decimated scans: every sector whose faces lie in no open hemisphere is cut
/// (measured: dragon_res4 98 sectors at 145 edges, dragon_res3 293 at 378), and afterwards
/// every sector has a normal facing all its faces (none is left without one on either).
#[test]
fn the_decimated_dragons_are_cut_where_they_fold() {
    for name in ["dragon_res4.ply", "dragon_res3.ply"] {
        let raw = meshio::read_file(fixtures::corpus::corpus_dir().join(name)).unwrap();
        let choice = EstimateChoice::parse(estimate::DEFAULT_ESTIMATOR).unwrap();
        let p = prepare(&raw, choice, false).expect("prepared");
        let f = p.facing;
        assert!(
            f.fold_sectors_cut > 0 && f.fold_edges_cut >= f.fold_sectors_cut,
            "{f:?}"
        );
        let sec = p.mesh.sectors().expect("sectors");
        let against = faces_by_slot(&p.mesh)
            .iter()
            .enumerate()
            .filter(|(s, faces)| {
                let n = sec.normal(*s).unwrap();
                faces.iter().any(|a| a.dot(n) <= 0.0)
            })
            .count();
        assert_eq!(f.no_facing_normal, 0, "{name}: {f:?}");
        assert_eq!(against, 0, "{name}: {f:?}");
    }
}

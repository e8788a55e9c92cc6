//! Adjacency invariants of the half-edge mesh over generated closed meshes.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use proptest::prelude::*;
use surface::{dataset_by_name, Mesh};

fn check(m: &Mesh) -> Result<(), TestCaseError> {
    let f = m.num_faces();
    // Every edge twice, neighbours mutual, edge indices shared.
    for face in 0..f {
        for l in 0..3 {
            let (g, k) = m.neighbour(face, l).unwrap().expect("closed mesh");
            prop_assert_eq!(m.neighbour(g, k).unwrap(), Some((face, l)));
            prop_assert_eq!(m.edge_index(face, l).unwrap(), m.edge_index(g, k).unwrap());
            // The shared edge is traversed in opposite directions.
            let a = m.face(face).unwrap();
            let b = m.face(g).unwrap();
            prop_assert_eq!((a[l], a[(l + 1) % 3]), (b[(k + 1) % 3], b[k]));
        }
    }
    prop_assert_eq!(2 * m.num_edges(), 3 * f);
    // Fans partition the corners: 3F in all, each fan's ring has as many vertices as faces.
    let mut corners = 0;
    for v in 0..m.num_vertices() {
        let fan = m.faces_around_vertex(v);
        prop_assert_eq!(m.vertex_ring(v).len(), fan.len());
        for w in m.vertex_ring(v) {
            prop_assert!(m.find_edge(v, w).is_some());
        }
        corners += fan.len();
    }
    prop_assert_eq!(corners, 3 * f);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn ring_adjacency(n in 3usize..24) {
        let d = dataset_by_name("ring", Some(n)).unwrap();
        prop_assert_eq!(d.mesh.euler_characteristic(), 0);
        check(&d.mesh)?;
    }

    #[test]
    fn capsule_adjacency(n in 3usize..24) {
        let d = dataset_by_name("capsule", Some(n)).unwrap();
        prop_assert_eq!(d.mesh.euler_characteristic(), 2);
        check(&d.mesh)?;
    }

    #[test]
    fn walks_are_reversible(level in 0usize..3, start in 0usize..8, steps in prop::collection::vec(0usize..3, 0..12)) {
        let d = dataset_by_name("sphere", Some(level)).unwrap();
        let m = &d.mesh;
        let path = m.walk(start, &steps).unwrap();
        prop_assert_eq!(path.len(), steps.len() + 1);
        // Walk back: from each face, cross the edge we arrived through.
        let mut back = Vec::new();
        for (i, &l) in steps.iter().enumerate() {
            let (_, k) = m.neighbour(path[i], l).unwrap().unwrap();
            back.push(k);
        }
        back.reverse();
        let home = m.walk(*path.last().unwrap(), &back).unwrap();
        prop_assert_eq!(*home.last().unwrap(), start);
    }
}

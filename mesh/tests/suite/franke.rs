//! The Franke data sets: samplings, exact data at the vertices, the graph as the error
//! measures' truth, and the resolution range.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use mesh::analytic_franke::Franke;
use mesh::datasets::{dataset_by_name, DataSetError, FRANKE_NAMES};
use nalgebra::Vector3;

/// Vertices are built from closed forms: their data is exact to rounding.
const EXACT: f64 = 1e-12;

#[test]
fn the_twelve_sets_sample_the_six_functions_exactly() {
    for name in FRANKE_NAMES {
        let d = dataset_by_name(name, None).unwrap();
        let k = usize::from(name.as_bytes()[6] - b'0');
        let f = Franke::by_number(k).unwrap();
        let m = &d.mesh;
        if name.ends_with("@scattered") {
            // 100 points, 20 on the hull (the corners and 4 a side): 2V − h − 2 faces.
            assert_eq!((m.num_vertices(), m.num_faces()), (100, 178), "{name}");
        } else {
            assert_eq!(
                (m.num_vertices(), m.num_faces()),
                (33 * 33, 2 * 32 * 32),
                "{name}"
            );
        }
        assert_eq!(m.euler_characteristic(), 1, "{name}: a disc");
        for v in m.vertices() {
            let p = v.data.p;
            assert!((0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y));
            let jet = f.jet(p.x, p.y);
            assert!((p.z - jet.f).abs() < EXACT, "{name}: value");
            let n = Vector3::new(-jet.grad.x, -jet.grad.y, 1.0).normalize();
            assert!((v.data.n - n).norm() < EXACT, "{name}: normal");
            assert!((v.data.shape * v.data.n).norm() < EXACT, "{name}: S n = 0");
            let c = d.surface.closest(&p);
            assert!(
                (c.data.p - p).norm() < EXACT,
                "{name}: the vertex is its own closest point"
            );
        }
        // Counter-clockwise seen from above (the upward normals' side).
        for face in m.faces() {
            let [a, b, c] = face.map(|v| m.vertices()[v].data.p);
            assert!((b - a).cross(&(c - a)).z > 0.0, "{name}");
        }
    }
}

#[test]
fn resolutions_and_names_are_checked() {
    let g = dataset_by_name("franke1", Some(5)).unwrap();
    assert_eq!(g.mesh.num_faces(), 32);
    let s = dataset_by_name("franke2@scattered", Some(20)).unwrap();
    assert_eq!(s.mesh.num_vertices(), 20);
    assert!(matches!(
        dataset_by_name("franke1", Some(1)),
        Err(DataSetError::BadResolution { .. })
    ));
    assert!(matches!(
        dataset_by_name("franke3@scattered", Some(3)),
        Err(DataSetError::BadResolution { .. })
    ));
    assert!(matches!(
        dataset_by_name("franke7", None),
        Err(DataSetError::UnknownName { .. })
    ));
}

//! Rusinkiewicz's estimator: exact on the sphere (Max normals are exact there and normal
//! differences are position differences), convergence on the ring, Voronoi weights.

use crate::support;

use estimate::rusinkiewicz::{face_tensor, mixed_area};
use estimate::RUSINKIEWICZ;
use nalgebra::{Matrix3, Point3};
use support::*;

#[test]
fn exact_on_the_sphere() {
    /// Max normals and face tensors are exact on the sphere: rounding only (observed 1e-14).
    const EXACT: f64 = 1e-11;
    for l in [1, 3, 5] {
        let d = mesh::datasets::sphere(l).expect("valid");
        let e = run(&RUSINKIEWICZ, &d.mesh, None);
        for (v, vert) in d.mesh.vertices().iter().enumerate() {
            let n = e.normals[v];
            assert!((n - vert.data.n).norm() < EXACT);
            let want = -(Matrix3::identity() - n * n.transpose());
            assert!((e.shapes[v] - want).norm() < EXACT, "level {l} vertex {v}");
        }
    }
}

/// Observed on the ring 32→64→128 (RMS): normals exact to 1e-14 (Max weights on this regular
/// grid), K 0.103, 0.026, 6.5e-3, H 0.0126, 3.2e-3, 7.9e-4: order 2.0.
#[test]
fn converges_on_the_ring() {
    let (_, ring) = convergence(&RUSINKIEWICZ);
    assert_order(
        &ring.iter().map(|e| e.k).collect::<Vec<_>>(),
        ORDER_2,
        "ring K",
    );
    assert_order(
        &ring.iter().map(|e| e.h).collect::<Vec<_>>(),
        ORDER_2,
        "ring H",
    );
}

#[test]
fn face_tensor_of_a_sphere_triangle() {
    /// Exact for normals `n = p` on the unit sphere: rounding only.
    const EXACT: f64 = 1e-13;
    let p = [
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
        Point3::new(0.0, 0.0, 1.0),
    ];
    let n = p.map(|q| q.coords);
    let (s, nf) = face_tensor([&p[0], &p[1], &p[2]], [&n[0], &n[1], &n[2]]).expect("valid");
    let want = -(Matrix3::identity() - nf * nf.transpose());
    assert!((s - want).norm() < EXACT);
    // Zero-area face: none.
    assert!(face_tensor([&p[0], &p[0], &p[2]], [&n[0], &n[1], &n[2]]).is_none());
}

#[test]
fn mixed_areas_partition_the_triangle() {
    /// The three mixed areas of a triangle add up to its area (Meyer et al. 2003).
    const SUM: f64 = 1e-15;
    for (q, r) in [
        (Point3::new(1.0, 0.0, 0.0), Point3::new(0.3, 0.8, 0.0)),
        (Point3::new(1.0, 0.0, 0.0), Point3::new(1.5, 0.2, 0.0)), // obtuse at q
    ] {
        let p = Point3::origin();
        let area = 0.5 * (q - p).cross(&(r - p)).norm();
        let sum = mixed_area(&p, &q, &r) + mixed_area(&q, &r, &p) + mixed_area(&r, &p, &q);
        assert!((sum - area).abs() < SUM);
    }
    assert_eq!(
        mixed_area(
            &Point3::origin(),
            &Point3::origin(),
            &Point3::new(1.0, 0.0, 0.0)
        ),
        0.0
    );
}

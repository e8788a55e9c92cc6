//! The analytic data sets: exact vertex data, topology and closest-point queries.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use mesh::datasets::{dataset_by_name, AnalyticSurface, DataSet, DataSetError, DATASET_NAMES};
use mesh::datasets::{Capsule, Sphere, Torus};
use nalgebra::{Point3, Vector3};
use proptest::prelude::*;

/// Vertices are built from closed forms: their distance to the surface is rounding only.
const ON_SURFACE: f64 = 1e-12;
/// Identities between exact quantities (unit normals, `S n = 0`, symmetric tensors).
const EXACT: f64 = 1e-12;
/// Central-difference step for the gradient of the signed distance.
const FD_STEP: f64 = 1e-6;
/// The signed distance is smooth near the surface: its central difference is accurate to
/// O(h²) plus rounding ε/h ≈ 1e-10.
const FD_TOL: f64 = 1e-8;
/// On the capsule's seam circles the distance is only C¹: its second derivative jumps by the
/// meridian curvature 1/r = 2, so the central difference is off by O(h · 2)/4 ≈ 5e-7.
const SEAM_FD_TOL: f64 = 1e-6;

fn all() -> Vec<DataSet> {
    DATASET_NAMES
        .iter()
        .map(|n| dataset_by_name(n, None).unwrap())
        .collect()
}

#[test]
fn counts_and_topology() {
    let expect = [
        ("sphere", 66, 192, 128, 2),
        ("ring", 128, 384, 256, 0),
        ("capsule", 194, 576, 384, 2),
        ("octa", 6, 12, 8, 2),
    ];
    for (name, v, e, f, chi) in expect {
        let d = dataset_by_name(name, None).unwrap();
        let m = &d.mesh;
        assert_eq!(
            (
                m.num_vertices(),
                m.num_edges(),
                m.num_faces(),
                m.euler_characteristic()
            ),
            (v, e, f, chi),
            "{name}"
        );
        assert!(m.is_closed(), "{name}");
        assert!(m.vertices().iter().all(|v| v.curvature_known), "{name}");
    }
    let s0 = dataset_by_name("sphere", Some(0)).unwrap();
    assert_eq!((s0.mesh.num_vertices(), s0.mesh.num_faces()), (6, 8));
    let s3 = dataset_by_name("sphere", Some(3)).unwrap();
    assert_eq!((s3.mesh.num_vertices(), s3.mesh.num_faces()), (258, 512));
    let r = dataset_by_name("ring", Some(8)).unwrap();
    assert_eq!(
        (r.mesh.num_vertices(), r.mesh.euler_characteristic()),
        (32, 0)
    );
    let c = dataset_by_name("capsule", Some(4)).unwrap();
    assert_eq!(c.mesh.euler_characteristic(), 2);
}

#[test]
fn registry_rejects_bad_requests() {
    assert!(matches!(
        dataset_by_name("teapot", None),
        Err(DataSetError::UnknownName { .. })
    ));
    let msg = dataset_by_name("teapot", None).unwrap_err().to_string();
    assert!(msg.contains("sphere, ring, capsule, octa"), "{msg}");
    assert!(matches!(
        dataset_by_name("octa", Some(3)),
        Err(DataSetError::BadResolution { name: "octa", .. })
    ));
    assert!(matches!(
        dataset_by_name("ring", Some(2)),
        Err(DataSetError::BadResolution { name: "ring", .. })
    ));
    assert!(matches!(
        dataset_by_name("sphere", Some(9)),
        Err(DataSetError::BadResolution { .. })
    ));
}

#[test]
fn vertices_carry_the_exact_surface_data() {
    for d in all() {
        for (i, v) in d.mesh.vertices().iter().enumerate() {
            let data = &v.data;
            let s = &*d.surface;
            let truth = s.closest(&data.p);
            assert!(
                truth.signed_distance.abs() < ON_SURFACE,
                "{} vertex {i}",
                d.name
            );
            assert!((data.n.norm() - 1.0).abs() < EXACT);
            assert!(
                (data.n - truth.data.n).norm() < EXACT,
                "{} vertex {i}",
                d.name
            );
            // The normal is the gradient of the signed distance: ⊥ the tangent plane.
            let grad = Vector3::from_fn(|k, _| {
                let mut e = Vector3::zeros();
                e[k] = FD_STEP;
                (s.signed_distance(&(data.p + e)) - s.signed_distance(&(data.p - e)))
                    / (2.0 * FD_STEP)
            });
            let seam = d.name == "capsule" && (data.p.z.abs() - 0.5).abs() < EXACT;
            let tol = if seam { SEAM_FD_TOL } else { FD_TOL };
            assert!(
                (grad - data.n).norm() < tol,
                "{} vertex {i}: {grad}",
                d.name
            );
            // Shape tensor: symmetric, annihilates n, same as the surface's, and its invariants
            // are the principal curvatures.
            let sh = &data.shape;
            assert!((sh - sh.transpose()).amax() < EXACT);
            assert!((sh * data.n).norm() < EXACT);
            assert!(
                (sh - truth.data.shape).amax() < EXACT,
                "{} vertex {i}",
                d.name
            );
            let trace = sh.trace();
            let k_from_tensor = 0.5 * (trace * trace - (sh * sh).trace());
            assert!((0.5 * trace - truth.mean()).abs() < EXACT);
            assert!((k_from_tensor - truth.gaussian()).abs() < 1e-11);
        }
        // Outward and consistently oriented: each face's geometric normal points along its
        // vertex normals.
        for f in 0..d.mesh.num_faces() {
            let g = d.mesh.face_area_normal(f).unwrap();
            let [a, b, c] = d.mesh.face_data(f).unwrap();
            assert!(g.dot(&(a.n + b.n + c.n)) > 0.0, "{} face {f}", d.name);
        }
    }
}

#[test]
fn ring_edges_are_the_curve_layers_grid_edges() {
    let d = dataset_by_name("ring", None).unwrap();
    let grid = mesh::analytic::torus_grid_edges(16, 8);
    assert_eq!(grid.len(), d.mesh.num_edges());
    let key = |p: &Point3<f64>| [p.x, p.y, p.z].map(|c| (c * 1e9).round() as i64);
    let mesh_edges: std::collections::BTreeSet<_> = d
        .mesh
        .edges()
        .map(|e| {
            let [a, b] = e.vertices.map(|v| key(&d.mesh.vertex(v).unwrap().data.p));
            (a.min(b), a.max(b))
        })
        .collect();
    for ((ua, va), (ub, vb)) in grid {
        let pa = mesh::analytic::torus_point(ua, va, 1.0, 0.4).p;
        let pb = mesh::analytic::torus_point(ub, vb, 1.0, 0.4).p;
        let (a, b) = (key(&pa), key(&pb));
        assert!(mesh_edges.contains(&(a.min(b), a.max(b))));
    }
}

#[test]
fn capsule_seams_carry_the_cylinder_tensor() {
    let d = dataset_by_name("capsule", None).unwrap();
    let seam: Vec<_> = d
        .mesh
        .vertices()
        .iter()
        .filter(|v| (v.data.p.z.abs() - 0.5).abs() < EXACT)
        .collect();
    assert_eq!(seam.len(), 32);
    for v in seam {
        // Along z (the meridian on the cylinder side) κn = 0; around, κn = −1/r = −2.
        assert!(v.data.normal_curvature(&Vector3::z()).abs() < EXACT);
        let around = Vector3::z().cross(&v.data.n);
        assert!((v.data.normal_curvature(&around) + 2.0).abs() < EXACT);
    }
}

#[test]
fn closest_points_against_closed_forms() {
    let sphere = Sphere::unit();
    let c = sphere.closest(&Point3::new(0.0, 0.0, 2.0));
    assert_eq!(c.data.p, Point3::new(0.0, 0.0, 1.0));
    assert_eq!(c.signed_distance, 1.0);
    assert_eq!((c.gaussian(), c.mean()), (1.0, -1.0));
    // At the centre: a documented choice, not NaN.
    assert_eq!(
        sphere.closest_point(&Point3::origin()),
        Point3::new(0.0, 0.0, 1.0)
    );
    assert_eq!(sphere.signed_distance(&Point3::new(0.3, 0.4, 0.0)), -0.5);

    let torus = Torus {
        big: 1.0,
        small: 0.4,
    };
    let c = torus.closest(&Point3::new(2.0, 0.0, 0.0));
    assert!((c.data.p - Point3::new(1.4, 0.0, 0.0)).norm() < EXACT);
    assert!((c.signed_distance - 0.6).abs() < EXACT);
    // Outer equator: κ = −1/r and −1/(R + r).
    assert!((c.gaussian() - 1.0 / (0.4 * 1.4)).abs() < EXACT);
    assert!((c.mean() - 0.5 * (-2.5 - 1.0 / 1.4)).abs() < EXACT);
    // Inside the hole: inner equator, saddle K = −1/(r (R − r)).
    let c = torus.closest(&Point3::new(0.0, -0.3, 0.0));
    assert!((c.data.p - Point3::new(0.0, -0.6, 0.0)).norm() < EXACT);
    assert!((c.data.n - Vector3::new(0.0, 1.0, 0.0)).norm() < EXACT);
    assert!((c.signed_distance - 0.3).abs() < EXACT);
    assert!((c.gaussian() + 1.0 / (0.4 * 0.6)).abs() < 1e-12);
    // Top of the tube: K = 0, H = −1/(2r).
    let c = torus.closest(&Point3::new(1.0, 0.0, 0.5));
    assert!((c.data.p - Point3::new(1.0, 0.0, 0.4)).norm() < EXACT);
    assert!(c.gaussian().abs() < EXACT);
    assert!((c.mean() + 1.25).abs() < EXACT);
    assert!((torus.signed_distance(&Point3::new(1.0, 0.0, 0.1)) + 0.3).abs() < EXACT);

    let capsule = Capsule {
        radius: 0.5,
        half_length: 0.5,
    };
    let c = capsule.closest(&Point3::new(1.0, 0.0, 0.2));
    assert!((c.data.p - Point3::new(0.5, 0.0, 0.2)).norm() < EXACT);
    assert_eq!(
        (c.signed_distance, c.gaussian(), c.mean()),
        (0.5, 0.0, -1.0)
    );
    let c = capsule.closest(&Point3::new(0.0, 0.0, 2.0));
    assert_eq!(c.data.p, Point3::new(0.0, 0.0, 1.0));
    assert_eq!(
        (c.signed_distance, c.gaussian(), c.mean()),
        (1.0, 4.0, -2.0)
    );
    // Inside, near a cap: the axis point is the nearest, not the cap.
    assert!((capsule.signed_distance(&Point3::new(0.0, 0.2, 0.45)) + 0.3).abs() < EXACT);
    let c = capsule.closest(&Point3::new(0.3, 0.0, -0.9));
    let expect = Point3::new(0.0, 0.0, -0.5) + Vector3::new(0.3, 0.0, -0.4) / 0.5 * 0.5;
    assert!((c.data.p - expect).norm() < EXACT);
    assert!((c.signed_distance - 0.0).abs() < EXACT);
}

fn surfaces() -> Vec<Box<dyn AnalyticSurface>> {
    vec![
        Box::new(Sphere::unit()),
        Box::new(Torus {
            big: 1.0,
            small: 0.4,
        }),
        Box::new(Capsule {
            radius: 0.5,
            half_length: 0.5,
        }),
    ]
}

proptest! {
    /// `q = p + d n` with `p` on the surface, for points in a box around the surfaces.
    #[test]
    fn closest_point_decomposes_the_query(
        x in -2.0..2.0f64, y in -2.0..2.0f64, z in -2.0..2.0f64
    ) {
        let q = Point3::new(x, y, z);
        for s in surfaces() {
            let c = s.closest(&q);
            prop_assert!((c.data.p + c.data.n * c.signed_distance - q).norm() < 1e-12);
            prop_assert!(s.signed_distance(&c.data.p).abs() < 1e-12);
            prop_assert!((c.data.n.norm() - 1.0).abs() < 1e-12);
            prop_assert!((c.data.shape * c.data.n).norm() < 1e-12);
            prop_assert!(c.principal[0] <= c.principal[1]);
        }
    }
}

//! `pn-triangles`: a net derived by hand, normal interpolation at the corners, and the
//! quadratic normal field: the data normals at the corners, one shared field along each edge.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions, VertexData};
use nalgebra::{Matrix3, Point3, Vector3};
use surface::beztri::index;
use surface::scheme::pn_triangles::{eval_normal_field, normal_field};
use surface::{dataset_by_name, fit_scheme, measure_g1, scheme_by_name, SchemeOptions};

/// Hand-derived values are short decimals: rounding only.
const EXACT: f64 = 1e-14;
/// The corners' tangent planes are the data's to rounding.
const NORMALS: f64 = 1e-12;

fn vd(p: [f64; 3], n: [f64; 3]) -> VertexData {
    VertexData::new(
        Point3::from(p),
        Vector3::from(n).normalize(),
        Matrix3::zeros(),
    )
}

#[test]
fn a_net_derived_by_hand() {
    let s = 0.5f64.sqrt();
    let v = [
        vd([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        vd([3.0, 0.0, 0.0], [s, 0.0, s]),
        vd([0.0, 3.0, 0.0], [0.0, 0.0, 1.0]),
    ];
    let edges = [curves::CubicBez3::new([Point3::origin(); 4]); 3];
    let input = surface::scheme::FaceInput {
        face: 0,
        vertices: [&v[0], &v[1], &v[2]],
        edges: &edges,
        creases: surface::scheme::NO_CREASES,
    };
    let scheme = scheme_by_name("pn-triangles", &SchemeOptions::default()).unwrap();
    let mut net = vec![Point3::origin(); 10];
    scheme.build(&input, &mut net).unwrap();
    // Next to P0 towards P1: w = (P1 − P0)·N0 = 0, so (2P0 + P1)/3 = (1, 0, 0).
    assert!((net[index(3, 2, 1, 0)] - Point3::new(1.0, 0.0, 0.0)).norm() < EXACT);
    // Next to P1 towards P0: w = (P0 − P1)·N1 = −3/√2; (2P1 + P0 − w N1)/3 = (2.5, 0, 0.5).
    assert!((net[index(3, 1, 2, 0)] - Point3::new(2.5, 0.0, 0.5)).norm() < EXACT);
    // Next to P1 towards P2: w = (P2 − P1)·N1 = −3/√2; (2P1 + P2 + (3/√2) N1)/3 = (2.5, 1, 0.5).
    assert!((net[index(3, 0, 2, 1)] - Point3::new(2.5, 1.0, 0.5)).norm() < EXACT);
    // Centre: E = mean of the six edge points, V = centroid, b111 = E + (E − V)/2.
    let edge_pts = [
        (2, 1, 0),
        (1, 2, 0),
        (0, 2, 1),
        (0, 1, 2),
        (1, 0, 2),
        (2, 0, 1),
    ];
    let e: Vector3<f64> = edge_pts
        .iter()
        .map(|&(i, j, k)| net[index(3, i, j, k)].coords)
        .sum::<Vector3<f64>>()
        / 6.0;
    let c = Vector3::new(1.0, 1.0, 0.0);
    assert!((net[index(3, 1, 1, 1)].coords - (e + (e - c) * 0.5)).norm() < EXACT);
    // Only the two edge points next to P1 leave the plane z = 0, each by 1/2: E_z = 1/6.
    assert!((e.z - 1.0 / 6.0).abs() < EXACT);
}

#[test]
fn corners_carry_the_data_normals() {
    let m = method_by_name("chord", &MethodOptions::default()).unwrap();
    let s = scheme_by_name("pn-triangles", &SchemeOptions::default()).unwrap();
    for name in ["sphere", "ring", "capsule"] {
        let data = dataset_by_name(name, None).unwrap();
        let f = fit_scheme(&data.mesh, s.as_ref(), m.as_ref()).unwrap();
        let g1 = measure_g1(&data.mesh, &f, 5);
        assert!(g1.normal_error < NORMALS, "{name}: {}", g1.normal_error);
    }
}

#[test]
fn the_normal_field_interpolates_and_is_shared_along_edges() {
    let mut rng = fixtures::SplitMix64::new(5);
    let mut r = move || rng.uniform(-1.0, 1.0);
    for _ in 0..50 {
        let p: [Point3<f64>; 4] = std::array::from_fn(|_| Point3::new(r(), r(), r()));
        let n: [Vector3<f64>; 4] =
            std::array::from_fn(|_| Vector3::new(r(), r(), r() + 2.5).normalize());
        // Faces (0, 1, 2) and (1, 0, 3) share the edge 0–1.
        let fa = normal_field([p[0], p[1], p[2]], [n[0], n[1], n[2]]);
        let fb = normal_field([p[1], p[0], p[3]], [n[1], n[0], n[3]]);
        assert!((eval_normal_field(&fa, 1.0, 0.0, 0.0) - n[0]).norm() < EXACT);
        assert!((eval_normal_field(&fa, 0.0, 1.0, 0.0) - n[1]).norm() < EXACT);
        for t in [0.1, 0.35, 0.5, 0.9] {
            let a = eval_normal_field(&fa, 1.0 - t, t, 0.0);
            let b = eval_normal_field(&fb, t, 1.0 - t, 0.0);
            assert!((a - b).norm() < NORMALS, "t = {t}");
            assert!((a.norm() - 1.0).abs() < NORMALS);
        }
    }
}

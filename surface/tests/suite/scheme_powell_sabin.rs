//! `powell-sabin`: the unit sphere's octant in closed form, the C1 rules inside measured, the
//! data normals at the corners, the C0 fallback, and the normal jump across mesh edges measured
//! and printed (the claim is C0).

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions, VertexData};
use nalgebra::{Matrix3, Point3, Vector3};
use surface::beztri::index;
use surface::scheme::FaceInput;
use surface::{
    dataset_by_name, fit_scheme, measure_g1, scheme_by_name, BezierTriangle, Continuity,
    SchemeOptions,
};

/// Hand-derived values are short fractions: rounding only.
const EXACT: f64 = 1e-14;
/// C1 inside the face: normals of rounding size apart (the G1 bound of docs/conventions.md).
const G1_TOL: f64 = 1e-9;
/// Corner normals equal to the data's to rounding.
const NORMALS: f64 = 1e-12;
/// Evaluation of a quadratic with coordinates of order one by de Casteljau: a few roundings.
const EVAL: f64 = 1e-13;

fn p(x: f64, y: f64, z: f64) -> Point3<f64> {
    Point3::new(x, y, z)
}

fn nets(v: &[VertexData; 3], fallback: bool) -> Vec<Point3<f64>> {
    let edges = [curves::CubicBez3::new([Point3::origin(); 4]); 3];
    let input = FaceInput {
        face: 0,
        vertices: [&v[0], &v[1], &v[2]],
        edges: &edges,
        creases: surface::scheme::NO_CREASES,
    };
    let s = scheme_by_name("powell-sabin", &SchemeOptions::default()).unwrap();
    let mut out = vec![Point3::origin(); 36];
    if fallback {
        s.fallback(&input, &mut out);
    } else {
        s.build(&input, &mut out).unwrap();
    }
    out
}

fn octant() -> [VertexData; 3] {
    [Vector3::x(), Vector3::y(), Vector3::z()]
        .map(|e| VertexData::new(Point3::from(e), e, -Matrix3::identity()))
}

#[test]
fn the_sphere_octant_in_closed_form() {
    let net = nets(&octant(), false);
    // Sub-patch 0 = (V_0, M_0, S): V_0, Q⁺_0, M_0, W_0, Z_0, S.
    // Q⁺_0 = V_0 + ¼π_0(V_1 − V_0): π_0(−1, 1, 0) = (0, 1, 0), so (1, ¼, 0); by symmetry
    // Q⁻_1 = (¼, 1, 0) and M_0 = (5/8, 5/8, 0), at radius 5√2/8 ≈ 0.884.
    assert!((net[1] - p(1.0, 0.25, 0.0)).norm() < EXACT);
    assert!((net[2] - p(0.625, 0.625, 0.0)).norm() < EXACT);
    assert!(
        (net[6 + 1] - p(0.25, 1.0, 0.0)).norm() < EXACT,
        "Q⁻_1 in sub-patch 1"
    );
    // W_0 = ⅔(Q⁺_0 + Q⁻_0) − ⅓V_0 = ⅔(2, ¼, ¼) − (⅓, 0, 0) = (1, 1/6, 1/6): in the plane x = 1.
    assert!((net[3] - p(1.0, 1.0 / 6.0, 1.0 / 6.0)).norm() < EXACT);
    // Z_0 = (W_0 + W_1)/2 = (7/12, 7/12, 1/6); S = mean of the W = (4/9)(1, 1, 1).
    assert!((net[4] - p(7.0 / 12.0, 7.0 / 12.0, 1.0 / 6.0)).norm() < EXACT);
    for k in 0..6 {
        assert!((net[6 * k + 5] - p(4.0 / 9.0, 4.0 / 9.0, 4.0 / 9.0)).norm() < EXACT);
    }
    // The patch centre over the face's centroid is S.
    let b = BezierTriangle::new(2, net[..6].to_vec()).unwrap();
    assert!((b.eval(0.0, 0.0, 1.0) - p(4.0 / 9.0, 4.0 / 9.0, 4.0 / 9.0)).norm() < EXACT);
}

#[test]
fn c1_inside_data_normals_at_corners_and_the_jump_across_edges() {
    let s = scheme_by_name("powell-sabin", &SchemeOptions::default()).unwrap();
    assert_eq!(s.continuity(), Continuity::C0);
    assert!(!s.uses_curves());
    let chord = method_by_name("chord", &MethodOptions::default()).unwrap();
    for name in ["sphere", "ring", "capsule"] {
        let data = dataset_by_name(name, None).unwrap();
        let f = fit_scheme(&data.mesh, s.as_ref(), chord.as_ref()).unwrap();
        assert!(f.face_fallbacks.is_empty() && f.curves.is_empty());
        let g1 = measure_g1(&data.mesh, &f, 9);
        assert!(g1.interior_max < G1_TOL, "{name}: C1 inside, {g1:?}");
        assert!(g1.normal_error < NORMALS, "{name}: G1 at the vertices");
        eprintln!(
            "{name}: powell-sabin normal jump across edges {:.3e} rad",
            g1.exterior_max
        );
        assert!(
            g1.exterior_max > G1_TOL,
            "{name}: the C0 claim is not understated"
        );
    }
}

#[test]
fn the_fallback_shares_the_boundary_and_keeps_planar_data_flat() {
    let regular = nets(&octant(), false);
    let fallback = nets(&octant(), true);
    for k in 0..6 {
        // Row 0 of every sub-patch: the shared boundary pieces.
        assert_eq!(&regular[6 * k..6 * k + 3], &fallback[6 * k..6 * k + 3]);
        // Interior boundaries shared between neighbouring sub-patches.
        let next = 6 * ((k + 1) % 6);
        assert_eq!(
            fallback[6 * k + index(2, 0, 1, 1)],
            fallback[next + index(2, 1, 0, 1)]
        );
    }
    let v = [p(0.0, 0.0, 0.0), p(2.0, 0.0, 0.5), p(0.3, 1.5, 1.0)];
    let n = (v[1] - v[0]).cross(&(v[2] - v[0])).normalize();
    let vd = v.map(|q| VertexData::new(q, n, Matrix3::zeros()));
    let net = nets(&vd, true);
    let sub = surface::scheme::SIX_SPLIT;
    for (k, corners) in sub.iter().enumerate() {
        let b = BezierTriangle::new(2, net[6 * k..6 * k + 6].to_vec()).unwrap();
        for (l0, l1) in [(0.2, 0.3), (0.5, 0.1), (0.1, 0.7)] {
            let l = [l0, l1, 1.0 - l0 - l1];
            let x: [f64; 3] = std::array::from_fn(|c| (0..3).map(|r| l[r] * corners[r][c]).sum());
            let want = v[0].coords * x[0] + v[1].coords * x[1] + v[2].coords * x[2];
            assert!((b.eval(l[0], l[1], l[2]).coords - want).norm() < EVAL);
        }
    }
}

//! `clough-tocher`: a net derived by hand, the classical rules checked on the patches themselves
//! (linear median cross-boundary derivative, C1 inside, data normals at the corners), the C0
//! fallback, and the normal jump across mesh edges measured and printed (the claim is C0).

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, CubicBez3, MethodOptions, VertexData};
use nalgebra::{Matrix3, Point3, Vector3};
use surface::scheme::{FaceInput, Scheme};
use surface::{
    dataset_by_name, fit_scheme, measure_g1, scheme_by_name, BezierTriangle, Continuity,
    SchemeOptions,
};

/// Hand-derived values are short fractions: rounding only.
const EXACT: f64 = 1e-14;
/// Derivatives of patches of size one, from a few de Casteljau steps: rounding only.
const DERIVATIVE: f64 = 1e-12;
/// C1 inside the face: normals of rounding size apart (the G1 bound of docs/conventions.md).
const G1_TOL: f64 = 1e-9;
/// Corner normals equal to the data's to rounding.
const NORMALS: f64 = 1e-12;
/// Evaluation of a cubic with coordinates of order one by de Casteljau: a few roundings.
const EVAL: f64 = 1e-13;

fn p(x: f64, y: f64, z: f64) -> Point3<f64> {
    Point3::new(x, y, z)
}

fn line(a: Point3<f64>, b: Point3<f64>) -> CubicBez3 {
    CubicBez3::new([a, a + (b - a) / 3.0, a + (b - a) * (2.0 / 3.0), b])
}

/// Face (0,0,0), (3,0,0), (0,3,0); edge 0 bent to E¹ = (1,0,1), E² = (2,0,1), the others straight;
/// the corner normals are the corners' tangent planes' (`e_l × e_a` of the leaving and arriving
/// tangents), so the curves lie in them: V_0 (1,0,1) × (0,1,0) ∝ (−1,0,1), V_1 (−3,3,0) ×
/// (−1,0,1) ∝ (1,1,1), V_2 +z.
fn bent_face() -> ([VertexData; 3], [CubicBez3; 3]) {
    let v = [p(0.0, 0.0, 0.0), p(3.0, 0.0, 0.0), p(0.0, 3.0, 0.0)];
    let normals = [
        Vector3::new(-1.0, 0.0, 1.0).normalize(),
        Vector3::new(1.0, 1.0, 1.0).normalize(),
        Vector3::z(),
    ];
    let vd: [VertexData; 3] =
        std::array::from_fn(|i| VertexData::new(v[i], normals[i], Matrix3::zeros()));
    let edges = [
        CubicBez3::new([v[0], p(1.0, 0.0, 1.0), p(2.0, 0.0, 1.0), v[1]]),
        line(v[1], v[2]),
        line(v[2], v[0]),
    ];
    (vd, edges)
}

fn run(f: impl Fn(&dyn Scheme, &FaceInput<'_>, &mut [Point3<f64>])) -> Vec<Point3<f64>> {
    let (vd, edges) = bent_face();
    let input = FaceInput {
        face: 0,
        vertices: [&vd[0], &vd[1], &vd[2]],
        edges: &edges,
        creases: surface::scheme::NO_CREASES,
    };
    let s = scheme_by_name("clough-tocher", &SchemeOptions::default()).unwrap();
    let mut out = vec![Point3::origin(); 30];
    f(s.as_ref(), &input, &mut out);
    out
}

#[test]
fn a_net_derived_by_hand() {
    let net = run(|s, i, o| s.build(i, o).unwrap());
    // Net of sub-patch e at 10e: row 0 (4 points), I¹_a, C_e, I¹_b, I²_a, I²_b, S.
    // I¹_0 = (V_0 + E¹_0 + E²_2)/3 = ((0,0,0) + (1,0,1) + (0,1,0))/3.
    assert!((net[4] - p(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0)).norm() < EXACT);
    // I¹_1 = ((3,0,0) + (2,1,0) + (2,0,1))/3.
    assert!((net[6] - p(7.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0)).norm() < EXACT);
    // C_0 = (E¹ + E²)/4 + (I¹_0 + I¹_1)/2 − (V_0 + V_1)/4
    //     = (3/4, 0, 1/2) + (4/3, 1/3, 1/3) − (3/4, 0, 0).
    assert!((net[5] - p(4.0 / 3.0, 1.0 / 3.0, 5.0 / 6.0)).norm() < EXACT);
    // Edge 2 (V_2 → V_0) is straight: C_2 = (0,3,0)/4 + (I¹_2 + I¹_0)/2 − (0,3,0)/4 with
    // I¹_2 = ((0,3,0) + (0,2,0) + (1,2,0))/3 = (1/3, 7/3, 0): C_2 = (1/3, 4/3, 1/6).
    assert!((net[25] - p(1.0 / 3.0, 4.0 / 3.0, 1.0 / 6.0)).norm() < EXACT);
    // I²_0 = (I¹_0 + C_0 + C_2)/3 and S = mean of the I², shared by all three sub-patches.
    let i2_0 = (net[4].coords + net[5].coords + net[25].coords) / 3.0;
    assert!((net[7].coords - i2_0).norm() < EXACT);
    assert!(
        (net[28].coords - i2_0).norm() < EXACT,
        "shared with sub-patch 2"
    );
    let s = (net[7].coords + net[17].coords + net[27].coords) / 3.0;
    for e in 0..3 {
        assert!((net[10 * e + 9].coords - s).norm() < EXACT);
    }
}

/// The derivative of a sub-patch along the domain median (from the exterior edge towards the
/// split point) at edge parameter `t`.
fn median_derivative(b: &BezierTriangle, t: f64) -> Vector3<f64> {
    b.directional([1.0 - t, t, 0.0], &[[-0.5, -0.5, 1.0]])
}

#[test]
fn the_classical_rules_hold_on_the_patches() {
    let s = scheme_by_name("clough-tocher", &SchemeOptions::default()).unwrap();
    assert_eq!(s.continuity(), Continuity::C0);
    for (name, method) in ["sphere", "ring", "capsule"]
        .into_iter()
        .flat_map(|n| ["chord", "dbhs", "optimized"].map(|m| (n, m)))
    {
        let data = dataset_by_name(name, None).unwrap();
        let m = method_by_name(method, &MethodOptions::default()).unwrap();
        let f = fit_scheme(&data.mesh, s.as_ref(), m.as_ref()).unwrap();
        assert!(f.face_fallbacks.is_empty());
        for b in f.bezier_patches().iter().take(90) {
            let d = [0.0, 0.5, 1.0].map(|t| median_derivative(b, t));
            let scale = d[0].norm().max(1.0);
            assert!(
                (d[1] - (d[0] + d[2]) / 2.0).norm() < DERIVATIVE * scale,
                "{name}: the median derivative is linear"
            );
        }
        let g1 = measure_g1(&data.mesh, &f, 9);
        assert!(g1.interior_max < G1_TOL, "{name}: C1 inside, {g1:?}");
        assert!(g1.normal_error < NORMALS, "{name}: G1 at the vertices");
        eprintln!(
            "{name}/{method}: clough-tocher normal jump across edges {:.3e} rad",
            g1.exterior_max
        );
        assert!(
            g1.exterior_max > G1_TOL,
            "{name}: the C0 claim is not understated"
        );
    }
}

#[test]
fn the_fallback_is_c0_on_the_curves_and_flat_on_planar_data() {
    let (_, edges) = bent_face();
    let net = run(|s, i, o| s.fallback(i, o));
    for e in 0..3 {
        assert_eq!(
            &net[10 * e..10 * e + 4],
            &edges[e].points[..],
            "row 0 is the curve"
        );
        // Interior boundary V_{e+1} → S: points b_{0,3−k,k} of e equal b_{3−k,0,k} of e + 1.
        let next = 10 * ((e + 1) % 3);
        for (mine, theirs) in [(3, 0), (6, 4), (8, 7), (9, 9)] {
            assert_eq!(net[10 * e + mine], net[next + theirs]);
        }
    }
    // Straight edges of a flat face: the affine map.
    let v = [p(0.0, 0.0, 0.0), p(2.0, 0.0, 0.5), p(0.3, 1.5, 1.0)];
    let vd = v.map(|q| VertexData::new(q, Vector3::z(), Matrix3::zeros()));
    let edges = [line(v[0], v[1]), line(v[1], v[2]), line(v[2], v[0])];
    let input = FaceInput {
        face: 0,
        vertices: [&vd[0], &vd[1], &vd[2]],
        edges: &edges,
        creases: surface::scheme::NO_CREASES,
    };
    let s = scheme_by_name("clough-tocher", &SchemeOptions::default()).unwrap();
    let mut out = vec![Point3::origin(); 30];
    s.fallback(&input, &mut out);
    let centre = (v[0].coords + v[1].coords + v[2].coords) / 3.0;
    for e in 0..3 {
        let b = BezierTriangle::new(3, out[10 * e..10 * e + 10].to_vec()).unwrap();
        let (a, c) = (v[e].coords, v[(e + 1) % 3].coords);
        for (l0, l1) in [(0.2, 0.3), (0.5, 0.1), (0.1, 0.7)] {
            let want = a * l0 + c * l1 + centre * (1.0 - l0 - l1);
            assert!((b.eval(l0, l1, 1.0 - l0 - l1).coords - want).norm() < EVAL);
        }
    }
}

//! `phong`: the closed form on the unit sphere's octant, the flat triangle at α = 0, and the
//! shape factor checked.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::VertexData;
use nalgebra::{Matrix3, Point3, Vector3};
use surface::beztri::index;
use surface::scheme::phong::Phong;
use surface::scheme::{FaceInput, Scheme};
use surface::{BezierTriangle, FaceFallbackReason};

/// Hand-derived values are short decimals: rounding only.
const EXACT: f64 = 1e-14;

fn octant() -> [VertexData; 3] {
    [Vector3::x(), Vector3::y(), Vector3::z()]
        .map(|e| VertexData::new(Point3::from(e), e, -Matrix3::identity()))
}

fn net(alpha: f64) -> Result<Vec<Point3<f64>>, FaceFallbackReason> {
    let v = octant();
    let edges = [curves::CubicBez3::new([Point3::origin(); 4]); 3];
    let input = FaceInput {
        face: 0,
        vertices: [&v[0], &v[1], &v[2]],
        edges: &edges,
        creases: surface::scheme::NO_CREASES,
    };
    let mut out = vec![Point3::origin(); 6];
    Phong { alpha }.build(&input, &mut out).map(|()| out)
}

#[test]
fn the_sphere_octant_in_closed_form() {
    // π_0(P1) = P1 − ((P1 − P0)·n0) n0 = (1, 1, 0) = π_1(P0), so at α = 1 the edge point is
    // (1, 1, 0), and the edge midpoint ¼P0 + ¼P1 + ½b01 = (0.75, 0.75, 0); at α = 3/4 the
    // edge point is ¼(½, ½, 0) + ¾(1, 1, 0) = (0.875, 0.875, 0) and the midpoint
    // (0.6875, 0.6875, 0), at radius 0.972 (the flat chord's midpoint is at 0.707).
    let full = net(1.0).unwrap();
    assert!((full[index(2, 1, 1, 0)] - Point3::new(1.0, 1.0, 0.0)).norm() < EXACT);
    let p = BezierTriangle::new(2, full).unwrap().eval(0.5, 0.5, 0.0);
    assert!((p - Point3::new(0.75, 0.75, 0.0)).norm() < EXACT);
    let three_quarters = BezierTriangle::new(2, net(0.75).unwrap()).unwrap();
    let p = three_quarters.eval(0.5, 0.5, 0.0);
    assert!((p - Point3::new(0.6875, 0.6875, 0.0)).norm() < EXACT);
    // The centre by symmetry lies on the diagonal: (1/9)(P0+P1+P2) + (2/9)(b01 + b12 + b20).
    let c = three_quarters.eval(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0);
    let want = (1.0 + 2.0 * 2.0 * 0.875) / 9.0;
    assert!((c - Point3::new(want, want, want)).norm() < EXACT);
}

#[test]
fn alpha_zero_is_the_flat_triangle() {
    let flat = BezierTriangle::new(2, net(0.0).unwrap()).unwrap();
    for (u, v) in [(0.2, 0.3), (0.5, 0.5), (0.1, 0.1)] {
        let w = 1.0 - u - v;
        let p = flat.eval(u, v, w);
        assert!((p - Point3::new(u, v, w)).norm() < EXACT);
    }
}

#[test]
fn a_non_finite_shape_factor_is_a_setting_error() {
    assert!(matches!(
        net(f64::NAN),
        Err(FaceFallbackReason::Scheme(
            surface::SchemeError::BadParameter { .. }
        ))
    ));
}

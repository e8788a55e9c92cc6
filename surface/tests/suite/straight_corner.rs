//! Straight crease corners (`surface::shirman_sequin`, "Straight crease corners"): a single face
//! between two crease edges whose tangents at the vertex are opposite (a cap on a curved crease
//! line, as remeshed CAD parts have). Without the crease information the construction refuses
//! the corner (its cross vector lies on the crease line); with it, the face is built G1 inside
//! and across its smooth edge, its corner normal the sector's, and every face without such a
//! corner keeps its nets bit for bit.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{CubicBez3, VertexData};
use nalgebra::{Matrix3, Point3, Rotation3, Vector3};
use proptest::prelude::*;
use surface::patch_g1::measure_patches;
use surface::{
    macro_patch, macro_patch_creased, BezierTriangle, InteriorParameters, QuarticNet, SchemeError,
};

/// G1 is exact by construction; measured angles are rounding noise (the G1 bound of
/// docs/conventions.md).
const G1_TOL: f64 = 1e-9;
/// Two unit normals computed from control points of order one agree to rounding.
const SAME_NORMAL: f64 = 1e-12;
/// Positions interpolated from coordinates of order one: rounding.
const INTERPOLATION: f64 = 1e-12;
/// Samples per shared boundary for the G1 measure.
const SAMPLES: usize = 17;

fn data(p: Point3<f64>, n: Vector3<f64>) -> VertexData {
    VertexData::new(p, n.normalize(), Matrix3::zeros())
}

/// `d` projected onto the plane `⊥ n`, a third of its length: the leg of a curve leaving along
/// its chord in that tangent plane.
fn leg(n: &Vector3<f64>, d: Vector3<f64>) -> Vector3<f64> {
    let n = n.normalize();
    (d - n * d.dot(&n)) / 3.0
}

fn cubic(a: Point3<f64>, la: Vector3<f64>, lb: Vector3<f64>, b: Point3<f64>) -> CubicBez3 {
    CubicBez3::new([a, a + la, b - lb, b])
}

/// A cap with a straight crease corner at corner 0: the crease runs along `x` through the
/// origin, the face's corner there has angle `angle` in the data, `tilt` turns the sector's
/// normal about the crease line, `lift` raises the other corners off the plane (in units of the
/// cap's height, so the face stays within 45° of the plane), and `ratio` is
/// the length of the arriving crease leg over the leaving one's (1: the straight corner the
/// fit makes). Returns the vertex data and the three edge curves (edge `e` from corner `e`).
fn cap(angle: f64, tilt: f64, lift: [f64; 2], ratio: f64) -> ([VertexData; 3], [CubicBez3; 3]) {
    let half = (std::f64::consts::PI - angle) / 2.0;
    let p0 = Point3::origin();
    let height = half.sin();
    let p1 = Point3::new(half.cos(), height, lift[0] * height);
    let p2 = Point3::new(-half.cos(), height, lift[1] * height);
    let n0 = Rotation3::from_axis_angle(&Vector3::x_axis(), tilt) * Vector3::z();
    let n1 = Vector3::new(-lift[0], 0.1, 1.0);
    let n2 = Vector3::new(lift[1], 0.1, 1.0);
    let v = [data(p0, n0), data(p1, n1), data(p2, n2)];
    let len = (p1 - p0).norm() / 3.0;
    let edges = [
        cubic(p0, Vector3::x() * len, leg(&n1, p1 - p0), p1),
        cubic(p1, leg(&n1, p2 - p1), leg(&n2, p2 - p1), p2),
        // Arriving at the corner along +x, leaving it along −x: the crease line's other half.
        cubic(p2, leg(&n2, p0 - p2), Vector3::x() * (len * ratio), p0),
    ];
    (v, edges)
}

fn patches(nets: &[QuarticNet]) -> Vec<BezierTriangle> {
    nets.iter()
        .map(|n| BezierTriangle::new(4, n.to_vec()).unwrap())
        .collect()
}

fn worst_angle(nets: &[QuarticNet]) -> (usize, f64) {
    let r = measure_patches(&patches(nets), SAMPLES);
    (r.shared, r.worst.map_or(f64::NAN, |w| w.angle))
}

fn build(v: &[VertexData; 3], edges: &[CubicBez3; 3]) -> Result<[QuarticNet; 3], SchemeError> {
    macro_patch_creased(
        [&v[0], &v[1], &v[2]],
        edges,
        &InteriorParameters::default(),
        [true, false, false],
    )
}

/// The checks every straight corner must pass: the three sub-patches meet G1 along the interior
/// boundaries, interpolate the edge curves, and both sub-patches at the corner have its normal.
fn check_straight(v: &[VertexData; 3], edges: &[CubicBez3; 3], nets: &[QuarticNet; 3]) {
    let (shared, angle) = worst_angle(nets);
    assert_eq!(shared, 3, "the three interior boundaries");
    assert!(angle < G1_TOL, "G1 inside the face: {angle:e}");
    for (net, curve) in nets.iter().zip(edges) {
        for (p, q) in net[..5].iter().zip(curve.elevate().points) {
            assert!((p - q).norm() < INTERPOLATION, "row 0 is the edge curve");
        }
    }
    let p = patches(nets);
    // Sub-patch 0 has the corner at (1, 0, 0), sub-patch 2 (over V_2, V_0, S) at (0, 1, 0).
    let at_corner = [p[0].normal(1.0, 0.0), p[2].normal(0.0, 1.0)];
    for n in at_corner {
        let n = n.expect("a regular corner: the two tangents are not parallel");
        assert!((n - v[0].n).norm() < SAME_NORMAL, "{n:?} vs {:?}", v[0].n);
    }
}

#[test]
fn a_straight_crease_corner_is_refused_without_creases_and_built_g1_with_them() {
    let (v, edges) = cap(170f64.to_radians(), 0.3, [0.5, -0.3], 1.0);
    assert!(matches!(
        macro_patch(
            [&v[0], &v[1], &v[2]],
            &edges,
            &InteriorParameters::default()
        ),
        Err(SchemeError::NoCrossComponent { corner: 0, .. })
    ));
    let nets = build(&v, &edges).unwrap();
    check_straight(&v, &edges, &nets);
}

/// The face's third edge is smooth: a neighbour built by the plain construction on the same
/// curve meets it G1 (Chiyokura–Kimura along that edge is untouched).
#[test]
fn the_face_meets_its_neighbour_across_its_smooth_edge_g1() {
    let (v, edges) = cap(165f64.to_radians(), -0.2, [0.4, 0.2], 1.0);
    let nets = build(&v, &edges).unwrap();
    // The neighbour (V_2, V_1, V_3) on the reversed edge curve 1.
    let p3 = Point3::new(0.1, 0.9, 0.15);
    let n3 = Vector3::new(0.0, -0.2, 1.0);
    let w = [v[2], v[1], data(p3, n3)];
    let [a, b, c, d] = edges[1].points;
    let other = [
        CubicBez3::new([d, c, b, a]),
        cubic(w[1].p, leg(&w[1].n, p3 - w[1].p), leg(&n3, p3 - w[1].p), p3),
        cubic(p3, leg(&n3, w[0].p - p3), leg(&w[0].n, w[0].p - p3), w[0].p),
    ];
    let params = InteriorParameters::default();
    let neighbour = macro_patch([&w[0], &w[1], &w[2]], &other, &params).unwrap();
    let all: Vec<QuarticNet> = nets.iter().chain(&neighbour).copied().collect();
    let (shared, angle) = worst_angle(&all);
    assert_eq!(
        shared, 7,
        "three interior boundaries each, and the shared edge"
    );
    assert!(angle < G1_TOL, "{angle:e}");
    // Crease flags on a face without a straight corner change nothing, bit for bit.
    let flagged = macro_patch_creased([&w[0], &w[1], &w[2]], &other, &params, [true; 3]).unwrap();
    for (x, y) in flagged.iter().flatten().zip(neighbour.iter().flatten()) {
        assert_eq!(x.coords.map(f64::to_bits), y.coords.map(f64::to_bits));
    }
}

/// Legs of different lengths are not a straight corner (`m = 0` cannot hold with `μ_0 = 0`):
/// the corner is refused as without the crease information. The fit gives a straight corner
/// one length first (`surface::fit::fan`).
#[test]
fn opposite_legs_of_different_lengths_are_refused() {
    let (v, edges) = cap(170f64.to_radians(), 0.3, [0.5, -0.3], 1.1);
    assert!(matches!(
        build(&v, &edges),
        Err(SchemeError::NoCrossComponent { corner: 0, .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Any cap on a curved crease: corner angles from 100° to 179.5°, the sector's normal
    /// turned about the crease line by up to 0.5 rad, the other corners lifted off the plane by
    /// up to half the cap's height.
    #[test]
    fn every_straight_corner_is_built_g1_with_the_sector_normal(
        angle in 100.0f64..179.5,
        tilt in -0.5f64..0.5,
        lift0 in -0.5f64..0.5,
        lift1 in -0.5f64..0.5,
    ) {
        let (v, edges) = cap(angle.to_radians(), tilt, [lift0, lift1], 1.0);
        let nets = build(&v, &edges).unwrap();
        check_straight(&v, &edges, &nets);
    }
}

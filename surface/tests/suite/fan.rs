//! Tangent fans (`surface::fit::fan`): the directions a sector's curves leave a vertex along,
//! chosen together. Properties of the fan on random stars (in the tangent plane, in cyclic
//! order, every corner convex, fixed ends kept), and through the fit: an octahedron whose top
//! normal leans further and further over, where the per-edge rule leaves corners that are not
//! convex, is fitted regularly and G1 on every face once the fans are applied; data whose
//! corners all pass is left bit for bit.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions};
use nalgebra::{Matrix3, Point3, Vector3};
use proptest::prelude::*;
use surface::fit::fan::{corner_is_convex, fan_directions, FanEnd, MAX_CORNER};
use surface::{
    dataset_by_name, fit_scheme, measure_g1, scheme_by_name, Mesh, SchemeOptions, Vertex,
    VertexData,
};

/// A fan direction is a unit vector built as `cos φ e1 + sin φ e2` in an orthonormal basis of
/// the plane `⊥ n`: its component along `n` and its length's error are rounding.
const ROUNDING: f64 = 1e-12;

/// The G1 bound of docs/conventions.md (`Continuity::G1`'s claim).
const G1_TOL: f64 = 1e-9;

/// The counter-clockwise angle about unit `n` from `a` to `b`, in `[0, 2π)`.
fn ccw(a: &Vector3<f64>, b: &Vector3<f64>, n: &Vector3<f64>) -> f64 {
    a.cross(b)
        .dot(n)
        .atan2(a.dot(b))
        .rem_euclid(std::f64::consts::TAU)
}

/// A star of `k` neighbours at azimuths `az` (sorted, counter-clockwise about z) and heights
/// `h` around the origin, and a normal tilted from z by `tilt` towards azimuth `towards`.
fn star(az: &[f64], h: &[f64], tilt: f64, towards: f64) -> (Vector3<f64>, Vec<Vector3<f64>>) {
    let n = Vector3::new(
        tilt.sin() * towards.cos(),
        tilt.sin() * towards.sin(),
        tilt.cos(),
    );
    let chords = az
        .iter()
        .zip(h)
        .map(|(a, z)| Vector3::new(a.cos(), a.sin(), *z))
        .collect();
    (n, chords)
}

proptest! {
    #[test]
    fn a_closed_fan_is_convex_in_order_and_in_the_plane(
        gaps in prop::collection::vec(0.05f64..1.0, 3..12),
        heights in prop::collection::vec(-3.0f64..3.0, 12),
        tilt in 0.0f64..1.4,
        towards in 0.0f64..std::f64::consts::TAU,
    ) {
        // Azimuths from gaps scaled to a full turn (each gap below π: a star, not a fold).
        let total: f64 = gaps.iter().sum();
        let mut az = Vec::new();
        let mut a = 0.0;
        for g in &gaps {
            az.push(a);
            a += g / total * std::f64::consts::TAU;
        }
        prop_assume!(gaps.iter().all(|g| g / total * std::f64::consts::TAU < 3.0));
        let (n, mut chords) = star(&az, &heights[..az.len()], tilt, towards);
        chords.push(chords[0]);
        let dirs = fan_directions(&n, &chords, None).expect("a closed star of 3 or more has a fan");
        prop_assert_eq!(dirs.len(), chords.len());
        let mut turned = 0.0;
        for w in dirs.windows(2) {
            prop_assert!((w[0].norm() - 1.0).abs() < ROUNDING);
            prop_assert!(w[0].dot(&n).abs() < ROUNDING);
            prop_assert!(corner_is_convex(&w[0], &w[1], &n));
            let angle = ccw(&w[0], &w[1], &n);
            prop_assert!(angle > 0.0 && angle <= MAX_CORNER + ROUNDING, "{angle}");
            turned += angle;
        }
        // One turn exactly: the cyclic order is the edges'.
        prop_assert!((turned - std::f64::consts::TAU).abs() < 1e-9, "{turned}");
    }

    #[test]
    fn an_open_fan_keeps_its_fixed_ends(
        gaps in prop::collection::vec(0.1f64..1.0, 1..8),
        heights in prop::collection::vec(-1.0f64..1.0, 9),
        opening in 0.3f64..5.5,
    ) {
        // A sector between two crease lines in the plane z = 0 (normal z), `opening` apart.
        let total: f64 = gaps.iter().sum();
        let mut az = vec![0.0];
        let mut a = 0.0;
        for g in &gaps {
            a += g / total * opening;
            az.push(a);
        }
        let m = gaps.len();
        prop_assume!(opening < m as f64 * MAX_CORNER * 0.999);
        let (n, chords) = star(&az, &heights[..az.len()], 0.0, 0.0);
        let first = Vector3::x();
        let last = Vector3::new(opening.cos(), opening.sin(), 0.0);
        let dirs = fan_directions(&n, &chords, Some([FanEnd::Fixed(first), FanEnd::Fixed(last)]))
            .expect("feasible");
        prop_assert!((dirs[0] - first).norm() < ROUNDING);
        prop_assert!((dirs[m] - last).norm() < ROUNDING);
        let mut turned = 0.0;
        for w in dirs.windows(2) {
            prop_assert!(corner_is_convex(&w[0], &w[1], &n));
            turned += ccw(&w[0], &w[1], &n);
        }
        prop_assert!((turned - opening).abs() < 1e-9);
    }
}

#[test]
fn a_straight_corner_between_fixed_ends_has_no_fan() {
    // One face between two crease lines that are one line: the corner is π whatever the fan.
    let n = Vector3::z();
    let chords = [Vector3::x(), -Vector3::x()];
    let ends = [FanEnd::Fixed(Vector3::x()), FanEnd::Fixed(-Vector3::x())];
    assert!(fan_directions(&n, &chords, Some(ends)).is_none());
    // Two faces may share it: 90° each.
    let chords = [Vector3::x(), Vector3::y(), -Vector3::x()];
    let dirs = fan_directions(&n, &chords, Some(ends)).expect("two corners of π/2");
    assert!((dirs[1] - Vector3::y()).norm() < ROUNDING);
}

/// The octahedron with unit-sphere data (normal `p`, shape tensor `−(I − p pᵀ)`), its top
/// vertex's normal tilted by `tilt` towards `+x`.
fn tilted_octahedron(tilt: f64) -> Mesh {
    let ps = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let vertices = ps
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let p = Point3::from(*p);
            let n = if i == 4 {
                Vector3::new(tilt.sin(), 0.0, tilt.cos())
            } else {
                p.coords
            };
            Vertex::new(VertexData::new(
                p,
                n,
                -(Matrix3::identity() - n * n.transpose()),
            ))
        })
        .collect();
    let faces = vec![
        [4, 0, 1],
        [4, 1, 2],
        [4, 2, 3],
        [4, 3, 0],
        [5, 1, 0],
        [5, 2, 1],
        [5, 3, 2],
        [5, 0, 3],
    ];
    Mesh::new(vertices, faces).expect("valid octahedron")
}

#[test]
fn a_leaning_normal_is_fitted_g1_once_its_star_has_a_fan() {
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).unwrap();
    let mut failing_before = 0;
    // Tilts whose normal still faces all four top faces (below 45°).
    for degrees in [0, 10, 20, 30, 35, 40, 44] {
        let mesh = tilted_octahedron(f64::from(degrees).to_radians());
        for method in ["chord", "optimized"] {
            let m = method_by_name(method, &MethodOptions::default()).unwrap();
            let f = fit_scheme(&mesh, scheme.as_ref(), m.as_ref()).unwrap();
            failing_before += f.fan.corners_failing_before;
            assert_eq!(f.fan.corners_failing_after, 0, "{degrees}° {method}");
            assert!(
                f.face_fallbacks.is_empty(),
                "{degrees}° {method}: {:?}",
                f.face_fallbacks
            );
            let g1 = measure_g1(&mesh, &f, 9);
            assert!(
                g1.max_angle() < G1_TOL,
                "{degrees}° {method}: G1 {:.3e}",
                g1.max_angle()
            );
        }
    }
    // The premise: the per-edge tangents do fail somewhere in this range.
    assert!(failing_before > 0);
}

#[test]
fn data_whose_corners_all_pass_is_left_as_the_per_edge_rule_builds_it() {
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).unwrap();
    for name in ["ring", "sphere", "octa", "capsule"] {
        let data = dataset_by_name(name, None).unwrap();
        for method in ["chord", "optimized", "dbhs"] {
            let m = method_by_name(method, &MethodOptions::default()).unwrap();
            let f = fit_scheme(&data.mesh, scheme.as_ref(), m.as_ref()).unwrap();
            assert_eq!(f.fan.corners_failing_before, 0, "{name} {method}");
            assert_eq!(f.fan.sectors_fanned, 0, "{name} {method}");
            assert_eq!(f.fan.tangents_turned, 0, "{name} {method}");
        }
    }
}

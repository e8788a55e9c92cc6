//! End to end on the ring (a 16×8 torus): from exact vertex data through the unit problem and
//! every construction back to world curves, checked against the surface.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, BoundaryProblem, MethodOptions, REGISTRY};
use surface::analytic::{torus_grid_edges, torus_point};

/// Interpolation of positions and tangent directions is exact up to rounding.
const INTERPOLATION: f64 = 1e-12;
/// dBHS curvature matching, in world units, after the unit-chord round trip.
const CURVATURE_MATCH: f64 = 1e-8;

#[test]
fn every_construction_interpolates_and_dbhs_matches_normal_curvature() {
    let (big, small) = (1.0, 0.4);
    let mut matched = 0;
    for ((ua, va), (ub, vb)) in torus_grid_edges(16, 8) {
        let a = torus_point(ua, va, big, small);
        let b = torus_point(ub, vb, big, small);
        let p = BoundaryProblem::new((0, 1), &a, &b).expect("regular torus edge");
        for entry in REGISTRY {
            let m = method_by_name(entry.name, &MethodOptions::default()).expect("registered");
            let choice = m.construct(&p.unit);
            let c = p.curve(choice.alpha);
            // Positions and tangent planes are interpolated.
            assert!((c.eval(0.0) - a.p).norm() < INTERPOLATION);
            assert!((c.eval(1.0) - b.p).norm() < INTERPOLATION);
            assert!(c.deriv(0.0).normalize().dot(&a.n).abs() < INTERPOLATION);
            assert!(c.deriv(1.0).normalize().dot(&b.n).abs() < INTERPOLATION);
            if entry.name == "dbhs" && !choice.fallback {
                // Meusnier, end to end: the world curve's curvature vector has normal component
                // equal to the surface's normal curvature along the curve's tangent.
                for (t, v) in [(0.0, &a), (1.0, &b)] {
                    let tangent = c.deriv(t).normalize();
                    let kn = v.normal_curvature(&tangent);
                    let got = c.curvature_vector(t).dot(&v.n);
                    assert!((got - kn).abs() < CURVATURE_MATCH, "{got} vs {kn}");
                }
                matched += 1;
            }
        }
    }
    // All edges but the 32 along the top and bottom circles of the tube have a dBHS curve.
    assert_eq!(matched, 384 - 32);
}

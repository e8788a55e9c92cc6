//! The original testbed's tangent rules (`curves::projection`, `curves::tweak`) through the
//! surface fit: the `ring` and `sphere` data sets fitted by `shirman-sequin` on each rule's
//! curves (the projection family at both reaches), G1 measured on every regular edge, no face
//! refused; the projection's space curves keep their tangents in the tangent planes, and leave
//! Furth's (chord's) plane where the data is not coplanar with the chord.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions, Reach};
use surface::{dataset_by_name, fit_scheme, measure_g1, scheme_by_name, SchemeOptions};

/// The G1 bound of docs/conventions.md, as for `chord`.
const G1_TOL: f64 = 1e-9;

/// Patch corners interpolate the data to rounding.
const INTERPOLATION: f64 = 1e-12;

/// `|t̂ · n|` of a projected tangent: one projection and one normalization.
const IN_PLANE: f64 = 1e-14;

/// A turn from Furth's tangent that is no rounding: far above [`SAME_DIRECTION`], far below
/// the 0.096 rad measured on the ring.
const LEAVES_THE_PLANE: f64 = 1e-3;

/// The angle between two tangents along the same unit vector at different lengths (the planar
/// rules and chord both take the problem's tangents): rounding of the scaling.
const SAME_DIRECTION: f64 = 1e-14;

#[test]
fn ring_and_sphere_stay_g1_on_every_tangent_rule() {
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).unwrap();
    for name in ["ring", "sphere"] {
        let data = dataset_by_name(name, None).unwrap();
        let mesh = &data.mesh;
        let chord = method_by_name("chord", &MethodOptions::default()).unwrap();
        let furth = fit_scheme(mesh, scheme.as_ref(), chord.as_ref()).unwrap();
        for reach in [Reach::Third, Reach::FourNinths] {
            let options = MethodOptions {
                reach,
                ..MethodOptions::default()
            };
            for method in [
                "projection",
                "projection-scaled",
                "piper",
                "tweak",
                "quadric",
            ] {
                let planar = matches!(method, "tweak" | "quadric");
                if planar && reach == Reach::FourNinths {
                    continue;
                }
                let m = method_by_name(method, &options).unwrap();
                let f = fit_scheme(mesh, scheme.as_ref(), m.as_ref()).unwrap();
                let g1 = measure_g1(mesh, &f, 9);
                // How far the rule's tangents turn from Furth's (= chord's): the largest angle
                // between the two fits' leaving tangents over the edges.
                let turn = f
                    .curves
                    .iter()
                    .zip(&furth.curves)
                    .map(|(c, k)| {
                        let (u, v) = (c.points[1] - c.points[0], k.points[1] - k.points[0]);
                        u.cross(&v).norm().atan2(u.dot(&v))
                    })
                    .fold(0.0, f64::max);
                if planar || name == "sphere" {
                    // The planar rules take the problem's tangents; on the sphere every edge's
                    // normals lie in its great circle's plane, where the projected chord is
                    // the plane's tangent.
                    assert!(turn < SAME_DIRECTION, "{name}/{method}: {turn}");
                } else {
                    // The ring's diagonal edges are not coplanar with their normals: the
                    // projection rules' tangents leave the curve plane (0.096 rad measured).
                    assert!(turn > LEAVES_THE_PLANE, "{name}/{method}: {turn}");
                }
                eprintln!(
                    "{name}/{method}/{reach:?}: G1 exterior {:.3e}, interior {:.3e} rad; \
                     tangents up to {turn:.3e} rad from Furth's; \
                     fallback curves {}, shortened {} of {}, clamped {}, fallback faces {}",
                    g1.exterior_max,
                    g1.interior_max,
                    f.fallbacks,
                    f.shortened_curves,
                    f.curves.len(),
                    f.clamped_tangents,
                    f.face_fallbacks.len()
                );
                let what = format!("{name}/{method}/{reach:?}: {g1:?}");
                assert!(f.face_fallbacks.is_empty(), "{what}");
                assert_eq!(f.fallbacks, 0, "{what}");
                assert_eq!(f.clamped_tangents, 0, "{what}");
                assert!(g1.exterior_max <= G1_TOL, "{what}");
                assert!(g1.interior_max <= G1_TOL, "{what}");
                assert!(g1.position_error < INTERPOLATION, "{what}");
                // Every curve leaves and enters its ends in the vertex's tangent plane.
                for (e, c) in mesh.edges().zip(&f.curves) {
                    let [a, b] = e.vertices.map(|v| mesh.vertices()[v].data.n.normalize());
                    let [p0, p1, p2, p3] = c.points;
                    assert!((p1 - p0).normalize().dot(&a).abs() < IN_PLANE, "{what}");
                    assert!((p3 - p2).normalize().dot(&b).abs() < IN_PLANE, "{what}");
                }
            }
        }
    }
}

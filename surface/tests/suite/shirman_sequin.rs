//! The modified Shirman–Séquin scheme against the techreport's appendices, measured G1 on curved
//! data for every boundary-curve construction, linear precision and similarity invariance.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, BoundaryProblem, CubicBez3, MethodOptions, VertexData, REGISTRY};
use nalgebra::{Matrix3, Point3, Rotation3, Vector3};
use proptest::prelude::*;
use surface::beztri::index;
use surface::{
    chiyokura_kimura, dataset_by_name, fit, macro_patch, measure_g1, BezierTriangle, CrossEnd,
    FaceFallbackReason, InteriorParameters, Mesh, QuarticNet, SchemeError,
};

/// Appendix A's nets are exact thirds and twelfths; the construction reproduces them to
/// rounding.
const APPENDIX: f64 = 1e-12;
/// G1 is exact by construction; measured angles are rounding noise (the G1 bound of
/// docs/conventions.md).
const G1_TOL: f64 = 1e-9;
/// G1 next to curves whose control points lie 10⁶–10⁷ chord lengths away: rounding of order
/// 1e-16 grows by that factor (measured 5.6e-9).
const G1_TOL_HUGE_CURVES: f64 = 1e-7;
/// Interpolation of positions is exact up to rounding of coordinates of order one.
const INTERPOLATION: f64 = 1e-12;

/// A net given as a function of `(i, j, k)` over corners `(A, B, C)`, re-expressed over the
/// corners `(X_0, X_1, X_2) = (old[perm[0]], old[perm[1]], old[perm[2]])`.
fn permuted(net: &QuarticNet, perm: [usize; 3]) -> QuarticNet {
    let mut out = *net;
    for k in 0..=4 {
        for i in 0..=4 - k {
            let j = 4 - k - i;
            let new = [i, j, k];
            let mut old = [0; 3];
            for c in 0..3 {
                old[perm[c]] = new[c];
            }
            out[index(4, i, j, k)] = net[index(4, old[0], old[1], old[2])];
        }
    }
    out
}

fn flat(p: [f64; 3]) -> VertexData {
    VertexData::new(Point3::from(p), Vector3::z(), Matrix3::zeros())
}

/// Curves of a face from its vertex data with a registered construction.
fn face_curves(v: [&VertexData; 3], method: &str) -> [CubicBez3; 3] {
    let m = method_by_name(method, &MethodOptions::default()).unwrap();
    std::array::from_fn(|e| {
        let (a, b) = (v[e], v[(e + 1) % 3]);
        let p = BoundaryProblem::new((e, (e + 1) % 3), a, b).unwrap();
        // As the fit builds it (planar via α, or in space for the projection rules).
        m.space_curve(&p, [None, None]).curve
    })
}

fn rows(r: &[&[(f64, f64)]]) -> QuarticNet {
    let pts: Vec<Point3<f64>> = r
        .iter()
        .flat_map(|row| row.iter().map(|&(x, y)| Point3::new(x, y, 0.0)))
        .collect();
    std::array::from_fn(|i| pts[i])
}

#[test]
fn appendix_a_nets() {
    let (p, q, r) = (
        flat([0.0, 0.0, 0.0]),
        flat([1.0, 0.0, 0.0]),
        flat([0.0, 1.0, 0.0]),
    );
    let curves = face_curves([&p, &q, &r], "chord");
    let nets = macro_patch([&p, &q, &r], &curves, &InteriorParameters::default()).unwrap();
    let (t, tw) = (1.0 / 3.0, 1.0 / 12.0);
    // The three nets exactly as printed (0.8̄3 = 5/6, 0.08̄3 = 1/12, 0.58̄3 = 7/12, …), each in
    // its printed corner order.
    let printed = [
        rows(&[
            &[(1.0, 0.0), (0.75, 0.0), (0.5, 0.0), (0.25, 0.0), (0.0, 0.0)],
            &[(10.0 * tw, tw), (7.0 * tw, tw), (t, tw), (tw, tw)],
            &[
                (2.0 * t, 2.0 * tw),
                (5.0 * tw, 2.0 * tw),
                (2.0 * tw, 2.0 * tw),
            ],
            &[(0.5, 0.25), (0.25, 0.25)],
            &[(t, t)],
        ]),
        rows(&[
            &[
                (1.0, 0.0),
                (10.0 * tw, tw),
                (2.0 * t, 2.0 * tw),
                (0.5, 0.25),
                (t, t),
            ],
            &[
                (0.75, 0.25),
                (7.0 * tw, t),
                (5.0 * tw, 5.0 * tw),
                (0.25, 0.5),
            ],
            &[(0.5, 0.5), (t, 7.0 * tw), (2.0 * tw, 2.0 * t)],
            &[(0.25, 0.75), (tw, 10.0 * tw)],
            &[(0.0, 1.0)],
        ]),
        rows(&[
            &[
                (t, t),
                (0.25, 0.25),
                (2.0 * tw, 2.0 * tw),
                (tw, tw),
                (0.0, 0.0),
            ],
            &[(0.25, 0.5), (2.0 * tw, 5.0 * tw), (tw, t), (0.0, 0.25)],
            &[(2.0 * tw, 2.0 * t), (tw, 7.0 * tw), (0.0, 0.5)],
            &[(tw, 10.0 * tw), (0.0, 0.75)],
            &[(0.0, 1.0)],
        ]),
    ];
    // Ours: sub-patch e over (V_e, V_{e+1}, S). Printed patch 1 is over (Q, P, S), patch 2 over
    // (Q, S, R), patch 3 over (S, P, R).
    let ours = [
        permuted(&nets[0], [1, 0, 2]),
        permuted(&nets[1], [0, 2, 1]),
        permuted(&nets[2], [2, 1, 0]),
    ];
    for (n, (a, b)) in ours.iter().zip(printed.iter()).enumerate() {
        for (x, y) in a.iter().zip(b.iter()) {
            assert!((x - y).norm() < APPENDIX, "patch {}: {x} vs {y}", n + 1);
        }
    }
}

#[test]
fn appendix_b_chiyokura_kimura() {
    let quad = BezierTriangle::new(
        2,
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.5, 0.0, 3.0),
            Point3::new(3.0, 0.0, 0.0),
            Point3::new(0.75, 2.0, 0.0),
            Point3::new(2.25, 2.0, 0.0),
            Point3::new(1.5, 4.0, 0.0),
        ],
    )
    .unwrap();
    let quartic = quad.elevate().elevate();
    let pt = |i, j, k| quartic.point(i, j, k).unwrap();
    assert!((pt(2, 1, 1) - Point3::new(1.125, 1.0, 1.0)).norm() < APPENDIX);
    assert!((pt(1, 2, 1) - Point3::new(1.875, 1.0, 1.0)).norm() < APPENDIX);
    // The cubic boundary from (0,0,0) to (3,0,0) (the quadratic edge raised once).
    let curve = CubicBez3::new([
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.0, 2.0),
        Point3::new(2.0, 0.0, 2.0),
        Point3::new(3.0, 0.0, 0.0),
    ]);
    let ends = [
        CrossEnd {
            normal: quad.normal(1.0, 0.0).unwrap(),
            cross: pt(3, 0, 1) - pt(4, 0, 0),
        },
        CrossEnd {
            normal: quad.normal(0.0, 1.0).unwrap(),
            cross: pt(0, 3, 1) - pt(0, 4, 0),
        },
    ];
    let [c1, c2] = chiyokura_kimura(&curve, &ends, 1.0).unwrap();
    assert!(
        (c1 - Point3::new(1.125, 1.0, 1.8)).norm() < APPENDIX,
        "{c1}"
    );
    assert!(
        (c2 - Point3::new(1.875, 1.0, 1.8)).norm() < APPENDIX,
        "{c2}"
    );
}

/// Deterministic pseudo-random numbers in [0, 1).
/// The workspace's one test generator.
use fixtures::SplitMix64 as Rng;

fn random_params(seed: u64, faces: usize) -> Vec<InteriorParameters> {
    let mut rng = Rng::new(seed);
    (0..faces)
        .map(|_| InteriorParameters {
            beta: std::array::from_fn(|_| 0.2 + 0.6 * rng.next_f64()),
            c: std::array::from_fn(|_| 0.5 + 1.5 * rng.next_f64()),
        })
        .collect()
}

fn check_g1(mesh: &Mesh, label: &str, seed: u64, skip: &[&str]) {
    let params = random_params(seed, mesh.num_faces());
    for entry in REGISTRY.iter().filter(|e| !skip.contains(&e.name)) {
        let m = method_by_name(entry.name, &MethodOptions::default()).unwrap();
        let f = fit(mesh, m.as_ref(), &|face| params[face])
            .unwrap_or_else(|e| panic!("{label}/{}: {e}", entry.name));
        let r = measure_g1(mesh, &f, 9);
        assert!(
            r.interior_max < G1_TOL,
            "{label}/{}: interior {r:?}",
            entry.name
        );
        assert!(
            r.exterior_max < G1_TOL,
            "{label}/{}: exterior {r:?}",
            entry.name
        );
        assert!(
            r.position_error < INTERPOLATION,
            "{label}/{}: {r:?}",
            entry.name
        );
        assert!(r.normal_error < G1_TOL, "{label}/{}: {r:?}", entry.name);
        assert_eq!(r.undefined_normals, 0);
    }
}

#[test]
fn g1_on_curved_data_for_every_construction() {
    for (i, name) in ["sphere", "ring", "capsule"].iter().enumerate() {
        let data = dataset_by_name(name, None).unwrap();
        check_g1(&data.mesh, name, 17 + i as u64, &[]);
    }
}

#[test]
fn g1_with_perturbed_normals() {
    for (i, name) in ["sphere", "ring", "capsule"].iter().enumerate() {
        let mut data = dataset_by_name(name, None).unwrap();
        let mut rng = Rng::new(99 + i as u64);
        for v in data.mesh.vertices_mut() {
            // Tilt each normal by up to 0.05 rad about a random tangent axis (larger tilts fold
            // the projected edges of the capsule's thinnest triangles over each other, where no
            // G1 construction of this form exists and `fit` reports the face).
            let axis = v.data.n.cross(&Vector3::new(
                rng.next_f64() - 0.5,
                rng.next_f64() - 0.5,
                rng.next_f64() - 0.5,
            ));
            if axis.norm() > 1e-6 {
                let rot = Rotation3::new(axis.normalize() * 0.05 * rng.next_f64());
                v.data.n = rot * v.data.n;
                v.data.shape = rot.matrix() * v.data.shape * rot.matrix().transpose();
            }
        }
        // dBHS on the perturbed capsule: the rulings of the cylinder are straight, and the
        // perturbation leaves curvatures of order 1e-8 there, which dBHS matches with end
        // derivatives of 10⁶–10⁷ chord lengths. The corner cross vectors then lie within 1e-8 of
        // the edge, or the patch turns over its face, and `fit` gives the face the C0 fallback
        // (checked below) instead of building a cusp.
        let skip: &[&str] = if *name == "capsule" { &["dbhs"] } else { &[] };
        check_g1(
            &data.mesh,
            &format!("{name} (perturbed)"),
            5 + i as u64,
            skip,
        );
        if *name == "capsule" {
            let m = method_by_name("dbhs", &MethodOptions::default()).unwrap();
            let params = random_params(5 + i as u64, data.mesh.num_faces());
            let per_face = |face: usize| params[face];
            let unfolding = surface::scheme::shirman_sequin::ShirmanSequin::per_face(&per_face)
                .with_unfold(true);
            let f = surface::fit_scheme(&data.mesh, &unfolding, m.as_ref()).unwrap();
            // Most regular patches on those curves turn over their faces at the given
            // parameters (measured: 192 of the 384 faces, once the curves' α are bounded by
            // `curves::UnitProblem::bounded_alpha`); the scheme with the choice on
            // (`with_unfold`) rebuilds them with interior parameters that do not fold, or gives
            // them the fallback where none does and the fallback does not.
            let as_given = surface::scheme::shirman_sequin::ShirmanSequin::per_face(&per_face);
            let kept = surface::fit_scheme(&data.mesh, &as_given, m.as_ref()).unwrap();
            let folded_given = surface::folds::measure(&data.mesh, &kept).folded.len();
            let folded = surface::folds::measure(&data.mesh, &f).folded.len();
            assert!(folded_given > 100, "{folded_given}");
            assert!(folded * 4 < folded_given, "{folded_given} → {folded}");
            for fb in &f.face_fallbacks {
                assert!(
                    matches!(
                        fb.reason,
                        FaceFallbackReason::Scheme(
                            SchemeError::NoCrossComponent { .. } | SchemeError::FoldsOverFace
                        )
                    ),
                    "{}",
                    fb.reason
                );
            }
            let r = measure_g1(&data.mesh, &f, 9);
            // The regular faces beside them carry curves with end derivatives of 10⁶–10⁷ chord
            // lengths: G1 holds to the rounding of control points that large.
            assert!(
                r.interior_max < G1_TOL_HUGE_CURVES && r.exterior_max < G1_TOL_HUGE_CURVES,
                "{r:?}"
            );
            assert!(r.position_error < INTERPOLATION, "{r:?}");
        }
    }
}

fn planar_triangle(seed: u64) -> ([VertexData; 3], Rotation3<f64>, Vector3<f64>) {
    let mut rng = Rng::new(seed);
    let rot = Rotation3::new(Vector3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 3.0);
    let shift =
        Vector3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()) * 10.0 - Vector3::repeat(5.0);
    let mut pts = [[0.0; 2]; 3];
    loop {
        for p in pts.iter_mut() {
            *p = [rng.next_f64() * 4.0 - 2.0, rng.next_f64() * 4.0 - 2.0];
        }
        let area = (pts[1][0] - pts[0][0]) * (pts[2][1] - pts[0][1])
            - (pts[2][0] - pts[0][0]) * (pts[1][1] - pts[0][1]);
        if area > 0.5 {
            break;
        }
    }
    let v = pts.map(|[x, y]| {
        VertexData::new(
            Point3::from(rot * Vector3::new(x, y, 0.0) + shift),
            rot * Vector3::z(),
            Matrix3::zeros(),
        )
    });
    (v, rot, shift)
}

proptest! {
    /// Linear precision: planar data with the Shirman–Séquin defaults give, for every curve
    /// construction whose curves on planar data are the edges at thirds, exactly the linear
    /// nets over the centroid split. Every construction gives straight curves there; the one
    /// registered construction that does not put them at thirds is the original testbed's
    /// Piper rule (inner points at 10/9 of the third: the segment, parametrized unevenly), for
    /// which the patch is not the linear one — checked here too, so the exception is measured.
    #[test]
    fn linear_precision(seed in 0u64..1_000_000) {
        let (v, _, _) = planar_triangle(seed);
        let s = Point3::from((v[0].p.coords + v[1].p.coords + v[2].p.coords) / 3.0);
        let mut uneven = Vec::new();
        for entry in REGISTRY {
            let curves = face_curves([&v[0], &v[1], &v[2]], entry.name);
            let mut thirds = true;
            for c in &curves {
                let [p0, p1, p2, p3] = c.points;
                let d = p3 - p0;
                prop_assert!((p1 - p0).cross(&d).norm() < 1e-11 * d.norm_squared(), "{}: not straight", entry.name);
                prop_assert!((p2 - p0).cross(&d).norm() < 1e-11 * d.norm_squared(), "{}: not straight", entry.name);
                thirds &= (p1 - (p0 + d / 3.0)).norm() < 1e-12 * d.norm()
                    && (p2 - (p3 - d / 3.0)).norm() < 1e-12 * d.norm();
            }
            if !thirds {
                uneven.push(entry.name);
                continue;
            }
            let nets = macro_patch([&v[0], &v[1], &v[2]], &curves, &InteriorParameters::default()).unwrap();
            for (e, net) in nets.iter().enumerate() {
                let (a, b) = (v[e].p, v[(e + 1) % 3].p);
                for k in 0..=4 {
                    for i in 0..=4 - k {
                        let j = 4 - k - i;
                        let linear = Point3::from((a.coords * i as f64 + b.coords * j as f64 + s.coords * k as f64) / 4.0);
                        let got = net[index(4, i, j, k)];
                        prop_assert!((got - linear).norm() < 1e-11, "{}: b{i}{j}{k} {got} vs {linear}", entry.name);
                    }
                }
            }
        }
        prop_assert_eq!(uneven, vec!["piper"]);
    }

    /// Planar data stay planar for any positive β and c (the patches need not be linear).
    #[test]
    fn planar_data_stay_planar(seed in 0u64..1_000_000, b in 0.2f64..0.8, c in 0.5f64..2.0) {
        let (v, rot, shift) = planar_triangle(seed);
        let n = rot * Vector3::z();
        let curves = face_curves([&v[0], &v[1], &v[2]], "chord");
        let params = InteriorParameters { beta: [b, 0.5 * b + 0.2, 0.6], c: [c, 1.0, 2.0 / c] };
        let nets = macro_patch([&v[0], &v[1], &v[2]], &curves, &params).unwrap();
        for net in &nets {
            for p in net {
                prop_assert!((p.coords - shift).dot(&n).abs() < 1e-11);
            }
        }
    }

    /// Similarity invariance: rotating, translating and uniformly scaling the data (positions,
    /// normals rotated, shape tensors rotated and divided by the scale) moves the nets the
    /// same way. The construction uses perpendiculars, so general affine maps are not expected
    /// to commute with it.
    #[test]
    fn similarity_invariance(
        ax in -3.0f64..3.0, ay in -3.0f64..3.0, az in -3.0f64..3.0, scale in 0.01f64..100.0,
        tx in -5.0f64..5.0, face in 0usize..20,
    ) {
        let data = dataset_by_name("ring", None).unwrap();
        let f = data.mesh.face(face).unwrap();
        let v: [VertexData; 3] = f.map(|i| data.mesh.vertices()[i].data);
        let rot = Rotation3::new(Vector3::new(ax, ay, az));
        let shift = Vector3::new(tx, -tx, 0.5 * tx);
        let moved = v.map(|d| VertexData::new(
            Point3::from(rot * d.p.coords * scale + shift),
            rot * d.n,
            rot.matrix() * d.shape * rot.matrix().transpose() / scale,
        ));
        let params = InteriorParameters { beta: [0.3, 0.45, 0.25], c: [0.8, 1.3, 1.0] };
        for entry in REGISTRY {
            let a = macro_patch([&v[0], &v[1], &v[2]], &face_curves([&v[0], &v[1], &v[2]], entry.name), &params).unwrap();
            let b = macro_patch([&moved[0], &moved[1], &moved[2]], &face_curves([&moved[0], &moved[1], &moved[2]], entry.name), &params).unwrap();
            // Optimized curves are repeatable to the solver's tolerance only.
            let tol = if entry.name == "optimized" { 1e-7 } else { 1e-10 };
            for (na, nb) in a.iter().zip(b.iter()) {
                for (p, q) in na.iter().zip(nb.iter()) {
                    let expect = rot * p.coords * scale + shift;
                    prop_assert!((q.coords - expect).norm() < tol * scale.max(1.0), "{}", entry.name);
                }
            }
        }
    }
}

#[test]
fn a_vertex_normal_at_or_past_the_face_is_refused() {
    // The flat triangle of Appendix A with the normal at corner 1 turned about y: at 85° it
    // still fits, at 95° it makes more than 90° with the face normal and the patch, which
    // interpolates it, would fold there.
    let turned = |deg: f64| {
        let n = Rotation3::new(Vector3::y() * deg.to_radians()) * Vector3::z();
        VertexData::new(Point3::new(1.0, 0.0, 0.0), n, Matrix3::zeros())
    };
    let (p, r) = (flat([0.0, 0.0, 0.0]), flat([0.0, 1.0, 0.0]));
    for (deg, refused) in [(85.0, false), (95.0, true)] {
        let q = turned(deg);
        let curves = face_curves([&p, &q, &r], "chord");
        let built = macro_patch([&p, &q, &r], &curves, &InteriorParameters::default());
        assert_eq!(
            built.err() == Some(SchemeError::NormalAgainstFace { corner: 1 }),
            refused,
            "{deg}°"
        );
    }
}

#[test]
fn a_clamped_tangent_is_refused() {
    // The normal at corner 1 leans 85° along the edge to corner 0 (a rotation about y): the
    // tangent of edge 0 at corner 1 climbs 85° from the chord and is clamped to 80°, off the
    // tangent plane.
    let n = Rotation3::new(Vector3::y() * (-85f64).to_radians()) * Vector3::z();
    let q = VertexData::new(Point3::new(1.0, 0.0, 0.0), n, Matrix3::zeros());
    let (p, r) = (flat([0.0, 0.0, 0.0]), flat([0.0, 1.0, 0.0]));
    let edge0 = BoundaryProblem::new((0, 1), &p, &q).unwrap();
    assert_eq!(edge0.clamped, [false, true]);
    let curves = face_curves([&p, &q, &r], "chord");
    assert_eq!(
        macro_patch([&p, &q, &r], &curves, &InteriorParameters::default()).err(),
        Some(SchemeError::TangentOffPlane { edge: 0, corner: 1 })
    );
}

//! The original testbed's projection rules (`projection`, `projection-scaled`, `piper`, each at
//! the third or five ninths of the chord): closed forms on a circle sampled by chords, agreement
//! of the space construction with the planar one on planar data, the projection's defining
//! identity `E − V = P(f d)` and the tangent plane on data that is not planar, crease lines,
//! the degenerate end, and edge reversal.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::projection::{Projection, Reach, Scaling, PIPER_FACTOR};
use curves::{method_by_name, BoundaryProblem, CurveMethod, MethodOptions, VertexData};
use nalgebra::{Matrix3, Point3, Vector3};

/// Closed forms through normalizations, cross products and the frame map: a few roundings on
/// coordinates of order one.
const ROUNDING: f64 = 1e-12;

/// `|û · n|` of a tangent the projection put in the tangent plane: rounding of one projection
/// and one normalization (far below the G1 schemes' `OFF_PLANE_SINE` = 1e-8).
const IN_PLANE: f64 = 1e-14;

/// Every member of the family.
fn members() -> Vec<Projection> {
    let mut out = Vec::new();
    for scaling in [Scaling::Projected, Scaling::Rescaled, Scaling::Piper] {
        for reach in [Reach::Third, Reach::FourNinths] {
            out.push(Projection { scaling, reach });
        }
    }
    out
}

/// `g(p)` of each member by hand (the source's table), times `3f`.
fn alpha_by_hand(m: &Projection, p: f64) -> f64 {
    let three_f = match m.reach {
        Reach::Third => 1.0,
        Reach::FourNinths => 5.0 / 3.0,
    };
    three_f
        * match m.scaling {
            Scaling::Projected => p,
            Scaling::Rescaled => 1.0,
            Scaling::Piper => p * 10.0 / 9.0,
        }
}

fn vertex(p: [f64; 3], n: Vector3<f64>) -> VertexData {
    VertexData::new(Point3::from(p), n.normalize(), Matrix3::zeros())
}

fn unit(v: Vector3<f64>) -> Vector3<f64> {
    v.normalize()
}

/// `v` projected onto the plane `⊥ n` (`n` unit).
fn project(v: Vector3<f64>, n: Vector3<f64>) -> Vector3<f64> {
    v - n * v.dot(&n)
}

/// The unit sphere's equator sampled by a chord of arc angle `psi`: radial normals, both in the
/// equator's plane, which is the curve plane; the tangents make `psi/2` with the chord.
fn equator_edge(psi: f64) -> BoundaryProblem {
    let a = mesh::analytic::sphere_point(&Vector3::new(1.0, 0.0, 0.0), 1.0);
    let b = mesh::analytic::sphere_point(&Vector3::new(psi.cos(), psi.sin(), 0.0), 1.0);
    BoundaryProblem::new((0, 1), &a, &b).unwrap()
}

#[test]
fn a_circle_sampled_by_chords_gets_each_rule_s_closed_form() {
    // |P(x̂)| = cos(ψ/2): the chord makes 90° − ψ/2 with each radial normal.
    for psi in [0.3f64, 1.0, 2.0, 2.6] {
        let p = equator_edge(psi);
        let c = (psi / 2.0).cos();
        for m in members() {
            let want = alpha_by_hand(&m, c);
            // The planar rule (cos θ = c on the unit problem) and the space rule agree.
            let planar = m.construct(&p.unit);
            let space = m.space_curve(&p, [None, None]);
            assert!(!planar.fallback && !space.choice.fallback, "{m:?}");
            for i in 0..2 {
                assert!((planar.alpha[i] - want).abs() < ROUNDING, "{m:?} ψ {psi}");
                assert!(
                    (space.choice.alpha[i] - want).abs() < ROUNDING,
                    "{m:?} ψ {psi}"
                );
            }
            // The fit's bound: α c summed over both ends at most 3.
            let (bounded, shortened) = p.unit.bounded_alpha(planar.alpha);
            assert_eq!(shortened, 2.0 * want * c > 3.0, "{m:?} ψ {psi}");
            assert_eq!(space.shortened, shortened, "{m:?} ψ {psi}");
            let same = p.curve(bounded);
            for (q, r) in space.curve.points.iter().zip(same.points.iter()) {
                assert!((q - r).norm() < ROUNDING, "{m:?} ψ {psi}: {q} vs {r}");
            }
            for (a, b) in space.alpha.iter().zip(bounded) {
                assert!((a - b).abs() < ROUNDING, "{m:?} ψ {psi}");
            }
        }
    }
    // At the third the polygon is always monotone; the four-ninths Piper is shortened on short
    // arcs (2 · (50/27) cos²(ψ/2) > 3 for ψ < 51°).
    let short = equator_edge(0.3);
    let piper49 = Projection {
        scaling: Scaling::Piper,
        reach: Reach::FourNinths,
    };
    assert!(piper49.space_curve(&short, [None, None]).shortened);
}

#[test]
fn normals_coplanar_with_the_chord_give_furth_s_directions() {
    // Both normals in the xz-plane, which contains the chord: the curve plane; the projected
    // chord is the plane's tangent, i.e. the problem's (Furth's) direction.
    let a = vertex(
        [0.0, 0.0, 0.0],
        Vector3::new(-(0.3f64.sin()), 0.0, 0.3f64.cos()),
    );
    let b = vertex(
        [1.0, 0.0, 0.0],
        Vector3::new(0.7f64.sin(), 0.0, 0.7f64.cos()),
    );
    let p = BoundaryProblem::new((0, 1), &a, &b).unwrap();
    assert_eq!(p.clamped, [false, false]);
    for m in members() {
        let c = m.space_curve(&p, [None, None]).curve;
        let leaving = unit(c.points[1] - c.points[0]);
        let arriving = unit(c.points[3] - c.points[2]);
        assert!((leaving - p.tangents[0]).norm() < ROUNDING, "{m:?}");
        assert!((arriving - p.tangents[1]).norm() < ROUNDING, "{m:?}");
    }
}

/// Edges with random positions and normals (both normals within 80° of +z, so that the
/// problem exists and no tangent is clamped or flipped).
fn random_edges(n: usize) -> Vec<(VertexData, VertexData)> {
    let mut rng = fixtures::SplitMix64::new(27);
    let normal = |rng: &mut fixtures::SplitMix64| {
        let v = Vector3::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 1.0);
        unit(v)
    };
    (0..n)
        .map(|_| {
            let pa = [rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.0];
            let pb = [
                pa[0] + rng.uniform(0.5, 2.0),
                pa[1] + rng.uniform(-1.0, 1.0),
                rng.uniform(-0.3, 0.3),
            ];
            let (na, nb) = (normal(&mut rng), normal(&mut rng));
            (vertex(pa, na), vertex(pb, nb))
        })
        .collect()
}

#[test]
fn off_the_plane_the_inner_points_are_the_projected_chord_points() {
    let mut left_the_plane = 0;
    for (a, b) in random_edges(200) {
        let p = BoundaryProblem::new((0, 1), &a, &b).unwrap();
        let d = b.p - a.p;
        let (na, nb) = (a.n.normalize(), b.n.normalize());
        for m in members() {
            let s = m.space_curve(&p, [None, None]);
            let [v0, e0, e1, v1] = s.curve.points;
            assert!((v0 - a.p).norm() < ROUNDING && (v1 - b.p).norm() < ROUNDING);
            // The tangents lie in the tangent planes.
            assert!(unit(e0 - v0).dot(&na).abs() < IN_PLANE, "{m:?}");
            assert!(unit(v1 - e1).dot(&nb).abs() < IN_PLANE, "{m:?}");
            assert!(!s.choice.fallback && s.clamped == [false, false]);
            if s.shortened {
                continue;
            }
            // The source's formulas, written out: P(f d), f|d| unit(P(d)), (10/9) P(f d).
            let f = m.reach.fraction();
            let want = |n: Vector3<f64>, v: Vector3<f64>| match m.scaling {
                Scaling::Projected => project(v * f, n),
                Scaling::Rescaled => unit(project(v, n)) * (f * v.norm()),
                Scaling::Piper => project(v * f, n) * PIPER_FACTOR,
            };
            assert!((e0 - v0 - want(na, d)).norm() < ROUNDING, "{m:?}");
            assert!((e1 - v1 - want(nb, -d)).norm() < ROUNDING, "{m:?}");
        }
        // Not Furth: the projected tangent leaves the problem's plane.
        let s = method_by_name("projection", &MethodOptions::default())
            .unwrap()
            .space_curve(&p, [None, None]);
        let t = unit(s.curve.points[1] - s.curve.points[0]);
        if t.dot(&p.frame.w).abs() > 1e-3 {
            left_the_plane += 1;
        }
    }
    assert!(left_the_plane > 150, "{left_the_plane} of 200 edges");
}

#[test]
fn a_crease_end_projects_onto_its_line() {
    let (a, b) = random_edges(1)[0];
    let p = BoundaryProblem::new((0, 1), &a, &b).unwrap();
    let d = b.p - a.p;
    // A line in the tangent plane at a, within 60° of the chord.
    let line = unit(project(d, a.n.normalize()) + a.n.normalize().cross(&d) * 0.5);
    for m in members() {
        let s = m.space_curve(&p, [Some(line), None]);
        let e = s.curve.points[1] - s.curve.points[0];
        assert!(unit(e).cross(&line).norm() < ROUNDING, "{m:?}");
        let want = alpha_by_hand(&m, line.dot(&unit(d)));
        if !s.shortened {
            assert!((e.norm() * 3.0 / d.norm() - want).abs() < ROUNDING, "{m:?}");
        }
    }
}

#[test]
fn a_normal_along_the_chord_falls_back_to_furth_at_that_end() {
    let (a, b) = random_edges(1)[0];
    let mut p = BoundaryProblem::new((0, 1), &a, &b).unwrap();
    // A problem is never built with a normal along its chord (`t · x̂ ≤ |P(x̂)|`); its normal is
    // set by hand to reach the guard.
    p.normals[0] = p.frame.x;
    for m in members() {
        let s = m.space_curve(&p, [None, None]);
        assert!(s.choice.fallback, "{m:?}");
        assert_eq!(s.choice.alpha[0], 1.0);
        let e = s.curve.points[1] - s.curve.points[0];
        assert!((e - p.tangents[0] * (p.frame.scale / 3.0)).norm() < ROUNDING);
    }
}

#[test]
fn a_reversed_edge_gets_the_same_curve() {
    for (a, b) in random_edges(50) {
        let p = BoundaryProblem::new((0, 1), &a, &b).unwrap();
        let r = BoundaryProblem::new((1, 0), &b, &a).unwrap();
        for m in members() {
            let c = m.space_curve(&p, [None, None]).curve.points;
            let q = m.space_curve(&r, [None, None]).curve.points;
            for k in 0..4 {
                assert!((c[k] - q[3 - k]).norm() < ROUNDING, "{m:?}");
            }
        }
    }
}

#[test]
fn the_registry_builds_each_rule_with_its_reach_and_none_reads_curvature() {
    let p = equator_edge(1.0);
    let c = 0.5f64.cos();
    for reach in [Reach::Third, Reach::FourNinths] {
        let options = MethodOptions {
            reach,
            ..MethodOptions::default()
        };
        for (name, scaling) in [
            ("projection", Scaling::Projected),
            ("projection-scaled", Scaling::Rescaled),
            ("piper", Scaling::Piper),
        ] {
            let m = method_by_name(name, &options).unwrap();
            assert_eq!(m.name(), name);
            assert!(!m.needs_curvature());
            let want = alpha_by_hand(&Projection { scaling, reach }, c);
            assert!((m.construct(&p.unit).alpha[0] - want).abs() < ROUNDING);
            // Curvature targets do not enter.
            let mut bent = p.unit;
            bent.k0 = 7.0;
            bent.k1 = -3.0;
            assert_eq!(m.construct(&bent), m.construct(&p.unit));
        }
    }
}

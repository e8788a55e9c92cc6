//! The original testbed's `tweak` and `quadric` curves: closed forms on a circle sampled by
//! chords, the quadric as the degree-raised quadratic through the tangents' intersection, the
//! rule `E = V + t (X − V)` in world coordinates, the fallbacks, and the parameter's range.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::tweak::{check_t, tangent_intersection, Quadric, Tweak, DEFAULT_TWEAK_T, QUADRIC_T};
use curves::{method_by_name, BoundaryProblem, CurveMethod, MethodOptions, UnitProblem};
use nalgebra::{Point3, Vector2, Vector3};

/// Closed forms through a 2×2 solve and the frame map: a few roundings on coordinates of order
/// one.
const ROUNDING: f64 = 1e-12;

fn unit_problem(t0: [f64; 2], t1: [f64; 2]) -> UnitProblem {
    UnitProblem::new(
        Vector2::from(t0).normalize(),
        Vector2::from(t1).normalize(),
        0.0,
        0.0,
    )
    .unwrap()
}

/// The arc of angle `psi` on the unit chord: tangents at `psi/2` to the chord.
fn arc(psi: f64) -> UnitProblem {
    let (s, c) = (psi / 2.0).sin_cos();
    unit_problem([c, s], [c, -s])
}

#[test]
fn a_circle_sampled_by_chords_gets_three_t_over_two_cos() {
    for psi in [0.2f64, 1.0, 2.0, 2.8] {
        let c = (psi / 2.0).cos();
        for t in [0.1, DEFAULT_TWEAK_T, 0.9, 1.0] {
            let choice = Tweak::new(t).unwrap().construct(&arc(psi));
            assert!(!choice.fallback);
            for a in choice.alpha {
                assert!((a - 1.5 * t / c).abs() < ROUNDING, "ψ {psi}, t {t}: {a}");
            }
        }
        let q = Quadric.construct(&arc(psi));
        assert!((q.alpha[0] - 1.0 / c).abs() < ROUNDING && (q.alpha[1] - 1.0 / c).abs() < ROUNDING);
    }
}

#[test]
fn the_quadric_is_the_raised_quadratic_through_the_intersection() {
    for (t0, t1) in [([0.8, 0.6], [0.6, -0.8]), ([0.9, 0.3], [0.95, -0.1])] {
        let u = unit_problem(t0, t1);
        let [s, _] = tangent_intersection(&u).unwrap();
        let x = Point3::new(0.0, 0.0, 0.0) + Vector3::new(u.t0.x, u.t0.y, 0.0) * s;
        let c = u.curve(Quadric.construct(&u).alpha);
        for k in 0..=10 {
            let t = f64::from(k) / 10.0;
            let quad = x.coords * (2.0 * t * (1.0 - t)) + Vector3::x() * (t * t);
            let p = c.eval(t);
            assert!((p.x - quad.x).abs() < ROUNDING && (p.y - quad.y).abs() < ROUNDING);
        }
    }
}

#[test]
fn in_space_the_inner_points_are_t_of_the_way_to_the_intersection() {
    // An oblique torus edge: its curve plane is neither a principal plane nor through an axis.
    let a = mesh::analytic::torus_point(0.3, 0.4, 1.0, 0.4);
    let b = mesh::analytic::torus_point(0.7, 1.1, 1.0, 0.4);
    let p = BoundaryProblem::new((0, 1), &a, &b).unwrap();
    assert_eq!(p.clamped, [false, false]);
    // X from the world tangent lines, solved in the curve plane's frame.
    let (ta, tb) = (p.tangents[0], p.tangents[1]);
    let d = b.p - a.p;
    let cross = |u: &Vector3<f64>, v: &Vector3<f64>| u.cross(v).dot(&p.frame.w);
    let s = cross(&d, &tb) / cross(&ta, &tb);
    let x = a.p + ta * s;
    assert!((x - (b.p - tb * (cross(&ta, &d) / cross(&ta, &tb)))).norm() < ROUNDING);
    for t in [0.25, DEFAULT_TWEAK_T, QUADRIC_T] {
        let m = Tweak::new(t).unwrap();
        let c = m.space_curve(&p, [None, None]);
        assert!(!c.choice.fallback && !c.shortened);
        assert!((c.curve.points[1] - (a.p + (x - a.p) * t)).norm() < ROUNDING);
        assert!((c.curve.points[2] - (b.p + (x - b.p) * t)).norm() < ROUNDING);
    }
}

#[test]
fn lines_that_do_not_meet_in_front_fall_back_to_the_chord() {
    // S-shaped: parallel tangents off the chord never meet.
    // Meeting behind: the lines cross before the start (s < 0).
    for u in [
        unit_problem([0.8, 0.6], [0.8, 0.6]),
        unit_problem([0.6, 0.8], [0.8, 0.6]),
    ] {
        for m in [
            Box::new(Tweak::default()) as Box<dyn CurveMethod>,
            Box::new(Quadric),
        ] {
            let c = m.construct(&u);
            assert!(c.fallback, "{u:?}");
            assert_eq!(c.alpha, [1.0, 1.0]);
        }
    }
    let behind = unit_problem([0.6, 0.8], [0.8, 0.6]);
    assert!(tangent_intersection(&behind).unwrap()[0] < 0.0);
    // Both along the chord: the segment, not a fallback.
    let straight = Tweak::default().construct(&unit_problem([1.0, 0.0], [1.0, 0.0]));
    assert!(!straight.fallback);
    assert_eq!(straight.alpha, [1.0, 1.0]);
}

#[test]
fn t_outside_zero_to_one_is_refused_with_a_clear_error() {
    for bad in [
        0.0,
        -1e-12,
        -3.0,
        1.0 + 1e-9,
        2.0,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ] {
        let e = check_t(bad).unwrap_err();
        assert!(e.to_string().contains("outside (0, 1]"), "{e}");
        assert!(Tweak::new(bad).is_err());
        // Built regardless (a struct literal, or options set by hand): the chord, as a fallback.
        let options = MethodOptions {
            tweak_t: bad,
            ..MethodOptions::default()
        };
        let c = method_by_name("tweak", &options)
            .unwrap()
            .construct(&arc(1.0));
        assert!(c.fallback && c.alpha == [1.0, 1.0], "{bad}");
    }
}

#[test]
fn the_registry_passes_t_and_quadric_is_two_thirds() {
    let u = unit_problem([0.9, 0.3], [0.95, -0.1]);
    let at = |t: f64| {
        let options = MethodOptions {
            tweak_t: t,
            ..MethodOptions::default()
        };
        method_by_name("tweak", &options)
            .unwrap()
            .construct(&u)
            .alpha
    };
    let (half, one) = (at(0.5), at(1.0));
    // Linear in t.
    assert!((one[0] - 2.0 * half[0]).abs() < ROUNDING && (one[1] - 2.0 * half[1]).abs() < ROUNDING);
    let quadric = method_by_name("quadric", &MethodOptions::default()).unwrap();
    assert_eq!(quadric.construct(&u), Tweak { t: QUADRIC_T }.construct(&u));
    assert!(!quadric.needs_curvature());
    assert!(!method_by_name("tweak", &MethodOptions::default())
        .unwrap()
        .needs_curvature());
    // Reversal swaps the lengths.
    let r = Tweak::default().construct(&u.reversed()).alpha;
    let f = Tweak::default().construct(&u).alpha;
    assert!((r[0] - f[1]).abs() < ROUNDING && (r[1] - f[0]).abs() < ROUNDING);
}

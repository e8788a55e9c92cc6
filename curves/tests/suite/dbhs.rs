//! The de Boor–Höllig–Sabin construction against closed forms, brute force and round trips.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{dbhs, CurveMethod, Dbhs, DbhsPick, UnitProblem};
use nalgebra::Vector2;
use proptest::prelude::*;

/// End curvatures of a dBHS solution match the targets to this relative accuracy (the solutions
/// are polished by Newton's method to rounding level).
const CURVATURE_MATCH: f64 = 1e-9;
/// Closed-form solutions are recovered to this relative accuracy.
const CLOSED_FORM: f64 = 1e-10;

fn dir(angle: f64) -> Vector2<f64> {
    Vector2::new(angle.cos(), angle.sin())
}

fn unit(a0: f64, a1: f64, k0: f64, k1: f64) -> UnitProblem {
    UnitProblem::new(dir(a0), dir(a1), k0, k1).expect("valid unit problem")
}

fn assert_matches_targets(p: &UnitProblem, alpha: [f64; 2]) {
    let c = p.curve(alpha);
    for (t, k) in [(0.0, p.k0), (1.0, p.k1)] {
        let got = c.curvature(t);
        assert!(
            (got - k).abs() <= CURVATURE_MATCH * k.abs().max(1.0),
            "κ({t}) = {got}, target {k}, α = {alpha:?}"
        );
    }
}

#[test]
fn circular_arc_closed_form() {
    // Arc from (0,0) to (1,0) leaving at angle θ above the chord: radius 1/(2 sin θ), turning
    // right (κ = −2 sin θ). By symmetry α0 = α1 = α with α² + 2 cos θ α − 3 = 0.
    for theta in [1e-3, 0.1, 0.5, 1.0, 1.4] {
        let k = -2.0 * f64::sin(theta);
        let p = unit(theta, -theta, k, k);
        let sols = dbhs::solve(&p);
        let expected = -theta.cos() + (theta.cos().powi(2) + 3.0).sqrt();
        let found = sols
            .iter()
            .find(|s| (s.alpha[0] - expected).abs() <= CLOSED_FORM * expected)
            .unwrap_or_else(|| panic!("θ = {theta}: symmetric solution missing in {sols:?}"));
        assert!((found.alpha[1] - expected).abs() <= CLOSED_FORM * expected);
        for s in sols.iter() {
            assert_matches_targets(&p, s.alpha);
        }
        let choice = Dbhs::default().construct(&p);
        assert!(!choice.fallback);
        assert_matches_targets(&p, choice.alpha);
        // The curve stays close to the circle: radial deviation well below the sagitta.
        let radius = 1.0 / (2.0 * theta.sin());
        let centre = Vector2::new(0.5, -radius * theta.cos());
        let c = p.curve(choice.alpha);
        let max_dev = (0..=100)
            .map(|i| ((c.eval(i as f64 / 100.0).coords - centre).norm() - radius).abs())
            .fold(0.0, f64::max);
        // dBHS interpolation is sixth-order accurate (de Boor et al. 1987): the deviation falls
        // like θ⁶; 0.6 θ⁶ bounds it with margin over this range (0.0051 measured at θ = 1).
        assert!(
            max_dev <= (0.6 * theta.powi(6) + 1e-12) * radius,
            "θ = {theta}: deviation {max_dev}"
        );
    }
}

#[test]
fn straight_segment_is_free_and_picks_the_chord() {
    let p = unit(0.0, 0.0, 0.0, 0.0);
    let sols = dbhs::solve(&p);
    assert_eq!(sols.len(), 1);
    let s = sols.get(0).expect("one solution");
    assert_eq!(s.alpha, [1.0, 1.0]);
    assert_eq!(s.free, [true, true]);
    let c = p.curve(s.alpha);
    assert!(c.curvature(0.5).abs() < 1e-15);
}

#[test]
fn parallel_tangents_decouple() {
    // t0 = t1 at 0.3 rad: the ends are independent, k0 α0² = 6 d0, k1 α1² = −6 d1.
    let th: f64 = 0.3;
    let (d0, d1) = (-th.sin(), -th.sin());
    let p = unit(th, th, -2.0, 1.5);
    let sols = dbhs::solve(&p);
    assert_eq!(sols.len(), 1);
    let s = sols.get(0).expect("one solution");
    assert!((s.alpha[0] - (6.0 * d0 / -2.0_f64).sqrt()).abs() < CLOSED_FORM);
    assert!((s.alpha[1] - (-6.0 * d1 / 1.5_f64).sqrt()).abs() < CLOSED_FORM);
    assert_matches_targets(&p, s.alpha);
    // Wrong-signed curvature at one end: no solution, chord fallback.
    let q = unit(th, th, 2.0, 1.5);
    assert!(dbhs::solve(&q).is_empty());
    let choice = Dbhs::default().construct(&q);
    assert!(choice.fallback);
    assert_eq!(choice.alpha, [1.0, 1.0]);
    assert_eq!(choice.chosen, None);
}

#[test]
fn s_shaped_data() {
    // Tangents both turned up by 0.4 rad; the curve must turn right then left.
    let p = unit(0.4, 0.4, -3.0, 3.0);
    let sols = dbhs::solve(&p);
    assert!(!sols.is_empty());
    for s in sols.iter() {
        assert_matches_targets(&p, s.alpha);
        let c = p.curve(s.alpha);
        assert!(c.curvature(0.0) < 0.0 && c.curvature(1.0) > 0.0);
    }
}

#[test]
fn zero_curvature_at_one_end_is_linear() {
    // k0 = 0: E0 fixes α1 = 3 d0 / c, then E1 gives α0 = −(6 d1 + k1 α1²) / (2c); exactly one
    // solution when both are positive, none otherwise. Tangents at 0.3 and −0.2 rad: c < 0 and
    // α1 = 1.85, so α0 > 0 exactly when k1 > −6 d1 / α1² ≈ −0.349.
    let closed_form = |p: &UnitProblem| {
        let c = curves::cross2(&p.t0, &p.t1);
        let (d0, d1) = (-p.t0.y, -p.t1.y);
        let a1 = 3.0 * d0 / c;
        (-(6.0 * d1 + p.k1 * a1 * a1) / (2.0 * c), a1)
    };
    let p = unit(0.3, -0.2, 0.0, 0.5);
    let (a0, a1) = closed_form(&p);
    assert!(a0 > 0.0 && a1 > 0.0, "{a0} {a1}");
    let sols = dbhs::solve(&p);
    assert_eq!(sols.len(), 1, "{sols:?}");
    let s = sols.get(0).expect("one");
    assert!((s.alpha[0] - a0).abs() < CLOSED_FORM * a0);
    assert!((s.alpha[1] - a1).abs() < CLOSED_FORM * a1);
    assert_matches_targets(&p, s.alpha);
    // k1 = −1: the closed form's α0 is negative, and there is no solution.
    let p = unit(0.3, -0.2, 0.0, -1.0);
    assert!(closed_form(&p).0 < 0.0);
    assert!(dbhs::solve(&p).is_empty());
}

#[test]
fn picking_policies() {
    // A circular arc of 0.2 rad has three solutions: the symmetric one near (1, 1) and two
    // lopsided ones, (1.180, 0.807) and its mirror.
    let p = unit(0.1, -0.1, -0.2, -0.2);
    let sols = dbhs::solve(&p);
    assert_eq!(sols.len(), 3, "{sols:?}");
    assert!(
        (sols.get(0).expect("first").alpha[0] - 0.806_826_482_109).abs() < 1e-9,
        "{sols:?}"
    );
    let closest = DbhsPick::Closest.pick(&sols).expect("some");
    let longest = DbhsPick::LongestShort.pick(&sols).expect("some");
    let dist = |i: usize| {
        let a = sols.get(i).expect("in range").alpha;
        (a[0] - 1.0).hypot(a[1] - 1.0)
    };
    let short = |i: usize| {
        let a = sols.get(i).expect("in range").alpha;
        a[0].min(a[1])
    };
    for i in 0..sols.len() {
        assert!(dist(closest) <= dist(i));
        assert!(short(longest) >= short(i));
    }
    assert_eq!(DbhsPick::Index(1).pick(&sols), Some(1));
    assert_eq!(DbhsPick::Index(9).pick(&sols), None);
    let fallback = Dbhs {
        pick: DbhsPick::Index(9),
    }
    .construct(&p);
    assert!(fallback.fallback);
    assert_eq!(fallback.candidates.len(), sols.len());
    assert_eq!(
        "longest-short".parse::<DbhsPick>(),
        Ok(DbhsPick::LongestShort)
    );
    assert_eq!("2".parse::<DbhsPick>(), Ok(DbhsPick::Index(2)));
    assert!("nearest".parse::<DbhsPick>().is_err());
}

/// Brute force: walk α0 along a fine geometric grid, take α1 from E0 and watch E1 change sign.
/// Returns the brackets `[α0_lo, α0_hi]` in which a positive solution lies.
fn scan(p: &UnitProblem, lo: f64, hi: f64, n: usize) -> Vec<(f64, f64)> {
    let c = curves::cross2(&p.t0, &p.t1);
    let (d0, d1) = (-p.t0.y, -p.t1.y);
    let a1_of = |a0: f64| (6.0 * d0 - p.k0 * a0 * a0) / (2.0 * c);
    let e1 = |a0: f64| {
        let a1 = a1_of(a0);
        p.k1 * a1 * a1 + 6.0 * d1 + 2.0 * c * a0
    };
    let ratio = (hi / lo).powf(1.0 / n as f64);
    let mut out = Vec::new();
    let mut x = lo;
    let mut fx = e1(x);
    for _ in 0..n {
        let y = x * ratio;
        let fy = e1(y);
        if (fx < 0.0) != (fy < 0.0) && a1_of(x) > 0.0 && a1_of(y) > 0.0 {
            out.push((x, y));
        }
        x = y;
        fx = fy;
    }
    out
}

#[test]
fn finds_every_solution_the_brute_force_scan_finds() {
    // Deterministic pseudo-random problems (the workspace's test generator, fixed seed).
    let mut rng = fixtures::SplitMix64::new(0x2545_f491_4f6c_dd1d);
    let mut next = || rng.next_f64();
    let (lo, hi, n) = (1e-3, 1e2, 40_000);
    let mut counts = [0usize; 5];
    let mut checked = 0;
    for i in 0..400 {
        // Half the problems come from a cubic (consistent data, as on a smooth surface: there
        // are then often three solutions), every other one of them perturbed by up to ±40 %;
        // half are arbitrary.
        let (th0, th1) = ((next() - 0.5) * 2.4, (next() - 0.5) * 2.4);
        let p = if i % 2 == 0 {
            let (th0, th1) = (th0 * 0.4, th1 * 0.4);
            let q = unit(th0, th1, 0.0, 0.0);
            let [k0, k1] = q.end_curvatures([0.5 + next(), 0.5 + next()]);
            let (f0, f1) = if i % 4 == 0 {
                (1.0, 1.0)
            } else {
                (0.6 + 0.8 * next(), 0.6 + 0.8 * next())
            };
            unit(th0, th1, k0 * f0, k1 * f1)
        } else {
            unit(th0, th1, (next() - 0.5) * 10.0, (next() - 0.5) * 10.0)
        };
        if curves::cross2(&p.t0, &p.t1).abs() < 1e-3 {
            continue;
        }
        let brackets = scan(&p, lo, hi, n);
        let sols = dbhs::solve(&p);
        for s in sols.iter() {
            assert_matches_targets(&p, s.alpha);
        }
        let in_range: Vec<_> = sols
            .iter()
            .filter(|s| s.alpha[0] > lo && s.alpha[0] < hi)
            .collect();
        // Every bracket holds a solution the solver found.
        for (a, b) in &brackets {
            assert!(
                in_range
                    .iter()
                    .any(|s| s.alpha[0] >= *a && s.alpha[0] <= *b),
                "{p:?}: scan bracket [{a}, {b}] missing from {sols:?}"
            );
        }
        // And the solver finds nothing the scan misses, except tangential (double) roots,
        // which have no sign change to see.
        assert!(in_range.len() >= brackets.len());
        counts[sols.len()] += 1;
        checked += 1;
    }
    assert!(checked > 300);
    // The sample exercises every multiplicity that occurs.
    assert!(
        counts[0] > 0 && counts[1] > 0 && counts[3] > 0,
        "{counts:?}"
    );
}

proptest! {
    /// Any cubic with positive end derivatives generates a problem (its own end tangents and
    /// curvatures) whose dBHS solution set contains it.
    #[test]
    fn recovers_the_cubic_that_made_the_data(
        a0 in 0.2f64..2.5, a1 in 0.2f64..2.5, th0 in -1.2f64..1.2, th1 in -1.2f64..1.2,
    ) {
        let p0 = unit(th0, th1, 0.0, 0.0);
        let [k0, k1] = p0.end_curvatures([a0, a1]);
        let p = UnitProblem { k0, k1, ..p0 };
        prop_assume!(curves::cross2(&p.t0, &p.t1).abs() > 1e-3);
        let sols = dbhs::solve(&p);
        let hit = sols.iter().any(|s| {
            (s.alpha[0] - a0).abs() < 1e-7 * a0 && (s.alpha[1] - a1).abs() < 1e-7 * a1
        });
        prop_assert!(hit, "α = ({a0}, {a1}) not among {sols:?}");
    }

    /// Reversing the problem reverses every solution.
    #[test]
    fn reversal_swaps_solutions(
        th0 in -1.2f64..1.2, th1 in -1.2f64..1.2, k0 in -6.0f64..6.0, k1 in -6.0f64..6.0,
    ) {
        let p = unit(th0, th1, k0, k1);
        let a = dbhs::solve(&p);
        let b = dbhs::solve(&p.reversed());
        prop_assert_eq!(a.len(), b.len());
        for s in a.iter() {
            let matched = b.iter().any(|r| {
                (r.alpha[0] - s.alpha[1]).abs() < 1e-8 * s.alpha[1].max(1.0)
                    && (r.alpha[1] - s.alpha[0]).abs() < 1e-8 * s.alpha[0].max(1.0)
            });
            prop_assert!(matched, "{:?} has no mirror in {:?}", s, b);
        }
    }
}

#[test]
fn torus_16x8_solution_counts() {
    // The ring of the seeds, sampled 16 × 8 (R = 1, r = 0.4). The 32 edges along the top and
    // bottom circles of the tube have both tangents along the chord and non-zero curvature:
    // no cubic matches them (one edge in twelve). Most other edges have three solutions.
    use mesh::analytic::{torus_grid_edges, torus_point};
    let mut counts = [0usize; 5];
    for ((ua, va), (ub, vb)) in torus_grid_edges(16, 8) {
        let (a, b) = (torus_point(ua, va, 1.0, 0.4), torus_point(ub, vb, 1.0, 0.4));
        let p = curves::BoundaryProblem::new((0, 1), &a, &b).expect("torus edges are regular");
        let sols = dbhs::solve(&p.unit);
        for s in sols.iter() {
            assert_matches_targets(&p.unit, s.alpha);
        }
        counts[sols.len()] += 1;
    }
    assert_eq!(counts[0], 32, "{counts:?}");
    assert!(counts[3] > 384 / 2, "{counts:?}");
    assert_eq!(counts.iter().sum::<usize>(), 384);
}

//! `dbhs-guarded`: the dBHS solution where its lengths keep within [`GUARD`], the optimized
//! construction's choice elsewhere, bit for bit either way.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::dbhs_guarded::GUARD;
use curves::{method_by_name, CurveMethod, Dbhs, DbhsGuarded, MethodOptions, UnitProblem};
use nalgebra::Vector2;
use proptest::prelude::*;

fn dir(angle: f64) -> Vector2<f64> {
    Vector2::new(angle.cos(), angle.sin())
}

fn guarded() -> Box<dyn CurveMethod> {
    method_by_name("dbhs-guarded", &MethodOptions::default()).unwrap()
}

fn optimized() -> Box<dyn CurveMethod> {
    method_by_name("optimized", &MethodOptions::default()).unwrap()
}

fn inside(a: [f64; 2]) -> bool {
    a.iter().all(|&x| (GUARD.0..=GUARD.1).contains(&x))
}

#[test]
fn a_circular_arc_takes_the_dbhs_solution() {
    // A symmetric arc leaving 0.3 rad above the chord: dBHS's symmetric solution
    // α = −cos θ + √(cos²θ + 3) ≈ 1.02, inside the guard.
    let theta: f64 = 0.3;
    let k = -2.0 * theta.sin();
    let p = UnitProblem::new(dir(theta), dir(-theta), k, k).unwrap();
    let got = guarded().construct(&p);
    let want = Dbhs::default().construct(&p);
    assert!(inside(want.alpha), "{:?}", want.alpha);
    assert_eq!(got.alpha, want.alpha);
    assert_eq!(got.candidates, want.candidates);
    assert!(got.report.is_none() && !got.fallback);
}

#[test]
fn tangents_along_the_chord_with_curvature_take_the_optimized_choice() {
    // No cubic leaves along its chord with non-zero end curvature at both ends: dBHS has no
    // solution (the ring's top and bottom circles), and the guard hands the problem to
    // `optimized`.
    let p = UnitProblem::new(dir(0.0), dir(0.0), 0.5, 0.5).unwrap();
    let got = guarded().construct(&p);
    let want = optimized().construct(&p);
    assert_eq!(got.alpha, want.alpha);
    assert!(got.report.is_some());
}

proptest! {
    /// On any problem the choice is the picked dBHS solution when it keeps within the guard,
    /// and the optimized choice otherwise.
    #[test]
    fn the_choice_is_dbhs_inside_the_guard_and_optimized_outside(
        a0 in -1.2..1.2f64, a1 in -1.2..1.2f64, k0 in -4.0..4.0f64, k1 in -4.0..4.0f64,
    ) {
        let Ok(p) = UnitProblem::new(dir(a0), dir(a1), k0, k1) else { return Ok(()) };
        let got = DbhsGuarded {
            pick: Default::default(),
            optimized: curves::Optimized {
                solver: MethodOptions::default().solver,
                weights: MethodOptions::default().weights,
                alpha_min: MethodOptions::default().alpha_min,
                solve_options: MethodOptions::default().solve_options,
            },
        }
        .construct(&p);
        let d = Dbhs::default().construct(&p);
        if !d.fallback && inside(d.alpha) {
            prop_assert_eq!(got.alpha, d.alpha);
        } else {
            prop_assert_eq!(got.alpha, optimized().construct(&p).alpha);
        }
    }
}

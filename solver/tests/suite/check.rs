//! The finite-difference checker passes correct derivatives and catches wrong ones.

use crate::common;

use common::{EndCurvature, Rosenbrock};
use nalgebra::{SMatrix, SVector, Vector2};
use solver::{
    check_gradient, check_gradient_with, check_jacobian, check_problem, check_second_order,
    CheckOptions,
};

/// Central differences with h = ε^{1/3} are accurate to ~1e-10 relative on these smooth,
/// well-scaled functions; 1e-7 leaves margin.
const CENTRAL_TOL: f64 = 1e-7;
/// Forward differences (at a bound) are accurate to ~√ε ≈ 1e-8 times the curvature scale.
const FORWARD_TOL: f64 = 1e-5;
/// A deliberately wrong derivative is off by a factor of order one.
const WRONG_MIN_ERROR: f64 = 1e-2;

fn f(x: &SVector<f64, 2>) -> f64 {
    x[0].sin() * x[1].exp() + x[0] * x[0] * x[1]
}
fn grad(x: &SVector<f64, 2>) -> SVector<f64, 2> {
    Vector2::new(
        x[0].cos() * x[1].exp() + 2.0 * x[0] * x[1],
        x[0].sin() * x[1].exp() + x[0] * x[0],
    )
}

#[test]
fn correct_gradient_passes() {
    let c = check_gradient(f, grad, &Vector2::new(0.7, -0.3));
    assert!(c.passes(CENTRAL_TOL), "{c}");
    assert!(!c.worst.unwrap().one_sided);
}

#[test]
fn wrong_gradient_is_caught_at_the_right_entry() {
    // Drop the 2x₀x₁ term of ∂f/∂x₀.
    let wrong = |x: &SVector<f64, 2>| {
        let mut g = grad(x);
        g[0] -= 2.0 * x[0] * x[1];
        g
    };
    let x = Vector2::new(0.7, -0.3);
    let c = check_gradient(f, wrong, &x);
    let w = c.worst.unwrap();
    assert_eq!(w.row, 0);
    assert!(w.error > WRONG_MIN_ERROR, "{c}");
    assert!(
        (w.numeric - grad(&x)[0]).abs() < 1e-8,
        "numeric is the true derivative"
    );
    assert!(!c.passes(CENTRAL_TOL));
}

#[test]
fn jacobians_of_test_problems_pass() {
    let r = Rosenbrock {
        lower_x2: f64::NEG_INFINITY,
    };
    assert!(
        check_problem(&r, &Vector2::new(-1.2, 1.0), &CheckOptions::default()).passes(CENTRAL_TOL)
    );
    let e = EndCurvature::representative();
    let c = check_problem(&e, &Vector2::new(0.8, 1.3), &CheckOptions::default());
    assert!(c.passes(CENTRAL_TOL), "{c}");
}

#[test]
fn second_order_terms_pass_and_problems_without_one_are_skipped() {
    let e = EndCurvature::representative();
    for a in [
        Vector2::new(0.8, 1.3),
        Vector2::new(1.0, 1.0),
        Vector2::new(0.2, 2.5),
    ] {
        let c = check_second_order(&e, &a, &CheckOptions::default()).unwrap();
        assert!(c.passes(CENTRAL_TOL), "{c}");
    }
    // At the bound α₀ = 0.05: forward differences.
    let c = check_second_order(&e, &Vector2::new(0.05, 1.0), &CheckOptions::default()).unwrap();
    assert!(c.worst.unwrap().one_sided && c.passes(FORWARD_TOL), "{c}");
    let r = Rosenbrock {
        lower_x2: f64::NEG_INFINITY,
    };
    assert!(check_second_order(&r, &Vector2::new(-1.2, 1.0), &CheckOptions::default()).is_none());
}

#[test]
fn wrong_jacobian_entry_is_located() {
    let e = EndCurvature::representative();
    let wrong = |a: &SVector<f64, 2>| {
        let mut j: SMatrix<f64, 4, 2> = solver::LeastSquaresProblem::jacobian(&e, a);
        j[(3, 0)] *= -1.0; // sign error in ∂κ₁/∂α₀
        j
    };
    let c = check_jacobian(
        |a| solver::LeastSquaresProblem::residuals(&e, a),
        wrong,
        &Vector2::new(0.8, 1.3),
    );
    let w = c.worst.unwrap();
    assert_eq!((w.row, w.column), (3, 0), "{c}");
    assert!(
        (w.error - 2.0).abs() < 1e-6,
        "a sign error gives |a − (−a)|/|a| = 2: {c}"
    );
}

#[test]
fn checks_at_a_bound_stay_feasible_and_use_forward_differences() {
    // f is undefined (NaN) below the bound x₀ ≥ 1: a central difference at x₀ = 1 would see NaN.
    let lower = Vector2::new(1.0, f64::NEG_INFINITY);
    let fb = |x: &SVector<f64, 2>| (x[0] - 1.0).sqrt() + x[0] * x[0] + x[1];
    let gb = |x: &SVector<f64, 2>| Vector2::new(0.5 / (x[0] - 1.0).sqrt() + 2.0 * x[0], 1.0);
    let x = Vector2::new(1.0 + 1e-6, 0.0);
    let c = check_gradient_with(fb, gb, &x, &lower, &CheckOptions::default());
    let w = c.worst.unwrap();
    assert!(w.numeric.is_finite() && w.analytic.is_finite(), "{c}");
    assert!(w.numeric > 0.0, "forward slope of √ is positive: {c}");
    // Smooth case at the bound: the forward difference is accurate.
    let fs = |x: &SVector<f64, 2>| x[0] * x[0] + x[1];
    let gs = |x: &SVector<f64, 2>| Vector2::new(2.0 * x[0], 1.0);
    let c = check_gradient_with(
        fs,
        gs,
        &Vector2::new(1.0, 0.0),
        &lower,
        &CheckOptions::default(),
    );
    assert!(c.passes(FORWARD_TOL), "{c}");
    let one_sided_entry = check_gradient_with(
        fs,
        |x| Vector2::new(2.0 * x[0], 0.0),
        &Vector2::new(1.0, 0.0),
        &lower,
        &CheckOptions::default(),
    );
    // Only x₁'s derivative is wrong; x₀'s (at the bound) used a forward difference and passed.
    assert_eq!(one_sided_entry.worst.unwrap().row, 1);
}

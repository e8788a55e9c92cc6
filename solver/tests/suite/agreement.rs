//! Property tests: the three adapters agree on random well-conditioned linear least-squares
//! problems, with the bounds inactive and with the optimum on a bound.

use crate::common;

use common::Linear;
use nalgebra::{SMatrix, SVector, Vector2};
use proptest::prelude::*;
use solver::{solve, SolveOptions, SolverKind};

/// Interior optimum: every adapter converges superlinearly on a quadratic; 1e-8 is the agreement
/// the workbench requires.
const X_TOL: f64 = 1e-8;
/// L-BFGS with nonzero optimal residual: near x* the cost is flat to rounding once
/// |x − x*| ≲ √ε·scale ≈ 1.5e-8, where argmin's line search returns an unchanged cost (observed
/// `|cost_change| = 0`); so L-BFGS agrees to a few times that, not to 1e-8.
const LBFGS_X_TOL: f64 = 1e-7;
/// Optimum on the bound: the change-of-variables adapters stop at x − l = y² with y small but not
/// zero; what they honestly achieve on these problems is within this distance.
const NEAR_BOUND_TOL: f64 = 1e-5;

/// A well-conditioned 4×2 matrix: a scaled identity block plus a bounded perturbation.
fn matrix() -> impl Strategy<Value = SMatrix<f64, 4, 2>> {
    proptest::collection::vec(-0.4..0.4f64, 8).prop_map(|v| {
        let mut a = SMatrix::<f64, 4, 2>::from_column_slice(&v);
        a[(0, 0)] += 1.0;
        a[(1, 1)] += 1.0;
        a
    })
}

// A test helper: JᵀJ is positive definite for these matrices by construction.
#[allow(clippy::unwrap_used)]
fn unconstrained_optimum(a: &SMatrix<f64, 4, 2>, b: &SVector<f64, 4>) -> Vector2<f64> {
    let ata = a.transpose() * a;
    ata.cholesky()
        .map(|c| c.solve(&(a.transpose() * b)))
        .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn adapters_agree_with_inactive_bounds(a in matrix(), b in proptest::collection::vec(-2.0..2.0f64, 4)) {
        let b = SVector::<f64, 4>::from_column_slice(&b);
        let star = unconstrained_optimum(&a, &b);
        // Bounds one unit below the optimum: inactive.
        let p = Linear { a, b, lower: star - Vector2::new(1.0, 1.0) };
        let x0 = star + Vector2::new(0.5, -0.5);
        for kind in SolverKind::ALL {
            let s = solve(kind, &p, x0, &SolveOptions::default()).unwrap();
            prop_assert!(s.report.converged(), "{}: {}", kind, s.report.table());
            let tol = if kind == SolverKind::Lbfgs { LBFGS_X_TOL } else { X_TOL };
            prop_assert!((s.x - star).amax() < tol, "{}: {} vs {} {}", kind, s.x, star, s.report.message());
        }
    }

    #[test]
    fn optimum_on_the_bound(a in matrix(), b in proptest::collection::vec(-2.0..2.0f64, 4), shift in 0.2..1.0f64) {
        let b = SVector::<f64, 4>::from_column_slice(&b);
        let free = unconstrained_optimum(&a, &b);
        // Bound x₀ above the unconstrained optimum: active at the solution, whose x₁ minimises
        // ‖a₁ x₁ − (b − a₀ l₀)‖ (1-D least squares).
        let l0 = free[0] + shift;
        let lower = Vector2::new(l0, f64::NEG_INFINITY);
        let rhs = b - a.column(0) * l0;
        let x1 = a.column(1).dot(&rhs) / a.column(1).norm_squared();
        let grad0 = a.column(0).dot(&(a.column(0) * l0 + a.column(1) * x1 - b));
        // Only keep problems where the bound is strongly active (positive multiplier).
        prop_assume!(grad0 > 1e-2);
        let star = Vector2::new(l0, x1);
        let p = Linear { a, b, lower };
        let x0 = Vector2::new(l0 + 1.0, x1 + 0.5);
        for kind in SolverKind::ALL {
            let s = solve(kind, &p, x0, &SolveOptions::default()).unwrap();
            prop_assert!(s.report.converged(), "{}: {}", kind, s.report.table());
            prop_assert!(s.x[0] >= l0);
            if kind == SolverKind::ExactPenalty {
                prop_assert_eq!(s.x[0], l0, "exactly on the bound");
                prop_assert!((s.x[1] - x1).abs() < X_TOL);
            } else {
                prop_assert!((s.x - star).amax() < NEAR_BOUND_TOL, "{}: {} vs {}", kind, s.x, star);
            }
        }
    }
}

//! The boundary-curve objective: value against its definition, every derivative against finite
//! differences at many random points (also at and near the bound), and eqs 11–14 as printed.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use cost::boundary_curve::printed_eqs_11_to_14;
use cost::{BoundaryCurveObjective, CostError, Weights};
use nalgebra::{SVector, Vector2};
use proptest::prelude::*;
use solver::{
    check_gradient_with, check_jacobian_with, check_second_order, CheckOptions, LeastSquaresProblem,
};

/// Central differences with steps of ε^{1/3}|x| carry relative errors near 1e-10 on these smooth
/// rational functions; 1e-6 leaves room for the large curvature terms near small α while any
/// wrong term (errors of order one) fails by orders of magnitude.
const FD_TOL: f64 = 1e-6;
/// One-sided differences at the bound are first-order accurate: errors near √ε·|f''/f'|.
const FD_TOL_ONE_SIDED: f64 = 1e-4;

fn dir(angle: f64) -> Vector2<f64> {
    Vector2::new(angle.cos(), angle.sin())
}

fn objective(
    th0: f64,
    th1: f64,
    k0: f64,
    k1: f64,
    w: Weights,
    amin: f64,
) -> BoundaryCurveObjective {
    BoundaryCurveObjective::new(dir(th0), dir(th1), [k0, k1], w, amin).expect("valid data")
}

#[test]
fn value_is_the_stated_sum() {
    let w = Weights {
        tangent: 0.7,
        curvature: 2.5,
    };
    let f = objective(0.3, -0.2, -0.5, 1.5, w, 0.05);
    let a = SVector::<f64, 2>::new(0.8, 1.3);
    let [k0, k1] = f.end_curvatures(&a);
    // κ(0) = 2(3 t0×D − α1 t0×t1)/α0² with t0×D = −sin θ0, t0×t1 = sin(θ1 − θ0).
    let c = (-0.5f64).sin();
    let expect_k0 = 2.0 * (3.0 * -(0.3f64.sin()) - 1.3 * c) / 0.64;
    let expect_k1 = 2.0 * (-3.0 * -((-0.2f64).sin()) - 0.8 * c) / 1.69;
    assert!((k0 - expect_k0).abs() < 1e-14 && (k1 - expect_k1).abs() < 1e-14);
    let expected = 0.7 * (0.04 + 0.09) + 2.5 * ((k0 + 0.5).powi(2) + (k1 - 1.5).powi(2));
    assert!((f.objective(&a) - expected).abs() < 1e-13 * expected);
    assert!((f.cost(&a) - 0.5 * expected).abs() < 1e-13 * expected);
}

#[test]
fn gradient_is_eqs_11_to_14_plus_the_tangent_terms() {
    let (t0, t1) = (dir(0.25), dir(-0.4));
    let (k0, k1) = (-0.8, 0.3);
    let f = BoundaryCurveObjective::new(t0, t1, [k0, k1], Weights::default(), 0.05).unwrap();
    for a in [[1.0, 1.0], [0.4, 1.7], [2.2, 0.3]] {
        let g = f.gradient(&SVector::<f64, 2>::new(a[0], a[1]));
        let e = printed_eqs_11_to_14(t0, t1, k0, k1, a);
        let expect = [
            2.0 * (a[0] - 1.0) + e[0] + e[2],
            2.0 * (a[1] - 1.0) + e[1] + e[3],
        ];
        for i in 0..2 {
            assert!(
                (g[i] - expect[i]).abs() < 1e-12 * expect[i].abs().max(1.0),
                "{g} vs {expect:?}"
            );
        }
    }
}

#[test]
fn bad_data_is_refused() {
    let t = dir(0.1);
    let w = Weights::default();
    let nan = Vector2::new(f64::NAN, 0.0);
    assert_eq!(
        BoundaryCurveObjective::new(nan, t, [0.0, 0.0], w, 0.1),
        Err(CostError::NonFinite("t0"))
    );
    assert_eq!(
        BoundaryCurveObjective::new(t, t, [f64::INFINITY, 0.0], w, 0.1),
        Err(CostError::NonFinite("target curvature"))
    );
    let neg = Weights {
        tangent: -1.0,
        curvature: 1.0,
    };
    assert!(matches!(
        BoundaryCurveObjective::new(t, t, [0.0, 0.0], neg, 0.1),
        Err(CostError::BadWeights(..))
    ));
    assert!(matches!(
        BoundaryCurveObjective::new(t, t, [0.0, 0.0], w, 0.0),
        Err(CostError::BadAlphaMin(..))
    ));
}

proptest! {
    /// Residuals' Jacobian, the objective's gradient and the cost's Hessian (the second-order
    /// term) against finite differences, anywhere in the feasible region, including points on and just above the bound.
    #[test]
    fn derivatives_match_finite_differences(
        th0 in -1.2f64..1.2, th1 in -1.2f64..1.2, k0 in -5.0f64..5.0, k1 in -5.0f64..5.0,
        wt in 0.0f64..3.0, wk in 0.1f64..3.0,
        a0 in 0.05f64..3.0, a1 in 0.05f64..3.0, at_bound in 0usize..3,
    ) {
        let amin = 0.05;
        let w = Weights { tangent: wt, curvature: wk };
        let f = objective(th0, th1, k0, k1, w, amin);
        let mut a = SVector::<f64, 2>::new(a0, a1);
        if at_bound == 1 { a[0] = amin; }
        if at_bound == 2 { a[1] = amin * (1.0 + 1e-9); }
        let lower = f.lower_bounds();
        // Values reach 10²–10³ near small α, so central differences carry absolute noise near
        // 1e-9: entries below 1e-4 compare absolutely against that floor.
        let opts = CheckOptions { floor: 1e-4 };
        let jc = check_jacobian_with(|x| f.residuals(x), |x| f.jacobian(x), &a, &lower, &opts);
        let gc = check_gradient_with(|x| f.objective(x), |x| f.gradient(x), &a, &lower, &opts);
        // The Hessian JᵀJ + S (with the second-order term) against differences of Jᵀr.
        let hc = check_second_order(&f, &a, &opts).expect("the objective gives S");
        for c in [&jc, &gc, &hc] {
            let w = c.worst.expect("entries checked");
            let tol = if w.one_sided { FD_TOL_ONE_SIDED } else { FD_TOL };
            prop_assert!(w.error <= tol, "{}", c);
        }
    }

    /// Eqs 11–14 as printed in the techreport are the partials of the curvature terms (9) and
    /// (10): checked against finite differences of (κ(0) − k0)² and (κ(1) − k1)².
    #[test]
    fn printed_eqs_11_to_14_match_finite_differences(
        th0 in -1.2f64..1.2, th1 in -1.2f64..1.2, k0 in -5.0f64..5.0, k1 in -5.0f64..5.0,
        a0 in 0.1f64..3.0, a1 in 0.1f64..3.0,
    ) {
        let (t0, t1) = (dir(th0), dir(th1));
        let f = BoundaryCurveObjective::new(t0, t1, [k0, k1], Weights::default(), 0.05).unwrap();
        let term = |i: usize| move |x: &SVector<f64, 2>| (f.end_curvatures(x)[i] - [k0, k1][i]).powi(2);
        let e = printed_eqs_11_to_14(t0, t1, k0, k1, [a0, a1]);
        let a = SVector::<f64, 2>::new(a0, a1);
        let lower = SVector::<f64, 2>::from_element(f64::NEG_INFINITY);
        // Values reach 10²–10³ near small α, so central differences carry absolute noise near
        // 1e-9: entries below 1e-4 compare absolutely against that floor.
        let opts = CheckOptions { floor: 1e-4 };
        let c9 = check_gradient_with(term(0), |_| SVector::<f64, 2>::new(e[0], e[1]), &a, &lower, &opts);
        let c10 = check_gradient_with(term(1), |_| SVector::<f64, 2>::new(e[2], e[3]), &a, &lower, &opts);
        prop_assert!(c9.max_error() <= FD_TOL, "eqs 11/12: {}", c9);
        prop_assert!(c10.max_error() <= FD_TOL, "eqs 13/14: {}", c10);
    }
}

//! The fixed-size fast paths against the backends they transcribe: `solve` (and `solve_lm`,
//! `solve_lbfgs`) must return **bit for bit** what the reference paths through the
//! `levenberg-marquardt` crate (`solve_lm_crate`) and argmin (`solve_lbfgs_argmin`) return —
//! the same point, the same termination with the same measured values, the same counts and
//! cost history. Only `time_seconds` may differ.

mod common;

use common::{EndCurvature, Linear, Misra1a, Rosenbrock};
use nalgebra::{SMatrix, SVector, Vector2};
use proptest::prelude::*;
use solver::{LeastSquaresProblem, Solution, SolveOptions, SolverKind};

/// The whole report but the timing, printed with `{:?}` (so NaN equals NaN and −0 differs
/// from +0).
fn fingerprint<const N: usize>(s: &Solution<N>) -> String {
    let mut r = s.report.clone();
    r.time_seconds = 0.0;
    format!("{:?} {:?}", s.x, r)
}

/// Every fast path against its reference on one problem and start, with and without history
/// and with a small iteration limit.
fn check<P, const N: usize, const M: usize>(p: &P, x0: SVector<f64, N>)
where
    P: LeastSquaresProblem<N, M>,
    solver::Dims<N, M>: solver::LmDims<N, M>,
{
    for options in [
        SolveOptions::default(),
        SolveOptions {
            record_history: false,
            ..SolveOptions::default()
        },
        SolveOptions {
            max_iterations: 0,
            ..SolveOptions::default()
        },
        SolveOptions {
            max_iterations: 1,
            ..SolveOptions::default()
        },
        SolveOptions {
            max_iterations: 2,
            ..SolveOptions::default()
        },
        SolveOptions {
            function_tolerance: 1e-6,
            step_tolerance: 1e-6,
            gradient_tolerance: 1e-6,
            ..SolveOptions::default()
        },
    ] {
        let pairs = [
            (
                solver::solve(SolverKind::Lm, p, x0, &options),
                solver::solve_lm_crate(p, x0, &options),
            ),
            (
                solver::solve(SolverKind::Lbfgs, p, x0, &options),
                solver::solve_lbfgs_argmin(p, x0, &options),
            ),
        ];
        for (fast, reference) in pairs {
            match (fast, reference) {
                (Ok(a), Ok(b)) => assert_eq!(fingerprint(&a), fingerprint(&b), "from {x0}"),
                (a, b) => assert_eq!(a.is_err(), b.is_err()),
            }
        }
    }
}

#[test]
fn fixed_problems() {
    check(&EndCurvature::representative(), Vector2::new(1.0, 1.0));
    check(&EndCurvature::representative(), Vector2::new(0.05, 3.0));
    for lower_x2 in [f64::NEG_INFINITY, -1.5, 1.5] {
        let p = Rosenbrock { lower_x2 };
        check(&p, Vector2::new(-1.2, 1.6));
        check(&p, Vector2::new(1.2, 1.6));
        check(&p, Vector2::new(-2.0, 1.5));
    }
    check(&Misra1a, Vector2::new(500.0, 1e-4));
    check(&Misra1a, Vector2::new(250.0, 5e-4));
    check(&Box3d, SVector::<f64, 3>::new(0.0, 10.0, 20.0));
    check(&Box3d, SVector::<f64, 3>::new(1.0, 1.0, 1.0));
    check(&Blowup, Vector2::new(1.0, 1.0));
    check(&Square, SVector::<f64, 2>::new(0.0, 0.0));
    check(&Square, SVector::<f64, 2>::new(3.0, -1.0));
    check(&Exp1, SVector::<f64, 1>::new(0.5));
    check(&Exp1, SVector::<f64, 1>::new(-2.0));
}

/// One unknown, 20 residuals: `r_i = exp(x t_i) − (1 + t_i)`, a nonzero-residual fit.
struct Exp1;

impl LeastSquaresProblem<1, 20> for Exp1 {
    fn residuals(&self, x: &SVector<f64, 1>) -> SVector<f64, 20> {
        SVector::from_fn(|i, _| {
            let t = i as f64 / 19.0;
            (x[0] * t).exp() - (1.0 + t)
        })
    }
    fn jacobian(&self, x: &SVector<f64, 1>) -> SMatrix<f64, 20, 1> {
        SMatrix::from_fn(|i, _| {
            let t = i as f64 / 19.0;
            t * (x[0] * t).exp()
        })
    }
}

/// MINPACK's Box three-dimensional function (10 residuals, 3 unknowns, zero residual at
/// (1, 10, 1)).
struct Box3d;

impl LeastSquaresProblem<3, 10> for Box3d {
    fn residuals(&self, x: &SVector<f64, 3>) -> SVector<f64, 10> {
        SVector::from_fn(|i, _| {
            let t = 0.1 * (i + 1) as f64;
            (-t * x[0]).exp() - (-t * x[1]).exp() - x[2] * ((-t).exp() - (-10.0 * t).exp())
        })
    }
    fn jacobian(&self, x: &SVector<f64, 3>) -> SMatrix<f64, 10, 3> {
        SMatrix::from_fn(|i, k| {
            let t = 0.1 * (i + 1) as f64;
            match k {
                0 => -t * (-t * x[0]).exp(),
                1 => t * (-t * x[1]).exp(),
                _ => -((-t).exp() - (-10.0 * t).exp()),
            }
        })
    }
}

/// Undefined (NaN) for x₀ + x₁ < 1.5: trial points there are rejected.
struct Blowup;

impl LeastSquaresProblem<2, 3> for Blowup {
    fn residuals(&self, x: &SVector<f64, 2>) -> SVector<f64, 3> {
        let s = (x[0] + x[1] - 1.5).sqrt();
        SVector::<f64, 3>::new(s - 0.1, x[0] - 3.0, x[1] + 2.0)
    }
    fn jacobian(&self, x: &SVector<f64, 2>) -> SMatrix<f64, 3, 2> {
        let d = 0.5 / (x[0] + x[1] - 1.5).sqrt();
        SMatrix::<f64, 3, 2>::new(d, d, 1.0, 0.0, 0.0, 1.0)
    }
}

/// A zero-residual square problem with a rank-deficient Jacobian at the start.
struct Square;

impl LeastSquaresProblem<2, 2> for Square {
    fn residuals(&self, x: &SVector<f64, 2>) -> SVector<f64, 2> {
        Vector2::new(x[0] * x[0] - 1.0, x[0] * x[1] - 2.0)
    }
    fn jacobian(&self, x: &SVector<f64, 2>) -> SMatrix<f64, 2, 2> {
        SMatrix::<f64, 2, 2>::new(2.0 * x[0], 0.0, x[1], x[0])
    }
}

/// A boundary problem from tangent angles, targets and a start.
fn end_curvature(th0: f64, th1: f64, k0: f64, k1: f64) -> EndCurvature {
    let t0 = (th0.cos(), th0.sin());
    let t1 = (th1.cos(), th1.sin());
    EndCurvature {
        c: t0.0 * t1.1 - t0.1 * t1.0,
        d0: -t0.1,
        d1: -t1.1,
        k0,
        k1,
        alpha_min: 0.05,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn boundary_problems(
        th0 in -1.2..1.2f64, th1 in -1.2..1.2f64, k0 in -3.0..3.0f64, k1 in -3.0..3.0f64,
        a0 in 0.05..2.5f64, a1 in 0.05..2.5f64,
    ) {
        check(&end_curvature(th0, th1, k0, k1), Vector2::new(a0, a1));
    }

    #[test]
    fn linear_problems(v in proptest::collection::vec(-1.0..1.0f64, 12), l in -2.0..0.5f64) {
        let a = SMatrix::<f64, 4, 2>::from_column_slice(&v[..8]);
        let b = SVector::<f64, 4>::from_column_slice(&v[8..]);
        let p = Linear { a, b, lower: Vector2::new(l, f64::NEG_INFINITY) };
        check(&p, Vector2::new(l.max(0.5), 0.5));
    }
}

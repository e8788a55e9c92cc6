//! Generic solvers for small bound-constrained nonlinear least-squares problems.
//!
//! This crate knows nothing of geometry: a problem is a residual vector `r(x) ∈ ℝᴹ` of `N`
//! unknowns with its Jacobian and simple lower bounds `x ≥ l` ([`LeastSquaresProblem`]). It
//! provides
//!
//! - three solver adapters selectable by name ([`SolverKind`]: `exact-penalty`, `lbfgs`, `lm`)
//!   behind one entry point, [`solve`];
//! - convergence reports a Ceres or SciPy user recognises ([`SolveReport`]), serialisable to JSON;
//! - finite-difference derivative checks for other crates' tests ([`check_jacobian`],
//!   [`check_gradient`], [`check_problem`]).
//!
//! **Costs in reports are `½‖r‖²`** (Ceres/SciPy); the seed papers' objective is `‖r‖²`, twice
//! that — see [`problem`].
//!
//! All arithmetic is `f64` on fixed-size nalgebra types (`SVector<f64, N>`, `SMatrix<f64, M, N>`),
//! so the exact-penalty adapter allocates nothing per iteration.
//!
//! # Fast paths and reference paths
//!
//! [`solve`] — what the boundary curves (2 unknowns, 4 residuals) and every other fixed-size
//! caller use — runs each adapter on a **fixed-size fast path**:
//!
//! - `exact-penalty` is this crate's own code; its 2×2 model system is solved in closed form
//!   (`small`), and it takes Newton steps where the problem gives its second-order term
//!   ([`LeastSquaresProblem::second_order_term`]).
//! - `lm` runs, for two unknowns, `lm_nielsen`: a hand-written Levenberg–Marquardt iteration
//!   (Nielsen's damping, the 2×2 damped normal equations in closed form, MINPACK's tests); for
//!   other sizes with `M ≥ N`, `lm_fixed`, the `levenberg-marquardt` crate's MINPACK `lmder`
//!   (pivoted QR, `lmpar`, `qrsolv`) transcribed over fixed-size arrays.
//! - `lbfgs` runs `lbfgs_fixed`, one argmin `Executor` run of `LBFGS` with
//!   `MoreThuenteLineSearch` transcribed (no executor, observers, state clones or `HashMap`
//!   counters; cost and gradient from one [`ObjectiveProblem::value_and_gradient`] call; the
//!   gradient argmin recomputes at each accepted point reused, and counted as argmin counts it).
//!
//! The transcriptions (`lbfgs_fixed`, `lm_fixed`) perform the backends' floating-point operations
//! in the backends' order, so they return **the same points, termination reasons, iteration and
//! evaluation counts and cost histories, bit for bit**, as the backends themselves;
//! `lm_nielsen` returns the same optima to the agreement tolerances (and the same kind of
//! termination); `tests/suite/fast_paths.rs` checks both on fixed and random problems. The backends stay available as the reference paths:
//! [`solve_lm_crate`] and [`solve_lbfgs_argmin`] (fixed size), and [`solve_any`], which runs
//! [`solve_lm_any`] (dynamic matrices, any number of residuals) and argmin for problems of any
//! size. `cargo run --release -p solver --example profile_solvers -- lm` is a loop for `perf`.
//!
//! ```
//! use nalgebra::{SMatrix, SVector, Vector2};
//! use solver::{solve, LeastSquaresProblem, SolveOptions, SolverKind};
//!
//! /// Rosenbrock as least squares: r = (10(x₂ − x₁²), 1 − x₁).
//! struct Rosenbrock;
//! impl LeastSquaresProblem<2, 2> for Rosenbrock {
//!     fn residuals(&self, x: &SVector<f64, 2>) -> SVector<f64, 2> {
//!         Vector2::new(10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0])
//!     }
//!     fn jacobian(&self, x: &SVector<f64, 2>) -> SMatrix<f64, 2, 2> {
//!         SMatrix::<f64, 2, 2>::new(-20.0 * x[0], 10.0, -1.0, 0.0)
//!     }
//! }
//!
//! let kind: SolverKind = "exact-penalty".parse()?;
//! let solution = solve(kind, &Rosenbrock, Vector2::new(-1.2, 1.0), &SolveOptions::default())?;
//! assert!(solution.report.converged());
//! assert!((solution.x - Vector2::new(1.0, 1.0)).norm() < 1e-8);
//! println!("{}", solution.report.brief());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod bounds;
pub mod check;
mod error;
pub mod exact_penalty;
mod kind;
pub mod lbfgs;
mod lbfgs_fixed;
pub mod lm;
mod lm_fixed;
mod lm_nielsen;
mod options;
pub mod problem;
pub mod report;
mod small;

use nalgebra::SVector;

pub use check::{
    check_gradient, check_gradient_with, check_jacobian, check_jacobian_with, check_problem,
    check_second_order, CheckOptions, DerivativeCheck, WorstEntry,
};
pub use error::SolveError;
pub use exact_penalty::solve_exact_penalty;
pub use kind::{SolverKind, UnknownSolver};
pub use lbfgs::{minimize_lbfgs, minimize_lbfgs_argmin, solve_lbfgs, solve_lbfgs_argmin};
pub use lm::{solve_lm, solve_lm_any, solve_lm_crate, Dims, LmDims};
pub use options::SolveOptions;
pub use problem::{HalfSumOfSquares, LeastSquaresProblem, ObjectiveProblem, SecantModel};
pub use report::{ConvergenceTest, FailureReason, SolveReport, Termination};

/// A solver's result: the best point found and the report.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution<const N: usize> {
    /// The returned point (feasible, the best found).
    pub x: SVector<f64, N>,
    /// What the solver did and why it stopped.
    pub report: SolveReport,
}

/// Solves `min ½‖r(x)‖² s.t. x ≥ l` from `x0` with the adapter `kind`.
///
/// A solver that does not converge still returns `Ok`, with its best point and a report saying
/// why it stopped. The bound `Dims<N, M>: LmDims<N, M>` holds for every concrete size up to 127.
/// Every adapter runs its fixed-size fast path (see the crate documentation).
///
/// # Errors
/// [`SolveError`] only for invalid input: a non-finite start, a start below its lower bound, a
/// NaN or `+∞` lower bound, or an invalid tolerance.
pub fn solve<P, const N: usize, const M: usize>(
    kind: SolverKind,
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: LeastSquaresProblem<N, M>,
    Dims<N, M>: LmDims<N, M>,
{
    match kind {
        SolverKind::ExactPenalty => solve_exact_penalty(problem, x0, options),
        SolverKind::Lbfgs => solve_lbfgs(problem, x0, options),
        SolverKind::Lm => solve_lm(problem, x0, options),
    }
}

/// [`solve`] for problems of any size, through the backends themselves (the reference paths):
/// Levenberg–Marquardt through [`solve_lm_any`] (the crate on dynamic linear algebra, no bound on
/// the number of residuals), L-BFGS through argmin ([`solve_lbfgs_argmin`]), exact penalty as in
/// [`solve`]. Use [`solve`] where its bound holds: its fast paths give the same results sooner.
///
/// # Errors
/// As [`solve`].
pub fn solve_any<P, const N: usize, const M: usize>(
    kind: SolverKind,
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: LeastSquaresProblem<N, M>,
{
    match kind {
        SolverKind::ExactPenalty => solve_exact_penalty(problem, x0, options),
        SolverKind::Lbfgs => solve_lbfgs_argmin(problem, x0, options),
        SolverKind::Lm => solve_lm_any(problem, x0, options),
    }
}

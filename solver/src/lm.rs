//! Levenberg–Marquardt (the `levenberg-marquardt` 0.15 crate, a port of MINPACK's `lmder`), bounds
//! by the change of variables `x = l + y²`.
//!
//! # Paths
//!
//! [`solve_lm`] (what [`crate::solve`] runs) uses, for two unknowns (every boundary curve), a
//! hand-written Levenberg–Marquardt iteration with Nielsen's damping on the closed-form 2×2
//! normal equations (`lm_nielsen`; Madsen, Nielsen & Tingleff 2004, Algorithm 3.16: different
//! iterates from MINPACK's, the same optima to the adapters' agreement tolerances), and for other
//! sizes with `M ≥ N` a fixed-size transcription of the crate's `minimize` (`lm_fixed`: the same
//! floating-point operations in the same order, so the same iterates, counts and termination);
//! [`solve_lm_crate`] runs the crate itself on fixed-size matrices (the reference) and
//! [`solve_lm_any`] on dynamic ones (any number of residuals). All share this wrapper (bounds,
//! counts, the mapping of termination reasons), so their reports mean the same.
//!
//! # Bounds
//!
//! The crate has no bounds, so the adapter solves for `y` with residuals `r(l + y²)` and Jacobian
//! `J(x)·diag(∂x/∂y)`; see [`crate::bounds`] for the choice of `y²` and its behaviour at a bound.
//! Every point the crate tries is feasible by construction.
//!
//! # Tests, counts and limits
//!
//! The crate's `MinimizationReport` holds only the
//! termination, the number of residual evaluations and `½‖r‖²`, so the wrapper counts Jacobian
//! evaluations itself and takes one outer iteration per Jacobian evaluation (`iterations`). It
//! also keeps the best point evaluated, because a run the crate ends inside its inner loop can
//! leave a rejected trial point in the problem.
//!
//! - `function_tolerance` → the crate's `ftol` (relative actual and predicted reduction);
//!   `step_tolerance` → `xtol` (trust-region radius relative to `‖D y‖`); `gradient_tolerance` →
//!   `gtol`, the cosine between `r` and the columns of the Jacobian. The report's numbers for
//!   these tests are measured by the wrapper: the relative cost change and relative step of the
//!   last iteration, and the largest cosine at the returned point.
//! - If a test passes only at machine precision (the crate's `NoImprovementPossible`), the report
//!   says converged with tolerance `f64::EPSILON`.
//! - `max_iterations` is enforced by refusing a further Jacobian evaluation
//!   ([`Termination::MaxIterations`]); the crate's own limit of `patience·(N + 1)` residual
//!   evaluations, with `patience = 4·max_iterations`, gives [`Termination::MaxEvaluations`].
//! - Non-finite residuals at a trial point are replaced by residuals of size `1e100`, so the crate
//!   rejects the step and shrinks its trust region instead of stopping there.
//!
//! Reference: J. J. Moré, "The Levenberg–Marquardt algorithm: implementation and theory",
//! *Lecture Notes in Mathematics* 630, 1978.

use levenberg_marquardt::{LevenbergMarquardt, MinimizationReport, TerminationReason};
use nalgebra::allocator::{Allocator, Reallocator};
use nalgebra::{
    Const, DMatrix, DVector, DefaultAllocator, DimMax, DimMaximum, DimMin, Dyn, Owned, SMatrix,
    SVector, VecStorage, U1,
};
use std::cell::{Cell, RefCell};
use std::time::Instant;

use crate::bounds::{projected_gradient_norm, validate_start, SquareMap};
use crate::{
    ConvergenceTest, FailureReason, LeastSquaresProblem, Solution, SolveError, SolveOptions,
    SolverKind, Termination,
};

/// Size given to each residual at a trial point where the model is not finite.
const REJECT: f64 = 1e100;

/// Dimension pairs the fixed-size Levenberg–Marquardt backend accepts: every `N, M` that nalgebra
/// maps to type-level integers (up to 127), so concrete sizes never notice this bound.
pub trait LmDims<const N: usize, const M: usize> {
    /// Runs the crate's minimiser on `target`.
    fn minimize<T>(lm: &LevenbergMarquardt<f64>, target: T) -> (T, MinimizationReport<f64>)
    where
        T: levenberg_marquardt::LeastSquaresProblem<
            f64,
            Const<M>,
            Const<N>,
            ResidualStorage = Owned<f64, Const<M>>,
            JacobianStorage = Owned<f64, Const<M>, Const<N>>,
            ParameterStorage = Owned<f64, Const<N>>,
        >;
}

/// The marker type implementing [`LmDims`] for supported sizes.
#[derive(Debug, Clone, Copy)]
pub struct Dims<const N: usize, const M: usize>;

impl<const N: usize, const M: usize> LmDims<N, M> for Dims<N, M>
where
    Const<M>: DimMin<Const<N>> + DimMax<Const<N>>,
    DefaultAllocator: Allocator<DimMaximum<Const<M>, Const<N>>, Const<N>>
        + Reallocator<f64, Const<M>, Const<N>, DimMaximum<Const<M>, Const<N>>, Const<N>>,
{
    fn minimize<T>(lm: &LevenbergMarquardt<f64>, target: T) -> (T, MinimizationReport<f64>)
    where
        T: levenberg_marquardt::LeastSquaresProblem<
            f64,
            Const<M>,
            Const<N>,
            ResidualStorage = Owned<f64, Const<M>>,
            JacobianStorage = Owned<f64, Const<M>, Const<N>>,
            ParameterStorage = Owned<f64, Const<N>>,
        >,
    {
        lm.minimize(target)
    }
}

/// The crate's settings as the adapter chooses them (built into a `LevenbergMarquardt` for the
/// crate's paths, read directly by the fixed-size transcription).
struct LmSettings {
    ftol: f64,
    xtol: f64,
    gtol: f64,
    patience: usize,
}

impl LmSettings {
    fn build(&self) -> LevenbergMarquardt<f64> {
        LevenbergMarquardt::new()
            .with_ftol(self.ftol)
            .with_xtol(self.xtol)
            .with_gtol(self.gtol)
            .with_patience(self.patience)
    }
}

/// The problem in transformed variables, with counters and the best point seen.
struct Target<'a, P, const N: usize, const M: usize> {
    problem: &'a P,
    map: SquareMap<N>,
    y: SVector<f64, N>,
    residual_evaluations: Cell<usize>,
    jacobian_evaluations: Cell<usize>,
    max_jacobians: usize,
    hit_limit: Cell<bool>,
    /// Cost of the latest residual evaluation (that of the current `y` when a Jacobian is asked).
    last_cost: Cell<f64>,
    /// `(cost, y, r(y))` at the lowest cost evaluated.
    best: Cell<(f64, SVector<f64, N>, SVector<f64, M>)>,
    /// `(cost, y)` at the start of the previous and the current outer iteration.
    iterates: Cell<[(f64, SVector<f64, N>); 2]>,
    history: Option<RefCell<Vec<f64>>>,
}

impl<P, const N: usize, const M: usize> Target<'_, P, N, M>
where
    P: LeastSquaresProblem<N, M>,
{
    #[inline]
    fn eval_residuals(&self) -> Option<SVector<f64, M>> {
        self.residual_evaluations
            .set(self.residual_evaluations.get() + 1);
        let r = self.problem.residuals(&self.map.to_x(&self.y));
        let cost = 0.5 * r.norm_squared();
        if !cost.is_finite() {
            self.last_cost.set(f64::INFINITY);
            return Some(SVector::from_element(REJECT));
        }
        self.last_cost.set(cost);
        if cost < self.best.get().0 {
            self.best.set((cost, self.y, r));
        }
        Some(r)
    }

    #[inline]
    fn eval_jacobian(&self) -> Option<SMatrix<f64, M, N>> {
        let count = self.jacobian_evaluations.get();
        if count >= self.max_jacobians {
            self.hit_limit.set(true);
            return None;
        }
        self.jacobian_evaluations.set(count + 1);
        let [_, current] = self.iterates.get();
        self.iterates.set([current, (self.last_cost.get(), self.y)]);
        if count > 0 {
            if let Some(h) = &self.history {
                h.borrow_mut().push(self.last_cost.get());
            }
        }
        let j = self.problem.jacobian(&self.map.to_x(&self.y));
        let d = self.map.dx_dy(&self.y);
        Some(SMatrix::from_fn(|i, k| j[(i, k)] * d[k]))
    }
}

/// The fixed-size view of the problem (stack-allocated vectors and matrices): the fast path for
/// the sizes [`LmDims`] accepts.
impl<P, const N: usize, const M: usize>
    levenberg_marquardt::LeastSquaresProblem<f64, Const<M>, Const<N>> for Target<'_, P, N, M>
where
    P: LeastSquaresProblem<N, M>,
{
    type ResidualStorage = Owned<f64, Const<M>>;
    type JacobianStorage = Owned<f64, Const<M>, Const<N>>;
    type ParameterStorage = Owned<f64, Const<N>>;

    fn set_params(&mut self, y: &SVector<f64, N>) {
        self.y = *y;
    }

    fn params(&self) -> SVector<f64, N> {
        self.y
    }

    fn residuals(&self) -> Option<SVector<f64, M>> {
        self.eval_residuals()
    }

    fn jacobian(&self) -> Option<SMatrix<f64, M, N>> {
        self.eval_jacobian()
    }
}

impl<P, const N: usize, const M: usize> crate::lm_fixed::FixedTarget<N, M> for Target<'_, P, N, M>
where
    P: LeastSquaresProblem<N, M>,
{
    #[inline]
    fn set_params(&mut self, y: &SVector<f64, N>) {
        self.y = *y;
    }

    #[inline]
    fn residuals(&self) -> Option<SVector<f64, M>> {
        self.eval_residuals()
    }

    #[inline]
    fn jacobian(&self) -> Option<SMatrix<f64, M, N>> {
        self.eval_jacobian()
    }
}

/// The same problem with heap-allocated (dynamically sized) vectors and matrices, for sizes
/// beyond the fixed-size backend's bound (more than 127 residuals).
struct DynTarget<'a, P, const N: usize, const M: usize>(Target<'a, P, N, M>);

impl<P, const N: usize, const M: usize> levenberg_marquardt::LeastSquaresProblem<f64, Dyn, Dyn>
    for DynTarget<'_, P, N, M>
where
    P: LeastSquaresProblem<N, M>,
{
    type ResidualStorage = VecStorage<f64, Dyn, U1>;
    type JacobianStorage = VecStorage<f64, Dyn, Dyn>;
    type ParameterStorage = VecStorage<f64, Dyn, U1>;

    fn set_params(&mut self, y: &DVector<f64>) {
        self.0.y = SVector::from_iterator(y.iter().copied());
    }

    fn params(&self) -> DVector<f64> {
        DVector::from_column_slice(self.0.y.as_slice())
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.0
            .eval_residuals()
            .map(|r| DVector::from_column_slice(r.as_slice()))
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.0
            .eval_jacobian()
            .map(|j| DMatrix::from_column_slice(M, N, j.as_slice()))
    }
}

/// Solves `min ½‖r(x)‖² s.t. x ≥ l` with the `levenberg-marquardt` crate's algorithm on
/// fixed-size (stack) linear algebra: the fast path, for every size up to 127 residuals.
///
/// For two unknowns and at least two residuals (the boundary curve's 4 × 2 among them) a
/// hand-written iteration runs (`lm_nielsen`: Nielsen's damping, closed-form 2×2 steps, MINPACK's
/// tests; the same optima as the crate to the agreement tolerances, not the same iterates). With
/// other sizes and at least as many residuals as unknowns the crate's `minimize` runs as a
/// fixed-size transcription (`lm_fixed`, the same floating-point operations in the same order,
/// so the same iterates and report, without the generic machinery); otherwise the crate itself
/// runs on fixed-size matrices. [`solve_lm_crate`] always runs the crate.
///
/// # Errors
/// [`SolveError`] for invalid options, a non-finite start, invalid bounds or a start below a bound.
pub fn solve_lm<P, const N: usize, const M: usize>(
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: LeastSquaresProblem<N, M>,
    Dims<N, M>: LmDims<N, M>,
{
    if M < N || N == 0 {
        return solve_lm_crate(problem, x0, options);
    }
    solve_lm_with(problem, x0, options, |lm, mut target| {
        let config = crate::lm_fixed::Config {
            ftol: lm.ftol,
            xtol: lm.xtol,
            gtol: lm.gtol,
            patience: lm.patience,
        };
        let y0 = target.y;
        let termination = if N == 2 {
            crate::lm_nielsen::minimize(&config, &mut target, y0)
        } else {
            crate::lm_fixed::minimize(&config, &mut target, y0)
        };
        (target, termination)
    })
}

/// [`solve_lm`] through the `levenberg-marquardt` crate's own `minimize` on fixed-size
/// matrices: the reference for the fast path (same results; kept available and tested).
///
/// # Errors
/// As [`solve_lm`].
pub fn solve_lm_crate<P, const N: usize, const M: usize>(
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: LeastSquaresProblem<N, M>,
    Dims<N, M>: LmDims<N, M>,
{
    solve_lm_with(problem, x0, options, |lm, target| {
        let (t, report) = <Dims<N, M> as LmDims<N, M>>::minimize(&lm.build(), target);
        (t, report.termination)
    })
}

/// [`solve_lm`] for problems of any size: the same algorithm and report with heap-allocated
/// (dynamically sized) linear algebra, so it has no bound on the number of residuals (the
/// fairing problems have 162 and 180). Slower on small problems than [`solve_lm`], which is the
/// one to use where its bound holds.
///
/// # Errors
/// As [`solve_lm`].
pub fn solve_lm_any<P, const N: usize, const M: usize>(
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: LeastSquaresProblem<N, M>,
{
    solve_lm_with(problem, x0, options, |lm, target| {
        let (t, report) = lm.build().minimize(DynTarget(target));
        (t.0, report.termination)
    })
}

/// The adapter around a minimizer of the crate (fixed-size or dynamic).
fn solve_lm_with<'p, P, const N: usize, const M: usize>(
    problem: &'p P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
    minimize: impl FnOnce(&LmSettings, Target<'p, P, N, M>) -> (Target<'p, P, N, M>, TerminationReason),
) -> Result<Solution<N>, SolveError>
where
    P: LeastSquaresProblem<N, M>,
{
    let start = Instant::now();
    options.validate()?;
    let lower = problem.lower_bounds();
    validate_start(&x0, &lower)?;
    let map = SquareMap::new(lower);
    let y0 = map.to_y(&x0);
    let initial_cost = problem.cost(&x0);

    let reporter = crate::report::Reporter {
        solver: SolverKind::Lm,
        initial_cost,
        start,
    };
    if !initial_cost.is_finite() {
        let termination = Termination::Failure {
            reason: FailureReason::NonFiniteCost,
        };
        return Ok(reporter.solution(x0, initial_cost, f64::NAN, termination, 0, 1, 0, Vec::new()));
    }

    let patience = options.max_iterations.max(1).saturating_mul(4);
    let lm = LmSettings {
        ftol: options.function_tolerance,
        xtol: options.step_tolerance,
        gtol: options.gradient_tolerance,
        patience,
    };
    let y_start = map.to_y(&x0);
    let target = Target::<P, N, M> {
        problem,
        map,
        y: y0,
        residual_evaluations: Cell::new(0),
        jacobian_evaluations: Cell::new(0),
        max_jacobians: options.max_iterations,
        hit_limit: Cell::new(false),
        last_cost: Cell::new(f64::INFINITY),
        best: Cell::new((f64::INFINITY, y0, SVector::zeros())),
        iterates: Cell::new([(f64::INFINITY, y0); 2]),
        history: options
            .record_history
            .then(|| RefCell::new(Vec::with_capacity(16))),
    };
    let (target, lm_termination) = minimize(&lm, target);

    let (best_cost, best_y, best_r) = target.best.get();
    let y = if best_cost.is_finite() {
        best_y
    } else {
        y_start
    };
    let x = map.to_x(&y);
    // The Jacobian at the returned point, for the report; its residuals were kept (the same
    // evaluation at the same `x`).
    let r = if best_cost.is_finite() {
        best_r
    } else {
        problem.residuals(&x)
    };
    let j = problem.jacobian(&x);
    let final_cost = 0.5 * r.norm_squared();
    let g = j.transpose() * r;
    let gnorm_x = projected_gradient_norm(&x, &g, &lower);
    let iterations = target.jacobian_evaluations.get();
    let [(prev_cost, prev_y), _] = target.iterates.get();
    let last_change = || {
        let (c0, y0) = if iterations >= 1 && prev_cost.is_finite() && iterations > 1 {
            (prev_cost, prev_y)
        } else {
            (initial_cost, y_start)
        };
        let rel_cost = if c0 > 0.0 {
            (c0 - final_cost).abs() / c0
        } else {
            0.0
        };
        let rel_step = (y - y0).norm() / (y.norm() + options.step_tolerance);
        (rel_cost, rel_step)
    };
    let cosine = || {
        let jy = SMatrix::<f64, M, N>::from_fn(|i, k| j[(i, k)] * map.dx_dy(&y)[k]);
        let rn = r.norm();
        (0..N)
            .map(|k| {
                let cn = jy.column(k).norm();
                if cn == 0.0 || rn == 0.0 {
                    0.0
                } else {
                    jy.column(k).dot(&r).abs() / (cn * rn)
                }
            })
            .fold(0.0, f64::max)
    };
    let converged = |test| Termination::Converged { test };
    let termination = match lm_termination {
        TerminationReason::ResidualsZero => {
            converged(ConvergenceTest::ZeroResidual { cost: final_cost })
        }
        TerminationReason::Orthogonal => converged(ConvergenceTest::Gradient {
            norm: cosine(),
            tolerance: options.gradient_tolerance,
        }),
        TerminationReason::Converged { ftol: true, .. } => converged(ConvergenceTest::CostChange {
            relative_change: last_change().0,
            tolerance: options.function_tolerance,
        }),
        TerminationReason::Converged { .. } => converged(ConvergenceTest::Step {
            relative_step: last_change().1,
            tolerance: options.step_tolerance,
        }),
        TerminationReason::NoImprovementPossible("ftol") => {
            converged(ConvergenceTest::CostChange {
                relative_change: last_change().0,
                tolerance: f64::EPSILON,
            })
        }
        TerminationReason::NoImprovementPossible("xtol") => converged(ConvergenceTest::Step {
            relative_step: last_change().1,
            tolerance: f64::EPSILON,
        }),
        TerminationReason::NoImprovementPossible(_) => converged(ConvergenceTest::Gradient {
            norm: cosine(),
            tolerance: f64::EPSILON,
        }),
        TerminationReason::User(_) if target.hit_limit.get() => Termination::MaxIterations {
            limit: options.max_iterations,
        },
        TerminationReason::LostPatience => Termination::MaxEvaluations {
            limit: patience.saturating_mul(N + 1),
        },
        TerminationReason::Numerical("jacobian") => Termination::Failure {
            reason: FailureReason::NonFiniteDerivative,
        },
        other => Termination::Failure {
            reason: FailureReason::Backend {
                message: format!("levenberg-marquardt: {other:?}"),
            },
        },
    };
    let history = match target.history {
        Some(h) => {
            let mut h = h.into_inner();
            h.insert(0, initial_cost);
            h.push(final_cost);
            h
        }
        None => Vec::new(),
    };
    Ok(reporter.solution(
        x,
        final_cost,
        gnorm_x,
        termination,
        iterations,
        // The start's cost, and the returned point's residuals unless they were kept.
        target.residual_evaluations.get() + if best_cost.is_finite() { 1 } else { 2 },
        iterations + 1,
        history,
    ))
}

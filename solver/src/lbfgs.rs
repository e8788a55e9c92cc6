//! L-BFGS (argmin 0.11) with the Moré–Thuente line search, bounds by the change of variables
//! `x = l + y²`.
//!
//! # Paths
//!
//! [`minimize_lbfgs`] / [`solve_lbfgs`] (what [`crate::solve`] runs) use a fixed-size
//! transcription of one argmin run (`lbfgs_fixed`: argmin's arithmetic and bookkeeping without
//! its executor, so the same iterates, counts and termination);
//! [`minimize_lbfgs_argmin`] / [`solve_lbfgs_argmin`] run argmin's `Executor` itself (the
//! reference, and [`crate::solve_any`]'s path). The restarts and the report below are shared.
//!
//! # Bounds
//!
//! argmin's L-BFGS has no bounds, so the adapter minimises `f(l + y²)` over `y` (free unknowns
//! untouched); see [`crate::bounds`] for why `y²` rather than `exp(y)` and what happens at a
//! bound: a start on a bound is moved inside by [`START_OFFSET`](crate::bounds::START_OFFSET),
//! and an optimum on a bound is approached, not reached exactly. The returned point is always
//! feasible.
//!
//! # Tests and counts
//!
//! - Gradient test: argmin stops when `‖∇_y f‖₂ < gradient_tolerance` (transformed variables,
//!   Euclidean norm); the report's [`ConvergenceTest::Gradient`] holds that norm.
//! - Cost test: argmin's test is **absolute**, `|f_{k−1} − f_k| < tol`; the adapter passes
//!   `tol = 10⁻⁴ · function_tolerance · f(x_s)` (see `COST_FACTOR`) with `x_s` the start of the run. When that test stops a
//!   run whose cost fell below half its starting cost, L-BFGS is restarted from the best point
//!   (memory discarded) with the tolerance rescaled to the new cost, so that the test finally
//!   applied is relative to the current cost as the other adapters' tests are. The report's
//!   `relative_change` is `|Δf| / f(x_s)` of the last run; iterations, counts and the history
//!   cover all runs.
//! - `step_tolerance` is not used (argmin's L-BFGS has no step test).
//! - Function counting and the timer are switched on (`state.counting(true)`,
//!   `Executor::timer(true)`), so the report's evaluation counts are argmin's own (the fast path
//!   counts the same calls, including the gradient argmin evaluates again at each accepted point,
//!   which the fast path takes from its line search). One extra
//!   gradient evaluation at the returned point, for the report's projected gradient, is included.
//! - A cost that is not finite at a trial point is returned to argmin as an error; inside the
//!   line search that ends the run with [`FailureReason::LineSearch`] and the best point so far.
//!
//! Reference: Nocedal & Wright, *Numerical Optimization*, 2nd ed., §7.2 (L-BFGS) and §3.5;
//! Moré & Thuente, "Line search algorithms with guaranteed sufficient decrease", *ACM TOMS* 20(3),
//! 1994.

use argmin::core::observers::{Observe, ObserverMode};
use argmin::core::{
    CostFunction, Error, Executor, Gradient, IterState, State, TerminationReason,
    TerminationStatus, KV,
};
use argmin::solver::linesearch::MoreThuenteLineSearch;
use argmin::solver::quasinewton::LBFGS;
use nalgebra::SVector;
use std::cell::RefCell;
use std::rc::Rc;
use std::time::Instant;

use crate::bounds::{projected_gradient_norm, validate_start, SquareMap};
use crate::{
    ConvergenceTest, FailureReason, HalfSumOfSquares, LeastSquaresProblem, ObjectiveProblem,
    Solution, SolveError, SolveOptions, SolverKind, Termination,
};

/// Factor applied to `function_tolerance` for L-BFGS: one quasi-Newton iteration's decrease
/// understates the remaining distance to the optimum more than a (Gauss–)Newton step's does, so
/// L-BFGS needs a tighter cost test to agree with the other adapters to 1e-8 in `x`.
const COST_FACTOR: f64 = 1e-4;

/// Number of correction pairs kept by L-BFGS.
pub(crate) const MEMORY: usize = 7;

/// The problem in transformed variables `y`, as argmin sees it.
struct Transformed<'a, P, const N: usize> {
    problem: &'a P,
    map: SquareMap<N>,
}

impl<P: ObjectiveProblem<N>, const N: usize> CostFunction for Transformed<'_, P, N> {
    type Param = SVector<f64, N>;
    type Output = f64;

    fn cost(&self, y: &Self::Param) -> Result<f64, Error> {
        let f = self.problem.value(&self.map.to_x(y));
        if f.is_finite() {
            Ok(f)
        } else {
            Err(Error::msg("cost is not finite"))
        }
    }
}

impl<P: ObjectiveProblem<N>, const N: usize> Gradient for Transformed<'_, P, N> {
    type Param = SVector<f64, N>;
    type Gradient = SVector<f64, N>;

    fn gradient(&self, y: &Self::Param) -> Result<Self::Gradient, Error> {
        let g = self
            .problem
            .gradient(&self.map.to_x(y))
            .component_mul(&self.map.dx_dy(y));
        if g.iter().all(|v| v.is_finite()) {
            Ok(g)
        } else {
            Err(Error::msg("gradient is not finite"))
        }
    }
}

type LbfgsState<const N: usize> = IterState<SVector<f64, N>, SVector<f64, N>, (), (), (), f64>;

/// Records the cost after every iteration.
struct History(Rc<RefCell<Vec<f64>>>);

impl<const N: usize> Observe<LbfgsState<N>> for History {
    fn observe_iter(&mut self, state: &LbfgsState<N>, _kv: &KV) -> Result<(), Error> {
        self.0.borrow_mut().push(state.get_cost());
        Ok(())
    }
}

/// Minimises a smooth objective `f(x)` subject to `x ≥ l` with argmin's L-BFGS algorithm; the
/// report's costs are values of `f`.
///
/// Runs the fixed-size transcription of argmin's run (`lbfgs_fixed`: the same iterates, counts
/// and termination, without the executor's overhead); [`minimize_lbfgs_argmin`] runs argmin
/// itself.
///
/// # Errors
/// [`SolveError`] for invalid options, a non-finite start, invalid bounds or a start below a bound.
pub fn minimize_lbfgs<P, const N: usize>(
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: ObjectiveProblem<N>,
{
    minimize_lbfgs_with(problem, x0, options, Backend::Fixed)
}

/// [`minimize_lbfgs`] through argmin's `Executor`, `LBFGS` and `MoreThuenteLineSearch`: the
/// reference for the fast path (same results; kept available and tested).
///
/// # Errors
/// As [`minimize_lbfgs`].
pub fn minimize_lbfgs_argmin<P, const N: usize>(
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: ObjectiveProblem<N>,
{
    minimize_lbfgs_with(problem, x0, options, Backend::Argmin)
}

/// Which implementation runs L-BFGS.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Backend {
    Fixed,
    Argmin,
}

/// One run of argmin's L-BFGS with the Moré–Thuente line search through its `Executor`.
fn run_argmin<P: ObjectiveProblem<N>, const N: usize>(
    problem: &P,
    map: SquareMap<N>,
    y_start: SVector<f64, N>,
    (tol_grad, tol_cost): (f64, f64),
    max_iters: u64,
    history: Option<&mut Vec<f64>>,
) -> Result<Outcome<N>, RunFailed> {
    let solver = LBFGS::new(MoreThuenteLineSearch::new(), MEMORY)
        .with_tolerance_grad(tol_grad)
        .and_then(|s| s.with_tolerance_cost(tol_cost))
        .map_err(|e| RunFailed::Config(e.to_string()))?;
    let run_history = Rc::new(RefCell::new(Vec::new()));
    let mut executor = Executor::new(Transformed { problem, map }, solver)
        .configure(|state| state.param(y_start).max_iters(max_iters).counting(true))
        .timer(true);
    if history.is_some() {
        executor = executor.add_observer(History(Rc::clone(&run_history)), ObserverMode::Always);
    }
    let result = executor.run().map_err(|_| RunFailed::Start)?;
    let state = result.state();
    let counts = state.get_func_counts();
    let count = |key: &str| {
        counts
            .get(key)
            .and_then(|&c| usize::try_from(c).ok())
            .unwrap_or(0)
    };
    if let Some(h) = history {
        h.extend(run_history.take());
    }
    let status = match state.get_termination_status() {
        TerminationStatus::Terminated(TerminationReason::SolverConverged) => RunStatus::Converged,
        TerminationStatus::Terminated(TerminationReason::MaxItersReached) => RunStatus::MaxIters,
        TerminationStatus::Terminated(TerminationReason::SolverExit(message))
            if message.starts_with("Line search") =>
        {
            RunStatus::LineSearch
        }
        other => RunStatus::Other(format!("{other:?}")),
    };
    Ok(Outcome {
        status,
        iterations: state.get_iter(),
        cost_count: count("cost_count"),
        gradient_count: count("gradient_count"),
        best_param: state.get_best_param().copied(),
        best_cost: state.get_best_cost(),
        prev_cost: state.get_prev_cost(),
        cost: state.get_cost(),
        gradient: state.get_gradient().copied(),
    })
}

/// A run that could not start.
enum RunFailed {
    /// argmin refused the tolerances (unreachable after `validate`).
    Config(String),
    /// The cost or the gradient failed at the start point.
    Start,
}

/// How one run ended, for either backend.
enum RunStatus {
    Converged,
    MaxIters,
    LineSearch,
    /// argmin stopped for another reason (quoted).
    Other(String),
}

/// What the adapter reads from a finished run, for either backend.
struct Outcome<const N: usize> {
    status: RunStatus,
    iterations: u64,
    cost_count: usize,
    gradient_count: usize,
    best_param: Option<SVector<f64, N>>,
    best_cost: f64,
    prev_cost: f64,
    cost: f64,
    gradient: Option<SVector<f64, N>>,
}

fn minimize_lbfgs_with<P, const N: usize>(
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
    backend: Backend,
) -> Result<Solution<N>, SolveError>
where
    P: ObjectiveProblem<N>,
{
    let start = Instant::now();
    options.validate()?;
    let lower = problem.lower_bounds();
    validate_start(&x0, &lower)?;
    let map = SquareMap::new(lower);
    let y0 = map.to_y(&x0);
    let initial_cost = problem.value(&x0);

    let reporter = crate::report::Reporter {
        solver: SolverKind::Lbfgs,
        initial_cost,
        start,
    };

    if !initial_cost.is_finite() {
        let termination = Termination::Failure {
            reason: FailureReason::NonFiniteCost,
        };
        return Ok(reporter.solution(x0, initial_cost, f64::NAN, termination, 0, 1, 0, Vec::new()));
    }

    // argmin's cost test is absolute; restarts from the best point with the tolerance rescaled to
    // the current cost make it relative (see the module docs).
    let mut history = if options.record_history {
        vec![initial_cost]
    } else {
        Vec::new()
    };
    let mut y_start = y0;
    let mut run_start_cost = initial_cost;
    let (mut iterations, mut cost_evaluations, mut gradient_evaluations) = (0usize, 1usize, 0usize);
    let (status, prev_cost, last_cost, best_y) = loop {
        let cost_tolerance = options.function_tolerance * COST_FACTOR * run_start_cost.abs();
        let remaining = options.max_iterations.saturating_sub(iterations);
        let max_iters = u64::try_from(remaining).unwrap_or(u64::MAX);
        let hist = options.record_history.then_some(&mut history);
        let outcome = match backend {
            Backend::Argmin => run_argmin(
                problem,
                map,
                y_start,
                (options.gradient_tolerance, cost_tolerance),
                max_iters,
                hist,
            ),
            Backend::Fixed => crate::lbfgs_fixed::run(
                problem,
                map,
                y_start,
                options.gradient_tolerance,
                cost_tolerance,
                max_iters,
                hist,
            )
            .map_err(|()| RunFailed::Start)
            .map(|o| Outcome {
                status: match o.status {
                    crate::lbfgs_fixed::Status::Converged => RunStatus::Converged,
                    crate::lbfgs_fixed::Status::MaxIters => RunStatus::MaxIters,
                    crate::lbfgs_fixed::Status::LineSearch => RunStatus::LineSearch,
                },
                iterations: o.iterations,
                cost_count: o.cost_count,
                gradient_count: o.gradient_count,
                best_param: o.best_param,
                best_cost: o.best_cost,
                prev_cost: o.prev_cost,
                cost: o.cost,
                gradient: o.gradient,
            }),
        };
        let state = match outcome {
            Ok(state) => state,
            // Unreachable after `validate`, but reported rather than unwrapped.
            Err(RunFailed::Config(message)) => {
                let termination = Termination::Failure {
                    reason: FailureReason::Backend { message },
                };
                return Ok(reporter.solution(
                    x0,
                    initial_cost,
                    f64::NAN,
                    termination,
                    0,
                    1,
                    0,
                    Vec::new(),
                ));
            }
            // The cost or gradient failed at the start point of the run.
            Err(RunFailed::Start) => {
                let termination = Termination::Failure {
                    reason: FailureReason::NonFiniteDerivative,
                };
                let x = map.to_x(&y_start);
                let c = problem.value(&x);
                return Ok(reporter.solution(
                    x,
                    c,
                    f64::NAN,
                    termination,
                    iterations,
                    cost_evaluations,
                    gradient_evaluations,
                    history,
                ));
            }
        };
        cost_evaluations += state.cost_count;
        gradient_evaluations += state.gradient_count;
        iterations += usize::try_from(state.iterations).unwrap_or(usize::MAX);
        let best_y = state.best_param.unwrap_or(y_start);
        let best_cost = state.best_cost;
        let by_cost_test = matches!(state.status, RunStatus::Converged)
            && state
                .gradient
                .is_none_or(|g| g.norm() >= options.gradient_tolerance);
        if by_cost_test && best_cost < 0.5 * run_start_cost && iterations < options.max_iterations {
            y_start = best_y;
            run_start_cost = best_cost;
            continue;
        }
        break (state.status, state.prev_cost, state.cost, best_y);
    };

    let x = map.to_x(&best_y);
    let final_cost = problem.value(&x);
    let g = problem.gradient(&x);
    let gnorm_x = projected_gradient_norm(&x, &g, &lower);
    let gnorm_y = g.component_mul(&map.dx_dy(&best_y)).norm();

    let termination = match status {
        RunStatus::Converged => {
            if gnorm_y < options.gradient_tolerance {
                Termination::Converged {
                    test: ConvergenceTest::Gradient {
                        norm: gnorm_y,
                        tolerance: options.gradient_tolerance,
                    },
                }
            } else {
                let change = (prev_cost - last_cost).abs();
                Termination::Converged {
                    test: ConvergenceTest::CostChange {
                        relative_change: if run_start_cost == 0.0 {
                            0.0
                        } else {
                            change / run_start_cost.abs()
                        },
                        tolerance: options.function_tolerance,
                    },
                }
            }
        }
        RunStatus::MaxIters => Termination::MaxIterations {
            limit: options.max_iterations,
        },
        RunStatus::LineSearch => Termination::Failure {
            reason: FailureReason::LineSearch,
        },
        RunStatus::Other(message) => Termination::Failure {
            reason: FailureReason::Backend { message },
        },
    };
    Ok(reporter.solution(
        x,
        final_cost,
        gnorm_x,
        termination,
        iterations,
        cost_evaluations + 1,
        gradient_evaluations + 1,
        history,
    ))
}

/// Solves `min ½‖r(x)‖² s.t. x ≥ l` with L-BFGS on the cost `½‖r‖²` (gradient `Jᵀr`), by the
/// fixed-size fast path ([`minimize_lbfgs`]).
///
/// # Errors
/// As [`minimize_lbfgs`].
pub fn solve_lbfgs<P, const N: usize, const M: usize>(
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: LeastSquaresProblem<N, M>,
{
    minimize_lbfgs(&HalfSumOfSquares::<P, M>(problem), x0, options)
}

/// [`solve_lbfgs`] through argmin itself ([`minimize_lbfgs_argmin`]): the reference path.
///
/// # Errors
/// As [`minimize_lbfgs`].
pub fn solve_lbfgs_argmin<P, const N: usize, const M: usize>(
    problem: &P,
    x0: SVector<f64, N>,
    options: &SolveOptions,
) -> Result<Solution<N>, SolveError>
where
    P: LeastSquaresProblem<N, M>,
{
    minimize_lbfgs_argmin(&HalfSumOfSquares::<P, M>(problem), x0, options)
}

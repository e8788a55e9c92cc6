//! L-BFGS (argmin 0.11) with the Moré–Thuente line search, bounds by the change of variables
//! `x = l + y²`.
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
//!   `Executor::timer(true)`), so the report's evaluation counts are argmin's own. One extra
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
const MEMORY: usize = 7;

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

/// Minimises a smooth objective `f(x)` subject to `x ≥ l` with argmin's L-BFGS; the report's costs
/// are values of `f`.
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
        let solver = LBFGS::new(MoreThuenteLineSearch::new(), MEMORY)
            .with_tolerance_grad(options.gradient_tolerance)
            .and_then(|s| s.with_tolerance_cost(cost_tolerance));
        let solver = match solver {
            Ok(s) => s,
            // Unreachable after `validate`, but reported rather than unwrapped.
            Err(e) => {
                let termination = Termination::Failure {
                    reason: FailureReason::Backend {
                        message: e.to_string(),
                    },
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
        };
        let run_history = Rc::new(RefCell::new(Vec::new()));
        let remaining = options.max_iterations.saturating_sub(iterations);
        let max_iters = u64::try_from(remaining).unwrap_or(u64::MAX);
        let mut executor = Executor::new(Transformed { problem, map }, solver)
            .configure(|state| state.param(y_start).max_iters(max_iters).counting(true))
            .timer(true);
        if options.record_history {
            executor =
                executor.add_observer(History(Rc::clone(&run_history)), ObserverMode::Always);
        }
        let Ok(result) = executor.run() else {
            // The cost or gradient failed at the start point of the run.
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
        };
        let state = result.state();
        let counts = state.get_func_counts();
        let count = |key: &str| {
            counts
                .get(key)
                .and_then(|&c| usize::try_from(c).ok())
                .unwrap_or(0)
        };
        cost_evaluations += count("cost_count");
        gradient_evaluations += count("gradient_count");
        iterations += usize::try_from(state.get_iter()).unwrap_or(usize::MAX);
        history.extend(run_history.take());
        let best_y = state.get_best_param().copied().unwrap_or(y_start);
        let best_cost = state.get_best_cost();
        let status = state.get_termination_status().clone();
        let by_cost_test = matches!(
            status,
            TerminationStatus::Terminated(TerminationReason::SolverConverged)
        ) && state
            .get_gradient()
            .is_none_or(|g| g.norm() >= options.gradient_tolerance);
        if by_cost_test && best_cost < 0.5 * run_start_cost && iterations < options.max_iterations {
            y_start = best_y;
            run_start_cost = best_cost;
            continue;
        }
        break (status, state.get_prev_cost(), state.get_cost(), best_y);
    };

    let x = map.to_x(&best_y);
    let final_cost = problem.value(&x);
    let g = problem.gradient(&x);
    let gnorm_x = projected_gradient_norm(&x, &g, &lower);
    let gnorm_y = g.component_mul(&map.dx_dy(&best_y)).norm();

    let termination = match status {
        TerminationStatus::Terminated(TerminationReason::SolverConverged) => {
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
        TerminationStatus::Terminated(TerminationReason::MaxItersReached) => {
            Termination::MaxIterations {
                limit: options.max_iterations,
            }
        }
        TerminationStatus::Terminated(TerminationReason::SolverExit(message))
            if message.starts_with("Line search") =>
        {
            Termination::Failure {
                reason: FailureReason::LineSearch,
            }
        }
        other => Termination::Failure {
            reason: FailureReason::Backend {
                message: format!("{other:?}"),
            },
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

/// Solves `min ½‖r(x)‖² s.t. x ≥ l` with L-BFGS on the cost `½‖r‖²` (gradient `Jᵀr`).
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

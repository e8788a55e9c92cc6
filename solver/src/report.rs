//! Convergence reports: what a solver did, why it stopped, and what it cost.
//!
//! The fields follow what a Ceres Solver (`Solver::Summary`) or SciPy
//! (`OptimizeResult`) user expects. **Costs are `½‖r‖²`** for least-squares problems (the Ceres and
//! SciPy convention; the seed papers' objective `‖r‖²` is twice that, see
//! [`SolveReport::final_objective`]). For a general smooth problem minimised with
//! [`minimize_lbfgs`](crate::minimize_lbfgs) the cost is the objective value itself.
//!
//! JSON keys are snake_case and stable; the only timing field is `time_seconds`. Enums are
//! internally tagged with `"kind"`, e.g.
//! `{"kind":"converged","test":{"kind":"cost_change","relative_change":1e-13,"tolerance":1e-12}}`.

use serde::{Deserialize, Serialize};
use std::fmt;

use crate::SolverKind;

/// Which convergence test a solver passed, with the measured value and the tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum ConvergenceTest {
    /// The (projected) gradient norm fell to the gradient tolerance.
    ///
    /// For the change-of-variables adapters the norm is that of the solver's own test in its
    /// transformed variables; see the adapter's documentation.
    Gradient {
        /// The measured gradient norm.
        norm: f64,
        /// The gradient tolerance.
        tolerance: f64,
    },
    /// The cost changed by less than the function tolerance, relative to the cost.
    CostChange {
        /// `|cost_change| / cost` (absolute change for L-BFGS, whose test is absolute).
        relative_change: f64,
        /// The function tolerance the change was compared with.
        tolerance: f64,
    },
    /// The step was small relative to the unknowns: `‖Δx‖ ≤ tol·(‖x‖ + tol)`.
    Step {
        /// `‖Δx‖ / (‖x‖ + tol)`.
        relative_step: f64,
        /// The step tolerance.
        tolerance: f64,
    },
    /// The residuals vanished (cost at or below the smallest positive normal `f64`).
    ZeroResidual {
        /// The final cost.
        cost: f64,
    },
}

/// Why a solver failed: it stopped without meeting a convergence test or a limit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum FailureReason {
    /// The cost (or a residual) was NaN or infinite at the start point.
    NonFiniteCost,
    /// The gradient or Jacobian was NaN or infinite at an accepted point.
    NonFiniteDerivative,
    /// The line search found no acceptable step along a descent direction.
    LineSearch,
    /// The backend library stopped for a reason of its own, quoted here.
    Backend {
        /// The backend's explanation.
        message: String,
    },
}

/// Why a solver stopped.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Termination {
    /// A convergence test passed.
    Converged {
        /// The test that passed.
        test: ConvergenceTest,
    },
    /// The iteration limit was reached; the report holds the best point found.
    MaxIterations {
        /// The limit.
        limit: usize,
    },
    /// The limit on function evaluations was reached (Levenberg–Marquardt's patience).
    MaxEvaluations {
        /// The limit.
        limit: usize,
    },
    /// The solver failed; the report holds the best point found.
    Failure {
        /// What went wrong.
        reason: FailureReason,
    },
}

impl fmt::Display for Termination {
    /// A one-line human message in the style of Ceres' `Summary::message`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Converged { test } => match test {
                ConvergenceTest::Gradient { norm, tolerance } => write!(
                    f,
                    "Gradient tolerance reached. Gradient max norm: {norm:.3e} <= {tolerance:.3e}"
                ),
                ConvergenceTest::CostChange {
                    relative_change,
                    tolerance,
                } => write!(
                    f,
                    "Function tolerance reached. |cost_change|/cost: {relative_change:.3e} <= {tolerance:.3e}"
                ),
                ConvergenceTest::Step {
                    relative_step,
                    tolerance,
                } => write!(
                    f,
                    "Parameter tolerance reached. Relative step_norm: {relative_step:.3e} <= {tolerance:.3e}"
                ),
                ConvergenceTest::ZeroResidual { cost } => {
                    write!(f, "Residuals vanished. cost: {cost:.3e}")
                }
            },
            Self::MaxIterations { limit } => {
                write!(f, "Maximum number of iterations reached. Number of iterations: {limit}")
            }
            Self::MaxEvaluations { limit } => write!(
                f,
                "Maximum number of function evaluations reached. Limit: {limit}"
            ),
            Self::Failure { reason } => match reason {
                FailureReason::NonFiniteCost => {
                    write!(f, "Failure: cost or residuals not finite at the start point")
                }
                FailureReason::NonFiniteDerivative => {
                    write!(f, "Failure: gradient or Jacobian not finite")
                }
                FailureReason::LineSearch => {
                    write!(f, "Failure: line search found no acceptable step")
                }
                FailureReason::Backend { message } => write!(f, "Failure: {message}"),
            },
        }
    }
}

/// What a solve did: the record every adapter fills in.
///
/// `iterations` counts completed iterations (accepted steps, Ceres' "successful steps" plus, for
/// Levenberg–Marquardt, the outer iterations that ended in a rejected step; see each adapter).
/// `cost_history[0]` is the initial cost and `cost_history[k]` the cost after iteration `k`, when
/// [`SolveOptions::record_history`](crate::SolveOptions::record_history) is on; it is empty
/// otherwise.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct SolveReport {
    /// The adapter that produced this report.
    pub solver: SolverKind,
    /// Why the solver stopped.
    pub termination: Termination,
    /// Completed iterations.
    pub iterations: usize,
    /// Evaluations of the residuals (or the cost), including rejected trial points.
    pub cost_evaluations: usize,
    /// Evaluations of the Jacobian (or the gradient).
    pub gradient_evaluations: usize,
    /// Cost `½‖r‖²` at the start point.
    pub initial_cost: f64,
    /// Cost `½‖r‖²` at the returned point.
    pub final_cost: f64,
    /// Max-norm of the projected gradient of the cost, `‖x − P(x − Jᵀr)‖∞` with `P` the projection
    /// onto the bounds, at the returned point (evaluated in the original unknowns for every
    /// adapter).
    pub final_gradient_norm: f64,
    /// The returned point (the best one found).
    pub x: Vec<f64>,
    /// Cost after every iteration, starting with the initial cost (empty if switched off).
    pub cost_history: Vec<f64>,
    /// Wall-clock time of the solve in seconds.
    pub time_seconds: f64,
}

impl SolveReport {
    /// Whether a convergence test passed.
    #[must_use]
    pub fn converged(&self) -> bool {
        matches!(self.termination, Termination::Converged { .. })
    }

    /// The human message, e.g. `Function tolerance reached. |cost_change|/cost: 1.2e-13 <= 1e-12`.
    #[must_use]
    pub fn message(&self) -> String {
        self.termination.to_string()
    }

    /// The seed papers' objective `‖r‖² = 2·cost` at the start point (least-squares solves).
    #[must_use]
    pub fn initial_objective(&self) -> f64 {
        2.0 * self.initial_cost
    }

    /// The seed papers' objective `‖r‖² = 2·cost` at the returned point (least-squares solves).
    #[must_use]
    pub fn final_objective(&self) -> f64 {
        2.0 * self.final_cost
    }

    /// One line: solver, outcome, iterations, costs and time.
    #[must_use]
    pub fn brief(&self) -> String {
        format!(
            "{}: {}, {} iterations, cost {:.6e} -> {:.6e}, {:.3e} s",
            self.solver,
            if self.converged() {
                "CONVERGED"
            } else {
                "NO CONVERGENCE"
            },
            self.iterations,
            self.initial_cost,
            self.final_cost,
            self.time_seconds
        )
    }

    /// The full multi-line table (the same as `Display`).
    #[must_use]
    pub fn table(&self) -> String {
        self.to_string()
    }
}

impl fmt::Display for SolveReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "Solver summary (cost = 1/2 |r|^2)")?;
        writeln!(f, "{:<28}{}", "Solver", self.solver)?;
        writeln!(f, "{:<28}{:.12e}", "Initial cost", self.initial_cost)?;
        writeln!(f, "{:<28}{:.12e}", "Final cost", self.final_cost)?;
        writeln!(
            f,
            "{:<28}{:.12e}",
            "Change",
            self.initial_cost - self.final_cost
        )?;
        writeln!(
            f,
            "{:<28}{:.3e}",
            "Projected gradient (max)", self.final_gradient_norm
        )?;
        writeln!(f, "{:<28}{}", "Iterations", self.iterations)?;
        writeln!(f, "{:<28}{}", "Cost evaluations", self.cost_evaluations)?;
        writeln!(
            f,
            "{:<28}{}",
            "Gradient evaluations", self.gradient_evaluations
        )?;
        writeln!(f, "{:<28}{:.6e}", "Time (s)", self.time_seconds)?;
        let xs: Vec<String> = self.x.iter().map(|v| format!("{v:.12e}")).collect();
        writeln!(f, "{:<28}[{}]", "x", xs.join(", "))?;
        writeln!(
            f,
            "{:<28}{}",
            "Termination",
            if self.converged() {
                "CONVERGENCE"
            } else {
                "NO_CONVERGENCE"
            }
        )?;
        write!(f, "{:<28}{}", "Message", self.termination)
    }
}

impl Serialize for SolveReport {
    /// Serialises every field plus the derived `message`, in a fixed key order.
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut s = serializer.serialize_struct("SolveReport", 13)?;
        s.serialize_field("solver", &self.solver)?;
        s.serialize_field("converged", &self.converged())?;
        s.serialize_field("termination", &self.termination)?;
        s.serialize_field("message", &self.message())?;
        s.serialize_field("iterations", &self.iterations)?;
        s.serialize_field("cost_evaluations", &self.cost_evaluations)?;
        s.serialize_field("gradient_evaluations", &self.gradient_evaluations)?;
        s.serialize_field("initial_cost", &self.initial_cost)?;
        s.serialize_field("final_cost", &self.final_cost)?;
        s.serialize_field("final_gradient_norm", &self.final_gradient_norm)?;
        s.serialize_field("x", &self.x)?;
        s.serialize_field("cost_history", &self.cost_history)?;
        s.serialize_field("time_seconds", &self.time_seconds)?;
        s.end()
    }
}

/// Builds the [`crate::Solution`]s of one run of an adapter: every adapter reports the same
/// fields the same way (one builder instead of one closure per adapter).
pub(crate) struct Reporter {
    /// The adapter.
    pub solver: SolverKind,
    /// `½‖r(x0)‖²`.
    pub initial_cost: f64,
    /// When the run started (for `time_seconds`).
    pub start: std::time::Instant,
}

impl Reporter {
    /// The solution at `x` with its report.
    #[allow(clippy::too_many_arguments)] // the report's fields, named at every call
    pub(crate) fn solution<const N: usize>(
        &self,
        x: nalgebra::SVector<f64, N>,
        final_cost: f64,
        final_gradient_norm: f64,
        termination: Termination,
        iterations: usize,
        cost_evaluations: usize,
        gradient_evaluations: usize,
        cost_history: Vec<f64>,
    ) -> crate::Solution<N> {
        crate::Solution {
            x,
            report: SolveReport {
                solver: self.solver,
                termination,
                iterations,
                cost_evaluations,
                gradient_evaluations,
                initial_cost: self.initial_cost,
                final_cost,
                final_gradient_norm,
                x: x.iter().copied().collect(),
                cost_history,
                time_seconds: self.start.elapsed().as_secs_f64(),
            },
        }
    }
}

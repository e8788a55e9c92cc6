//! Options shared by every adapter.

use serde::{Deserialize, Serialize};

use crate::SolveError;

/// Stopping rules and bookkeeping shared by every adapter.
///
/// The defaults are tighter than Ceres' (function 1e-6, gradient 1e-10, parameter 1e-8) because
/// the workbench compares adapters to about 1e-8 in `x`; on the small problems it solves the extra
/// iterations cost little, as all three adapters converge superlinearly near a solution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SolveOptions {
    /// Iteration limit (default 200). A solver that reaches it returns its best point with
    /// [`Termination::MaxIterations`](crate::Termination::MaxIterations).
    pub max_iterations: usize,
    /// Gradient tolerance (default `1e-10`): converged when the max-norm of the projected gradient
    /// of the cost `½‖r‖²` is at most this (exact penalty); L-BFGS and Levenberg–Marquardt apply
    /// their own gradient tests in transformed variables, see their modules.
    pub gradient_tolerance: f64,
    /// Function tolerance (default `1e-12`): converged when `|Δcost| ≤ tol·cost`.
    pub function_tolerance: f64,
    /// Step tolerance (default `1e-10`): converged when `‖Δx‖ ≤ tol·(‖x‖ + tol)`.
    pub step_tolerance: f64,
    /// Whether to record the cost after every iteration (default `true`). Switch off in hot loops
    /// to avoid the allocation.
    pub record_history: bool,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            max_iterations: 200,
            gradient_tolerance: 1e-10,
            function_tolerance: 1e-12,
            step_tolerance: 1e-10,
            record_history: true,
        }
    }
}

impl SolveOptions {
    /// Checks that every tolerance is finite and non-negative.
    ///
    /// # Errors
    /// [`SolveError::InvalidOption`] naming the first bad option.
    pub fn validate(&self) -> Result<(), SolveError> {
        for (name, value) in [
            ("gradient_tolerance", self.gradient_tolerance),
            ("function_tolerance", self.function_tolerance),
            ("step_tolerance", self.step_tolerance),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(SolveError::InvalidOption { name, value });
            }
        }
        Ok(())
    }
}

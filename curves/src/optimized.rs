//! Mann's optimized boundary curve (techreport §3, conference §3): the cubic whose end-derivative
//! lengths minimize `w_t[(α0−1)² + (α1−1)²] + w_k[(κ(0)−k0)² + (κ(1)−k1)²]` subject to
//! `α ≥ α_min` — the objective is `cost::BoundaryCurveObjective`, solved by any adapter of the
//! `solver` crate.
//!
//! The start is the chord choice `α = (1, 1)` (raised to `α_min` if that is larger): it is
//! feasible, it minimizes the tangent terms, and it is the Shirman–Séquin default the method
//! improves on, so the optimizer moves only as far as the curvature terms ask. Starting from a
//! dBHS solution would instead bias the result towards the short tangents the method exists to
//! avoid.
//!
//! The bound keeps the curvature terms finite (`κ ∝ 1/α²`). Its default, [`DEFAULT_ALPHA_MIN`],
//! is far below every optimum seen on the data sets (shortest 0.45 on the 16×8 ring), so it is
//! active only on pathological data.

use cost::{BoundaryCurveObjective, Weights};
use nalgebra::SVector;
use solver::{solve, SolveOptions, SolverKind};

use crate::method::{CurveChoice, CurveMethod};
use crate::problem::UnitProblem;

/// Default lower bound on both lengths: one twentieth of the chord choice.
pub const DEFAULT_ALPHA_MIN: f64 = 0.05;

/// The optimized construction with its solver, weights and bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Optimized {
    /// Which solver adapter runs the minimization.
    pub solver: SolverKind,
    /// Weights of the tangent and curvature terms.
    pub weights: Weights,
    /// Lower bound on `α0, α1`.
    pub alpha_min: f64,
    /// Solver settings (tolerances, iteration limit, whether to keep the cost history).
    pub solve_options: SolveOptions,
}

impl CurveMethod for Optimized {
    fn name(&self) -> &'static str {
        "optimized"
    }

    fn takes_solver(&self) -> bool {
        true
    }

    /// Minimizes from `α = (1, 1)`. Invalid settings (negative weights, `α_min ≤ 0`) cannot
    /// produce a curve: the chord choice is returned with `fallback` set and no report.
    fn construct(&self, problem: &UnitProblem) -> CurveChoice {
        let fallback = || CurveChoice {
            fallback: true,
            ..CurveChoice::plain([1.0, 1.0])
        };
        let Ok(objective) = BoundaryCurveObjective::new(
            problem.t0,
            problem.t1,
            [problem.k0, problem.k1],
            self.weights,
            self.alpha_min,
        ) else {
            return fallback();
        };
        let start = SVector::<f64, 2>::from_element(self.alpha_min.max(1.0));
        match solve(self.solver, &objective, start, &self.solve_options) {
            Ok(solution) => CurveChoice {
                report: Some(solution.report),
                ..CurveChoice::plain([solution.x[0], solution.x[1]])
            },
            Err(_) => fallback(),
        }
    }
}

//! The options of the boundary-curve constructions, one argument group shared by every
//! experiment that builds curves (`fit`, `ring`, `curve`).

use curves::{DbhsPick, MethodOptions};
use solver::SolverKind;

/// `--solver` and `--dbhs-pick`.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct CurveOptions {
    /// Solver of the optimized construction (and of `--interior` fairing): exact-penalty, lbfgs
    /// or lm.
    #[arg(long, default_value_t = SolverKind::ExactPenalty)]
    pub solver: SolverKind,
    /// Which dBHS solution to take: closest (to α = (1, 1)), longest-short (largest shorter
    /// tangent), or a solution index in order of increasing α0.
    #[arg(long, default_value_t = DbhsPick::Closest)]
    pub dbhs_pick: DbhsPick,
}

impl CurveOptions {
    /// The constructions' options with these choices, the rest at their defaults.
    pub fn method_options(&self) -> MethodOptions {
        MethodOptions {
            dbhs_pick: self.dbhs_pick,
            solver: self.solver,
            ..MethodOptions::default()
        }
    }
}

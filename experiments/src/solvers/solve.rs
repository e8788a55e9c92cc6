//! Solving: every edge problem of the data sets asked for, minimized by every solver adapter
//! from α = (1, 1) with the constructions' default weights and bound, each solve timed (the
//! fastest of [`TIMING_REPEATS`] repeats without history) and run once more with its history.

use std::collections::BTreeMap;
use std::time::Instant;

use cost::BoundaryCurveObjective;
use curves::{MethodOptions, UnitProblem};
use nalgebra::SVector;
use solver::{solve, ConvergenceTest, SolveOptions, SolveReport, SolverKind, Termination};

use crate::datasets::edge_problems;
use crate::error::ExperimentError;

use super::TIMING_REPEATS;

/// One solve of one problem by one adapter.
pub(super) struct Run {
    /// The optimum found.
    pub(super) alpha: [f64; 2],
    /// The solver's report (with the cost history).
    pub(super) report: SolveReport,
    /// Fastest of [`TIMING_REPEATS`] repeated solves, in seconds.
    pub(super) time_seconds: f64,
}

/// One edge problem with the runs of every adapter (in `SolverKind::ALL` order).
pub(super) struct Problem {
    /// The data set.
    pub(super) dataset: String,
    /// The edge's vertices.
    pub(super) edge: (usize, usize),
    /// The problem on the unit chord.
    pub(super) unit: UnitProblem,
    /// One run per adapter.
    pub(super) runs: Vec<Run>,
}

/// A short name for how a run ended: `converged: gradient`, `max iterations`, `failure: …`.
pub(super) fn termination_kind(r: &SolveReport) -> String {
    match &r.termination {
        Termination::Converged { test } => format!(
            "converged: {}",
            match test {
                ConvergenceTest::Gradient { .. } => "gradient",
                ConvergenceTest::CostChange { .. } => "cost change",
                ConvergenceTest::Step { .. } => "step",
                ConvergenceTest::ZeroResidual { .. } => "zero residual",
            }
        ),
        Termination::MaxIterations { .. } => "max iterations".into(),
        Termination::MaxEvaluations { .. } => "max evaluations".into(),
        Termination::Failure { reason } => format!("failure: {reason:?}"),
    }
}

/// Solves one problem with one adapter; `Err` only if the adapter refuses the input (it cannot
/// here: the start (1, 1) is feasible and the options are the defaults).
fn solve_one(
    kind: SolverKind,
    objective: &BoundaryCurveObjective,
    opts: &SolveOptions,
) -> Result<Run, String> {
    let start = SVector::<f64, 2>::from_element(1.0);
    let timing_opts = SolveOptions {
        record_history: false,
        ..*opts
    };
    let mut best = f64::INFINITY;
    for _ in 0..TIMING_REPEATS {
        let t = Instant::now();
        let r = solve(kind, objective, start, &timing_opts);
        best = best.min(t.elapsed().as_secs_f64());
        std::hint::black_box(r.is_ok());
    }
    solve(kind, objective, start, opts)
        .map(|s| Run {
            alpha: [s.x[0], s.x[1]],
            report: s.report,
            time_seconds: best,
        })
        .map_err(|e| format!("{kind}: {e}"))
}

/// The largest difference of two optima in α (max norm).
pub(super) fn max_diff(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).abs().max((a[1] - b[1]).abs())
}

/// What solving the data sets gave.
pub(super) struct Solved {
    /// The problems every adapter accepted, each with its runs.
    pub(super) problems: Vec<Problem>,
    /// Per data set, the edges skipped as degenerate.
    pub(super) skipped: BTreeMap<String, usize>,
    /// The problems an adapter refused, with its reason.
    pub(super) refused: Vec<String>,
}

/// Every edge problem of the data sets `data` solved by every adapter (`SolverKind::ALL`, in
/// that order) with `opts`.
pub(super) fn solve_all(data: &[String], opts: &SolveOptions) -> Result<Solved, ExperimentError> {
    let kinds = SolverKind::ALL;
    let defaults = MethodOptions::default();
    let mut problems = Vec::new();
    let mut skipped = BTreeMap::new();
    let mut refused = Vec::new();
    for d in data {
        let (edges, errors) = edge_problems(d)?;
        skipped.insert(d.clone(), errors);
        for (edge, p) in edges {
            let Ok(objective) = BoundaryCurveObjective::new(
                p.unit.t0,
                p.unit.t1,
                [p.unit.k0, p.unit.k1],
                defaults.weights,
                defaults.alpha_min,
            ) else {
                continue;
            };
            let runs = match kinds
                .iter()
                .map(|k| solve_one(*k, &objective, opts))
                .collect::<Result<Vec<_>, _>>()
            {
                Ok(runs) => runs,
                Err(e) => {
                    refused.push(format!("{d} edge {}–{}: {e}", edge.0, edge.1));
                    continue;
                }
            };
            problems.push(Problem {
                dataset: d.clone(),
                edge,
                unit: p.unit,
                runs,
            });
        }
    }
    Ok(Solved {
        problems,
        skipped,
        refused,
    })
}

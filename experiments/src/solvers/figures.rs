//! The solvers study's figures: cost against iteration on characteristic problems (chosen by
//! stated rules) and the histogram of iterations per solve.

use std::path::Path;

use curves::{dbhs, DbhsPick};
use render::{Histogram, LineChart, Series};
use solver::SolverKind;

use crate::error::ExperimentError;

use super::solve::{max_diff, Problem};

/// The problems shown in the cost-against-iteration plots, each with the rule that chose it.
pub(super) fn characteristic_problems(problems: &[Problem]) -> Vec<(String, usize)> {
    let mut out: Vec<(String, usize)> = Vec::new();
    let mut push = |why: &str, i: Option<usize>| {
        if let Some(i) = i {
            if !out.iter().any(|(_, j)| *j == i) {
                out.push((why.to_string(), i));
            }
        }
    };
    let argmax = |f: &dyn Fn(&Problem) -> f64| {
        problems
            .iter()
            .enumerate()
            .max_by(|a, b| f(a.1).total_cmp(&f(b.1)))
            .map(|(i, _)| i)
    };
    push(
        "shortest dBHS end derivative (the seeds' lump)",
        argmax(&|p| {
            let s = dbhs::solve(&p.unit);
            DbhsPick::Closest
                .pick(&s)
                .and_then(|i| s.get(i))
                .map(|s| -s.alpha[0].min(s.alpha[1]))
                .unwrap_or(f64::NEG_INFINITY)
        }),
    );
    push(
        "most iterations of any adapter",
        argmax(&|p| {
            p.runs
                .iter()
                .map(|r| r.report.iterations as f64)
                .fold(0.0, f64::max)
        }),
    );
    push(
        "largest disagreement between adapters",
        argmax(&|p| {
            let mut d = 0.0f64;
            for a in &p.runs {
                for b in &p.runs {
                    d = d.max(max_diff(a.alpha, b.alpha));
                }
            }
            d
        }),
    );
    push(
        "largest final cost",
        argmax(&|p| p.runs[0].report.final_cost),
    );
    out
}

/// `cost-history.png`/`.svg` and `iterations.png`/`.svg`.
pub(super) fn write_figures(
    out: &Path,
    problems: &[Problem],
    characteristic: &[(String, usize)],
) -> Result<(), ExperimentError> {
    let charts: Vec<LineChart> = characteristic
        .iter()
        .map(|(why, i)| {
            let p = &problems[*i];
            // Suboptimality against the best final cost of any adapter, so the convergence
            // rate shows on the log axis (exact zeros, reached optima, are not drawn).
            let best = p
                .runs
                .iter()
                .map(|r| r.report.final_cost)
                .fold(f64::INFINITY, f64::min);
            LineChart {
                title: format!("{} edge {}–{}: {}", p.dataset, p.edge.0, p.edge.1, why),
                x_label: "iteration".into(),
                y_label: "cost − best final cost".into(),
                series: p
                    .runs
                    .iter()
                    .map(|r| Series {
                        label: r.report.solver.to_string(),
                        points: r
                            .report
                            .cost_history
                            .iter()
                            .enumerate()
                            .map(|(k, c)| (k as f64, *c - best))
                            .collect(),
                    })
                    .collect(),
                log_y: true,
            }
        })
        .collect();
    render::write_line_charts(
        &charts,
        2,
        "Cost against iteration on characteristic edge problems",
        &out.join("cost-history.png"),
        &out.join("cost-history.svg"),
    )?;
    let max_it = problems
        .iter()
        .flat_map(|p| p.runs.iter().map(|r| r.report.iterations))
        .max()
        .unwrap_or(0);
    let categories: Vec<String> = (0..=max_it).map(|i| i.to_string()).collect();
    let groups = SolverKind::ALL
        .iter()
        .enumerate()
        .map(|(k, kind)| {
            let mut counts = vec![0.0; max_it + 1];
            for p in problems {
                counts[p.runs[k].report.iterations] += 1.0;
            }
            (kind.name().to_string(), counts)
        })
        .collect();
    render::write_histogram(
        &Histogram {
            title: "Iterations per solve".into(),
            x_label: "iterations".into(),
            y_label: "edge problems".into(),
            categories,
            groups,
        },
        &out.join("iterations.png"),
        &out.join("iterations.svg"),
    )?;
    Ok(())
}

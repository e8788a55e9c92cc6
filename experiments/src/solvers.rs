//! `experiments -- solvers`: every boundary-curve problem of the data sets solved by every solver
//! adapter, compared.
//!
//! For each data set the edge problems (`curves::BoundaryProblem`, unit-chord form) are built
//! from exact vertex data and Mann's objective (`cost::BoundaryCurveObjective`, default weights
//! and bound) is minimized from `α = (1, 1)` by each adapter. The report gives per adapter: share
//! converged, iterations and evaluations (median, max), agreement of the optimum with the other
//! adapters, and time per solve; cost-against-iteration plots for characteristic problems; an
//! iteration histogram. Costs are `½‖r‖²` (the Ceres/SciPy convention), as in every solver report.

use std::collections::BTreeMap;
use std::path::Path;
use std::path::PathBuf;
use std::time::Instant;

use cost::BoundaryCurveObjective;
use curves::{dbhs, DbhsPick, MethodOptions, UnitProblem};
use nalgebra::SVector;
use render::{Histogram, LineChart, Series};
use serde_json::{json, Value};
use solver::{solve, ConvergenceTest, SolveOptions, SolveReport, SolverKind, Termination};

use crate::datasets::edge_problems;
use crate::error::ExperimentError;
use crate::output::{write_result, Staged};
use surface::metrics::median;

/// Two adapters "agree" on a problem when their optima differ by at most this in α (max norm):
/// the standard for well-conditioned problems.
pub const AGREEMENT: f64 = 1e-8;

/// Repetitions of each solve when timing (history off): the minimum over repetitions is the
/// time per solve, which removes scheduling noise on a shared machine.
const TIMING_REPEATS: usize = 5;

/// Options of the `solvers` experiment.
#[derive(clap::Args, Debug)]
pub struct SolversArgs {
    /// Output directory.
    #[arg(long, default_value = "results/solvers")]
    out: PathBuf,
    /// Data sets whose edges are solved (comma-separated).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "ring,sphere,capsule,octa"
    )]
    data: Vec<String>,
}

/// One solve of one problem by one adapter.
struct Run {
    alpha: [f64; 2],
    report: SolveReport,
    /// Fastest of [`TIMING_REPEATS`] repeated solves, in seconds.
    time_seconds: f64,
}

/// One edge problem with the runs of every adapter (in `SolverKind::ALL` order).
struct Problem {
    dataset: String,
    edge: (usize, usize),
    unit: UnitProblem,
    runs: Vec<Run>,
}

/// A short name for how a run ended: `converged: gradient`, `max iterations`, `failure: …`.
fn termination_kind(r: &SolveReport) -> String {
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

fn max_diff(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).abs().max((a[1] - b[1]).abs())
}

/// Runs the experiment.
pub fn run(args: &SolversArgs) -> Result<std::process::ExitCode, ExperimentError> {
    let kinds = SolverKind::ALL;
    let defaults = MethodOptions::default();
    let opts = SolveOptions {
        record_history: true,
        ..defaults.solve_options
    };
    let wall = Instant::now();
    let mut problems = Vec::new();
    let mut skipped = BTreeMap::new();
    let mut refused = Vec::new();
    for d in &args.data {
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
                .map(|k| solve_one(*k, &objective, &opts))
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
    let total_time = wall.elapsed().as_secs_f64();

    // Per-adapter summary.
    let mut summaries = Vec::new();
    for (k, kind) in kinds.iter().enumerate() {
        let runs: Vec<&Run> = problems.iter().map(|p| &p.runs[k]).collect();
        let n = runs.len();
        let converged = runs.iter().filter(|r| r.report.converged()).count();
        let its: Vec<f64> = runs.iter().map(|r| r.report.iterations as f64).collect();
        let fev: Vec<f64> = runs
            .iter()
            .map(|r| r.report.cost_evaluations as f64)
            .collect();
        let jev: Vec<f64> = runs
            .iter()
            .map(|r| r.report.gradient_evaluations as f64)
            .collect();
        let times: Vec<f64> = runs.iter().map(|r| r.time_seconds).collect();
        let mut worst_disagreement = 0.0f64;
        let mut disagreeing = 0usize;
        for p in &problems {
            let d = (0..kinds.len())
                .filter(|&j| j != k)
                .map(|j| max_diff(p.runs[k].alpha, p.runs[j].alpha))
                .fold(0.0, f64::max);
            worst_disagreement = worst_disagreement.max(d);
            if d > AGREEMENT {
                disagreeing += 1;
            }
        }
        let mut reasons: BTreeMap<String, usize> = BTreeMap::new();
        for r in &runs {
            *reasons.entry(termination_kind(&r.report)).or_default() += 1;
        }
        summaries.push(json!({
            "solver": kind.name(),
            "problems": n,
            "converged": converged,
            "converged_share": converged as f64 / n.max(1) as f64,
            "terminations": reasons,
            "iterations_median": median(its.clone()),
            "iterations_max": its.iter().copied().fold(0.0, f64::max),
            "cost_evaluations_median": median(fev.clone()),
            "cost_evaluations_max": fev.iter().copied().fold(0.0, f64::max),
            "gradient_evaluations_median": median(jev.clone()),
            "gradient_evaluations_max": jev.iter().copied().fold(0.0, f64::max),
            "max_alpha_difference_to_others": worst_disagreement,
            "problems_disagreeing": disagreeing,
            "time_per_solve_median_seconds": median(times.clone()),
            "time_per_solve_max_seconds": times.iter().copied().fold(0.0, f64::max),
        }));
    }

    // Pairwise agreement: the largest α difference between each pair of adapters.
    let mut pairwise = Vec::new();
    for a in 0..kinds.len() {
        for b in a + 1..kinds.len() {
            let diffs: Vec<f64> = problems
                .iter()
                .map(|p| max_diff(p.runs[a].alpha, p.runs[b].alpha))
                .collect();
            // How each adapter stopped on the problems where the pair disagrees.
            let mut how: BTreeMap<String, usize> = BTreeMap::new();
            for (p, d) in problems.iter().zip(&diffs) {
                if *d > AGREEMENT {
                    *how.entry(format!(
                        "{} {} / {} {}",
                        kinds[a].name(),
                        termination_kind(&p.runs[a].report),
                        kinds[b].name(),
                        termination_kind(&p.runs[b].report)
                    ))
                    .or_default() += 1;
                }
            }
            pairwise.push(json!({
                "terminations_where_disagreeing": how,
                "pair": [kinds[a].name(), kinds[b].name()],
                "max_alpha_difference": diffs.iter().copied().fold(0.0, f64::max),
                "median_alpha_difference": median(diffs.clone()),
                "problems_beyond_tolerance": diffs.iter().filter(|d| **d > AGREEMENT).count(),
            }));
        }
    }
    let characteristic = characteristic_problems(&problems);
    let staged = Staged::begin(&args.out)?;
    let out = staged.path().to_path_buf();
    write_figures(&out, &problems, &characteristic)?;

    let problem_records: Vec<Value> = problems
        .iter()
        .map(|p| {
            let mut runs = serde_json::Map::new();
            for (k, kind) in kinds.iter().enumerate() {
                let r = &p.runs[k];
                runs.insert(
                    kind.name().to_string(),
                    json!({
                        "alpha": r.alpha,
                        "converged": r.report.converged(),
                        "termination": termination_kind(&r.report),
                        "iterations": r.report.iterations,
                        "cost_evaluations": r.report.cost_evaluations,
                        "gradient_evaluations": r.report.gradient_evaluations,
                        "final_cost": r.report.final_cost,
                        "time_seconds": r.time_seconds,
                    }),
                );
            }
            json!({
                "dataset": p.dataset,
                "edge": [p.edge.0, p.edge.1],
                "t0": [p.unit.t0.x, p.unit.t0.y],
                "t1": [p.unit.t1.x, p.unit.t1.y],
                "k0": p.unit.k0,
                "k1": p.unit.k1,
                "runs": runs,
            })
        })
        .collect();
    let report = json!({
        "experiment": "solvers",
        "datasets": args.data,
        "objective": {
            "weights": {"tangent": defaults.weights.tangent, "curvature": defaults.weights.curvature},
            "alpha_min": defaults.alpha_min,
            "start": [1.0, 1.0],
            "cost_convention": "cost = 1/2 |r|^2 (Ceres/SciPy); Mann's F = |r|^2 = 2 cost",
        },
        "solve_options": opts,
        "agreement_tolerance": AGREEMENT,
        "edges_skipped_as_degenerate": skipped,
        "edges_refused_by_a_solver": refused,
        "summary": summaries,
        "pairwise_agreement": pairwise,
        "characteristic_problems": characteristic.iter().map(|(why, i)| json!({"rule": why, "index": i})).collect::<Vec<_>>(),
        "problems": problem_records,
        "total_time_seconds": total_time,
    });
    let text = crate::output::pretty_json(&report, "the solvers report")?;
    write_result(Some(&out.join("report.json")), text.as_bytes())?;
    let md = markdown(
        args,
        &problems,
        &summaries,
        &pairwise,
        &characteristic,
        total_time,
    );
    write_result(Some(&out.join("report.md")), md.as_bytes())?;
    say!(
        "solvers: {} problems × {} adapters in {:.2} s; written to {}",
        problems.len(),
        kinds.len(),
        total_time,
        args.out.display()
    );
    staged.commit()?;
    Ok(std::process::ExitCode::SUCCESS)
}

/// The problems shown in the cost-against-iteration plots, each with the rule that chose it.
fn characteristic_problems(problems: &[Problem]) -> Vec<(String, usize)> {
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

fn write_figures(
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

fn markdown(
    args: &SolversArgs,
    problems: &[Problem],
    summaries: &[Value],
    pairwise: &[Value],
    characteristic: &[(String, usize)],
    total_time: f64,
) -> String {
    let mut md = String::new();
    md.push_str("# Solvers on Mann's boundary-curve problems\n\n");
    md.push_str(&format!(
        "Written by `cargo run --release -p experiments -- solvers --data {} --out {}`. \
         {} edge problems from the data sets, each minimized from α = (1, 1) with weights (1, 1) \
         and α ≥ {} by every adapter. Costs are ½‖r‖² (Ceres/SciPy); Mann's objective F = ‖r‖² \
         is twice that. Agreement: optima within {:e} in α (max norm). Times are the fastest of \
         {} repeated solves without history, on the machine that wrote this report (total {:.2} s).\n\n",
        args.data.join(","),
        args.out.display(),
        problems.len(),
        MethodOptions::default().alpha_min,
        AGREEMENT,
        TIMING_REPEATS,
        total_time
    ));
    md.push_str("| adapter | converged | terminations | iterations median / max | cost evals median / max | gradient evals median / max | max Δα to others | disagreeing | time per solve median / max |\n");
    md.push_str("|---|---:|---|---:|---:|---:|---:|---:|---:|\n");
    for s in summaries {
        let f = |k: &str| s[k].as_f64().unwrap_or(f64::NAN);
        md.push_str(&format!(
            "| {} | {}/{} | {} | {} / {} | {} / {} | {} / {} | {:.1e} | {} | {:.2} µs / {:.2} µs |\n",
            s["solver"].as_str().unwrap_or("?"),
            s["converged"],
            s["problems"],
            s["terminations"]
                .as_object()
                .map(|m| m
                    .iter()
                    .map(|(k, v)| format!("{k}: {v}"))
                    .collect::<Vec<_>>()
                    .join(", "))
                .unwrap_or_default(),
            f("iterations_median"),
            f("iterations_max"),
            f("cost_evaluations_median"),
            f("cost_evaluations_max"),
            f("gradient_evaluations_median"),
            f("gradient_evaluations_max"),
            f("max_alpha_difference_to_others"),
            s["problems_disagreeing"],
            f("time_per_solve_median_seconds") * 1e6,
            f("time_per_solve_max_seconds") * 1e6,
        ));
    }
    md.push_str("\n## Agreement between adapters\n\n| pair | max Δα | median Δα | problems beyond 1e-8 | how each stopped there |\n|---|---:|---:|---:|---|\n");
    for p in pairwise {
        md.push_str(&format!(
            "| {} / {} | {:.1e} | {:.1e} | {} | {} |\n",
            p["pair"][0].as_str().unwrap_or("?"),
            p["pair"][1].as_str().unwrap_or("?"),
            p["max_alpha_difference"].as_f64().unwrap_or(f64::NAN),
            p["median_alpha_difference"].as_f64().unwrap_or(f64::NAN),
            p["problems_beyond_tolerance"],
            p["terminations_where_disagreeing"]
                .as_object()
                .map(|m| m
                    .iter()
                    .map(|(k, v)| format!("{k}: {v}"))
                    .collect::<Vec<_>>()
                    .join("; "))
                .unwrap_or_default()
        ));
    }
    md.push_str("\n## Cost against iteration\n\nProblems chosen by rule:\n\n");
    for (why, i) in characteristic {
        let p = &problems[*i];
        md.push_str(&format!(
            "- {}: {} edge {}–{} (t0 = ({:.4}, {:.4}), t1 = ({:.4}, {:.4}), k = ({:.4}, {:.4}))\n",
            why,
            p.dataset,
            p.edge.0,
            p.edge.1,
            p.unit.t0.x,
            p.unit.t0.y,
            p.unit.t1.x,
            p.unit.t1.y,
            p.unit.k0,
            p.unit.k1
        ));
    }
    md.push_str(
        "\n![cost history](cost-history.png)\n\n## Iterations\n\n![iterations](iterations.png)\n\n",
    );
    md.push_str("## Why adapters differ\n\n");
    md.push_str(
        "All adapters start from α = (1, 1) and stop on the first of: projected gradient of the \
         cost below 1e-10, relative cost change below 1e-12, relative step below 1e-10. The \
         exact-penalty adapter keeps α feasible and returns an active bound exactly; L-BFGS and \
         Levenberg–Marquardt run on α = α_min + y² (a change of variables for the bound), so \
         they approach an active bound without landing on it. A cost-change stop leaves α \
         uncertain by about √(tol · cost / λ_min) where the objective is flat along some \
         direction (λ_min the smallest eigenvalue of JᵀJ): the agreement table shows how each \
         adapter stopped where a pair differs by more than 1e-8. No adapter failed or ran out \
         of iterations on these data.\n",
    );
    md
}

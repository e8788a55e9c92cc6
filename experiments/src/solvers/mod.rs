//! `experiments -- solvers`: every boundary-curve problem of the data sets solved by every solver
//! adapter, compared.
//!
//! For each data set the edge problems (`curves::BoundaryProblem`, unit-chord form) are built
//! from exact vertex data and Mann's objective (`cost::BoundaryCurveObjective`, default weights
//! and bound) is minimized from `α = (1, 1)` by each adapter. The report gives per adapter: share
//! converged, iterations and evaluations (median, max), agreement of the optimum with the other
//! adapters, and time per solve; cost-against-iteration plots for characteristic problems; an
//! iteration histogram. Costs are `½‖r‖²` (the Ceres/SciPy convention), as in every solver report.
//!
//! Here: the options and the run; [`solve`] solves every problem with every adapter,
//! [`report`] sums up and writes `report.json` and `report.md`, [`figures`] chooses the
//! characteristic problems and draws the cost histories and the iteration histogram.

mod figures;
mod report;
mod solve;

use std::path::PathBuf;
use std::time::Instant;

use curves::MethodOptions;
use solver::{SolveOptions, SolverKind};

use crate::error::ExperimentError;
use crate::output::{pretty_json, write_result, Staged};

/// Two adapters "agree" on a problem when their optima differ by at most this in α (max norm):
/// the workbench's standard for well-conditioned problems.
pub const AGREEMENT: f64 = 1e-8;

/// Repetitions of each solve when timing (history off): the minimum over repetitions is the
/// time per solve, which removes scheduling noise on a shared machine.
const TIMING_REPEATS: usize = 5;

/// Options of the `solvers` experiment.
#[derive(clap::Args, Debug)]
pub struct SolversArgs {
    /// Output directory.
    #[arg(short = 'o', long, default_value = "results/solvers")]
    output: PathBuf,
    /// Data sets whose edges are solved (comma-separated or the option repeated; each once).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = crate::datasets::all_joined()
    )]
    data: Vec<String>,
}

/// Runs the experiment.
pub fn run(args: &SolversArgs) -> Result<std::process::ExitCode, ExperimentError> {
    let kinds = SolverKind::ALL;
    let defaults = MethodOptions::default();
    let opts = SolveOptions {
        record_history: true,
        ..defaults.solve_options
    };
    crate::study::refuse_duplicate_names("--data", &args.data)?;
    let wall = Instant::now();
    let solved = solve::solve_all(&args.data, &opts)?;
    let problems = &solved.problems;
    let total_time = wall.elapsed().as_secs_f64();

    let summaries = report::summaries(problems);
    let pairwise = report::pairwise(problems);
    let characteristic = figures::characteristic_problems(problems);
    let staged = Staged::begin(&args.output)?;
    let out = staged.path().to_path_buf();
    figures::write_figures(&out, problems, &characteristic)?;

    let report = report::report_json(
        args,
        &opts,
        &solved,
        &summaries,
        &pairwise,
        &characteristic,
        total_time,
    );
    let text = pretty_json(&report, "the solvers report")?;
    write_result(Some(&out.join("report.json")), text.as_bytes())?;
    let md = report::markdown(
        args,
        problems,
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
        args.output.display()
    );
    staged.commit()?;
    Ok(std::process::ExitCode::SUCCESS)
}

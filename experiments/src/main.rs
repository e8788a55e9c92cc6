//! The experiment runner of the workbench.
//!
//! `cargo run --release -p experiments -- <experiment> [options]`; `--help` lists the
//! experiments and each one's `--help` its options and defaults. Experiments write their results
//! atomically (temporary file, then rename) so an interrupted run never leaves half a file.

/// `eprintln!` that never panics: a closed or broken standard error loses the message, not the
/// run (results are files; the exit status still tells).
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

mod convert;
mod curve;
mod estimation;
mod fit;
mod franke;
mod interior;
mod output;
mod pages;
mod realmesh;
mod ring;
mod schemes;
mod solvers;
mod sweep;
mod view;

// The library's modules, under the names the experiments use (`crate::error::…`).
use experiments::{curve_args, datasets, error, input, limits, study};

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Experiments on triangular surface interpolants and their boundary curves.
#[derive(Parser, Debug)]
#[command(name = "experiments", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    experiment: Experiment,
}

#[derive(Subcommand, Debug)]
enum Experiment {
    /// The seeds' ring study: true ring, flat triangles and the Shirman–Séquin surface with chord,
    /// dBHS and optimized curves, measured against the torus, pictured (shaded, KColor, Radial)
    /// and written to results/ring/.
    Ring(ring::RingArgs),
    /// Boundary curves for planar unit-chord problems given as JSON Lines: every construction's
    /// (α0, α1), control points and end curvatures, and Figure-2-style plots.
    Curve(curve::CurveArgs),
    /// The ring study's measures over a grid: data sets or mesh files × resolution × scheme ×
    /// its parameters × curve construction × solver × segments (lists on the command line or
    /// `--grid FILE.toml`; by default every data set × construction × solver), one JSON Lines
    /// result a task; `--list-tasks`, `--task ID` and `--shard i/n` let any scheduler run it.
    Sweep(sweep::SweepArgs),
    /// Section 4's claim measured: interior-boundary curvature and corner twists against β and c.
    Interior(interior::InteriorArgs),
    /// Join the task and shard results of `sweep --task`/`--shard` into one report, each line
    /// checked against the sweep's task manifest.
    Merge(sweep::MergeArgs),
    /// Every boundary-curve problem of the data sets solved by every solver adapter (exact
    /// penalty, L-BFGS, Levenberg–Marquardt): convergence, agreement, iterations, time.
    Solvers(solvers::SolversArgs),
    /// Fit a data set or mesh file with any surface scheme (default: the modified Shirman–Séquin
    /// scheme), streamed; write the patches (JSON Lines or .bzp) and the tessellation (any mesh
    /// format) and report G1 defect, interpolation error and speed.
    Fit(fit::FitArgs),
    /// Read a mesh in any supported format, repair it, estimate what it lacks (normals, shape
    /// tensors) and write it in the format of the output's extension.
    Convert(convert::ConvertArgs),
    /// Every normal and curvature estimator against the exact data of the analytic surfaces at
    /// several resolutions, regular and irregular: errors, convergence orders, libigl's golden
    /// numbers, and the ring study rebuilt from estimated data.
    Estimation(estimation::EstimationArgs),
    /// The functional C1 schemes (clough-tocher, powell-sabin on height fields) on Franke's six
    /// test functions, 33 × 33 grid and 100 scattered points, exact and estimated gradients:
    /// max and RMS error over a 101 × 101 grid.
    Franke(franke::FrankeArgs),
    /// Every registered surface scheme on the data sets or the user's mesh files, side by side:
    /// G1 against the claimed continuity, errors against the true surface (data sets), shaded
    /// and KColor pictures.
    Schemes(schemes::SchemesArgs),
    /// The committed real-world meshes read, repaired, completed by estimation and fitted with
    /// every curve construction; pictures of the optimized-curve surfaces.
    Realmesh(realmesh::RealMeshArgs),
    /// One self-contained interactive HTML page of mesh or patch files side by side (shaded,
    /// curvature, reflection lines, isophotes; linked cameras; works offline).
    View(view::ViewArgs),
    /// Print the shell completion script (bash, zsh, fish, elvish, powershell) to standard
    /// output.
    Completions {
        /// The shell.
        shell: clidocs::Shell,
    },
    /// Write the man pages (section 1: `experiments.1` and one page an experiment) to a
    /// directory.
    Man {
        /// Directory for the pages (created if absent).
        #[arg(short = 'o', long)]
        output: std::path::PathBuf,
    },
}

/// The completion script or the man pages, from the parser's own command (so they list what
/// `--help` lists, the registries' names included).
fn docs(experiment: &Experiment) -> Option<Result<(), clidocs::DocsError>> {
    use clap::CommandFactory as _;
    match experiment {
        Experiment::Completions { shell } => {
            Some(clidocs::print_completions(&mut Cli::command(), *shell))
        }
        Experiment::Man { output } => Some(clidocs::man_pages_into(&Cli::command(), output)),
        _ => None,
    }
}

fn main() -> ExitCode {
    // On SIGINT, SIGTERM or SIGHUP: remove the temporary files and staging directories in
    // flight, so an interrupted run leaves the previous results as they were and nothing else.
    let _ = ctrlc::set_handler(|| {
        let removed = meshio::outfile::remove_in_flight();
        say!("interrupted: removed {removed} temporary files and directories");
        std::process::exit(130);
    });
    let cli = Cli::parse();
    if let Some(done) = docs(&cli.experiment) {
        return match done {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                say!("error: {e}");
                ExitCode::FAILURE
            }
        };
    }
    let result = match cli.experiment {
        Experiment::Completions { .. } | Experiment::Man { .. } => Ok(ExitCode::SUCCESS),
        Experiment::Ring(args) => ring::run(&args),
        Experiment::Curve(args) => curve::run(&args),
        Experiment::Sweep(args) => sweep::run(&args),
        Experiment::Merge(args) => sweep::merge(&args),
        Experiment::Interior(args) => interior::run(&args),
        Experiment::Solvers(args) => solvers::run(&args),
        Experiment::Fit(args) => fit::run(&args),
        Experiment::Convert(args) => convert::run(&args),
        Experiment::Estimation(args) => estimation::run(&args),
        Experiment::Realmesh(args) => realmesh::run(&args),
        Experiment::Schemes(args) => schemes::run(&args),
        Experiment::Franke(args) => franke::run(&args),
        Experiment::View(args) => view::run(&args),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            // The error, then each cause on its own `caused by:` line.
            say!("error: {}", error::chain(&e));
            ExitCode::from(e.exit_code())
        }
    }
}

//! `experiments -- sweep` and `experiments -- merge`: the ring study's measures over a grid of
//! meshes and parameters (data × resolution × scheme × scheme parameters × curves × solver ×
//! segments, [`grid`]), one task a point of the grid, as one comparison table.
//!
//! By default (no axis given) the grid is every data set × every curve construction × every
//! solver of `optimized` (forty tasks with the original testbed's five rules; the twenty of
//! chord, dbhs and optimized in the committed `results/sweep/`, which predates them), with the
//! modified Shirman–Séquin scheme at β = 1/3, c = 1 and 4 segments per patch edge.
//!
//! A scheduler drives it by task or by shard, and nothing depends on which runs a task (its
//! result is the same wherever it runs):
//!
//! - `sweep --list-tasks` writes the manifest (JSON: the grid's options and every task with its
//!   index, stable id, data and parameters) to standard output;
//! - `sweep --task ID` runs one task and writes `task-K.jsonl` (`K` its index), for GNU
//!   parallel, a Slurm array or Snakemake;
//! - `sweep --shard i/n` runs the tasks whose index is `i mod n` (round-robin, so shards get
//!   similar mixes) and writes `shard-i-of-n.jsonl`;
//! - a whole run writes everything at once.
//!
//! Every run also writes the manifest as `tasks.json` into its directory, and refuses a
//! directory whose manifest is another grid's. Results are JSON Lines, one line a task
//! (`experiments::shard`); `merge` joins the `shard-*.jsonl` and `task-*.jsonl` files of a
//! directory, checks every line against the manifest's task of its index (identity key by key,
//! every measure's type and range), that every task is present exactly once, and writes the
//! report a whole run writes: `results.jsonl` (pandas: `read_json(path, lines=True)`),
//! `report.json` and `report.md`.
//!
//! The grid, the manifest and the task function are the library's (`experiments::sweep_tasks`):
//! another front end gives the grid as JSON and runs the very tasks this command runs.

use std::fmt::Write as _;
use std::io::{BufRead, Read as _};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::builder::PossibleValuesParser;
use clap::{Arg, ArgAction, ArgMatches, Command};
use serde_json::{json, Value};
use solver::SolverKind;
use surface::scheme::{parameters_of, ParameterSpec, REGISTRY};

use crate::curve_args::InteriorOption;
use crate::error::ExperimentError;
use crate::output::{ensure_dir, pretty_json, write_result, Staged};
use crate::study::StudyError;
use experiments::shard::{check_line, ShardError, MAX_LINE_BYTES};
use experiments::sweep_tasks::grid::{self, Axes, Grid, Task, MANIFEST};
use experiments::sweep_tasks::{check_schemes, find_task, join_results, run_grid_task_keeping};

pub(crate) mod curvature;
mod pictures;

/// A shard `i/n`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    index: usize,
    count: usize,
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("expected i/n, got `{s}`"))?;
        let index: usize = i
            .trim()
            .parse()
            .map_err(|_| format!("bad shard index `{i}`"))?;
        let count: usize = n
            .trim()
            .parse()
            .map_err(|_| format!("bad shard count `{n}`"))?;
        if count == 0 || index >= count {
            return Err(format!("shard {index}/{count}: need 0 ≤ i < n"));
        }
        Ok(Shard { index, count })
    }
}

/// One list option a scheme parameter (`--beta 0.2,0.33`, `--c`, `--phong-alpha`, …),
/// generated from the scheme registry like the single-valued options of `fit`.
#[derive(Clone, Debug, Default)]
pub struct ParameterLists(Vec<(&'static ParameterSpec, Vec<f64>)>);

impl clap::FromArgMatches for ParameterLists {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut lists = Vec::new();
        for (p, _) in parameters_of(REGISTRY) {
            if let Some(values) = matches.get_many::<f64>(p.name) {
                lists.push((p, values.copied().collect()));
            }
        }
        Ok(ParameterLists(lists))
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

impl clap::Args for ParameterLists {
    fn augment_args(cmd: Command) -> Command {
        let mut cmd = cmd;
        for (p, owners) in parameters_of(REGISTRY) {
            cmd = cmd.arg(
                Arg::new(p.name)
                    .long(p.name)
                    .value_name(p.symbol)
                    .value_delimiter(',')
                    .action(ArgAction::Append)
                    .value_parser(clap::value_parser!(f64))
                    .help(format!(
                        "Values of {} [{}; range {}..={}; default: {}], a grid axis",
                        p.summary,
                        owners.join(", "),
                        p.range.0,
                        p.range.1,
                        p.default
                    )),
            );
        }
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

/// The schemes `--scheme` takes: the registry's and the subdivision schemes.
fn scheme_names() -> PossibleValuesParser {
    PossibleValuesParser::new(
        surface::scheme_names()
            .into_iter()
            .chain(subdiv::SCHEMES.iter().map(|e| e.name)),
    )
}

/// The solvers `--solver` takes.
fn solver_names() -> PossibleValuesParser {
    PossibleValuesParser::new(SolverKind::ALL.map(SolverKind::name))
}

/// Options of the `sweep` experiment. Every list is comma-separated or the option repeated,
/// each item once; an axis not given takes its default.
#[derive(clap::Args, Debug)]
pub struct SweepArgs {
    /// Data sets (ring, sphere, capsule, octa) or mesh files [default: every data set].
    #[arg(long, value_delimiter = ',', value_name = "NAME|FILE")]
    data: Vec<String>,
    /// Resolutions of the named data sets [default: each its own].
    #[arg(long, value_delimiter = ',', value_name = "N")]
    resolution: Vec<usize>,
    /// Surface schemes (subdivision schemes measured at the limit of three levels)
    /// [default: shirman-sequin].
    #[arg(long, value_delimiter = ',', value_parser = scheme_names())]
    scheme: Vec<String>,
    /// Curve constructions of the schemes on edge curves [default: every registered one].
    #[arg(long, value_delimiter = ',', value_parser = fitjob::cli::curve_method_names())]
    curves: Vec<String>,
    /// Solvers of the `optimized` construction [default: every one].
    #[arg(long, value_delimiter = ',', value_parser = solver_names())]
    solver: Vec<String>,
    /// The schemes' parameters, each a list (generated from the registry).
    #[command(flatten)]
    parameters: ParameterLists,
    /// Tessellation densities: segments per patch edge [default: 4].
    #[arg(short = 's', long, value_delimiter = ',', value_name = "N")]
    segments: Vec<usize>,
    /// A TOML file of axes (`data = ["ring", "bunny.ply"]`, `beta = [0.2, 0.33]`, `segments =
    /// [4, 8]`, …); an axis given on the command line replaces the file's.
    #[arg(long, value_name = "FILE.toml")]
    grid: Option<PathBuf>,
    /// The interior parameters of every task's surface.
    #[command(flatten)]
    interior: InteriorOption,
    /// How to estimate what a mesh file lacks (normals, shape tensors).
    #[arg(long, value_parser = fitjob::cli::estimator_names())]
    estimate: Option<String>,
    /// Write the task manifest (JSON) to standard output and stop.
    #[arg(long, conflicts_with_all = ["shard", "task"])]
    list_tasks: bool,
    /// Run the one task of this id (from `--list-tasks`) and write `task-K.jsonl`.
    #[arg(long, value_name = "ID", conflicts_with = "shard")]
    task: Option<String>,
    /// Run only the tasks `k` with `k mod n = i` and write `shard-i-of-n.jsonl` (join with
    /// `merge`).
    #[arg(long)]
    shard: Option<Shard>,
    /// Output directory.
    #[arg(short = 'o', long, default_value = "results/sweep")]
    output: PathBuf,
}

/// Options of the `merge` step.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// Directory holding `tasks.json` and the `shard-*.jsonl` and `task-*.jsonl` files; the
    /// merged report is written there.
    #[arg(short = 'o', long, default_value = "results/sweep")]
    output: PathBuf,
}

/// The grid of `args`: the grid file's axes under the command line's.
fn grid_of(args: &SweepArgs) -> Result<Grid, ExperimentError> {
    let given = |v: &Vec<String>| (!v.is_empty()).then(|| v.clone());
    let cli = Axes {
        data: given(&args.data),
        resolution: (!args.resolution.is_empty()).then(|| args.resolution.clone()),
        scheme: given(&args.scheme),
        curves: given(&args.curves),
        solver: given(&args.solver),
        segments: (!args.segments.is_empty()).then(|| args.segments.clone()),
        parameters: args.parameters.0.clone(),
        // `--interior` has a default: it replaces the file's only when not the default.
        interior: (args.interior.choice != surface::fairing::InteriorChoice::Default)
            .then_some(args.interior.choice),
        estimate: args.estimate.clone(),
    };
    let axes = match &args.grid {
        Some(path) => cli.over(grid::read_grid_file(path)?),
        None => cli,
    };
    Ok(Grid::new(axes)?)
}

/// Most tasks on the sweep's page, and their triangles together: a page near 3 MB.
const PAGE_VIEWS: usize = 8;
/// See [`PAGE_VIEWS`].
const PAGE_TRIANGLES: usize = 65_000;

/// Runs the sweep: the manifest, one task, one shard, or the whole grid.
pub fn run(args: &SweepArgs) -> Result<ExitCode, ExperimentError> {
    let grid = grid_of(args)?;
    let all = grid.tasks()?;
    let manifest = grid::manifest(&grid, &all);
    if args.list_tasks {
        let text = pretty_json(&manifest, "the task manifest")?;
        write_result(None, text.as_bytes())?;
        return Ok(ExitCode::SUCCESS);
    }
    // A bad scheme parameter is refused before any task runs (the grid checked the ranges;
    // the schemes build).
    check_schemes(&grid)?;
    let mine: Vec<&Task> = match (&args.task, args.shard) {
        (Some(id), _) => vec![find_task(&all, id)?],
        (None, shard) => all.iter().filter(|t| in_shard(shard, t.index)).collect(),
    };
    let partial = args.task.is_some() || args.shard.is_some();
    let out_dir = crate::output::results_dir(&args.output)?;
    if partial {
        // Refused before any work when the directory holds another grid's tasks.
        ensure_dir(&out_dir)?;
        check_manifest(&out_dir, &manifest)?;
    }
    let mut results = Vec::with_capacity(mine.len());
    // The curvature along paths of the data-set tasks, for a whole run's plots (sampled as each
    // task finishes; its surface is not kept).
    let mut paths = Vec::new();
    // The interactive page: the tasks of the grid's first data set (the ring's when it is in
    // the grid), side by side.
    let page_data = mine
        .iter()
        .find(|t| !t.file && t.data == "ring")
        .or_else(|| mine.iter().find(|t| !t.file))
        .map(|t| t.data.clone());
    let mut views = Vec::new();
    let mut page_triangles = 0usize;
    // Each data set's tasks' surfaces for its composite (at most pictures::MAX_COLUMNS).
    let mut shots: Vec<pictures::Group> = Vec::new();
    let started = Instant::now();
    let bar = progress::Progress::bar("sweep", mine.len() as u64);
    for t in &mine {
        bar.stage(&t.id);
        let (line, surface) = run_grid_task_keeping(t, &grid)?;
        if !partial {
            paths.extend(curvature::task_paths(t, &surface));
            let group = match t.resolution {
                Some(r) => format!("{}@{r}", t.data),
                None => t.data.clone(),
            };
            let k_true_max = surface.truth.as_deref().map(|tr| {
                surface
                    .tessellation
                    .positions
                    .iter()
                    .map(|p| tr.closest(p).gaussian().abs())
                    .fold(0.0f64, f64::max)
            });
            let shot = pictures::Shot {
                id: t.id.clone(),
                tess: surface.tessellation.clone(),
                k_true_max,
            };
            match shots.iter_mut().find(|g| g.name == group) {
                Some(g) => g.add(shot),
                None => shots.push(pictures::Group::new(group, shot)),
            }
            if page_data.as_deref() == Some(t.data.as_str())
                && views.len() < PAGE_VIEWS
                && page_triangles + surface.tessellation.faces.len() <= PAGE_TRIANGLES
            {
                page_triangles += surface.tessellation.faces.len();
                let mut view = crate::pages::fit_view(
                    &t.id,
                    &surface.tessellation,
                    None,
                    None,
                    surface.truth.as_deref(),
                );
                view.boundaries = None;
                views.push(view);
            }
        }
        results.push(line);
        bar.inc(1);
    }
    bar.finish();
    let lines = json_lines(&results)?;
    let manifest_text = pretty_json(&manifest, "the task manifest")?;
    if partial {
        check_manifest(&out_dir, &manifest)?;
        write_result(
            Some(&grid::manifest_path(&out_dir)),
            manifest_text.as_bytes(),
        )?;
        let name = match (args.shard, mine.first()) {
            (Some(s), _) => format!("shard-{}-of-{}.jsonl", s.index, s.count),
            (None, Some(t)) => format!("task-{}.jsonl", t.index),
            (None, None) => "task-none.jsonl".into(),
        };
        let path = out_dir.join(name);
        write_result(Some(&path), lines.as_bytes())?;
        say!(
            "sweep: {} of {} tasks in {:.2} s → {}",
            results.len(),
            all.len(),
            started.elapsed().as_secs_f64(),
            path.display()
        );
    } else {
        // A whole run replaces the directory; the partial results of the same grid are kept
        // (another scheduler's), those of another grid are not.
        let same_grid = read_manifest(&out_dir).is_ok_and(|m| m == manifest);
        let staged = Staged::begin_keeping(&out_dir, move |n| same_grid && is_partial(n))?;
        write_result(
            Some(&grid::manifest_path(staged.path())),
            manifest_text.as_bytes(),
        )?;
        write_report(staged.path(), &grid.json(), results, &lines)?;
        let page = match (&page_data, views.is_empty()) {
            (Some(data), false) => {
                let file = format!("{data}.html");
                crate::pages::write(
                    &staged.path().join(&file),
                    &format!("sweep: the tasks on {data}"),
                    views,
                )?;
                Some(file)
            }
            _ => None,
        };
        let mut composites = Vec::new();
        for group in &shots {
            composites.push(pictures::write(staged.path(), group)?);
        }
        curvature::write(staged.path(), &paths, page.as_deref(), &composites)?;
        staged.commit()?;
        say!(
            "sweep: {} tasks in {:.2} s → {}",
            all.len(),
            started.elapsed().as_secs_f64(),
            args.output.join("report.md").display()
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// The results as JSON Lines, one line a task.
fn json_lines(results: &[Value]) -> Result<String, ExperimentError> {
    let mut text = String::new();
    for r in results {
        let line = serde_json::to_string(r).map_err(|source| ExperimentError::Json {
            what: "a sweep result",
            source,
        })?;
        text.push_str(&line);
        text.push('\n');
    }
    Ok(text)
}

/// The manifest in `dir`, as JSON.
fn read_manifest(dir: &Path) -> Result<Value, ExperimentError> {
    let path = grid::manifest_path(dir);
    let text = std::fs::read_to_string(&path).map_err(|source| ExperimentError::Read {
        path: path.clone(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| ExperimentError::JsonFile { path, source })
}

/// Refuses a directory whose manifest is another grid's (its shards would not join this run's).
fn check_manifest(dir: &Path, manifest: &Value) -> Result<(), ExperimentError> {
    let path = grid::manifest_path(dir);
    if !path.exists() {
        return Ok(());
    }
    let theirs = read_manifest(dir)?;
    if theirs != *manifest {
        return Err(StudyError::OtherGrid {
            path,
            these: manifest["options"].to_string(),
            theirs: theirs["options"].to_string(),
        }
        .into());
    }
    Ok(())
}

/// True when task `k` belongs to `shard` (every task when there is no shard): round-robin over
/// the grid's order, so shard membership depends only on the task's index.
fn in_shard(shard: Option<Shard>, k: usize) -> bool {
    shard.is_none_or(|s| k % s.count == s.index)
}

/// A partial result file's name (`shard-i-of-n.jsonl`, `task-K.jsonl`): what `merge` reads and
/// a whole run of the same grid carries over.
fn is_partial(name: &str) -> bool {
    (name.starts_with("shard-") || name.starts_with("task-")) && name.ends_with(".jsonl")
}

/// Reads the result lines of `path` one at a time, none longer than [`MAX_LINE_BYTES`] held,
/// each checked against the manifest's task of its index.
fn read_checked(path: &Path, tasks: &[Value]) -> Result<Vec<(usize, Value)>, ExperimentError> {
    let shard_err = |source| ExperimentError::Shard {
        path: path.to_path_buf(),
        source,
    };
    let read_err = |source| ExperimentError::Read {
        path: path.to_path_buf(),
        source,
    };
    let meta = std::fs::metadata(path).map_err(read_err)?;
    if let Some(kind) = crate::study::special_kind(meta.file_type()) {
        return Err(StudyError::SpecialFile {
            path: path.to_path_buf(),
            kind,
        }
        .into());
    }
    let mut reader = std::io::BufReader::new(std::fs::File::open(path).map_err(read_err)?);
    let mut out = Vec::new();
    let mut line = 0;
    loop {
        line += 1;
        let mut buf = Vec::new();
        let n = (&mut reader)
            .take(MAX_LINE_BYTES as u64 + 1)
            .read_until(b'\n', &mut buf)
            .map_err(read_err)?;
        if n == 0 {
            break;
        }
        if buf.len() > MAX_LINE_BYTES {
            return Err(shard_err(ShardError::LineTooLong { line }));
        }
        let text = String::from_utf8_lossy(&buf);
        let one = experiments::shard::read_shard(&text, tasks.len()).map_err(|e| {
            shard_err(match e {
                ShardError::NotJson { message, .. } => ShardError::NotJson { line, message },
                ShardError::BadIndex { total, .. } => ShardError::BadIndex { line, total },
                other => other,
            })
        })?;
        for (k, v) in one.results {
            check_line(line, &v, &tasks[k]).map_err(shard_err)?;
            out.push((k, v));
        }
        if out.len() > tasks.len() {
            // More lines than tasks: some task repeats; found below with its name.
            break;
        }
    }
    Ok(out)
}

/// Joins the partial results of a directory into the report.
pub fn merge(args: &MergeArgs) -> Result<ExitCode, ExperimentError> {
    let dir = crate::output::results_dir(&args.output)?;
    let manifest = read_manifest(&dir)?;
    let tasks: Vec<Value> = manifest["tasks"].as_array().cloned().unwrap_or_default();
    let total = tasks.len();
    let read_dir = std::fs::read_dir(&dir).map_err(|source| ExperimentError::Read {
        path: dir.clone(),
        source,
    })?;
    let mut paths: Vec<PathBuf> = read_dir
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(is_partial)
        })
        .collect();
    paths.sort();
    let results = join_results(
        &tasks,
        paths
            .iter()
            .map(|p| read_checked(p, &tasks).map(|lines| (p.clone(), lines))),
    )?;
    let lines = json_lines(&results)?;
    let staged = Staged::begin_keeping(&dir, |n| is_partial(n) || n == MANIFEST)?;
    write_report(staged.path(), &manifest["options"], results, &lines)?;
    staged.commit()?;
    say!(
        "merge: {} file(s), {total} tasks → {}",
        paths.len(),
        args.output.join("report.md").display()
    );
    Ok(ExitCode::SUCCESS)
}

/// A number formatted by `fmt`, or a dash where the measure does not apply (`null`: no G1
/// column and no curves for subdivision).
fn or_dash(v: &Value, fmt: impl Fn(f64) -> String) -> String {
    v.as_f64().map_or_else(|| "—".to_string(), fmt)
}

/// Writes `results.jsonl` (`lines`), `report.json` (the grid's `options` and every result) and
/// `report.md` (one table row a task) into `out`.
/// A ratio summary of `surface::measure::ends` as `median (share above)`, `—` where absent.
fn ends(v: &Value) -> String {
    match (v["median"].as_f64(), v["above_reference"].as_f64()) {
        (Some(m), Some(a)) => format!("{m:.3} ({:.0} %)", 100.0 * a),
        _ => "—".into(),
    }
}

fn write_report(
    out: &Path,
    options: &Value,
    results: Vec<Value>,
    lines: &str,
) -> Result<(), ExperimentError> {
    write_result(Some(&out.join("results.jsonl")), lines.as_bytes())?;
    let report = json!({"experiment": "sweep", "options": options, "results": results});
    let text = pretty_json(&report, "the sweep report")?;
    write_result(Some(&out.join("report.json")), text.as_bytes())?;
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Sweep: data × schemes × boundary curves × solvers × parameters\n"
    );
    // The same text for a whole run and for its tasks and shards merged (the merged report
    // equals the whole one): the grid below says what ran, `scripts/results.sh` the command.
    let _ = writeln!(md, "Written by `cargo run --release -p experiments -- sweep` over the grid given below (or its tasks and shards joined by `merge`; `scripts/results.sh` has the commands of the committed sweeps). Every task of the grid below (by default every data set at its default resolution × every curve construction × every solver of `optimized`, with the modified Shirman–Séquin scheme at β = 1/3, c = 1), tessellated at the task's segments per patch edge (default 4), measured against the true surface (— for a mesh file, which has none); a subdivision scheme (`--scheme loop|loop-warren|catmull-clark`) is measured at the limit of three levels with curvature estimated on that mesh, its data-to-limit distance in `report.json`. One line a task in `results.jsonl`. *ends/middle* is the seeds' finding that boundary curves gather their curvature near their ends (`surface::measure::ends`): the mean |curvature| over the two end fifths of each edge against the middle (0.3–0.7), for the curve itself, for the surface's normal curvature along the edge, and for the true surface along the same directions; each cell is the median over the edges and, in brackets, the share of edges above the truth's ratio (above 1 for the curve and the truth). Grid: `{options}`.\n");
    let _ = writeln!(md, "| task | faces | position max | normal RMS (°) | K RMS | H RMS | G1 (rad) | κ error max | shortest α | fallbacks | ends/middle: curve | surface | truth | fit (ms) |");
    let _ = writeln!(
        md,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in &results {
        let e = &r["errors"];
        let c = &r["curve_measures"];
        let fallbacks = if c.is_null() {
            "—".to_string()
        } else {
            c["fallbacks_to_chord"].to_string()
        };
        let f = |v: &Value| v.as_f64().unwrap_or(f64::NAN);
        let _ = writeln!(
            md,
            "| {} | {} | {:.3e} | {:.3} | {:.4} | {:.4} | {} | {} | {} | {} | {} | {} | {} | {:.2} |",
            r["task"].as_str().unwrap_or("?"),
            r["faces"],
            f(&e["position_max"]),
            f(&e["normal_rms_degrees"]),
            f(&e["gaussian_rms"]),
            f(&e["mean_rms"]),
            or_dash(&r["g1_defect_radians"], |x| format!("{x:.1e}")),
            or_dash(&c["end_curvature_error_max"], |x| format!("{x:.4}")),
            or_dash(&c["shortest_alpha"], |x| format!("{x:.4}")),
            fallbacks,
            ends(&r["ends"]["curves"]),
            ends(&r["ends"]["surface"]),
            ends(&r["ends"]["truth"]),
            f(&r["fit_time_seconds"]) * 1e3
        );
    }
    write_result(Some(&out.join("report.md")), md.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_task_list() {
        let n = Grid::new(Axes::default()).unwrap().tasks().unwrap().len();
        // Four data sets × every construction, those that take a solver once per solver (3).
        assert_eq!(
            n,
            4 * curves::REGISTRY
                .iter()
                .map(|e| if curves::takes_solver(e.name) { 3 } else { 1 })
                .sum::<usize>()
        );
        for count in 1..=7 {
            let mut seen = vec![0; n];
            for index in 0..count {
                for (k, slot) in seen.iter_mut().enumerate() {
                    if in_shard(Some(Shard { index, count }), k) {
                        *slot += 1;
                    }
                }
            }
            // Every task in exactly one shard, and in the unsharded run.
            assert!(seen.iter().all(|c| *c == 1), "{count}: {seen:?}");
            assert!((0..n).all(|k| in_shard(None, k)));
        }
        assert_eq!("2/5".parse::<Shard>(), Ok(Shard { index: 2, count: 5 }));
        assert!("5/5".parse::<Shard>().is_err());
        assert!("x".parse::<Shard>().is_err());
    }

    #[test]
    fn subdivision_runs_have_one_task_per_data_set() {
        assert!(grid::is_subdivision("loop") && grid::is_subdivision("catmull-clark"));
        assert!(!grid::is_subdivision("nielson") && !grid::is_subdivision("shirman-sequin"));
        let g = Grid::new(Axes {
            scheme: Some(vec!["loop".into()]),
            ..Axes::default()
        })
        .unwrap();
        let t = g.tasks().unwrap();
        assert_eq!(t.len(), crate::datasets::all().len());
        assert!(t
            .iter()
            .all(|t| t.curves.is_none() && t.solver.is_none() && t.segments.is_none()));
    }
}

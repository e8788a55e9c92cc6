//! `experiments -- sweep` and `experiments -- merge`: the ring study's measures over every data
//! set × curve construction × solver, as one comparison table.
//!
//! The task list is fixed and ordered (data sets in the studies' order — the ring first, then
//! the `surface` registry's order —, then constructions in `curves::REGISTRY` order, then — for
//! `optimized` — solvers). `--shard i/n` runs the tasks whose index is `i mod n`
//! (round-robin, so shards get similar mixes) and writes `shard-i-of-n.json`; `merge` joins the
//! shard files of a directory, checks that every task is present exactly once, and writes the
//! same `report.json`/`report.md` an unsharded run writes. Nothing depends on the shard: a task's
//! result is the same whichever shard runs it, so any scheduler (a Slurm array with
//! `--shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`, GNU parallel) can run the shards.

use std::fmt::Write as _;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use curves::MethodOptions;
use serde_json::{json, Value};
use solver::SolverKind;
use surface::compare_with_truth;

use crate::curve_args::InteriorOption;
use crate::error::ExperimentError;
use crate::output::{ensure_dir, pretty_json, write_result, Staged};

/// The construction that takes a solver: the sweep runs it once per solver (`SolverKind::ALL`),
/// every other construction once.
const SOLVED_METHOD: &str = "optimized";
/// Tessellation density of the sweep's measurements.
const SAMPLING: usize = 4;

/// One task of the sweep.
#[derive(Clone, Debug, PartialEq)]
struct Task {
    dataset: &'static str,
    curves: &'static str,
    solver: Option<SolverKind>,
}

impl Task {
    fn id(&self) -> String {
        match self.solver {
            Some(s) => format!("{}/{}/{}", self.dataset, self.curves, s),
            None => format!("{}/{}", self.dataset, self.curves),
        }
    }
}

/// The curve name of a subdivision task (subdivision makes no boundary curves).
const NO_CURVES: &str = "none";

/// True when `scheme` is a subdivision scheme (`subdiv::SCHEMES`), not a Bézier or sampled
/// surface scheme.
fn is_subdivision(scheme: &str) -> bool {
    !surface::scheme_names().contains(&scheme) && subdiv::scheme_by_name(scheme).is_ok()
}

/// The task list of a run with `scheme`: [`tasks`], or for a subdivision scheme one task per
/// data set (no curves, no solver).
fn tasks_for(scheme: &str) -> Vec<Task> {
    if is_subdivision(scheme) {
        crate::datasets::all()
            .into_iter()
            .map(|dataset| Task {
                dataset,
                curves: NO_CURVES,
                solver: None,
            })
            .collect()
    } else {
        tasks()
    }
}

/// A subdivision task: the limit surface of [`crate::schemes::SUBDIVISION_LEVELS`] steps
/// measured against the truth exactly as the schemes study measures it (curvature estimated
/// on the limit mesh; no G1 column: the schemes are C2 away from extraordinary points and
/// measured at the limit vertices), with the largest distance from a data point to the limit
/// surface (subdivision approximates).
fn run_subdivision_task(t: &Task, scheme: &str) -> Result<Value, ExperimentError> {
    let start = Instant::now();
    let data = surface::dataset_by_name(t.dataset, None).map_err(ExperimentError::from)?;
    let (tess, to_limit) =
        crate::schemes::subdivision_surface(&data.mesh, scheme, crate::schemes::SUBDIVISION_LEVELS)
            .map_err(|source| ExperimentError::Subdivision {
                subject: t.id(),
                source,
            })?;
    let fit_time = start.elapsed().as_secs_f64();
    let errors = compare_with_truth(&tess, data.surface.as_ref());
    Ok(json!({
        "task": t.id(),
        "dataset": t.dataset,
        "curves": t.curves,
        "solver": Value::Null,
        "faces": data.mesh.num_faces(),
        "g1_defect_radians": Value::Null,
        "levels": crate::schemes::SUBDIVISION_LEVELS,
        "data_to_limit_max": to_limit,
        "errors": serde_json::to_value(errors).unwrap_or(Value::Null),
        "curve_measures": Value::Null,
        "fit_time_seconds": fit_time,
        "task_time_seconds": start.elapsed().as_secs_f64(),
    }))
}

/// Every data set (in the studies' order, [`crate::datasets::all`]) × every registered
/// construction (registry order) × every solver for [`SOLVED_METHOD`].
fn tasks() -> Vec<Task> {
    let mut out = Vec::new();
    for dataset in crate::datasets::all() {
        for curves in curves::REGISTRY.iter().map(|e| e.name) {
            if curves == SOLVED_METHOD {
                for s in SolverKind::ALL {
                    out.push(Task {
                        dataset,
                        curves,
                        solver: Some(s),
                    });
                }
            } else {
                out.push(Task {
                    dataset,
                    curves,
                    solver: None,
                });
            }
        }
    }
    out
}

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

/// Options of the `sweep` experiment.
#[derive(clap::Args, Debug)]
pub struct SweepArgs {
    /// Run only the tasks `k` with `k mod n = i` and write `shard-i-of-n.json` (join with
    /// `merge`).
    #[arg(long)]
    shard: Option<Shard>,
    /// The interior parameters of every task's surface.
    #[command(flatten)]
    interior: InteriorOption,
    /// The surface scheme of every task.
    #[command(flatten)]
    scheme: fitjob::cli::SchemeArgs,
    /// Output directory.
    #[arg(long, default_value = "results/sweep")]
    out: PathBuf,
}

/// Options of the `merge` step.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// Directory holding the `shard-*-of-*.json` files; the merged report is written there.
    #[arg(long, default_value = "results/sweep")]
    out: PathBuf,
}

fn run_task(
    t: &Task,
    interior: surface::fairing::InteriorChoice,
    scheme: &fitjob::cli::SchemeArgs,
) -> Result<Value, ExperimentError> {
    let start = Instant::now();
    let data = surface::dataset_by_name(t.dataset, None).map_err(ExperimentError::from)?;
    let mesh = &data.mesh;
    let options = MethodOptions {
        solver: t.solver.unwrap_or(SolverKind::ExactPenalty),
        ..MethodOptions::default()
    };
    let problems = surface::curve_stats::edge_problems(mesh).map_err(|source| {
        ExperimentError::EdgeProblems {
            subject: t.id(),
            source,
        }
    })?;
    // The fit and its G1 by the fit job, as every front end gets them.
    let (f, g1, fit_time) = crate::input::fit_kept(fitjob::FitOptions {
        input: fitjob::InputOptions {
            source: fitjob::Source::DataSet {
                name: t.dataset.into(),
                resolution: None,
            },
            ..fitjob::InputOptions::default()
        },
        scheme: scheme.scheme.clone(),
        scheme_options: scheme.options.clone(),
        curves: t.curves.into(),
        method_options: options,
        interior,
        ..fitjob::FitOptions::default()
    })?;
    let cs = surface::curve_stats::curve_stats(&problems, &f);
    let tess = surface::tessellate_fit(mesh, &f, SAMPLING).map_err(|source| {
        ExperimentError::Tessellate {
            subject: t.id(),
            source,
        }
    })?;
    let errors = compare_with_truth(&tess, data.surface.as_ref());
    Ok(json!({
        "task": t.id(),
        "dataset": t.dataset,
        "curves": t.curves,
        "solver": t.solver.map(|s| s.name()),
        "faces": mesh.num_faces(),
        "g1_defect_radians": g1.max_angle(),
        "errors": serde_json::to_value(errors).unwrap_or(Value::Null),
        "curve_measures": {
            "end_curvature_error_max": cs.end_curvature_error_max,
            "shortest_alpha": cs.shortest_alpha,
            "curvature_variation_max": cs.curvature_variation_max,
            "fallbacks_to_chord": cs.fallbacks,
            "unconverged_optimizations": cs.unconverged,
        },
        "fit_time_seconds": fit_time,
        "task_time_seconds": start.elapsed().as_secs_f64(),
    }))
}

/// Runs the sweep (or one shard of it).
pub fn run(args: &SweepArgs) -> Result<ExitCode, ExperimentError> {
    let subdivision = args.scheme.is_subdivision();
    // A bad scheme or parameter is refused before any task runs.
    if !subdivision {
        surface::scheme_by_name(&args.scheme.scheme, &args.scheme.options)?;
    }
    let all = tasks_for(&args.scheme.scheme);
    let mine: Vec<(usize, &Task)> = all
        .iter()
        .enumerate()
        .filter(|(k, _)| in_shard(args.shard, *k))
        .collect();
    let tty = std::io::stderr().is_terminal();
    let mut results = Vec::with_capacity(mine.len());
    for (done, (k, t)) in mine.iter().enumerate() {
        if tty {
            say_inline!("\rsweep: [{:>2}/{}] {:<32}", done + 1, mine.len(), t.id());
        }
        let mut v = if subdivision {
            run_subdivision_task(t, &args.scheme.scheme)?
        } else {
            run_task(t, args.interior.choice, &args.scheme)?
        };
        v["interior"] = json!(args.interior.choice.to_string());
        v["index"] = json!(k);
        results.push(v);
    }
    if tty {
        say!();
    }
    ensure_dir(&args.out)?;
    match args.shard {
        Some(s) => {
            let shard = json!({"shard": [s.index, s.count], "tasks_total": all.len(),
                               "options": options_json(args.interior.choice, &args.scheme), "results": results});
            let text = pretty_json(&shard, "the shard report")?;
            let path = args
                .out
                .join(format!("shard-{}-of-{}.json", s.index, s.count));
            write_result(Some(&path), text.as_bytes())?;
            say!(
                "sweep: shard {}/{}: {} tasks → {}",
                s.index,
                s.count,
                results.len(),
                path.display()
            );
        }
        None => {
            let staged = Staged::begin_keeping(&args.out, is_shard)?;
            write_report(
                staged.path(),
                &options_json(args.interior.choice, &args.scheme),
                results,
            )?;
            staged.commit()?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// True when task `k` belongs to `shard` (every task when there is no shard): round-robin over
/// the fixed task order, so shard membership depends only on the task's index.
fn in_shard(shard: Option<Shard>, k: usize) -> bool {
    shard.is_none_or(|s| k % s.count == s.index)
}

/// A shard file's name (`shard-i-of-n.json`): carried over when a report is swapped in.
fn is_shard(name: &str) -> bool {
    name.starts_with("shard-") && name.ends_with(".json")
}

/// The options every task of a run shares: what a shard records and `merge` compares.
/// Every scheme parameter is recorded (generated from the registry: `beta`, `c`, `phong_alpha`,
/// …), so shards of runs with different parameters are told apart.
fn options_json(
    interior: surface::fairing::InteriorChoice,
    scheme: &fitjob::cli::SchemeArgs,
) -> Value {
    let mut v =
        json!({"interior": interior.to_string(), "sampling": SAMPLING, "scheme": scheme.scheme});
    for (p, _) in surface::scheme::parameters_of(surface::scheme::REGISTRY) {
        v[p.key()] = json!(scheme.options.value(p));
    }
    v
}

/// Joins shard files into the report.
pub fn merge(args: &MergeArgs) -> Result<ExitCode, ExperimentError> {
    let read_dir = std::fs::read_dir(&args.out).map_err(|source| ExperimentError::Read {
        path: args.out.clone(),
        source,
    })?;
    let mut paths: Vec<PathBuf> = read_dir
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.file_name().and_then(|n| n.to_str()).is_some_and(is_shard))
        .collect();
    paths.sort();
    let texts = paths
        .iter()
        .map(|p| {
            std::fs::read_to_string(p)
                .map(|t| (p, t))
                .map_err(|source| ExperimentError::Read {
                    path: p.clone(),
                    source,
                })
        })
        .collect::<Result<Vec<_>, _>>()?;
    // The task list follows the run's scheme (subdivision runs have one task per data set),
    // read from the first shard's options; the shards' options are compared below.
    let scheme_of_run = texts
        .first()
        .and_then(|(_, t)| serde_json::from_str::<Value>(t).ok())
        .and_then(|v| v["options"]["scheme"].as_str().map(str::to_string))
        .unwrap_or_else(|| surface::DEFAULT_SCHEME.to_string());
    let all = tasks_for(&scheme_of_run);
    let total = all.len();
    let mut results: Vec<Option<Value>> = vec![None; total];
    let mut options: Option<(PathBuf, Value)> = None;
    for (p, text) in &texts {
        let p = *p;
        let shard = experiments::shard::read_shard(text, total).map_err(|source| {
            ExperimentError::Shard {
                path: p.clone(),
                source,
            }
        })?;
        // Shards of different runs must not be joined: their options must agree.
        let these = shard.options.clone();
        match &options {
            None => options = Some((p.clone(), these)),
            Some((first, o)) if *o != these => {
                return Err(ExperimentError::ShardOptionsDiffer {
                    path: p.clone(),
                    these: these.to_string(),
                    first: first.clone(),
                    theirs: o.to_string(),
                })
            }
            Some(_) => {}
        }
        for (k, r) in shard.results {
            if results[k].is_some() {
                return Err(ExperimentError::ShardTaskRepeated {
                    path: p.clone(),
                    index: k,
                    task: r["task"].clone(),
                });
            }
            results[k] = Some(r);
        }
    }
    let missing: Vec<String> = results
        .iter()
        .enumerate()
        .filter(|(_, r)| r.is_none())
        .map(|(k, _)| all[k].id())
        .collect();
    if !missing.is_empty() {
        return Err(ExperimentError::ShardTasksMissing {
            missing,
            total,
            files: paths.len(),
        });
    }
    let options = options.map(|(_, o)| o).unwrap_or(Value::Null);
    let staged = Staged::begin_keeping(&args.out, is_shard)?;
    write_report(
        staged.path(),
        &options,
        results.into_iter().flatten().collect(),
    )?;
    staged.commit()?;
    say!(
        "merge: {} shard file(s), {total} tasks → {}",
        paths.len(),
        args.out.join("report.md").display()
    );
    Ok(ExitCode::SUCCESS)
}

/// A number formatted by `fmt`, or a dash where the measure does not apply (`null`: no G1
/// column and no curves for subdivision).
fn or_dash(v: &Value, fmt: impl Fn(f64) -> String) -> String {
    v.as_f64().map_or_else(|| "—".to_string(), fmt)
}

fn write_report(out: &Path, options: &Value, results: Vec<Value>) -> Result<(), ExperimentError> {
    let report = json!({"experiment": "sweep", "sampling": SAMPLING, "beta": surface::shirman_sequin::DEFAULT_BETA,
                        "c": surface::shirman_sequin::DEFAULT_C, "options": options, "results": results});
    let text = pretty_json(&report, "the sweep report")?;
    write_result(Some(&out.join("report.json")), text.as_bytes())?;
    let mut md = String::new();
    let _ = writeln!(md, "# Sweep: data sets × boundary curves × solvers\n");
    let _ = writeln!(md, "Written by `cargo run --release -p experiments -- sweep` (or shards joined by `merge`). Every data set at its default resolution, the surface scheme of the options (default: the modified Shirman–Séquin scheme with β = 1/3, c = 1), tessellated at s = {SAMPLING} per patch edge, measured against the true surface; a subdivision scheme (`--scheme loop|loop-warren|catmull-clark`) is measured at the limit of three levels with curvature estimated on that mesh, its data-to-limit distance in `report.json`. Options: `{options}`.\n");
    let _ = writeln!(md, "| task | faces | position max | normal RMS (°) | K RMS | H RMS | G1 (rad) | κ error max | shortest α | fallbacks | fit (ms) |");
    let _ = writeln!(
        md,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
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
            "| {} | {} | {:.3e} | {:.3} | {:.4} | {:.4} | {} | {} | {} | {} | {:.2} |",
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
        let n = tasks().len();
        assert_eq!(n, 20);
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
        assert!(is_subdivision("loop") && is_subdivision("catmull-clark"));
        assert!(!is_subdivision("nielson") && !is_subdivision("shirman-sequin"));
        let t = tasks_for("loop");
        assert_eq!(t.len(), crate::datasets::all().len());
        assert!(t
            .iter()
            .all(|t| t.curves == NO_CURVES && t.solver.is_none()));
        assert_eq!(tasks_for("nielson"), tasks());
    }
}

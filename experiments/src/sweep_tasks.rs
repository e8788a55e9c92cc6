//! The tasks of `experiments -- sweep` as a library: the grid ([`grid`]), its manifest and the
//! one task function, so that another front end (a Python package on Dask workers) runs the very
//! code the binary runs and gets the lines it writes.
//!
//! A grid is given as a JSON object with the keys and values of a grid file (`sweep --grid
//! FILE.toml`: `data`, `resolution`, `scheme`, `curves`, `solver`, `segments`, every scheme
//! parameter such as `beta`, `c` or `phong-alpha`, `interior`, `estimate`; each a value or an
//! array), read by the grid file's own reader ([`grid::axes_from_json`]):
//!
//! - [`grid_manifest`] is what `sweep --list-tasks` prints for that grid;
//! - [`run_task`] runs one task of it by id and returns the line `sweep --task ID` writes to
//!   `task-K.jsonl` (only the `*_time_seconds` measures differ from run to run);
//! - [`merge_results`] checks result lines against a manifest and orders them, as `merge`
//!   does with the shard files.
//!
//! Their error, [`SweepError`], shows the message the command line prints for the same error
//! and tells a usage error (the grid or the id is wrong) from a run error (the input or the
//! machine refused).

pub mod grid;
pub mod paths;

use std::path::PathBuf;
use std::time::Instant;

use curves::MethodOptions;
use serde_json::{json, Value};
use solver::SolverKind;
use surface::compare_with_truth;

use crate::error::ExperimentError;
use crate::shard::{check_line, task_index, ShardError};
use crate::study::StudyError;
use grid::{Axes, Grid, Task};

/// Why a grid, a task or a merge of this module failed: the command line's error, shown as the
/// command line shows it (boxed: the error travels far, the result stays small).
#[derive(Debug)]
pub struct SweepError(Box<ExperimentError>);

impl SweepError {
    /// True for a usage error (a bad grid key or value, an unknown task id: the command line
    /// exits with status 2), false for a run error (status 1: the input, the machine or a
    /// result refused).
    pub fn is_usage(&self) -> bool {
        self.0.exit_code() == 2
    }

    /// The command line's exit status for this error (2 usage, 1 run).
    pub fn exit_code(&self) -> u8 {
        self.0.exit_code()
    }

    /// The error itself, with its causes as sources.
    pub fn error(&self) -> &ExperimentError {
        &self.0
    }
}

/// The message the command line prints after `error: `: the error, then each cause on its own
/// `caused by:` line ([`crate::error::chain`]). The causes are in the message, so
/// [`std::error::Error::source`] gives none (a reporter would show them twice).
impl std::fmt::Display for SweepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&crate::error::chain(&self.0))
    }
}

impl std::error::Error for SweepError {}

impl<E: Into<ExperimentError>> From<E> for SweepError {
    fn from(e: E) -> Self {
        SweepError(Box::new(e.into()))
    }
}

/// The grid of a JSON object of axes (a grid file's keys and values), settled and checked as a
/// grid file's is ([`grid::axes_from_json`], [`Grid::new`]), with its tasks.
pub fn grid_of_json(axes: &Value) -> Result<(Grid, Vec<Task>), SweepError> {
    let axes: Axes =
        grid::axes_from_json(axes).map_err(|message| StudyError::JsonGrid { message })?;
    let grid = Grid::new(axes)?;
    let tasks = grid.tasks()?;
    Ok((grid, tasks))
}

/// The task manifest of the grid `axes` (a JSON object with the keys and values of a grid
/// file): the JSON `sweep --list-tasks` prints for the same grid (the grid's options as run,
/// `tasks_total`, and every task's identity with its index and id), key for key.
pub fn grid_manifest(axes: &Value) -> Result<Value, SweepError> {
    let (grid, tasks) = grid_of_json(axes)?;
    Ok(grid::manifest(&grid, &tasks))
}

/// Runs the task `id` of the grid `axes` (the JSON object [`grid_manifest`] takes, not the
/// manifest) and returns its result: the line `sweep --task ID` writes to `task-K.jsonl` for
/// the same grid, the same keys and numbers (only `fit_time_seconds` and `task_time_seconds`
/// differ from run to run). The steps of `sweep --task`, but no file is written: the grid is
/// checked, the schemes built ([`check_schemes`]), the task found ([`find_task`]) and run
/// ([`run_grid_task`]). Mesh files of `data` are read relative to the working directory, as
/// the command line reads them.
pub fn run_task(axes: &Value, id: &str) -> Result<Value, SweepError> {
    let (grid, tasks) = grid_of_json(axes)?;
    check_schemes(&grid)?;
    let task = find_task(&tasks, id)?;
    Ok(run_grid_task(task, &grid)?)
}

/// Refuses a grid with a scheme that does not build, before any task runs (the grid checked the
/// parameters' ranges; subdivision schemes are checked by name).
pub fn check_schemes(grid: &Grid) -> Result<(), ExperimentError> {
    for s in &grid.schemes {
        if !grid::is_subdivision(s) {
            surface::scheme_by_name(s, &surface::SchemeOptions::default())?;
        }
    }
    Ok(())
}

/// The task of `tasks` with id `id`; an unknown id is a usage error naming it (`--task ID`).
pub fn find_task<'a>(tasks: &'a [Task], id: &str) -> Result<&'a Task, ExperimentError> {
    tasks.iter().find(|t| t.id == id).ok_or_else(|| {
        StudyError::UnknownTask {
            id: id.to_string(),
            total: tasks.len(),
        }
        .into()
    })
}

/// The label of the results given to [`merge_results`] in its messages (they come from no file).
const GIVEN_RESULTS: &str = "<results>";

/// Checks result lines against `manifest` (the value [`grid_manifest`] returns, or a sweep's
/// `tasks.json`) as `merge` checks the lines of its shard files, and returns them in task order:
/// each line a JSON object whose index is a task of the manifest and whose identity is that
/// task's, key for key, with every measure of its type and range; every task exactly once. The
/// messages count the lines from 1 in the order given and name the results `<results>`.
pub fn merge_results(manifest: &Value, results: Vec<Value>) -> Result<Vec<Value>, SweepError> {
    let tasks: Vec<Value> = manifest["tasks"].as_array().cloned().unwrap_or_default();
    let path = PathBuf::from(GIVEN_RESULTS);
    let shard_err = |source| ExperimentError::Shard {
        path: path.clone(),
        source,
    };
    let mut checked = Vec::with_capacity(results.len());
    for (i, v) in results.into_iter().enumerate() {
        let line = i + 1;
        let k = task_index(line, &v, tasks.len()).map_err(shard_err)?;
        check_line(line, &v, &tasks[k]).map_err(shard_err)?;
        checked.push((k, v));
    }
    Ok(join_results(&tasks, [Ok((path, checked))])?)
}

/// Joins the checked results of several files (each with its task indices), read one at a time
/// as `files` yields them, into one list in task order: a file that could not be read stops the
/// join with its error, a task found twice is refused with the file it appears again in, and
/// tasks found nowhere are named. What `merge` and [`merge_results`] share.
pub fn join_results(
    tasks: &[Value],
    files: impl IntoIterator<Item = Result<(PathBuf, Vec<(usize, Value)>), ExperimentError>>,
) -> Result<Vec<Value>, ExperimentError> {
    let total = tasks.len();
    let mut count = 0;
    let mut results: Vec<Option<Value>> = vec![None; total];
    for file in files {
        let (p, lines) = file?;
        count += 1;
        for (i, (k, r)) in lines.into_iter().enumerate() {
            // The readers give indices below `total`; one beyond is refused, never indexed.
            let Some(slot) = results.get_mut(k) else {
                return Err(ExperimentError::Shard {
                    path: p,
                    source: ShardError::BadIndex { line: i + 1, total },
                });
            };
            if slot.is_some() {
                return Err(ExperimentError::ShardTaskRepeated {
                    path: p,
                    index: k,
                    task: r["task"].clone(),
                });
            }
            *slot = Some(r);
        }
    }
    let missing: Vec<String> = results
        .iter()
        .enumerate()
        .filter(|(_, r)| r.is_none())
        .map(|(k, _)| tasks[k]["task"].as_str().unwrap_or("?").to_string())
        .collect();
    if !missing.is_empty() {
        return Err(ExperimentError::ShardTasksMissing {
            missing,
            total,
            files: count,
        });
    }
    Ok(results.into_iter().flatten().collect())
}

/// The scheme options of a task: its parameters' values, the others at their defaults.
fn scheme_options(t: &Task) -> surface::SchemeOptions {
    let mut o = surface::SchemeOptions::default();
    for (p, v) in &t.parameters {
        o.set(p, *v);
    }
    o
}

/// Runs one task: its identity ([`Task::identity`]) followed by its measures, checked as
/// `merge` checks them (a measure that is not finite is an error naming the task, never a
/// `null` passed off as a number).
pub fn run_grid_task(t: &Task, grid: &Grid) -> Result<Value, ExperimentError> {
    run_grid_task_keeping(t, grid).map(|(v, _)| v)
}

/// The surface a task measured: its tessellation (in world coordinates) and the true surface
/// of its data set, if any; what the sweep's curvature plots ([`paths`]) read.
pub struct TaskSurface {
    /// The tessellation the task's errors were measured on.
    pub tessellation: surface::Tessellation,
    /// The data set's true surface (`None` for a mesh file).
    pub truth: Option<std::sync::Arc<dyn surface::AnalyticSurface>>,
}

/// [`run_grid_task`], also giving back the surface it measured.
pub fn run_grid_task_keeping(
    t: &Task,
    grid: &Grid,
) -> Result<(Value, TaskSurface), ExperimentError> {
    let start = Instant::now();
    let subject = crate::datasets::load_subject(&t.data, t.resolution, &grid.estimate)?;
    let mesh = &subject.mesh;
    let faces = mesh.num_faces() as u128;
    // The fit and its tessellation (at most six patches a face), estimated before either is
    // made.
    if let Some(s) = t.segments {
        crate::limits::check_memory(
            &format!("sweep task {}", t.id),
            faces
                .saturating_mul(crate::limits::FIT_BYTES_PER_FACE as u128)
                .saturating_add(crate::limits::tessellation_bytes(
                    faces.saturating_mul(6),
                    s,
                )),
        )?;
    }
    let mut v = t.identity();
    v["faces"] = json!(mesh.num_faces());
    let tessellation: surface::Tessellation;
    if t.subdivision {
        let (tess, to_limit) = crate::subdivision::subdivision_surface(
            mesh,
            &t.scheme,
            crate::subdivision::SUBDIVISION_LEVELS,
        )
        .map_err(|source| ExperimentError::Subdivision {
            subject: t.id.clone(),
            source,
        })?;
        let fit_time = start.elapsed().as_secs_f64();
        let errors = subject
            .truth
            .as_deref()
            .map(|truth| compare_with_truth(&tess, truth));
        v["g1_defect_radians"] = Value::Null;
        v["levels"] = json!(crate::subdivision::SUBDIVISION_LEVELS);
        v["data_to_limit_max"] = json!(to_limit);
        v["errors"] = serde_json::to_value(errors).unwrap_or(Value::Null);
        v["curve_measures"] = Value::Null;
        v["fit_time_seconds"] = json!(fit_time);
        tessellation = tess;
    } else {
        let options = MethodOptions {
            solver: t.solver.unwrap_or(SolverKind::ExactPenalty),
            ..MethodOptions::default()
        };
        let curves = t.curves.clone();
        // The fit and its G1 by the fit job, as every front end gets them.
        let crate::input::KeptFit {
            fit: f,
            g1,
            seconds: fit_time,
            ..
        } = crate::input::fit_kept(fitjob::FitOptions {
            input: fitjob::InputOptions {
                source: fitjob::Source::Prepared {
                    label: t.id.clone(),
                    mesh: Box::new(mesh.clone()),
                    frame: subject.frame,
                },
                ..fitjob::InputOptions::default()
            },
            scheme: t.scheme.clone(),
            scheme_options: scheme_options(t),
            curves: curves
                .clone()
                .unwrap_or_else(|| fitjob::FitOptions::default().curves),
            method_options: options,
            interior: t.interior,
            ..fitjob::FitOptions::default()
        })?;
        let segments = t.segments.unwrap_or(grid::DEFAULT_SEGMENTS);
        let tess = surface::tessellate_fit(mesh, &f, segments).map_err(|source| {
            ExperimentError::Tessellate {
                subject: t.id.clone(),
                source,
            }
        })?;
        let errors = subject
            .truth
            .as_deref()
            .map(|truth| compare_with_truth(&tess, truth));
        v["g1_defect_radians"] = json!(g1.max_angle());
        v["interpolation_position_error"] = json!(g1.position_error);
        v["interpolation_normal_error_radians"] = json!(g1.normal_error);
        v["errors"] = serde_json::to_value(errors).unwrap_or(Value::Null);
        v["curve_measures"] = match curves {
            None => Value::Null,
            Some(_) => match surface::curve_stats::edge_problems(mesh) {
                Ok(problems) => {
                    let cs = surface::curve_stats::curve_stats(&problems, &f);
                    json!({
                        "end_curvature_error_max": cs.end_curvature_error_max,
                        "shortest_alpha": cs.shortest_alpha,
                        "curvature_variation_max": cs.curvature_variation_max,
                        "fallbacks_to_chord": cs.fallbacks,
                        "unconverged_optimizations": cs.unconverged,
                    })
                }
                // A data set's edges are never degenerate: that is a defect, reported.
                Err(source) if !t.file => {
                    return Err(ExperimentError::EdgeProblems {
                        subject: t.id.clone(),
                        source,
                    })
                }
                // A user's mesh may have a degenerate edge (the fit gave it a straight cubic);
                // the measures of the other edges would not be comparable: a stated null.
                Err(e) => {
                    v["curve_measures_note"] =
                        json!(format!("not measured: a degenerate edge ({e})"));
                    Value::Null
                }
            },
        };
        // The seeds' finding on boundary curves (curvature gathered at their ends), measured
        // on the curves and on the surface along them, against the truth's own ratio.
        v["ends"] =
            serde_json::to_value(surface::ends::measure(mesh, &f, subject.truth.as_deref()))
                .unwrap_or(Value::Null);
        v["fit_time_seconds"] = json!(fit_time);
        tessellation = tess;
    }
    v["task_time_seconds"] = json!(start.elapsed().as_secs_f64());
    check_line(t.index + 1, &v, &t.identity()).map_err(|source| StudyError::BadResult {
        task: t.id.clone(),
        source,
    })?;
    let surface = TaskSurface {
        tessellation,
        truth: subject.truth.clone(),
    };
    Ok((v, surface))
}

//! The `sweep` experiment's grid and task function (`experiments::sweep_tasks`) for a
//! scheduler in Python: `sweep_manifest(grid)` lists the tasks, `sweep_task(grid, id)` runs
//! one and returns the line `experiments sweep --task ID` writes, `sweep_merge(manifest,
//! results)` checks and orders the lines as `merge` does. A grid is a dict with the keys and
//! values of a grid file (`data`, `resolution`, `scheme`, `curves`, `solver`, `segments`, the
//! scheme parameters, `interior`, `estimate`). `triwb.sweep` maps the task function over Dask.

use pyo3::prelude::*;
use serde_json::Value;

use crate::errors::{failed, usage};

/// A Python object (a dict of lists, numbers and strings) as JSON, through Python's `json`.
fn to_json(py: Python<'_>, obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Value> {
    let text: String = py
        .import("json")?
        .call_method1("dumps", (obj,))
        .map_err(|e| usage(format!("{what} is not JSON: {e}")))?
        .extract()?;
    serde_json::from_str(&text).map_err(|e| usage(format!("{what}: {e}")))
}

/// JSON as Python objects.
fn to_python(py: Python<'_>, v: &Value) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| failed(format!("JSON: {e}")))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// The sweep's error as the exception its exit status stands for.
fn sweep_error(e: experiments::sweep_tasks::SweepError) -> PyErr {
    if e.is_usage() {
        usage(e.to_string())
    } else {
        failed(e.to_string())
    }
}

/// The task manifest of `grid`: what `experiments sweep --list-tasks` prints for the same
/// grid (its options as run, `tasks_total`, and every task with its `index`, `id` and
/// parameters).
#[pyfunction]
pub fn sweep_manifest(py: Python<'_>, grid: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    let axes = to_json(py, grid, "the grid")?;
    let m = py
        .detach(|| experiments::sweep_tasks::grid_manifest(&axes))
        .map_err(sweep_error)?;
    to_python(py, &m)
}

/// Runs the task `id` of `grid` and returns its result: the line `experiments sweep --task ID`
/// writes for the same grid (only `fit_time_seconds` and `task_time_seconds` differ between
/// runs). Mesh files in `data` are read relative to the working directory. Runs without the
/// GIL, so threads (and Dask's threaded workers) run tasks side by side.
#[pyfunction]
pub fn sweep_task(py: Python<'_>, grid: &Bound<'_, PyAny>, id: &str) -> PyResult<Py<PyAny>> {
    let axes = to_json(py, grid, "the grid")?;
    let r = py
        .detach(|| experiments::sweep_tasks::run_task(&axes, id))
        .map_err(sweep_error)?;
    to_python(py, &r)
}

/// Checks result lines against `manifest` as `experiments merge` checks its shard files
/// (every task exactly once, each identity key for key, every measure of its type and range)
/// and returns them in task order.
#[pyfunction]
pub fn sweep_merge(
    py: Python<'_>,
    manifest: &Bound<'_, PyAny>,
    results: &Bound<'_, PyAny>,
) -> PyResult<Py<PyAny>> {
    let manifest = to_json(py, manifest, "the manifest")?;
    let results = match to_json(py, results, "the results")? {
        Value::Array(a) => a,
        _ => return Err(usage("the results must be a list of result dicts")),
    };
    let merged = py
        .detach(|| experiments::sweep_tasks::merge_results(&manifest, results))
        .map_err(sweep_error)?;
    to_python(py, &Value::Array(merged))
}

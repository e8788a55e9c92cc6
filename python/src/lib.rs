//! The workbench from Python: the `triwb` package's native module (`triwb._triwb`), built by
//! maturin as one abi3 wheel (`pip install ./python`).
//!
//! Every function is a thin layer over the library: `fit` runs [`fitjob::run`], the job every
//! front end runs, so limits, repairs, estimation, fallbacks and measures are the command
//! line's, bit for bit; the arrays are checked and read in place ([`arrays`]), the work runs
//! with the GIL released (`Python::detach`), and errors are the command line's messages as
//! Python exceptions ([`errors`]).
//!
//! * [`meshes`] — `read_mesh`, `write_mesh`, the data sets;
//! * [`estimation`] — `estimate`;
//! * [`fit`] — `fit` and `Fit`;
//! * [`curve`] — `curve`, `curves`;
//! * [`registry`] — `schemes`, `curve_methods`, `solvers`, `estimators`;
//! * [`sweep`] — the sweep's manifest, task function and merge, for Dask or Ray.

// The job's error (`fitjob::JobError`) crosses each `detach` closure once and becomes a Python
// exception at once: boxing it there would only add an allocation.
#![allow(clippy::result_large_err)]

use pyo3::prelude::*;

/// mimalloc, for its per-thread heaps: the nets of a fit (a hundred megabytes at 10⁵ faces) are
/// written out 1.7× faster than with the system allocator (docs/python.md, "Speed").
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

pub mod arrays;
pub mod curve;
pub mod errors;
pub mod estimation;
pub mod fit;
pub mod input;
pub mod meshes;
pub mod registry;
pub mod sweep;
pub mod threads;

/// The native module.
#[pymodule]
fn _triwb(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("WorkbenchError", py.get_type::<errors::WorkbenchError>())?;
    m.add("UsageError", py.get_type::<errors::UsageError>())?;
    m.add_class::<meshes::MeshData>()?;
    m.add_class::<fit::Fit>()?;
    m.add_function(wrap_pyfunction!(meshes::read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::write_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::ring, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::sphere, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::capsule, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::octa, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::datasets, m)?)?;
    m.add_function(wrap_pyfunction!(estimation::estimate, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit, m)?)?;
    m.add_function(wrap_pyfunction!(curve::curve, m)?)?;
    m.add_function(wrap_pyfunction!(curve::curves, m)?)?;
    m.add_function(wrap_pyfunction!(registry::schemes, m)?)?;
    m.add_function(wrap_pyfunction!(registry::curve_methods, m)?)?;
    m.add_function(wrap_pyfunction!(registry::solvers, m)?)?;
    m.add_function(wrap_pyfunction!(registry::estimators, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_manifest, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_task, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_merge, m)?)?;
    Ok(())
}

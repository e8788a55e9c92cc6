//! The registries as Python lists of dicts: `schemes()`, `curve_methods()`, `solvers()`,
//! `estimators()`, each member with its parameters and defaults, read from the library's own
//! registries (a new member appears here without a change to this file).

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// Every surface scheme: `name`, `summary`, `kind` (`"patches"` or `"subdivision"`),
/// `continuity`, `uses_curves`, `layout` (degree, patches and points per patch), `parameters`
/// (each with `name`, `key` — the keyword `fit` takes —, `symbol`, `default`, `range`,
/// `range_reason`, `summary`) and `default` (whether `fit` uses it when none is named).
#[pyfunction]
pub fn schemes(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for e in surface::scheme::REGISTRY {
        let s = (e.build)(&surface::SchemeOptions::default());
        let d = PyDict::new(py);
        d.set_item("name", e.name)?;
        d.set_item("summary", e.summary)?;
        d.set_item("kind", "patches")?;
        d.set_item("continuity", s.continuity().to_string())?;
        d.set_item("uses_curves", s.uses_curves())?;
        let l = s.layout();
        let layout = PyDict::new(py);
        layout.set_item("degree", l.degree)?;
        layout.set_item("patches_per_face", l.patches_per_face())?;
        layout.set_item("points_per_patch", l.points_per_patch())?;
        d.set_item("layout", layout)?;
        let params = PyList::empty(py);
        for p in e.parameters {
            let q = PyDict::new(py);
            q.set_item("name", p.name)?;
            q.set_item("key", p.key())?;
            q.set_item("symbol", p.symbol)?;
            q.set_item("default", p.default)?;
            q.set_item("range", p.range)?;
            q.set_item("range_reason", p.range_reason)?;
            q.set_item("summary", p.summary)?;
            params.append(q)?;
        }
        d.set_item("parameters", params)?;
        d.set_item("default", e.name == surface::DEFAULT_SCHEME)?;
        out.append(d)?;
    }
    for e in subdiv::SCHEMES {
        let d = PyDict::new(py);
        d.set_item("name", e.name)?;
        d.set_item("summary", e.summary)?;
        d.set_item("kind", "subdivision")?;
        d.set_item("continuity", py.None())?;
        d.set_item("uses_curves", false)?;
        d.set_item("layout", py.None())?;
        d.set_item("parameters", PyList::empty(py))?;
        d.set_item("default", false)?;
        out.append(d)?;
    }
    Ok(out)
}

/// Every boundary-curve construction: `name`, `summary`, `needs_curvature` (whether it reads
/// the end curvatures), `enumerates_solutions` (dBHS: every solution is listed), and the
/// options every construction is built with, at their defaults (`solver`, `dbhs_pick`,
/// `alpha_min`).
#[pyfunction]
pub fn curve_methods(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let defaults = ::curves::MethodOptions::default();
    let out = PyList::empty(py);
    for e in ::curves::REGISTRY {
        let m = (e.build)(&defaults);
        let d = PyDict::new(py);
        d.set_item("name", e.name)?;
        d.set_item("summary", e.summary)?;
        d.set_item("needs_curvature", m.needs_curvature())?;
        d.set_item("enumerates_solutions", m.enumerates_solutions())?;
        let o = PyDict::new(py);
        o.set_item("solver", defaults.solver.name())?;
        o.set_item("dbhs_pick", defaults.dbhs_pick.to_string())?;
        o.set_item("alpha_min", defaults.alpha_min)?;
        d.set_item("options", o)?;
        d.set_item("default", e.name == fitjob::FitOptions::default().curves)?;
        out.append(d)?;
    }
    Ok(out)
}

/// Every solver of the `optimized` construction: `name` and `default`.
#[pyfunction]
pub fn solvers(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let default = ::curves::MethodOptions::default().solver;
    let out = PyList::empty(py);
    for k in solver::SolverKind::ALL {
        let d = PyDict::new(py);
        d.set_item("name", k.name())?;
        d.set_item("default", k == default)?;
        out.append(d)?;
    }
    Ok(out)
}

/// Every estimator of normals and shape tensors: `name`, `description`, `default`.
#[pyfunction]
pub fn estimators(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let out = PyList::empty(py);
    for e in ::estimate::ESTIMATORS {
        let d = PyDict::new(py);
        d.set_item("name", e.name())?;
        d.set_item("description", e.description())?;
        d.set_item("default", e.name() == ::estimate::DEFAULT_ESTIMATOR)?;
        out.append(d)?;
    }
    Ok(out)
}

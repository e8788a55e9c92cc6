//! `curve(…)` and `curves(…)`: the planar boundary-curve problem on the unit chord from (0, 0)
//! to (1, 0) with end tangents `t0`, `t1` and end curvatures `k0`, `k1`, answered by a
//! registered construction exactly as the command line's `curve` answers a line
//! (`curves::jsonl`).

use std::str::FromStr;

use ::curves::jsonl::{answer_json, LineAnswer};
use ::curves::{CurveMethod, MethodOptions, UnitProblem};
use nalgebra::Vector2;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::{json, Value};

use crate::arrays;
use crate::errors::{failed, usage};

/// The curve constructions' options of the keyword arguments, as the command line's
/// `--solver`, `--dbhs-pick`, `--tweak-t` (checked to lie in `(0, 1]`) and `--four-ninths`.
pub fn method_options(
    solver: &str,
    dbhs_pick: Option<&str>,
    tweak_t: f64,
    four_ninths: bool,
) -> PyResult<MethodOptions> {
    let mut options = MethodOptions {
        solver: solver::SolverKind::from_str(solver).map_err(|e| usage(e.to_string()))?,
        tweak_t: ::curves::tweak::check_t(tweak_t).map_err(|e| usage(format!("tweak_t: {e}")))?,
        reach: if four_ninths {
            ::curves::Reach::FourNinths
        } else {
            ::curves::Reach::Third
        },
        ..MethodOptions::default()
    };
    if let Some(p) = dbhs_pick {
        options.dbhs_pick = ::curves::DbhsPick::from_str(p).map_err(usage)?;
    }
    Ok(options)
}

/// The construction `method` with `options`; `history`: the solver reports keep the cost at
/// every iteration (as the command line's `curve` asks, for its plots).
fn method(name: &str, mut options: MethodOptions, history: bool) -> PyResult<Box<dyn CurveMethod>> {
    options.solve_options.record_history = history;
    ::curves::method_by_name(name, &options).map_err(|e| usage(e.to_string()))
}

/// The command line's record of one construction's answer to `problem`.
fn answer(problem: UnitProblem, m: &dyn CurveMethod, input: Value) -> Value {
    let choice = m.construct(&problem);
    let a = LineAnswer {
        line: 1,
        input,
        choices: vec![(m.name(), m.enumerates_solutions(), choice)],
        problem,
    };
    let mut v = answer_json(&a);
    v["methods"][m.name()].take()
}

/// JSON text as Python objects.
fn to_python(py: Python<'_>, v: &Value) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| failed(format!("JSON: {e}")))?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

/// The boundary curve of one planar problem by `method` (`curve_methods()`; the solver for
/// `optimized`, the pick among dBHS solutions): a dict with `alpha` (the end-derivative
/// lengths), `points` (the four Bézier points), `kappa` (the end curvatures achieved),
/// `curvature_variation` (`∫ (dκ/ds)² ds`), and what the construction adds (dBHS's
/// `solutions`, `optimized`'s solver `report` with its cost history), the record the command
/// line's `curve` writes.
#[pyfunction]
#[pyo3(signature = (t0, t1, k0, k1, method="optimized", *, solver="exact-penalty", dbhs_pick=None,
    tweak_t=::curves::tweak::DEFAULT_TWEAK_T, four_ninths=false))]
#[allow(clippy::too_many_arguments)]
pub fn curve(
    py: Python<'_>,
    t0: [f64; 2],
    t1: [f64; 2],
    k0: f64,
    k1: f64,
    method: &str,
    solver: &str,
    dbhs_pick: Option<&str>,
    tweak_t: f64,
    four_ninths: bool,
) -> PyResult<Py<PyAny>> {
    let m = self::method(
        method,
        method_options(solver, dbhs_pick, tweak_t, four_ninths)?,
        true,
    )?;
    let problem = UnitProblem::new(Vector2::from(t0), Vector2::from(t1), k0, k1)
        .map_err(|e| usage(e.to_string()))?;
    let input = json!({"t0": t0, "t1": t1, "k0": k0, "k1": k1});
    let v = py.detach(|| answer(problem, m.as_ref(), input));
    to_python(py, &v)
}

/// Many planar problems at once: `problems` is an (n, 6) array of rows
/// `[t0x, t0y, t1x, t1y, k0, k1]`. Returns a dict of arrays, row for row: `alpha` (n × 2),
/// `points` (n × 4 × 2), `kappa` (n × 2), `curvature_variation` (n; NaN where unbounded, at a
/// cusp), `fallback` (n, bool: the construction fell back to the chord choice), `converged`
/// (n, bool; True for constructions without a solver), `iterations` (n), and `reports` (the
/// solver reports without their cost histories, a list of dicts, or None for constructions
/// without one). The work runs
/// without the GIL.
#[pyfunction]
#[pyo3(signature = (problems, method="optimized", *, solver="exact-penalty", dbhs_pick=None,
    tweak_t=::curves::tweak::DEFAULT_TWEAK_T, four_ninths=false))]
pub fn curves<'py>(
    py: Python<'py>,
    problems: &Bound<'py, PyAny>,
    method: &str,
    solver: &str,
    dbhs_pick: Option<&str>,
    tweak_t: f64,
    four_ninths: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let m = self::method(
        method,
        method_options(solver, dbhs_pick, tweak_t, four_ninths)?,
        false,
    )?;
    let mut list = Vec::new();
    let mut bad = None;
    let rows = {
        let mut rows = Vec::new();
        arrays_rows(problems, &mut rows)?;
        rows
    };
    for (i, r) in rows.iter().enumerate() {
        match UnitProblem::new(
            Vector2::new(r[0], r[1]),
            Vector2::new(r[2], r[3]),
            r[4],
            r[5],
        ) {
            Ok(p) => list.push(p),
            Err(e) => {
                bad = Some(format!("problems row {i}: {e}"));
                break;
            }
        }
    }
    if let Some(b) = bad {
        return Err(usage(b));
    }
    let n = list.len();
    let answers: Vec<(::curves::CurveChoice, UnitProblem)> =
        py.detach(|| list.into_iter().map(|p| (m.construct(&p), p)).collect());
    let mut alpha = Vec::with_capacity(2 * n);
    let mut points = Vec::with_capacity(8 * n);
    let mut kappa = Vec::with_capacity(2 * n);
    let mut variation = Vec::with_capacity(n);
    let mut fallback = Vec::with_capacity(n);
    let mut converged = Vec::with_capacity(n);
    let mut iterations = Vec::with_capacity(n);
    let mut reports = Vec::new();
    let has_reports = answers.iter().any(|(c, _)| c.report.is_some());
    for (c, p) in &answers {
        alpha.extend_from_slice(&c.alpha);
        let bez = p.curve(c.alpha);
        for q in &bez.points {
            points.extend_from_slice(&[q.x, q.y]);
        }
        kappa.extend_from_slice(&p.end_curvatures(c.alpha));
        let v = bez.curvature_variation();
        variation.push(if v.is_finite() { v } else { f64::NAN });
        fallback.push(c.fallback);
        converged.push(c.report.as_ref().is_none_or(|r| r.converged()));
        iterations.push(c.report.as_ref().map_or(0, |r| r.iterations as i64));
        if has_reports {
            reports.push(serde_json::to_value(&c.report).unwrap_or(Value::Null));
        }
    }
    let out = PyDict::new(py);
    out.set_item("alpha", arrays::shaped(py, alpha, &[n, 2])?)?;
    out.set_item("points", arrays::shaped(py, points, &[n, 4, 2])?)?;
    out.set_item("kappa", arrays::shaped(py, kappa, &[n, 2])?)?;
    out.set_item("curvature_variation", arrays::floats_out(py, variation)?)?;
    out.set_item("fallback", arrays::shaped(py, fallback, &[n])?)?;
    out.set_item("converged", arrays::shaped(py, converged, &[n])?)?;
    out.set_item("iterations", arrays::shaped(py, iterations, &[n])?)?;
    if has_reports {
        out.set_item("reports", to_python(py, &Value::Array(reports))?)?;
    } else {
        out.set_item("reports", py.None())?;
    }
    Ok(out)
}

/// The rows of an (n, 6) float array.
fn arrays_rows(obj: &Bound<'_, PyAny>, rows: &mut Vec<[f64; 6]>) -> PyResult<()> {
    arrays::float_rows::<6>(obj, "problems", rows)
}

//! numpy arrays in and out.
//!
//! **In.** An argument may be any array-like (`numpy.asarray` is applied to what is not an
//! array already). Its shape is checked against what it stands for (`V`: n × 3, `F`: m × 3, a
//! shape tensor per vertex: n × 3 × 3), its dtype against the kinds allowed (floating point:
//! float64, or float32 widened exactly; indices: any signed or unsigned integer of 32 or 64
//! bits), and every value: a float must be finite, an index inside `0..n`. A refusal names the
//! argument, the row and what was wrong, as a [`crate::errors::UsageError`] (a `TypeError` for
//! a dtype). The array's memory is read where it is, with no copy: a C-contiguous float64
//! array as one slice, any other layout (a transposed view, a slice with a step, float32)
//! through its strides; the values go straight into the library's own types, the one
//! conversion the job needs.
//!
//! **Out.** Results are built as one `Vec` each and handed to numpy without a copy
//! (`PyArray::from_vec` keeps the vector's buffer), then reshaped as a view.

use nalgebra::{Matrix3, Point3, Vector3};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

use crate::errors::usage;

/// `obj` as a numpy array (`numpy.asarray(obj)` unless it is one).
fn as_array<'py>(obj: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyUntypedArray>> {
    if let Ok(a) = obj.cast::<PyUntypedArray>() {
        return Ok(a.clone());
    }
    let np = obj.py().import("numpy")?;
    let a = np.call_method1("asarray", (obj,))?;
    Ok(a.cast_into::<PyUntypedArray>()?)
}

/// The dtype's name (`float64`, `int32`, `object`).
fn dtype_name(a: &Bound<'_, PyUntypedArray>) -> String {
    a.dtype()
        .str()
        .map(|s| s.to_string())
        .unwrap_or_else(|_| "unknown".into())
}

/// Refuses a shape other than `(any, tail…)`.
fn check_shape(a: &Bound<'_, PyUntypedArray>, name: &str, tail: &[usize]) -> PyResult<usize> {
    let shape = a.shape();
    let want = {
        let mut s = String::from("(n");
        for t in tail {
            s.push_str(&format!(", {t}"));
        }
        s + ")"
    };
    if shape.len() != tail.len() + 1 || shape[1..] != *tail {
        return Err(usage(format!(
            "{name} must have shape {want}, got {shape:?}"
        )));
    }
    Ok(shape[0])
}

/// Calls `row(i, values)` for every row of a floating-point array of shape `(n, tail…)`, the
/// row's `tail` product values in C order, each checked finite. Returns `n`.
fn for_each_float_row(
    obj: &Bound<'_, PyAny>,
    name: &str,
    tail: &[usize],
    mut row: impl FnMut(usize, &[f64]),
) -> PyResult<usize> {
    let a = as_array(obj)?;
    let n = check_shape(&a, name, tail)?;
    let width: usize = tail.iter().product();
    let bad = |i: usize, values: &[f64]| {
        usage(format!(
            "{name} row {i} is not finite: {values:?} (NaN and infinity are refused)"
        ))
    };
    let mut buf = vec![0.0; width];
    if let Ok(a) = a.cast::<PyArrayDyn<f64>>() {
        let ro = a.try_readonly()?;
        // Only a C-contiguous buffer is in row order (`as_slice` also takes a Fortran one).
        let c_order = a.is_c_contiguous();
        if let (true, Ok(slice)) = (c_order, ro.as_slice()) {
            for (i, r) in slice.chunks_exact(width.max(1)).enumerate() {
                if !r.iter().all(|x| x.is_finite()) {
                    return Err(bad(i, r));
                }
                row(i, r);
            }
            return Ok(n);
        }
        let view = ro.as_array();
        for (i, r) in view.outer_iter().enumerate() {
            for (b, x) in buf.iter_mut().zip(r.iter()) {
                *b = *x;
            }
            if !buf.iter().all(|x| x.is_finite()) {
                return Err(bad(i, &buf));
            }
            row(i, &buf);
        }
        return Ok(n);
    }
    if let Ok(a) = a.cast::<PyArrayDyn<f32>>() {
        let ro = a.try_readonly()?;
        let view = ro.as_array();
        for (i, r) in view.outer_iter().enumerate() {
            for (b, x) in buf.iter_mut().zip(r.iter()) {
                *b = f64::from(*x);
            }
            if !buf.iter().all(|x| x.is_finite()) {
                return Err(bad(i, &buf));
            }
            row(i, &buf);
        }
        return Ok(n);
    }
    Err(PyTypeError::new_err(format!(
        "{name} must be a float64 or float32 array, got dtype {}",
        dtype_name(&a)
    )))
}

/// Points of an `(n, 3)` array.
pub fn points(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<Point3<f64>>> {
    let mut out = Vec::new();
    let n = for_each_float_row(obj, name, &[3], |_, r| {
        out.push(Point3::new(r[0], r[1], r[2]))
    })?;
    debug_assert_eq!(out.len(), n);
    Ok(out)
}

/// Vectors of an `(n, 3)` array with exactly `rows` rows (one per vertex).
pub fn vectors(obj: &Bound<'_, PyAny>, name: &str, rows: usize) -> PyResult<Vec<Vector3<f64>>> {
    let mut out = Vec::with_capacity(rows);
    let n = for_each_float_row(obj, name, &[3], |_, r| {
        out.push(Vector3::new(r[0], r[1], r[2]))
    })?;
    if n != rows {
        return Err(usage(format!("{name} has {n} rows, V has {rows}")));
    }
    Ok(out)
}

/// 3 × 3 tensors of an `(n, 3, 3)` array with exactly `rows` of them.
pub fn tensors(obj: &Bound<'_, PyAny>, name: &str, rows: usize) -> PyResult<Vec<Matrix3<f64>>> {
    let mut out = Vec::with_capacity(rows);
    let n = for_each_float_row(obj, name, &[3, 3], |_, r| {
        out.push(Matrix3::from_row_slice(r))
    })?;
    if n != rows {
        return Err(usage(format!(
            "{name} has {n} tensors, V has {rows} vertices"
        )));
    }
    Ok(out)
}

/// Rows of `width` indices of an integer array of shape `(m, width)`, each in `0..bound`.
pub fn index_rows<const W: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    bound: usize,
) -> PyResult<Vec<[usize; W]>> {
    let a = as_array(obj)?;
    check_shape(&a, name, &[W])?;
    macro_rules! read {
        ($t:ty) => {
            if let Ok(a) = a.cast::<PyArrayDyn<$t>>() {
                let ro = a.try_readonly()?;
                let bad = |i: usize, x: $t| {
                    usage(format!(
                        "{name} row {i} has index {x}, outside 0..{bound} (V has {bound} rows)"
                    ))
                };
                // A C-contiguous buffer (numpy's default) is read as one slice.
                if let (true, Ok(slice)) = (a.is_c_contiguous(), ro.as_slice()) {
                    let mut out = Vec::with_capacity(slice.len() / W.max(1));
                    for (i, r) in slice.chunks_exact(W.max(1)).enumerate() {
                        let mut row = [0usize; W];
                        for (k, x) in r.iter().enumerate() {
                            row[k] = usize::try_from(*x)
                                .ok()
                                .filter(|v| *v < bound)
                                .ok_or_else(|| bad(i, *x))?;
                        }
                        out.push(row);
                    }
                    return Ok(out);
                }
                let view = ro.as_array();
                let mut out = Vec::with_capacity(view.shape()[0]);
                for (i, r) in view.outer_iter().enumerate() {
                    let mut row = [0usize; W];
                    for (k, x) in r.iter().enumerate() {
                        let v = usize::try_from(*x).ok().filter(|v| *v < bound);
                        row[k] = v.ok_or_else(|| bad(i, *x))?;
                    }
                    out.push(row);
                }
                return Ok(out);
            }
        };
    }
    read!(i64);
    read!(i32);
    read!(u32);
    read!(u64);
    Err(PyTypeError::new_err(format!(
        "{name} must be an integer array (int32, int64, uint32 or uint64), got dtype {}",
        dtype_name(&a)
    )))
}

/// A flat vector as an array of `shape` (its product must be the length), without a copy.
pub fn shaped<'py, T: numpy::Element>(
    py: Python<'py>,
    values: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let flat = PyArray1::from_vec(py, values);
    Ok(flat.reshape(shape.to_vec())?.into_any())
}

/// Points as an `(n, 3)` float64 array.
pub fn points_out<'py>(
    py: Python<'py>,
    points: impl ExactSizeIterator<Item = [f64; 3]>,
) -> PyResult<Bound<'py, PyAny>> {
    let n = points.len();
    let mut flat = Vec::with_capacity(3 * n);
    for p in points {
        flat.extend_from_slice(&p);
    }
    shaped(py, flat, &[n, 3])
}

/// Index rows as an `(m, W)` int64 array (numpy's default integer, what libigl and trimesh
/// give).
pub fn indices_out<'py, const W: usize>(
    py: Python<'py>,
    rows: &[[usize; W]],
) -> PyResult<Bound<'py, PyAny>> {
    let flat: Vec<i64> = rows
        .iter()
        .flat_map(|r| r.iter().map(|&i| i as i64))
        .collect();
    shaped(py, flat, &[rows.len(), W])
}

/// Tensors as an `(n, 3, 3)` float64 array (row-major: `S[i, r, c]`).
pub fn tensors_out<'py>(py: Python<'py>, tensors: &[Matrix3<f64>]) -> PyResult<Bound<'py, PyAny>> {
    let mut flat = Vec::with_capacity(9 * tensors.len());
    for m in tensors {
        for r in 0..3 {
            for c in 0..3 {
                flat.push(m[(r, c)]);
            }
        }
    }
    shaped(py, flat, &[tensors.len(), 3, 3])
}

/// A vector of floats as a 1-D array.
pub fn floats_out<'py>(py: Python<'py>, values: Vec<f64>) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, values).into_any())
}

/// The `rows` finite values of a 1-D float array (one per vertex).
pub fn floats(obj: &Bound<'_, PyAny>, name: &str, rows: usize) -> PyResult<Vec<f64>> {
    let mut out = Vec::with_capacity(rows);
    let n = for_each_float_row(obj, name, &[], |_, r| out.push(r[0]))?;
    if n != rows {
        return Err(usage(format!("{name} has {n} values, V has {rows} rows")));
    }
    Ok(out)
}

/// The rows of an `(n, W)` float array, appended to `out`.
pub fn float_rows<const W: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    out: &mut Vec<[f64; W]>,
) -> PyResult<()> {
    for_each_float_row(obj, name, &[W], |_, r| {
        let mut row = [0.0; W];
        row.copy_from_slice(r);
        out.push(row);
    })?;
    Ok(())
}

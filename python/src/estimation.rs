//! `estimate(V, F, …)`: per-vertex normals, shape tensors and principal curvatures and
//! directions of a bare mesh, by the estimators the fit completes files with.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays;
use crate::errors::job_error;
use crate::input::{crease_rule, raw_from_arrays};

/// Estimates normals and curvature of the mesh `V`, `F` with `method` (`estimators()` lists
/// them; `"hybrid"` by default), keeping given `normals` when there are any.
///
/// The mesh goes through what a file given to the command line goes through (repair, working
/// frame, creases, estimation), and the results are given back per input vertex in the input's
/// coordinates. A dict of arrays:
/// `normals` (n × 3 unit), `shape` (n × 3 × 3 shape tensors, the workbench's convention:
/// `κn(d) = dᵀ S d` positive towards the normal), and in libigl's convention (`κ1 ≥ κ2`,
/// positive where the surface bends away from the normal: the unit sphere with outward normals
/// has `K = H = 1`) `k1`, `k2`, `d1`, `d2` (unit principal directions, `d2 = n × d1`), `K`,
/// `H`; `missing` counts input vertices the repair dropped (unreferenced or degenerate), whose
/// rows are NaN; `crease_vertices` counts vertices on creases, where the fit uses one estimate
/// per sector and these rows hold the estimate over all the vertex's faces; `notes` lists what
/// the repair and the estimator did. `radius`: estimate on Euclidean balls of this many mean
/// edge lengths (the degree-2 jet at one radius, for noisy scans) instead of `method`'s own
/// neighbourhoods. `threads`: as `fit`'s.
#[pyfunction]
#[pyo3(signature = (V, F, method="hybrid", normals=None, *, crease_angle=None, no_creases=false, radius=None, threads=None))]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn estimate<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    method: &str,
    normals: Option<&Bound<'py, PyAny>>,
    crease_angle: Option<f64>,
    no_creases: bool,
    radius: Option<f64>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let raw = raw_from_arrays(V, F, normals, None, None)?;
    let n = raw.positions.len();
    let options = fitjob::InputOptions {
        source: fitjob::Source::Raw {
            label: "arrays".into(),
            raw: Box::new(raw),
        },
        estimate: method.to_string(),
        radius,
        replace_normals: false,
        creases: crease_rule(crease_angle, no_creases)?,
    };
    let loaded = crate::threads::run(py, threads, move || fitjob::input::load_owned(options))?
        .map_err(job_error)?;
    let mut mesh = loaded.mesh;
    loaded.frame.mesh_to_world(&mut mesh);
    // Input vertex → its first mesh vertex (the repair may split a vertex or drop one).
    let mut of_input: Vec<Option<usize>> = vec![None; n];
    for (i, src) in loaded
        .vertex_source
        .clone()
        .unwrap_or_else(|| (0..mesh.num_vertices()).collect())
        .into_iter()
        .enumerate()
    {
        if let Some(slot) = of_input.get_mut(src) {
            slot.get_or_insert(i);
        }
    }
    let nan3 = [f64::NAN; 3];
    let vs = mesh.vertices();
    let known = |v: usize| vs[v].curvature_known;
    let mut normals_out = Vec::with_capacity(n);
    let mut shapes = Vec::with_capacity(n);
    let (mut k1, mut k2, mut kg, mut hm) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    let (mut d1, mut d2) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for m in &of_input {
        match m {
            Some(v) => {
                let d = &vs[*v].data;
                normals_out.push([d.n.x, d.n.y, d.n.z]);
                shapes.push(d.shape);
                if known(*v) {
                    let p = ::estimate::principal_frame(&d.shape, &d.n);
                    k1.push(p.k1);
                    k2.push(p.k2);
                    kg.push(p.k1 * p.k2);
                    hm.push(0.5 * (p.k1 + p.k2));
                    d1.push([p.d1.x, p.d1.y, p.d1.z]);
                    d2.push([p.d2.x, p.d2.y, p.d2.z]);
                } else {
                    for c in [&mut k1, &mut k2, &mut kg, &mut hm] {
                        c.push(f64::NAN);
                    }
                    d1.push(nan3);
                    d2.push(nan3);
                }
            }
            None => {
                normals_out.push(nan3);
                shapes.push(nalgebra::Matrix3::from_element(f64::NAN));
                for c in [&mut k1, &mut k2, &mut kg, &mut hm] {
                    c.push(f64::NAN);
                }
                d1.push(nan3);
                d2.push(nan3);
            }
        }
    }
    let missing = of_input.iter().filter(|m| m.is_none()).count();
    let crease_vertices = match mesh.sectors() {
        Some(s) => s
            .slots_per_vertex(mesh.num_vertices())
            .iter()
            .filter(|&&k| k > 1)
            .count(),
        None => 0,
    };
    let out = PyDict::new(py);
    out.set_item("normals", arrays::points_out(py, normals_out.into_iter())?)?;
    out.set_item("shape", arrays::tensors_out(py, &shapes)?)?;
    out.set_item("k1", arrays::floats_out(py, k1)?)?;
    out.set_item("k2", arrays::floats_out(py, k2)?)?;
    out.set_item("d1", arrays::points_out(py, d1.into_iter())?)?;
    out.set_item("d2", arrays::points_out(py, d2.into_iter())?)?;
    out.set_item("K", arrays::floats_out(py, kg)?)?;
    out.set_item("H", arrays::floats_out(py, hm)?)?;
    out.set_item("missing", missing)?;
    out.set_item("crease_vertices", crease_vertices)?;
    out.set_item("notes", loaded.notes)?;
    Ok(out)
}

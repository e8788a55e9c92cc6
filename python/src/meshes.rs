//! Meshes as arrays: [`MeshData`], `read_mesh`, `write_mesh`, and the data sets (`ring`,
//! `sphere`, `capsule`, `octa`) with their exact normals and shape tensors.

use std::path::PathBuf;

use nalgebra::Point3;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays;
use crate::errors::{job_error, usage};

/// A mesh as arrays, what `read_mesh` and the data sets give.
///
/// `V` (n × 3 float64) and `F` (m × 3 int64) unpack like libigl's pair (`V, F = read_mesh(p)`);
/// `normals` (n × 3) and `shape` (n × 3 × 3 shape tensors in the workbench's convention:
/// `κn(d) = dᵀ S d`, positive where the surface bends towards the normal, the `.m` files'
/// `shape`) are `None` where the source has none; `colors` (n × 3, linear RGB 0–1);
/// `creases` (k × 2 vertex pairs, `a < b`) the edges the file marks sharp; `notes` what the
/// reader did (a polygon split into a fan, say).
#[pyclass(module = "triwb", frozen, get_all)]
pub struct MeshData {
    /// Vertex positions, n × 3.
    #[pyo3(name = "V")]
    pub v: Py<PyAny>,
    /// Triangles, m × 3 indices into `V`.
    #[pyo3(name = "F")]
    pub f: Py<PyAny>,
    /// Per-vertex normals (n × 3) or None.
    pub normals: Option<Py<PyAny>>,
    /// Per-vertex shape tensors (n × 3 × 3) or None.
    pub shape: Option<Py<PyAny>>,
    /// Per-vertex colours (n × 3) or None.
    pub colors: Option<Py<PyAny>>,
    /// Edges marked sharp in the file, k × 2.
    pub creases: Py<PyAny>,
    /// The source: a path or a data set's name.
    pub name: String,
    /// What the reader did, one line each.
    pub notes: Vec<String>,
}

#[pymethods]
impl MeshData {
    /// `V, F = mesh`.
    fn __iter__(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let pair = (self.v.clone_ref(py), self.f.clone_ref(py)).into_pyobject(py)?;
        Ok(pair.try_iter()?.into_any().unbind())
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let len = |o: &Py<PyAny>| o.bind(py).len().unwrap_or(0);
        Ok(format!(
            "MeshData({:?}: {} vertices, {} triangles{}{})",
            self.name,
            len(&self.v),
            len(&self.f),
            if self.normals.is_some() {
                ", normals"
            } else {
                ""
            },
            if self.shape.is_some() {
                ", shape tensors"
            } else {
                ""
            },
        ))
    }
}

/// `raw` as arrays; polygons of more than three corners are split into a fan around their
/// first corner (the rule the fit's repair applies, so a fit of the arrays sees what a fit of
/// the file sees), and counted in the notes.
fn mesh_data(py: Python<'_>, raw: meshio::RawMesh, name: String) -> PyResult<MeshData> {
    let mut tris: Vec<[usize; 3]> = Vec::with_capacity(raw.polygons.len());
    let mut fanned = 0usize;
    for poly in raw.polygons.iter() {
        if poly.len() > 3 {
            fanned += 1;
        }
        for k in 1..poly.len().saturating_sub(1) {
            tris.push([poly[0], poly[k], poly[k + 1]]);
        }
    }
    let mut notes = raw.notes.clone();
    if fanned > 0 {
        notes.push(format!(
            "{fanned} polygons of more than three corners split into fans around their first corner"
        ));
    }
    let v = arrays::points_out(py, raw.positions.iter().map(|p| [p.x, p.y, p.z]))?;
    let f = arrays::indices_out(py, &tris)?;
    let normals = match &raw.normals {
        Some(n) => Some(arrays::points_out(py, n.iter().map(|v| [v.x, v.y, v.z]))?.unbind()),
        None => None,
    };
    let shape = match &raw.shapes {
        Some(s) => Some(arrays::tensors_out(py, s)?.unbind()),
        None => None,
    };
    let colors = match &raw.colors {
        Some(c) => Some(
            arrays::points_out(
                py,
                c.iter()
                    .map(|c| [f64::from(c[0]), f64::from(c[1]), f64::from(c[2])]),
            )?
            .unbind(),
        ),
        None => None,
    };
    Ok(MeshData {
        v: v.unbind(),
        f: f.unbind(),
        normals,
        shape,
        colors,
        creases: arrays::indices_out(py, &raw.crease_edges)?.unbind(),
        name,
        notes,
    })
}

/// Reads a mesh file (`.obj`, `.ply`, `.stl`, `.off`, `.glb`, `.m`; the format by extension,
/// checked against the content) into arrays, as the command line reads it. Errors name the
/// file and line as the command line's do.
#[pyfunction]
pub fn read_mesh(py: Python<'_>, path: PathBuf) -> PyResult<MeshData> {
    let read = {
        let path = path.clone();
        py.detach(move || meshio::read_file(&path))
    };
    let raw = read.map_err(|e| job_error(fitjob::JobError::MeshIo(e)))?;
    mesh_data(py, raw, path.display().to_string())
}

/// Writes `V`, `F` (and the optional per-vertex fields) to `path` in the format its extension
/// names, as the command line's writers do (atomically: a temporary file renamed).
///
/// Fields: `normals` (n × 3), `colors` (n × 3 linear RGB in 0–1), `K` and `H` (n each: the
/// Gaussian and mean curvature in libigl's convention, H > 0 on a sphere with outward normals;
/// written by PLY and glTF, both or neither), `shape` (n × 3 × 3, written by `.m`). Options:
/// `ascii` (PLY, STL text), `double` (PLY positions as 64-bit floats), `up` (`"z"` or `"y"`:
/// the data's up axis, for glTF).
#[pyfunction]
#[pyo3(signature = (path, V, F, *, normals=None, colors=None, K=None, H=None, shape=None, ascii=false, double=false, up="z"))]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn write_mesh(
    py: Python<'_>,
    path: PathBuf,
    V: &Bound<'_, PyAny>,
    F: &Bound<'_, PyAny>,
    normals: Option<&Bound<'_, PyAny>>,
    colors: Option<&Bound<'_, PyAny>>,
    K: Option<&Bound<'_, PyAny>>,
    H: Option<&Bound<'_, PyAny>>,
    shape: Option<&Bound<'_, PyAny>>,
    ascii: bool,
    double: bool,
    up: &str,
) -> PyResult<PathBuf> {
    let positions = arrays::points(V, "V")?;
    let n = positions.len();
    let tris = arrays::index_rows::<3>(F, "F", n)?;
    let mut raw = meshio::RawMesh::from_triangles(positions, &tris);
    if let Some(a) = normals {
        raw.normals = Some(arrays::vectors(a, "normals", n)?);
    }
    if let Some(a) = colors {
        let c = arrays::vectors(a, "colors", n)?;
        if let Some(bad) = c
            .iter()
            .position(|c| c.iter().any(|x| !(0.0..=1.0).contains(x)))
        {
            return Err(usage(format!(
                "colors row {bad} is outside 0..1 (linear RGB): {:?}",
                c[bad].as_slice()
            )));
        }
        raw.colors = Some(
            c.iter()
                .map(|c| [c.x as f32, c.y as f32, c.z as f32])
                .collect(),
        );
    }
    match (K, H) {
        (Some(k), Some(h)) => {
            let gaussian = arrays::floats(k, "K", n)?;
            let mean = arrays::floats(h, "H", n)?;
            raw.curvature = Some(meshio::Curvature::from_exported(gaussian, mean));
        }
        (None, None) => {}
        _ => {
            return Err(usage(
                "give K and H together (a file stores both or neither)",
            ))
        }
    }
    if let Some(s) = shape {
        raw.shapes = Some(arrays::tensors(s, "shape", n)?);
    }
    let up: meshio::UpAxis = up.parse().map_err(usage)?;
    let format = fitjob::output::mesh_format_for("path", &path).map_err(job_error)?;
    let mut options = meshio::WriteOptions::new().up(up);
    if ascii {
        options = options.ascii();
    }
    if double {
        options = options.double_precision();
    }
    let written = {
        let path = path.clone();
        // Streamed into the file as it is encoded (no copy of the file's bytes in memory).
        py.detach(move || fitjob::output::write_mesh_result(&path, format, &raw, &options))
    };
    written.map_err(job_error)?;
    Ok(path)
}

/// A data set as arrays: positions, triangles, the exact unit normals and shape tensors.
fn dataset(py: Python<'_>, name: &str, resolution: Option<usize>) -> PyResult<MeshData> {
    let options = fitjob::InputOptions {
        source: fitjob::Source::DataSet {
            name: name.into(),
            resolution,
        },
        ..fitjob::InputOptions::default()
    };
    let loaded = py
        .detach(|| fitjob::input::load(&options))
        .map_err(job_error)?;
    let mesh = &loaded.mesh;
    let vs = mesh.vertices();
    let positions: Vec<Point3<f64>> = vs.iter().map(|v| v.data.p).collect();
    let mut raw = meshio::RawMesh::from_triangles(positions, mesh.faces());
    raw.normals = Some(vs.iter().map(|v| v.data.n).collect());
    raw.shapes = Some(vs.iter().map(|v| v.data.shape).collect());
    mesh_data(py, raw, name.to_string())
}

/// The ring data set (a torus patch of Mann's report) at `resolution` (its default when None).
#[pyfunction]
#[pyo3(signature = (resolution=None))]
pub fn ring(py: Python<'_>, resolution: Option<usize>) -> PyResult<MeshData> {
    dataset(py, "ring", resolution)
}

/// The sphere data set at `resolution` (its default when None).
#[pyfunction]
#[pyo3(signature = (resolution=None))]
pub fn sphere(py: Python<'_>, resolution: Option<usize>) -> PyResult<MeshData> {
    dataset(py, "sphere", resolution)
}

/// The capsule data set at `resolution` (its default when None).
#[pyfunction]
#[pyo3(signature = (resolution=None))]
pub fn capsule(py: Python<'_>, resolution: Option<usize>) -> PyResult<MeshData> {
    dataset(py, "capsule", resolution)
}

/// The octahedron of Mann's Figure 2 (no resolution).
#[pyfunction]
pub fn octa(py: Python<'_>) -> PyResult<MeshData> {
    dataset(py, "octa", None)
}

/// The names of the data sets.
#[pyfunction]
pub fn datasets() -> Vec<&'static str> {
    mesh::DATASET_NAMES.to_vec()
}

/// A dict from pairs.
pub fn dict_of<'py>(
    py: Python<'py>,
    items: &[(&str, Bound<'py, PyAny>)],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in items {
        d.set_item(k, v)?;
    }
    Ok(d)
}

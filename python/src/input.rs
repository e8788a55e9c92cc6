//! The fit's input from arguments: a raw mesh from arrays, and the crease rule from the
//! command line's two options.

use pyo3::prelude::*;

use crate::arrays;
use crate::errors::usage;

/// A raw mesh of `V`, `F` and the optional per-vertex `normals`, `shape` tensors and marked
/// `creases` (k × 2 vertex pairs), checked (shapes, dtypes, finite values, indices in range).
pub fn raw_from_arrays(
    v: &Bound<'_, PyAny>,
    f: &Bound<'_, PyAny>,
    normals: Option<&Bound<'_, PyAny>>,
    shape: Option<&Bound<'_, PyAny>>,
    creases: Option<&Bound<'_, PyAny>>,
) -> PyResult<meshio::RawMesh> {
    let positions = arrays::points(v, "V")?;
    let n = positions.len();
    let tris = arrays::index_rows::<3>(f, "F", n)?;
    let mut raw = meshio::RawMesh::from_triangles(positions, &tris);
    if let Some(a) = normals {
        raw.normals = Some(arrays::vectors(a, "normals", n)?);
    }
    if let Some(a) = shape {
        raw.shapes = Some(arrays::tensors(a, "shape", n)?);
    }
    if let Some(a) = creases {
        let mut pairs: Vec<[usize; 2]> = arrays::index_rows::<2>(a, "creases", n)?
            .into_iter()
            .map(|[a, b]| [a.min(b), a.max(b)])
            .collect();
        if let Some(k) = pairs.iter().position(|[a, b]| a == b) {
            return Err(usage(format!(
                "creases row {k} joins vertex {} to itself",
                pairs[k][0]
            )));
        }
        pairs.sort_unstable();
        pairs.dedup();
        raw.crease_edges = pairs;
    }
    Ok(raw)
}

/// `--crease-angle DEG` / `--no-creases` as the rule, refused together and out of range as the
/// command line refuses them.
pub fn crease_rule(
    crease_angle: Option<f64>,
    no_creases: bool,
) -> PyResult<mesh::features::CreaseRule> {
    use mesh::features::CreaseRule;
    match (crease_angle, no_creases) {
        (Some(_), true) => Err(usage(
            "crease_angle and no_creases exclude each other (the command line's --crease-angle and --no-creases)",
        )),
        (None, true) => Ok(CreaseRule::None),
        (None, false) => Ok(CreaseRule::Auto),
        (Some(d), false) if d > 0.0 && d <= 180.0 => Ok(CreaseRule::Angle(d)),
        (Some(d), false) => Err(usage(format!(
            "crease_angle must be in (0, 180] degrees, got {d}"
        ))),
    }
}

//! Edge problems of the data sets (the `surface` crate's registry), by name.

use curves::BoundaryProblem;
use surface::{dataset_by_name, DataSet};

use crate::error::ExperimentError;

/// Loads a data set at its default resolution; an unknown name is a usage error listing the
/// known ones.
pub fn load(name: &str) -> Result<DataSet, ExperimentError> {
    dataset_by_name(name, None).map_err(ExperimentError::from)
}

/// The edge problems of a data set, each with its `(a, b)` vertex pair.
pub type EdgeProblems = Vec<((usize, usize), BoundaryProblem)>;

/// Every edge of a data set as a boundary-curve problem (each edge once, oriented as in its
/// first face), and the number of edges whose problem is degenerate (skipped).
pub fn edge_problems(name: &str) -> Result<(EdgeProblems, usize), ExperimentError> {
    let data = load(name)?;
    let verts = data.mesh.vertices();
    let mut out = Vec::with_capacity(data.mesh.edges().len());
    let mut skipped = 0;
    for e in data.mesh.edges() {
        let [a, b] = e.vertices;
        match BoundaryProblem::new((a, b), &verts[a].data, &verts[b].data) {
            Ok(p) => out.push(((a, b), p)),
            Err(_) => skipped += 1,
        }
    }
    Ok((out, skipped))
}

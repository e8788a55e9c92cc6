//! The data sets of the `surface` crate's registry in the order the studies list them, their
//! edge problems by name, and a study's mesh by `--data` item (a data set or a mesh file).

use std::sync::LazyLock;

use curves::BoundaryProblem;
use surface::{dataset_by_name, DataSet, DATASET_NAMES};

use crate::error::ExperimentError;

/// The data set the studies list first: the seeds' ring.
const LEADING: &str = "ring";

/// Every data set of the registry ([`surface::DATASET_NAMES`]), in the order the studies list
/// them (`sweep`'s tasks, the `solvers` default, `interior`'s comparison): the seeds' ring first,
/// then the others in registry order.
pub fn all() -> Vec<&'static str> {
    let mut names = DATASET_NAMES.to_vec();
    // Stable: the ring first, the rest keep their registry order.
    names.sort_by_key(|n| *n != LEADING);
    names
}

/// [`all`], comma-separated: the default of a `--data` list.
pub fn all_joined() -> &'static str {
    static ALL: LazyLock<String> = LazyLock::new(|| all().join(","));
    &ALL
}

/// Loads a data set at its default resolution; an unknown name is a usage error listing the
/// known ones.
pub fn load(name: &str) -> Result<DataSet, ExperimentError> {
    dataset_by_name(name, None).map_err(ExperimentError::from)
}

/// One mesh of the study: its name in the report, the mesh in its working frame, and the true
/// surface when it is a data set.
pub struct Subject {
    /// The `--data` item as given.
    pub name: String,
    /// The mesh (a file's in its working frame).
    pub mesh: surface::Mesh,
    /// The working frame of a file (identity for a data set).
    pub frame: surface::Frame,
    /// The true surface of a data set.
    pub truth: Option<std::sync::Arc<dyn surface::AnalyticSurface>>,
}

/// Loads `--data` item `data`: an existing file is read, repaired and completed by `estimate`
/// (the fit job's input, `fitjob::input::load`); any other name is a data set (at
/// `resolution`), with its true surface.
pub fn load_subject(
    data: &str,
    resolution: Option<usize>,
    estimate: &str,
) -> Result<Subject, ExperimentError> {
    if std::path::Path::new(data).is_file() {
        let loaded = fitjob::input::load(&fitjob::InputOptions {
            source: fitjob::Source::Data {
                data: data.to_string(),
                resolution,
            },
            estimate: estimate.to_string(),
            radius: None,
            replace_normals: false,
            creases: mesh::features::CreaseRule::Auto,
        })?;
        return Ok(Subject {
            name: data.to_string(),
            mesh: loaded.mesh,
            frame: loaded.frame,
            truth: None,
        });
    }
    // A data set's size is known from its resolution: refused before it is built when its fit
    // could not be held.
    if let Some(r) = resolution {
        crate::limits::check_memory(
            &format!("--data {data} --resolution {r}"),
            crate::limits::dataset_faces(data, r)
                .saturating_mul(crate::limits::FIT_BYTES_PER_FACE as u128),
        )?;
    }
    let set = surface::dataset_by_name(data, resolution).map_err(|source| {
        ExperimentError::DataOption {
            given: match resolution {
                Some(r) => format!("--data {data} --resolution {r}"),
                None => format!("--data {data}"),
            },
            source: Box::new(source),
        }
    })?;
    Ok(Subject {
        name: data.to_string(),
        mesh: set.mesh,
        frame: surface::Frame::identity(),
        truth: Some(set.surface),
    })
}

/// The edge problems of a data set, each with its `(a, b)` vertex pair.
pub type EdgeProblems = Vec<((usize, usize), BoundaryProblem)>;

/// Every edge of a data set as a boundary-curve problem (each edge once, oriented as in its
/// first face), and the number of edges whose problem is degenerate (skipped).
pub fn edge_problems(name: &str) -> Result<(EdgeProblems, usize), ExperimentError> {
    let data = load(name)?;
    let verts = data.mesh.vertices();
    let mut out = Vec::with_capacity(data.mesh.num_edges());
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_registered_data_set_is_listed_once_ring_first() {
        let names = all();
        assert_eq!(names.len(), DATASET_NAMES.len());
        assert!(DATASET_NAMES.iter().all(|n| names.contains(n)));
        assert_eq!(names.first(), Some(&LEADING));
        // The order the committed results were written in.
        assert_eq!(all_joined(), "ring,sphere,capsule,octa");
    }
}

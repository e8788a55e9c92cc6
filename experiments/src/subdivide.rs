//! `fit --scheme loop|loop-warren|catmull-clark`: subdivision of the data mesh (the `subdiv`
//! crate) instead of a Bézier scheme. The mesh is read with its polygons kept as they are (a
//! data set is its triangles); `--levels N` steps are applied and the control mesh after them
//! is written to `--mesh-out` (not pushed to the limit, so it compares with other
//! implementations). Subdivision approximates: the report gives the distance from each data
//! point to its limit position (limit stencils at the original vertices), against the model
//! size.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use crate::error::ExperimentError;
use crate::output::write_result;

/// Runs `entry` on `data` (a data-set name or a mesh file) for `levels` steps.
pub fn run(
    data: &str,
    resolution: Option<usize>,
    scheme: &str,
    levels: u32,
    mesh_out: Option<&Path>,
) -> Result<ExitCode, ExperimentError> {
    let t0 = Instant::now();
    let subject = |e: subdiv::SubdivError| ExperimentError::Subdivision {
        subject: data.to_string(),
        source: e,
    };
    let s = subdiv::scheme_by_name(scheme).map_err(subject)?;
    let mesh = if surface::DATASET_NAMES.contains(&data) {
        let d = surface::dataset_by_name(data, resolution).map_err(|source| {
            ExperimentError::DataOption {
                given: data.to_string(),
                source,
            }
        })?;
        let positions = d.mesh.vertices().iter().map(|v| v.data.p).collect();
        subdiv::PolyMesh::from_triangles(positions, d.mesh.faces()).map_err(subject)?
    } else {
        let raw = meshio::read_file(Path::new(data)).map_err(ExperimentError::MeshIo)?;
        subdiv::PolyMesh::from_raw(&raw).map_err(subject)?
    };
    let refined =
        subdiv::subdivide(s.as_ref(), &mesh, levels, subdiv::DEFAULT_MAX_FACES).map_err(subject)?;
    let t_sub = t0.elapsed().as_secs_f64();
    // Distance from the data points to the limit surface at the same vertices.
    let limit = s.limit_positions(&mesh).map_err(subject)?;
    let size = surface::mesh::bounding_size(mesh.positions().iter()).max(f64::MIN_POSITIVE);
    let d: Vec<f64> = mesh
        .positions()
        .iter()
        .zip(&limit)
        .map(|(p, q)| (p - q).norm())
        .collect();
    let max = d.iter().copied().fold(0.0f64, f64::max);
    let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len().max(1) as f64).sqrt();
    if let Some(path) = mesh_out {
        crate::output::refuse_overwriting_input("--mesh-out", path, data)?;
        let format = crate::output::mesh_format_for("--mesh-out", path)?;
        let bytes = meshio::write_bytes(&refined.to_raw(), format, &meshio::WriteOptions::new())
            .map_err(|source| ExperimentError::MeshWrite {
                path: path.to_path_buf(),
                source,
            })?;
        write_result(Some(path), &bytes)?;
    }
    say!(
        "fit: {data} ({} vertices, {} faces), subdivision {} × {levels}: {} vertices, {} faces in {:.3} s",
        mesh.num_vertices(),
        mesh.num_faces(),
        s.name(),
        refined.num_vertices(),
        refined.num_faces(),
        t_sub
    );
    say!(
        "  approximation: data point to limit surface max {:.3e}, RMS {:.3e} ({:.3e} and {:.3e} of the model size)",
        max,
        rms,
        max / size,
        rms / size
    );
    Ok(ExitCode::SUCCESS)
}

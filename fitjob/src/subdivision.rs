//! A subdivision scheme (`loop`, `loop-warren`, `catmull-clark`: the `subdiv` crate) instead of
//! a Bézier scheme. The mesh is read with its polygons kept as they are (a data set is its
//! triangles); [`FitOptions::levels`] steps are applied and the control mesh after them is
//! written to [`FitOptions::mesh_out`] (not pushed to the limit, so it compares with other
//! implementations). Subdivision approximates: the report gives the distance from each data
//! point to its limit position (limit stencils at the original vertices), against the model
//! size.

use std::path::Path;
use std::time::Instant;

use crate::error::JobError;
use crate::input::Source;
use crate::options::FitOptions;
use crate::output::{mesh_format_for, refuse_overwriting_input};
use crate::report::{FitReport, SubdivisionSummary, Timings};

/// The crease tags of a file's polygons: the creases `rule` finds on the file's mesh, the ones
/// the file marks included (repaired
/// and triangulated as the Bézier schemes see it, `mesh::features::Features::find`), mapped back
/// to the file's vertices and kept where they are edges of its polygons (a fan diagonal of a
/// polygon is never one). A mesh the repair cannot make anything of gets no tags (the
/// subdivision then reports what is wrong with it).
fn raw_creases(raw: &meshio::RawMesh, rule: mesh::features::CreaseRule) -> Vec<[usize; 2]> {
    let Ok(repaired) = mesh::repair::repair(raw, &mesh::repair::RepairOptions::default()) else {
        return Vec::new();
    };
    let features = mesh::features::Features::find(&repaired.mesh, rule, &repaired.crease_edges);
    let mut polygon_edges = std::collections::BTreeSet::new();
    for poly in raw.polygons.iter() {
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            polygon_edges.insert([a.min(b), a.max(b)]);
        }
    }
    let source = &repaired.vertex_source;
    let mut out: Vec<[usize; 2]> = repaired
        .mesh
        .edges()
        .zip(&features.crease)
        .filter(|(_, &c)| c)
        .filter_map(|(e, _)| {
            let [a, b] = e.vertices.map(|v| source.get(v).copied());
            let (a, b) = (a?, b?);
            let key = [a.min(b), a.max(b)];
            polygon_edges.contains(&key).then_some(key)
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Runs the subdivision scheme of `options`.
pub fn run(options: &FitOptions) -> Result<FitReport, JobError> {
    let t0 = Instant::now();
    let label = options.input.source.label().to_string();
    let subject = |e: subdiv::SubdivError| JobError::Subdivision {
        subject: label.clone(),
        source: e,
    };
    let s = subdiv::scheme_by_name(&options.scheme).map_err(subject)?;
    // A data set's triangles, or a file's (or raw mesh's) polygons as they are.
    let dataset = match &options.input.source {
        Source::DataSet { name, resolution } => Some((name, *resolution)),
        Source::Data { data, resolution } if mesh::DATASET_NAMES.contains(&data.as_str()) => {
            Some((data, *resolution))
        }
        _ => None,
    };
    let mesh = match (dataset, &options.input.source) {
        (Some((name, resolution)), _) => {
            let d =
                mesh::dataset_by_name(name, resolution).map_err(|source| JobError::DataOption {
                    given: name.to_string(),
                    source,
                })?;
            let positions = d.mesh.vertices().iter().map(|v| v.data.p).collect();
            subdiv::PolyMesh::from_triangles(positions, d.mesh.faces()).map_err(subject)?
        }
        (None, Source::Raw { raw, .. }) => {
            let creases = raw_creases(raw, options.input.creases);
            subdiv::PolyMesh::with_creases(raw.positions.clone(), &raw.polygons, &creases)
                .map_err(subject)?
        }
        (None, Source::Prepared { mesh, .. }) => {
            let positions = mesh.vertices().iter().map(|v| v.data.p).collect();
            subdiv::PolyMesh::from_triangles(positions, mesh.faces()).map_err(subject)?
        }
        (None, _) => {
            let raw = meshio::read_file(Path::new(&label)).map_err(JobError::MeshIo)?;
            let creases = raw_creases(&raw, options.input.creases);
            subdiv::PolyMesh::with_creases(raw.positions, &raw.polygons, &creases)
                .map_err(subject)?
        }
    };
    let refined = subdiv::subdivide(s.as_ref(), &mesh, options.levels, subdiv::DEFAULT_MAX_FACES)
        .map_err(subject)?;
    let t_sub = t0.elapsed().as_secs_f64();
    // Distance from the data points to the limit surface at the same vertices.
    let limit = s.limit_positions(&mesh).map_err(subject)?;
    let size = mesh::mesh::bounding_size(mesh.positions().iter()).max(f64::MIN_POSITIVE);
    let d: Vec<f64> = mesh
        .positions()
        .iter()
        .zip(&limit)
        .map(|(p, q)| (p - q).norm())
        .collect();
    let max = d.iter().copied().fold(0.0f64, f64::max);
    let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len().max(1) as f64).sqrt();
    if let Some(path) = &options.mesh_out {
        let input = options
            .input
            .source
            .file()
            .map(|p| p.to_string_lossy().into_owned())
            .unwrap_or_default();
        refuse_overwriting_input("--mesh-output", path, &input)?;
        let format = mesh_format_for("--mesh-output", path)?;
        let write_options = options.mesh_options.write_options();
        crate::output::write_mesh_result(path, format, &refined.to_raw(), &write_options)?;
    }
    Ok(FitReport {
        input: label,
        vertices: mesh.num_vertices(),
        faces: mesh.num_faces(),
        scheme: s.name().to_string(),
        subdivision: Some(SubdivisionSummary {
            levels: options.levels,
            vertices: refined.num_vertices(),
            faces: refined.num_faces(),
            approximation_max: max,
            approximation_rms: rms,
            model_size: size,
        }),
        time: Timings {
            fit: t_sub,
            ..Timings::default()
        },
        ..FitReport::default()
    })
}

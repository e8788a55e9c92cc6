//! The `--data` option shared by the experiments that take a mesh: a named analytic data set, or
//! a mesh file of any supported format, repaired and completed by an estimator
//! ([`estimate::prepare`]).

use std::path::Path;

use estimate::EstimateChoice;
use surface::repair::RepairReport;
use surface::Mesh;

use crate::error::ExperimentError;

/// Options naming the input mesh and how to complete it.
#[derive(clap::Args, Debug, Clone)]
pub struct InputArgs {
    /// A data set (ring, sphere, capsule, octa) or a mesh file (.m, .obj, .ply, .stl, .off; the
    /// format by extension, checked against the content).
    #[arg(long, default_value = "ring")]
    pub data: String,
    /// Resolution of a named data set (its default when absent).
    #[arg(long)]
    pub resolution: Option<usize>,
    /// How to estimate what a mesh file lacks (normals, shape tensors): an estimator's name
    /// (hybrid, jet, jet2, jet3, jet4, quadric, rusinkiewicz) or `none` (use the file's data only;
    /// curvature-based curves then need a file with shape tensors).
    #[arg(long, default_value = estimate::DEFAULT_ESTIMATOR)]
    pub estimate: String,
    /// Estimate normals even where the file gives them (by default the file's normals are kept
    /// and only the curvature is estimated, in their tangent planes).
    #[arg(long)]
    pub replace_normals: bool,
}

/// A loaded input mesh.
pub struct Loaded {
    /// The mesh, every vertex with a normal and (unless `--estimate none`) a shape tensor.
    pub mesh: Mesh,
    /// The working frame of the mesh (identity for a data set): `world = center + scale · mesh`.
    pub frame: surface::Frame,
    /// What was done to a file (repairs, estimation, notes), one line each.
    pub notes: Vec<String>,
    /// What the repair did to a file (`None` for a data set).
    pub repairs: Option<RepairReport>,
    /// For each mesh face, the file's face it came from (`None` for a data set).
    pub face_source: Option<Vec<usize>>,
    /// For each mesh vertex, the file's vertex it came from (`None` for a data set).
    pub vertex_source: Option<Vec<usize>>,
    /// The process's peak resident memory once the file was read, before the repair (`None`
    /// for a data set, or where the system does not say), bytes.
    pub peak_after_read: Option<u64>,
}

/// Loads `--data`: an existing file is read as a mesh; otherwise the name is a data set.
pub fn load(args: &InputArgs) -> Result<Loaded, ExperimentError> {
    let path = Path::new(&args.data);
    // A name of a data set is one unless a file of that name exists; anything else with an
    // extension is a file (whose absence `meshio` reports by name).
    if path.is_file()
        || !surface::DATASET_NAMES.contains(&args.data.as_str()) && path.extension().is_some()
    {
        let t = std::time::Instant::now();
        let mut raw = meshio::read_file(path).map_err(ExperimentError::MeshIo)?;
        let t_read = t.elapsed().as_secs_f64();
        let choice =
            EstimateChoice::parse(&args.estimate).map_err(|source| ExperimentError::Estimate {
                value: args.estimate.clone(),
                source,
            })?;
        let peak_read = crate::limits::peak_resident_bytes();
        let mut notes: Vec<String> = std::mem::take(&mut raw.notes);
        // The raw mesh is handed over and freed once repaired: a large file is not held twice.
        let prepared =
            estimate::prepare_owned(raw, choice, args.replace_normals).map_err(|source| {
                ExperimentError::Prepare {
                    path: path.to_path_buf(),
                    source,
                }
            })?;
        notes.extend(prepared.summary_lines());
        notes.push(format!(
            "time: read {:.3} s, repair {:.3} s, estimation {:.3} s",
            t_read, prepared.repair_time_seconds, prepared.estimate_time_seconds
        ));

        return Ok(Loaded {
            mesh: prepared.mesh,
            frame: prepared.frame,
            notes,
            repairs: Some(prepared.report),
            face_source: Some(prepared.face_source),
            vertex_source: Some(prepared.vertex_source),
            peak_after_read: peak_read,
        });
    }
    let data = surface::dataset_by_name(&args.data, args.resolution).map_err(|source| {
        ExperimentError::DataOption {
            given: match args.resolution {
                Some(r) => format!("--data {} --resolution {r}", args.data),
                None => format!("--data {}", args.data),
            },
            source,
        }
    })?;
    Ok(Loaded {
        mesh: data.mesh,
        frame: surface::Frame::identity(),
        notes: Vec::new(),
        repairs: None,
        face_source: None,
        vertex_source: None,
        peak_after_read: None,
    })
}

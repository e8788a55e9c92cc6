//! The job's input: a named analytic data set, a mesh file of any supported format, or a raw
//! mesh already in memory, repaired and completed by an estimator ([`estimate::prepare`]).

use std::path::{Path, PathBuf};

use estimate::EstimateChoice;
use mesh::repair::RepairReport;
use mesh::{Frame, Mesh};
use serde::Serialize;

use crate::error::JobError;

/// Where the mesh comes from.
#[derive(Clone, Debug)]
pub enum Source {
    /// A data set (`ring`, `sphere`, `capsule`, `octa`) or a mesh file (`.m`, `.obj`, `.ply`,
    /// `.stl`, `.off`; the format by extension, checked against the content): an existing file
    /// of that name is read; otherwise the name is a data set.
    Data {
        /// The name or path.
        data: String,
        /// Resolution of a named data set (its default when absent).
        resolution: Option<usize>,
    },
    /// A named data set, never a file (`ring`, `sphere`, `capsule`, `octa`).
    DataSet {
        /// The data set's name.
        name: String,
        /// Its resolution (its default when absent).
        resolution: Option<usize>,
    },
    /// A mesh already repaired and complete (every vertex with its normal and, for curve
    /// methods that need it, its shape tensor), in its working frame: fitted as it is, with no
    /// repair and no estimation (a study fitting one loaded mesh several ways; the job gives
    /// the mesh back in [`crate::Kept::mesh`] when asked to keep it).
    Prepared {
        /// What to call it in messages and reports.
        label: String,
        /// The mesh.
        mesh: Box<Mesh>,
        /// The way back to the input's coordinates.
        frame: Frame,
    },
    /// A raw mesh already in memory (positions, polygons, optional normals and shape tensors),
    /// treated as a file's content: repaired and completed.
    Raw {
        /// What to call it in messages and reports.
        label: String,
        /// The mesh.
        raw: Box<meshio::RawMesh>,
    },
}

impl Source {
    /// The name messages and reports give the input.
    pub fn label(&self) -> &str {
        match self {
            Source::Data { data, .. } => data,
            Source::DataSet { name, .. } => name,
            Source::Prepared { label, .. } => label,
            Source::Raw { label, .. } => label,
        }
    }

    /// The file this input reads, if it reads one (for the outputs' "is the input" check).
    pub fn file(&self) -> Option<&Path> {
        match self {
            Source::Data { data, .. } if is_file_input(data) => Some(Path::new(data)),
            _ => None,
        }
    }
}

/// The input and how to complete it.
#[derive(Clone, Debug)]
pub struct InputOptions {
    /// Where the mesh comes from.
    pub source: Source,
    /// How to estimate what a mesh file lacks (normals, shape tensors): an estimator's name or
    /// `none` (use the file's data only).
    pub estimate: String,
    /// `--radius`: estimate on Euclidean balls of this many mean edge lengths (the degree-2
    /// jet at one radius, [`estimate::EstimateChoice::Ball`]) instead of `estimate`'s rule.
    pub radius: Option<f64>,
    /// Estimate normals even where the file gives them.
    pub replace_normals: bool,
    /// How creases are found in a mesh file (`--crease-angle`, `--no-creases`); data sets are
    /// smooth and taken as they are.
    pub creases: mesh::features::CreaseRule,
}

impl Default for InputOptions {
    /// The ring data set, the default estimator, the file's normals kept.
    fn default() -> Self {
        InputOptions {
            source: Source::Data {
                data: "ring".into(),
                resolution: None,
            },
            estimate: estimate::DEFAULT_ESTIMATOR.into(),
            radius: None,
            replace_normals: false,
            creases: mesh::features::CreaseRule::Auto,
        }
    }
}

/// A loaded input mesh.
pub struct Loaded {
    /// The mesh, every vertex with a normal and (unless the estimator is `none`) a shape tensor.
    pub mesh: Mesh,
    /// The working frame of the mesh (identity for a data set): `world = center + scale · mesh`.
    pub frame: Frame,
    /// What was done to a file (repairs, estimation, notes), one line each.
    pub notes: Vec<String>,
    /// What the repair did to a file (`None` for a data set).
    pub repairs: Option<RepairReport>,
    /// For each mesh face, the file's face it came from (`None` for a data set).
    pub face_source: Option<Vec<usize>>,
    /// For each mesh vertex, the file's vertex it came from (`None` for a data set).
    pub vertex_source: Option<Vec<usize>>,
    /// What the crease detection found (`None` for a data set).
    pub creases: Option<estimate::CreaseSummary>,
    /// The process's peak resident memory once the file was read, before the repair (`None`
    /// for a data set, or where the system does not say), bytes.
    pub peak_after_read: Option<u64>,
    /// Seconds spent reading, repairing and estimating (zero for a data set).
    pub time: InputTime,
}

/// Seconds spent on each step of loading a file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct InputTime {
    /// Reading and parsing the file.
    pub read_time: f64,
    /// The repair.
    pub repair_time: f64,
    /// The estimation of what the file lacks.
    pub estimate_time: f64,
}

/// Whether `data` names a file to read rather than a data set: an existing file is one, and so
/// is any name with an extension that is not a data set's (its absence is then reported by
/// name).
pub fn is_file_input(data: &str) -> bool {
    let path = Path::new(data);
    path.is_file() || !mesh::DATASET_NAMES.contains(&data) && path.extension().is_some()
}

/// Loads the input.
pub fn load(options: &InputOptions) -> Result<Loaded, JobError> {
    match &options.source {
        Source::Data { data, resolution } => {
            if is_file_input(data) {
                let path = Path::new(data);
                let t = std::time::Instant::now();
                let raw = meshio::read_file(path).map_err(JobError::MeshIo)?;
                let read_time = t.elapsed().as_secs_f64();
                prepare(raw, options.how(), path.to_path_buf(), read_time)
            } else {
                dataset(data, *resolution)
            }
        }
        Source::DataSet { name, resolution } => dataset(name, *resolution),
        Source::Prepared { mesh, frame, .. } => Ok(prepared((**mesh).clone(), *frame)),
        Source::Raw { label, raw } => {
            prepare((**raw).clone(), options.how(), PathBuf::from(label), 0.0)
        }
    }
}

/// A mesh taken as it is.
fn prepared(mesh: Mesh, frame: Frame) -> Loaded {
    Loaded {
        mesh,
        frame,
        notes: Vec::new(),
        repairs: None,
        face_source: None,
        vertex_source: None,
        creases: None,
        peak_after_read: None,
        time: InputTime::default(),
    }
}

/// [`load`], taking the input: a raw mesh in memory is repaired without a copy of it being made
/// first (a large mesh is not held twice).
pub fn load_owned(options: InputOptions) -> Result<Loaded, JobError> {
    match options.source {
        Source::Raw { label, raw } => prepare(
            *raw,
            How {
                estimate: &options.estimate,
                radius: options.radius,
                replace_normals: options.replace_normals,
                creases: options.creases,
            },
            PathBuf::from(label),
            0.0,
        ),
        Source::Prepared { mesh, frame, .. } => Ok(prepared(*mesh, frame)),
        source => load(&InputOptions { source, ..options }),
    }
}

/// How a raw mesh is completed: [`InputOptions`] but the source.
#[derive(Clone, Copy)]
struct How<'a> {
    estimate: &'a str,
    radius: Option<f64>,
    replace_normals: bool,
    creases: mesh::features::CreaseRule,
}

impl InputOptions {
    fn how(&self) -> How<'_> {
        How {
            estimate: &self.estimate,
            radius: self.radius,
            replace_normals: self.replace_normals,
            creases: self.creases,
        }
    }
}

/// A raw mesh repaired and completed.
fn prepare(
    mut raw: meshio::RawMesh,
    options: How<'_>,
    path: PathBuf,
    read_time: f64,
) -> Result<Loaded, JobError> {
    let estimator = options.estimate;
    let choice =
        EstimateChoice::parse_with_radius(estimator, options.radius).map_err(|source| {
            JobError::Estimate {
                value: estimator.to_string(),
                source,
            }
        })?;
    let peak_read = crate::limits::peak_resident_bytes();
    let mut notes: Vec<String> = std::mem::take(&mut raw.notes);
    triangulate_point_cloud(&mut raw, &mut notes);
    // The raw mesh is handed over and freed once repaired: a large file is not held twice.
    let prepared = estimate::prepare_with(raw, choice, options.replace_normals, options.creases)
        .map_err(|source| JobError::Prepare { path, source })?;
    notes.extend(prepared.summary_lines());
    notes.push(format!(
        "time: read {:.3} s, repair {:.3} s, estimation {:.3} s",
        read_time, prepared.repair_time_seconds, prepared.estimate_time_seconds
    ));
    Ok(Loaded {
        mesh: prepared.mesh,
        frame: prepared.frame,
        notes,
        repairs: Some(prepared.report),
        face_source: Some(prepared.face_source),
        vertex_source: Some(prepared.vertex_source),
        creases: Some(prepared.creases),
        peak_after_read: peak_read,
        time: InputTime {
            read_time,
            repair_time: prepared.repair_time_seconds,
            estimate_time: prepared.estimate_time_seconds,
        },
    })
}

/// A file with points and no faces is taken as a height field's samples: its faces are the
/// Delaunay triangulation of the points' `(x, y)` (`mesh::delaunay`), said in a note. Points
/// the triangulation cannot take (fewer than three, all on a line, too many) leave the file as
/// it is, with the reason in a note (the repair then finds nothing to fit and says so).
fn triangulate_point_cloud(raw: &mut meshio::RawMesh, notes: &mut Vec<String>) {
    if !raw.polygons.is_empty() || raw.positions.is_empty() {
        return;
    }
    let xy: Vec<nalgebra::Vector2<f64>> = raw
        .positions
        .iter()
        .map(|p| nalgebra::Vector2::new(p.x, p.y))
        .collect();
    match mesh::delaunay::delaunay(&xy) {
        Ok(tris) => {
            notes.push(format!(
                "no faces in the file: its {} points triangulated by the Delaunay triangulation of their (x, y) into {} triangles (a height field's samples)",
                xy.len(),
                tris.len()
            ));
            raw.polygons = meshio::Polygons::from_triangles(&tris);
        }
        Err(e) => notes.push(format!(
            "no faces in the file, and its points cannot be triangulated in (x, y): {e}"
        )),
    }
}

/// A named data set.
fn dataset(data: &str, resolution: Option<usize>) -> Result<Loaded, JobError> {
    let set = mesh::dataset_by_name(data, resolution).map_err(|source| JobError::DataOption {
        given: match resolution {
            Some(r) => format!("--data {data} --resolution {r}"),
            None => format!("--data {data}"),
        },
        source,
    })?;
    Ok(prepared(set.mesh, Frame::identity()))
}

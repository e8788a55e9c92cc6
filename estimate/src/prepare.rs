//! From a file's raw mesh to a mesh ready to fit: moved into a working frame (unit bounding box,
//! [`mesh::Frame`]: coordinates from 1e-100 to 1e100 work), repaired ([`mesh::repair`])
//! and completed by an estimator where the file lacks normals or shape tensors.
//!
//! # What is kept and what is estimated
//!
//! * Normals the file gives are kept (and the shape tensors estimated in their tangent planes)
//!   unless `replace_normals` asks for estimated ones.
//! * Shape tensors the file gives (the testbed format's `shape`) are kept; an estimator then
//!   only supplies missing normals (which a testbed file always has).
//! * [`EstimateChoice::None`] estimates nothing: a file without normals is then refused (no
//!   scheme can fit it), and one without shape tensors leaves the curvature unknown (the
//!   curvature-based curve constructions refuse it, `chord` runs).

use mesh::repair::{repair, RepairError, RepairOptions, RepairReport, Repaired};
use mesh::Mesh;
use meshio::RawMesh;

use crate::{apply, estimator_by_name, EstimateSummary, Estimator, UnknownEstimator};

/// How to complete a mesh file.
#[derive(Clone, Copy)]
pub enum EstimateChoice {
    /// Use the file's data only.
    None,
    /// Estimate what is missing with this estimator.
    With(&'static dyn Estimator),
}

impl std::fmt::Debug for EstimateChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EstimateChoice::None => write!(f, "None"),
            EstimateChoice::With(e) => write!(f, "With({})", e.name()),
        }
    }
}

impl EstimateChoice {
    /// `none` or a registered estimator's name.
    pub fn parse(name: &str) -> Result<Self, UnknownEstimator> {
        if name == "none" {
            return Ok(EstimateChoice::None);
        }
        estimator_by_name(name).map(EstimateChoice::With)
    }

    /// The name (`none` or the estimator's).
    pub fn name(&self) -> &'static str {
        match self {
            EstimateChoice::None => "none",
            EstimateChoice::With(e) => e.name(),
        }
    }
}

/// Why a file could not be prepared.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PrepareError {
    /// Nothing usable could be built from the faces.
    #[error(transparent)]
    Repair(#[from] RepairError),
    /// The coordinates cannot be brought into a working frame.
    #[error(transparent)]
    Frame(#[from] mesh::FrameError),
    /// The file has no (usable) normals and no estimation was asked for.
    #[error("the file gives no usable vertex normals and `--estimate none` was asked: name an estimator (jet, quadric, rusinkiewicz, …)")]
    NoNormals,
}

/// A prepared mesh and the record of what was done to it.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The mesh, in the working frame [`Prepared::frame`] (bounding box centred at the origin,
    /// largest side 1): map results back with the frame for output.
    pub mesh: Mesh,
    /// The working frame: `world = frame.center + frame.scale · working`.
    pub frame: mesh::Frame,
    /// What the repair did.
    pub report: RepairReport,
    /// True when every vertex's normal came from the file.
    pub normals_given: bool,
    /// For each mesh face, the file's face (polygon) it came from.
    pub face_source: Vec<usize>,
    /// For each mesh vertex, the file's vertex it came from.
    pub vertex_source: Vec<usize>,
    /// The estimator's record, when one ran.
    pub estimate: Option<EstimateSummary>,
    /// What was estimated: `"normals and curvature"`, `"curvature"`, `"normals"` or `"nothing"`.
    pub estimated: &'static str,
    /// Wall-clock time of the repair, seconds.
    pub repair_time_seconds: f64,
    /// Wall-clock time of the estimation, seconds.
    pub estimate_time_seconds: f64,
}

impl Prepared {
    /// One line per thing a user should know (repairs, estimation and its fallbacks).
    pub fn summary_lines(&self) -> Vec<String> {
        let mut out = self.report.summary_lines();
        if let Some(e) = &self.estimate {
            let counts: Vec<String> = e
                .fallback_counts
                .iter()
                .map(|(k, n)| format!("{n} {k}"))
                .collect();
            out.push(format!(
                "estimated {} by `{}`{}",
                self.estimated,
                e.estimator,
                if counts.is_empty() {
                    String::new()
                } else {
                    format!(" (fallbacks: {})", counts.join(", "))
                }
            ));
        }
        out
    }
}

/// Repairs `raw` and estimates what it lacks (module docs).
pub fn prepare(
    raw: &RawMesh,
    choice: EstimateChoice,
    replace_normals: bool,
) -> Result<Prepared, PrepareError> {
    prepare_owned(raw.clone(), choice, replace_normals)
}

/// [`prepare`], taking the raw mesh: it is moved into the working frame in place and freed as
/// soon as the repaired mesh is built, so a large file is not held twice (the `fit` and
/// `convert` commands read a file only to prepare it).
pub fn prepare_owned(
    raw: RawMesh,
    choice: EstimateChoice,
    replace_normals: bool,
) -> Result<Prepared, PrepareError> {
    let t0 = std::time::Instant::now();
    let frame = mesh::Frame::of_points(&raw.positions)?;
    // What `Frame::raw_to_work` does, in place.
    let mut work = raw;
    for p in &mut work.positions {
        *p = frame.to_work(p);
    }
    if let Some(shapes) = &mut work.shapes {
        for s in shapes {
            *s *= frame.scale;
        }
    }
    let Repaired {
        mut mesh,
        normals_given,
        face_source,
        vertex_source,
        report,
        ..
    } = repair(&work, &RepairOptions::default())?;
    drop(work);
    let repair_time_seconds = t0.elapsed().as_secs_f64();
    let t1 = std::time::Instant::now();
    let curvature_given = mesh.vertices().iter().all(|v| v.curvature_known);
    let (estimate, estimated) = match choice {
        EstimateChoice::None => {
            if !normals_given {
                return Err(PrepareError::NoNormals);
            }
            (None, "nothing")
        }
        EstimateChoice::With(est) => {
            let keep = normals_given && !replace_normals;
            if curvature_given && keep {
                (None, "nothing")
            } else if curvature_given {
                // Shapes are kept: estimate normals only, then put the file's shapes back
                // (projected into the new tangent planes so that S n = 0 holds).
                let shapes: Vec<_> = mesh.vertices().iter().map(|v| v.data.shape).collect();
                let summary = apply(&mut mesh, est, false);
                for (v, s) in mesh.vertices_mut().iter_mut().zip(shapes) {
                    let n = v.data.n;
                    let p = nalgebra::Matrix3::identity() - n * n.transpose();
                    v.data.shape = p * s * p;
                }
                (Some(summary), "normals")
            } else {
                let summary = apply(&mut mesh, est, keep);
                (
                    Some(summary),
                    if keep {
                        "curvature"
                    } else {
                        "normals and curvature"
                    },
                )
            }
        }
    };
    Ok(Prepared {
        mesh,
        frame,
        report,
        normals_given,
        face_source,
        vertex_source,
        estimate,
        estimated,
        repair_time_seconds,
        estimate_time_seconds: t1.elapsed().as_secs_f64(),
    })
}

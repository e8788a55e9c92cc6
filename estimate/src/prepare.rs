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
    /// Estimate what is missing with the degree-2 jet on one Euclidean ball of this many mean
    /// edge lengths around each vertex (`--radius`: [`crate::multiscale`]'s fit at a radius
    /// the user chose).
    Ball(f64),
}

impl std::fmt::Debug for EstimateChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EstimateChoice::None => write!(f, "None"),
            EstimateChoice::With(e) => write!(f, "With({})", e.name()),
            EstimateChoice::Ball(r) => write!(f, "Ball({r})"),
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
            EstimateChoice::Ball(_) => crate::multiscale::BALL_NAME,
        }
    }

    /// `name` (as [`EstimateChoice::parse`]), or with `radius` the ball of that many mean edge
    /// lengths ([`EstimateChoice::Ball`]): a radius must be finite and positive, and asks for
    /// an estimate, so it cannot go with `none`.
    pub fn parse_with_radius(name: &str, radius: Option<f64>) -> Result<Self, ChoiceError> {
        let choice = Self::parse(name)?;
        match (radius, choice) {
            (None, c) => Ok(c),
            (Some(r), _) if !(r > 0.0 && r.is_finite()) => Err(ChoiceError::Radius(r)),
            (Some(_), EstimateChoice::None) => Err(ChoiceError::RadiusWithNone),
            (Some(r), _) => Ok(EstimateChoice::Ball(r)),
        }
    }
}

/// Why an estimate choice was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ChoiceError {
    /// Not a registered estimator.
    #[error(transparent)]
    Unknown(#[from] UnknownEstimator),
    /// A radius that is not a positive number.
    #[error("--radius {0}: the radius must be a positive number of mean edge lengths")]
    Radius(f64),
    /// A radius with `none`.
    #[error("--radius asks for an estimate: it cannot go with `none`")]
    RadiusWithNone,
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
    /// Wall-clock time of the estimation (crease detection included), seconds.
    pub estimate_time_seconds: f64,
    /// What the crease detection found.
    pub creases: CreaseSummary,
    /// Flat sectors set to their plane and normals turned to face their faces
    /// ([`crate::facing`]).
    pub facing: crate::facing::FacingSummary,
}

impl Prepared {
    /// One line per thing a user should know (repairs, estimation and its fallbacks).
    pub fn summary_lines(&self) -> Vec<String> {
        let mut out = self.report.summary_lines();
        out.push(self.creases.line());
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
        let f = &self.facing;
        if f.flat_sectors
            + f.normals_turned
            + f.no_facing_normal
            + f.given_normals_against_faces
            + f.fold_sectors_cut
            > 0
        {
            out.push(format!(
                "sectors: {} flat (given their plane's normal and no curvature), {} normals turned to face every face they touch, {}{} with no such normal (the data folds there){}",
                f.flat_sectors,
                f.normals_turned,
                if f.fold_sectors_cut > 0 {
                    format!(
                        "{} with no such normal cut at {} edges where the data folds (made creases), ",
                        f.fold_sectors_cut, f.fold_edges_cut
                    )
                } else {
                    String::new()
                },
                f.no_facing_normal,
                if f.given_normals_against_faces > 0 {
                    format!(", {} normals from the file at 90° or more from a face (kept)", f.given_normals_against_faces)
                } else {
                    String::new()
                }
            ));
        }
        out
    }
}

/// What the crease detection of [`prepare_with`] found and did.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct CreaseSummary {
    /// The rule (`auto`, `angle 30°`, `none`).
    pub rule: String,
    /// Crease edges the data is split at (both ends' sectors differ at one end at least).
    pub creases: usize,
    /// Of the edges found, those from the geometry.
    pub from_geometry: usize,
    /// Of the edges found, those the file marks (and the geometry did not).
    pub from_file: usize,
    /// Crease edges found that separate no sectors (between two darts), treated as smooth.
    pub demoted: usize,
    /// Vertices where creases meet (three or more, or two turning sharply, or on a boundary).
    pub corners: usize,
    /// Vertices where a crease ends inside a smooth region.
    pub darts: usize,
    /// Vertices with two or more sectors.
    pub split_vertices: usize,
    /// Sectors (slots) in all.
    pub sectors: usize,
    /// Components, and those taken as tessellated models (geometric creases by default).
    pub components: usize,
    /// Components taken as tessellated models.
    pub tessellated_components: usize,
    /// Wall-clock time of the detection and the sector assignment, seconds.
    pub time_seconds: f64,
}

impl CreaseSummary {
    /// One line for the fit's notes.
    pub fn line(&self) -> String {
        if self.creases == 0 {
            return format!(
                "creases ({}): none{}",
                self.rule,
                if self.rule == "auto" && self.tessellated_components < self.components {
                    format!(
                        " ({} of {} components are not tessellated models: geometric creases need --crease-angle)",
                        self.components - self.tessellated_components,
                        self.components
                    )
                } else {
                    String::new()
                }
            );
        }
        format!(
            "creases ({}): {} edges ({} from the geometry, {} from the file), {} corners, {} darts; {} vertices split by them ({} sectors in all)",
            self.rule,
            self.creases,
            self.from_geometry,
            self.from_file,
            self.corners,
            self.darts,
            self.split_vertices,
            self.sectors
        )
    }
}

/// Finds the creases of `mesh` by `rule` and the file's `file_creases` (vertex pairs of the
/// mesh), and attaches the sectors when there is a crease: the estimation that follows is then
/// per sector ([`crate::apply`]).
pub fn attach_creases(
    mesh: &mut Mesh,
    rule: mesh::features::CreaseRule,
    file_creases: &[[usize; 2]],
) -> CreaseSummary {
    use mesh::features::{CreaseRule, Features, VertexKind};
    let t0 = std::time::Instant::now();
    let features = Features::find(mesh, rule, file_creases);
    let mut summary = CreaseSummary {
        rule: match rule {
            CreaseRule::Auto => "auto".into(),
            CreaseRule::Angle(d) => format!("angle {d}°"),
            CreaseRule::None => "none".into(),
        },
        components: features.components,
        tessellated_components: features.tessellated_components,
        ..CreaseSummary::default()
    };
    if features.num_creases() > 0 {
        if let Ok(sectors) = mesh::Sectors::new(mesh, &features.crease) {
            summary.creases = sectors.num_creases();
            summary.demoted = sectors.demoted();
            summary.sectors = sectors.num_slots();
            summary.split_vertices = sectors
                .slots_per_vertex(mesh.num_vertices())
                .iter()
                .filter(|&&n| n > 1)
                .count();
            let kept = sectors.creases();
            summary.from_file = (0..kept.len())
                .filter(|&e| kept[e] && features.by_file[e])
                .count();
            summary.from_geometry = summary.creases - summary.from_file;
            summary.corners = features.count(VertexKind::Corner);
            summary.darts = features.count(VertexKind::Dart);
            if kept.iter().any(|&c| c) && mesh.set_sectors(Some(sectors)).is_err() {
                summary = CreaseSummary {
                    rule: summary.rule,
                    ..CreaseSummary::default()
                };
            }
        }
    }
    summary.time_seconds = t0.elapsed().as_secs_f64();
    summary
}

/// Repairs `raw` and estimates what it lacks (module docs), with creases by the default rule
/// ([`mesh::features::CreaseRule::Auto`]).
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
    prepare_with(
        raw,
        choice,
        replace_normals,
        mesh::features::CreaseRule::Auto,
    )
}

/// [`prepare_owned`] with the crease rule `creases` (`--crease-angle`, `--no-creases`).
pub fn prepare_with(
    raw: RawMesh,
    choice: EstimateChoice,
    replace_normals: bool,
    creases: mesh::features::CreaseRule,
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
        crease_edges,
    } = repair(&work, &RepairOptions::default())?;
    drop(work);
    let repair_time_seconds = t0.elapsed().as_secs_f64();
    let t1 = std::time::Instant::now();
    let mut crease_summary = attach_creases(&mut mesh, creases, &crease_edges);
    let curvature_given = mesh.vertices().iter().all(|v| v.curvature_known);
    let ball;
    let chosen: Option<&dyn Estimator> = match choice {
        EstimateChoice::None => None,
        EstimateChoice::With(e) => Some(e),
        EstimateChoice::Ball(r) => {
            ball = crate::multiscale::Multiscale::ball(r);
            Some(&ball)
        }
    };
    let (estimate, estimated) = match chosen {
        None => {
            if !normals_given {
                return Err(PrepareError::NoNormals);
            }
            (None, "nothing")
        }
        Some(est) => {
            let keep = normals_given && !replace_normals;
            if curvature_given && keep {
                (None, "nothing")
            } else if curvature_given {
                // Shapes are kept: estimate normals only, then put the file's shapes back
                // (projected into the new tangent planes so that S n = 0 holds).
                let shapes: Vec<_> = mesh.vertices().iter().map(|v| v.data.shape).collect();
                let summary = apply(&mut mesh, est, false);
                let project = |n: &nalgebra::Vector3<f64>, s: &nalgebra::Matrix3<f64>| {
                    let p = nalgebra::Matrix3::identity() - n * n.transpose();
                    p * s * p
                };
                for (v, s) in mesh.vertices_mut().iter_mut().zip(&shapes) {
                    v.data.shape = project(&v.data.n, s);
                }
                if let Some(sec) = mesh.sectors_mut() {
                    for slot in 0..sec.num_slots() {
                        if let (Some(&v), Some(&n)) =
                            (sec.slot_vertices().get(slot), sec.normal(slot))
                        {
                            sec.set_slot(slot, n, project(&n, &shapes[v]), true);
                        }
                    }
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
    // Flat sectors get their plane, normals facing away from a face are turned (`facing`).
    let facing = if matches!(choice, EstimateChoice::None) {
        crate::facing::FacingSummary::default()
    } else {
        crate::facing::face_the_faces(
            &mut mesh,
            normals_given && !replace_normals,
            curvature_given,
        )
    };
    if mesh.sectors().is_none() && crease_summary.creases > 0 {
        // The estimation dropped the sectors (`crate::apply`): say so rather than count
        // creases the fit does not have.
        crease_summary = CreaseSummary {
            rule: format!(
                "{}, dropped: the mesh cut along its creases did not validate",
                crease_summary.rule
            ),
            ..CreaseSummary::default()
        };
    }
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
        creases: crease_summary,
        facing,
    })
}

//! The `--data` option shared by the experiments that take a mesh: a named analytic data set, or
//! a mesh file of any supported format, repaired and completed by an estimator
//! ([`estimate::prepare()`]): the fit job's input (`fitjob::input`) as command-line options.

use crate::error::ExperimentError;

/// Options naming the input mesh and how to complete it.
#[derive(clap::Args, Debug, Clone)]
pub struct InputArgs {
    /// A data set or a mesh file (the format by extension, checked against the content); the
    /// help lists both from their registries.
    #[arg(long, default_value = "ring", help = data_help())]
    pub data: String,
    /// Resolution of a named data set (its default when absent).
    #[arg(long)]
    pub resolution: Option<usize>,
    /// How to estimate what a mesh file lacks (normals, shape tensors): an estimator's name or
    /// `none` (use the file's data only; curvature-based curves then need a file with shape
    /// tensors). The names come from the estimator registry.
    #[arg(long, default_value = estimate::DEFAULT_ESTIMATOR, value_parser = fitjob::cli::estimator_names())]
    pub estimate: String,
    /// Estimate on Euclidean balls of this many mean edge lengths around each vertex (the
    /// degree-2 jet at one radius, Huber-weighted for the mesh's noise) instead of the
    /// estimator's own neighbourhoods: wider for noisier scans (`estimate::multiscale`).
    #[arg(long, value_name = "R")]
    pub radius: Option<f64>,
    /// Estimate normals even where the file gives them (by default the file's normals are kept
    /// and only the curvature is estimated, in their tangent planes).
    #[arg(long)]
    pub replace_normals: bool,
    /// How creases are found (`--crease-angle DEG`, `--no-creases`).
    #[command(flatten)]
    pub creases: fitjob::cli::CreaseArgs,
}

/// `--data`'s help: the data sets and the readable mesh formats, from their registries.
fn data_help() -> String {
    format!(
        "A data set ({}) or a mesh file ({}; the format by extension, checked against the content)",
        mesh::datasets::DATASET_NAMES.join(", "),
        meshio::readable_extensions()
    )
}

/// A loaded input mesh (the fit job's).
pub use fitjob::input::Loaded;

impl InputArgs {
    /// The fit job's input for these options.
    pub fn job_input(&self) -> fitjob::InputOptions {
        fitjob::InputOptions {
            source: fitjob::Source::Data {
                data: self.data.clone(),
                resolution: self.resolution,
            },
            estimate: self.estimate.clone(),
            radius: self.radius,
            replace_normals: self.replace_normals,
            creases: self.creases.rule(),
        }
    }
}

/// Loads `--data`: an existing file is read as a mesh; otherwise the name is a data set
/// (`fitjob::input::load`).
pub fn load(args: &InputArgs) -> Result<Loaded, ExperimentError> {
    Ok(fitjob::input::load(&args.job_input())?)
}

/// A study's fit as the fit job made and measured it ([`fit_kept`]).
pub struct KeptFit {
    /// The fit.
    pub fit: surface::Fit,
    /// Its whole G1 measurement.
    pub g1: surface::G1Report,
    /// The fit's time, seconds.
    pub seconds: f64,
    /// The mesh faces whose surface turns over (`surface::folds`, measured by the job), in
    /// face order.
    pub folded: Vec<usize>,
    /// The smallest cosine between a patch normal and its face's (`None`: nothing measured).
    pub worst_fold_cosine: Option<f64>,
}

/// A study's fit through the fit job (`fitjob::run`, the fit and G1 every front end gets), the
/// fit kept: the fit, its whole G1 measurement and the fit's time in seconds.
pub fn fit_kept(options: fitjob::FitOptions) -> Result<KeptFit, ExperimentError> {
    let label = options.input.source.label().to_string();
    let outcome = fitjob::run(
        fitjob::FitOptions {
            keep: true,
            ..options
        },
        &mut |_| {},
    )?;
    match (outcome.kept.fit, outcome.kept.g1) {
        (Some(fit), Some(g1)) => Ok(KeptFit {
            fit,
            g1,
            seconds: outcome.report.time.fit,
            folded: outcome.report.folds.as_ref().map_or_else(Vec::new, |f| {
                f.folded_faces.iter().map(|r| r.face).collect()
            }),
            worst_fold_cosine: outcome.report.folds.and_then(|f| f.worst_cosine),
        }),
        // A subdivision scheme: no patches to keep.
        _ => Err(ExperimentError::from(fitjob::JobError::Write {
            path: label.into(),
            source: std::io::Error::other("the fit job kept no fit"),
        })),
    }
}

/// [`fit_kept`] of an already prepared mesh (`mesh` in its working `frame`, as
/// [`fitjob::Source::Prepared`]) with `scheme` on `curves` (with `method_options`).
pub fn fit_prepared(
    label: &str,
    mesh: &surface::Mesh,
    frame: surface::Frame,
    scheme: &str,
    curves: &str,
    method_options: curves::MethodOptions,
) -> Result<KeptFit, ExperimentError> {
    fit_kept(fitjob::FitOptions {
        input: fitjob::InputOptions {
            source: fitjob::Source::Prepared {
                label: label.to_string(),
                mesh: Box::new(mesh.clone()),
                frame,
            },
            ..fitjob::InputOptions::default()
        },
        scheme: scheme.to_string(),
        curves: curves.to_string(),
        method_options,
        ..fitjob::FitOptions::default()
    })
}

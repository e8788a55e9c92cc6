//! What can stop a fit job, each variant naming the file, option or value involved; the cause
//! is kept as the variant's `source` so that a front end can show the whole chain.

use std::path::PathBuf;

/// A fit job could not run or could not write its outputs.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    /// A result could not be written.
    #[error("cannot write {path}")]
    Write {
        /// The file (or `<stdout>`).
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// An output file could not be written (`meshio::outfile`: atomic, regular files only).
    #[error(transparent)]
    Output(#[from] meshio::outfile::OutputError),
    /// A mesh file could not be read.
    #[error(transparent)]
    MeshIo(meshio::MeshIoError),
    /// A mesh file was read but could not be made into a mesh to fit (nothing left after
    /// repair, coordinates beyond a working frame, no normals and no estimator).
    #[error("{path}: cannot make a mesh to fit of it")]
    Prepare {
        /// The file.
        path: PathBuf,
        /// Why.
        source: estimate::PrepareError,
    },
    /// `--estimate` names no estimator, or `--radius` is not a positive number or goes with
    /// `none`.
    #[error("--estimate {value}: {source}")]
    Estimate {
        /// The value given.
        value: String,
        /// What is wrong (an unknown name lists the known ones).
        source: estimate::ChoiceError,
    },
    /// The input names a data set that cannot be built: an unknown name that is no mesh file
    /// either, or a resolution out of range.
    #[error("{given}: {}", data_hint(source))]
    DataOption {
        /// The options as given (`--data NAME`, `--resolution N`).
        given: String,
        /// The data-set registry's answer.
        source: mesh::DataSetError,
    },
    /// A curve construction name is not registered.
    #[error(transparent)]
    Method(#[from] curves::UnknownMethod),
    /// A surface scheme name is not registered.
    #[error(transparent)]
    Scheme(#[from] surface::UnknownScheme),
    /// Subdivision could not run (an unknown scheme, non-triangles for Loop, a non-manifold
    /// spot, or more faces than the limit).
    #[error("{subject}: subdivision")]
    Subdivision {
        /// The input.
        subject: String,
        /// Why.
        source: subdiv::SubdivError,
    },
    /// A fit could not be made (a bad parameter, or curvature the data does not have).
    #[error("{subject}: cannot fit")]
    Fit {
        /// What was being fitted (the input's name).
        subject: String,
        /// Why.
        source: surface::FitError,
    },
    /// `--heightfield` on data that is not a height field, or with a scheme that has no
    /// functional form (`surface::scheme::functional`).
    #[error("{subject}: cannot fit as a height field")]
    HeightField {
        /// What was being fitted.
        subject: String,
        /// Why.
        source: surface::scheme::functional::HeightFieldError,
    },
    /// A tessellation could not be made.
    #[error("{subject}: cannot tessellate")]
    Tessellate {
        /// What was being tessellated.
        subject: String,
        /// Why.
        source: surface::TessError,
    },
    /// A tessellation or mesh could not be encoded in the format of its output file.
    #[error("cannot write {path} as a mesh")]
    MeshWrite {
        /// The output file.
        path: PathBuf,
        /// The format writer's answer (the format and what it cannot hold).
        source: meshio::WriteError,
    },
    /// An output option names a file whose extension no mesh writer handles.
    #[error("{option} {path}: unsupported output format (writable: {writable})", path = .path.display())]
    UnsupportedOutputFormat {
        /// The option (`--output`, `--mesh-output`).
        option: &'static str,
        /// The file given.
        path: PathBuf,
        /// The writable extensions, comma-separated.
        writable: String,
    },
    /// An output option names the input file (by any path): writing would destroy the input.
    #[error("{option} {path}: the output is the input file; choose another output path", path = .path.display())]
    OutputIsInput {
        /// The option (`--output`, `--mesh-output`).
        option: &'static str,
        /// The file given.
        path: PathBuf,
    },
    /// A report could not be serialized as JSON.
    #[error("cannot serialize {what} as JSON")]
    Json {
        /// Which report.
        what: &'static str,
        /// Why.
        source: serde_json::Error,
    },
    /// A numeric option is outside its valid range.
    #[error("--{option} {value}: outside its valid range {range}{}", why.map(|w| format!(" ({w})")).unwrap_or_default())]
    OutOfRange {
        /// The option, without its dashes (`beta`, `tess`).
        option: &'static str,
        /// The value as given (shown in scientific notation when very small or large).
        value: String,
        /// The valid range, `[lo, hi]`.
        range: String,
        /// Why the range is what it is, where that needs saying.
        why: Option<&'static str>,
    },
    /// A setting would need more memory than the machine has available.
    #[error("{what} would need about {:.1} GB, more than this machine has available ({:.1} GB): choose a smaller setting", *needed_bytes as f64 / 1e9, *budget_bytes as f64 / 1e9)]
    TooMuchMemory {
        /// The options responsible (`--resolution 4096 --segments 4`).
        what: String,
        /// Estimated need, bytes.
        needed_bytes: u128,
        /// What the run may use, bytes.
        budget_bytes: u128,
    },
}

impl JobError {
    /// Whether the command line is at fault whatever the input (an unknown name, a value
    /// outside its range, an output that is the input or has no writer): front ends exit with
    /// status 2 for these and 1 for the rest (docs/conventions.md, "The command language").
    pub fn is_usage(&self) -> bool {
        matches!(
            self,
            JobError::Estimate { .. }
                | JobError::DataOption { .. }
                | JobError::Method(_)
                | JobError::Scheme(_)
                | JobError::UnsupportedOutputFormat { .. }
                | JobError::OutputIsInput { .. }
                | JobError::OutOfRange { .. }
        )
    }
}

/// The second half of a [`JobError::DataOption`] message.
fn data_hint(e: &mesh::DataSetError) -> String {
    match e {
        mesh::DataSetError::UnknownName { .. } => format!(
            "not a data set, and no mesh file of that name (mesh files: {})",
            meshio::readable_extensions()
        ),
        _ => "cannot build this data set".into(),
    }
}

/// An error and its causes as the user sees them: the error on the first line, then each cause
/// on its own `caused by:` line, leaving out a cause whose text is already shown (errors of other
/// crates often repeat their source in their own message).
pub fn chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        let line = c.to_string();
        if !text.contains(&line) {
            text.push_str("\n  caused by: ");
            text.push_str(&line);
        }
        cause = c.source();
    }
    text
}

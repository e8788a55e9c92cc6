//! What can stop an experiment before it produces anything.
//!
//! Every variant says what the experiment was doing and names the file, option or value
//! involved; where another error is the cause it is kept as the variant's `source` (never
//! flattened into a string), so the whole chain reaches the user: [`chain`] writes the error
//! and then each cause on its own `caused by:` line. The variants of this crate do not repeat
//! their cause in their own message; errors of other crates often do (`"{path}: {source}"`),
//! and [`chain`] leaves out a cause whose text is already shown.

use std::path::PathBuf;

/// An experiment could not run or could not write its results.
#[derive(Debug, thiserror::Error)]
pub enum ExperimentError {
    /// A file, directory or standard input could not be read.
    #[error("cannot read {path}")]
    Read {
        /// The file (or `<stdin>`).
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A result could not be written.
    #[error("cannot write {path}")]
    Write {
        /// The file (or `<stdout>`).
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A figure could not be drawn, or a file could not be written atomically (the renderer's
    /// writer refuses a directory, device, FIFO or socket by name).
    #[error(transparent)]
    Render(#[from] render::RenderError),
    /// An output file could not be written (`meshio::outfile`).
    #[error(transparent)]
    Output(#[from] meshio::outfile::OutputError),
    /// The fit job (or its input, limits or outputs) refused or failed (`fitjob`).
    #[error(transparent)]
    Job(Box<fitjob::JobError>),
    /// `--data` (with `--resolution`), or the ring study's `--resolution`, asks for a data set
    /// that cannot be built: an unknown name that is no mesh file either, or a resolution out of
    /// range.
    #[error("{given}: {}", data_hint(source))]
    DataOption {
        /// The options as given (`--data NAME`, `--resolution N`).
        given: String,
        /// The data-set registry's answer (boxed: the largest cause, and the error stays small
        /// for the library's callers).
        source: Box<surface::DataSetError>,
    },
    /// A data set the experiment builds by itself could not be built (a defect, not a usage
    /// error: the names and resolutions are the experiment's own).
    #[error(transparent)]
    DataSet(#[from] surface::DataSetError),
    /// A curve construction name is not registered (`curve --methods`; `fit --curves` is checked
    /// against the registry by the command-line parser).
    #[error(transparent)]
    Method(#[from] curves::UnknownMethod),
    /// Subdivision could not run (an unknown scheme, non-triangles for Loop, a non-manifold
    /// spot, or more faces than the limit).
    #[error("{subject}: subdivision")]
    Subdivision {
        /// The input.
        subject: String,
        /// Why.
        source: subdiv::SubdivError,
    },
    /// A surface scheme name is not registered.
    #[error(transparent)]
    Scheme(#[from] surface::UnknownScheme),
    /// The boundary-curve problems of a mesh could not be set up (a degenerate edge, named by
    /// its vertices).
    #[error("{subject}: cannot set up the boundary-curve problems")]
    EdgeProblems {
        /// What was being fitted (`ring`, a sweep task such as `sphere/optimized/lm`).
        subject: String,
        /// The degenerate edge.
        source: curves::EdgeError,
    },
    /// A fit could not be made (a bad parameter, or curvature the data does not have).
    #[error("{subject}: cannot fit")]
    Fit {
        /// What was being fitted (the `--data` value, `ring/dbhs`, a sweep task, a file).
        subject: String,
        /// Why.
        source: surface::FitError,
    },
    /// A fit could not be measured (its patches do not match its mesh: a bug, reported).
    #[error("{subject}: cannot measure the fit: {message}")]
    Measure {
        /// What was being measured.
        subject: String,
        /// Why.
        message: String,
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
    /// A results directory exists as something that is not a directory.
    #[error("{path}: exists and is not a directory; results are a directory")]
    NotADirectory {
        /// The path given.
        path: PathBuf,
    },
    /// A results directory holds files the study did not write (no manifest of a study's,
    /// or entries it does not list): it is not the study's to replace.
    #[error(
        "{path}: holds files no study of this workbench wrote ({}{}); results replace their \
         directory whole, so give an empty or new directory (or move those files away)",
        names.join(", "),
        if *more > 0 { format!(" and {more} more") } else { String::new() }
    )]
    ForeignFiles {
        /// The results directory.
        path: PathBuf,
        /// The first few such entries.
        names: Vec<String>,
        /// How many more there are.
        more: usize,
    },
    /// A report could not be serialized as JSON.
    #[error("cannot serialize {what} as JSON")]
    Json {
        /// Which report (`the ring report`, `a sweep shard`, …).
        what: &'static str,
        /// Why.
        source: serde_json::Error,
    },
    /// A JSON input file (golden numbers) is not valid JSON.
    #[error("{path}: not valid JSON")]
    JsonFile {
        /// The file.
        path: PathBuf,
        /// The parser's answer (line and column).
        source: serde_json::Error,
    },
    /// A shard file of `sweep --shard` could not be read by `merge`.
    #[error("{path}: not a shard file of `sweep` that merge can read")]
    Shard {
        /// The file.
        path: PathBuf,
        /// Why.
        source: crate::shard::ShardError,
    },
    /// A task appears in two shard files.
    #[error("{path}: task {index} ({task}) appears in more than one shard", path = .path.display())]
    ShardTaskRepeated {
        /// The shard file where it appears again.
        path: PathBuf,
        /// The task's index in the sweep.
        index: usize,
        /// The task's name as the shard file gives it (JSON).
        task: serde_json::Value,
    },
    /// Tasks of the sweep are in no shard file.
    #[error("merge: {} of {total} tasks missing from {files} shard file(s): {}", missing.len(), missing.join(", "))]
    ShardTasksMissing {
        /// The missing tasks' names.
        missing: Vec<String>,
        /// Tasks of the sweep.
        total: usize,
        /// Shard files read.
        files: usize,
    },
    /// Options that cannot be used together, or a value the parser could not check (exit
    /// status 2, like the parser's own usage errors).
    #[error("{0}")]
    Usage(String),
    /// A study refused its options or its input (`crate::study::StudyError`; its `is_usage`
    /// tells a usage error from a runtime one).
    #[error(transparent)]
    Study(#[from] crate::study::StudyError),
    /// A surface could not be put on an interactive page (a value no page can draw).
    #[error("{}: cannot draw it on the page", path.display())]
    Page {
        /// The page, or the file drawn on it.
        path: PathBuf,
        /// Why.
        #[source]
        source: viewer::ViewError,
    },
    /// `--corpus` holds no readable mesh file.
    #[error("--corpus {path}: no mesh files (readable: {})", meshio::readable_extensions(), path = .path.display())]
    EmptyCorpus {
        /// The directory given.
        path: PathBuf,
    },
}

impl ExperimentError {
    /// The exit status this error ends the run with (docs/conventions.md, "The command
    /// language"): 2 for a usage error (an unknown name, a value outside its range, options that
    /// cannot go together: the command line is wrong whatever the input), 1 for everything else
    /// (the input, the machine or the output refused).
    pub fn exit_code(&self) -> u8 {
        match self {
            ExperimentError::Usage(_)
            | ExperimentError::DataOption { .. }
            | ExperimentError::Method(_)
            | ExperimentError::Scheme(_) => 2,
            ExperimentError::Job(e) if e.is_usage() => 2,
            ExperimentError::Study(e) if e.is_usage() => 2,
            _ => 1,
        }
    }
}

impl From<fitjob::JobError> for ExperimentError {
    fn from(e: fitjob::JobError) -> Self {
        ExperimentError::Job(Box::new(e))
    }
}

/// The second half of a [`ExperimentError::DataOption`] message.
fn data_hint(e: &surface::DataSetError) -> String {
    match e {
        surface::DataSetError::UnknownName { .. } => format!(
            "not a data set, and no mesh file of that name (mesh files: {})",
            meshio::readable_extensions()
        ),
        _ => "cannot build this data set".into(),
    }
}

/// An error and its causes as the user sees them (the fit job's [`fitjob::chain`], so every
/// front end shows causes alike).
pub use fitjob::chain;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_chain_shows_every_cause_once() {
        let e = ExperimentError::Json {
            what: "the ring report",
            source: serde_json::from_str::<serde_json::Value>("{").unwrap_err(),
        };
        let text = chain(&e);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 2, "{text}");
        assert_eq!(lines[0], "cannot serialize the ring report as JSON");
        assert!(lines[1].starts_with("  caused by: EOF"), "{text}");
        // A cause the message already repeats is not shown twice.
        let e = ExperimentError::Output(meshio::outfile::OutputError::Io {
            path: "x.png".into(),
            source: std::io::Error::other("disk full"),
        });
        assert_eq!(chain(&e), "cannot write x.png: disk full");
    }

    #[test]
    fn data_option_errors_name_the_option_and_keep_the_registry_answer() {
        let source =
            surface::dataset_by_name("torus", None).expect_err("`torus` is not a data set");
        let e = ExperimentError::DataOption {
            given: "--data torus".into(),
            source: Box::new(source),
        };
        let text = chain(&e);
        assert!(text.starts_with("--data torus: not a data set"), "{text}");
        assert!(
            text.contains("caused by: unknown data set `torus`"),
            "{text}"
        );
    }
}

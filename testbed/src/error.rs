//! Typed errors of the stream readers, writers and filters.

/// Where a record starts in its stream: its number (1-based, counting every record read,
/// good or bad) and the line of its first byte (1-based; `0` for the binary format, which has
/// no lines).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Position {
    /// Record number, from 1.
    pub record: usize,
    /// Line of the record's first byte, from 1 (0: not a text stream).
    pub line: usize,
}

impl std::fmt::Display for Position {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line > 0 {
            write!(f, "record {} (line {})", self.record, self.line)
        } else {
            write!(f, "record {}", self.record)
        }
    }
}

/// A field of a record that a filter needs is missing or malformed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("field `{field}`: {message}")]
pub struct FieldError {
    /// The field's path in the record (`vertex1.pos`, `points[3]`).
    pub field: String,
    /// What is wrong with it.
    pub message: String,
}

impl FieldError {
    /// A field error at `field`.
    pub fn new(field: impl Into<String>, message: impl Into<String>) -> Self {
        FieldError {
            field: field.into(),
            message: message.into(),
        }
    }
}

/// Why a stream could not be read or written, or a record could not be used.
#[derive(Debug, thiserror::Error)]
pub enum StreamError {
    /// Reading or writing the underlying file or pipe failed.
    #[error("{context}: {source}")]
    Io {
        /// What was being read or written.
        context: String,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// A record could not be parsed (the stream's syntax).
    #[error("{at}: {message}")]
    Syntax {
        /// Where the record starts.
        at: Position,
        /// What is wrong.
        message: String,
    },
    /// A record parsed but a field a filter needs is missing or malformed.
    #[error("{at} ({kind}): {source}")]
    Field {
        /// Where the record starts.
        at: Position,
        /// The record's type.
        kind: String,
        /// The field and what is wrong with it.
        source: FieldError,
    },
    /// The stream's first bytes name no known format.
    #[error("unrecognised stream: the first byte {found:?} starts neither JSON Lines (`{{`), a dstruct (`(`) nor the binary form (`TBIN`)")]
    UnknownFormat {
        /// The first non-space byte, as a character.
        found: char,
    },
    /// A binary stream is damaged in a way that cannot be skipped (records have no
    /// separators to resynchronise on).
    #[error("binary stream, {at}: {message}")]
    Binary {
        /// The record being read.
        at: Position,
        /// What is wrong.
        message: String,
    },
    /// A record cannot be written in the chosen format.
    #[error("{at}: cannot write as {format}: {message}")]
    Unwritable {
        /// The record.
        at: Position,
        /// The output format.
        format: &'static str,
        /// Why.
        message: String,
    },
}

impl StreamError {
    /// True for errors confined to one record, which `--keep-going` may skip: syntax errors in
    /// a text stream and field errors. I/O errors, unknown formats and damaged binary streams
    /// end the run.
    pub fn is_record_error(&self) -> bool {
        matches!(
            self,
            StreamError::Syntax { .. } | StreamError::Field { .. } | StreamError::Unwritable { .. }
        )
    }

    /// An I/O error with its context.
    pub fn io(context: impl Into<String>, source: std::io::Error) -> Self {
        StreamError::Io {
            context: context.into(),
            source,
        }
    }
}

/// Why a filter failed as a whole.
#[derive(Debug, thiserror::Error)]
pub enum FilterError {
    /// The record stream.
    #[error(transparent)]
    Stream(#[from] StreamError),
    /// An option is invalid.
    #[error("{0}")]
    Usage(String),
    /// Reading the input mesh failed.
    #[error(transparent)]
    MeshIo(#[from] meshio::MeshIoError),
    /// Repairing or completing the input mesh failed.
    #[error("preparing the mesh: {0}")]
    Prepare(#[from] estimate::PrepareError),
    /// Fitting failed.
    #[error("fitting: {0}")]
    Fit(#[from] surface::FitError),
    /// Tessellation failed.
    #[error("tessellating: {0}")]
    Tess(#[from] surface::TessError),
    /// A data set could not be built.
    #[error("data set: {0}")]
    DataSet(#[from] surface::DataSetError),
    /// Rendering failed.
    #[error("rendering: {0}")]
    Render(#[from] render::RenderError),
    /// Encoding the PNG failed.
    #[error("encoding PNG: {0}")]
    Png(String),
    /// Writing a mesh file failed.
    #[error("writing {path}: {message}")]
    MeshWrite {
        /// The file.
        path: std::path::PathBuf,
        /// Why.
        message: String,
    },
    /// A setting would need more memory than the run may use (the estimate made before
    /// allocating: [`surface::limits`]).
    #[error(transparent)]
    TooMuchMemory(Box<surface::limits::TooMuchMemory>),
    /// The fit job refused or failed in a way none of the variants above says
    /// (`fitjob::JobError`).
    #[error(transparent)]
    Job(Box<fitjob::JobError>),
    /// `g1 --strict`: boundaries were left unmeasured, or nothing was measured (and perhaps
    /// the tolerance exceeded too: every reason is named).
    #[error("--strict: {0}")]
    G1Unmeasured(String),
    /// A value that would be written is not finite (a curvature beyond the range of `f64`):
    /// the message names the record or patch and the value.
    #[error("{0}")]
    NotFinite(String),
    /// A picture would be blank: nothing to draw (the message says why and what to do).
    #[error("{0}")]
    Blank(String),
    /// A colouring filter found no `Triangle` or `TriangleMesh` to colour (a `tess` forgotten
    /// before it, most likely); its records passed through.
    #[error("no Triangle or TriangleMesh records to colour ({held}): put `tess` before `{filter}` (testbed fit … | testbed tess | testbed {filter})")]
    NothingToColour {
        /// The filter.
        filter: &'static str,
        /// What the stream held instead.
        held: String,
    },
    /// `g1 --strict`: a boundary exceeds the tolerance.
    #[error("G1 defect {angle:.3e} rad exceeds the tolerance {tolerance:.1e} rad")]
    G1Exceeded {
        /// The largest angle measured.
        angle: f64,
        /// The tolerance.
        tolerance: f64,
    },
}

impl FilterError {
    /// The process's exit status for this error (docs/conventions.md, "The command
    /// language"): 2 for a usage error (an option's value out of its range, a bad name, options
    /// that cannot go together), 1 for every runtime error (bad input, a refusal, a failed
    /// `--strict`).
    pub fn exit_code(&self) -> u8 {
        match self {
            FilterError::Usage(_) => 2,
            _ => 1,
        }
    }
}

impl From<fitjob::JobError> for FilterError {
    /// The fit job's errors as the pipeline has always reported them: usage errors for bad
    /// names, the library's own errors for a failed read, repair, fit or data set.
    fn from(e: fitjob::JobError) -> Self {
        use fitjob::JobError as J;
        match e {
            J::MeshIo(e) => FilterError::MeshIo(e),
            J::Prepare { source, .. } => FilterError::Prepare(source),
            J::Fit { source, .. } => FilterError::Fit(source),
            J::Tessellate { source, .. } => FilterError::Tess(source),
            J::DataOption { source, .. } => FilterError::DataSet(source),
            J::Estimate { value, source } => {
                FilterError::Usage(format!("--estimate {value}: {source}"))
            }
            J::Scheme(e) => FilterError::Usage(e.to_string()),
            J::Method(e) => FilterError::Usage(e.to_string()),
            J::TooMuchMemory {
                what,
                needed_bytes,
                budget_bytes,
            } => FilterError::TooMuchMemory(Box::new(surface::limits::TooMuchMemory {
                what,
                needed_bytes,
                budget_bytes,
            })),
            other => FilterError::Job(Box::new(other)),
        }
    }
}

impl From<surface::limits::TooMuchMemory> for FilterError {
    fn from(e: surface::limits::TooMuchMemory) -> Self {
        // Boxed: its figures are u128s, and every filter returns this error type.
        FilterError::TooMuchMemory(Box::new(e))
    }
}

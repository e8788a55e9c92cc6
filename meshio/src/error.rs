//! Typed errors of reading and writing: where in the file, what went wrong, which format.

use std::fmt;
use std::path::PathBuf;

/// Where in a file a reader stopped.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Location {
    /// A line of a text format (1-based).
    Line(usize),
    /// A record of a record-based format: PLY elements (`vertex`, `face`, …), STL facets
    /// (`facet`), 0-based index.
    Element {
        /// The element's name.
        element: String,
        /// Its 0-based index.
        index: usize,
        /// The property of the record being read, when the error is about one value.
        property: Option<String>,
    },
    /// A byte offset (0-based) in a binary format.
    Byte(u64),
    /// The header of a format that has one (PLY, binary STL).
    Header,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(n) => write!(f, "line {n}"),
            Location::Element {
                element,
                index,
                property: None,
            } => write!(f, "element {element} {index}"),
            Location::Element {
                element,
                index,
                property: Some(p),
            } => write!(f, "element {element} {index}, property {p}"),
            Location::Byte(o) => write!(f, "byte {o}"),
            Location::Header => write!(f, "header"),
        }
    }
}

/// A file could not be read: the format, where, and what.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{location}: {message}")]
pub struct ReadError {
    /// The format's name ([`crate::MeshFormat::name`]).
    pub format: &'static str,
    /// Where the reader stopped.
    pub location: Location,
    /// What was wrong or expected.
    pub message: String,
}

impl ReadError {
    /// An error of `format` at `location`.
    pub fn new(format: &'static str, location: Location, message: impl Into<String>) -> Self {
        ReadError {
            format,
            location,
            message: message.into(),
        }
    }

    /// An error at a 1-based line.
    pub fn line(format: &'static str, line: usize, message: impl Into<String>) -> Self {
        Self::new(format, Location::Line(line), message)
    }

    /// An error at record `index` of `element`.
    pub fn element(
        format: &'static str,
        element: &str,
        index: usize,
        message: impl Into<String>,
    ) -> Self {
        Self::new(
            format,
            Location::Element {
                element: element.to_string(),
                index,
                property: None,
            },
            message,
        )
    }

    /// An error at `property` of record `index` of `element`.
    pub fn property(
        format: &'static str,
        element: &str,
        index: usize,
        property: &str,
        message: impl Into<String>,
    ) -> Self {
        Self::new(
            format,
            Location::Element {
                element: element.to_string(),
                index,
                property: Some(property.to_string()),
            },
            message,
        )
    }

    /// An error in the header.
    pub fn header(format: &'static str, message: impl Into<String>) -> Self {
        Self::new(format, Location::Header, message)
    }
}

/// A mesh could not be written in a format.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The format is read-only.
    #[error("{format}: writing is not supported")]
    NotSupported {
        /// The format's name.
        format: &'static str,
    },
    /// The mesh cannot be written in this format (a name the format cannot hold, a NaN, an
    /// index out of range, too many vertices for the index type, …).
    #[error("{format}: {message}")]
    Invalid {
        /// The format's name.
        format: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The mesh was valid but the bytes could not be delivered: the writer given to
    /// [`crate::MeshFormat::write_to`] failed (a full disk, a closed pipe). Every check runs
    /// before the first byte, so this is never a mesh problem.
    #[error("{format}: {source}")]
    Io {
        /// The format's name.
        format: &'static str,
        /// The writer's error.
        #[source]
        source: std::io::Error,
    },
}

impl WriteError {
    pub(crate) fn invalid(format: &'static str, message: impl Into<String>) -> Self {
        WriteError::Invalid {
            format,
            message: message.into(),
        }
    }
}

/// Reading a mesh file failed: the file, and why.
#[derive(Debug, thiserror::Error)]
pub enum MeshIoError {
    /// The file could not be read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file was read but its content is not a valid file of its format.
    #[error("{}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The format error.
        source: ReadError,
    },
    /// Neither the extension nor the content names a supported format.
    #[error("{}: unsupported format (supported extensions: {extensions})", path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// The readable extensions, comma-separated.
        extensions: String,
    },
}

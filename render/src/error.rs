//! The error type of every renderer in this crate.

use std::path::PathBuf;

/// Why a figure could not be rendered or written; every variant names the output file.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// Reading or writing the file (or its temporary sibling) failed.
    #[error("cannot write {path}: {source}", path = .path.display())]
    Io {
        /// The file being written.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The output path has no file name (for example `/` or `..`), so there is nothing to
    /// create a temporary sibling of.
    #[error("cannot write {path}: the path has no file name", path = .path.display())]
    NoFileName {
        /// The offending path.
        path: PathBuf,
    },
    /// The output path exists and is not a regular file (a directory, a device, a FIFO, a
    /// socket, or a symbolic link to one): writing would replace or feed something that is not
    /// a result file.
    #[error("cannot write {path}: it is {kind}, not a regular file (choose a file path; to write to standard output, leave the option out)", path = .path.display())]
    NotRegularFile {
        /// The offending path.
        path: PathBuf,
        /// What it is (`"a directory"`, `"a FIFO"`, …).
        kind: &'static str,
    },
    /// The figure has nothing to draw.
    #[error("cannot write {path}: the figure has no panels", path = .path.display())]
    EmptyFigure {
        /// The file that was to be written.
        path: PathBuf,
    },
    /// The plotting library reported an error while drawing.
    #[error("cannot draw {path}: {message}", path = .path.display())]
    Draw {
        /// The file being drawn.
        path: PathBuf,
        /// The plotting library's message.
        message: String,
    },
    /// Encoding the bitmap as PNG failed.
    #[error("cannot encode {path} as PNG: {message}", path = .path.display())]
    Encode {
        /// The file being encoded.
        path: PathBuf,
        /// The encoder's message.
        message: String,
    },
    /// The bundled font could not be registered with the plotting library.
    #[error("cannot draw {path}: the bundled font could not be loaded", path = .path.display())]
    Font {
        /// The file that was to be drawn.
        path: PathBuf,
    },
}

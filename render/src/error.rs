//! The error type of every renderer in this crate.

use std::path::PathBuf;

/// Why a figure could not be rendered or written; every variant names the output file.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The file could not be written (`meshio::outfile`: atomic, regular files only).
    #[error(transparent)]
    Output(#[from] meshio::outfile::OutputError),
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
    /// The shading mode's numbers are out of range ([`crate::shade::Shading::validate`]).
    #[error("shading mode {mode}: {message}")]
    Shading {
        /// The mode (`reflection`, `isophotes`, `highlight`).
        mode: &'static str,
        /// What is wrong, naming the field.
        message: String,
    },
    /// A drawing option the incremental canvas cannot honour ([`crate::canvas::Canvas`]: the
    /// wireframe overlay needs the finished depth buffer).
    #[error("{0}")]
    Unsupported(String),
}

//! What can stop an experiment before it produces anything.

use std::path::PathBuf;

/// An experiment could not run or could not write its results.
#[derive(Debug, thiserror::Error)]
pub enum ExperimentError {
    /// A file or standard input could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file (or `<stdin>`).
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A result could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A figure could not be drawn or written.
    #[error(transparent)]
    Render(#[from] render::RenderError),
    /// A mesh file could not be read.
    #[error(transparent)]
    MeshIo(meshio::MeshIoError),
    /// A mesh file was read but could not be made into a mesh to fit.
    #[error("{}: {source}", path.display())]
    Prepare {
        /// The file.
        path: PathBuf,
        /// Why.
        source: estimate::PrepareError,
    },
    /// A named data set does not exist or its resolution is out of range.
    #[error(transparent)]
    DataSet(#[from] surface::DataSetError),
    /// A curve construction name is not registered.
    #[error(transparent)]
    Method(#[from] curves::UnknownMethod),
    /// A surface scheme name is not registered.
    #[error(transparent)]
    Scheme(#[from] surface::UnknownScheme),
    /// An edge's boundary-curve problem is degenerate (names the edge's vertices).
    #[error(transparent)]
    Edge(#[from] curves::EdgeError),
    /// A fit could not be made (a bad parameter, or curvature the data does not have).
    #[error(transparent)]
    Fit(#[from] surface::FitError),
    /// A tessellation could not be made.
    #[error("tessellation: {0}")]
    Tess(#[from] surface::TessError),
    /// A command-line setting names something that does not exist.
    #[error("{0}")]
    Usage(String),
}

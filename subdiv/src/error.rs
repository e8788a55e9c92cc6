//! The one error type of the crate: every refusal names the element it is about.

use thiserror::Error;

/// Why a mesh was refused or a subdivision could not be done. Vertex and face numbers are
/// 0-based indices into the mesh the operation was given.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum SubdivError {
    /// A position is NaN or infinite.
    #[error("vertex {vertex}: position is not finite")]
    NonFinitePosition {
        /// The vertex.
        vertex: usize,
    },
    /// A face has fewer than three corners.
    #[error("face {face}: {corners} corners, a face needs at least 3")]
    FaceTooSmall {
        /// The face.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face}: vertex index {index} out of range ({vertices} vertices)")]
    IndexOutOfRange {
        /// The face.
        face: usize,
        /// The offending index.
        index: usize,
        /// Number of vertices of the mesh.
        vertices: usize,
    },
    /// A face visits the same vertex twice.
    #[error("face {face}: vertex {vertex} appears more than once")]
    RepeatedVertex {
        /// The face.
        face: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// An edge is shared by more than two faces.
    #[error("edge ({a}, {b}) is non-manifold: {faces} faces share it")]
    NonManifoldEdge {
        /// One end.
        a: usize,
        /// The other end.
        b: usize,
        /// Number of faces that contain the edge.
        faces: usize,
    },
    /// Two faces traverse an edge in the same direction (inconsistent orientation, or a face
    /// given twice).
    #[error("edge ({a}, {b}) is traversed in the same direction by two faces: inconsistent orientation or a duplicate face")]
    InconsistentOrientation {
        /// Start of the directed edge used twice.
        a: usize,
        /// End of the directed edge used twice.
        b: usize,
    },
    /// The faces around a vertex form more than one fan (a "bowtie" vertex).
    #[error("vertex {vertex} is non-manifold: its faces form more than one fan")]
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
    },
    /// A crease was tagged on a pair of vertices that is not an edge of the mesh.
    #[error("crease ({a}, {b}) is not an edge of the mesh")]
    CreaseNotAnEdge {
        /// One end.
        a: usize,
        /// The other end.
        b: usize,
    },
    /// A triangle-only scheme met a polygon that is not a triangle.
    #[error("{scheme}: face {face} has {corners} corners, the scheme needs triangles")]
    NotTriangular {
        /// The scheme's name.
        scheme: &'static str,
        /// The first non-triangular face.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// The output would be larger than the stated limit (or than 32-bit indices allow).
    #[error("{levels} levels would make {faces} faces, over the limit of {limit}")]
    TooLarge {
        /// Levels asked for.
        levels: u32,
        /// Faces the output would have (saturating at `u64::MAX`).
        faces: u64,
        /// The limit in force.
        limit: u64,
    },
    /// A mesh has more vertices or corners than 32-bit indices can address.
    #[error("{what}: {count} is more than 32-bit indices can address")]
    IndexOverflow {
        /// What overflowed ("vertices", "corners").
        what: &'static str,
        /// How many there were.
        count: usize,
    },
    /// No scheme is registered under that name.
    #[error("unknown subdivision scheme {name:?}; known: {known}")]
    UnknownScheme {
        /// The name asked for.
        name: String,
        /// The registered names, comma-separated.
        known: String,
    },
}

//! Mesh file formats of the workbench.
//!
//! Every reader parses a file into a [`RawMesh`] (positions, optional per-vertex normals,
//! shape tensors, colours and other properties, polygons, notes), and every writer writes one.
//! Validation and repair (non-manifold edges, orientation, degenerate faces) happen in the
//! `surface` crate, so a reader's only job is to read exactly what the file says, or to say
//! exactly where it cannot.

pub mod raw;

pub use raw::{Polygons, RawMesh, VertexProperties};

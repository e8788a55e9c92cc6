//! Triangle meshes as the workbench fits them: validated half-edge adjacency with per-vertex
//! data (position, normal, shape tensor), the repair of user files by stated and counted
//! rules, the working frame a user's mesh is fitted in, and the testbed's "semi-dstruct" `.m`
//! format read strictly.
//!
//! * [`vertex`] — [`VertexData`]: a point of the surface with its normal and second
//!   fundamental form;
//! * [`mesh`](mod@mesh) — [`Mesh`]: validated triangle meshes with half-edge adjacency, stable
//!   edge indices, vertex fans, walks;
//! * [`features`] — creases, darts and corners found from the geometry; [`sectors`] — data
//!   per sector of a vertex (per face corner), and the mesh cut open along its creases;
//! * [`repair`] — a file's raw mesh to a valid mesh by stated, counted rules;
//! * [`frame`] — the working frame of a user's mesh (unit bounding box), and the way back;
//! * [`analytic`] — points of analytic surfaces (sphere, torus) with exact normals and shape
//!   tensors;
//! * [`analytic_franke`] — Franke's six test functions with their derivatives, and their
//!   graphs as analytic surfaces; [`delaunay`] — planar Delaunay triangulation (the scattered
//!   Franke samplings);
//! * [`datasets`] — analytic reference surfaces with exact closest points and curvatures, and
//!   the named data sets sampled from them ([`dataset_by_name`]);
//! * [`testbed_format`] — the testbed's mesh format (Lounsbery et al. 1990, Figure 2), read and
//!   written strictly (a file must already be a valid mesh).
//!
//! This crate knows nothing of patches, curves or schemes: `estimate` computes normals and
//! shape tensors on it, `surface` fits patches to it, both on top of it.

pub mod analytic;
pub mod analytic_franke;
pub mod datasets;
pub mod delaunay;
pub mod disjoint;
mod edge_groups;
pub mod features;
pub mod frame;
pub mod mesh;
pub mod repair;
pub mod sectors;
pub mod testbed_format;
pub mod vertex;
mod vertex_pieces;
pub mod weld;

pub use datasets::{
    dataset_by_name, AnalyticSurface, Capsule, DataSet, DataSetError, Sphere, SurfacePoint, Torus,
    DATASET_NAMES,
};
pub use frame::{Frame, FrameError};
pub use mesh::{Edge, ExtraFields, Mesh, MeshError, Vertex, MAX_FACES, MAX_VERTICES};
pub use sectors::{SectorError, Sectors};
pub use testbed_format::{
    read_testbed, read_testbed_file, write_testbed, write_testbed_file, TestbedError,
};
pub use vertex::VertexData;

//! The testbed's other fitters: Loop and Catmull–Clark subdivision surfaces.
//!
//! A [`PolyMesh`] is a validated manifold polygon mesh (boundaries, several components and
//! isolated vertices allowed; non-manifold edges and vertices, repeated corners and bad indices
//! refused with a [`SubdivError`] naming the element) with its adjacency and crease tags. A
//! [`Subdivision`] scheme refines it one step at a time and gives the limit positions and
//! normals at its vertices; [`SCHEMES`] lists the schemes by name and [`subdivide`] runs
//! several levels under a face limit.
//!
//! | scheme | file | faces | rules |
//! |---|---|---|---|
//! | `loop`, `loop-warren` | [`loop_scheme`] | triangles | Loop's or Warren's β; boundary and crease curves `(1/8, 3/4, 1/8)`, sharp edge midpoints |
//! | `catmull-clark` | [`catmull_clark`] | any | centroid face points; boundary and crease curves `(1/8, 6/8, 1/8)`, sharp edge midpoints |
//!
//! Everything is `f64` with nalgebra points; every vertex of the input keeps its index through
//! a step, new vertices follow in the order each scheme documents.

pub mod bench_meshes;
pub mod catmull_clark;
pub mod error;
pub mod loop_scheme;
pub mod mesh;
pub mod scheme;
pub mod shapes;

pub use catmull_clark::CatmullClark;
pub use error::SubdivError;
pub use loop_scheme::{Loop, LoopWeights};
pub use mesh::{PolyMesh, VertexKind};
pub use scheme::{scheme_by_name, subdivide, SchemeEntry, Subdivision, DEFAULT_MAX_FACES, SCHEMES};

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
//!
//! # Checked against
//!
//! One and two steps match libigl 2.6.3 (`igl.loop`, Warren's β) and CGAL's
//! `Subdivision_method_3` (Loop with Loop's β, Catmull–Clark; through compas_cgal 0.10.0) to
//! 3.4·10⁻¹⁶ on closed and open meshes with valences 3–8 (`tests/suite/golden.rs`, data from
//! `scripts/golden_subdivision.py`). Both implementations use the same boundary rules as this
//! crate, valence-2 boundary corners included; neither has creases, so creases are tested
//! against their definition only.
//!
//! # Speed
//!
//! Three levels on about 10⁵ faces ([`bench_meshes`]), one thread, best estimate of criterion
//! against the best of three runs of the C++ call from Python (`--bench`), same machine, idle:
//!
//! | mesh | scheme | this crate | CGAL | libigl |
//! |---|---|---|---|---|
//! | torus-tri (100 352) | Loop | 1.11 s | 3.32 s | |
//! | torus-tri | Loop, Warren | 1.15 s | | 7.40 s |
//! | torus-tri | Catmull–Clark | 1.41 s | 3.64 s | |
//! | irregular-tri (98 094) | Loop | 1.40 s | 2.43 s | |
//! | irregular-tri | Loop, Warren | 1.41 s | | 5.88 s |
//! | irregular-tri | Catmull–Clark | 1.49 s | 3.99 s | |
//! | torus-quad (99 856) | Catmull–Clark | 1.75 s | 6.49 s | |

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

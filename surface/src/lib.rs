//! Surfaces: triangle meshes with adjacency and per-vertex data (position, normal, shape
//! tensor), the testbed's mesh format and OBJ, analytic data sets (sphere, ring, capsule, the
//! octahedron of the testbed's Figure 2), triangular Bézier patches, the modified
//! Shirman–Séquin split-domain scheme built on the boundary curves of the `curves` crate,
//! tessellation with differential geometry, and G1 measurement.
//!
//! This crate is the next layer of the workbench (issue 4) and holds no code yet; the curve
//! layer it builds on is complete in `curves`.

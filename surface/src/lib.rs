//! Surfaces on a mesh: triangular Bézier patches, the surface schemes with their per-face
//! fallback, the fit of a whole mesh, G1 and error measures, and tessellation with
//! differential geometry. The mesh itself (adjacency, repair, working frame, the `.m` format,
//! the analytic data sets) is the `mesh` crate's, re-exported here under the same paths
//! ([`mesh`](mod@mesh), [`repair`], [`frame`], [`testbed_format`], [`datasets`]).
//!
//! The files are grouped by the stage of the data flow they serve; every module keeps its path
//! at the crate root (`surface::g1`, `surface::beztri`, …):
//!
//! ```text
//! mesh ─► construct/ + scheme/ ─► fit/ ─► measure/ ─► tessellate/ ─► io/
//!         (patches of a face)    (a mesh)  (G1, errors) (triangles)   (patch files)
//! ```
//!
//! * `patch/` — what a patch is: [`beztri`] (triangular Bézier patches of any degree,
//!   [`BezierTriangle`]), the patch abstraction [`patch`] (any scheme evaluated with exact
//!   second derivatives), [`side_vertex`] (Nielson's side-vertex form);
//! * `construct/` — the constructions schemes are made of: [`shirman_sequin`] (the modified
//!   Shirman–Séquin split-domain macro-patch, G1 by construction; derivation in its docs) and
//!   [`fallback`] (the C0 macro-patch of a face a scheme cannot fit);
//! * [`scheme`] — surface schemes as a plug-in family ([`Scheme`], [`scheme::REGISTRY`]),
//!   one file a scheme, its parameters declared once;
//! * `fit/` — a whole mesh: [`fit`](mod@fit) (one curve per edge, shared; one macro-patch per
//!   face), [`stream`] (measured and written a window of faces at a time, without holding the
//!   nets), [`fairing`] (β and c chosen per triangle by thin-plate or membrane energy);
//! * `measure/` — [`g1`] (the testbed's `G1`: normal continuity and interpolation),
//!   [`patch_g1`] (the same for patches with no mesh, boundaries matched within a tolerance),
//!   [`metrics`] (errors against the true surface), [`interior`] (Section 4's corner
//!   measures), [`curve_stats`] (boundary-curve statistics), [`folds`] (faces whose surface
//!   turns over), [`sharp`] (kinks across smooth data, creases kept, flat regions kept flat);
//! * `tessellate/` — [`tessellate`](mod@tessellate) (the testbed's `Tess`: patches to one
//!   welded triangle mesh with position, normal, Gaussian and mean curvature),
//!   [`tessellate_fit`](mod@tessellate_fit) (a fitted mesh, welded by topology, in parallel),
//!   [`weld`] (the weld by position within a tolerance);
//! * `io/` — [`patch_io`] (patches as JSON Lines or the compact binary `.bzp`);
//! * [`limits`] — memory estimates and the limit checked before large allocations.
//!
//! Conventions (docs/conventions.md): normal curvature `κn(d) = dᵀ S d` is positive where the surface
//! bends towards its normal, so the unit sphere with outward normals has `κn = −1`, Gaussian
//! curvature `K = +1` and mean curvature `H = (κ1 + κ2)/2 = −1`.

// The mesh layer this crate builds on, re-exported under the paths it had here, so that
// `surface::Mesh`, `surface::repair` and `surface::frame` keep naming the same items.
pub use ::mesh::{analytic, datasets, frame, mesh, repair, testbed_format, vertex};

mod construct;
pub mod fit;
mod io;
pub mod limits;
mod measure;
pub mod patch;
pub mod scheme;
pub mod tessellate;

pub use construct::{curvature_cross, fallback, shirman_sequin, ss_variants};
pub use fit::{fairing, stream};
pub use io::patch_io;
pub use measure::{curve_stats, ends, folds, g1, interior, metrics, patch_g1, sharp};
pub use patch::{beztri, side_vertex};
pub use tessellate::{tessellate_fit, weld};

pub use ::mesh::datasets::{
    dataset_by_name, AnalyticSurface, Capsule, DataSet, DataSetError, Sphere, SurfacePoint, Torus,
    DATASET_NAMES,
};
pub use ::mesh::{
    read_testbed, read_testbed_file, write_testbed, write_testbed_file, TestbedError,
};
pub use ::mesh::{Edge, ExtraFields, Mesh, MeshError, Vertex};
pub use ::mesh::{Frame, FrameError, VertexData};
pub use beztri::{BezTriError, BezierCurve, BezierTriangle, Curvature, Derivatives};
pub use fit::{
    face_curves, fit, fit_into, fit_scheme, fit_scheme_into, DegenerateEdge, FaceFallback,
    FaceFallbackReason, Fit, FitError,
};
pub use g1::{measure as measure_g1, Boundary, G1Report};
pub use metrics::{compare as compare_with_truth, SurfaceErrors};
pub use scheme::{
    scheme_by_name, scheme_names, Continuity, Layout, Scheme, SchemeOptions, UnknownScheme,
    DEFAULT_SCHEME,
};
pub use shirman_sequin::{
    chiyokura_kimura, macro_patch, macro_patch_creased, CrossEnd, CrossFailure, InteriorParameters,
    QuarticNet, SchemeError,
};
pub use tessellate::{tessellate, TessError, Tessellation};
pub use tessellate_fit::{
    tessellate_fit, tessellate_fit_rebuilt, tessellate_fit_rebuilt_taking,
    tessellate_fit_rebuilt_with, welds_by_topology,
};

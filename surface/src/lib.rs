//! Surfaces on a mesh: triangular Bézier patches, the surface schemes with their per-face
//! fallback, the fit of a whole mesh, G1 and error measures, and tessellation with
//! differential geometry. The mesh itself (adjacency, repair, working frame, the `.m` format,
//! the analytic data sets) is the `mesh` crate's, re-exported here under the same paths
//! ([`mesh`](mod@mesh), [`repair`], [`frame`], [`testbed_format`], [`datasets`]).
//!
//! * [`fallback`] — the C0 macro-patch of a face the scheme cannot fit;
//! * [`beztri`] — triangular Bézier patches of any degree ([`BezierTriangle`]);
//! * [`scheme`] — surface schemes as a plug-in family ([`Scheme`], [`scheme::REGISTRY`]):
//!   `flat`, `shirman-sequin`, `pn-triangles`, `phong`, …;
//! * [`shirman_sequin`] — the modified Shirman–Séquin split-domain scheme: three quartic
//!   patches per triangle, G1 by construction (derivation in the module docs);
//! * [`fit`](mod@fit) — a whole mesh: one curve per edge (shared), one macro-patch per face;
//! * [`patch_io`] — a fit's patches written as JSON Lines or a compact binary form;
//! * [`stream`] — a fit measured and written a window of faces at a time, without holding its nets;
//! * [`metrics`] — errors of a tessellation against the true surface;
//! * [`fairing`] — thin-plate and membrane energies of a macro-patch in β and c, for optimizing
//!   the interior parameters;
//! * [`interior`] — Section 4's corner measures (interior-boundary curvature, twists);
//! * [`g1`] — the testbed's `G1`: measured normal continuity and interpolation;
//! * [`patch_g1`] — the same for a list of patches with no mesh, boundaries matched by
//!   position within a tolerance;
//! * [`tessellate`](mod@tessellate) — the testbed's `Tess`: patches to one welded triangle mesh carrying
//!   position, normal, Gaussian and mean curvature;
//! * [`tessellate_fit`](mod@tessellate_fit) — the same for a fitted mesh, welded by topology and
//!   in parallel;
//! * [`weld`] — the weld by position within a tolerance (tessellations, triangle soups);
//! * [`limits`] — memory estimates and the limit checked before large allocations.
//!
//! Conventions (docs/conventions.md): normal curvature `κn(d) = dᵀ S d` is positive where the surface
//! bends towards its normal, so the unit sphere with outward normals has `κn = −1`, Gaussian
//! curvature `K = +1` and mean curvature `H = (κ1 + κ2)/2 = −1`.

// The mesh layer this crate builds on, re-exported under the paths it had here, so that
// `surface::Mesh`, `surface::repair` and `surface::frame` keep naming the same items.
pub use ::mesh::{analytic, datasets, frame, mesh, repair, testbed_format, vertex};

pub mod beztri;
pub mod curve_stats;
pub mod fairing;
pub mod fallback;
pub mod fit;
pub mod g1;
pub mod interior;
pub mod limits;
pub mod metrics;
pub mod patch;
pub mod patch_g1;
pub mod patch_io;
pub mod scheme;
pub mod shirman_sequin;
pub mod side_vertex;
pub mod stream;
pub mod tessellate;
pub mod tessellate_fit;
pub mod weld;

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
    chiyokura_kimura, macro_patch, CrossEnd, CrossFailure, InteriorParameters, QuarticNet,
    SchemeError,
};
pub use tessellate::{tessellate, TessError, Tessellation};
pub use tessellate_fit::{tessellate_fit, tessellate_fit_rebuilt, welds_by_topology};

//! Jet fitting: Cazals & Pouget, *Estimating differential quantities using polynomial fitting
//! of osculating jets*, SGP 2003 (CAGD 22(2), 2005).
//!
//! At each vertex `v`:
//!
//! 1. **Frame.** `z` along a first normal estimate `n0`: the given normal, else the
//!    angle-weighted vertex normal ([`crate::normals`]); `x`, `y` an orthonormal tangent basis
//!    ([`crate::fit::tangent_basis`]). Cazals–Pouget use a PCA frame; the angle-weighted normal
//!    costs less and is as good a first estimate on a mesh (their §5.1 only needs the height
//!    function to be well defined over the neighbourhood).
//! 2. **Neighbourhood.** The vertex and its rings 1, 2, … added whole until there are at least
//!    [`POINTS_PER_COEFFICIENT`] times as many points as coefficients, at most [`MAX_RINGS`]
//!    rings and [`MAX_POINTS`] points. On a regular valence-6 mesh: degree 2 (6 coefficients,
//!    12 points) uses the 2-ring (19 points), degree 3 (10, 20) and degree 4 (15, 30) the
//!    3-ring (37 points).
//! 3. **Fit.** The jet `z(x, y) = Σ_{i+j ≤ d} c_ij xⁱ yʲ` (constant term included: the jet
//!    approximates, it does not interpolate the vertex) by least squares on coordinates scaled by
//!    the neighbourhood radius, solved by pivoted QR ([`crate::fit`]).
//! 4. **Differential quantities.** The normal from the jet's gradient at the origin (unless
//!    given), the shape tensor from the Weingarten map `I⁻¹ II` of the graph at the origin with
//!    the gradient terms included ([`crate::fit`] module docs), projected onto the output
//!    normal's tangent plane.
//!
//! **Fallbacks.** Fewer points than coefficients, rank deficiency or a condition number above
//! [`crate::fit::MAX_CONDITION`]: the next lower degree, down to 2
//! ([`FallbackKind::LowerDegree`]); when degree 2 fails too, `S = 0` with the first normal
//! ([`FallbackKind::Planar`]).
//!
//! **Order.** For a degree-`d` jet fitted to samples at spacing `h` Cazals–Pouget (Theorem 2)
//! show normal errors `O(h^d)` and curvature errors `O(h^{d−1})`; on the regular data sets of
//! the tests the symmetric neighbourhoods cancel a further order for even `d` (see
//! `tests/suite/jet.rs` for the measured orders).

use mesh::Mesh;
use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

use crate::fit::{fit_vertex, num_coeffs, FitFailure, FitSpec, RingRule, Workspace};
use crate::normals::{vertex_normals_with, NormalWeighting, Normals};
use crate::Topology;
use crate::{
    finish, finish_vertex, given_normal, project_shape, Estimate, Estimator, Fallback,
    FallbackKind, PlanarReason,
};

/// The neighbourhood has at least this many points per coefficient: twice as many equations as
/// unknowns, so that the fit averages rather than interpolates (Cazals–Pouget only require at
/// least as many).
pub const POINTS_PER_COEFFICIENT: usize = 2;

/// At most this many rings are added (a far-reaching neighbourhood no longer sees the local
/// shape; on a regular mesh degree 4 needs 3).
pub const MAX_RINGS: usize = 5;

/// At most this many points (the vertex included): bounds the work at high-valence vertices.
pub const MAX_POINTS: usize = 200;

/// A jet-fitting estimator of a fixed highest degree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Jet {
    /// Registered name.
    pub name: &'static str,
    /// One line for reports.
    pub description: &'static str,
    /// Degree of the jet (2, 3 or 4).
    pub degree: usize,
}

/// `jet`: the degree-2 jet on the adaptive neighbourhood (the 2-ring on a
/// regular mesh), chosen by the convergence tests (`tests/suite/jet.rs`). Degree 4 converges at
/// order 4 against degree 2's order 2 and wins from about 64×32 on the ring, but it needs the
/// 3-ring, costs three times as much, and loses on the coarse meshes this workbench
/// interpolates (K RMS on ring 16×8: jet2 1.7, jet4 6.9; sphere level 2: 0.75 against 0.96);
/// degree 3 is worse than degree 2 on both counts (odd degree, no symmetric cancellation).
pub static JET: Jet = Jet {
    name: "jet",
    description: "jet fitting (Cazals–Pouget 2003), recommended degree (2) on an adaptive k-ring",
    degree: 2,
};
/// Degree-2 jet.
pub static JET2: Jet = Jet {
    name: "jet2",
    description: "jet fitting (Cazals–Pouget 2003), degree 2 on an adaptive k-ring",
    degree: 2,
};
/// Degree-3 jet.
pub static JET3: Jet = Jet {
    name: "jet3",
    description: "jet fitting (Cazals–Pouget 2003), degree 3 on an adaptive k-ring",
    degree: 3,
};
/// Degree-4 jet.
pub static JET4: Jet = Jet {
    name: "jet4",
    description: "jet fitting (Cazals–Pouget 2003), degree 4 on an adaptive k-ring",
    degree: 4,
};

impl Jet {
    /// What [`Jet::estimate`] fits.
    pub(crate) fn spec(&self) -> FitSpec {
        FitSpec {
            degree: self.degree,
            constant: true,
            rule: RingRule {
                min_points: POINTS_PER_COEFFICIENT * num_coeffs(self.degree, true),
                max_rings: MAX_RINGS,
                max_points: MAX_POINTS,
            },
        }
    }
}

/// Per-vertex result of a fitting estimator: normal, shape, one optional fallback.
pub(crate) type VertexResult = (Vector3<f64>, Matrix3<f64>, Option<FallbackKind>);

/// The fit at one vertex (see [`estimate_by_fitting`]).
#[allow(clippy::too_many_arguments)]
fn fit_one(
    mesh: &Mesh,
    topo: &Topology,
    first: &[Vector3<f64>],
    given: Option<&[Vector3<f64>]>,
    spec: &FitSpec,
    use_fit_normal: bool,
    v: usize,
    ws: &mut Workspace,
) -> VertexResult {
    let n0 = first.get(v).copied().unwrap_or_else(Vector3::z);
    if topo.faces(v).is_empty() {
        // Isolated: recorded by the normals.
        return (n0, Matrix3::zeros(), None);
    }
    match fit_vertex(mesh, topo, v, &n0, spec, ws) {
        Ok(fit) => {
            let keep = !use_fit_normal || given_normal(given, v).is_some();
            let n = if keep { n0 } else { fit.normal };
            let fb = (fit.degree < spec.degree).then_some(FallbackKind::LowerDegree {
                from: spec.degree,
                to: fit.degree,
            });
            (n, project_shape(&fit.shape, &n), fb)
        }
        Err(e) => {
            let reason = match e {
                FitFailure::TooFewPoints => PlanarReason::TooFewNeighbours,
                FitFailure::IllConditioned => PlanarReason::IllConditioned,
            };
            (n0, Matrix3::zeros(), Some(FallbackKind::Planar { reason }))
        }
    }
}

/// The weighting of the first normals of the fitting estimators (when not given).
pub(crate) const FIRST_WEIGHTING: NormalWeighting = NormalWeighting::Angle;

/// The normal and tensor [`estimate_by_fitting`] (with the fitted normal) gives vertex `v`, if
/// it records no fallback of its own there (a lower degree, a planar or non-finite tensor);
/// `first` as `vertex_normals_with` under [`FIRST_WEIGHTING`] gives it. The same per-vertex steps, for estimators that want
/// the fit at some vertices only.
pub(crate) fn fit_at(
    mesh: &Mesh,
    topo: &Topology,
    first: &Normals,
    given: Option<&[Vector3<f64>]>,
    spec: &FitSpec,
    v: usize,
    ws: &mut Workspace,
) -> Option<(Vector3<f64>, Matrix3<f64>)> {
    let (mut n, mut s, fb) = fit_one(mesh, topo, &first.normals, given, spec, true, v, ws);
    let non_finite = finish_vertex(&mut n, &mut s, first.normals.get(v));
    (fb.is_none() && !non_finite).then_some((n, s))
}

/// Runs a local fit at every vertex (in parallel) and assembles the [`Estimate`].
/// `use_fit_normal`: output the fitted surface's normal where the normal is not given.
pub(crate) fn estimate_by_fitting(
    mesh: &Mesh,
    given: Option<&[Vector3<f64>]>,
    spec: FitSpec,
    use_fit_normal: bool,
) -> Estimate {
    let topo = Topology::new(mesh);
    let first = vertex_normals_with(mesh, &topo, FIRST_WEIGHTING, given);
    let nv = mesh.num_vertices();
    let mut normals = vec![Vector3::z(); nv];
    let mut shapes = vec![Matrix3::zeros(); nv];
    let fits: Vec<Fallback> = normals
        .par_iter_mut()
        .zip(shapes.par_iter_mut())
        .enumerate()
        .with_min_len(256)
        .map_init(Workspace::default, |ws, (v, (n_out, s_out))| {
            let (n, s, fb) = fit_one(
                mesh,
                &topo,
                &first.normals,
                given,
                &spec,
                use_fit_normal,
                v,
                ws,
            );
            *n_out = n;
            *s_out = s;
            fb.map(|kind| Fallback { vertex: v, kind })
        })
        .flatten()
        .collect();
    let mut fallbacks = first.fallbacks.clone();
    fallbacks.extend(fits);
    finish(normals, shapes, fallbacks, &first)
}

impl Estimator for Jet {
    fn name(&self) -> &'static str {
        self.name
    }

    fn description(&self) -> &'static str {
        self.description
    }

    fn estimate(&self, mesh: &Mesh, given: Option<&[Vector3<f64>]>) -> Estimate {
        estimate_by_fitting(mesh, given, self.spec(), true)
    }
}

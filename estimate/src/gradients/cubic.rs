//! `cubic`: the gradient and Hessian at a vertex of a weighted least-squares cubic through it —
//! the cubic nodal functions of Renka's modified Shepard method (Renka, *Multivariate
//! interpolation of large sets of scattered data*, ACM TOMS 14, 1988, for the quadratic form;
//! Renka and Brown, *Algorithm 790: CSHEP2D*, ACM TOMS 25, 1999, for the cubic one).
//!
//! # The rule
//!
//! At vertex `k` with xy position `q_k` and value `z_k`:
//!
//! 1. **Neighbours.** The vertex's rings are gathered ([`Topology::rings_into`]: at least
//!    `2 N + 1` vertices, at most [`GATHER_RINGS`] rings and [`GATHER_POINTS`] vertices) and the
//!    [`NEIGHBOURS`] `= N` nearest to `q_k` in the xy plane are kept (Renka and Brown's
//!    `N_c = 17`); vertices at the same xy point as `q_k` are skipped (they carry no slope).
//! 2. **Weights.** `wᵢ = ((R − dᵢ)₊ / (R dᵢ))²` with `dᵢ = |qᵢ − q_k|` and `R` the distance of the
//!    next-nearest gathered vertex (the first one left out), or `(1 + ` [`RADIUS_MARGIN`]`)`
//!    times the farthest kept one when there is none: Renka's inverse-distance weights, which
//!    vanish continuously at the radius of influence `R` and grow like `1/d²` near the vertex.
//! 3. **Fit.** The cubic `p(x, y) = z_k + Σ_{1 ≤ i+j ≤ 3} c_ij (x − x_k)ⁱ (y − y_k)ʲ`, which
//!    interpolates the vertex (nine coefficients), minimizing `Σ wᵢ (zᵢ − p(qᵢ))²`, on
//!    coordinates scaled by `R` and solved by the crate's pivoted least squares
//!    ([`crate::fit::fit_height`] with row weights).
//! 4. **Result.** `∇f(q_k) ≈ ∇p(q_k) = (c₁₀, c₀₁)`, Hessian `(2c₂₀, c₁₁, 2c₀₂)`.
//!
//! **Order.** The fit reproduces cubics exactly (the residual is zero), so for smooth `f` at
//! spacing `h` the error of `∇p` is `O(h³)` and of the Hessian `O(h²)` (Taylor's theorem on the
//! neighbourhood of radius `O(h)`; measured in `tests/suite/gradients.rs`).
//!
//! **Fallbacks.** Fewer than nine usable neighbours, or a rank-deficient or ill-conditioned
//! cubic system ([`crate::fit::MAX_CONDITION`]): the quadratic (five coefficients), then the
//! linear fit (two, no Hessian), each recorded as [`GradientFallback::LowerDegree`]; when even
//! that fails, the faces' mean linear gradient ([`GradientFallback::FaceGradients`]).

use mesh::Mesh;
use nalgebra::Vector2;
use rayon::prelude::*;

use super::{face_gradient_mean, GradientEstimator, GradientFallback, Gradients};
use crate::fit::{fit_height, Workspace};
use crate::Topology;

/// How many nearest neighbours the fit uses: Renka and Brown's `N_c` for the cubic nodal
/// functions (their recommendation from tests on Franke's data; nine are the minimum).
pub const NEIGHBOURS: usize = 17;

/// At most this many rings are searched for the neighbours (a regular triangulation has 18
/// vertices in two rings, so three give a choice of nearest ones).
pub const GATHER_RINGS: usize = 4;

/// At most this many candidates are gathered (bounds the work at high-valence vertices).
pub const GATHER_POINTS: usize = 96;

/// Where no gathered vertex lies beyond the kept ones, the radius of influence is this much
/// beyond the farthest kept neighbour, so that its weight is positive (Renka's `R` is "slightly
/// larger" than that distance).
pub const RADIUS_MARGIN: f64 = 0.1;

/// The degree of the nodal function.
pub const DEGREE: usize = 3;

/// The `cubic` gradient estimator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cubic;

/// The registered `cubic`.
pub static CUBIC: Cubic = Cubic;

impl GradientEstimator for Cubic {
    fn name(&self) -> &'static str {
        "cubic"
    }

    fn description(&self) -> &'static str {
        "weighted least-squares cubic through the vertex over its 17 nearest neighbours (Renka's nodal functions, 1988/1999)"
    }

    fn gradients(&self, mesh: &Mesh) -> Gradients {
        let topo = Topology::new(mesh);
        let n = mesh.num_vertices();
        type One = (Vector2<f64>, Option<[f64; 3]>, Option<GradientFallback>);
        let per: Vec<One> = (0..n)
            .into_par_iter()
            .with_min_len(256)
            .map_init(
                || (Workspace::default(), Vec::new()),
                |(ws, cand), v| at_vertex(mesh, &topo, v, ws, cand),
            )
            .collect();
        let mut out = Gradients {
            solver: "local (no global solve)".into(),
            ..Gradients::default()
        };
        for (v, (g, h, fb)) in per.into_iter().enumerate() {
            out.grad.push(g);
            out.hess.push(h);
            if let Some(fb) = fb {
                out.fallbacks.push((v, fb));
            }
        }
        out
    }
}

/// The rule at one vertex (module docs): gradient, Hessian (when the fit had degree ≥ 2) and
/// the fallback taken, if any.
fn at_vertex(
    mesh: &Mesh,
    topo: &Topology,
    v: usize,
    ws: &mut Workspace,
    cand: &mut Vec<(f64, usize)>,
) -> (Vector2<f64>, Option<[f64; 3]>, Option<GradientFallback>) {
    let verts = mesh.vertices();
    if topo.neighbours(v).is_empty() {
        return (Vector2::zeros(), None, Some(GradientFallback::Isolated));
    }
    let o = verts[v].data.p;
    topo.rings_into(
        v,
        2 * NEIGHBOURS + 1,
        GATHER_RINGS,
        GATHER_POINTS,
        &mut ws.ring,
    );
    cand.clear();
    for &u in ws.ring.iter().filter(|&&u| u != v) {
        let p = verts[u].data.p;
        let d = (p.x - o.x).hypot(p.y - o.y);
        if d > 0.0 && d.is_finite() && p.z.is_finite() {
            cand.push((d, u));
        }
    }
    cand.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let k = cand.len().min(NEIGHBOURS);
    let fallback = || {
        (
            face_gradient_mean(mesh, topo.faces(v)),
            None,
            Some(GradientFallback::FaceGradients),
        )
    };
    if k == 0 {
        return fallback();
    }
    let r = match cand.get(k) {
        Some(&(d, _)) if d > cand[k - 1].0 => d,
        _ => cand[k - 1].0 * (1.0 + RADIUS_MARGIN),
    };
    ws.local.clear();
    ws.weights.clear();
    for &(d, u) in &cand[..k] {
        let p = verts[u].data.p;
        ws.local
            .push([(p.x - o.x) / r, (p.y - o.y) / r, (p.z - o.z) / r]);
        // ((R − d)/(R d))², times R² to be free of units (a common factor changes nothing).
        let w = (r - d) / d;
        ws.weights.push(w * w);
    }
    for degree in (1..=DEGREE).rev() {
        if let Ok(der) = fit_height(ws, degree, false) {
            let grad = Vector2::new(der.grad[0], der.grad[1]);
            let hess = (degree >= 2).then(|| der.hess.map(|c| c / r));
            let ok = grad
                .iter()
                .chain(hess.iter().flatten())
                .all(|c| c.is_finite());
            if ok {
                let fb = (degree < DEGREE).then_some(GradientFallback::LowerDegree {
                    from: DEGREE,
                    to: degree,
                });
                return (grad, hess, fb);
            }
        }
    }
    fallback()
}

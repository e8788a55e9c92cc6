//! Gradients of functional data `z = f(x, y)`: estimators of `∇f` (and where the rule gives it,
//! the Hessian) at the vertices of a mesh whose `(x, y)` projection is a planar triangulation
//! and whose `z` are the values — the data of the functional Clough–Tocher and Powell–Sabin
//! interpolants (`surface::scheme::functional`).
//!
//! The estimators of the crate root ([`crate::Estimator`]) find normals of a surface in space
//! from positions alone, in frames of their own; on a height field the natural frame is the
//! fixed one, `z` up, and the classical scattered-data estimators work in it. Every rule is a
//! [`GradientEstimator`] registered in [`GRADIENT_ESTIMATORS`] ([`gradient_estimator_by_name`]),
//! one a file:
//!
//! * [`cubic`] — `cubic`: a weighted least-squares cubic through the vertex over its nearest
//!   neighbours (Renka's nodal functions: Renka 1988; Renka and Brown 1999), third order;
//! * [`minimum_norm`] — `minimum-norm`: the gradients of Nielson's minimum-norm network
//!   (Nielson 1983), the curve network of cubics along the edges of least total squared
//!   second derivative; scipy's `CloughTocher2DInterpolator` estimates its gradients so.
//!
//! [`apply_gradients`] writes the result into the mesh as the normals `(−f_x, −f_y, 1)/W` (and
//! shape tensors of the graph where a Hessian is known), which is how the functional schemes
//! read gradients (`Node::of` there: `∇f = (−n_x/n_z, −n_y/n_z)`).

pub mod cubic;
pub mod minimum_norm;

use mesh::Mesh;
use nalgebra::{Matrix3, Vector2, Vector3};

pub use cubic::{Cubic, CUBIC};
pub use minimum_norm::{MinimumNorm, MINIMUM_NORM};

use crate::fit::HeightDerivatives;

/// A way to estimate the gradients of functional data at the vertices.
pub trait GradientEstimator: Send + Sync {
    /// The registered name.
    fn name(&self) -> &'static str;

    /// One line for `--help` and reports.
    fn description(&self) -> &'static str;

    /// The gradient (and Hessian, where the rule has one) of the data at every vertex of `mesh`,
    /// read as `z = f(x, y)` at `(x, y)` of each vertex. Never panics; a vertex whose rule
    /// could not be applied gets a stated lower-order value, recorded in
    /// [`Gradients::fallbacks`].
    fn gradients(&self, mesh: &Mesh) -> Gradients;
}

/// Why a vertex got a lower-order gradient.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum GradientFallback {
    /// A lower degree than the rule's was fitted (too few neighbours, or their system was
    /// rank-deficient or ill-conditioned).
    LowerDegree {
        /// The degree asked for.
        from: usize,
        /// The degree used.
        to: usize,
    },
    /// No fit was possible: the area-weighted mean of the gradients of the vertex's faces (the
    /// piecewise-linear interpolant's), or zero when it has no face of positive xy area.
    FaceGradients,
    /// The vertex belongs to no edge: gradient zero.
    Isolated,
}

impl GradientFallback {
    /// A short stable label for summaries.
    pub fn label(&self) -> &'static str {
        match self {
            GradientFallback::LowerDegree { .. } => "lower_degree",
            GradientFallback::FaceGradients => "face_gradients",
            GradientFallback::Isolated => "isolated",
        }
    }
}

/// The result of a [`GradientEstimator`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Gradients {
    /// `∇f` per vertex, finite.
    pub grad: Vec<Vector2<f64>>,
    /// `(f_xx, f_xy, f_yy)` per vertex where the rule gives them.
    pub hess: Vec<Option<[f64; 3]>>,
    /// Every vertex that got a lower-order value, sorted by vertex.
    pub fallbacks: Vec<(usize, GradientFallback)>,
    /// What the rule's solver did, for reports (`"—"` for a local rule).
    pub solver: String,
}

/// Every registered gradient estimator.
pub static GRADIENT_ESTIMATORS: &[&dyn GradientEstimator] = &[&CUBIC, &MINIMUM_NORM];

/// A name that is not in [`GRADIENT_ESTIMATORS`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown gradient estimator `{name}` (known: {known})")]
pub struct UnknownGradientEstimator {
    /// The name asked for.
    pub name: String,
    /// The registered names, comma-separated.
    pub known: String,
}

/// Looks a gradient estimator up by name.
pub fn gradient_estimator_by_name(
    name: &str,
) -> Result<&'static dyn GradientEstimator, UnknownGradientEstimator> {
    GRADIENT_ESTIMATORS
        .iter()
        .copied()
        .find(|e| e.name() == name)
        .ok_or_else(|| UnknownGradientEstimator {
            name: name.to_string(),
            known: GRADIENT_ESTIMATORS
                .iter()
                .map(|e| e.name())
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// The unit upward normal of the graph with gradient `g`: `(−g_x, −g_y, 1)/√(1 + |g|²)` (the
/// tangent plane `z = z₀ + g · (q − q₀)` has the normal `(−g, 1)`).
pub fn graph_normal(g: &Vector2<f64>) -> Vector3<f64> {
    Vector3::new(-g.x, -g.y, 1.0) / (1.0 + g.norm_squared()).sqrt()
}

/// Writes `g` into `mesh`: every vertex's normal becomes [`graph_normal`] of its gradient; where
/// a Hessian is known the shape tensor is the graph's (the Monge patch over the fixed frame
/// `(x, y, z)`, [`HeightDerivatives::normal_and_shape`]) and the curvature is marked known,
/// elsewhere the tensor is zero and the curvature unknown. Vertices beyond `g` are untouched.
pub fn apply_gradients(mesh: &mut Mesh, g: &Gradients) {
    let (t1, t2, n0) = (Vector3::x(), Vector3::y(), Vector3::z());
    for (i, v) in mesh.vertices_mut().iter_mut().enumerate() {
        let Some(grad) = g.grad.get(i) else { break };
        v.data.n = graph_normal(grad);
        let hess = g.hess.get(i).copied().flatten();
        let shape = hess.and_then(|hess| {
            HeightDerivatives {
                grad: [grad.x, grad.y],
                hess,
            }
            .normal_and_shape(&t1, &t2, &n0)
        });
        match shape {
            Some((_, s)) => {
                v.data.shape = s;
                v.curvature_known = true;
            }
            None => {
                v.data.shape = Matrix3::zeros();
                v.curvature_known = false;
            }
        }
    }
}

/// The mean gradient of the linear interpolants of the faces `faces`, weighted by their xy
/// areas: the fallback of every rule ([`GradientFallback::FaceGradients`]); zero when no face
/// has positive xy area. On a face with corners `a, b, c`, `e₁ = b − a`, `e₂ = c − a` (xy) and
/// value differences `Δ₁ = z_b − z_a`, `Δ₂ = z_c − z_a`, the linear interpolant's gradient
/// solves `g · e₁ = Δ₁`, `g · e₂ = Δ₂`; by Cramer's rule with `D = e₁ₓ e₂ᵧ − e₁ᵧ e₂ₓ` (twice the
/// signed area) `g = ((Δ₁ e₂ᵧ − Δ₂ e₁ᵧ)/D, (Δ₂ e₁ₓ − Δ₁ e₂ₓ)/D)`.
pub(crate) fn face_gradient_mean(mesh: &Mesh, faces: &[u32]) -> Vector2<f64> {
    let verts = mesh.vertices();
    let mut sum = Vector2::zeros();
    let mut area = 0.0;
    for f in faces.iter().map(|&f| f as usize) {
        let Some(face) = mesh.faces().get(f) else {
            continue;
        };
        let p = face.map(|i| verts[i].data.p);
        let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
        let det = e1.x * e2.y - e1.y * e2.x;
        if !(det.abs() > 0.0 && det.is_finite()) {
            continue;
        }
        let (d1, d2) = (e1.z, e2.z);
        let g = Vector2::new(d1 * e2.y - d2 * e1.y, d2 * e1.x - d1 * e2.x) / det;
        let w = det.abs();
        if g.iter().all(|c| c.is_finite()) {
            sum += g * w;
            area += w;
        }
    }
    if area > 0.0 {
        sum / area
    } else {
        Vector2::zeros()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_names_are_unique_and_resolve() {
        for e in GRADIENT_ESTIMATORS {
            assert_eq!(
                gradient_estimator_by_name(e.name()).expect("found").name(),
                e.name()
            );
        }
        let Err(err) = gradient_estimator_by_name("nope") else {
            panic!("an unknown name resolved")
        };
        assert!(err.to_string().contains("cubic"), "{err}");
    }

    #[test]
    fn the_graph_normal_is_perpendicular_to_the_tangent_plane() {
        /// Three products and a square root: rounding only.
        const ROUNDING: f64 = 1e-15;
        let g = Vector2::new(0.7, -2.5);
        let n = graph_normal(&g);
        assert!((n.norm() - 1.0).abs() < ROUNDING);
        // Tangent vectors of z = g·q: (1, 0, g_x) and (0, 1, g_y).
        assert!(n.dot(&Vector3::new(1.0, 0.0, g.x)).abs() < ROUNDING);
        assert!(n.dot(&Vector3::new(0.0, 1.0, g.y)).abs() < ROUNDING);
        assert!(n.z > 0.0);
    }
}

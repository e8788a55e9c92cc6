//! `minimum-norm`: the gradients of Nielson's minimum-norm network (G. M. Nielson, *A method for
//! interpolating scattered data based upon a minimum norm network*, Math. Comp. 40, 1983) — the
//! gradients scipy's `CloughTocher2DInterpolator` estimates (its `estimate_gradients_2d_global`
//! runs Gauss–Seidel sweeps on the same minimum).
//!
//! # The functional
//!
//! Along an edge from `q_i` to `q_j` (xy), `e = q_j − q_i`, `L = |e|`, `Δ = z_j − z_i`, the cubic
//! Hermite curve `c(t)`, `t ∈ [0, 1]`, with `c(0) = z_i`, `c(1) = z_j`, `c'(0) = u = ∇f_i · e`,
//! `c'(1) = w = ∇f_j · e` has the linear second derivative with `c''(0) = 6Δ − 4u − 2w`,
//! `c''(1) = −6Δ + 2u + 4w`, and `∫₀¹ c''² dt = (a² + ab + b²)/3` for a linear function from `a`
//! to `b`, which expands to
//!
//! `I = 4(u² + uw + w²) − 12Δ(u + w) + 12Δ²`.
//!
//! In arc length `s = L t` the second derivative is `c''/L²`, so `∫ (d²c/ds²)² ds = I / L³`.
//! The network's energy is `E(∇f) = Σ_edges I_e / L_e³`, a convex quadratic in the `2V`
//! gradient components; its minimizer solves `A g = b` with, per edge,
//!
//! `∂E/∂∇f_i = (8u + 4w − 12Δ) e / L³`, `∂E/∂∇f_j = (4u + 8w − 12Δ) e / L³`,
//!
//! so `(A g)_i = Σ_e (8u + 4w) e / L³` and `b_i = Σ_e 12Δ e / L³`. `A` is symmetric positive
//! semidefinite, and definite on every vertex with two non-parallel edges (each edge's form
//! `4(u² + uw + w²)` is positive definite in `(u, w)`); a vertex of a triangle always has two.
//! Linear data `f = a + g·q` gives `u = w = Δ = g·e`, `c'' ≡ 0` and `E = 0`: the rule has linear
//! precision. It is not quadratic-precise (a network of cubics along edges does not carry a
//! quadratic's cross-edge information), and its gradients are second-order at best.
//!
//! # Solver
//!
//! Conjugate gradients on `A g = b`, preconditioned by the 2×2 diagonal blocks `Σ_e 8 e eᵀ/L³`
//! (Hestenes and Stiefel 1952; the block-Jacobi preconditioner keeps the method invariant to
//! a per-vertex choice of axes), to a relative residual of [`RELATIVE_RESIDUAL`] or at most
//! [`MAX_ITERATIONS`]; the iterations and residual reached are in [`Gradients::solver`].
//! Vertices on no edge are left out (gradient zero, [`GradientFallback::Isolated`]).

use mesh::Mesh;
use nalgebra::{Matrix2, Vector2};

use super::{GradientEstimator, GradientFallback, Gradients};

/// Conjugate gradients stop at this residual relative to `|b|`: ten digits, far below the
/// interpolation errors the gradients feed (scipy stops its Gauss–Seidel sweeps at a relative
/// change of 1e-6).
pub const RELATIVE_RESIDUAL: f64 = 1e-10;

/// At most this many conjugate-gradient iterations (per the system's size it is `min(2V,
/// this)`, in exact arithmetic `2V` suffice).
pub const MAX_ITERATIONS: usize = 20_000;

/// A preconditioner block whose determinant is below this times its squared trace has (nearly)
/// parallel edges only and is replaced by its trace (a ratio of `1e-12` is a condition number
/// of about `1e12`, where the 2×2 inverse has lost most digits).
pub const SINGULAR_BLOCK: f64 = 1e-12;

/// The `minimum-norm` gradient estimator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MinimumNorm;

/// The registered `minimum-norm`.
pub static MINIMUM_NORM: MinimumNorm = MinimumNorm;

/// One edge of the network: its ends, `e / L^{3/2}` (so that `e eᵀ / L³` is its outer product)
/// and `Δ / L^{3/2}`; with both scaled so, `u`, `w` and `Δ` of the module docs carry the factor
/// `L^{−3/2}` and `I` itself is the edge's `I / L³`.
struct Edge {
    i: usize,
    j: usize,
    e: Vector2<f64>,
    delta: f64,
}

impl Edge {
    /// `(A g)` contributions at `i` and `j` of this edge.
    fn apply(&self, g: &[Vector2<f64>]) -> (Vector2<f64>, Vector2<f64>) {
        let (u, w) = (g[self.i].dot(&self.e), g[self.j].dot(&self.e));
        (self.e * (8.0 * u + 4.0 * w), self.e * (4.0 * u + 8.0 * w))
    }
}

/// The network's edges with scaled data; edges of zero or non-finite xy length are dropped.
fn network(mesh: &Mesh) -> Vec<Edge> {
    let verts = mesh.vertices();
    mesh.edges()
        .filter_map(|edge| {
            let [i, j] = edge.vertices;
            let (p, q) = (verts[i].data.p, verts[j].data.p);
            let e = Vector2::new(q.x - p.x, q.y - p.y);
            let l = e.norm();
            let scale = l.powf(-1.5);
            let delta = q.z - p.z;
            (l > 0.0 && scale.is_finite() && delta.is_finite()).then(|| Edge {
                i,
                j,
                e: e * scale,
                delta: delta * scale,
            })
        })
        .collect()
}

/// `A g` (module docs).
fn product(edges: &[Edge], g: &[Vector2<f64>], out: &mut [Vector2<f64>]) {
    out.iter_mut().for_each(|o| *o = Vector2::zeros());
    for e in edges {
        let (a, b) = e.apply(g);
        out[e.i] += a;
        out[e.j] += b;
    }
}

/// The network's energy `E = Σ I_e / L_e³` at `g` (module docs), for tests and reports.
pub fn energy(mesh: &Mesh, g: &[Vector2<f64>]) -> f64 {
    network(mesh)
        .iter()
        .map(|e| {
            let (u, w) = (g[e.i].dot(&e.e), g[e.j].dot(&e.e));
            4.0 * (u * u + u * w + w * w) - 12.0 * e.delta * (u + w) + 12.0 * e.delta * e.delta
        })
        .sum()
}

impl GradientEstimator for MinimumNorm {
    fn name(&self) -> &'static str {
        "minimum-norm"
    }

    fn description(&self) -> &'static str {
        "gradients of Nielson's minimum-norm network of edge cubics (1983; scipy's CloughTocher2DInterpolator estimate)"
    }

    fn gradients(&self, mesh: &Mesh) -> Gradients {
        let n = mesh.num_vertices();
        let edges = network(mesh);
        // Right-hand side and the block-diagonal preconditioner.
        let mut b = vec![Vector2::zeros(); n];
        let mut block = vec![Matrix2::zeros(); n];
        for e in &edges {
            let r = e.e * (12.0 * e.delta);
            b[e.i] += r;
            b[e.j] += r;
            let outer = e.e * e.e.transpose() * 8.0;
            block[e.i] += outer;
            block[e.j] += outer;
        }
        // Vertices on no edge stay at zero; a singular block (all edges parallel, not possible
        // on a triangle) is preconditioned by its trace.
        let inverse: Vec<Option<Matrix2<f64>>> = block
            .iter()
            .map(|m| {
                let t = m.trace();
                (t > 0.0).then(|| {
                    m.try_inverse()
                        .filter(|inv| {
                            inv.iter().all(|c| c.is_finite())
                                && m.determinant() > SINGULAR_BLOCK * t * t
                        })
                        .unwrap_or_else(|| Matrix2::identity() / t)
                })
            })
            .collect();
        let precondition = |r: &[Vector2<f64>], z: &mut [Vector2<f64>]| {
            for ((z, r), inv) in z.iter_mut().zip(r).zip(&inverse) {
                *z = inv.map_or_else(Vector2::zeros, |m| m * r);
            }
        };
        let dot = |x: &[Vector2<f64>], y: &[Vector2<f64>]| -> f64 {
            x.iter().zip(y).map(|(a, b)| a.dot(b)).sum()
        };
        let norm_b = dot(&b, &b).sqrt();
        let mut g = vec![Vector2::zeros(); n];
        let mut iterations = 0;
        let mut relative = 0.0;
        if norm_b > 0.0 && norm_b.is_finite() {
            // Preconditioned conjugate gradients from g = 0 (Golub and Van Loan, Alg. 11.5.1).
            let mut r = b.clone();
            let mut z = vec![Vector2::zeros(); n];
            precondition(&r, &mut z);
            let mut p = z.clone();
            let mut ap = vec![Vector2::zeros(); n];
            let mut rz = dot(&r, &z);
            let limit = MAX_ITERATIONS.min(2 * n + 10);
            relative = 1.0;
            while iterations < limit && relative > RELATIVE_RESIDUAL {
                product(&edges, &p, &mut ap);
                let pap = dot(&p, &ap);
                if !(pap > 0.0 && pap.is_finite()) {
                    break;
                }
                let alpha = rz / pap;
                for k in 0..n {
                    g[k] += p[k] * alpha;
                    r[k] -= ap[k] * alpha;
                }
                precondition(&r, &mut z);
                let rz_next = dot(&r, &z);
                let beta = rz_next / rz;
                rz = rz_next;
                for k in 0..n {
                    p[k] = z[k] + p[k] * beta;
                }
                iterations += 1;
                relative = dot(&r, &r).sqrt() / norm_b;
            }
        }
        let mut fallbacks = Vec::new();
        for (v, inv) in inverse.iter().enumerate() {
            if inv.is_none() {
                fallbacks.push((v, GradientFallback::Isolated));
            }
        }
        if g.iter().any(|x| !x.iter().all(|c| c.is_finite())) {
            // Not expected: the system is finite and definite. Never hand out a NaN.
            let topo = crate::Topology::new(mesh);
            for (v, x) in g.iter_mut().enumerate() {
                if !x.iter().all(|c| c.is_finite()) {
                    *x = super::face_gradient_mean(mesh, topo.faces(v));
                    fallbacks.push((v, GradientFallback::FaceGradients));
                }
            }
            fallbacks.sort();
        }
        Gradients {
            hess: vec![None; n],
            grad: g,
            fallbacks,
            solver: format!(
                "preconditioned conjugate gradients: {iterations} iterations, relative residual {relative:.1e}"
            ),
        }
    }
}

//! The functional Clough–Tocher interpolant (Clough and Tocher 1965, in the Bézier form of
//! Farin, *Triangular Bernstein–Bézier patches*, CAGD 3 (1986), and of Farin, *A modified
//! Clough–Tocher interpolant*, CAGD 2 (1985)): three cubics per face over the centroid split,
//! C1 across every edge of the triangulation, from values and gradients at the vertices.
//!
//! # Construction
//!
//! Face `(V_0, V_1, V_2)` in xy with values `f_i` and gradients `g_i` ([`super::Node`]), `S` the
//! centroid, sub-triangle `e` over `(V_e, V_{e+1}, S)` with the net of
//! [`crate::scheme::clough_tocher`] (row 0 the edge `V_a, E¹, E², V_b`, row 1 `I¹_a, C_e, I¹_b`,
//! row 2 `I²_a, I²_b`, row 3 `S`). The ordinates:
//!
//! * **boundary** (the cubic Hermite interpolant of `f` along the straight edge): `E¹` over
//!   `V_a + d/3` with ordinate `f_a + g_a · d/3`, `E²` over `V_b − d/3` with `f_b − g_b · d/3`,
//!   `d = V_b − V_a`. It depends on the edge's two vertices only: both faces on an edge share it
//!   (C0), and along the edge the tangential derivative is shared too;
//! * **vertex rule**: `I¹_i` over `V_i + (S − V_i)/3` with `f_i + g_i · (S − V_i)/3`, i.e. on the
//!   tangent plane at `V_i`, like `E¹`, `E²` there — the parametric rule
//!   `I¹_i = (V_i + E¹_i + E²_{i−1})/3` gives exactly this point (the domain points combine the
//!   same way), so every sub-patch has the gradient `g_i` at `V_i`;
//! * **cross-boundary points**: the derivative of sub-patch `e` along the edge's unit normal
//!   `ν` (into the face) is a quadratic along the edge whose end values `g_a · ν`, `g_b · ν` are
//!   shared data. Requiring it to be **linear** makes it the same function for both faces (the
//!   neighbour's is `−` it, along `−ν`), and with the shared tangential derivative the whole
//!   gradient is continuous across the edge: **C1 across edges**. With `H` the foot of the
//!   perpendicular from `S` on the edge, `H = (1 − τ) V_a + τ V_b`,
//!   `τ = (S − V_a) · d / |d|²`, the derivative along `S − H` (a positive multiple of `ν`) is
//!   the quadratic `D_m = 3(b_{1,m} − (1 − τ) b_{0,m} − τ b_{0,m+1})`, and linear means
//!   `D_1 = (D_0 + D_2)/2`: [`crate::scheme::clough_tocher::cross_boundary_point_along`] at this
//!   `τ`. (The parametric scheme uses the median, `τ = ½`: the derivative along `S − M_e` is
//!   then linear, but that direction differs between the two faces unless the median is
//!   perpendicular, which is why it is only C0 across edges.) The xy parts of these rules are
//!   the domain points `(V_a + V_b + S)/3` themselves (`D_0 = D_2 = S − H` in xy);
//! * **C1 inside** (the classical rules, derived in [`crate::scheme::clough_tocher`]):
//!   `I²_i = (I¹_i + C_i + C_{i−1})/3`, `S = (I²_0 + I²_1 + I²_2)/3`.
//!
//! # Precision
//!
//! Linear and **quadratic precision**: for a quadratic `f` with exact gradients the Hermite
//! boundary, the tangent-plane points and the (linear) normal derivative are those of `f`
//! raised to degree 3, and `f` satisfies every C1 rule: the interpolant is `f` (tested). Not
//! cubic precision: a cubic's normal derivative along an edge is quadratic, not linear, in
//! general (tested: `f = x²y` on a grid with diagonals is not reproduced).
//!
//! # Farin's modification, and why the classical rule is implemented
//!
//! The one freedom per edge and side, `C_e`, is tied across the edge by one linear C1 condition
//! (the neighbour's `C'_e` is an affine combination of `E¹`, `E²` and `C_e` with the barycentric
//! coordinates of its split point), leaving one degree of freedom per *edge*. The classical rule
//! spends it on "normal derivative linear", which uses only the edge's data. Farin (1985)
//! spends it instead so that the interpolant gets **cubic precision**: the data of one triangle
//! cannot fix a cubic (the bubble `λ_0 λ_1 λ_2` has zero value and gradient at every vertex),
//! so the choice uses both triangles on the edge, the free pair chosen by least squares (as
//! restated in ../shared/testbed-sources.md: "the cross-boundary freedom chosen by least
//! squares (Farin 1985)"); for data from a global cubic the least-squares solution is the cubic
//! itself. This workbench's [`crate::scheme::FaceInput`] gives a scheme one face, and Farin's
//! paper was not available to check the exact objective, so the classical, local rule is
//! implemented and the difference stated: same degree, split and C1 rules, quadratic instead
//! of cubic precision.

use nalgebra::{Point3, Vector2};

use super::Node;
use crate::fit::FaceFallbackReason;
use crate::scheme::clough_tocher::{fallback_patch, macro_patch_along};
use crate::scheme::{Continuity, FaceInput, Layout, Scheme, CENTROID_SPLIT};

/// Control points per cubic net.
const NP: usize = 10;

/// The functional Clough–Tocher scheme (module docs); registered as `clough-tocher`'s
/// functional form ([`crate::scheme::Scheme::on_height_field`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct FunctionalCloughTocher;

/// The Hermite boundary cubic of `f` from node `a` to node `b` (module docs), computed in the
/// edge's canonical orientation (its end with the smaller `(x, y)` first) so that both faces on
/// the edge get the same points to the bit.
pub fn boundary(a: &Node, b: &Node) -> [Point3<f64>; 4] {
    if (a.xy.x, a.xy.y) > (b.xy.x, b.xy.y) {
        let [p0, p1, p2, p3] = boundary(b, a);
        return [p3, p2, p1, p0];
    }
    let d = b.xy - a.xy;
    [
        a.point(),
        a.tangent(&(a.xy + d / 3.0)),
        b.tangent(&(b.xy - d / 3.0)),
        b.point(),
    ]
}

/// The foot parameter `τ` of the perpendicular from `s` on the line `a → b`.
pub fn foot(a: &Vector2<f64>, b: &Vector2<f64>, s: &Vector2<f64>) -> f64 {
    let d = b - a;
    (s - a).dot(&d) / d.norm_squared()
}

/// The three cubic nets of the face with corner data `nodes` (module docs), in the order of
/// [`CENTROID_SPLIT`].
pub fn macro_patch(nodes: &[Node; 3]) -> [[Point3<f64>; NP]; 3] {
    let curves: [[Point3<f64>; 4]; 3] =
        std::array::from_fn(|e| boundary(&nodes[e], &nodes[(e + 1) % 3]));
    let s = (nodes[0].xy + nodes[1].xy + nodes[2].xy) / 3.0;
    let taus = std::array::from_fn(|e| foot(&nodes[e].xy, &nodes[(e + 1) % 3].xy, &s));
    macro_patch_along(&curves, taus)
}

/// The corner data of a face, with a gradient of zero where a normal does not point up (only
/// for the fallback: [`super::detect`] admits no such data).
fn nodes_or_flat(input: &FaceInput<'_>) -> [Node; 3] {
    input.vertices.map(|v| {
        Node::of(v).unwrap_or(Node {
            xy: Vector2::new(v.p.x, v.p.y),
            z: v.p.z,
            grad: Vector2::zeros(),
        })
    })
}

impl Scheme for FunctionalCloughTocher {
    fn name(&self) -> &'static str {
        "clough-tocher"
    }

    fn layout(&self) -> Layout {
        Layout::bezier(3, &CENTROID_SPLIT)
    }

    /// C1 across every edge and inside each face (module docs).
    fn continuity(&self) -> Continuity {
        Continuity::C1
    }

    fn uses_curves(&self) -> bool {
        false
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        let mut nodes = [Node {
            xy: Vector2::zeros(),
            z: 0.0,
            grad: Vector2::zeros(),
        }; 3];
        for (corner, (slot, v)) in nodes.iter_mut().zip(input.vertices).enumerate() {
            *slot = Node::of(v).ok_or(FaceFallbackReason::Folded { corner })?;
        }
        let nets = macro_patch(&nodes);
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
        Ok(())
    }

    /// C0 on the shared Hermite boundaries ([`fallback_patch`] on them).
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        let nodes = nodes_or_flat(input);
        let curves: [[Point3<f64>; 4]; 3] =
            std::array::from_fn(|e| boundary(&nodes[e], &nodes[(e + 1) % 3]));
        let nets = fallback_patch(&curves);
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
    }
}

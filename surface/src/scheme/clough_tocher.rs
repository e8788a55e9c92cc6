//! `clough-tocher`: the parametric split-domain cubic scheme, three cubic Bézier triangles per
//! face over the centroid split, on the shared cubic edge curves (the testbed seed's
//! Clough–Tocher fitter; Farin, *A modified Clough–Tocher interpolant*, CAGD 2 (1985) 19–27).
//!
//! # Notation
//!
//! Face `(V_0, V_1, V_2)`, exterior edge `e` from `V_e` to `V_{e+1}` carrying the shared cubic
//! `V_e, E¹_e, E²_e, V_{e+1}` (indices mod 3), split point `S` over the centroid. Sub-patch `e` is
//! the cubic over `(V_e, V_{e+1}, S)`; in the row order of docs/conventions.md (`a = e`,
//! `b = e + 1`):
//!
//! ```text
//! row 0:  V_a    E¹_e   E²_e   V_b      (the exterior cubic itself)
//! row 1:  I¹_a   C_e    I¹_b
//! row 2:  I²_a   I²_b
//! row 3:  S
//! ```
//!
//! The interior boundary from `V_i` to `S` is the cubic `V_i, I¹_i, I²_i, S`, shared by
//! sub-patches `i` and `i − 1`. The only points not fixed by C1 conditions are the three
//! cross-boundary points `C_e` (one per edge).
//!
//! # C1 inside the face
//!
//! In the centroid split `V_{i+1} = −V_{i−1} − V_i + 3S` (barycentric coordinates of the domain
//! point `V_{i+1}` in the sub-triangle `(V_{i−1}, V_i, S)`). The C1 condition across the interior
//! boundary `V_i → S` between sub-patch `L = i` and `R = i − 1` says that every point of `L` one
//! step off the boundary is the blossom of `R` with one argument `(−1, −1, 3)`: with boundary
//! points `P_0 … P_3 = V_i, I¹_i, I²_i, S` and `R`'s points one step off the other side,
//!
//! * `m = 0`: `E¹_i = −E²_{i−1} − V_i + 3I¹_i`, so `I¹_i = (V_i + E¹_i + E²_{i−1})/3`;
//! * `m = 1`: `C_i = −C_{i−1} − I¹_i + 3I²_i`, so `I²_i = (I¹_i + C_i + C_{i−1})/3`;
//! * `m = 2`: `I²_{i+1} = −I²_{i−1} − I²_i + 3S`, so `S = (I²_0 + I²_1 + I²_2)/3`.
//!
//! These are the classical Clough–Tocher rules; for any choice of the `C_e` the macro-patch is
//! C1 inside (so G1 wherever its partials are independent: measured below 1e-9 rad).
//!
//! # The cross-boundary points, and why the claim across mesh edges is C0
//!
//! The derivative of sub-patch `e` along the domain median from the edge midpoint to `S`
//! (barycentric direction `(−½, −½, 1)`) is the quadratic `D(t) = Σ B²_m(t) D_m` with
//! `D_0 = 3(I¹_a − (V_a + E¹)/2)`, `D_1 = 3(C_e − (E¹ + E²)/2)`, `D_2 = 3(I¹_b − (E² + V_b)/2)`;
//! the edge curve's derivative is `B'(t) = Σ B²_m(t) B'_m` with `B'_0 = 3(E¹ − V_a)`,
//! `B'_1 = 3(E² − E¹)`, `B'_2 = 3(V_b − E²)`. `D_0` and `D_2` are fixed by the vertex rule and
//! lie in the tangent planes (the curve layer builds the curves' end tangents in them, so
//! `I¹`, `E¹`, `E²` of a corner lie in its tangent plane): every sub-patch has the data normal
//! at the data vertices, so the surface is G1 at the vertices. `D_1`, i.e. `C_e`, is free.
//!
//! The classical rule makes the median derivative linear (degree-reduced),
//! `D_1 = (D_0 + D_2)/2`:
//!
//! ```text
//! C_e = (E¹ + E²)/2 + [(I¹_a − (V_a + E¹)/2) + (I¹_b − (E² + V_b)/2)]/2
//! ```
//!
//! It uses the face's other edges (through `I¹_a`, `I¹_b`), which the neighbour does not share,
//! so the normal `B'(t) × D(t)` differs between the two faces inside the edge.
//!
//! Could the one free point per edge and side buy G1 instead? Both faces are tangent-plane
//! continuous along the edge if a field `n(t)` built from shared data only has `n·B' ≡ 0` and
//! `n·D ≡ 0` for each face's `D`. The curve layer's curves are planar (the plane through both
//! ends containing `n_a + n_b`, unit normal `w`), and the quadratic fields orthogonal to `B'`
//! with `n(0) ∥ n_a`, `n(1) ∥ n_b` are exactly `n = Σ B²_m (w × B'_m + β_m w)` with `β_0, β_2`
//! fixed by the end normals and `β_1` free (a tilt of the field out of the curve plane in the
//! middle of the edge). `n·D` is then a quartic whose end coefficients vanish by the vertex
//! rule, and whose middle three, `n_0·D_1 = −n_1·D_0`, `n_1·D_1 = −(n_0·D_2 + n_2·D_0)/4`,
//! `n_2·D_1 = −n_1·D_2`, are three linear equations for `D_1`, with determinant
//! `β_0 [B'_1, B'_2] − β_1 [B'_0, B'_2] + β_2 [B'_0, B'_1]` (2D cross products in the curve
//! plane). So a G1 cubic Clough–Tocher surface exists for every shared `β_1` making this
//! non-zero — but it is not a usable scheme:
//!
//! * where the normals are coplanar with the chord (every edge of a sphere or a surface of
//!   revolution along a meridian) `β_0 = β_2 = 0`, the field lies in the curve plane for
//!   `β_1 = 0`, and the system is singular (its rows are all orthogonal to `w`). For
//!   `β_1 ≠ 0` the outer equations fix the in-plane part of `D_1` and the middle one gives
//!   `β_1 (w·D_1) = −(n_0·D_2 + n_2·D_0)/4 − (w × B'_1)·D_1`: the component of `D_1` along
//!   `w` — the cross-boundary magnitude itself — is set by the shared tilt `β_1`, not by the
//!   face;
//! * a shared `β_1` fits at most one of the two faces: each face's natural magnitude `w·D_1`
//!   asks for its own `β_1`. For two faces mirror-symmetric about the curve plane the right
//!   sides are equal and the magnitudes opposite, so the two asks have opposite signs: one
//!   `β_1` satisfies both only where that right side vanishes.
//!
//! (With `β_1 = (β_0 + β_2)/2` the system is singular on every edge of the sphere data set,
//! whose radial normals are coplanar with every chord; this was tried and measured: 4.7e-4 rad
//! at the edge midpoints with the singular part dropped.) The claim is therefore
//! [`Continuity::C0`] across mesh edges, with G1 at the vertices and C1 inside each face; the
//! jump is measured and reported. This is why Shirman–Séquin go to quartics: there the
//! Chiyokura–Kimura field gives each side its own magnitude `K(t)` along a shared direction
//! field `Ĉ(t)`, which a quadratic cross-boundary derivative cannot carry.
//!
//! Linear precision: for planar data the chord curves are straight at thirds and every rule
//! above is affine, so the macro-patch is the flat triangle (tested).
//!
//! # Where the sources are ambiguous, and how it was settled
//!
//! * Farin (1985) modifies Clough–Tocher for *functions*: the free cross-boundary ordinate is
//!   chosen to minimize the C2 discontinuity across the mesh edge against the neighbouring
//!   face's quadratic-precision patch (the testbed's implementation does this on `z` values in
//!   a fixed frame). That needs the neighbouring face's data, which a scheme does not get
//!   ([`FaceInput`] holds one face), and has no frame-free meaning for a parametric surface.
//!   It is replaced by the classical linear cross-boundary rule, as the brief allows: what is
//!   Farin's here is the split, the C1 rules inside and the cubic degree, not his choice of
//!   the free point.
//! * "Linear cross-boundary derivative" depends on the transversal direction when the edge
//!   curve is not a raised quadratic (two directions differ by a multiple of `B'(t)`). The
//!   functional scheme uses the edge normal of the planar domain; a parametric domain has no
//!   metric, so the median direction is used: symmetric in the edge's two ends and affine
//!   invariant.
//!
//! # On height fields
//!
//! On data `z = f(x, y)` (detected by the fit, or asked for with `fit --heightfield`) the fit
//! uses this scheme's functional form instead ([`Scheme::on_height_field`]:
//! [`super::functional::clough_tocher`]), which is C1 across every edge and claims
//! [`Continuity::C1`]; what is said above is the parametric scheme on any other data.

use nalgebra::{Point3, Vector3};

use super::{Continuity, FaceInput, Layout, Scheme, CENTROID_SPLIT};
use crate::fit::FaceFallbackReason;

/// The parametric Clough–Tocher scheme (module docs); on height fields its functional form,
/// whose cross-boundary rule blends in the least-squares cubic by [`CUBIC_WEIGHT`].
#[derive(Clone, Copy, Debug, Default)]
pub struct CloughTocher {
    /// [`CUBIC_WEIGHT`]'s value (read only by the functional form).
    pub cubic_weight: f64,
}

/// The weight `w` of the least-squares cubic in the functional form's cross-boundary
/// derivatives ([`super::functional::clough_tocher`], "Cubic precision"): 0 the classical
/// linear normal derivative, 1 cubic precision on interior edges.
pub const CUBIC_WEIGHT: super::ParameterSpec = super::ParameterSpec {
    name: "ct-cubic",
    symbol: "w",
    default: 0.0,
    range: (0.0, 1.0),
    range_reason: "a blend of two cross-boundary derivatives: 0 the classical linear one, 1 the least-squares cubic's",
    summary: "on height fields, `clough-tocher`'s cross-boundary normal derivative at edge midpoints: (1 − w) the classical linear rule + w the least-squares cubic of the edge's two faces (cubic precision at 1)",
};

/// The scheme's parameters.
pub const PARAMETERS: &[super::ParameterSpec] = &[CUBIC_WEIGHT];

/// Control points per cubic net.
const NP: usize = 10;

fn comb(terms: &[(f64, &Point3<f64>)]) -> Point3<f64> {
    Point3::from(
        terms
            .iter()
            .fold(Vector3::zeros(), |s, (w, p)| s + p.coords * *w),
    )
}

/// The cross-boundary point `C_e` of an edge with curve `V_a, E¹, E², V_b` and this face's
/// corner points `I¹_a`, `I¹_b`: the median derivative made linear (module docs).
pub fn cross_boundary_point(
    curve: &[Point3<f64>; 4],
    i1a: &Point3<f64>,
    i1b: &Point3<f64>,
) -> Point3<f64> {
    cross_boundary_point_along(curve, i1a, i1b, 0.5)
}

/// The cross-boundary point `C_e` that makes the derivative of sub-patch `e` along the domain
/// direction from `H = (1 − τ) V_a + τ V_b` to `S` linear along the edge. That derivative is the
/// quadratic with Bézier coefficients `D_m = 3(b_{1,m} − (1 − τ) b_{0,m} − τ b_{0,m+1})` (row 1
/// `I¹_a, C_e, I¹_b`, row 0 the edge curve), so linear means `D_1 = (D_0 + D_2)/2`:
///
/// ```text
/// C_e = (1 − τ) E¹ + τ E² + ½ [(I¹_a − (1 − τ) V_a − τ E¹) + (I¹_b − (1 − τ) E² − τ V_b)]
/// ```
///
/// `τ = ½` is the median rule of the parametric scheme; the functional scheme takes the foot of
/// the perpendicular from `S`, so that the *normal* derivative is linear
/// ([`super::functional::clough_tocher`]).
pub fn cross_boundary_point_along(
    curve: &[Point3<f64>; 4],
    i1a: &Point3<f64>,
    i1b: &Point3<f64>,
    tau: f64,
) -> Point3<f64> {
    let [va, e1, e2, vb] = curve;
    let s = 1.0 - tau;
    comb(&[
        (s - 0.5 * tau, e1),
        (tau - 0.5 * s, e2),
        (0.5, i1a),
        (0.5, i1b),
        (-0.5 * s, va),
        (-0.5 * tau, vb),
    ])
}

/// The three cubic nets of one face from its oriented edge curves `curves[e]`
/// (`V_e → V_{e+1}`), in the order of the layout.
pub fn macro_patch(curves: &[[Point3<f64>; 4]; 3]) -> [[Point3<f64>; NP]; 3] {
    macro_patch_along(curves, [0.5; 3])
}

/// [`macro_patch`] with the cross-boundary point of edge `e` from
/// [`cross_boundary_point_along`] at `taus[e]`; the C1 rules inside the face are the same.
pub fn macro_patch_along(curves: &[[Point3<f64>; 4]; 3], taus: [f64; 3]) -> [[Point3<f64>; NP]; 3] {
    macro_patch_with(curves, |e, i1a, i1b| {
        cross_boundary_point_along(&curves[e], i1a, i1b, taus[e])
    })
}

/// [`macro_patch`] with the cross-boundary point of edge `e` given by `cross(e, I¹_a, I¹_b)`;
/// the vertex rule and the C1 rules inside the face are the same.
pub fn macro_patch_with(
    curves: &[[Point3<f64>; 4]; 3],
    cross: impl Fn(usize, &Point3<f64>, &Point3<f64>) -> Point3<f64>,
) -> [[Point3<f64>; NP]; 3] {
    let prev = |i: usize| (i + 2) % 3;
    let next = |i: usize| (i + 1) % 3;
    let v: [Point3<f64>; 3] = std::array::from_fn(|i| curves[i][0]);
    let i1: [Point3<f64>; 3] = std::array::from_fn(|i| {
        comb(&[
            (1.0 / 3.0, &v[i]),
            (1.0 / 3.0, &curves[i][1]),
            (1.0 / 3.0, &curves[prev(i)][2]),
        ])
    });
    let c: [Point3<f64>; 3] = std::array::from_fn(|e| cross(e, &i1[e], &i1[next(e)]));
    let i2: [Point3<f64>; 3] = std::array::from_fn(|i| {
        comb(&[
            (1.0 / 3.0, &i1[i]),
            (1.0 / 3.0, &c[i]),
            (1.0 / 3.0, &c[prev(i)]),
        ])
    });
    let s = comb(&[
        (1.0 / 3.0, &i2[0]),
        (1.0 / 3.0, &i2[1]),
        (1.0 / 3.0, &i2[2]),
    ]);
    std::array::from_fn(|e| {
        let (a, b) = (e, next(e));
        let q = &curves[e];
        [q[0], q[1], q[2], q[3], i1[a], c[e], i1[b], i2[a], i2[b], s]
    })
}

/// The C0 fallback on the shared curves: the curves as row 0, the split point at the mean of
/// the six inner curve points, straight interior boundaries at thirds, and each `C_e` the mean
/// of its six net neighbours (which a linear function satisfies: linear precision).
pub fn fallback_patch(curves: &[[Point3<f64>; 4]; 3]) -> [[Point3<f64>; NP]; 3] {
    let next = |i: usize| (i + 1) % 3;
    let v: [Point3<f64>; 3] = std::array::from_fn(|i| curves[i][0]);
    let inner: Vec<(f64, &Point3<f64>)> = curves
        .iter()
        .flat_map(|c| [(1.0 / 6.0, &c[1]), (1.0 / 6.0, &c[2])])
        .collect();
    let s = comb(&inner);
    let i1: [Point3<f64>; 3] = std::array::from_fn(|i| v[i] + (s - v[i]) / 3.0);
    let i2: [Point3<f64>; 3] = std::array::from_fn(|i| v[i] + (s - v[i]) * (2.0 / 3.0));
    std::array::from_fn(|e| {
        let (a, b) = (e, next(e));
        let q = &curves[e];
        let w = 1.0 / 6.0;
        let c = comb(&[
            (w, &q[1]),
            (w, &q[2]),
            (w, &i1[a]),
            (w, &i1[b]),
            (w, &i2[a]),
            (w, &i2[b]),
        ]);
        [q[0], q[1], q[2], q[3], i1[a], c, i1[b], i2[a], i2[b], s]
    })
}

impl Scheme for CloughTocher {
    fn name(&self) -> &'static str {
        "clough-tocher"
    }

    fn layout(&self) -> Layout {
        Layout::bezier(3, &CENTROID_SPLIT)
    }

    /// C0 across mesh edges; G1 at the vertices and C1 inside each face (module docs).
    fn continuity(&self) -> Continuity {
        Continuity::C0
    }

    fn uses_curves(&self) -> bool {
        true
    }

    /// The functional form on height fields ([`super::functional`]): C1.
    fn on_height_field(&self, mesh: &crate::mesh::Mesh) -> Option<Box<dyn super::Scheme>> {
        Some(Box::new(
            super::functional::clough_tocher::FunctionalCloughTocher::new(mesh, self.cubic_weight),
        ))
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        if let Some(corner) = super::folded_corner(input) {
            return Err(FaceFallbackReason::Folded { corner });
        }
        let nets = macro_patch(&input.edges.map(|c| c.points));
        if !nets
            .iter()
            .flatten()
            .all(|p| p.iter().all(|c| c.is_finite()))
        {
            return Err(FaceFallbackReason::NonFinite);
        }
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
        Ok(())
    }

    /// [`fallback_patch`]: C0 on the shared edge curves.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        let nets = fallback_patch(&input.edges.map(|c| c.points));
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
    }
}

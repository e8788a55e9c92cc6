//! A cross-boundary field that carries the vertices' curvature: the variant
//! `shirman-sequin-curvature` of the modified Shirman–Séquin macro-patch
//! ([`crate::shirman_sequin`], whose notation this module keeps).
//!
//! # What Chiyokura–Kimura leaves out
//!
//! Along exterior edge `B(t)` (from `V_a` to `V_b`, `T_0 = B'(0) = 3(E¹ − V_a)`,
//! `T_1 = B'(1) = 3(V_b − E²)`) both faces' cross-boundary derivatives lie in
//! `span(B'(t), W(t))`, so the surface normal along the edge is `N ∝ B' × W`.
//! Chiyokura–Kimura take `W` linear, `W(t) = (1 − t)Ĉ_0 + tĈ_1`, which fixes the normal's whole
//! derivative along the edge from the two end normals alone. The normal's derivative has two
//! parts: along the curve (`−N·B''`, the curve's normal curvature, which the boundary curve
//! already matches to the data where its construction does) and across it, the geodesic
//! torsion. With `M = B' × W`, `M(0) = |T_0| n_a` and `Ĉ_0 × T̂_0 = −n_a`:
//!
//! ```text
//! N'(0)·Ĉ_0 = M'(0)·Ĉ_0 / |M(0)| = (T_0 × W'(0))·Ĉ_0 / |T_0| = −W'(0)·n_a,
//! N'(1)·Ĉ_1 = −W'(1)·n_b.
//! ```
//!
//! For linear `W`, `N'(0)·Ĉ_0 = −Ĉ_1·n_a`: the torsion averaged over the edge, not the data's
//! torsion at the vertex. The surface's second fundamental form at a vertex is then off by
//! `O(h)` in its twist, and every curvature measure converges as `h` (the ring's K RMS halves
//! with the edge length).
//!
//! # The field used here
//!
//! With the data's shape tensors `S_a`, `S_b` (Weingarten, in this workbench's sign
//! convention: `dN = −S dp`, docs/conventions.md), the normal's derivative at the ends should
//! be `N'(0) = −S_a T_0` and `N'(1) = −S_b T_1`. Take `W` quadratic,
//! `W(t) = B²_0(t) Ĉ_0 + B²_1(t) w + B²_2(t) Ĉ_1`, so `W'(0) = 2(w − Ĉ_0)`,
//! `W'(1) = 2(Ĉ_1 − w)`, and the two torsions match when
//!
//! ```text
//! w·n_a = a_0 := ½ Ĉ_0ᵀ S_a T_0,        w·n_b = a_1 := −½ Ĉ_1ᵀ S_b T_1.
//! ```
//!
//! Write `w = w_CK + x` with `w_CK = (Ĉ_0 + Ĉ_1)/2`, Chiyokura–Kimura's middle vector, and
//! `r_0 = a_0 − w_CK·n_a`, `r_1 = a_1 − w_CK·n_b` the two conditions' residuals at `w_CK`.
//! Chiyokura–Kimura's end rates are `N'(0)·Ĉ_0 = −Ĉ_1·n_a` and `N'(1)·Ĉ_1 = Ĉ_0·n_b`; the data's
//! `ρ_0 = −Ĉ_0ᵀ S_a T_0`, `ρ_1 = −Ĉ_1ᵀ S_b T_1`; so `r_0 = ½(−Ĉ_1·n_a − ρ_0)` and
//! `r_1 = ½(ρ_1 − Ĉ_0·n_b)`. In the basis `e_s = (n_a + n_b)/|…|`, `e_d = (n_b − n_a)/|…|` of
//! `span(n_a, n_b)` (`e_s·n = cos θ/2`, `∓e_d·n = sin θ/2`, `θ` the angle between the
//! normals) the exact solution nearest `w_CK` is `x = x_s e_s + x_d e_d` with
//!
//! ```text
//! x_s = (r_0 + r_1) / (2 cos θ/2),      x_d = (r_1 − r_0) / (2 sin θ/2).
//! ```
//!
//! `m = r_1 − r_0` is half the difference between the trapezoid rule of the data's rates and of
//! Chiyokura–Kimura's, whose sum is the normals' actual turn about the edge: `O(h³)` on smooth
//! data. Where the data's curvature jumps (a seam between a cylinder and a cap, a fillet
//! meeting a plane: a vertex on the seam carries one side's tensor) it is `O(h)`, and divided
//! by `sin θ/2` it is unbounded as the normals align: the data then asks for more than the
//! normals allow. So the end rates are moved to agree with the normals' turn first, and only
//! then matched: `ρ'_0 = ρ_0 − 2m ω_a`, `ρ'_1 = ρ_1 − 2m ω_b` with `ω_a + ω_b = 1`, which keeps
//! their sum the normals' own (`r'_1 = r'_0 + 0`: `x_d = 0`, no ill-conditioned quotient) and
//! gives
//!
//! ```text
//! x_s = [(r_0 + r_1) + (r_1 − r_0)(ω_a − ω_b)] / (2 cos θ/2),    x_d = 0.
//! ```
//!
//! The shift goes to the end whose tensor agrees least with the normals across the edge:
//! `ω_a = (e_a + ε)/(e_a + e_b + 2ε)` (ε a rounding floor, [`PREDICTION_FLOOR`]), with
//! `e_a = |Ĉ_0·(n_b − n_a) + Ĉ_0ᵀ S_a d|` and `e_b = |Ĉ_1·(n_a − n_b) − Ĉ_1ᵀ S_b d|`,
//! `d = V_b − V_a`: each tensor's first-order
//! prediction (`dN = −S dp`) of the other end's normal, across the edge. On smooth data both are
//! `O(h²)` and any split keeps the rates within `O(h³)` of the data's (the order this
//! construction aims at); at a seam the one-sided tensor mispredicts by `O(h)` and takes the
//! whole shift, so the edge gets the other side's torsion (on the capsule, the cap's: K RMS
//! 0.392 at 16 meridians where an equal split gave 0.829 and Chiyokura–Kimura 0.392). Measured
//! on the ring with dBHS curves: K RMS 0.0276 at 64 × 32 (equal split 0.0270; the exact
//! solution with `x_d` 0.0253, which on `box_fillet` folded 186 faces instead of 31 and raised
//! the G1 rounding to 4e-9 rad). `x_s` is clamped to `±`[`MAX_CORRECTION`] (it only grows as
//! the normals turn opposite, `cos θ/2 → 0`).
//!
//! The degree budget: the quartic's cross-boundary derivative is cubic, `D = 4K W + ⁴⁄₃ h B'`,
//! so with `W` quadratic `K` is linear, `K(t) = (1 − t)k_0 + t k_1` (Jensen's `c`, the
//! quadratic freedom of `K`, is spent on `W`). The product's cubic Bézier coefficients are
//! `k_0 Ĉ_0`, `(2k_0 w + k_1 Ĉ_0)/3`, `(k_0 Ĉ_1 + 2k_1 w)/3`, `k_1 Ĉ_1`; at `w = w_CK` these
//! are Chiyokura–Kimura's (`c = 1`), so the row-1 points are theirs moved by `⅔ k_0 x` and
//! `⅔ k_1 x`:
//!
//! ```text
//! C¹ = C¹_CK + ⅔ k_0 x,      C² = C²_CK + ⅔ k_1 x.
//! ```
//!
//! # G1
//!
//! `w` depends only on the edge: its curve, end normals and end shape tensors. The neighbour
//! travels the edge the other way (`B(1 − t)`): its `T̃_0 = −T_1`, `Ĉ̃_0 = −Ĉ_1`, so
//! `ã_0 = −a_1`, `r̃_0 = −r_1`, `r̃_1 = −r_0`, `ẽ_a = e_b`, `ω̃_a = ω_b`, `x̃_s = −x_s`: `x̃ = −x`
//! (the clamp is odd), `W̃(t) = −W(1 − t)`, and both faces have the normal
//! `B' × W` along the edge. The interior of the macro-patch is built as before from the row-1
//! points, for any rule (G1 inside for every `β > 0`).

use curves::CubicBez3;
use nalgebra::{Matrix3, Point3, Vector3};

use crate::shirman_sequin::{
    chiyokura_kimura_with_k, macro_patch_with, CrossEnd, CrossFailure, InteriorParameters,
    QuarticNet, SchemeError,
};
use curves::VertexData;

/// The largest correction `|x_s|` of the middle vector of `W` (module docs): the length of the
/// unit perpendiculars it corrects. On smooth data `x_s = O(h²)`; it grows without bound only
/// as the two end normals turn opposite, where a middle vector longer than its ends would turn
/// `W` towards the curve.
pub const MAX_CORRECTION: f64 = 1.0;

/// The floor added to both mispredictions `e_a`, `e_b` (module docs), relative to the sizes
/// they are differences of (`|n_b − n_a| + |S_a d| + |S_b d|`): `√ε`-size. Below it a
/// misprediction is rounding (a sphere's tensor predicts its normals exactly, and a latitude
/// edge of a cylinder has none across it), and the split must not follow the noise: a
/// rotated copy of the data would otherwise get another surface (measured 8e-6 on the capsule
/// before the floor).
pub const PREDICTION_FLOOR: f64 = 1e-8;

/// The correction `x = x_s e_s` of the middle vector of the quadratic field `W` of edge
/// `curve` with end normals `normals` (unit) and shape tensors `shapes` (module docs: the end
/// rates moved to the normals' turn, the shift weighted by each tensor's misprediction, then
/// matched), or `None` where the curve has a zero end derivative or a normal along it.
pub fn middle_correction(
    curve: &CubicBez3,
    normals: [&nalgebra::Vector3<f64>; 2],
    shapes: [&Matrix3<f64>; 2],
) -> Option<nalgebra::Vector3<f64>> {
    let [va, e1, e2, vb] = curve.points;
    let (t0, t1) = ((e1 - va) * 3.0, (vb - e2) * 3.0);
    let c0 = normals[0].cross(&t0).try_normalize(0.0)?;
    let c1 = normals[1].cross(&t1).try_normalize(0.0)?;
    let a0 = 0.5 * c0.dot(&(shapes[0] * t0));
    let a1 = -0.5 * c1.dot(&(shapes[1] * t1));
    let w_ck = (c0 + c1) * 0.5;
    let (r0, r1) = (a0 - w_ck.dot(normals[0]), a1 - w_ck.dot(normals[1]));
    let sum = normals[0] + normals[1];
    let ls = sum.norm();
    if ls == 0.0 {
        return Some(nalgebra::Vector3::zeros());
    }
    // e_s·n = |n_a + n_b|/2 = cos θ/2.
    // How far each end's tensor mispredicts the other end's normal across the edge: the shift
    // that makes the rates agree with the normals' turn goes to the worse one.
    let d = vb - va;
    let ea = (c0.dot(&(normals[1] - normals[0])) + c0.dot(&(shapes[0] * d))).abs();
    let eb = (c1.dot(&(normals[0] - normals[1])) - c1.dot(&(shapes[1] * d))).abs();
    // Mispredictions at rounding level (a sphere's tensor predicts its normals exactly) split
    // evenly, whatever their noise.
    let floor = PREDICTION_FLOOR
        * ((normals[1] - normals[0]).norm() + (shapes[0] * d).norm() + (shapes[1] * d).norm());
    let (wa, wb) = if ea + eb + 2.0 * floor > 0.0 {
        let total = ea + eb + 2.0 * floor;
        ((ea + floor) / total, (eb + floor) / total)
    } else {
        (0.5, 0.5)
    };
    let xs = ((r0 + r1) + (r1 - r0) * (wa - wb)) / ls;
    let x = sum / ls * xs.clamp(-MAX_CORRECTION, MAX_CORRECTION);
    Some(x)
}

/// The row-1 points `[C¹, C²]` of the curvature-matched field (module docs): Chiyokura–Kimura's
/// at `c = 1` moved by `⅔ k_0 x` and `⅔ k_1 x`.
pub fn curvature_cross(
    curve: &CubicBez3,
    ends: &[CrossEnd; 2],
    shapes: [&Matrix3<f64>; 2],
) -> Result<[Point3<f64>; 2], CrossFailure> {
    let x = middle_correction(curve, [&ends[0].normal, &ends[1].normal], shapes)
        .ok_or(CrossFailure::ZeroDerivative(0))?;
    moved_cross(curve, ends, &x)
}

/// The macro-patch of [`crate::shirman_sequin::macro_patch_creased`] with the quadratic
/// cross-boundary field of middle vector `w_CK + middles[e]` on each face edge `e` (module
/// docs): the field's free vector, given. It is shared by the two faces on an edge when the
/// neighbour, travelling the edge the other way, gives its negative (G1 for any vectors); the
/// curvature variant sets it from the data ([`macro_patch_curvature`]), an optimizer of the
/// curve network could set it from anything. β as given, `params.c` unused.
pub fn macro_patch_with_middles(
    vertices: [&VertexData; 3],
    edges: &[CubicBez3; 3],
    params: &InteriorParameters,
    creased: [bool; 3],
    middles: [Vector3<f64>; 3],
) -> Result<[QuarticNet; 3], SchemeError> {
    macro_patch_with(vertices, edges, params, creased, &|e, ends| {
        moved_cross(&edges[e], ends, &middles[e])
    })
}

/// Chiyokura–Kimura's row-1 points at `c = 1` moved by `⅔ k_0 x` and `⅔ k_1 x` (module docs).
fn moved_cross(
    curve: &CubicBez3,
    ends: &[CrossEnd; 2],
    x: &Vector3<f64>,
) -> Result<[Point3<f64>; 2], CrossFailure> {
    let ([c1, c2], [k0, k1]) = chiyokura_kimura_with_k(curve, ends, 1.0)?;
    Ok([c1 + x * (2.0 / 3.0 * k0), c2 + x * (2.0 / 3.0 * k1)])
}

/// The macro-patch of [`crate::shirman_sequin::macro_patch_creased`] with the curvature-matched
/// cross-boundary field on every exterior edge (module docs): β as given, `params.c` unused
/// (the field's quadratic freedom is `W`'s middle vector, not `K`).
pub fn macro_patch_curvature(
    vertices: [&VertexData; 3],
    edges: &[CubicBez3; 3],
    params: &InteriorParameters,
    creased: [bool; 3],
) -> Result<[QuarticNet; 3], SchemeError> {
    macro_patch_with(vertices, edges, params, creased, &|e, ends| {
        let shapes = [&vertices[e].shape, &vertices[(e + 1) % 3].shape];
        curvature_cross(&edges[e], ends, shapes)
    })
}

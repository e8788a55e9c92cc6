//! Two more split-domain constructions of the Shirman–Séquin family, beside Mann's β/c form
//! ([`crate::shirman_sequin`], whose notation this module keeps): the original 1987
//! construction with its free parameter `α₂`, and the modified fitter of the original testbed's
//! fitters (UW 1990). Both make three quartics per face over the centroid split
//! ([`crate::scheme::CENTROID_SPLIT`]) on the face's three shared cubic edge curves, with
//! Chiyokura–Kimura cross-boundary points (G1 across mesh edges); they differ in how the
//! interior is closed.
//!
//! # Common notation
//!
//! Face `V_0, V_1, V_2`, unit normals `n_i`; edge `e` from `V_e` to `V_{e+1}` carries the cubic
//! `V_e, E_e¹, E_e², V_{e+1}`. Sub-patch `e` is the quartic over `(V_e, V_{e+1}, Z)`, `Z` over
//! the centroid, with net rows (docs/conventions.md)
//!
//! ```text
//! row 0:  q0 … q4                    (edge e's cubic, degree-raised)
//! row 1:  T_a    L_e    K_e    T_b    (a = e, b = e + 1)
//! row 2:  M_a    N_e    M_b
//! row 3:  U_a    U_b
//! row 4:  Z
//! ```
//!
//! `V_a, T_a, M_a, U_a, Z` is the interior edge from corner `a` to `Z`, shared by sub-patches
//! `a` (on its left, travelling from `V_a`) and `a − 1`. `L_e`, `K_e` are the twists beside
//! `V_a`, `V_b`; the two twists beside corner `a` are `L_a` and `K_{a−1}`.
//!
//! # G1 across mesh edges: Chiyokura–Kimura
//!
//! Along edge `e` with parameter `t` the derivative of sub-patch `e` in the direction from the
//! edge point towards `Z` (the convex combination `(1−t)` of the derivative along `Z − V_a` and
//! `t` of the one along `Z − V_b`) is `W(t) = 4 (R(t) − B(t))`, with `B` the boundary cubic and
//! `R` the cubic whose control points are row 1 with the corner ones taken as `T_a, L, K, T_b`:
//! in the cubic basis, `W/4` has Bézier vectors `B_0 = T_a − V_a`, `B_1 = L − E¹`,
//! `B_2 = K − E²`, `B_3 = T_b − V_b`. Write `C_m` for the cubic's differences (`B' = 3ΣB²_m C_m`)
//! and `A_0`, `A_3` for the unit vectors in the end tangent planes perpendicular to `C_0`, `C_2`
//! (`n × C`, into the face: the neighbour on the edge travels it the other way and gets `−A`).
//! Decompose `B_0 = k_0 A_0 + h_0 C_0`, `B_3 = k_1 A_3 + h_1 C_2` and ask for
//! `W/4 = k(t) A(t) + h(t) C(t)` with `k, h, A` linear in `t`. The quadratic `kA` raised to
//! degree 3 and the cubic `hC` have the Bézier vectors
//!
//! ```text
//! B_1 = ((k_0 + k_1)/3) A_0 + (k_0/3) A_3 + (2h_0/3) C_1 + (h_1/3) C_0
//! B_2 = (k_1/3) A_0 + ((k_0 + k_1)/3) A_3 + (h_0/3) C_2 + (2h_1/3) C_1
//! ```
//!
//! and `B_0`, `B_3` as given. `W(t)` lies in the span of `B'(t)` and `A(t)`, which depends on
//! the edge's curve and end normals only, so both faces have the normal `B' × A` along the
//! edge: G1 (`k > 0` on the edge, `A` never along `B'`). These are exactly the equations of
//! [`crate::shirman_sequin::chiyokura_kimura`] at Jensen's `c = 1` (its `Ĉ_0, Ĉ_1, k, h` are
//! the `A_0, A_3, k, h` here), which both constructions call. The original testbed's fitters
//! (UW 1990) pick the sign of `A` so that `k > 0`; here it is fixed by the geometry and a face
//! with `k ≤ 0` is refused ([`SchemeError::NoCrossComponent`]): on valid data the same.
//!
//! # C1 across an interior edge
//!
//! The domain directions of the two sub-patches on interior edge `a–Z` add up to
//! `(V_{a+1} − V_a) + (V_{a−1} − V_a) = 3(Z − V_a)`. With `D_L`, `D_R` their derivatives across
//! the edge and `P'` the derivative along it (from `V_a` to `Z`), both sub-patches have one
//! gradient along the edge when `D_L + D_R = 3P'`; coplanarity (G1) when
//! `D_L + D_R = μ(t) P'(t)`, `μ > 0`. With the interior edge's quartic points `e_0 … e_4` and
//! the neighbouring points `l_m` (sub-patch `a`) and `r_m` (sub-patch `a − 1`), C1 reads
//! `l_m + r_m = 3 e_{m+1} − e_m`, `m = 0 … 3`:
//!
//! * `m = 0`: `q1 + q1' = 3T_a − V_a` (the quartic points beside `V_a` on its two edges);
//! * `m = 1`: `L_a + K_{a−1} = 3M_a − T_a`;
//! * `m = 2`: `N_a + N_{a−1} = 3U_a − M_a`;
//! * `m = 3`: `U_{a+1} + U_{a−1} = 3Z − U_a`, i.e. `Z = (U_0 + U_1 + U_2)/3`.
//!
//! # The 1987 construction ([`shirman_sequin_1987`])
//!
//! The interior edges are degree-raised cubics `V_a, S_a, P_a, Z`, so `T = (V + 3S)/4`,
//! `M = (S + P)/2`, `U = (3P + Z)/4`, and `P'` is the quadratic with differences
//! `δ_0 = S − V`, `δ_1 = P − S`, `δ_2 = Z − P`. With `μ(t) = (1−t)μ_0 + tμ_1` the cubic
//! coefficients of `μP'` are `3μ_0δ_0`, `μ_1δ_0 + 2μ_0δ_1`, `μ_0δ_2 + 2μ_1δ_1`, `3μ_1δ_2`, and those
//! of `D_L + D_R` are `4(l_m + r_m − 2e_m)`. The sources' steps (the original testbed's fitters,
//! UW 1990, after Shirman and Séquin 1987) are, with `α₁ = 2 − α₂`, `α₃ = −¾`, `α₄ = 11/4`:
//!
//! 1. `S_a = (1 − 2/α₂) V_a + (1/α₂)(Q_ab + Q_ac)`, `Q = ¼V + ¾E` the quartic points beside
//!    `V_a`; that is `S_a = V_a + (3/(4α₂))(E_ab + E_ac − 2V_a)`. Condition `m = 0` then holds
//!    with `μ_0 = 4α₂/3` (`4(Q_ab + Q_ac − 2V) = 3(E_ab + E_ac − 2V) = 4α₂ δ_0`). At `α₂ = 9/4`,
//!    `μ_0 = 3` and `S_a = ⅓(V_a + E_ab + E_ac)`: the vertex rule of a C1 cubic centroid split
//!    (the derivative along `Z − V` is ⅓ of the sum of those along the two edges).
//! 2. `m = 3` with `Z` the mean of the `P`s gives `4 · ¾(P_b + P_c − 2P_a) = 9δ_2`: `μ_1 = 3`.
//! 3. `m = 1`: `4(L + K' − 2T) = 3δ_0 + (8α₂/3)δ_1` gives
//!    `P_a = σ₀ V_a + σ₁ S_a + σ₂ (L_a + K_{a−1})` with `σ₂ = 3/(2α₂)`, `σ₀ = 3/(8α₂)`,
//!    `σ₁ = 1 − 27/(8α₂)`: the sources' `σ₀ = −α₃/(2α₂)`, `σ₁ = −(α₁/α₂ + α₄/(2α₂))`,
//!    `σ₂ = 3/(2α₂)` exactly (`σ₀ + σ₁ + 2σ₂ = 1` for every `α₂`: an affine combination).
//! 4. `m = 2`: `N_a + N_{a−1} = R_a := −½S_a + (5/2 − α₂/3) P_a + (α₂/3) Z`, three equations
//!    for the three `N`, solved by `N_e = ½(R_a + R_b − R_c)` (`c` the third corner), which with
//!    `Z = ⅓ΣP` is `N_e = (α₃/3)(S_a + S_b − S_c) + κ₁ (P_a + P_b) + κ₂ P_c`,
//!    `κ₁ = 5/4 − α₂/9`, `κ₂ = −5/4 + 2α₂/9`: the sources' `α₂/18 ± (α₁ + 2α₄)/6` exactly.
//!
//! So the sources' formulas are right (no slip found), and they are the G1 conditions with
//! `μ` running linearly from `4α₂/3` at the corner to 3 at `Z`: **C1 inside only at
//! `α₂ = 9/4`**; for any other `α₂` the sub-patches meet G1 with the derivative jump
//! `D_L + D_R − 3P' = (μ(t) − 3) P'(t)` (measured in the tests). The construction is the one
//! [`crate::shirman_sequin::macro_patch`] derives, with `β = 3/(4α₂)` and `c = 1`: the same
//! `J¹ = S`, `J² = P`, the same `m = 1` and `m = 2` equations (`μ_0 = 1/β`); the tests check
//! the nets agree to rounding. It degenerates at both ends of `α₂ > 0`: as `α₂ → 0` the points
//! `S`, `P` leave to infinity (`~1/α₂`), as `α₂ → ∞` the interior edges' end derivatives
//! `3(S − V)` vanish (`~1/α₂`) and with them `k_0, k_1`. [`ALPHA2_RANGE`] keeps the factor
//! within that of Mann's β range. On planar data every control point stays in the plane for
//! every `α₂`, but the parametrization is the linear one (linear precision) only at `9/4`:
//! elsewhere `S` sits `3/(4α₂)` rather than ⅓ of the way along the edge points' sum.
//!
//! # The testbed's modified fitter ([`testbed_modified`])
//!
//! One cubic macro patch over the face: the three edge cubics and the quadratic-precision
//! centre `b111 = ¼ΣE − ⅙ΣV` (the six edge points, the three corners); degree-raised to a
//! quartic and split at the centroid (the sub-nets are its blossom, `b_{ijk} = f(u_0^i, u_1^j,
//! u_2^k)` over the sub-triangle's corners `u`), so the three quartics are one polynomial.
//! Kept: the boundaries, `T_a` (`= ¼V + ¾·⅓(V + E_ab + E_ac)`, so `m = 0` holds), and the three
//! points `N_e` beside `Z`. Replaced: the twists `L, K` by Chiyokura–Kimura with the corner
//! cross vectors `T − V` (in the tangent plane: the macro patch's corner derivatives are along
//! the edges' end tangents). Then C1 is restored in the order of the conditions:
//! `M_a = ⅓(T_a + L_a + K_{a−1})` (`m = 1`), `U_a = ⅓(M_a + N_a + N_{a−1})` (`m = 2`), and
//! `Z = ⅓(U_0 + U_1 + U_2)` (`m = 3`). C1 inside for all data, G1 across edges, no parameter.
//!
//! It differs from Mann's β/c form in what is solved for: Mann's interior edges are
//! degree-raised cubics (`U = (3J² + Z)/4`, `Z` the mean of the `J²`) and the `N` are solved
//! from `m = 2`; here the interior edges are general quartics, the `N` come from the macro
//! patch and the `U` and `Z` are solved. At `β = ⅓, c = 1` rows 0 and 1 and `M` coincide
//! (Mann's `m = 1` with `μ = 3` is the same average); `N`, `U`, `Z` do not, and no other `β`,
//! `c` can make them coincide (a β ≠ ⅓ moves `T`, a c ≠ 1 moves `L` and `K`): the tests
//! measure the nets' distance over a grid of `β, c`.

use curves::{CubicBez3, VertexData};
use nalgebra::{Point3, Vector3};

use crate::beztri::BezierTriangle;
use crate::scheme::CENTROID_SPLIT;
use crate::shirman_sequin::{chiyokura_kimura, CrossEnd, QuarticNet, SchemeError};

/// The default of the 1987 construction's free parameter: the C1 one (module docs).
pub const DEFAULT_ALPHA2: f64 = 9.0 / 4.0;

/// The range of `α₂` accepted: `β = 3/(4α₂)` within Mann's β range `[0.01, 10]` (the corner
/// points move by `~1/α₂`, the interior edges' end derivatives shrink by it; module docs).
pub const ALPHA2_RANGE: (f64, f64) = (0.075, 75.0);

/// `α₃` and `α₄` of the 1987 construction (fixed constants of the sources).
const ALPHA3: f64 = -0.75;
const ALPHA4: f64 = 2.75;

fn prev(i: usize) -> usize {
    (i + 2) % 3
}

fn next(i: usize) -> usize {
    (i + 1) % 3
}

fn affine(terms: &[(f64, Point3<f64>)]) -> Point3<f64> {
    Point3::from(
        terms
            .iter()
            .fold(Vector3::zeros(), |acc, (w, p)| acc + p.coords * *w),
    )
}

/// The refusals of [`crate::shirman_sequin::macro_patch`], for the same reasons and by the same
/// check (`shirman_sequin::refuse_folding`: a vertex normal at 90° or more from the face normal,
/// an end tangent off its vertex's tangent plane), then an end derivative of zero length (or
/// NaN), which these constructions divide by (Mann's does not). A face with several defects
/// reports the first of that order.
fn refuse(
    v: &[Point3<f64>; 3],
    n: &[Vector3<f64>; 3],
    edges: &[CubicBez3; 3],
) -> Result<(), SchemeError> {
    crate::shirman_sequin::refuse_folding(v, n, edges)?;
    for (edge, c) in edges.iter().enumerate() {
        let [va, p1, p2, vb] = c.points;
        for (corner, t) in [(edge, p1 - va), (next(edge), vb - p2)] {
            if t.norm() == 0.0 || t.norm().is_nan() {
                return Err(SchemeError::ZeroEndDerivative { edge, corner });
            }
        }
    }
    Ok(())
}

/// Chiyokura–Kimura twists `(L_e, K_e)` of the three edges from the quartic points `t[i]`
/// beside each corner on its interior edge (module docs).
fn twists(
    n: &[Vector3<f64>; 3],
    v: &[Point3<f64>; 3],
    edges: &[CubicBez3; 3],
    t: &[Point3<f64>; 3],
) -> Result<[[Point3<f64>; 2]; 3], SchemeError> {
    let mut out = [[Point3::origin(); 2]; 3];
    for e in 0..3 {
        let (a, b) = (e, next(e));
        let ends = [
            CrossEnd {
                normal: n[a],
                cross: t[a] - v[a],
            },
            CrossEnd {
                normal: n[b],
                cross: t[b] - v[b],
            },
        ];
        out[e] = chiyokura_kimura(&edges[e], &ends, 1.0).map_err(|f| f.on_edge(e, [a, b]))?;
    }
    Ok(out)
}

/// The interior points of one face in the module's notation, assembled into the three nets.
struct Interior {
    t: [Point3<f64>; 3],
    lk: [[Point3<f64>; 2]; 3],
    m: [Point3<f64>; 3],
    n: [Point3<f64>; 3],
    u: [Point3<f64>; 3],
    z: Point3<f64>,
}

fn assemble(edges: &[CubicBez3; 3], p: &Interior) -> [QuarticNet; 3] {
    std::array::from_fn(|e| {
        let (a, b) = (e, next(e));
        let q = edges[e].elevate().points;
        [
            q[0], q[1], q[2], q[3], q[4], //
            p.t[a], p.lk[e][0], p.lk[e][1], p.t[b], //
            p.m[a], p.n[e], p.m[b], //
            p.u[a], p.u[b], //
            p.z,
        ]
    })
}

fn corners(vertices: [&VertexData; 3]) -> ([Point3<f64>; 3], [Vector3<f64>; 3]) {
    (
        std::array::from_fn(|i| vertices[i].p),
        std::array::from_fn(|i| {
            vertices[i]
                .n
                .try_normalize(0.0)
                .unwrap_or_else(Vector3::zeros)
        }),
    )
}

/// The 1987 Shirman–Séquin construction with free parameter `α₂` (module docs): the three
/// quartic sub-patch nets of one face, sub-patch `e` over `(V_e, V_{e+1}, Z)`. `edges[e]` runs
/// from `V_e` to `V_{e+1}`.
pub fn shirman_sequin_1987(
    vertices: [&VertexData; 3],
    edges: &[CubicBez3; 3],
    alpha2: f64,
) -> Result<[QuarticNet; 3], SchemeError> {
    if !(alpha2 > 0.0 && alpha2.is_finite()) {
        return Err(SchemeError::BadParameter {
            name: "alpha2",
            index: 0,
            value: alpha2,
        });
    }
    let (v, n) = corners(vertices);
    refuse(&v, &n, edges)?;
    let alpha1 = 2.0 - alpha2;
    // Step 1: S_a from the quartic points beside V_a on its two edges.
    let s: [Point3<f64>; 3] = std::array::from_fn(|a| {
        let qab = affine(&[(0.25, v[a]), (0.75, edges[a].points[1])]);
        let qac = affine(&[(0.25, v[a]), (0.75, edges[prev(a)].points[2])]);
        affine(&[
            (1.0 - 2.0 / alpha2, v[a]),
            (1.0 / alpha2, qab),
            (1.0 / alpha2, qac),
        ])
    });
    let t: [Point3<f64>; 3] = std::array::from_fn(|a| affine(&[(0.25, v[a]), (0.75, s[a])]));
    let lk = twists(&n, &v, edges, &t)?;
    // Step 3 (m = 1): P_a.
    let (s0, s1, s2) = (
        -ALPHA3 / (2.0 * alpha2),
        -(alpha1 / alpha2 + ALPHA4 / (2.0 * alpha2)),
        3.0 / (2.0 * alpha2),
    );
    let p: [Point3<f64>; 3] = std::array::from_fn(|a| {
        affine(&[(s0, v[a]), (s1, s[a]), (s2, lk[a][0]), (s2, lk[prev(a)][1])])
    });
    let z = affine(&[(1.0 / 3.0, p[0]), (1.0 / 3.0, p[1]), (1.0 / 3.0, p[2])]);
    // Step 4 (m = 2): N_e.
    let k1 = alpha2 / 18.0 + (alpha1 + 2.0 * ALPHA4) / 6.0;
    let k2 = alpha2 / 18.0 - (alpha1 + 2.0 * ALPHA4) / 6.0;
    let nn: [Point3<f64>; 3] = std::array::from_fn(|e| {
        let (a, b, c) = (e, next(e), prev(e));
        affine(&[
            (ALPHA3 / 3.0, s[a]),
            (ALPHA3 / 3.0, s[b]),
            (-ALPHA3 / 3.0, s[c]),
            (k1, p[a]),
            (k1, p[b]),
            (k2, p[c]),
        ])
    });
    let interior = Interior {
        t,
        lk,
        m: std::array::from_fn(|a| affine(&[(0.5, s[a]), (0.5, p[a])])),
        n: nn,
        u: std::array::from_fn(|a| affine(&[(0.75, p[a]), (0.25, z)])),
        z,
    };
    Ok(assemble(edges, &interior))
}

/// The cubic macro patch of a face with the quadratic-precision centre
/// `b111 = ¼ΣE − ⅙ΣV` (module docs).
pub fn cubic_macro_patch(vertices: [Point3<f64>; 3], edges: &[CubicBez3; 3]) -> BezierTriangle {
    let inner: Vector3<f64> = edges
        .iter()
        .map(|c| c.points[1].coords + c.points[2].coords)
        .sum();
    let corner_sum: Vector3<f64> = vertices.iter().map(|p| p.coords).sum();
    let centre = Point3::from(inner / 4.0 - corner_sum / 6.0);
    // b_ijk of the cubic: corners, the edge points (edge e from V_e to V_{e+1}: the point
    // weighted 2 towards V_e is E_e¹) and the centre.
    BezierTriangle::from_fn(3, |i, j, k| {
        let w = [i, j, k];
        if let Some(c) = (0..3).find(|&c| w[c] == 3) {
            return vertices[c];
        }
        match (0..3).find(|&c| w[c] == 0) {
            Some(zero) => {
                // The edge between the two other corners: e = zero + 1 runs V_e → V_{e+1}.
                let e = next(zero);
                if w[e] == 2 {
                    edges[e].points[1]
                } else {
                    edges[e].points[2]
                }
            }
            None => centre,
        }
    })
}

/// The sub-nets of `patch` over the sub-triangles of the centroid split, from its blossom.
fn split_at_centroid(patch: &BezierTriangle) -> [BezierTriangle; 3] {
    std::array::from_fn(|s| {
        let sub = CENTROID_SPLIT[s];
        BezierTriangle::from_fn(patch.degree(), |i, j, k| {
            let mut args = vec![sub[0]; i];
            args.extend(std::iter::repeat_n(sub[1], j));
            args.extend(std::iter::repeat_n(sub[2], k));
            Point3::from(patch.blossom(&args))
        })
    })
}

/// The testbed's modified fitter (module docs): the three quartic sub-patch nets of one face.
pub fn testbed_modified(
    vertices: [&VertexData; 3],
    edges: &[CubicBez3; 3],
) -> Result<[QuarticNet; 3], SchemeError> {
    let (v, n) = corners(vertices);
    refuse(&v, &n, edges)?;
    let subs = split_at_centroid(&cubic_macro_patch(v, edges).elevate());
    let point = |s: usize, i, j, k| {
        subs[s]
            .point(i, j, k)
            .unwrap_or_else(|| Point3::from(Vector3::repeat(f64::NAN)))
    };
    let t: [Point3<f64>; 3] = std::array::from_fn(|a| point(a, 3, 0, 1));
    let nn: [Point3<f64>; 3] = std::array::from_fn(|e| point(e, 1, 1, 2));
    let lk = twists(&n, &v, edges, &t)?;
    let third = 1.0 / 3.0;
    let m: [Point3<f64>; 3] = std::array::from_fn(|a| {
        affine(&[(third, t[a]), (third, lk[a][0]), (third, lk[prev(a)][1])])
    });
    let u: [Point3<f64>; 3] =
        std::array::from_fn(|a| affine(&[(third, m[a]), (third, nn[a]), (third, nn[prev(a)])]));
    let z = affine(&[(third, u[0]), (third, u[1]), (third, u[2])]);
    Ok(assemble(
        edges,
        &Interior {
            t,
            lk,
            m,
            n: nn,
            u,
            z,
        },
    ))
}

//! The fallback macro-patch of a face the split-domain construction cannot fit: C0, meeting
//! every neighbour exactly along the shared boundary curves, G1 not promised, and built so that
//! it does not fold over its face.
//!
//! Used where [`crate::shirman_sequin::macro_patch`] fails (a corner cross vector that does not
//! point into the patch, a vertex normal turned against the face, a clamped tangent, a zero end
//! derivative, non-finite points) and for faces of zero area. Same layout as the regular
//! macro-patch: three quartics over the centroid split, in docs/conventions.md row order,
//! sub-patch `e` over `(V_e, V_{e+1}, S)`, rows `V_e q1 q2 q3 V_{e+1} / I¹_e C¹ C² I¹_{e+1} /
//! I²_e N I²_{e+1} / I³_e I³_{e+1} / S`.
//!
//! # What "does not fold" means, and what decides it
//!
//! A face folds ([`crate::folds`]) where a patch normal `n = r_u × r_v` has `n · N_f ≤ 0`,
//! `N_f` the data face's unit normal. Write every point as its projection onto the face plane
//! plus a height along `N_f`: `(r_u × r_v) · N_f = det(π r_u, π r_v)` depends on the projected
//! patch alone. So folding is a plane question — is the projection of the macro-patch onto the
//! face plane an orientation-preserving immersion of the triangle? — and the heights are free.
//!
//! The boundary is given (the shared exterior cubics), and it already decides some faces: the
//! projection of an immersed disc has a boundary of turning number 1 (Hopf's Umlaufsatz, with
//! the corners' exterior angles taken in `(−π, π)`), so when the projected boundary loop turns
//! any other number of times, or a projected curve stops (its derivative vanishes) or a corner
//! is a cusp, **no** patch on those curves avoids folding: [`forced_fold`] says which, exactly
//! (the turning of a projected cubic is computed between the roots of `H × H'`, `H` its
//! hodograph, where the angle is monotone). Elsewhere the interior is chosen to keep the
//! projected Jacobian positive where it is decided first: at the corners (exactly) and along
//! the exterior edges and interior boundaries (by following the curves).
//!
//! # Construction (a face with a normal)
//!
//! * Row 0 of sub-patch `e` is the face's exterior cubic `e`, degree-raised: the same curve the
//!   neighbour uses, so the surface stays C0 (watertight) across every edge.
//! * **Corner curves**: at corner `i` the two edge curves leaving it, `B_i(t)` and
//!   `B_{i−1}(1 − t)`, have the mean `A_i(t)`, a cubic with control points the means of theirs.
//!   For straight edges at thirds `A_i` runs uniformly from `V_i` to the midpoint of the
//!   opposite edge, through the centroid at `t = ⅔`; on curved edges it follows both curves
//!   between them, which is where an interior boundary must run for the sub-patches on either
//!   side to stay open. Cut at `⅔` (de Casteljau) it is `V_i, A¹_i, A²_i, A³_i`.
//! * **Split point**: `S = (A³_0 + A³_1 + A³_2)/3 = Σ_e [B_e(⅓) + B_e(⅔)]/6`, the mean of the six
//!   curve points at thirds.
//! * **Corner legs** `l_i = J¹_i − V_i`: let `a = E¹_i − V_i` (leaving along edge `i`),
//!   `b = E²_{i−1} − V_i` (arriving along edge `i − 1`, reversed) and `φ_i ∈ (0, 2π)` the angle
//!   from `π a` counter-clockwise to `π b` (π minus the exterior angle taken in `(−π, π)`). The
//!   two sub-patches at `V_i` have there the projected Jacobians `det(πa, πl)` and
//!   `det(πl, πb)` (up to positive factors): both positive exactly when `πl` is strictly inside
//!   the angle. When `φ_i < π`, `l = (a + b)/3 = A¹_i − V_i` (the regular scheme's leg at
//!   `β = ⅓`) is a positive combination of `πa` and `πb`, hence inside. When `φ_i ≥ π` (a
//!   reflex corner, where the sum points out of the face) `πl` is the bisector of the angle,
//!   of length `(|πa| + |πb|)/6`, with the height of `(a + b)/3`.
//! * **Interior boundaries** `V_i → S`: the cubics `V_i, J¹_i, J²_i, S` with
//!   `J²_i = A²_i + (S − A³_i)`, the cut corner curve with its far end moved to `S`. Quartic
//!   points `I¹ = (V + 3J¹)/4`, `I² = (J¹ + J²)/2`, `I³ = (3J² + S)/4`.
//! * **Along the exterior edges** (`C¹ = b₂₁₁`, `C² = b₁₂₁`): Chiyokura–Kimura with `c = 1`
//!   ([`crate::shirman_sequin::chiyokura_kimura`]) on the sub-patch's **own** corner normals
//!   `t_0 × l_a` and `t_1 × l_b` (`t` the curve's end legs), instead of the data's vertex normals.
//!   Then `Ĉ_0` is the part of `l_a` perpendicular to `t_0` (so the decomposition
//!   `l_a = k_0 Ĉ_0 + h_0 t_0` is exact with `k_0 > 0`), and the cross-boundary derivative is
//!   `D(t) = 4K(t)Ĉ(t) + (4/3)h(t)B'(t)` with `K > 0` linear: the projected Jacobian along the
//!   edge is `4K(t) det(πB'(t), πĈ(t))`, positive at both ends by the corner rule
//!   (`det(πt_0, πĈ_0) ∝ det(πa, πl_a)`) and in between as long as the projected curve does not
//!   turn past `πĈ(t)`. **Row 2's middle point** `N = b₁₁₂` is the mean of its six neighbours.
//! * **Harmonic alternative**: Chiyokura–Kimura divides by the end legs' lengths, so a very
//!   short end derivative (dBHS's short solutions) throws `C¹`, `C²` far off. When the net above
//!   folds on the fold measure's samples ([`worst_cosine`]), `C¹`, `C²`, `N` are instead made
//!   discretely harmonic — each the mean of its six neighbours: writing `A`, `B`, `C'` for the
//!   sums of their known neighbours, `A = I¹_a + q₁ + q₂ + I²_a`, `B = I¹_b + q₂ + q₃ + I²_b`,
//!   `C' = I²_a + I²_b + I³_a + I³_b`, the equations `6C¹ − C² − N = A`, `−C¹ + 6C² − N = B`,
//!   `−C¹ − C² + 6N = C'` give `N = (A + B + 5C')/28`, `C¹ + C² = 6N − C'`,
//!   `C¹ − C² = (A − B)/7` — and of the two nets the one whose worst sample is better is kept.
//!
//! **Linear precision** ("never worse than the flat triangle"): for a face with straight edges
//! at thirds, `A_i(t) = V_i + t(M_i − V_i)` with `M_i` the opposite edge's midpoint, so
//! `A³_i = G` (the centroid), `S = G`, `J¹_i = V_i + (G − V_i)/3` (every corner convex,
//! `a + b = G − V_i`) and `J²_i = V_i + ⅔(G − V_i)`; Chiyokura–Kimura reproduces a plane (its
//! `C¹ − E¹ = (S − V_a)/4 − (V_b − V_a)/12` is the flat point) and so does the mean of six
//! neighbours on the triangular grid: every point of every net is the affine image of its
//! domain point, the flat triangle's (tested).
//!
//! **What is not promised**: positivity away from the corners where the projected curves turn
//! sharply or bulge across the face (an edge curve passing close to the opposite corner leaves
//! no room). [`jacobian_coefficients`] certifies a net (all Bernstein coefficients of its
//! projected Jacobian positive ⇒ no fold anywhere), and the fold measure reports what remains.
//!
//! A face of zero area has no normal to fold against (the fold measure skips it): it gets the
//! rule this module had before, the split point at the mean of the six inner control points,
//! straight interior boundaries and the harmonic `C¹`, `C²`, `N`.

use curves::CubicBez3;
use nalgebra::{Point3, Vector3};

use std::sync::OnceLock;

use crate::beztri::{index, multi_indices, net_derivatives, SampleWeights};
use crate::shirman_sequin::{chiyokura_kimura, CrossEnd, QuarticNet, DEGENERATE};

fn lerp(a: &Point3<f64>, b: &Point3<f64>, t: f64) -> Point3<f64> {
    a + (b - a) * t
}

/// The unit normal of the face with corners `v` (counter-clockwise), `None` when its area is
/// (relatively) zero: `|(v1 − v0) × (v2 − v0)|` at most [`DEGENERATE`] times the product of
/// the two edges' lengths (the sine of the corner angle).
pub fn face_normal(v: &[Point3<f64>; 3]) -> Option<Vector3<f64>> {
    let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
    let cross = e1.cross(&e2);
    let len = cross.norm();
    (len.is_finite() && len > DEGENERATE * e1.norm() * e2.norm()).then(|| cross / len)
}

/// `v` without its component along the unit `n`.
fn project(v: &Vector3<f64>, n: &Vector3<f64>) -> Vector3<f64> {
    v - n * v.dot(n)
}

/// The signed angle from `a` to `b` about the unit `n`, in `(−π, π]`.
fn signed_angle(a: &Vector3<f64>, b: &Vector3<f64>, n: &Vector3<f64>) -> f64 {
    a.cross(b).dot(n).atan2(a.dot(b))
}

/// The fallback macro-patch (module docs) of a face whose exterior cubics are `edges` (`edges[e]`
/// from corner `e` to corner `e + 1`).
pub fn fallback_patch(edges: &[CubicBez3; 3]) -> [QuarticNet; 3] {
    let v: [Point3<f64>; 3] = std::array::from_fn(|i| edges[i].points[0]);
    let Some(nf) = face_normal(&v) else {
        return zero_area_patch(edges, &v);
    };
    // The corner curves A_i (the mean of the two edge curves at corner i, both leaving it) cut
    // at 2/3 by de Casteljau: [A(0), first, second, A(2/3)].
    let cut: [[Point3<f64>; 4]; 3] = std::array::from_fn(|i| {
        let (out, inn) = (edges[i].points, edges[(i + 2) % 3].reversed().points);
        let p: [Point3<f64>; 4] =
            std::array::from_fn(|k| Point3::from((out[k].coords + inn[k].coords) / 2.0));
        let t = 2.0 / 3.0;
        let l1: [Point3<f64>; 3] = std::array::from_fn(|k| lerp(&p[k], &p[k + 1], t));
        let l2 = [lerp(&l1[0], &l1[1], t), lerp(&l1[1], &l1[2], t)];
        [p[0], l1[0], l2[0], lerp(&l2[0], &l2[1], t)]
    });
    let s = Point3::from((cut[0][3].coords + cut[1][3].coords + cut[2][3].coords) / 3.0);
    let j1: [Point3<f64>; 3] = std::array::from_fn(|i| {
        let a = edges[i].points[1] - v[i];
        let b = edges[(i + 2) % 3].points[2] - v[i];
        v[i] + corner_leg(&a, &b, &nf) / 3.0
    });
    let j2: [Point3<f64>; 3] = std::array::from_fn(|i| cut[i][2] + (s - cut[i][3]));
    let along = assemble(edges, &v, &j1, &j2, &s, true);
    let Some(worst) = worst_cosine(&along, &nf) else {
        return along;
    };
    if worst > 0.0 {
        return along;
    }
    let harmonic = assemble(edges, &v, &j1, &j2, &s, false);
    match worst_cosine(&harmonic, &nf) {
        Some(w) if w <= worst => along,
        _ => harmonic,
    }
}

/// The leg `3(J¹ − V)` at a corner with legs `a` (leaving) and `b` (arriving, reversed): `a + b`
/// where the projected angle from `a` to `b` is below π, else the bisector of that angle with
/// the mean projected length and the height of `a + b` (module docs). A leg with no projection
/// (a tangent along the normal) gives the sum: no direction in the plane is better.
fn corner_leg(a: &Vector3<f64>, b: &Vector3<f64>, nf: &Vector3<f64>) -> Vector3<f64> {
    let sum = a + b;
    let (pa, pb) = (project(a, nf), project(b, nf));
    let (la, lb) = (pa.norm(), pb.norm());
    if la <= DEGENERATE * a.norm() || lb <= DEGENERATE * b.norm() {
        return sum;
    }
    // The exterior angle from the arriving direction −b to a, in (−π, π]; φ = π − it.
    let phi = std::f64::consts::PI - signed_angle(&(-pb), &pa, nf);
    if phi < std::f64::consts::PI {
        return sum;
    }
    let ua = pa / la;
    let half = phi / 2.0;
    let bisector = ua * half.cos() + nf.cross(&ua) * half.sin();
    bisector * ((la + lb) / 2.0) + nf * sum.dot(nf)
}

/// The nets from the exterior cubics, the interior boundaries' cubic points `J¹`, `J²` and the
/// split point `S`: `C¹`, `C²` by Chiyokura–Kimura on the sub-patch's own corner normals when
/// `cross_boundary` (and it succeeds), else harmonic with `N` (module docs).
fn assemble(
    edges: &[CubicBez3; 3],
    v: &[Point3<f64>; 3],
    j1: &[Point3<f64>; 3],
    j2: &[Point3<f64>; 3],
    s: &Point3<f64>,
    cross_boundary: bool,
) -> [QuarticNet; 3] {
    let i1: [Point3<f64>; 3] = std::array::from_fn(|i| lerp(&v[i], &j1[i], 0.75));
    let i2: [Point3<f64>; 3] = std::array::from_fn(|i| lerp(&j1[i], &j2[i], 0.5));
    let i3: [Point3<f64>; 3] = std::array::from_fn(|i| lerp(&j2[i], s, 0.25));
    std::array::from_fn(|e| {
        let (a, b) = (e, (e + 1) % 3);
        let q = edges[e].elevate().points;
        let sum_c = i2[a].coords + i2[b].coords + i3[a].coords + i3[b].coords;
        let along = cross_boundary
            .then(|| own_cross_boundary(&edges[e], &(i1[a] - v[a]), &(i1[b] - v[b])))
            .flatten();
        let (c1, c2, n) = match along {
            Some([c1, c2]) => {
                let n = (c1.coords + c2.coords + sum_c) / 6.0;
                (c1, c2, n)
            }
            None => {
                let sum_a = i1[a].coords + q[1].coords + q[2].coords + i2[a].coords;
                let sum_b = i1[b].coords + q[2].coords + q[3].coords + i2[b].coords;
                let n = (sum_a + sum_b + sum_c * 5.0) / 28.0;
                let plus = n * 6.0 - sum_c;
                let minus = (sum_a - sum_b) / 7.0;
                (
                    Point3::from((plus + minus) / 2.0),
                    Point3::from((plus - minus) / 2.0),
                    n,
                )
            }
        };
        [
            q[0],
            q[1],
            q[2],
            q[3],
            q[4],
            i1[a],
            c1,
            c2,
            i1[b],
            i2[a],
            Point3::from(n),
            i2[b],
            i3[a],
            i3[b],
            *s,
        ]
    })
}

/// Chiyokura–Kimura's `[C¹, C²]` along `curve` with `c = 1`, taking as the normal at each end
/// the sub-patch's own corner normal there (module docs), `None` where the corner is
/// degenerate.
fn own_cross_boundary(
    curve: &CubicBez3,
    cross_a: &Vector3<f64>,
    cross_b: &Vector3<f64>,
) -> Option<[Point3<f64>; 2]> {
    let [va, e1, e2, vb] = curve.points;
    let (t0, t1) = (e1 - va, vb - e2);
    let ends = [
        CrossEnd {
            normal: t0.cross(cross_a).try_normalize(0.0)?,
            cross: *cross_a,
        },
        CrossEnd {
            normal: t1.cross(cross_b).try_normalize(0.0)?,
            cross: *cross_b,
        },
    ];
    chiyokura_kimura(curve, &ends, 1.0).ok()
}

/// A face of zero area: the split point at the mean of the six inner control points, straight
/// interior boundaries at thirds (module docs).
fn zero_area_patch(edges: &[CubicBez3; 3], v: &[Point3<f64>; 3]) -> [QuarticNet; 3] {
    let inner = edges
        .iter()
        .map(|c| c.points[1].coords + c.points[2].coords)
        .fold(Vector3::zeros(), |a, b| a + b);
    let s = Point3::from(inner / 6.0);
    let j1: [Point3<f64>; 3] = std::array::from_fn(|i| lerp(&v[i], &s, 1.0 / 3.0));
    let j2: [Point3<f64>; 3] = std::array::from_fn(|i| lerp(&v[i], &s, 2.0 / 3.0));
    assemble(edges, v, &j1, &j2, &s, false)
}

/// Why no patch on a face's exterior cubics can avoid folding over the face (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ForcedFold {
    /// The projection of edge curve `edge` onto the face plane stops somewhere (its derivative
    /// vanishes): the Jacobian of any patch on it is zero there.
    StoppedEdge {
        /// The face edge (0, 1, 2).
        edge: usize,
    },
    /// At corner `corner` the projected curves leave in opposite directions (a cusp).
    Cusp {
        /// The face corner (0, 1, 2).
        corner: usize,
    },
    /// The projected boundary loop turns `turns` times, not once (its end tangents cross at a
    /// corner, or a curve loops across the face).
    Turning {
        /// The turning number of the projected boundary.
        turns: i64,
    },
}

/// A projected hodograph `|H|` below this fraction of the curve's control polygon length is a
/// stop: the Jacobian there is rounding.
const STOP: f64 = 1e-12;

/// Whether the exterior cubics `edges` of a face force any patch on them to fold over the face
/// (module docs), and why; `None` when they do not (a fold-free patch may exist). Faces of
/// zero area give `None`.
pub fn forced_fold(edges: &[CubicBez3; 3]) -> Option<ForcedFold> {
    let v: [Point3<f64>; 3] = std::array::from_fn(|i| edges[i].points[0]);
    let nf = face_normal(&v)?;
    let hodograph = |c: &CubicBez3| -> [Vector3<f64>; 3] {
        let p = c.points;
        [0, 1, 2].map(|m| project(&((p[m + 1] - p[m]) * 3.0), &nf))
    };
    let mut total = 0.0;
    for (e, c) in edges.iter().enumerate() {
        let h = hodograph(c);
        let scale = h
            .iter()
            .map(|x| x.norm())
            .sum::<f64>()
            .max(f64::MIN_POSITIVE);
        match sweep(&h, &nf, STOP * scale) {
            Some(a) => total += a,
            None => return Some(ForcedFold::StoppedEdge { edge: e }),
        }
    }
    for i in 0..3 {
        let arriving = hodograph(&edges[(i + 2) % 3])[2];
        let leaving = hodograph(&edges[i])[0];
        let ext = signed_angle(&arriving, &leaving, &nf);
        if ext.abs() >= std::f64::consts::PI {
            return Some(ForcedFold::Cusp { corner: i });
        }
        total += ext;
    }
    let turns = (total / std::f64::consts::TAU).round() as i64;
    (turns != 1).then_some(ForcedFold::Turning { turns })
}

/// The angle swept about `n` by the quadratic `H(t) = h0 B²₀ + h1 B²₁ + h2 B²₂` (a projected
/// hodograph) for `t ∈ [0, 1]`, `None` when `|H| ≤ tiny` at an end or a turning point.
///
/// The angular speed has the sign of `(H × H') · n`, a polynomial of degree ≤ 2 (the `t³` terms
/// cancel); between its roots the angle is monotone, so each piece's sweep is the principal
/// angle between its ends, moved by `±2π` when that has the wrong sign.
fn sweep(h: &[Vector3<f64>; 3], n: &Vector3<f64>, tiny: f64) -> Option<f64> {
    let at =
        |t: f64| h[0] * ((1.0 - t) * (1.0 - t)) + h[1] * (2.0 * t * (1.0 - t)) + h[2] * (t * t);
    let speed = |t: f64| {
        let d = ((h[1] - h[0]) * (1.0 - t) + (h[2] - h[1]) * t) * 2.0;
        at(t).cross(&d).dot(n)
    };
    // The quadratic through t = 0, ½, 1 in monomial form c0 + c1 t + c2 t².
    let (s0, sh, s1) = (speed(0.0), speed(0.5), speed(1.0));
    let c2 = 2.0 * (s0 - 2.0 * sh + s1);
    let c1 = s1 - s0 - c2;
    let mut cuts = vec![0.0];
    let mut roots: Vec<f64> = Vec::new();
    if c2 != 0.0 {
        let disc = c1 * c1 - 4.0 * c2 * s0;
        if disc >= 0.0 {
            let r = disc.sqrt();
            // The stable pair: q = −(c1 + sign(c1) r)/2, roots q/c2 and s0/q.
            let q = -(c1 + if c1 < 0.0 { -r } else { r }) / 2.0;
            roots.push(q / c2);
            if q != 0.0 {
                roots.push(s0 / q);
            }
        }
    } else if c1 != 0.0 {
        roots.push(-s0 / c1);
    }
    roots.retain(|t| *t > 0.0 && *t < 1.0);
    roots.sort_by(f64::total_cmp);
    cuts.extend(roots);
    cuts.push(1.0);
    let mut total = 0.0;
    for w in cuts.windows(2) {
        let (ha, hb) = (at(w[0]), at(w[1]));
        if ha.norm() <= tiny || hb.norm() <= tiny {
            return None;
        }
        let mut a = signed_angle(&ha, &hb, n);
        let dir = speed((w[0] + w[1]) / 2.0);
        if dir > 0.0 && a < 0.0 {
            a += std::f64::consts::TAU;
        } else if dir < 0.0 && a > 0.0 {
            a -= std::f64::consts::TAU;
        }
        total += a;
    }
    Some(total)
}

/// Number of Bernstein coefficients of a degree-6 triangle.
const SEXTIC: usize = 28;

/// The product table of the projected Jacobian of a quartic net: for every pair `(α, β)` of
/// degree-3 multi-indices (in net order), the net indices of `b_{α+e₁}`, `b_{α+e₂}`,
/// `b_{α+e₃}`, the slot of `γ = α + β` among the degree-6 coefficients and the weight
/// `C(3;α) C(3;β)`; with `1/C(6;γ)` per slot.
struct JacobianTable {
    /// `[b_{α+e₁}, b_{α+e₂}, b_{α+e₃}]` for each degree-3 `α`.
    legs: [[usize; 3]; 10],
    /// `(α, β, slot of α + β, C(3;α) C(3;β))`.
    pairs: Vec<(usize, usize, usize, f64)>,
    /// `1/C(6;γ)` for each slot.
    scale: [f64; SEXTIC],
}

fn jacobian_table() -> &'static JacobianTable {
    static TABLE: OnceLock<JacobianTable> = OnceLock::new();
    TABLE.get_or_init(|| {
        let fact = |k: usize| -> f64 { (1..=k).map(|x| x as f64).product() };
        let multinomial =
            |(i, j, k): (usize, usize, usize)| fact(i + j + k) / (fact(i) * fact(j) * fact(k));
        let cubic = multi_indices(3);
        let legs = std::array::from_fn(|a| {
            let (i, j, k) = cubic[a];
            [
                index(4, i + 1, j, k),
                index(4, i, j + 1, k),
                index(4, i, j, k + 1),
            ]
        });
        let mut pairs = Vec::with_capacity(100);
        for (a, &x) in cubic.iter().enumerate() {
            for (b, &y) in cubic.iter().enumerate() {
                let slot = index(6, x.0 + y.0, x.1 + y.1, x.2 + y.2);
                pairs.push((a, b, slot, multinomial(x) * multinomial(y)));
            }
        }
        let mut scale = [0.0; SEXTIC];
        for (slot, &g) in scale.iter_mut().zip(&multi_indices(6)) {
            *slot = 1.0 / multinomial(g);
        }
        JacobianTable { legs, pairs, scale }
    })
}

/// The Bernstein coefficients (degree 6, in [`multi_indices`] order) of the projected Jacobian
/// `det(π D₁, π D₂)` of a quartic net along the unit normal `n`, `D₁`, `D₂` its derivatives
/// along the domain directions `e₂ − e₁` and `e₃ − e₁` (up to the factor 16).
///
/// `D₁ = 4 Σ_α B³_α Δ¹_α` with `Δ¹_α = b_{α+e₂} − b_{α+e₁}`, likewise `D₂` with `e₃`, and
/// `B³_α B³_β = [C(3;α) C(3;β)/C(6;α+β)] B⁶_{α+β}` (multinomial coefficients), so the
/// coefficient of `B⁶_γ` is `Σ_{α+β=γ} C(3;α) C(3;β) det(Δ¹_α, Δ²_β) / C(6;γ)`, with
/// `det(x, y) = (x × y) · n = y · (n × x)`. All positive: the patch normal is on `n`'s side
/// everywhere on the patch, not only at samples.
pub fn jacobian_coefficients(net: &QuarticNet, n: &Vector3<f64>) -> [f64; SEXTIC] {
    let table = jacobian_table();
    let mut out = unscaled_jacobian(net, n, table);
    for (c, s) in out.iter_mut().zip(&table.scale) {
        *c *= s;
    }
    out
}

/// [`jacobian_coefficients`] times the positive `C(6;γ)`: the same signs, one product fewer.
fn unscaled_jacobian(net: &QuarticNet, n: &Vector3<f64>, table: &JacobianTable) -> [f64; SEXTIC] {
    let rotated: [Vector3<f64>; 10] =
        std::array::from_fn(|a| n.cross(&(net[table.legs[a][1]] - net[table.legs[a][0]])));
    let toward: [Vector3<f64>; 10] =
        std::array::from_fn(|b| net[table.legs[b][2]] - net[table.legs[b][0]]);
    let mut out = [0.0; SEXTIC];
    for &(a, b, slot, w) in &table.pairs {
        out[slot] += w * toward[b].dot(&rotated[a]);
    }
    out
}

/// True when every Bernstein coefficient of the net's projected Jacobian along `n` is positive
/// ([`jacobian_coefficients`]): then it folds nowhere.
fn certified(net: &QuarticNet, n: &Vector3<f64>) -> bool {
    unscaled_jacobian(net, n, jacobian_table())
        .iter()
        .all(|c| *c > 0.0)
}

/// The fold measure's samples of a quartic ([`crate::folds::FOLD_SEGMENTS`] segments a side),
/// prepared once.
fn fold_samples() -> &'static [SampleWeights] {
    static SAMPLES: OnceLock<Vec<SampleWeights>> = OnceLock::new();
    SAMPLES.get_or_init(|| {
        let s = crate::folds::FOLD_SEGMENTS;
        let mut out = Vec::with_capacity((s + 1) * (s + 2) / 2);
        for i in 0..=s {
            for j in 0..=s - i {
                out.push(SampleWeights::new(
                    4,
                    i as f64 / s as f64,
                    j as f64 / s as f64,
                ));
            }
        }
        out
    })
}

/// The smallest cosine between the patch normal and the unit `n` over the fold measure's
/// samples of the macro-patch `nets` ([`crate::folds`]; samples where the patch is singular
/// are skipped), or `None` when every sub-patch's projected Jacobian has positive Bernstein
/// coefficients ([`jacobian_coefficients`]): then no normal anywhere is at 90° or more from
/// `n`, and nothing is sampled.
pub fn worst_cosine(nets: &[QuarticNet; 3], n: &Vector3<f64>) -> Option<f64> {
    let mut worst: Option<f64> = None;
    for net in nets {
        if certified(net, n) {
            continue;
        }
        for w in fold_samples() {
            let d = net_derivatives(net, w);
            let normal = d.du.cross(&d.dv);
            let len = normal.norm();
            if len > 0.0 && len.is_finite() {
                let c = normal.dot(n) / len;
                worst = Some(worst.map_or(c, |x: f64| x.min(c)));
            }
        }
    }
    worst
}

/// Whether the macro-patch `nets` folds over the face with unit normal `n` as the fold measure
/// sees it: `n_patch · n ≤ 0` at a sample ([`worst_cosine`]).
pub fn folds_over(nets: &[QuarticNet; 3], n: &Vector3<f64>) -> bool {
    worst_cosine(nets, n).is_some_and(|c| c <= 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rounding of a few additions and one division per point.
    const EXACT: f64 = 1e-14;

    fn line(a: Point3<f64>, b: Point3<f64>) -> CubicBez3 {
        CubicBez3::new([a, lerp(&a, &b, 1.0 / 3.0), lerp(&a, &b, 2.0 / 3.0), b])
    }

    #[test]
    fn a_flat_face_with_straight_edges_gets_the_flat_patch() {
        let v = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.5),
            Point3::new(0.3, 1.5, 1.0),
        ];
        let edges = [line(v[0], v[1]), line(v[1], v[2]), line(v[2], v[0])];
        let s = Point3::from((v[0].coords + v[1].coords + v[2].coords) / 3.0);
        let nets = fallback_patch(&edges);
        for (e, net) in nets.iter().enumerate() {
            let corners = [v[e], v[(e + 1) % 3], s];
            for k in 0..=4 {
                for i in (0..=4 - k).rev() {
                    let j = 4 - k - i;
                    let want = Point3::from(
                        (corners[0].coords * i as f64
                            + corners[1].coords * j as f64
                            + corners[2].coords * k as f64)
                            / 4.0,
                    );
                    let got = net[index(4, i, j, k)];
                    assert!((got - want).norm() < EXACT, "e {e} ({i},{j},{k})");
                }
            }
        }
    }

    /// Rounding of the Jacobian's 100 products of differences of order one.
    const JACOBIAN: f64 = 1e-12;

    fn curved_edges() -> [CubicBez3; 3] {
        [
            CubicBez3::new([
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(0.4, -0.1, 0.3),
                Point3::new(0.8, 0.1, 0.2),
                Point3::new(1.0, 0.0, 0.0),
            ]),
            CubicBez3::new([
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.9, 0.4, 0.1),
                Point3::new(0.5, 0.9, -0.2),
                Point3::new(0.2, 1.0, 0.0),
            ]),
            CubicBez3::new([
                Point3::new(0.2, 1.0, 0.0),
                Point3::new(0.1, 0.6, 0.4),
                Point3::new(-0.1, 0.3, 0.1),
                Point3::new(0.0, 0.0, 0.0),
            ]),
        ]
    }

    #[test]
    fn the_jacobian_coefficients_are_those_of_the_patch() {
        // Σ_γ c_γ B⁶_γ(u, v, w) times 16 is (D₁ × D₂) · n of the net at (u, v, w).
        let nets = fallback_patch(&curved_edges());
        let n = Vector3::new(0.1, -0.2, 1.0).normalize();
        let fact = |k: usize| -> f64 { (1..=k).map(|x| x as f64).product() };
        for net in &nets {
            let c = jacobian_coefficients(net, &n);
            for (u, v) in [
                (0.2f64, 0.3f64),
                (0.7, 0.1),
                (0.05, 0.05),
                (1.0 / 3.0, 1.0 / 3.0),
            ] {
                let w = 1.0 - u - v;
                let sum: f64 = multi_indices(6)
                    .iter()
                    .zip(&c)
                    .map(|(&(i, j, k), c)| {
                        let b = fact(6) / (fact(i) * fact(j) * fact(k));
                        c * b * u.powi(i as i32) * v.powi(j as i32) * w.powi(k as i32)
                    })
                    .sum();
                let d = net_derivatives(net, &SampleWeights::new(4, u, v));
                // du, dv are along e₁ − e₃, e₂ − e₃: the same cross product as D₁ × D₂.
                let direct = d.du.cross(&d.dv).dot(&n);
                assert!(
                    (16.0 * sum - direct).abs() < JACOBIAN,
                    "{} vs {direct}",
                    16.0 * sum
                );
            }
        }
    }

    #[test]
    fn a_flat_triangle_is_certified_and_forces_nothing() {
        let v = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.5),
            Point3::new(0.3, 1.5, 1.0),
        ];
        let edges = [line(v[0], v[1]), line(v[1], v[2]), line(v[2], v[0])];
        let n = face_normal(&v).expect("a normal");
        assert_eq!(forced_fold(&edges), None);
        assert_eq!(worst_cosine(&fallback_patch(&edges), &n), None);
        // Seen from the other side it is turned over, everywhere.
        let turned = worst_cosine(&fallback_patch(&edges), &-n).expect("not certified");
        assert!((turned + 1.0).abs() < EXACT);
    }

    #[test]
    fn crossed_tangents_and_a_cusp_force_a_fold() {
        let (a, b, c) = (
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
        );
        // Edge 0 leaves a at 135°, past edge 2 arriving along the y axis: the loop turns
        // 0 times (its corner at a turns the wrong way round).
        let crossed = [
            CubicBez3::new([
                a,
                Point3::new(-0.3, 0.3, 0.0),
                Point3::new(0.7, 0.0, 0.0),
                b,
            ]),
            line(b, c),
            line(c, a),
        ];
        assert_eq!(
            forced_fold(&crossed),
            Some(ForcedFold::Turning { turns: 0 })
        );
        // Edge 0 with the hodograph 3(1, 1), 3(−1, 0), 3(1, −1) (scaled to the chord): zero at
        // t = ½, a cusp of the projected curve.
        let s = 1.0;
        let cusp = [
            CubicBez3::new([a, Point3::new(s, s, 0.3), Point3::new(0.0, s, 0.3), b]),
            line(b, c),
            line(c, a),
        ];
        assert_eq!(
            forced_fold(&cusp),
            Some(ForcedFold::StoppedEdge { edge: 0 })
        );
    }

    /// A two-face mesh, face 0 `(0, 1, 2)` beside face 1 `(0, 3, 1)` across the edge 0–1, all in
    /// the plane `z = 0` and seen from `+z`; vertex `i` has the normal `+z` turned by
    /// `turns[i] = (axis angle in the plane, angle)` in degrees. Fitted with `shirman-sequin` on
    /// `chord` curves with each edge's own tangents (`curves::TangentRule::PerEdge`: the curves
    /// this module's rules are about); returns face 0's fallback reason, the folded faces and
    /// face 0's curves.
    fn fit_two(
        corner2: [f64; 2],
        turns: [(f64, f64); 3],
    ) -> (
        Option<crate::fit::FaceFallbackReason>,
        Vec<usize>,
        [CubicBez3; 3],
    ) {
        fit_two_with(corner2, turns, curves::TangentRule::PerEdge)
    }

    /// [`fit_two`] with the tangent rule `tangents`.
    fn fit_two_with(
        corner2: [f64; 2],
        turns: [(f64, f64); 3],
        tangents: curves::TangentRule,
    ) -> (
        Option<crate::fit::FaceFallbackReason>,
        Vec<usize>,
        [CubicBez3; 3],
    ) {
        use crate::mesh::{Mesh, Vertex};
        use nalgebra::{Rotation3, Unit};
        let p = [[0.0, 0.0], [1.0, 0.0], corner2, [0.5, -0.5]];
        let verts = (0..4)
            .map(|i| {
                let (axis, angle) = turns.get(i).copied().unwrap_or((0.0, 0.0));
                let axis = Unit::new_normalize(Vector3::new(
                    axis.to_radians().cos(),
                    axis.to_radians().sin(),
                    0.0,
                ));
                let n = Rotation3::from_axis_angle(&axis, angle.to_radians()) * Vector3::z();
                Vertex::without_curvature(Point3::new(p[i][0], p[i][1], 0.0), n)
            })
            .collect();
        let mesh = Mesh::new(verts, vec![[0, 1, 2], [0, 3, 1]]).expect("a mesh");
        let scheme = crate::scheme::scheme_by_name(
            "shirman-sequin",
            &crate::scheme::SchemeOptions::default(),
        )
        .expect("registered");
        let options = curves::MethodOptions {
            tangents,
            ..curves::MethodOptions::default()
        };
        let chord = curves::method_by_name("chord", &options).expect("registered");
        let fit = crate::fit::fit_scheme(&mesh, scheme.as_ref(), chord.as_ref()).expect("fits");
        let reason = fit
            .face_fallbacks
            .iter()
            .find(|f| f.face == 0)
            .map(|f| f.reason);
        let edges = fit.face_curves(&mesh, 0).expect("curves");
        (reason, crate::folds::measure(&mesh, &fit).folded, edges)
    }

    /// The fallback of face 0 (its reason asserted by the caller) is not among the `folded`
    /// faces of the fit (its neighbour shares the turned normals and may be), the curves do not
    /// force a fold, and the rule this module had before folds on them.
    fn assert_unfolded_where_the_old_rule_folds(folded: &[usize], edges: &[CubicBez3; 3]) {
        assert!(!folded.contains(&0), "{folded:?}");
        assert_eq!(forced_fold(edges), None);
        let v: [Point3<f64>; 3] = std::array::from_fn(|i| edges[i].points[0]);
        let n = face_normal(&v).expect("a normal");
        assert!(!folds_over(&fallback_patch(edges), &n));
        assert!(folds_over(&zero_area_patch(edges, &v), &n));
    }

    #[test]
    fn a_needle_with_a_normal_turned_past_its_face_does_not_fold() {
        // A 2.9° needle; the normal at its far corner (1, 0.05) turned 95° about x, so it
        // points out of the needle's side, past the face.
        let (reason, folded, edges) =
            fit_two([1.0, 0.05], [(0.0, 0.0), (135.0, 30.0), (0.0, 95.0)]);
        assert_eq!(
            reason,
            Some(crate::fit::FaceFallbackReason::Scheme(
                crate::shirman_sequin::SchemeError::NormalAgainstFace { corner: 2 }
            ))
        );
        assert_unfolded_where_the_old_rule_folds(&folded, &edges);
    }

    #[test]
    fn a_cap_with_leaning_normals_does_not_fold() {
        // A cap: the corner (0.5, 0.03) has an angle of 173°. Normals leaning 50° at both ends
        // of the long edge's neighbour corners make the cross vector at corner 2 fold over
        // edge 1: the regular construction refuses the face.
        let (reason, folded, edges) =
            fit_two([0.5, 0.03], [(0.0, 0.0), (45.0, 50.0), (90.0, 50.0)]);
        assert_eq!(
            reason,
            Some(crate::fit::FaceFallbackReason::Scheme(
                crate::shirman_sequin::SchemeError::NoCrossComponent { edge: 1, corner: 2 }
            ))
        );
        assert_unfolded_where_the_old_rule_folds(&folded, &edges);
        // With the tangents chosen from each vertex's star the same cap is fitted regularly,
        // and does not fold.
        let (reason, folded, _) = fit_two_with(
            [0.5, 0.03],
            [(0.0, 0.0), (45.0, 50.0), (90.0, 50.0)],
            curves::TangentRule::Star,
        );
        assert_eq!(reason, None);
        assert!(!folded.contains(&0), "{folded:?}");
        // And with the normal at corner 1 turned 95°, past the face.
        let (reason, folded, edges) = fit_two([0.5, 0.03], [(0.0, 0.0), (45.0, 95.0), (0.0, 0.0)]);
        assert_eq!(
            reason,
            Some(crate::fit::FaceFallbackReason::Scheme(
                crate::shirman_sequin::SchemeError::NormalAgainstFace { corner: 1 }
            ))
        );
        // A normal past the face turns its edges' tangents by up to the clamp angle
        // (`curves::problem::MAX_TANGENT_ANGLE`, 80°): on this cap the two edge curves at
        // corner 1 then cross, and no patch on them avoids the fold — it is forced, and
        // reported as such.
        if forced_fold(&edges).is_none() {
            assert_unfolded_where_the_old_rule_folds(&folded, &edges);
        } else {
            assert!(folded.contains(&0), "{folded:?}");
        }
    }

    #[test]
    fn the_patch_meets_the_curves_and_itself() {
        let c0 = CubicBez3::new([
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(0.4, -0.1, 0.3),
            Point3::new(0.8, 0.1, 0.2),
            Point3::new(1.0, 0.0, 0.0),
        ]);
        let c1 = CubicBez3::new([
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.9, 0.4, 0.1),
            Point3::new(0.5, 0.9, -0.2),
            Point3::new(0.2, 1.0, 0.0),
        ]);
        let c2 = CubicBez3::new([
            Point3::new(0.2, 1.0, 0.0),
            Point3::new(0.1, 0.6, 0.4),
            Point3::new(-0.1, 0.3, 0.1),
            Point3::new(0.0, 0.0, 0.0),
        ]);
        let edges = [c0, c1, c2];
        let nets = fallback_patch(&edges);
        for e in 0..3 {
            let q = edges[e].elevate().points;
            assert_eq!(&nets[e][..5], &q[..], "row 0 is the exterior curve");
            // Interior boundary V_{e+1} → S: sub-patch e's right side equals sub-patch e+1's
            // left side (the points b_{0,4−k,k} and b_{4−k,0,k}).
            let next = &nets[(e + 1) % 3];
            for k in 0..=4 {
                assert_eq!(nets[e][index(4, 0, 4 - k, k)], next[index(4, 4 - k, 0, k)]);
            }
        }
    }
}

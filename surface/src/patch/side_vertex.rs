#![allow(clippy::needless_range_loop)] // corners, edges and operators are indexed 0..3 together
//! Side-vertex interpolants over cubic boundary curves: Nielson's transfinite, visually
//! continuous triangular interpolant (1987) and its discrete counterpart, evaluated with exact
//! first and second derivatives ([`crate::patch::SampledForm`]).
//!
//! # Data of one face
//!
//! The face `V_0, V_1, V_2` (counter-clockwise), its three edge curves `E_l` from `V_l` to
//! `V_{l+1}` (cubic Bézier, control points `c^l_0 … c^l_3`, from any curve method) and the unit
//! vertex normals `N_l`. Stored as 15 points: the twelve control points edge after edge, then
//! the three normals (as points). Indices are taken mod 3 throughout, and for operator `i` we
//! write `j = i + 1`, `k = i + 2`.
//!
//! # Side-vertex operators (Nielson 1987, §2)
//!
//! A point of the face with barycentric coordinates `b` lies on the segment from `V_i` to the
//! point `Q_i(s) = (1 − s) V_j + s V_k` of the opposite side, at ray parameter
//! `u = 1 − b_i` and `s = b_k / (b_j + b_k)`. Operator `S_i` is the cubic Hermite interpolant
//! along that ray,
//!
//! `S_i(u, s) = h_0(u) V_i + h_1(u) E(s) + h_2(u) T_0(s) + h_3(u) T_1(s)`,
//!
//! with `E = E_j` the opposite curve and `h` the cubic Hermite basis on `[0, 1]`. The ray's
//! direction in the domain is `(1 − s)(V_j − V_i) + s (V_k − V_i)`, so its end derivatives are
//!
//! * at `V_i`, from the two curves leaving it: `T_0(s) = (1 − s) D_{ij} + s D_{ik}` with
//!   `D_{ij} = 3(c^i_1 − c^i_0)` and `D_{ik} = −3(c^k_3 − c^k_2)`;
//! * at the side, the derivative across it: `T_1(s) = X(s) + (s − ½) E'(s)`, where `X(s)` is
//!   the surface's derivative at `E(s)` in the domain direction of the median,
//!   `M − V_i = ½(V_j − V_i) + ½(V_k − V_i)` (`M` the side's midpoint): the ray direction is
//!   the median direction plus `(s − ½)(V_k − V_j)`.
//!
//! At the ends of the side `X` is fixed by the curves: `X(0) = 3(c^i_3 − c^i_2) + ½E'(0)`
//! (at `V_j`: the end tangent of the curve from `V_i`, the derivative towards `V_j − V_i`, plus
//! half the side's tangent) and `X(1) = −½E'(1) − 3(c^k_1 − c^k_0)` (at `V_k`:
//! `M − V_i = (V_k − V_i) − ½(V_k − V_j)`). With these ends each operator reproduces all three
//! boundary curves: along `V_i V_j` (`s = 0`) it is the Hermite cubic with the end tangents of
//! `E_i`, which is `E_i`; along `V_i V_k` (`s = 1`) the reversed `E_k`; along the opposite side
//! (`u = 1`) it is `E(s)`.
//!
//! The median is the one transversal direction that treats `V_j` and `V_k` alike: reversing the
//! face (corners `i, k, j`, the side traversed backwards, `s → 1 − s`) leaves `X` and `T_1`
//! unchanged, so the surface does not depend on the face's orientation (a property test). An
//! interpolant of the derivative towards `V_j − V_i` instead, the first version of this module,
//! differs from its mirror image by `½(E'(s) − (1 − s)E'(0) − sE'(1))`, up to 2e-3 on unit
//! data.

//! # Cross-boundary data
//!
//! * **Nielson (transfinite):** the tangent plane along the side is given by a normal field
//!   that depends on the side alone: `m(s)` is the part of `(1 − s) N_j + s N_k` orthogonal
//!   to `E'(s)`, and `X(s)` is the linear interpolant `(1 − s) X(0) + s X(1)` projected on
//!   `m(s)⊥`. The face across the side computes the same `m` (the same normals and curve,
//!   traversed backwards), and both faces' tangent planes along the side are
//!   `span(E'(s), X(s)) = m(s)⊥`: G1 across every edge, up to rounding. At the ends the
//!   projection changes nothing (the curve tangents lie in the vertex tangent planes), so the
//!   boundary curves are still reproduced. Where `m` vanishes (normals along the curve, or
//!   opposite) the projection is skipped.
//! * **Discrete:** `X(s)` is the linear interpolant alone, as in a finite-dimensional
//!   ("discrete") side-vertex scheme, which uses nothing but the data at the vertices. The two
//!   faces on an edge then agree in position and, at the vertices, in tangent plane, but not in
//!   between: C0, with the normal jump measured.
//!
//! # Blending
//!
//! `N(b) = Σ_i W_i(b) S_i(b)` with `W_i = (b_j b_k)² / Σ_l (b_{l+1} b_{l+2})²`. On the side
//! `b_i = 0`, `W_i = 1` and the other two weights vanish with their first derivatives (they carry
//! the factor `b_i²`); since every operator interpolates the side, `Σ_l ∇W_l S_l = 0` there and
//! `∇N = ∇S_i`: the blend keeps operator `i`'s position and tangent plane along side `i`.
//! At a vertex the weights are `0/0`; the blend's limit there is the vertex with the tangent
//! plane spanned by the two curve tangents, which is what the evaluation returns (its second
//! derivatives are taken a small step inside, [`VERTEX_NUDGE`]).
//!
//! # Derivatives
//!
//! Everything that does not depend on the data (the Hermite basis at `u`, the cubic Bernstein
//! basis at `s` with three derivatives, the first and second partials of `u`, `s` and `W_i` in
//! the patch's `(λ_0, λ_1)`) is computed once per sample point with second-order jets; the
//! evaluation then differentiates `S_i` in `(u, s)` exactly (the projection by one-variable
//! second-order jets along the side) and applies the chain rule
//! `∂_a S = S_u u_a + S_s s_a`,
//! `∂_ab S = S_uu u_a u_b + S_us (u_a s_b + u_b s_a) + S_ss s_a s_b + S_u u_ab + S_s s_ab`,
//! then Leibniz's rule for the blend. The tests compare every partial with finite differences
//! of the positions.

use nalgebra::{Point3, Vector3};

use crate::beztri::Derivatives;
use crate::patch::SampledForm;
use crate::scheme::Bary;

/// Points stored per patch: twelve curve control points and three normals (module docs).
pub const POINTS: usize = 15;

/// How far towards the centre (as a fraction of the way) the second derivatives at a vertex
/// are taken: the blend is `0/0` at the vertex itself. Small enough that the curvature there
/// is the limit along the bisector to about this relative size, large enough that the
/// weights are far from underflow (`W ~ ε²`).
pub const VERTEX_NUDGE: f64 = 1e-5;

/// Below this ratio `|m|² / |n|²` the normal field along a side is taken as undefined and the
/// projection skipped (normals along the curve or opposite each other: degenerate data).
const DEGENERATE_NORMAL: f64 = 1e-24;

/// Writes a face's data in the stored order (module docs): the edge curves, then the unit
/// normals (zero normals make the transfinite form fall back to the discrete data, which is
/// what a face's C0 fallback uses).
pub fn write_face(
    edges: &[curves::CubicBez3; 3],
    normals: [Vector3<f64>; 3],
    out: &mut [Point3<f64>],
) {
    for (l, e) in edges.iter().enumerate() {
        out[4 * l..4 * l + 4].copy_from_slice(&e.points);
    }
    for (l, n) in normals.iter().enumerate() {
        out[12 + l] = Point3::from(n.try_normalize(0.0).unwrap_or_else(Vector3::zeros));
    }
}

/// One face's data written by `form`'s scheme (`nielson`, `discrete-side-vertex`): the face is
/// refused where a corner is folded ([`crate::scheme::folded_corner`]) or the transversal turns
/// over an edge ([`folded_edge`]); otherwise its curves and normals are written.
pub fn build_face(
    form: &SideVertexForm,
    input: &crate::scheme::FaceInput<'_>,
    out: &mut [Point3<f64>],
) -> Result<(), crate::fit::FaceFallbackReason> {
    use crate::fit::FaceFallbackReason;
    if let Some(corner) = crate::scheme::folded_corner(input) {
        return Err(FaceFallbackReason::Folded { corner });
    }
    write_face(input.edges, input.vertices.map(|v| v.n), out);
    match folded_edge(out, form.cross) {
        Some(edge) => Err(FaceFallbackReason::FoldedEdge { edge }),
        None => Ok(()),
    }
}

/// Which cross-boundary data (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CrossBoundary {
    /// Nielson's transfinite data: the projected linear interpolant (G1).
    Transfinite,
    /// The linear interpolant of the vertex data (C0).
    Discrete,
}

/// The side-vertex patch form.
#[derive(Clone, Copy, Debug)]
pub struct SideVertexForm {
    /// Its cross-boundary data.
    pub cross: CrossBoundary,
}

/// Nielson's transfinite form.
pub static NIELSON: SideVertexForm = SideVertexForm {
    cross: CrossBoundary::Transfinite,
};

/// The discrete form.
pub static DISCRETE: SideVertexForm = SideVertexForm {
    cross: CrossBoundary::Discrete,
};

// ---------------------------------------------------------------------------------------------
// Second-order jets in the two local parameters (preparation only).

/// A scalar with its gradient and Hessian `[xx, xy, yy]` in `(λ_0, λ_1)`.
#[derive(Clone, Copy, Debug)]
struct J2 {
    v: f64,
    g: [f64; 2],
    h: [f64; 3],
}

impl J2 {
    fn constant(v: f64) -> J2 {
        J2 {
            v,
            g: [0.0; 2],
            h: [0.0; 3],
        }
    }

    /// The three barycentric coordinates at `(λ_0, λ_1)`, `λ_2 = 1 − λ_0 − λ_1`.
    fn bary(b: Bary) -> [J2; 3] {
        [
            J2 {
                v: b[0],
                g: [1.0, 0.0],
                h: [0.0; 3],
            },
            J2 {
                v: b[1],
                g: [0.0, 1.0],
                h: [0.0; 3],
            },
            J2 {
                v: b[2],
                g: [-1.0, -1.0],
                h: [0.0; 3],
            },
        ]
    }

    fn add(self, o: J2) -> J2 {
        J2 {
            v: self.v + o.v,
            g: [self.g[0] + o.g[0], self.g[1] + o.g[1]],
            h: [self.h[0] + o.h[0], self.h[1] + o.h[1], self.h[2] + o.h[2]],
        }
    }

    fn sub(self, o: J2) -> J2 {
        self.add(o.scale(-1.0))
    }

    fn scale(self, c: f64) -> J2 {
        J2 {
            v: self.v * c,
            g: self.g.map(|x| x * c),
            h: self.h.map(|x| x * c),
        }
    }

    fn mul(self, o: J2) -> J2 {
        let (a, b) = (self, o);
        J2 {
            v: a.v * b.v,
            g: [a.g[0] * b.v + a.v * b.g[0], a.g[1] * b.v + a.v * b.g[1]],
            h: [
                a.h[0] * b.v + 2.0 * a.g[0] * b.g[0] + a.v * b.h[0],
                a.h[1] * b.v + a.g[0] * b.g[1] + a.g[1] * b.g[0] + a.v * b.h[1],
                a.h[2] * b.v + 2.0 * a.g[1] * b.g[1] + a.v * b.h[2],
            ],
        }
    }

    /// `self / o` (from `self = r o`: `r' = (a' − r o')/o`,
    /// `r'' = (a'' − r' o'ᵀ − o' r'ᵀ − r o'')/o`).
    fn div(self, o: J2) -> J2 {
        let (a, b) = (self, o);
        let v = a.v / b.v;
        let g = [(a.g[0] - v * b.g[0]) / b.v, (a.g[1] - v * b.g[1]) / b.v];
        J2 {
            v,
            g,
            h: [
                (a.h[0] - 2.0 * g[0] * b.g[0] - v * b.h[0]) / b.v,
                (a.h[1] - g[0] * b.g[1] - g[1] * b.g[0] - v * b.h[1]) / b.v,
                (a.h[2] - 2.0 * g[1] * b.g[1] - v * b.h[2]) / b.v,
            ],
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Preparation.

/// Numbers per operator in a prepared point: Hermite basis `h, h', h''` (12), cubic Bernstein
/// `B, B', B'', B'''` (16), `u_a, u_ab, s_a, s_ab` (10), `W, W_a, W_ab` (6).
const PER_OPERATOR: usize = 44;
/// Numbers of a prepared regular point: a tag and three operators.
const REGULAR: usize = 1 + 3 * PER_OPERATOR;

/// Cubic Hermite basis on `[0, 1]` and its first two derivatives at `u`:
/// `h_0 = 2u³ − 3u² + 1`, `h_1 = −2u³ + 3u²`, `h_2 = u³ − 2u² + u`, `h_3 = u³ − u²`.
fn hermite(u: f64) -> [[f64; 4]; 3] {
    let (u2, u3) = (u * u, u * u * u);
    [
        [
            2.0 * u3 - 3.0 * u2 + 1.0,
            -2.0 * u3 + 3.0 * u2,
            u3 - 2.0 * u2 + u,
            u3 - u2,
        ],
        [
            6.0 * u2 - 6.0 * u,
            -6.0 * u2 + 6.0 * u,
            3.0 * u2 - 4.0 * u + 1.0,
            3.0 * u2 - 2.0 * u,
        ],
        [
            12.0 * u - 6.0,
            -12.0 * u + 6.0,
            6.0 * u - 4.0,
            6.0 * u - 2.0,
        ],
    ]
}

/// Cubic Bernstein basis at `s` and its first three derivatives (expanded in powers of `s`).
fn bernstein(s: f64) -> [[f64; 4]; 4] {
    let t = 1.0 - s;
    [
        [t * t * t, 3.0 * s * t * t, 3.0 * s * s * t, s * s * s],
        [
            -3.0 * t * t,
            3.0 - 12.0 * s + 9.0 * s * s,
            6.0 * s - 9.0 * s * s,
            3.0 * s * s,
        ],
        [6.0 * t, -12.0 + 18.0 * s, 6.0 - 18.0 * s, 6.0 * s],
        [-6.0, 18.0, -18.0, 6.0],
    ]
}

/// Coordinates this close to zero count as zero when deciding whether a point is a vertex
/// (lattice points are exact; this absorbs the rounding of a sub-triangle's inverse).
const ZERO_COORD: f64 = 1e-14;

/// Prepares a point that is not a vertex.
fn prepare_regular(b: Bary, out: &mut Vec<f64>) {
    let l = J2::bary(b);
    let prods: [J2; 3] = std::array::from_fn(|i| {
        let p = l[(i + 1) % 3].mul(l[(i + 2) % 3]);
        p.mul(p)
    });
    let sum = prods[0].add(prods[1]).add(prods[2]);
    out.push(0.0);
    for i in 0..3 {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        let u = J2::constant(1.0).sub(l[i]);
        let s = l[k].div(l[j].add(l[k]));
        let w = prods[i].div(sum);
        for row in hermite(u.v) {
            out.extend_from_slice(&row);
        }
        for row in bernstein(s.v) {
            out.extend_from_slice(&row);
        }
        for x in [u, s] {
            out.extend_from_slice(&x.g);
            out.extend_from_slice(&x.h);
        }
        out.push(w.v);
        out.extend_from_slice(&w.g);
        out.extend_from_slice(&w.h);
    }
}

impl SampledForm for SideVertexForm {
    fn name(&self) -> &'static str {
        match self.cross {
            CrossBoundary::Transfinite => "nielson side-vertex",
            CrossBoundary::Discrete => "discrete side-vertex",
        }
    }

    fn points_per_patch(&self) -> usize {
        POINTS
    }

    /// The last three stored points are the unit normals.
    fn is_direction(&self, k: usize) -> bool {
        (12..POINTS).contains(&k)
    }

    /// A regular point: tag 0 and three operators. Vertex `i`: tag `1 + i`, then the regular
    /// point [`VERTEX_NUDGE`] of the way towards the centre.
    fn prepare(&self, local: Bary) -> Vec<f64> {
        let mut out = Vec::with_capacity(1 + REGULAR);
        let zero = local.map(|x| x.abs() < ZERO_COORD);
        if let Some(i) = (0..3).find(|&i| zero[(i + 1) % 3] && zero[(i + 2) % 3]) {
            out.push(1.0 + i as f64);
            let third = 1.0 / 3.0;
            let mut e = [0.0; 3];
            e[i] = 1.0;
            prepare_regular(e.map(|x| x + VERTEX_NUDGE * (third - x)), &mut out);
        } else {
            prepare_regular(local, &mut out);
        }
        out
    }

    fn eval(&self, points: &[Point3<f64>], prepared: &[f64]) -> Derivatives {
        let Some(data) = FaceData::new(points) else {
            return Derivatives::nan();
        };
        match prepared.first() {
            Some(&t) if t >= 1.0 => {
                let i = (t as usize - 1).min(2);
                let inner = eval_regular(&data, self.cross, &prepared[1..]);
                vertex(&data, i, inner)
            }
            _ => eval_regular(&data, self.cross, prepared),
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Evaluation.

/// One face's data read from its 15 points.
struct FaceData {
    c: [[Vector3<f64>; 4]; 3],
    n: [Vector3<f64>; 3],
}

impl FaceData {
    fn new(points: &[Point3<f64>]) -> Option<FaceData> {
        if points.len() < POINTS {
            return None;
        }
        Some(FaceData {
            c: std::array::from_fn(|l| std::array::from_fn(|m| points[4 * l + m].coords)),
            n: std::array::from_fn(|l| points[12 + l].coords),
        })
    }

    /// `D_{i,i+1}`: the derivative at `V_i` towards `V_{i+1}`.
    fn d_next(&self, i: usize) -> Vector3<f64> {
        (self.c[i][1] - self.c[i][0]) * 3.0
    }

    /// `D_{i,i+2}`: the derivative at `V_i` towards `V_{i+2}`.
    fn d_prev(&self, i: usize) -> Vector3<f64> {
        (self.c[(i + 2) % 3][3] - self.c[(i + 2) % 3][2]) * -3.0
    }
}

impl Derivatives {
    /// Every component NaN (data that cannot be evaluated, or a point prepared for another
    /// layout): visible downstream rather than a plausible wrong number.
    pub(crate) fn nan() -> Derivatives {
        let n = Vector3::repeat(f64::NAN);
        Derivatives {
            p: Point3::from(n),
            du: n,
            dv: n,
            duu: n,
            duv: n,
            dvv: n,
        }
    }
}

/// A vector with its first two derivatives along a side.
#[derive(Clone, Copy)]
struct V1 {
    v: Vector3<f64>,
    d: Vector3<f64>,
    dd: Vector3<f64>,
}

/// A scalar with its first two derivatives along a side.
#[derive(Clone, Copy)]
struct S1 {
    v: f64,
    d: f64,
    dd: f64,
}

fn dot1(a: &V1, b: &V1) -> S1 {
    S1 {
        v: a.v.dot(&b.v),
        d: a.d.dot(&b.v) + a.v.dot(&b.d),
        dd: a.dd.dot(&b.v) + 2.0 * a.d.dot(&b.d) + a.v.dot(&b.dd),
    }
}

fn div1(a: S1, b: S1) -> S1 {
    let v = a.v / b.v;
    let d = (a.d - v * b.d) / b.v;
    S1 {
        v,
        d,
        dd: (a.dd - 2.0 * d * b.d - v * b.dd) / b.v,
    }
}

/// `a − t b`.
fn sub_scaled1(a: &V1, t: S1, b: &V1) -> V1 {
    V1 {
        v: a.v - b.v * t.v,
        d: a.d - b.d * t.v - b.v * t.d,
        dd: a.dd - b.dd * t.v - b.d * (2.0 * t.d) - b.v * t.dd,
    }
}

/// The transversal `X(s)` (the derivative along the median direction) with its derivatives
/// along side `j` of operator `i` (module docs).
fn transversal(data: &FaceData, cross: CrossBoundary, i: usize, s: f64, e1: &V1) -> V1 {
    let (j, k) = ((i + 1) % 3, (i + 2) % 3);
    // E'(0) = 3(c1 − c0), E'(1) = 3(c3 − c2) of the side's curve.
    let (e0, e1end) = (
        (data.c[j][1] - data.c[j][0]) * 3.0,
        (data.c[j][3] - data.c[j][2]) * 3.0,
    );
    let x0 = (data.c[i][3] - data.c[i][2]) * 3.0 + e0 * 0.5;
    let x1 = e1end * -0.5 - (data.c[k][1] - data.c[k][0]) * 3.0;
    let xl = V1 {
        v: x0 + (x1 - x0) * s,
        d: x1 - x0,
        dd: Vector3::zeros(),
    };
    if cross == CrossBoundary::Discrete {
        return xl;
    }
    let nr = V1 {
        v: data.n[j] + (data.n[k] - data.n[j]) * s,
        d: data.n[k] - data.n[j],
        dd: Vector3::zeros(),
    };
    let ee = dot1(e1, e1);
    if ee.v <= 0.0 || !ee.v.is_finite() {
        return xl;
    }
    let m = sub_scaled1(&nr, div1(dot1(&nr, e1), ee), e1);
    let mm = dot1(&m, &m);
    if mm.v <= DEGENERATE_NORMAL * nr.v.norm_squared() || mm.v == 0.0 {
        return xl;
    }
    sub_scaled1(&xl, div1(dot1(&xl, &m), mm), &m)
}

/// Where the transversal is tested for a fold along each edge (the ends are the corners,
/// tested by [`crate::scheme::folded_corner`]).
const FOLD_SAMPLES: [f64; 3] = [0.25, 0.5, 0.75];

/// The first face edge `l` (from `V_l` to `V_{l+1}`) along which the cross-boundary
/// derivative turns to the wrong side: for a counter-clockwise face the edge tangent `E'`,
/// the outward transversal `X` and the interpolated normal `n` satisfy `(E' × X) · n < 0`;
/// where that fails the patch folds over the edge (its normal turns by π there, as on coarse
/// meshes whose vertex normals differ by nearly a right angle across an edge). Tested at
/// [`FOLD_SAMPLES`]; `points` are one face's stored data.
pub fn folded_edge(points: &[Point3<f64>], cross: CrossBoundary) -> Option<usize> {
    let data = FaceData::new(points)?;
    for i in 0..3 {
        let j = (i + 1) % 3;
        let k = (i + 2) % 3;
        for s in FOLD_SAMPLES {
            let b = bernstein(s);
            let e: [Vector3<f64>; 4] = std::array::from_fn(|r| {
                (0..4).fold(Vector3::zeros(), |acc, m| acc + data.c[j][m] * b[r][m])
            });
            let e1 = V1 {
                v: e[1],
                d: e[2],
                dd: e[3],
            };
            let x = transversal(&data, cross, i, s, &e1);
            let n = data.n[j] * (1.0 - s) + data.n[k] * s;
            if e[1].cross(&x.v).dot(&n).partial_cmp(&0.0) != Some(std::cmp::Ordering::Less) {
                return Some(j);
            }
        }
    }
    None
}

/// Operator `i`'s position and partials in `(u, s)`:
/// `[S, S_u, S_s, S_uu, S_us, S_ss]`.
fn operator(data: &FaceData, cross: CrossBoundary, i: usize, p: &[f64]) -> [Vector3<f64>; 6] {
    let j = (i + 1) % 3;
    let h = |r: usize, c: usize| p[4 * r + c];
    let bern = |r: usize, c: usize| p[12 + 4 * r + c];
    // s = Σ (m/3) B_m(s) (linear precision of the Bernstein basis).
    let s = bern(0, 1) / 3.0 + bern(0, 2) * (2.0 / 3.0) + bern(0, 3);
    let curve = &data.c[j];
    let e: [Vector3<f64>; 4] = std::array::from_fn(|r| {
        curve[0] * bern(r, 0)
            + curve[1] * bern(r, 1)
            + curve[2] * bern(r, 2)
            + curve[3] * bern(r, 3)
    });
    let e1 = V1 {
        v: e[1],
        d: e[2],
        dd: e[3],
    };
    let x = transversal(data, cross, i, s, &e1);
    // T1 = X + (s − ½) E'.
    let off = s - 0.5;
    let t1 = [
        x.v + e[1] * off,
        x.d + e[1] + e[2] * off,
        x.dd + e[2] * 2.0 + e[3] * off,
    ];
    let (dij, dik) = (data.d_next(i), data.d_prev(i));
    let t0 = [dij + (dik - dij) * s, dik - dij];
    let vi = data.c[i][0];
    let at = |r: usize| vi * h(r, 0) + e[0] * h(r, 1) + t0[0] * h(r, 2) + t1[0] * h(r, 3);
    let along = |r: usize, q: usize| e[q] * h(r, 1) + t1[q] * h(r, 3);
    [
        at(0),
        at(1),
        along(0, 1) + t0[1] * h(0, 2),
        at(2),
        along(1, 1) + t0[1] * h(1, 2),
        e[2] * h(0, 1) + t1[2] * h(0, 3),
    ]
}

/// The blend at a prepared regular point (tag 0 first).
fn eval_regular(data: &FaceData, cross: CrossBoundary, prepared: &[f64]) -> Derivatives {
    if prepared.len() < REGULAR {
        return Derivatives::nan();
    }
    let mut acc = [Vector3::zeros(); 6];
    for i in 0..3 {
        let p = &prepared[1 + i * PER_OPERATOR..1 + (i + 1) * PER_OPERATOR];
        let q = &p[28..];
        let (ua, uab, sa, sab) = (
            [q[0], q[1]],
            [q[2], q[3], q[4]],
            [q[5], q[6]],
            [q[7], q[8], q[9]],
        );
        let (w, wa, wab) = (q[10], [q[11], q[12]], [q[13], q[14], q[15]]);
        if w == 0.0 && wa == [0.0; 2] && wab == [0.0; 3] {
            continue;
        }
        let [v, su, ss, suu, sus, sss] = operator(data, cross, i, p);
        let d: [Vector3<f64>; 2] = std::array::from_fn(|a| su * ua[a] + ss * sa[a]);
        let dd = |a: usize, b: usize, ab: usize| {
            suu * (ua[a] * ua[b])
                + sus * (ua[a] * sa[b] + ua[b] * sa[a])
                + sss * (sa[a] * sa[b])
                + su * uab[ab]
                + ss * sab[ab]
        };
        let second = [dd(0, 0, 0), dd(0, 1, 1), dd(1, 1, 2)];
        acc[0] += v * w;
        acc[1] += v * wa[0] + d[0] * w;
        acc[2] += v * wa[1] + d[1] * w;
        acc[3] += v * wab[0] + d[0] * (2.0 * wa[0]) + second[0] * w;
        acc[4] += v * wab[1] + d[0] * wa[1] + d[1] * wa[0] + second[1] * w;
        acc[5] += v * wab[2] + d[1] * (2.0 * wa[1]) + second[2] * w;
    }
    Derivatives::from(acc)
}

/// Vertex `i`: the vertex, the tangents of its two curves in `(λ_0, λ_1)` (the direction
/// `e_0 − e_2` is `(e_0 − e_i) − (e_2 − e_i)`), second partials from `inner` (module docs).
fn vertex(data: &FaceData, i: usize, inner: Derivatives) -> Derivatives {
    // Derivative at V_i in the domain direction towards corner c.
    let towards = |c: usize| {
        if c == i {
            Vector3::zeros()
        } else if c == (i + 1) % 3 {
            data.d_next(i)
        } else {
            data.d_prev(i)
        }
    };
    Derivatives {
        p: Point3::from(data.c[i][0]),
        du: towards(0) - towards(2),
        dv: towards(1) - towards(2),
        ..inner
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Finite-difference step in the local parameters.
    const H: f64 = 1e-5;
    /// Central differences of order h²: agreement to about 1e-8 of the magnitudes here.
    const FD_TOL: f64 = 1e-6;

    fn sample_face() -> Vec<Point3<f64>> {
        // A curved face: corners on a sphere-like cap with perturbed inner control points.
        let v = [
            Vector3::new(1.0, 0.0, 0.1),
            Vector3::new(0.0, 1.0, 0.2),
            Vector3::new(-0.7, -0.6, 0.0),
        ];
        let n = [
            Vector3::new(0.3, 0.1, 1.0).normalize(),
            Vector3::new(-0.1, 0.35, 1.0).normalize(),
            Vector3::new(-0.2, -0.25, 1.0).normalize(),
        ];
        let mut pts = Vec::new();
        for l in 0..3 {
            let (a, b) = (v[l], v[(l + 1) % 3]);
            let chord = b - a;
            let ta = (chord - n[l] * n[l].dot(&chord)) / 3.0;
            let tb = (chord - n[(l + 1) % 3] * n[(l + 1) % 3].dot(&chord)) / 3.0;
            for p in [a, a + ta * 1.1, b - tb * 0.9, b] {
                pts.push(Point3::from(p));
            }
        }
        for x in n {
            pts.push(Point3::from(x));
        }
        pts
    }

    fn at(form: &SideVertexForm, pts: &[Point3<f64>], u: f64, v: f64) -> Derivatives {
        form.eval(pts, &form.prepare([u, v, 1.0 - u - v]))
    }

    #[test]
    fn partials_match_finite_differences() {
        let pts = sample_face();
        for form in [&NIELSON, &DISCRETE] {
            for &(u, v) in &[
                (0.2, 0.3),
                (0.6, 0.1),
                (0.1, 0.1),
                (0.45, 0.45),
                (0.33, 0.5),
            ] {
                let d = at(form, &pts, u, v);
                let pu = (at(form, &pts, u + H, v).p - at(form, &pts, u - H, v).p) / (2.0 * H);
                let pv = (at(form, &pts, u, v + H).p - at(form, &pts, u, v - H).p) / (2.0 * H);
                assert!(
                    (pu - d.du).norm() < FD_TOL,
                    "{:?} du {pu} {}",
                    form.cross,
                    d.du
                );
                assert!((pv - d.dv).norm() < FD_TOL, "dv");
                let duu = (at(form, &pts, u + H, v).du - at(form, &pts, u - H, v).du) / (2.0 * H);
                let duv = (at(form, &pts, u, v + H).du - at(form, &pts, u, v - H).du) / (2.0 * H);
                let dvv = (at(form, &pts, u, v + H).dv - at(form, &pts, u, v - H).dv) / (2.0 * H);
                assert!((duu - d.duu).norm() < FD_TOL, "duu {duu} {}", d.duu);
                assert!((duv - d.duv).norm() < FD_TOL, "duv");
                assert!((dvv - d.dvv).norm() < FD_TOL, "dvv");
            }
        }
    }
}

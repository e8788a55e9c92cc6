#![allow(clippy::needless_range_loop)] // corners, edges and jets are indexed 0..3 together
//! `gregory-charrot`: a convex combination of three corner interpolants after Gregory and
//! Charrot ("A C1 triangular interpolation patch for computer-aided geometric design",
//! *Computer Graphics and Image Processing* 13 (1980) 80–87), as the original testbed's fitters
//! (UW 1990) use it: over the cubic edge curves of any curve method, with Chiyokura–Kimura
//! cross-boundary data per edge, G1 across edges. Not a polynomial: the patch is evaluated by its
//! own rule ([`GREGORY_CHARROT`], a [`SampledForm`]) with exact first and second derivatives,
//! stored as Nielson's patches are (the twelve curve control points, then the three unit
//! normals: [`crate::side_vertex::write_face`]).
//!
//! The variant here is derived below from the paper's idea (corner interpolants that each match
//! the data of the two sides at their corner, blended by weights that vanish to first order on
//! the opposite side); the details of the sources are partly unverified, so this is the
//! workbench's reading, not a copy of theirs.
//!
//! # Edge data
//!
//! Face `V_0, V_1, V_2` (counter-clockwise), barycentrics `b`, edge `l` from `V_l` to `V_{l+1}`
//! the cubic `E_l(s)` (`s = b_{l+1}` along it), and per edge a transversal `X_l(s)`: the
//! surface's derivative in the domain direction `d_l = e_{l+2} − ½(e_l + e_{l+1})` (from the
//! edge's midpoint towards the opposite corner, the one direction that treats both ends alike).
//! Together with `E_l'` (the derivative along `e_{l+1} − e_l`) it fixes the derivative along
//! every domain direction at the edge. Its ends are fixed by the curves: at `V_l`,
//! `d_l = (e_{l+2} − e_l) − ½(e_{l+1} − e_l)`, so `X_l(0) = D_{l,l+2} − ½E_l'(0)`; at `V_{l+1}`,
//! `X_l(1) = D_{l+1,l+2} + ½E_l'(1)`, with `D_{a,c}` the derivative at `V_a` along the curve
//! towards `V_c` (`3(c_1 − c_0)` of the curve leaving, `−3(c_3 − c_2)` of the one arriving).
//!
//! **Chiyokura–Kimura in between.** With `A_0 = unit(n_l × E_l'(0))`,
//! `A_1 = unit(n_{l+1} × E_l'(1))` (in the end tangent planes, across the curve, into the face;
//! the neighbour, travelling the edge the other way, gets `−A`), decompose
//! `X_l(0) = k_0 A_0 + h_0 E_l'(0)` and `X_l(1) = k_1 A_1 + h_1 E_l'(1)`, and take
//! `X_l(s) = k(s) A(s) + h(s) E_l'(s)` with `k, h, A` linear in `s`. The tangent plane along the
//! edge is `span(A(s), E_l'(s))`, which only the edge's curve and end normals determine: the two
//! faces on the edge share it, G1 (`k_0, k_1 > 0`, else the face is refused as folded over the
//! edge). `X_l` is a cubic in `s`; its derivatives are `X' = k'A + kA' + h'E' + hE''` and
//! `X'' = 2k'A' + 2h'E'' + hE'''`. A face with zero normals (the fallback) takes the linear
//! interpolant of the ends instead: C0.
//!
//! # Corner interpolants
//!
//! At corner `i` take `x = b_{i+1}`, `y = b_{i+2}` (`V_i` at the origin). Side `y = 0` is edge
//! `i` (`s = x`), side `x = 0` is edge `i + 2` (`s = 1 − y`). The two first-order Taylor
//! projectors away from those sides,
//!
//! ```text
//! T_y F(x, y) = E_i(x) + y F_y(x, 0),          F_y(x, 0) = X_i(x) + ½E_i'(x)
//! T_x F(x, y) = E_{i+2}(1 − y) + x F_x(0, y),  F_x(0, y) = X_{i+2}(1 − y) − ½E_{i+2}'(1 − y)
//! ```
//!
//! (`e_{i+2} − e_i = d_i + ½(e_{i+1} − e_i)` and `e_{i+1} − e_i = d_{i+2} − ½(e_i − e_{i+2})`), are
//! combined in the Boolean sum `P_i = T_x F + T_y F − Q` with the corner's own Taylor expansion
//! `Q = V_i + x D_{i,i+1} + y D_{i,i+2} + xy τ(x, y)`. On `y = 0`, `T_x F = V_i + x D_{i,i+1}`
//! cancels with `Q`, so `P_i = E_i`; its `y`-derivative is
//! `F_y(x, 0) + [D_{i,i+2} + x ∂_y F_x(0, 0)] − [D_{i,i+2} + x τ(x, 0)]`, the data exactly when
//! `τ(x, 0)` is the twist `τ_x = ∂_y F_x(0, 0) = −X_{i+2}'(1) + ½E_{i+2}''(1)` of the *other*
//! side; likewise on `x = 0` when `τ(0, y) = τ_y = ∂_x F_y(0, 0) = X_i'(0) + ½E_i''(0)`. The two
//! twists differ in general (the twist incompatibility), and Gregory's rational twist
//! `τ = (x τ_x + y τ_y)/(x + y)` takes each on its side. So `P_i` matches position and
//! derivatives of the data along both sides at `V_i`. It is `0/0` at `V_i` only, where `xyτ`
//! and its gradient vanish: the patch takes `V_i` with the two curve tangents there, and its
//! second derivatives a small step inside ([`VERTEX_NUDGE`]; `xyτ` is homogeneous of degree
//! two, its Hessian at the corner depends on the direction of approach).
//!
//! # Blend
//!
//! `F = Σ_i w_i P_i` with `w_i = b_i² / Σ_j b_j²` (`Σ_j b_j² ≥ ⅓`: smooth everywhere). On edge
//! `l`, `w_{l+2}` vanishes with its gradient (the factor `b_{l+2}²`), and the two corner
//! interpolants at its ends, `P_l` and `P_{l+1}`, both match the edge's position and gradient,
//! so `Σ ∇w P = (∇w_l + ∇w_{l+1}) E = −∇w_{l+2} E = 0` and `∇F = w_l ∇P_l + w_{l+1} ∇P_{l+1}`:
//! the edge's data. Hence G1 across edges. Linear data (straight curves at thirds, one normal)
//! is reproduced exactly: each projector reproduces linear functions and the twists vanish.
//!
//! # Derivatives
//!
//! Everything is composed from second-order jets in the patch's local `(u, v) = (b_0, b_1)`
//! (`w = b_2 = 1 − u − v`, docs/conventions.md): the curves and transversals composed with the
//! jets of `x` and `y` by the chain rule, products and the quotients of `τ` and `w_i` by Leibniz's
//! and the quotient rule. The tests compare every partial with finite differences.

use curves::CubicBez3;
use nalgebra::{Point3, Vector3};

use super::{Continuity, FaceInput, Form, Layout, Scheme, WHOLE};
use crate::beztri::Derivatives;
use crate::fit::FaceFallbackReason;
use crate::patch::SampledForm;
use crate::scheme::Bary;
use crate::side_vertex::write_face;

/// Points stored per patch: twelve curve control points and three normals.
pub const POINTS: usize = 15;

/// How far towards the centre (as a fraction of the way) the second derivatives at a vertex
/// are taken (module docs): small enough that they are the limit along the bisector to about
/// this relative size, large enough that `x + y` is far from underflow.
pub const VERTEX_NUDGE: f64 = 1e-5;

/// Coordinates this close to zero count as zero when deciding whether a point is a vertex
/// (lattice points are exact; this absorbs the rounding of a sub-triangle's inverse).
const ZERO_COORD: f64 = 1e-14;

/// Below this sine of the angle between a normal and the curve tangent, `A` is undefined and
/// the edge takes the linear transversal (degenerate or fallback data).
const DEGENERATE_SINE: f64 = 1e-12;

/// The Gregory–Charrot patch form.
#[derive(Clone, Copy, Debug, Default)]
pub struct GregoryCharrotForm;

/// The form's instance.
pub static GREGORY_CHARROT: GregoryCharrotForm = GregoryCharrotForm;

// ---------------------------------------------------------------------------------------------
// Second-order jets in (u, v).

/// A scalar with gradient and Hessian `[uu, uv, vv]`.
#[derive(Clone, Copy, Debug)]
struct J {
    v: f64,
    g: [f64; 2],
    h: [f64; 3],
}

impl J {
    fn constant(v: f64) -> J {
        J {
            v,
            g: [0.0; 2],
            h: [0.0; 3],
        }
    }

    fn bary(b: Bary) -> [J; 3] {
        let lin = |v: f64, g: [f64; 2]| J { v, g, h: [0.0; 3] };
        [
            lin(b[0], [1.0, 0.0]),
            lin(b[1], [0.0, 1.0]),
            lin(b[2], [-1.0, -1.0]),
        ]
    }

    fn add(self, o: J) -> J {
        J {
            v: self.v + o.v,
            g: [self.g[0] + o.g[0], self.g[1] + o.g[1]],
            h: std::array::from_fn(|k| self.h[k] + o.h[k]),
        }
    }

    fn scale(self, c: f64) -> J {
        J {
            v: self.v * c,
            g: self.g.map(|x| x * c),
            h: self.h.map(|x| x * c),
        }
    }

    fn mul(self, o: J) -> J {
        let (a, b) = (self, o);
        J {
            v: a.v * b.v,
            g: [a.g[0] * b.v + a.v * b.g[0], a.g[1] * b.v + a.v * b.g[1]],
            h: [
                a.h[0] * b.v + 2.0 * a.g[0] * b.g[0] + a.v * b.h[0],
                a.h[1] * b.v + a.g[0] * b.g[1] + a.g[1] * b.g[0] + a.v * b.h[1],
                a.h[2] * b.v + 2.0 * a.g[1] * b.g[1] + a.v * b.h[2],
            ],
        }
    }

    /// `self / o` (from `self = r o`).
    fn div(self, o: J) -> J {
        let (a, b) = (self, o);
        let v = a.v / b.v;
        let g = [(a.g[0] - v * b.g[0]) / b.v, (a.g[1] - v * b.g[1]) / b.v];
        J {
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

/// A vector with gradient and Hessian `[uu, uv, vv]`.
#[derive(Clone, Copy, Debug)]
struct VJ {
    v: Vector3<f64>,
    g: [Vector3<f64>; 2],
    h: [Vector3<f64>; 3],
}

impl VJ {
    fn zero() -> VJ {
        VJ::constant(Vector3::zeros())
    }

    fn constant(v: Vector3<f64>) -> VJ {
        VJ {
            v,
            g: [Vector3::zeros(); 2],
            h: [Vector3::zeros(); 3],
        }
    }

    fn add(self, o: VJ) -> VJ {
        VJ {
            v: self.v + o.v,
            g: [self.g[0] + o.g[0], self.g[1] + o.g[1]],
            h: std::array::from_fn(|k| self.h[k] + o.h[k]),
        }
    }

    fn sub(self, o: VJ) -> VJ {
        self.add(o.times(-1.0))
    }

    fn times(self, c: f64) -> VJ {
        VJ {
            v: self.v * c,
            g: self.g.map(|x| x * c),
            h: self.h.map(|x| x * c),
        }
    }

    /// The scalar jet `s` times this vector jet (Leibniz).
    fn scaled(self, s: J) -> VJ {
        let a = self;
        VJ {
            v: a.v * s.v,
            g: [a.g[0] * s.v + a.v * s.g[0], a.g[1] * s.v + a.v * s.g[1]],
            h: [
                a.h[0] * s.v + a.g[0] * (2.0 * s.g[0]) + a.v * s.h[0],
                a.h[1] * s.v + a.g[0] * s.g[1] + a.g[1] * s.g[0] + a.v * s.h[1],
                a.h[2] * s.v + a.g[1] * (2.0 * s.g[1]) + a.v * s.h[2],
            ],
        }
    }

    /// The constant vector `c` times the scalar jet `s`.
    fn of(c: Vector3<f64>, s: J) -> VJ {
        VJ {
            v: c * s.v,
            g: s.g.map(|x| c * x),
            h: s.h.map(|x| c * x),
        }
    }

    /// `f(t)` for a curve with `f(t.v), f'(t.v), f''(t.v)` given (chain rule).
    fn compose(f: [Vector3<f64>; 3], t: J) -> VJ {
        VJ {
            v: f[0],
            g: [f[1] * t.g[0], f[1] * t.g[1]],
            h: [
                f[2] * (t.g[0] * t.g[0]) + f[1] * t.h[0],
                f[2] * (t.g[0] * t.g[1]) + f[1] * t.h[1],
                f[2] * (t.g[1] * t.g[1]) + f[1] * t.h[2],
            ],
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Edge data.

/// An edge's Chiyokura–Kimura coefficients: `k_0, k_1`, `A_0, A_1`, `h_0, h_1`.
type CkEnds = ([f64; 2], [Vector3<f64>; 2], [f64; 2]);

/// One edge's curve and Chiyokura–Kimura transversal (module docs).
struct Edge {
    c: [Vector3<f64>; 4],
    /// `None`: the linear transversal between the ends.
    ck: Option<CkEnds>,
    x_ends: [Vector3<f64>; 2],
}

impl Edge {
    /// `E^{(r)}(s)`, `r = 0 … 3`.
    fn curve(&self, s: f64) -> [Vector3<f64>; 4] {
        let c = &self.c;
        let t = 1.0 - s;
        let d = [c[1] - c[0], c[2] - c[1], c[3] - c[2]];
        let dd = [d[1] - d[0], d[2] - d[1]];
        [
            c[0] * (t * t * t)
                + c[1] * (3.0 * s * t * t)
                + c[2] * (3.0 * s * s * t)
                + c[3] * (s * s * s),
            (d[0] * (t * t) + d[1] * (2.0 * s * t) + d[2] * (s * s)) * 3.0,
            (dd[0] * t + dd[1] * s) * 6.0,
            (dd[1] - dd[0]) * 6.0,
        ]
    }

    /// `X(s), X'(s), X''(s)`.
    fn transversal(&self, s: f64) -> [Vector3<f64>; 3] {
        let [x0, x1] = self.x_ends;
        let Some((k, a, h)) = self.ck else {
            return [x0 + (x1 - x0) * s, x1 - x0, Vector3::zeros()];
        };
        let e = self.curve(s);
        let (kv, kd) = (k[0] + (k[1] - k[0]) * s, k[1] - k[0]);
        let (hv, hd) = (h[0] + (h[1] - h[0]) * s, h[1] - h[0]);
        let (av, ad) = (a[0] + (a[1] - a[0]) * s, a[1] - a[0]);
        [
            av * kv + e[1] * hv,
            av * kd + ad * kv + e[1] * hd + e[2] * hv,
            ad * (2.0 * kd) + e[2] * (2.0 * hd) + e[3] * hv,
        ]
    }
}

/// One face's data read from its 15 points.
struct FaceData {
    edges: [Edge; 3],
}

/// Why an edge's Chiyokura–Kimura data cannot be made: the transversal at end `end` (0, 1) has
/// no component across the curve.
struct Folded {
    edge: usize,
}

impl FaceData {
    fn new(points: &[Point3<f64>]) -> Result<FaceData, Option<Folded>> {
        if points.len() < POINTS {
            return Err(None);
        }
        let c: [[Vector3<f64>; 4]; 3] =
            std::array::from_fn(|l| std::array::from_fn(|m| points[4 * l + m].coords));
        let n: [Vector3<f64>; 3] = std::array::from_fn(|l| points[12 + l].coords);
        // D at V_a towards V_{a+1} and towards V_{a+2}.
        let d_next = |a: usize| (c[a][1] - c[a][0]) * 3.0;
        let d_prev = |a: usize| (c[(a + 2) % 3][3] - c[(a + 2) % 3][2]) * -3.0;
        let mut folded = None;
        let edges: [Edge; 3] = std::array::from_fn(|l| {
            let (b, e0, e1) = ((l + 1) % 3, d_next(l), (c[l][3] - c[l][2]) * 3.0);
            let x_ends = [d_prev(l) - e0 * 0.5, d_next(b) + e1 * 0.5];
            let across = |nn: &Vector3<f64>, t: &Vector3<f64>| {
                let p = nn.cross(t);
                (p.norm() > DEGENERATE_SINE * nn.norm() * t.norm()).then(|| p.normalize())
            };
            let ck = match (across(&n[l], &e0), across(&n[b], &e1)) {
                (Some(a0), Some(a1)) => {
                    let k = [x_ends[0].dot(&a0), x_ends[1].dot(&a1)];
                    let h = [
                        x_ends[0].dot(&e0) / e0.norm_squared(),
                        x_ends[1].dot(&e1) / e1.norm_squared(),
                    ];
                    if !(k[0] > 0.0 && k[1] > 0.0) && folded.is_none() {
                        folded = Some(Folded { edge: l });
                    }
                    Some((k, [a0, a1], h))
                }
                _ => None,
            };
            Edge {
                c: c[l],
                ck,
                x_ends,
            }
        });
        match folded {
            Some(f) => Err(Some(f)),
            None => Ok(FaceData { edges }),
        }
    }
}

/// The corner interpolant `P_i` at barycentric jets `b` (module docs); `twist` false drops
/// the `xyτ` term (at the vertex itself, where it vanishes with its gradient).
fn corner(data: &FaceData, i: usize, b: &[J; 3], twist: bool) -> VJ {
    let (ei, ek) = (&data.edges[i], &data.edges[(i + 2) % 3]);
    let (x, y) = (b[(i + 1) % 3], b[(i + 2) % 3]);
    let one = J::constant(1.0);
    // T_y: along edge i at s = x.
    let ci = ei.curve(x.v);
    let xi = ei.transversal(x.v);
    let fy = VJ::compose(
        [
            xi[0] + ci[1] * 0.5,
            xi[1] + ci[2] * 0.5,
            xi[2] + ci[3] * 0.5,
        ],
        x,
    );
    let ty = VJ::compose([ci[0], ci[1], ci[2]], x).add(fy.scaled(y));
    // T_x: along edge i + 2 at s = 1 − y.
    let s = one.add(y.scale(-1.0));
    let ck = ek.curve(s.v);
    let xk = ek.transversal(s.v);
    let fx = VJ::compose(
        [
            xk[0] - ck[1] * 0.5,
            xk[1] - ck[2] * 0.5,
            xk[2] - ck[3] * 0.5,
        ],
        s,
    );
    let tx = VJ::compose([ck[0], ck[1], ck[2]], s).add(fx.scaled(x));
    // Q: the corner's Taylor expansion with Gregory's rational twist.
    let c0 = ei.curve(0.0);
    let d1 = c0[1];
    let d2 = ek.curve(1.0)[1] * -1.0;
    let mut q = VJ::constant(c0[0]).add(VJ::of(d1, x)).add(VJ::of(d2, y));
    if twist {
        let tau_y = ei.transversal(0.0)[1] + c0[2] * 0.5;
        let tau_x = ek.transversal(1.0)[1] * -1.0 + ek.curve(1.0)[2] * 0.5;
        let r = x.div(x.add(y));
        let tau = VJ::of(tau_x, r).add(VJ::of(tau_y, one.add(r.scale(-1.0))));
        q = q.add(tau.scaled(x.mul(y)));
    }
    tx.add(ty).sub(q)
}

/// The blend at local point `local` (no coordinate pair both zero unless `vertex` names it).
fn blend(data: &FaceData, local: Bary, vertex: Option<usize>) -> VJ {
    let b = J::bary(local);
    let sq: [J; 3] = std::array::from_fn(|i| b[i].mul(b[i]));
    let sum = sq[0].add(sq[1]).add(sq[2]);
    (0..3).fold(VJ::zero(), |acc, i| {
        let w = sq[i].div(sum);
        acc.add(corner(data, i, &b, vertex != Some(i)).scaled(w))
    })
}

fn derivatives(j: &VJ) -> Derivatives {
    Derivatives {
        p: Point3::from(j.v),
        du: j.g[0],
        dv: j.g[1],
        duu: j.h[0],
        duv: j.h[1],
        dvv: j.h[2],
    }
}

impl SampledForm for GregoryCharrotForm {
    fn name(&self) -> &'static str {
        "gregory-charrot"
    }

    fn points_per_patch(&self) -> usize {
        POINTS
    }

    fn is_direction(&self, k: usize) -> bool {
        (12..POINTS).contains(&k)
    }

    /// The local point, then the vertex it is (0: none, `1 + i`: vertex `i`).
    fn prepare(&self, local: Bary) -> Vec<f64> {
        let zero = local.map(|x| x.abs() < ZERO_COORD);
        let vertex = (0..3).find(|&i| zero[(i + 1) % 3] && zero[(i + 2) % 3]);
        vec![
            local[0],
            local[1],
            local[2],
            vertex.map_or(0.0, |i| 1.0 + i as f64),
        ]
    }

    fn eval(&self, points: &[Point3<f64>], prepared: &[f64]) -> Derivatives {
        let (Ok(data), [u, v, w, tag, ..]) = (FaceData::new(points), prepared) else {
            return Derivatives::nan();
        };
        let local = [*u, *v, *w];
        if *tag >= 1.0 {
            let i = (*tag as usize - 1).min(2);
            let mut e = [0.0; 3];
            e[i] = 1.0;
            let at = derivatives(&blend(&data, e, Some(i)));
            let third = 1.0 / 3.0;
            let inner = derivatives(&blend(
                &data,
                e.map(|x| x + VERTEX_NUDGE * (third - x)),
                None,
            ));
            return Derivatives {
                p: at.p,
                du: at.du,
                dv: at.dv,
                ..inner
            };
        }
        derivatives(&blend(&data, local, None))
    }
}

// ---------------------------------------------------------------------------------------------
// The scheme.

/// The Gregory–Charrot scheme.
#[derive(Clone, Copy, Debug, Default)]
pub struct GregoryCharrot;

/// The face's stored data (curves, then unit normals), refused where a corner is folded
/// ([`crate::scheme::folded_corner`]) or an edge's transversal has no component across the
/// curve (`k ≤ 0`: it would fold over the edge).
pub fn build_face(
    input: &FaceInput<'_>,
    out: &mut [Point3<f64>],
) -> Result<(), FaceFallbackReason> {
    if let Some(corner) = crate::scheme::folded_corner(input) {
        return Err(FaceFallbackReason::Folded { corner });
    }
    write_face(input.edges, input.vertices.map(|v| v.n), out);
    match FaceData::new(out) {
        Ok(_) => Ok(()),
        Err(Some(Folded { edge })) => Err(FaceFallbackReason::FoldedEdge { edge }),
        Err(None) => Err(FaceFallbackReason::NonFinite),
    }
}

impl Scheme for GregoryCharrot {
    fn name(&self) -> &'static str {
        "gregory-charrot"
    }

    fn layout(&self) -> Layout {
        Layout {
            degree: 3,
            subs: &WHOLE,
            form: Form::Sampled(&GREGORY_CHARROT),
        }
    }

    fn continuity(&self) -> Continuity {
        Continuity::G1
    }

    fn uses_curves(&self) -> bool {
        true
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        build_face(input, out)
    }

    /// The same curves with zero normals (the linear transversal): C0 with the neighbours,
    /// which reproduce the same curves.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        write_face(input.edges, [Vector3::zeros(); 3], out);
    }
}

/// The stored data of a face from its curves and normals (for tests and tools).
pub fn face_points(edges: &[CubicBez3; 3], normals: [Vector3<f64>; 3]) -> Vec<Point3<f64>> {
    let mut out = vec![Point3::origin(); POINTS];
    write_face(edges, normals, &mut out);
    out
}

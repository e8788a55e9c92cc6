//! `powell-sabin`: the parametric split-domain quadratic scheme, six quadratic Bézier
//! triangles per face over the Powell–Sabin split (Powell and Sabin, *Piecewise quadratic
//! approximations on triangles*, ACM TOMS 3 (1977) 316–325; the testbed seed lists
//! Powell–Sabin among its fitters). The boundaries are built from the two vertices of each
//! edge (positions and normals) only, so neighbours share them.
//!
//! # Notation
//!
//! Face `(V_0, V_1, V_2)` with unit normals `n_i`, edge `e` from `V_e` to `V_{e+1}` (indices
//! mod 3), `M_e` over the edge midpoint, `S` over the centroid. The sub-triangles are
//! `(V_e, M_e, S)` and `(M_e, V_{e+1}, S)` ([`super::SIX_SPLIT`]); their nets, in the row order of
//! docs/conventions.md (`b200, b110, b020, b101, b011, b002`):
//!
//! ```text
//! (V_e, M_e, S):      V_e   Q⁺_e  M_e   W_e   Z_e      S
//! (M_e, V_{e+1}, S):  M_e   Q⁻_{e+1}  V_{e+1}   Z_e   W_{e+1}   S
//! ```
//!
//! `Q⁺_i` is the boundary point next to `V_i` on edge `i` (towards `V_{i+1}`), `Q⁻_i` the one
//! next to `V_i` on edge `i − 1` (towards `V_{i−1}`); `W_i` is on the interior boundary
//! `V_i → S`, `Z_e` on `M_e → S`.
//!
//! # Boundaries (shared, C0)
//!
//! Each edge is two quadratic pieces `V_a, Q_a, M` and `M, Q_b, V_b` with
//! `Q_a = V_a + ¼ π_a(V_b − V_a)`, `π_a(x) = x − (x·n_a) n_a` the projection onto `V_a`'s tangent
//! plane (the quarter point of the edge, projected: the point at a domain step of a quarter
//! edge along a linear map into the tangent plane), likewise `Q_b`, and `M = (Q_a + Q_b)/2`
//! (the two pieces join C1 at `M`, which the C1 condition across `M → S` needs). Everything
//! depends on the edge's two vertices only, and the formulas are symmetric under swapping
//! them, so the neighbouring face builds the same points: C0 across edges.
//!
//! # Interior (C1 inside the face)
//!
//! In the domain `M_i = −M_{i−1} + ½V_i + 3/2 S` (barycentric coordinates of `M_i` in the
//! sub-triangle `(M_{i−1}, V_i, S)`), and `V_{e+1} = 2M_e − V_e`. The C1 conditions across the
//! interior boundaries are then:
//!
//! * across `V_i → S`, level 0: `Q⁺_i = −Q⁻_i + ½V_i + 3/2 W_i`, so
//!   `W_i = ⅔(Q⁺_i + Q⁻_i) − ⅓V_i` (an affine combination of points of `V_i`'s tangent plane:
//!   `W_i` lies in it);
//! * across `M_e → S`: `M_e = (Q⁺_e + Q⁻_{e+1})/2` (the boundary rule) and
//!   `Z_e = (W_e + W_{e+1})/2`;
//! * across `V_i → S`, level 1: `Z_i + Z_{i−1} = ½W_i + 3/2 S`, which with the previous rule
//!   holds for all three `i` exactly when `S = (W_0 + W_1 + W_2)/3`.
//!
//! The interior is fully determined: the macro-patch is C1 inside (G1 where regular; measured).
//!
//! # Across mesh edges: what can be proved
//!
//! * At a data vertex every net point next to it (`Q⁺`, `Q⁻`, `W`) lies in its tangent plane,
//!   in every face around it: the surface has the data normal there, G1 at the vertices.
//! * Along an edge the two faces share the boundary, but the cross-boundary derivative of the
//!   half-edge patch `(V_a, M, S)` ends in `Z − Q_a` at `M`, and `Z = (W_a + W_b)/2` depends on
//!   the face's other two edges through `W_a`, `W_b`. The interior has no free point left once
//!   the C1 rules hold, so the tangent plane at `M` differs between the faces in general: the
//!   claim is [`Continuity::C0`], and the jump is measured and reported. (Making the tangent
//!   plane at `M` shared would need `Z` from shared data, i.e. giving up C1 inside; that is
//!   not pursued here.)
//!
//! Linear precision: for planar data the projections are the identity, the boundary points
//! are the quarter points and midpoints, and every rule is affine: the flat triangle (tested).
//!
//! # Where the source is ambiguous, and how it was settled
//!
//! Powell and Sabin interpolate *function values and gradients* on a planar triangulation;
//! the parametric version needs, per vertex, a linear map from the domain into the tangent
//! plane. It is taken from the projected edge vectors (`Q_a − V_a = ¼ π_a(V_b − V_a)`), which
//! is the one choice that uses only the edge's data (so neighbours agree) and is exact for
//! planar data. Powell and Sabin's split point may be any interior point (the incentre in
//! their second construction, for obtuse triangles); the layout fixes the centroid, and the
//! edge split point at the midpoint, since the domain is barycentric, not metric.
//!
//! # On height fields
//!
//! On data `z = f(x, y)` (detected by the fit, or asked for with `fit --heightfield`) the fit
//! uses this scheme's functional form instead ([`Scheme::on_height_field`]:
//! [`super::functional::powell_sabin`]), which is C1 across every edge and claims
//! [`Continuity::C1`]; what is said above is the parametric scheme on any other data.

use nalgebra::{Point3, Vector3};

use super::{Continuity, FaceInput, Layout, Scheme, SIX_SPLIT};
use crate::fit::FaceFallbackReason;

/// The parametric Powell–Sabin scheme (module docs).
#[derive(Clone, Copy, Debug, Default)]
pub struct PowellSabin;

/// Control points per quadratic net.
const NP: usize = 6;

fn mid(a: &Point3<f64>, b: &Point3<f64>) -> Point3<f64> {
    Point3::from((a.coords + b.coords) / 2.0)
}

/// The boundary point next to `p` on the edge towards `q` (module docs):
/// `p + ¼ π(q − p)`, `π` the projection onto the plane with unit normal `n`.
pub fn edge_point(p: &Point3<f64>, n: &Vector3<f64>, q: &Point3<f64>) -> Point3<f64> {
    let d = q - p;
    p + (d - n * d.dot(n)) / 4.0
}

/// The crease lines of a face's edges at their ends ([`super::FaceInput::creases`]).
pub type CreaseLines = [[Option<Vector3<f64>>; 2]; 3];

/// The shared boundary points of edge `e`: `[Q_a, M, Q_b]` (module docs). At an end where the
/// edge is a crease, the quarter point is projected onto the crease line `t` instead of the
/// tangent plane, `p + ¼ (d·t) t` ([`super::FaceInput::project`]): both faces then build the
/// same boundary from their own sectors' normals, and it lies in both tangent planes.
fn boundary(
    p: &[Point3<f64>; 3],
    n: &[Vector3<f64>; 3],
    creases: &CreaseLines,
    e: usize,
) -> [Point3<f64>; 3] {
    let (a, b) = (e, (e + 1) % 3);
    let point = |at: usize, to: usize, end: usize| match creases[e][end] {
        Some(t) => p[at] + t * (t.dot(&(p[to] - p[at])) / 4.0),
        None => edge_point(&p[at], &n[at], &p[to]),
    };
    let qa = point(a, b, 0);
    let qb = point(b, a, 1);
    [qa, mid(&qa, &qb), qb]
}

/// The six nets from the boundary points and the interior points `w` (one per corner), `z`
/// (one per edge) and `s`.
fn assemble(
    p: &[Point3<f64>; 3],
    bd: &[[Point3<f64>; 3]; 3],
    w: &[Point3<f64>; 3],
    z: &[Point3<f64>; 3],
    s: Point3<f64>,
) -> [[Point3<f64>; NP]; 6] {
    std::array::from_fn(|k| {
        let e = k / 2;
        let b = (e + 1) % 3;
        let [qa, m, qb] = bd[e];
        if k % 2 == 0 {
            [p[e], qa, m, w[e], z[e], s]
        } else {
            [m, qb, p[b], z[e], w[b], s]
        }
    })
}

/// The six quadratic nets of a face with corners `p` and unit normals `n` (module docs), in
/// the order of [`SIX_SPLIT`].
pub fn macro_patch(p: &[Point3<f64>; 3], n: &[Vector3<f64>; 3]) -> [[Point3<f64>; NP]; 6] {
    macro_patch_with_creases(p, n, &super::NO_CREASES)
}

/// [`macro_patch`] of a face with crease edges (`creases` as [`super::FaceInput::creases`]).
pub fn macro_patch_with_creases(
    p: &[Point3<f64>; 3],
    n: &[Vector3<f64>; 3],
    creases: &CreaseLines,
) -> [[Point3<f64>; NP]; 6] {
    let bd: [[Point3<f64>; 3]; 3] = std::array::from_fn(|e| boundary(p, n, creases, e));
    // Q⁺_i = bd[i][0], Q⁻_i = bd[i − 1][2].
    let w: [Point3<f64>; 3] = std::array::from_fn(|i| {
        let qp = bd[i][0].coords;
        let qm = bd[(i + 2) % 3][2].coords;
        Point3::from((qp + qm) * (2.0 / 3.0) - p[i].coords / 3.0)
    });
    let z: [Point3<f64>; 3] = std::array::from_fn(|e| mid(&w[e], &w[(e + 1) % 3]));
    let s = Point3::from((w[0].coords + w[1].coords + w[2].coords) / 3.0);
    assemble(p, &bd, &w, &z, s)
}

/// The C0 fallback: the shared boundary pieces, the split point at the mean of the three `M_e`,
/// and straight interior boundaries (`W_i`, `Z_e` at their midpoints); affine, so planar data
/// stay flat.
pub fn fallback_patch(p: &[Point3<f64>; 3], n: &[Vector3<f64>; 3]) -> [[Point3<f64>; NP]; 6] {
    fallback_patch_with_creases(p, n, &super::NO_CREASES)
}

/// [`fallback_patch`] of a face with crease edges (as [`macro_patch_with_creases`]).
pub fn fallback_patch_with_creases(
    p: &[Point3<f64>; 3],
    n: &[Vector3<f64>; 3],
    creases: &CreaseLines,
) -> [[Point3<f64>; NP]; 6] {
    let bd: [[Point3<f64>; 3]; 3] = std::array::from_fn(|e| boundary(p, n, creases, e));
    let s = Point3::from((bd[0][1].coords + bd[1][1].coords + bd[2][1].coords) / 3.0);
    let w: [Point3<f64>; 3] = std::array::from_fn(|i| mid(&p[i], &s));
    let z: [Point3<f64>; 3] = std::array::from_fn(|e| mid(&bd[e][1], &s));
    assemble(p, &bd, &w, &z, s)
}

impl Scheme for PowellSabin {
    fn name(&self) -> &'static str {
        "powell-sabin"
    }

    fn layout(&self) -> Layout {
        Layout::bezier(2, &SIX_SPLIT)
    }

    /// C0 across mesh edges; G1 at the vertices and C1 inside each face (module docs).
    fn continuity(&self) -> Continuity {
        Continuity::C0
    }

    fn uses_curves(&self) -> bool {
        false
    }

    /// The functional form on height fields ([`super::functional`]): C1.
    fn on_height_field(&self, mesh: &crate::mesh::Mesh) -> Option<Box<dyn super::Scheme>> {
        Some(Box::new(
            super::functional::powell_sabin::FunctionalPowellSabin::new(mesh),
        ))
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        if let Some(corner) = super::folded_winding(input) {
            return Err(FaceFallbackReason::Folded { corner });
        }
        let p = input.vertices.map(|v| v.p);
        let n = input.vertices.map(|v| v.n.normalize());
        let nets = macro_patch_with_creases(&p, &n, &input.creases);
        if !nets
            .iter()
            .flatten()
            .all(|q| q.iter().all(|c| c.is_finite()))
        {
            return Err(FaceFallbackReason::NonFinite);
        }
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
        Ok(())
    }

    /// [`fallback_patch`]: C0 on the shared boundary pieces (a zero normal gives unprojected
    /// quarter points, still shared).
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        let p = input.vertices.map(|v| v.p);
        let n = input
            .vertices
            .map(|v| v.n.try_normalize(0.0).unwrap_or_else(Vector3::zeros));
        let nets = fallback_patch_with_creases(&p, &n, &input.creases);
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
    }
}

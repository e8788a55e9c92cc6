//! The functional Powell–Sabin interpolant (Powell and Sabin, *Piecewise quadratic
//! approximations on triangles*, ACM TOMS 3 (1977) 316–325, their 6-split): six quadratics per
//! face, C1 across every edge of the triangulation, from values and gradients at the vertices;
//! quadratic precision.
//!
//! # The split
//!
//! Each face `(V_0, V_1, V_2)` is split at an interior point `Z` joined to the three vertices and
//! to one point `M_e` on each edge `e`, `M_e = (1 − τ_e) V_e + τ_e V_{e+1}`; the sub-triangles
//! are `(V_e, M_e, Z)` and `(M_e, V_{e+1}, Z)`, the combinatorics of [`SIX_SPLIT`] (whose
//! barycentric corners are the centroid and midpoints: the patches' own xy corners are these
//! `Z` and `M_e`, each patch parametrized affinely over its sub-triangle, so the layout holds
//! them and the surface is the same).
//!
//! **Why the split points must be collinear.** Along the edge half `V_a M`, the derivative of
//! face `L` in direction `Z_L − M` at `M` is fixed by the C1 rules inside `L` (below) to
//! `ĝ · (Z_L − M)`, `ĝ = (1 − τ) g_a + τ g_b`, and its tangential derivative there is the shared
//! boundary's. The neighbour `R` has the same with `Z_R − M`. The two gradients at `M` agree for
//! all data exactly when `Z_L − M` and `Z_R − M` are parallel: `Z_L`, `M`, `Z_R` collinear. Then
//! the derivative across each half edge is linear (the patches are quadratic) with the same end
//! values from both sides: **C1 across the edge**.
//!
//! **The choice** (Powell and Sabin §4 for general triangulations; the choice of most later
//! implementations, e.g. Cendes and Wong, *C1 quadratic interpolation over arbitrary point
//! sets*, IEEE CG&A 7 (1987)): `Z` the **incentre**, `Z = Σ ζ_i V_i` with `ζ_i` the length of
//! the edge opposite `V_i` over the perimeter; on an interior edge `M` is where the segment
//! between the two faces' incentres crosses it; on a boundary edge `M` is the midpoint (any
//! interior point keeps C1 there: there is no neighbour). The incentres lie at their inradii
//! `r_L`, `r_R` on opposite sides of the edge, so the crossing is
//! `T_L + (T_R − T_L) r_L/(r_L + r_R)` between the two tangency points `T`, strictly inside the
//! edge — for **obtuse** triangles too. The circumcentre (Powell and Sabin's other choice,
//! which gives the midpoints) lies outside an obtuse triangle and on the hypotenuse of a right
//! one (every triangle of a split grid), so it is not used.
//!
//! # The ordinates
//!
//! Quadratic nets `b200 b110 b020 b101 b011 b002` over `(P0, P1, P2)` at the domain points
//! `P0, (P0+P1)/2, P1, (P0+P2)/2, (P1+P2)/2, P2`; [`super::Node::tangent`] is the tangent-plane
//! point:
//!
//! * at `V_i` and at the midpoints towards its neighbours `M_e`, `M_{e−1}`, `Z`: the tangent
//!   plane of `V_i` (every patch at `V_i` has gradient `g_i`): `Q⁺_e` over `(V_e + M_e)/2`,
//!   `Q⁻_{e+1}` over `(M_e + V_{e+1})/2`, `W_i` over `(V_i + Z)/2`;
//! * `M_e = (1 − τ) Q⁺_e + τ Q⁻_{e+1}`: C1 across `M_e Z` at the edge (the domain point `M_e`
//!   divides `(V_e + M_e)/2 → (M_e + V_{e+1})/2` in the ratio `τ`); it depends on the edge's
//!   data and `τ` only, so both faces share the boundary;
//! * `R_e = (1 − τ) W_e + τ W_{e+1}` over `(M_e + Z)/2`: C1 across `M_e Z` one row in;
//! * `Z = Σ ζ_i W_i`: the three `W_i` span the tangent plane at `Z` (their domain points
//!   `(V_i + Z)/2` combine with weights `ζ_i` to `Z`), every `R_e` lies in it (affine
//!   combination of two `W`), so the seven points around `Z` are coplanar and every C1
//!   condition across `V_i Z` holds (a linear function satisfies it).
//!
//! Every rule is affine in the ordinates with the same weights as the domain points, so the 3D
//! control points `(ξ, b)` are those rules applied to points. Linear and quadratic precision:
//! a quadratic's ordinates satisfy every rule (tested).
//!
//! To share the boundary to the bit, both faces compute an edge's `M`, `Q` points in one
//! orientation (its end with the smaller `(x, y)` first) from a `τ` computed once per mesh edge.

use nalgebra::{Point3, Vector2};

use super::Node;
use crate::fit::FaceFallbackReason;
use crate::mesh::Mesh;
use crate::scheme::{Continuity, FaceInput, Layout, Scheme, SIX_SPLIT};

/// Control points per quadratic net.
const NP: usize = 6;

/// The functional Powell–Sabin scheme for one mesh: the edge split parameters of its faces
/// (module docs), built by [`FunctionalPowellSabin::new`]; `powell-sabin`'s functional form
/// ([`crate::scheme::Scheme::on_height_field`]).
#[derive(Clone, Debug, Default)]
pub struct FunctionalPowellSabin {
    /// Per face and face edge `e`, `τ` of the edge split point along the edge from its end with
    /// the smaller `(x, y)` to the other.
    taus: Vec<[f64; 3]>,
}

/// The incentre weights `ζ_i` of the xy triangle `p` (the opposite edge's length over the
/// perimeter; the centroid's for a triangle of no perimeter).
pub fn incentre_weights(p: &[Vector2<f64>; 3]) -> [f64; 3] {
    let l: [f64; 3] = std::array::from_fn(|i| (p[(i + 2) % 3] - p[(i + 1) % 3]).norm());
    let sum = l[0] + l[1] + l[2];
    if sum > 0.0 {
        l.map(|x| x / sum)
    } else {
        [1.0 / 3.0; 3]
    }
}

/// The incentre of the xy triangle `p`.
pub fn incentre(p: &[Vector2<f64>; 3]) -> Vector2<f64> {
    let z = incentre_weights(p);
    p[0] * z[0] + p[1] * z[1] + p[2] * z[2]
}

/// Whether `a` comes first in the canonical orientation of an edge (smaller `(x, y)`).
fn first(a: &Vector2<f64>, b: &Vector2<f64>) -> bool {
    (a.x, a.y) <= (b.x, b.y)
}

/// `τ` of the point where the line `z1 → z2` crosses the line `p → q`, along `p → q`.
pub fn crossing(p: &Vector2<f64>, q: &Vector2<f64>, z1: &Vector2<f64>, z2: &Vector2<f64>) -> f64 {
    let dz = z2 - z1;
    (z1 - p).perp(&dz) / (q - p).perp(&dz)
}

impl FunctionalPowellSabin {
    /// The split of every face of `mesh` (module docs): incentres, and on each interior edge
    /// the crossing of the two incentres' segment, on a boundary edge the midpoint. A `τ` that
    /// comes out non-finite or outside `(0, 1)` (only for data that is no planar triangulation,
    /// which [`super::detect`] refuses) is replaced by the midpoint's.
    pub fn new(mesh: &Mesh) -> Self {
        let xy = |v: usize| super::xy(&mesh.vertices()[v].data.p);
        let centres: Vec<Vector2<f64>> =
            mesh.faces().iter().map(|f| incentre(&f.map(xy))).collect();
        let edge_tau: Vec<f64> = mesh
            .edges()
            .map(|e| {
                let (a, b) = (xy(e.vertices[0]), xy(e.vertices[1]));
                let (p, q) = if first(&a, &b) { (a, b) } else { (b, a) };
                let tau = match e.second {
                    None => 0.5,
                    Some((g, _)) => crossing(&p, &q, &centres[e.first.0], &centres[g]),
                };
                if tau > 0.0 && tau < 1.0 {
                    tau
                } else {
                    0.5
                }
            })
            .collect();
        let taus = (0..mesh.num_faces())
            .map(|f| {
                std::array::from_fn(|l| {
                    mesh.edge_index(f, l)
                        .ok()
                        .and_then(|e| edge_tau.get(e).copied())
                        .unwrap_or(0.5)
                })
            })
            .collect();
        FunctionalPowellSabin { taus }
    }

    /// The split parameters of face `f`'s edges (canonical orientation, see the field).
    pub fn face_taus(&self, f: usize) -> [f64; 3] {
        self.taus.get(f).copied().unwrap_or([0.5; 3])
    }
}

/// `[Q_a, M, Q_b]` of the edge from `a` to `b` split at `τ` along it (module docs).
fn edge_points(a: &Node, b: &Node, tau: f64) -> [Point3<f64>; 3] {
    let m = a.xy + (b.xy - a.xy) * tau;
    let qa = a.tangent(&((a.xy + m) / 2.0));
    let qb = b.tangent(&((m + b.xy) / 2.0));
    let mp = Point3::from(qa.coords * (1.0 - tau) + qb.coords * tau);
    [qa, mp, qb]
}

/// [`edge_points`] computed in the edge's canonical orientation (`tau` along it), returned in
/// the face's `a → b`, and `τ` along `a → b`.
fn shared_edge_points(a: &Node, b: &Node, tau: f64) -> ([Point3<f64>; 3], f64) {
    if first(&a.xy, &b.xy) {
        (edge_points(a, b, tau), tau)
    } else {
        let [qb, m, qa] = edge_points(b, a, tau);
        ([qa, m, qb], 1.0 - tau)
    }
}

/// The six quadratic nets of a face with corner data `nodes` and canonical edge split
/// parameters `taus` (module docs), in the order of [`SIX_SPLIT`].
pub fn macro_patch(nodes: &[Node; 3], taus: [f64; 3]) -> [[Point3<f64>; NP]; 6] {
    let p = nodes.map(|n| n.xy);
    let zeta = incentre_weights(&p);
    let z = p[0] * zeta[0] + p[1] * zeta[1] + p[2] * zeta[2];
    let edges: [([Point3<f64>; 3], f64); 3] =
        std::array::from_fn(|e| shared_edge_points(&nodes[e], &nodes[(e + 1) % 3], taus[e]));
    let w: [Point3<f64>; 3] = std::array::from_fn(|i| nodes[i].tangent(&((p[i] + z) / 2.0)));
    let r: [Point3<f64>; 3] = std::array::from_fn(|e| {
        let t = edges[e].1;
        Point3::from(w[e].coords * (1.0 - t) + w[(e + 1) % 3].coords * t)
    });
    let zp = Point3::from(w[0].coords * zeta[0] + w[1].coords * zeta[1] + w[2].coords * zeta[2]);
    std::array::from_fn(|k| {
        let e = k / 2;
        let b = (e + 1) % 3;
        let [qa, m, qb] = edges[e].0;
        if k % 2 == 0 {
            [nodes[e].point(), qa, m, w[e], r[e], zp]
        } else {
            [m, qb, nodes[b].point(), r[e], w[b], zp]
        }
    })
}

impl Scheme for FunctionalPowellSabin {
    fn name(&self) -> &'static str {
        "powell-sabin"
    }

    fn layout(&self) -> Layout {
        Layout::bezier(2, &SIX_SPLIT)
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
        let nodes = super::face_nodes(input)?;
        let nets = macro_patch(&nodes, self.face_taus(input.face));
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
        Ok(())
    }

    /// The same construction with a zero gradient where a normal does not point up: C0 with
    /// neighbours built from the same data (only reached on data [`super::detect`] refuses).
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        let nodes = super::nodes_or_flat(input);
        let nets = macro_patch(&nodes, self.face_taus(input.face));
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
    }
}

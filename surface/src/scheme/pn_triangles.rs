//! `pn-triangles`: curved PN triangles (Vlachos, Peters, Boyd and Mitchell, *Curved PN
//! Triangles*, I3D 2001).
//!
//! One cubic Bézier triangle per face from the three positions `P_a` and unit normals `N_a`:
//!
//! * corners `b_{3e_a} = P_a`;
//! * edge points next to `P_a` towards `P_b`: `(2P_a + P_b − w_ab N_a)/3` with
//!   `w_ab = (P_b − P_a)·N_a` — the point at a third of the edge projected onto `P_a`'s tangent
//!   plane;
//! * centre `b_111 = E + (E − V)/2`, `E` the mean of the six edge points, `V` the mean of the
//!   corners (the paper's choice, which reproduces quadratics' "centre" for flat data).
//!
//! The edge points depend only on the edge's two vertices, so neighbouring patches share their
//! boundary (C0); their geometric normals differ across edges. The paper pairs the geometry with
//! a separate quadratic normal field ([`normal_field`]): corner normals `N_a`, and edge normals
//! `n_ab = normalize(N_a + N_b − v_ab (P_b − P_a))`, `v_ab = 2 (P_b − P_a)·(N_a + N_b) /
//! |P_b − P_a|²` (the average normal reflected across the plane perpendicular to the edge),
//! which is continuous across edges and is what a renderer shades with.

use nalgebra::{Point3, Vector3};

use super::{Continuity, FaceInput, Layout, Scheme, WHOLE};
use crate::beztri::index;
use crate::fit::FaceFallbackReason;

/// Curved PN triangles.
#[derive(Clone, Copy, Debug, Default)]
pub struct PnTriangles;

/// The quadratic normal field of a face, in degree-2 net order (`n_200 = N_0`, … corners;
/// `n_110` … edges), each unit (module docs). Evaluate with [`eval_normal_field`].
pub fn normal_field(p: [Point3<f64>; 3], n: [Vector3<f64>; 3]) -> [Vector3<f64>; 6] {
    let n = n.map(|v| v.normalize());
    let mut out = [Vector3::zeros(); 6];
    for c in 0..3 {
        let mut m = [0usize; 3];
        m[c] = 2;
        out[index(2, m[0], m[1], m[2])] = n[c];
        let d = (c + 1) % 3;
        let e = p[d] - p[c];
        let len2 = e.norm_squared();
        let v = if len2 > 0.0 {
            2.0 * e.dot(&(n[c] + n[d])) / len2
        } else {
            0.0
        };
        let h = n[c] + n[d] - e * v;
        let mut m = [0usize; 3];
        m[c] = 1;
        m[d] = 1;
        out[index(2, m[0], m[1], m[2])] = h.try_normalize(0.0).unwrap_or(n[c]);
    }
    out
}

/// The normal field at barycentric `(u, v, w)`, normalized (the paper normalizes per pixel).
pub fn eval_normal_field(field: &[Vector3<f64>; 6], u: f64, v: f64, w: f64) -> Vector3<f64> {
    let l = [u, v, w];
    let mut s = Vector3::zeros();
    for c in 0..3 {
        let mut m = [0usize; 3];
        m[c] = 2;
        s += field[index(2, m[0], m[1], m[2])] * (l[c] * l[c]);
        let d = (c + 1) % 3;
        let mut m = [0usize; 3];
        m[c] = 1;
        m[d] = 1;
        s += field[index(2, m[0], m[1], m[2])] * (2.0 * l[c] * l[d]);
    }
    s.try_normalize(0.0).unwrap_or(s)
}

impl Scheme for PnTriangles {
    fn name(&self) -> &'static str {
        "pn-triangles"
    }

    fn layout(&self) -> Layout {
        Layout::bezier(3, &WHOLE)
    }

    fn continuity(&self) -> Continuity {
        Continuity::C0WithNormals
    }

    fn uses_curves(&self) -> bool {
        false
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        let p = input.vertices.map(|v| v.p);
        let n = input.vertices.map(|v| v.n.normalize());
        let mut edge_sum = Vector3::zeros();
        for a in 0..3 {
            let mut m = [0usize; 3];
            m[a] = 3;
            out[index(3, m[0], m[1], m[2])] = p[a];
            for b in [(a + 1) % 3, (a + 2) % 3] {
                // The face edge between a and b: leaving a (index a) or arriving (index b).
                let edge = if b == (a + 1) % 3 { a } else { b };
                let q = match input.crease_line(a, edge) {
                    // On a crease: the third point projected onto the crease line, which both
                    // faces share (`FaceInput::project`).
                    Some(t) => p[a].coords + t * (t.dot(&(p[b] - p[a])) / 3.0),
                    None => {
                        let w = (p[b] - p[a]).dot(&n[a]);
                        (p[a].coords * 2.0 + p[b].coords - n[a] * w) / 3.0
                    }
                };
                let mut m = [0usize; 3];
                m[a] = 2;
                m[b] = 1;
                out[index(3, m[0], m[1], m[2])] = Point3::from(q);
                edge_sum += q;
            }
        }
        let e = edge_sum / 6.0;
        let v = (p[0].coords + p[1].coords + p[2].coords) / 3.0;
        out[index(3, 1, 1, 1)] = Point3::from(e + (e - v) * 0.5);
        if out.iter().all(|q| q.iter().all(|c| c.is_finite())) {
            Ok(())
        } else {
            Err(FaceFallbackReason::NonFinite)
        }
    }
}

//! Corner measures of a macro-patch that Mann's Section 4 hopes to steer with β and c: the
//! normal curvature of each interior boundary at its data vertex, and the normalized mixed
//! partial of each sub-patch at each of its two data corners, each against the target the
//! vertex's shape tensor gives.
//!
//! For sub-patch `e` over `(V_e, V_{e+1}, S)` (see [`crate::shirman_sequin`]):
//!
//! * the interior boundary from `V_i` is the quartic `V_i, I¹, I², I³, S`, with
//!   `Q'(0) = 4(I¹ − V)` and `Q''(0) = 12(I² − 2I¹ + V)`; its normal curvature is
//!   `⟨n, Q''(0)⟩ / |Q'(0)|²`, the target `tᵀ S t` for `t = Q'(0)/|Q'(0)|`;
//! * the mixed second derivative at corner `a = V_e` along the domain directions `V_{e+1} − V_e`
//!   and `S − V_e` is `12(C¹ − q1 − I¹_a + V_a)` (the corner "twist" of the net), at corner
//!   `b = V_{e+1}` along `V_e − V_{e+1}` and `S − V_{e+1}` it is `12(C² − q3 − I¹_b + V_b)`;
//!   normalized by the lengths of the two first derivatives `4(q1 − V)`, `4(I¹ − V)`, its
//!   normal component is compared with `t_uᵀ S t_v`.
//!
//! Derivation of what the construction implies (module docs of `shirman_sequin` for the
//! formulas): `I¹ − V = β(E⁴_a + E⁴_b − 2V)` lies in the tangent plane and scales with β; the
//! normal components of `I² − I¹` and of `C − q` come only from the Chiyokura–Kimura terms
//! `k_0 Ĉ_1` and `2h_0 (E² − E¹)`, whose coefficients `k_0, h_0` are proportional to β and which
//! do not involve `c` (it multiplies `Ĉ_0 ⊥ n`). So `⟨n, Q''(0)⟩ ∝ β²` against `|Q'(0)|² ∝ β²`,
//! and the mixed partial's normal part `∝ β` against `|D_u||D_v| ∝ β`: both measures are
//! independent of β and c — Mann's claim, with the seed's stray `|I_i1 − V_i|` (which does move
//! with β) cancelled by the β in the mixed partial it forgot.

use nalgebra::{Point3, Vector3};

use crate::shirman_sequin::QuarticNet;
use curves::VertexData;

/// The measures at one corner of one macro-patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerMeasures {
    /// Normal curvature of the interior boundary at the vertex.
    pub boundary_curvature: f64,
    /// Its target from the shape tensor.
    pub boundary_target: f64,
    /// Normalized mixed partial of the sub-patch starting at this vertex (`e = i`).
    pub twist_start: f64,
    /// Normalized mixed partial of the sub-patch ending at this vertex (`e = i − 1`).
    pub twist_end: f64,
    /// Targets of the two twists.
    pub twist_targets: [f64; 2],
}

fn p(net: &QuarticNet, i: usize, j: usize, k: usize) -> Point3<f64> {
    net[crate::beztri::index(4, i, j, k)]
}

fn normalized_twist(
    v: &VertexData,
    du: Vector3<f64>,
    dv: Vector3<f64>,
    duv: Vector3<f64>,
) -> (f64, f64) {
    let n = v.n.normalize();
    let (lu, lv) = (du.norm(), dv.norm());
    let value = n.dot(&duv) / (lu * lv);
    let target = (du / lu).dot(&(v.shape * (dv / lv)));
    (value, target)
}

/// The measures at corners `0, 1, 2` of a macro-patch.
pub fn corner_measures(nets: &[QuarticNet; 3], vertices: [&VertexData; 3]) -> [CornerMeasures; 3] {
    std::array::from_fn(|i| {
        let v = vertices[i];
        let start = &nets[i];
        let end = &nets[(i + 2) % 3];
        // Interior boundary V_i → S on the i–k side of the sub-patch starting at V_i.
        let (b0, b1, b2) = (p(start, 4, 0, 0), p(start, 3, 0, 1), p(start, 2, 0, 2));
        let d1 = (b1 - b0) * 4.0;
        let d2 = (b2 - b1 * 2.0 + b0.coords) * 12.0;
        let n = v.n.normalize();
        let t = d1.normalize();
        let boundary_curvature = n.dot(&d2) / d1.norm_squared();
        let boundary_target = t.dot(&(v.shape * t));
        // Twist of the sub-patch starting at V_i (its corner a = b400).
        let (ts, tts) = normalized_twist(
            v,
            (p(start, 3, 1, 0) - b0) * 4.0,
            d1,
            (p(start, 2, 1, 1) - p(start, 3, 1, 0) - (b1 - b0)) * 12.0,
        );
        // Twist of the sub-patch ending at V_i (its corner b = b040).
        let c0 = p(end, 0, 4, 0);
        let (te, tte) = normalized_twist(
            v,
            (p(end, 1, 3, 0) - c0) * 4.0,
            (p(end, 0, 3, 1) - c0) * 4.0,
            (p(end, 1, 2, 1) - p(end, 1, 3, 0) - (p(end, 0, 3, 1) - c0)) * 12.0,
        );
        CornerMeasures {
            boundary_curvature,
            boundary_target,
            twist_start: ts,
            twist_end: te,
            twist_targets: [tts, tte],
        }
    })
}

/// Section 4's two objectives for one macro-patch as a least-squares problem in
/// `(β_0, β_1, β_2, c_0, c_1, c_2)`: residuals 0–2 are `κ_boundary − κn(t)` at the three
/// corners, residuals 3–8 the normalized twists minus `t_uᵀ S t_v` (start then end sub-patch of
/// each corner). The Jacobian is the chain rule through the measures' formulas (module docs)
/// applied to the exact net derivatives, not an assumption that it vanishes: that it does
/// vanish is then a measured fact (tests, `experiments -- interior`).
///
/// The objectives live beside the construction they differentiate rather than in `cost/`,
/// which cannot see the surface crate.
#[derive(Clone, Debug)]
pub struct CornerObjectives {
    vertices: [VertexData; 3],
    edges: [curves::CubicBez3; 3],
}

type Grad = [f64; 6];

/// A vector and its derivatives with respect to the six interior parameters.
pub type WithGradient = (Vector3<f64>, [Vector3<f64>; 6]);

/// The curvature measure at a corner ([`cost::corner::corner_curvature`]: the patch's normal
/// curvature along the first derivative `A`, with second derivative `B`, minus the vertex's)
/// and its gradient in the six parameters by the chain rule, applied once:
/// `∂κ/∂x_k = ⟨∂κ/∂A, ∂A/∂x_k⟩ + ⟨∂κ/∂B, ∂B/∂x_k⟩`.
pub fn normal_curvature_with_gradient(
    vd: &VertexData,
    a: &WithGradient,
    b: &WithGradient,
) -> (f64, Grad) {
    let (val, ga, gb) = cost::corner::corner_curvature(&vd.n.normalize(), &vd.shape, &a.0, &b.0);
    (
        val,
        std::array::from_fn(|k| ga.dot(&a.1[k]) + gb.dot(&b.1[k])),
    )
}

/// The twist measure at a corner ([`cost::corner::corner_twist`]: the patch's mixed second
/// derivative `W` against the unit directions of `U`, `V`, minus the vertex's) and its gradient
/// in the six parameters by the chain rule, applied once.
pub fn twist_with_gradient(
    vd: &VertexData,
    u: &WithGradient,
    w: &WithGradient,
    tw: &WithGradient,
) -> (f64, Grad) {
    let (val, gu, gv, gw) =
        cost::corner::corner_twist(&vd.n.normalize(), &vd.shape, &u.0, &w.0, &tw.0);
    (
        val,
        std::array::from_fn(|k| gu.dot(&u.1[k]) + gv.dot(&w.1[k]) + gw.dot(&tw.1[k])),
    )
}

impl CornerObjectives {
    /// The objectives of one face (vertex data, edge curves oriented along the face).
    pub fn new(vertices: [VertexData; 3], edges: [curves::CubicBez3; 3]) -> Self {
        CornerObjectives { vertices, edges }
    }

    fn params(x: &nalgebra::SVector<f64, 6>) -> crate::shirman_sequin::InteriorParameters {
        crate::shirman_sequin::InteriorParameters {
            beta: [x[0], x[1], x[2]],
            c: [x[3], x[4], x[5]],
        }
    }

    /// Residuals and their gradients.
    fn eval(&self, x: &nalgebra::SVector<f64, 6>) -> Option<([f64; 9], [Grad; 9])> {
        let v = [&self.vertices[0], &self.vertices[1], &self.vertices[2]];
        let (nets, d) =
            crate::shirman_sequin::macro_patch_with_derivatives(v, &self.edges, &Self::params(x))
                .ok()?;
        let at = |e: usize, i: usize, j: usize, k: usize| {
            let idx = crate::beztri::index(4, i, j, k);
            (nets[e][idx].coords, d[e][idx])
        };
        type J = (Vector3<f64>, [Vector3<f64>; 6]);
        let curvature = |vd: &VertexData, a: J, b: J| normal_curvature_with_gradient(vd, &a, &b);
        let twist = |vd: &VertexData, u: J, w: J, tw: J| twist_with_gradient(vd, &u, &w, &tw);
        let lin = |parts: &[(f64, J)]| -> J {
            let v = parts.iter().map(|(w, p)| p.0 * *w).sum();
            let d = std::array::from_fn(|k| parts.iter().map(|(w, p)| p.1[k] * *w).sum());
            (v, d)
        };
        let mut r = [0.0; 9];
        let mut g = [[0.0; 6]; 9];
        for i in 0..3 {
            let vd = &self.vertices[i];
            let s = i;
            let e = (i + 2) % 3;
            let (b0, b1, b2) = (at(s, 4, 0, 0), at(s, 3, 0, 1), at(s, 2, 0, 2));
            let d1 = lin(&[(4.0, b1), (-4.0, b0)]);
            let d2 = lin(&[(12.0, b2), (-24.0, b1), (12.0, b0)]);
            (r[i], g[i]) = curvature(vd, d1, d2);
            let u = lin(&[(4.0, at(s, 3, 1, 0)), (-4.0, b0)]);
            let w = lin(&[
                (12.0, at(s, 2, 1, 1)),
                (-12.0, at(s, 3, 1, 0)),
                (-12.0, b1),
                (12.0, b0),
            ]);
            (r[3 + 2 * i], g[3 + 2 * i]) = twist(vd, u, d1, w);
            let c0 = at(e, 0, 4, 0);
            let ue = lin(&[(4.0, at(e, 1, 3, 0)), (-4.0, c0)]);
            let ve = lin(&[(4.0, at(e, 0, 3, 1)), (-4.0, c0)]);
            let we = lin(&[
                (12.0, at(e, 1, 2, 1)),
                (-12.0, at(e, 1, 3, 0)),
                (-12.0, at(e, 0, 3, 1)),
                (12.0, c0),
            ]);
            (r[4 + 2 * i], g[4 + 2 * i]) = twist(vd, ue, ve, we);
        }
        Some((r, g))
    }
}

impl solver::LeastSquaresProblem<6, 9> for CornerObjectives {
    fn residuals(&self, x: &nalgebra::SVector<f64, 6>) -> nalgebra::SVector<f64, 9> {
        self.eval(x)
            .map(|(r, _)| nalgebra::SVector::from(r))
            .unwrap_or_else(|| nalgebra::SVector::from_element(f64::NAN))
    }

    fn jacobian(&self, x: &nalgebra::SVector<f64, 6>) -> nalgebra::SMatrix<f64, 9, 6> {
        self.eval(x)
            .map(|(_, g)| nalgebra::SMatrix::from_fn(|i, k| g[i][k]))
            .unwrap_or_else(|| nalgebra::SMatrix::from_element(f64::NAN))
    }

    fn lower_bounds(&self) -> nalgebra::SVector<f64, 6> {
        nalgebra::SVector::from(crate::fairing::LOWER)
    }
}

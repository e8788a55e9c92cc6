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

use crate::fairing::MacroPatchConstruction;
use crate::shirman_sequin::QuarticNet;
use cost::corner::{CornerMeasure, CornerOnNet, CornerSet};
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
/// each corner). The measures are stated on the nets in [`cost::corner::CornerOnNet`] and
/// composed with the construction ([`crate::fairing::MacroPatchConstruction`]) by
/// [`cost::Composed`], which applies the chain rule: the Jacobian is computed, not assumed to
/// vanish, and that it does vanish is then a measured fact (tests, `experiments -- interior`).
pub type CornerObjectives = cost::Composed<CornerSet<9>, MacroPatchConstruction>;

/// [`CornerObjectives`] of one face (vertex data, edge curves oriented along the face). The
/// sub-patch `e` is net `e` of the construction, over `(V_e, V_{e+1}, S)` = corners 0, 1, 2.
pub fn corner_objectives(
    vertices: [VertexData; 3],
    edges: [curves::CubicBez3; 3],
) -> CornerObjectives {
    let np = crate::beztri::num_points(4);
    let mut measures = Vec::with_capacity(9);
    let on = |net: usize, corner: usize, measure: CornerMeasure, vd: &VertexData| {
        CornerOnNet::new(4, net * np, corner, measure, vd.n.normalize(), vd.shape)
    };
    // The corners and directions are fixed and valid, so `on` always succeeds; `flatten`
    // keeps that a matter of types rather than a panic.
    for (i, vd) in vertices.iter().enumerate() {
        measures.extend(on(i, 0, CornerMeasure::Curvature { toward: 2 }, vd));
    }
    for (i, vd) in vertices.iter().enumerate() {
        measures.extend(on(i, 0, CornerMeasure::Twist { u: 1, v: 2 }, vd));
        measures.extend(on((i + 2) % 3, 1, CornerMeasure::Twist { u: 0, v: 2 }, vd));
    }
    // Nine measures always fit nine residuals.
    let set = CornerSet::new(measures).unwrap_or_default();
    cost::Composed::new(set, MacroPatchConstruction::new(vertices, edges))
}

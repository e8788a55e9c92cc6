//! Measures of a fit's boundary curves over all edges, on the edges' unit-chord problems
//! (the quality measures of docs/conventions.md, "Boundary curves").

use curves::{BoundaryProblem, CubicBez3, EdgeError};

use crate::fit::Fit;
use crate::mesh::Mesh;
use crate::metrics::median;

/// Every edge of `mesh` as a boundary-curve problem, in edge order (a crease edge's with its
/// crease data, [`crate::fit::edge_ends`]); the first degenerate edge is an error naming it.
pub fn edge_problems(mesh: &Mesh) -> Result<Vec<BoundaryProblem>, EdgeError> {
    mesh.edges()
        .enumerate()
        .map(|(ei, e)| {
            let [a, b] = e.vertices;
            let ends = crate::fit::edge_ends(mesh, ei);
            BoundaryProblem::new((a, b), &ends.data[0], &ends.data[1])
        })
        .collect()
}

/// Statistics of one construction's boundary curves over all edges (unit-chord measures).
#[derive(Default)]
pub struct CurveStats {
    /// Largest |κ − k| at a curve end.
    pub end_curvature_error_max: f64,
    /// RMS of |κ − k| over all curve ends.
    pub end_curvature_error_rms: f64,
    /// Shortest end-derivative length α.
    pub shortest_alpha: f64,
    /// Largest ∫(dκ/ds)² ds.
    pub curvature_variation_max: f64,
    /// Median ∫(dκ/ds)² ds.
    pub curvature_variation_median: f64,
    /// Edges that fell back to the chord curve.
    pub fallbacks: usize,
    /// Edges whose optimization did not converge.
    pub unconverged: usize,
}

/// Relative distance (in chord lengths) beyond which a fit's world curve is not the planar
/// problem's curve for its α: far above the similarity map's rounding (~1e-16), far below any
/// construction's difference (a projection-rule tangent turns by up to 0.1 rad on the ring).
const SAME_CURVE: f64 = 1e-12;

/// Curve measures of a fit's edge curves.
///
/// An edge whose world curve is the planar problem's curve for its α (every construction but
/// the projection rules, away from crease ends) is measured on its unit problem: the signed
/// end curvatures against the targets `k`, and the variation of the unit curve. Any other curve
/// (built in space, `curves::CurveMethod::space_curve`, or turned to a crease line) is measured
/// as it is, scaled to the unit chord: its curvature variation in space
/// ([`curves::CubicBez3::curvature_variation`]), and at each end the error of its normal
/// curvature against the surface's in its own tangent direction `t'`,
/// `|κ⃗·n − t'ᵀ S t'| / |⟨w × t, n⟩|` (`t` the plane's tangent). For a curve in the plane this
/// is `|κ − k|` exactly: its curvature vector is `κ (w × t)` and `k = κn(t)/⟨w × t, n⟩` by
/// Meusnier's theorem (curves::problem), so the two kinds of edge are measured alike.
pub fn curve_stats(problems: &[BoundaryProblem], fit: &Fit) -> CurveStats {
    let mut s = CurveStats {
        shortest_alpha: f64::INFINITY,
        fallbacks: fit.fallbacks,
        unconverged: fit.unconverged,
        ..CurveStats::default()
    };
    let mut sq = 0.0;
    let mut vars = Vec::with_capacity(problems.len());
    for (i, (p, a)) in problems.iter().zip(&fit.alphas).enumerate() {
        let world = fit
            .curves
            .get(i)
            .filter(|c| !same_curve(&p.curve(*a), c, p));
        let (errors, v) = match world {
            None => {
                let k = p.unit.end_curvatures(*a);
                (
                    [(k[0] - p.unit.k0).abs(), (k[1] - p.unit.k1).abs()],
                    p.unit.curve(*a).curvature_variation(),
                )
            }
            Some(c) => (space_end_errors(c, p), unit_variation(c, p)),
        };
        for e in errors {
            s.end_curvature_error_max = s.end_curvature_error_max.max(e);
            sq += e * e;
        }
        s.shortest_alpha = s.shortest_alpha.min(a[0].min(a[1]));
        s.curvature_variation_max = s.curvature_variation_max.max(v);
        vars.push(v);
    }
    s.end_curvature_error_rms = (sq / (2 * problems.len().max(1)) as f64).sqrt();
    s.curvature_variation_median = median(vars);
    s
}

/// Whether `built` is `planar` (the problem's curve for the fit's α) to [`SAME_CURVE`] chords.
fn same_curve(planar: &CubicBez3, built: &CubicBez3, p: &BoundaryProblem) -> bool {
    let tol = SAME_CURVE * p.frame.scale;
    planar
        .points
        .iter()
        .zip(&built.points)
        .all(|(x, y)| (x - y).norm() <= tol)
}

/// The unit-chord end-curvature errors of a curve measured in space (see [`curve_stats`]).
fn space_end_errors(c: &CubicBez3, p: &BoundaryProblem) -> [f64; 2] {
    let w = p.frame.w;
    [0.0, 1.0].map(|t| {
        let end = usize::from(t > 0.5);
        let n = p.normals[end];
        let tangent = c.deriv(t).normalize();
        let target = tangent.dot(&(p.shapes[end] * tangent));
        let got = c.curvature_vector(t).dot(&n);
        let meusnier = w.cross(&p.tangents[end]).dot(&n).abs();
        (got - target).abs() / meusnier * p.frame.scale
    })
}

/// The unit-chord curvature variation of a world curve: `∫ (dκ/ds)² ds` scales as
/// length⁻³, so the world value times `|d|³`.
fn unit_variation(c: &CubicBez3, p: &BoundaryProblem) -> f64 {
    c.curvature_variation() * p.frame.scale.powi(3)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The space measures of a planar curve equal the unit problem's: rounding of a few
    /// similarity maps and one division, on values of order one to ten.
    const SAME_MEASURE: f64 = 1e-9;

    /// On a torus edge (different curvatures at the two ends, normals out of the chord's
    /// plane), the planar problem's own curve measured in space gives the unit problem's
    /// `|κ − k|` at both ends and its curvature variation: the two ways of measuring agree
    /// where both apply.
    #[test]
    fn a_planar_curve_measured_in_space_gives_the_unit_measures() {
        let a = mesh::analytic::torus_point(0.1, 0.4, 1.0, 0.4);
        let b = mesh::analytic::torus_point(0.5, 1.1, 1.0, 0.4);
        let p = BoundaryProblem::new((0, 1), &a, &b).expect("a valid edge");
        for alpha in [[1.0, 1.0], [0.7, 1.3], [1.4, 0.9]] {
            let k = p.unit.end_curvatures(alpha);
            let want = [(k[0] - p.unit.k0).abs(), (k[1] - p.unit.k1).abs()];
            let got = space_end_errors(&p.curve(alpha), &p);
            for i in 0..2 {
                assert!(
                    (got[i] - want[i]).abs() < SAME_MEASURE * want[i].max(1.0),
                    "α {alpha:?} end {i}: {} vs {}",
                    got[i],
                    want[i]
                );
            }
            let (v_unit, v_space) = (
                p.unit.curve(alpha).curvature_variation(),
                unit_variation(&p.curve(alpha), &p),
            );
            assert!(
                (v_unit - v_space).abs() < SAME_MEASURE * v_unit.max(1.0),
                "{v_unit} vs {v_space}"
            );
        }
    }
}

//! Measures of a fit's boundary curves over all edges, on the edges' unit-chord problems
//! (the quality measures of docs/conventions.md, "Boundary curves").

use curves::{BoundaryProblem, EdgeError};

use crate::fit::Fit;
use crate::mesh::Mesh;
use crate::metrics::median;

/// Every edge of `mesh` as a boundary-curve problem, in edge order (a crease edge's with its
/// crease data, [`crate::fit::edge_ends`]); the first degenerate edge is an error naming it.
pub fn edge_problems(mesh: &Mesh) -> Result<Vec<BoundaryProblem>, EdgeError> {
    mesh.edges()
        .iter()
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

/// Curve measures of a fit's edge curves, from the edges' unit problems.
pub fn curve_stats(problems: &[BoundaryProblem], fit: &Fit) -> CurveStats {
    let mut s = CurveStats {
        shortest_alpha: f64::INFINITY,
        fallbacks: fit.fallbacks,
        unconverged: fit.unconverged,
        ..CurveStats::default()
    };
    let mut sq = 0.0;
    let mut vars = Vec::with_capacity(problems.len());
    for (p, a) in problems.iter().zip(&fit.alphas) {
        let k = p.unit.end_curvatures(*a);
        for (got, want) in k.iter().zip([p.unit.k0, p.unit.k1]) {
            let e = (got - want).abs();
            s.end_curvature_error_max = s.end_curvature_error_max.max(e);
            sq += e * e;
        }
        s.shortest_alpha = s.shortest_alpha.min(a[0].min(a[1]));
        let v = p.unit.curve(*a).curvature_variation();
        s.curvature_variation_max = s.curvature_variation_max.max(v);
        vars.push(v);
    }
    s.end_curvature_error_rms = (sq / (2 * problems.len().max(1)) as f64).sqrt();
    s.curvature_variation_median = median(vars);
    s
}

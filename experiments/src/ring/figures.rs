//! Figure 2 of the ring study (Mann 1994's Figure 2, on the ring): the boundary curves of the two
//! edges where the constructions differ most, chosen by a stated rule, with their curvature.

use std::path::Path;

use curves::BoundaryProblem;
use render::{CurveFigure, CurvePanel};
use serde_json::{json, Value};

use crate::error::ExperimentError;

use super::surfaces::FittedMethod;

/// Figure 2: the two edges where the constructions differ most, by a stated rule.
pub(super) fn figure2(
    out: &Path,
    problems: &[BoundaryProblem],
    fits: &[FittedMethod],
) -> Result<Value, ExperimentError> {
    let alpha = |m: usize, e: usize| fits[m].fit.alphas[e];
    let short = |a: [f64; 2]| a[0].min(a[1]);
    // Rule 1: the shortest dBHS end derivative; rule 2: the largest chord end-curvature error
    // among the remaining edges.
    let e1 = (0..problems.len())
        .min_by(|&a, &b| short(alpha(1, a)).total_cmp(&short(alpha(1, b))))
        .unwrap_or(0);
    let chord_err = |e: usize| {
        let k = problems[e].unit.end_curvatures(alpha(0, e));
        (k[0] - problems[e].unit.k0)
            .abs()
            .max((k[1] - problems[e].unit.k1).abs())
    };
    let e2 = (0..problems.len())
        .filter(|&e| e != e1)
        .max_by(|&a, &b| chord_err(a).total_cmp(&chord_err(b)))
        .unwrap_or(0);
    let rows: Vec<Vec<CurvePanel>> = [e1, e2]
        .iter()
        .map(|&e| {
            let p = &problems[e];
            fits.iter()
                .enumerate()
                .map(|(m, FittedMethod { name, .. })| {
                    let a = alpha(m, e);
                    CurvePanel {
                        title: format!("{name}, edge {}–{}", p.edge.0, p.edge.1),
                        curve: p.unit.curve(a),
                        targets: [p.unit.k0, p.unit.k1],
                        notes: vec![format!("α = ({:.4}, {:.4})", a[0], a[1])],
                    }
                })
                .collect()
        })
        .collect();
    render::write_curve_figure(
        &CurveFigure {
            title:
                "Ring boundary curves (unit chord) and their curvature, as in Figure 2 of Mann 1994"
                    .into(),
            rows,
        },
        &out.join("figure2.png"),
        &out.join("figure2.svg"),
    )?;
    Ok(json!({
        "rule": "row 1: the edge with the shortest dBHS end derivative; row 2: among the others, the edge with the largest chord end-curvature error",
        "edges": [[problems[e1].edge.0, problems[e1].edge.1], [problems[e2].edge.0, problems[e2].edge.1]],
        "file": "figure2.png",
    }))
}

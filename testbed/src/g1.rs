//! The seed's `G1` as a filter: every record passes through unchanged; the BezierTriangles
//! are kept aside and, at the end of the stream, boundaries shared by two patches are found
//! and the normals of both compared along them.
//!
//! Two patches share a boundary when their boundary curves have **equal control points**
//! (bit for bit, `-0` = `0`), in reverse order (the usual case: neighbours traverse their
//! common edge in opposite directions) or in the same order (then the two patches are
//! oppositely oriented: counted, and the normal of the second is flipped before comparing).
//! Boundaries of different degrees are not matched. At `samples` equally spaced parameters
//! (ends included) the angle `atan2(|n₁ × n₂|, n₁ · n₂)` is measured; samples where either
//! normal is undefined (a collapsed corner) are skipped and counted.

use std::collections::HashMap;

use surface::BezierTriangle;

use crate::error::FilterError;
use crate::filters::Pipe;
use crate::record;

/// Largest normal angle (radians) along a shared boundary still called G1 by `--strict`:
/// 1e-6 rad is far above the rounding of a patch carried through the text formats and the
/// working frame's way back (about 1e-12 rad measured on `shirman-sequin`), far below any
/// crease a picture shows (a tenth of a degree is 1.7e-3 rad).
pub const G1_TOLERANCE: f64 = 1e-6;

/// Default samples per boundary (ends included).
pub const DEFAULT_SAMPLES: usize = 9;

/// What the G1 measurement found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct G1Summary {
    /// Patches read.
    pub patches: usize,
    /// Boundaries shared by two (or more) patches.
    pub shared: usize,
    /// Boundary curves belonging to one patch only (the surface's border, or a neighbour
    /// whose curve differs: not tangent-continuous at all, or not even C0).
    pub unmatched: usize,
    /// Shared boundaries traversed in the same direction by both patches.
    pub orientation_mismatches: usize,
    /// Samples skipped for an undefined normal.
    pub undefined: usize,
    /// The largest angle (radians) and where: record numbers, edges and parameter of the
    /// first patch's edge.
    pub worst: Option<Worst>,
}

/// Where the largest angle was measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Worst {
    /// Angle in radians.
    pub angle: f64,
    /// Record number of the first patch.
    pub record_a: usize,
    /// Its edge (0: `w = 0` from `u` to `v`; 1: `u = 0`; 2: `v = 0`).
    pub edge_a: usize,
    /// Record number of the second patch.
    pub record_b: usize,
    /// Its edge.
    pub edge_b: usize,
    /// Parameter along the first patch's edge.
    pub t: f64,
}

/// Barycentric `(u, v)` of parameter `t` along edge `e` (as `BezierTriangle::boundary_curve`).
fn edge_point(e: usize, t: f64) -> (f64, f64) {
    match e {
        0 => (1.0 - t, t),
        1 => (0.0, 1.0 - t),
        _ => (t, 0.0),
    }
}

fn bits(p: &nalgebra::Point3<f64>) -> [u64; 3] {
    [
        (p.x + 0.0).to_bits(),
        (p.y + 0.0).to_bits(),
        (p.z + 0.0).to_bits(),
    ]
}

/// One patch edge on a boundary: patch index, edge, traversed against the canonical order.
type Use = (usize, usize, bool);

/// Measures `patches` (each with its record number).
pub fn measure(patches: &[(usize, BezierTriangle)], samples: usize) -> G1Summary {
    let samples = samples.max(2);
    let mut out = G1Summary {
        patches: patches.len(),
        ..G1Summary::default()
    };
    // Canonical key: the control points in the lexicographically smaller direction.
    let mut boundaries: HashMap<Vec<[u64; 3]>, Vec<Use>> = HashMap::new();
    for (pi, (_, patch)) in patches.iter().enumerate() {
        for e in 0..3 {
            let Some(curve) = patch.boundary_curve(e) else {
                continue;
            };
            let fwd: Vec<[u64; 3]> = curve.points.iter().map(bits).collect();
            let mut rev = fwd.clone();
            rev.reverse();
            let (key, reversed) = if rev < fwd { (rev, true) } else { (fwd, false) };
            boundaries.entry(key).or_default().push((pi, e, reversed));
        }
    }
    let mut keys: Vec<_> = boundaries.into_iter().collect();
    keys.sort_by(|a, b| a.1.cmp(&b.1)); // deterministic order
    for (_, users) in keys {
        let Some((&(pa, ea, ra), rest)) = users.split_first() else {
            continue;
        };
        if rest.is_empty() {
            out.unmatched += 1;
            continue;
        }
        out.shared += 1;
        for &(pb, eb, rb) in rest {
            let same_direction = ra == rb;
            out.orientation_mismatches += usize::from(same_direction);
            for m in 0..samples {
                let s = m as f64 / (samples - 1) as f64;
                // Canonical parameter s → each patch's own edge parameter.
                let ta = if ra { 1.0 - s } else { s };
                let tb = if rb { 1.0 - s } else { s };
                let (ua, va) = edge_point(ea, ta);
                let (ub, vb) = edge_point(eb, tb);
                let (Some(na), Some(nb)) =
                    (patches[pa].1.normal(ua, va), patches[pb].1.normal(ub, vb))
                else {
                    out.undefined += 1;
                    continue;
                };
                let nb = if same_direction { -nb } else { nb };
                let angle = na.cross(&nb).norm().atan2(na.dot(&nb));
                if out.worst.is_none_or(|w| angle > w.angle) {
                    out.worst = Some(Worst {
                        angle,
                        record_a: patches[pa].0,
                        edge_a: ea,
                        record_b: patches[pb].0,
                        edge_b: eb,
                        t: ta,
                    });
                }
            }
        }
    }
    out
}

/// `g1 [--strict] [--samples N]`: passes every record through, measures the patches at the
/// end, reports on standard error; with `strict` an angle above [`G1_TOLERANCE`] is an error.
pub fn g1(pipe: &mut Pipe, strict: bool, samples: usize) -> Result<G1Summary, FilterError> {
    let mut patches = Vec::new();
    let mut rec = crate::stream::Record::default();
    while pipe.next_good(&mut rec)? {
        if rec.kind() == "BezierTriangle" {
            match record::bezier_triangle(&rec.tape) {
                Ok(p) => patches.push((rec.at.record, p)),
                Err(e) => {
                    pipe.bad_field(&rec, e)?;
                    continue;
                }
            }
        }
        pipe.write(&rec)?;
    }
    pipe.finish()?;
    let summary = measure(&patches, samples);
    eprintln!(
        "g1: {} patches, {} shared boundaries, {} unshared, {} orientation mismatches, {} undefined normals",
        summary.patches, summary.shared, summary.unmatched, summary.orientation_mismatches, summary.undefined
    );
    if let Some(w) = summary.worst {
        let verdict = if w.angle > G1_TOLERANCE {
            "warning: not G1"
        } else {
            "G1 within tolerance"
        };
        eprintln!(
            "g1: {verdict}: largest normal angle {:.3e} rad ({:.4}°) between record {} edge {} and record {} edge {} at t = {:.3} (tolerance {:.0e} rad)",
            w.angle,
            w.angle.to_degrees(),
            w.record_a,
            w.edge_a,
            w.record_b,
            w.edge_b,
            w.t,
            G1_TOLERANCE
        );
        if strict && w.angle > G1_TOLERANCE {
            return Err(FilterError::G1Exceeded {
                angle: w.angle,
                tolerance: G1_TOLERANCE,
            });
        }
    }
    Ok(summary)
}

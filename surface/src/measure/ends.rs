//! The seeds' finding on boundary curves, measured: cubic boundary curves built from end data
//! alone "concentrate the curvature near their ends and leave flat regions in the middle"
//! (Lounsbery et al. 1990, §6 on the ring; Mann 1994 on the chord and dBHS curves), and the
//! surface along them inherits it.
//!
//! For each mesh edge, the **curve's** curvature `κ(t) = |c′ × c″|/|c′|³` and the **surface's**
//! normal curvature along the edge, `κn = dᵀ S d` (`d` the unit tangent of the patch boundary
//! over the edge, `S` the patch's shape tensor there; taken from the edge's first face), are
//! averaged in absolute value over the two end stretches `t ∈ [0, END) ∪ (1 − END, 1]` and over
//! the middle `t ∈ [MIDDLE.0, MIDDLE.1]` ([`SAMPLES`] points each, uniform in the edge's
//! parameter). Their ratio `ends / middle` is 1 on a curve of constant curvature, above 1 where
//! the curvature gathers at the ends. The true surface's normal curvature along the same
//! directions at the closest points gives the ratio the geometry itself has (the torus's
//! curvature does vary along an edge): the finding holds where the fitted ratio exceeds the
//! true one. Each is summarized over the edges by its median and the share of edges above the
//! truth (or above 1 without a truth).

use nalgebra::{Point3, Vector3};

use crate::fit::Fit;
use crate::mesh::Mesh;
use crate::AnalyticSurface;

/// Each end stretch, as a share of the edge's parameter.
pub const END: f64 = 0.2;
/// The middle stretch.
pub const MIDDLE: (f64, f64) = (0.3, 0.7);
/// Sample points per stretch (each end stretch and the middle).
pub const SAMPLES: usize = 16;
/// Most edges measured: on a larger mesh every `⌈E / MAX_EDGES⌉`-th edge (and curve) by index,
/// an even sample whose median and shares are those of the whole to a few per cent, at a cost
/// that stays below the fit's (48 patch evaluations an edge, two closest points with a truth).
pub const MAX_EDGES: usize = 4096;

/// Below this mean |curvature| in the middle and at the ends alike (in the fit's units), an edge
/// is straight and its ratio undefined: not counted (a planar face's edges).
pub const STRAIGHT: f64 = 1e-9;

/// Ends-to-middle ratios over the edges.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct RatioStats {
    /// Edges measured (straight ones and those without a patch left out).
    pub edges: usize,
    /// Median of the ratio.
    pub median: f64,
    /// Share of the edges whose ratio exceeds the reference (the truth's at the same edge, or 1).
    pub above_reference: f64,
}

/// The measure of a fit (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct EndsReport {
    /// The boundary curves' own curvature (`None` for schemes without edge curves).
    pub curves: Option<RatioStats>,
    /// The surface's normal curvature along the edges (`None` for layouts that are not Bézier).
    pub surface: Option<RatioStats>,
    /// The true surface's, along the same directions (`None` without a truth or a surface).
    pub truth: Option<RatioStats>,
}

/// The sample parameters of the three stretches: ends (both), then middle.
fn stretches() -> ([f64; 2 * SAMPLES], [f64; SAMPLES]) {
    let mut ends = [0.0; 2 * SAMPLES];
    let mut middle = [0.0; SAMPLES];
    for i in 0..SAMPLES {
        let s = (i as f64 + 0.5) / SAMPLES as f64;
        ends[i] = s * END;
        ends[SAMPLES + i] = 1.0 - s * END;
        middle[i] = MIDDLE.0 + s * (MIDDLE.1 - MIDDLE.0);
    }
    (ends, middle)
}

/// The ratio of the mean of `f` over the ends to its mean over the middle, `None` for a
/// straight (or unmeasurable) edge.
fn ratio(f: &dyn Fn(f64) -> Option<f64>) -> Option<f64> {
    let (ends, middle) = stretches();
    let values = |ts: &[f64]| ts.iter().map(|&t| f(t)).collect::<Option<Vec<f64>>>();
    ratio_of(&values(&ends)?, &values(&middle)?)
}

/// The ratio of the mean |value| at the ends to that in the middle (module docs).
fn ratio_of(ends: &[f64], middle: &[f64]) -> Option<f64> {
    let mean = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>() / v.len().max(1) as f64;
    let (e, m) = (mean(ends), mean(middle));
    if !(e.is_finite() && m.is_finite()) || e.max(m) < STRAIGHT {
        return None;
    }
    Some(if m > 0.0 { e / m } else { f64::INFINITY })
}

/// Median and share above the reference of `ratios` (`(ratio, reference)` pairs).
fn stats(pairs: &[(f64, f64)]) -> Option<RatioStats> {
    if pairs.is_empty() {
        return None;
    }
    let mut r: Vec<f64> = pairs.iter().map(|p| p.0).collect();
    r.sort_by(f64::total_cmp);
    let median = if r.len() % 2 == 1 {
        r[r.len() / 2]
    } else {
        0.5 * (r[r.len() / 2 - 1] + r[r.len() / 2])
    };
    let above = pairs.iter().filter(|(a, b)| a > b).count();
    Some(RatioStats {
        edges: pairs.len(),
        median,
        above_reference: above as f64 / pairs.len() as f64,
    })
}

/// Where the surface of face `f` is at parameter `t` of its local edge `l` (corner `l` to
/// corner `l + 1`): the patch over it, its point and the edge's unit tangent, and the shape
/// tensor there; `None` when the layout is not Bézier or the patch is singular there.
fn surface_at(
    fit: &Fit,
    f: usize,
    l: usize,
    t: f64,
) -> Option<(Point3<f64>, Vector3<f64>, nalgebra::Matrix3<f64>)> {
    let layout = &fit.layout;
    let (b, off) = ((l + 1) % 3, (l + 2) % 3);
    for (s, sub) in layout.subs.iter().enumerate() {
        for k in 0..3 {
            let (i, j) = (k, (k + 1) % 3);
            let (ci, cj) = (sub[i], sub[j]);
            // The sub-edge lies on the face's edge l when both corners have no weight on the
            // corner opposite it.
            if ci[off].abs() > 1e-12 || cj[off].abs() > 1e-12 {
                continue;
            }
            let (ti, tj) = (ci[b], cj[b]);
            let (lo, hi) = (ti.min(tj), ti.max(tj));
            if t < lo || t > hi || hi - lo <= 0.0 {
                continue;
            }
            let tau = (t - ti) / (tj - ti);
            let mut at = [0.0; 3];
            at[i] = 1.0 - tau;
            at[j] = tau;
            let patch = fit.patch(f * layout.patches_per_face() + s)?;
            let mut dir = [0.0; 3];
            dir[i] = -1.0;
            dir[j] = 1.0;
            let d = patch.directional(at, &[dir]);
            let sign = if tj > ti { 1.0 } else { -1.0 };
            let c = patch.curvature(at[0], at[1])?;
            return Some((
                patch.eval(at[0], at[1], at[2]),
                (d * sign).try_normalize(0.0)?,
                c.shape,
            ));
        }
    }
    None
}

/// Measures `fit` of `mesh` (module docs); `truth` the true surface when there is one.
pub fn measure(mesh: &Mesh, fit: &Fit, truth: Option<&dyn AnalyticSurface>) -> EndsReport {
    let stride = |n: usize| n.div_ceil(MAX_EDGES).max(1);
    let mut curves = Vec::new();
    for c in fit.curves.iter().step_by(stride(fit.curves.len())) {
        if let Some(r) = ratio(&|t| Some(c.curvature(t)).filter(|k| k.is_finite())) {
            curves.push((r, 1.0));
        }
    }
    let mut surface = Vec::new();
    let mut truths = Vec::new();
    if fit.layout.is_bezier() {
        let (ends, middle) = stretches();
        for e in mesh.edges().step_by(stride(mesh.num_edges())) {
            let (f, l) = e.first;
            // Each sample's point, tangent and the fit's shape tensor, once.
            let at = |ts: &[f64]| {
                ts.iter()
                    .map(|&t| surface_at(fit, f, l, t))
                    .collect::<Option<Vec<_>>>()
            };
            let (Some(se), Some(sm)) = (at(&ends), at(&middle)) else {
                continue;
            };
            let normal = |v: &[(Point3<f64>, Vector3<f64>, nalgebra::Matrix3<f64>)]| -> Vec<f64> {
                v.iter().map(|(_, d, s)| d.dot(&(s * d))).collect()
            };
            let Some(fitted) = ratio_of(&normal(&se), &normal(&sm)) else {
                continue;
            };
            let true_normal = |tr: &dyn AnalyticSurface,
                               v: &[(Point3<f64>, Vector3<f64>, nalgebra::Matrix3<f64>)]|
             -> Vec<f64> {
                v.iter()
                    .map(|(p, d, _)| {
                        let s = tr.closest(p).data.shape;
                        d.dot(&(s * d))
                    })
                    .collect()
            };
            let reference =
                truth.and_then(|tr| ratio_of(&true_normal(tr, &se), &true_normal(tr, &sm)));
            match reference {
                Some(r) => {
                    surface.push((fitted, r));
                    truths.push((r, 1.0));
                }
                None => surface.push((fitted, 1.0)),
            }
        }
    }
    EndsReport {
        curves: stats(&curves),
        surface: stats(&surface),
        truth: stats(&truths),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A circular arc of constant curvature has ratio 1 to rounding; a cubic whose end
    /// derivatives are long (α = 2) bends hardest near its ends.
    #[test]
    fn constant_curvature_is_one_and_long_tangents_gather_it_at_the_ends() {
        let r = ratio(&|_| Some(2.0)).unwrap();
        assert!((r - 1.0).abs() < 1e-15);
        assert_eq!(ratio(&|_| Some(0.0)), None, "straight");
        let p = curves::UnitProblem::new(
            nalgebra::Vector2::new(0.8, 0.6),
            nalgebra::Vector2::new(0.8, -0.6),
            0.0,
            0.0,
        )
        .unwrap();
        let long = p.curve([2.0, 2.0]);
        let short = p.curve([0.6, 0.6]);
        let rl = ratio(&|t| Some(long.curvature(t))).unwrap();
        let rs = ratio(&|t| Some(short.curvature(t))).unwrap();
        assert!(
            rl < rs,
            "long end derivatives flatten the ends: {rl} vs {rs}"
        );
        assert!(rs > 1.0, "short ones gather the curvature there: {rs}");
    }

    /// On the ring: the measure runs on a Shirman–Séquin fit, every curve measured but the 32
    /// straight ones (the edges of the top and bottom circles: their normals are ±z, so the
    /// curve's plane is vertical and both tangents run along the chord), and the torus's own
    /// ratio (its curvature along the edges) stays near 1.
    #[test]
    fn the_ring_is_measured_against_the_torus() {
        let set = ::mesh::dataset_by_name("ring", None).unwrap();
        let params = crate::InteriorParameters::default();
        let fit = crate::fit::fit(&set.mesh, &curves::Chord, &|_| params).unwrap();
        let r = measure(&set.mesh, &fit, Some(set.surface.as_ref()));
        let (c, s, t) = (r.curves.unwrap(), r.surface.unwrap(), r.truth.unwrap());
        assert_eq!(c.edges, set.mesh.num_edges() - 32);
        // The same 32 are flat along the surface too: the torus's normal curvature along its
        // parallels is cos v/(R + r cos v), zero at v = ±90°.
        assert_eq!(s.edges, set.mesh.num_edges() - 32);
        assert!(t.median > 0.5 && t.median < 2.0, "{t:?}");
        assert!(c.median.is_finite() && s.median.is_finite(), "{c:?} {s:?}");
    }
}

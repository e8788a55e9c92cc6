//! G1 of a list of Bézier patches with no mesh behind them: the testbed's `G1` filter, which
//! sees only the patch records of a stream.
//!
//! **Matching.** Two patch edges are one boundary when their boundary curves have the same
//! control points **within a tolerance**, [`MATCH_RELATIVE`] times the diagonal of the bounding
//! box of all control points, in reverse order (the usual case: neighbours traverse their common
//! edge in opposite directions) or in the same order (then the two patches are oppositely
//! oriented: counted, and the second's normal is reversed before comparing). Never by bit
//! equality: a fit that evaluates a shared curve twice, or carries it through another frame,
//! gives its neighbours control points a few ulps apart. The corners of every patch are welded
//! with the library's weld ([`crate::weld::PositionWeld`], a spatial hash with an exact distance
//! check) at that tolerance; edges are grouped by their two welded corners, and within a group
//! the curves are compared control point by control point. Expected O(1) per edge.
//!
//! An edge whose group holds only itself is **border** (the surface's boundary, or a gap). An
//! edge whose group holds other edges none of which has its curve is **mismatched**: two
//! patches meet at both its ends but along different curves, a C0 defect the measurement cannot
//! measure (it is counted as unmeasured). An edge whose curve is a point (a collapsed patch
//! edge) is no boundary: counted as collapsed. Boundaries of three or more patches are measured
//! between the first and each of the others.
//!
//! **Measuring.** Each shared boundary is sampled as [`crate::g1::measure`] samples the edges
//! between faces, with the same code: the same normal evaluation from the two rows of control
//! points next to the edge and the same angle ([`crate::g1`]'s `boundary_chords`). A boundary
//! whose normals are undefined at every sample is counted as unmeasurable.

use std::collections::HashMap;

use nalgebra::Point3;

use crate::beztri::BezierTriangle;
use crate::g1::{boundary_chords, from_chord2, Plan};
use crate::scheme::{Layout, WHOLE};
use crate::weld::{finite_size, PositionWeld};

/// Control points of two patch edges closer than this fraction of the patches' bounding-box
/// diagonal are the same point: far above the rounding of a curve evaluated twice or carried
/// through a change of frame (a few ulps, 1e-16 relative, measured on the built-in ring), far
/// below any distance a fit puts between distinct control points (a mesh edge of a 10⁶-face
/// model is 1e-3 of its size). The tessellation's weld uses the same fraction
/// ([`crate::tessellate::WELD_RELATIVE`]).
pub const MATCH_RELATIVE: f64 = crate::tessellate::WELD_RELATIVE;

/// The fewest samples per boundary that say anything about it: with two, only the ends are
/// sampled, where every interpolating scheme takes the vertex normal on both sides, so even a
/// creased boundary measures zero.
pub const MIN_SAMPLES: usize = 3;

/// One patch edge: patch index and edge (0: `w = 0` from `u` to `v`; 1: `u = 0`; 2: `v = 0`,
/// as [`BezierTriangle::boundary_curve`]).
pub type PatchEdge = (usize, usize);

/// Where the largest normal angle was measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Worst {
    /// Angle in radians.
    pub angle: f64,
    /// The first patch's edge.
    pub a: PatchEdge,
    /// The second patch's edge.
    pub b: PatchEdge,
    /// Parameter along the first patch's edge (from its corner `edge` to `edge + 1`).
    pub t: f64,
}

/// What [`measure_patches`] found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PatchG1Report {
    /// Patches read.
    pub patches: usize,
    /// Boundaries shared by two (or more) patches.
    pub shared: usize,
    /// Shared boundaries measured (a normal defined on both sides at one sample at least).
    pub measured: usize,
    /// Shared boundaries with an undefined normal at every sample: not measured.
    pub unmeasurable: usize,
    /// Border edges: no other patch edge between the same two corners.
    pub border: usize,
    /// Edges between two corners other patch edges also join, along another curve: a C0
    /// defect, not measured (listed in [`PatchG1Report::mismatched_at`], at most
    /// [`LISTED`]).
    pub mismatched: usize,
    /// The first mismatched edges.
    pub mismatched_at: Vec<PatchEdge>,
    /// Edges whose curve is a point.
    pub collapsed: usize,
    /// Shared boundaries traversed in the same direction by both patches.
    pub orientation_mismatches: usize,
    /// Shared boundaries of more than two patches.
    pub non_manifold: usize,
    /// Shared boundaries a patch marks as a crease (C0 by construction, the data's dihedral
    /// kept): not measured ([`measure_patches_with_creases`]).
    pub creases: usize,
    /// Samples skipped for an undefined normal.
    pub undefined: usize,
    /// The largest angle and where (`None` when nothing was measured).
    pub worst: Option<Worst>,
    /// The matching tolerance used, absolute ([`MATCH_RELATIVE`] times the model size).
    pub tolerance: f64,
}

impl PatchG1Report {
    /// Boundaries left unmeasured: shared ones with no defined normals, and mismatched edges.
    pub fn unmeasured(&self) -> usize {
        self.unmeasurable + self.mismatched
    }
}

/// How many mismatched edges a report names.
pub const LISTED: usize = 10;

/// The control points of `patch`'s boundary curve `e`.
fn curve(patch: &BezierTriangle, e: usize) -> Vec<Point3<f64>> {
    patch
        .boundary_curve(e)
        .map(|c| c.points)
        .unwrap_or_default()
}

fn within(a: &[Point3<f64>], b: impl Iterator<Item = Point3<f64>>, tol: f64) -> bool {
    let mut n = 0;
    for (p, q) in a.iter().zip(b) {
        n += 1;
        let d = (p - q).norm();
        if d.is_nan() || d > tol {
            return false;
        }
    }
    n == a.len()
}

/// Measures G1 continuity along the boundaries `patches` share (module docs) at `samples`
/// points per boundary, ends included (at least 2; [`MIN_SAMPLES`] for a meaningful figure).
pub fn measure_patches(patches: &[BezierTriangle], samples: usize) -> PatchG1Report {
    measure_patches_with_creases(patches, samples, &|_| false)
}

/// [`measure_patches`], leaving out the shared boundaries where `crease(patch edge)` holds for
/// one side at least (a fit's crease edges, which its patch records mark): they are C0 by
/// construction and counted in [`PatchG1Report::creases`].
pub fn measure_patches_with_creases(
    patches: &[BezierTriangle],
    samples: usize,
    crease: &dyn Fn(PatchEdge) -> bool,
) -> PatchG1Report {
    let samples = samples.max(2);
    let size = finite_size(patches.iter().flat_map(|p| p.points().iter()));
    let mut weld = PositionWeld::new(MATCH_RELATIVE * size);
    let tol = weld.tolerance();
    let mut out = PatchG1Report {
        patches: patches.len(),
        tolerance: tol,
        ..PatchG1Report::default()
    };
    // Welded corners; edges grouped by their corner pair, in order of first appearance.
    let mut corners = Vec::new();
    let mut groups: HashMap<(usize, usize), usize> = HashMap::new();
    let mut members: Vec<Vec<PatchEdge>> = Vec::new();
    for (pi, patch) in patches.iter().enumerate() {
        let n = patch.degree();
        let ids = [(n, 0, 0), (0, n, 0), (0, 0, n)].map(|(i, j, k)| {
            let p = patch.point(i, j, k).unwrap_or_else(Point3::origin);
            weld.weld(p, &mut corners).0
        });
        for e in 0..3 {
            let points = curve(patch, e);
            let Some(first) = points.first() else {
                continue;
            };
            if points.iter().all(|p| (p - first).norm() <= tol) {
                out.collapsed += 1;
                continue;
            }
            let (a, b) = (ids[e], ids[(e + 1) % 3]);
            let key = (a.min(b), a.max(b));
            let g = *groups.entry(key).or_insert_with(|| {
                members.push(Vec::new());
                members.len() - 1
            });
            members[g].push((pi, e));
        }
    }
    drop(groups);
    let mut plans: HashMap<usize, Option<Plan>> = HashMap::new();
    let mut worst_c2: Option<(f64, Worst)> = None;
    for group in &members {
        if group.len() == 1 {
            out.border += 1;
            continue;
        }
        // Clusters of equal curves: (representative, reversed against it?) per member.
        let mut clusters: Vec<Vec<(PatchEdge, bool)>> = Vec::new();
        for &(pi, e) in group {
            let c = curve(&patches[pi], e);
            let found = clusters.iter().position(|cl| {
                let (rp, re) = cl[0].0;
                patches[rp].degree() == patches[pi].degree()
                    && (within(&curve(&patches[rp], re), c.iter().rev().copied(), tol)
                        || within(&curve(&patches[rp], re), c.iter().copied(), tol))
            });
            match found {
                Some(k) => {
                    let (rp, re) = clusters[k][0].0;
                    let reversed = within(&curve(&patches[rp], re), c.iter().rev().copied(), tol);
                    clusters[k].push(((pi, e), reversed));
                }
                None => clusters.push(vec![((pi, e), true)]),
            }
        }
        for cl in &clusters {
            let Some((&((pa, ea), _), rest)) = cl.split_first() else {
                continue;
            };
            if rest.is_empty() {
                out.mismatched += 1;
                if out.mismatched_at.len() < LISTED {
                    out.mismatched_at.push((pa, ea));
                }
                continue;
            }
            out.shared += 1;
            out.non_manifold += usize::from(rest.len() > 1);
            if crease((pa, ea)) || rest.iter().any(|&(pe, _)| crease(pe)) {
                out.creases += 1;
                continue;
            }
            let degree = patches[pa].degree();
            let plan = plans
                .entry(degree)
                .or_insert_with(|| Plan::new(&Layout::bezier(degree, &WHOLE), samples));
            let mut defined = 0;
            for &((pb, eb), reversed) in rest {
                out.orientation_mismatches += usize::from(!reversed);
                let Some(plan) = plan.as_ref() else {
                    out.undefined += samples;
                    continue;
                };
                let a = (&plan.exterior[ea][..], patches[pa].points());
                let b = (&plan.exterior[eb][..], patches[pb].points());
                boundary_chords(a, b, plan.np, reversed, !reversed, |t, c| match c {
                    Some(c) => {
                        defined += 1;
                        if worst_c2.is_none_or(|(w, _)| c > w) {
                            let at = Worst {
                                angle: 0.0,
                                a: (pa, ea),
                                b: (pb, eb),
                                t,
                            };
                            worst_c2 = Some((c, at));
                        }
                    }
                    None => out.undefined += 1,
                });
            }
            if defined > 0 {
                out.measured += 1;
            } else {
                out.unmeasurable += 1;
            }
        }
    }
    out.worst = worst_c2.map(|(c, w)| Worst {
        angle: from_chord2(c),
        ..w
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    fn flat(a: [f64; 3], b: [f64; 3], c: [f64; 3], n: usize) -> BezierTriangle {
        let (a, b, c) = (Vector3::from(a), Vector3::from(b), Vector3::from(c));
        BezierTriangle::from_fn(n, |i, j, k| {
            Point3::from((a * i as f64 + b * j as f64 + c * k as f64) / n as f64)
        })
    }

    /// Two flat patches on a square, the shared diagonal's control points a few ulps apart in
    /// one of them: matched, measured, zero angle; bent, the angle is the fold's.
    #[test]
    fn near_equal_boundaries_match_and_measure() {
        let (a, b, c, d) = (
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
        );
        let exact = flat(d, c, b, 3);
        let second = BezierTriangle::from_fn(3, |i, j, k| {
            let p = exact.point(i, j, k).unwrap_or_else(Point3::origin);
            p + Vector3::new(3e-16, -2e-16, 1e-16)
        });
        let r = measure_patches(&[flat(a, b, c, 3), second], 5);
        assert_eq!((r.shared, r.measured, r.border, r.mismatched), (1, 1, 4, 0));
        assert_eq!(r.orientation_mismatches, 0);
        assert!(r.worst.is_some_and(|w| w.angle < 1e-12), "{r:?}");
        // Folded along the diagonal: the normals differ by the fold angle.
        let lifted = flat(d, c, b, 3);
        let up = BezierTriangle::from_fn(3, |i, j, k| {
            let p = lifted.point(i, j, k).unwrap_or_else(Point3::origin);
            Point3::new(p.x, p.y, i as f64 / 3.0)
        });
        let r = measure_patches(&[flat(a, b, c, 3), up], 5);
        assert_eq!((r.shared, r.measured), (1, 1));
        let fold = r.worst.map_or(0.0, |w| w.angle);
        // The lifted triangle's normal is (1, 1, 1)/√3 against +z.
        assert!(
            (fold - (1.0f64 / 3.0f64.sqrt()).acos()).abs() < 1e-12,
            "{fold}"
        );
        // The same corners along another curve: mismatched, not measured.
        let bulged = BezierTriangle::from_fn(3, |i, j, k| {
            let p = lifted.point(i, j, k).unwrap_or_else(Point3::origin);
            if i == 0 && j > 0 && k > 0 {
                p + Vector3::z() * 0.1
            } else {
                p
            }
        });
        let r = measure_patches(&[flat(a, b, c, 3), bulged], 5);
        assert_eq!((r.shared, r.measured, r.mismatched), (0, 0, 2));
        assert_eq!(r.unmeasured(), 2);
        assert!(r.worst.is_none());
    }
}

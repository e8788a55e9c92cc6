//! Folds: faces whose fitted surface turns over.
//!
//! A face is **folded** when the normal of one of its patches, at some sample of the patch's
//! domain, points away from the data face: `n · N_f ≤ 0`, with `n = r_u × r_v / |r_u × r_v|`
//! the patch normal (oriented like the face: docs/conventions.md, "Surface schemes and
//! layouts") and `N_f` the data face's unit normal. A surface over a face that stays within
//! 90° of the face's plane cannot turn inside out over it; one that leaves it has either a
//! normal that changes sign over the face (the patch folds onto itself) or a patch lying
//! against its face (turned over whole), the two cases of a fold a user sees as a spike or a
//! balloon. On smooth data fitted well the normals stay within a few tens of degrees of the
//! face normal (the data's own normals do).
//!
//! The samples are the points `(i/s, j/s)`, `i + j ≤ s`, of each patch's local domain with
//! `s = `[`FOLD_SEGMENTS`], corners and edges included (a fold usually starts at a data
//! vertex whose normal leans far from the face). A sample where the patch is singular
//! (`r_u × r_v` zero or not finite) decides nothing and is counted; a face of zero area has no
//! normal and is counted apart, never as a fold.

use mesh::Mesh;
use nalgebra::{Point3, Vector3};

use crate::fit::Fit;
use crate::patch::{partials, prepare, Prepared};
use crate::scheme::Layout;

/// Segments a patch edge of the fold test's sample grid: 15 samples a patch (28 with a
/// corner-split layout's three patches, which share their edges), enough to see a fold that
/// spans a tenth of a face and cheap beside the fit (a fifth of the G1 measure's samples).
pub const FOLD_SEGMENTS: usize = 4;

/// Samples a patch of the fold test's grid: `(s + 1)(s + 2)/2` for `s = `[`FOLD_SEGMENTS`].
const FOLD_SAMPLES: usize = (FOLD_SEGMENTS + 1) * (FOLD_SEGMENTS + 2) / 2;

/// What [`measure`] found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FoldReport {
    /// Faces measured.
    pub faces: usize,
    /// Folded faces, in face order.
    pub folded: Vec<usize>,
    /// The smallest `n · N_f` over every sample of every face with a normal (−1: a patch
    /// normal opposite to its face; `None` when nothing was measured).
    pub worst_cosine: Option<f64>,
    /// Faces of zero area (no normal to test against).
    pub faces_without_normal: usize,
    /// Samples where a patch is singular (no normal there).
    pub singular_samples: usize,
}

impl FoldReport {
    /// Adds what `other` found (face lists concatenated: parts in face order stay in order).
    pub fn merge(&mut self, other: FoldReport) {
        self.faces += other.faces;
        self.folded.extend(other.folded);
        self.worst_cosine = match (self.worst_cosine, other.worst_cosine) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        self.faces_without_normal += other.faces_without_normal;
        self.singular_samples += other.singular_samples;
    }
}

/// The sample points of a layout's patches, prepared once ([`crate::patch::prepare`]).
#[derive(Clone, Debug)]
pub struct FoldPlan {
    layout: Layout,
    samples: Vec<Prepared>,
}

impl FoldPlan {
    /// The plan for patches of `layout`.
    pub fn new(layout: &Layout) -> FoldPlan {
        let s = FOLD_SEGMENTS;
        let mut samples = Vec::with_capacity((s + 1) * (s + 2) / 2);
        for i in 0..=s {
            for j in 0..=s - i {
                let (u, v) = (i as f64 / s as f64, j as f64 / s as f64);
                samples.push(prepare(layout, [u, v, 1.0 - u - v]));
            }
        }
        FoldPlan {
            layout: *layout,
            samples,
        }
    }

    /// Tests face `f` of `mesh`, whose patches' points (one face's worth, in layout order) are
    /// `points`, and adds what it finds to `report`.
    pub fn face(&self, mesh: &Mesh, f: usize, points: &[Point3<f64>], report: &mut FoldReport) {
        report.faces += 1;
        let normal = mesh
            .face_area_normal(f)
            .ok()
            .and_then(|n| unit(&n))
            .filter(|_| !mesh.is_degenerate_face(f));
        let Some(face_normal) = normal else {
            report.faces_without_normal += 1;
            return;
        };
        let per_patch = self.layout.points_per_patch();
        let mut worst = f64::INFINITY;
        // The cross products of a patch first, then their normalization: the square roots and
        // divisions of different samples are independent and overlap in the processor, where
        // one sample at a time waited on each (perf at 10⁶ faces: 1.13 s → 0.53 s of CPU in
        // this function; with `partials` instead of the full evaluation the fold test as a
        // whole went 2.0 s → 0.92 s. The same operations on the same numbers: the same bits).
        let mut normals = [Vector3::zeros(); FOLD_SAMPLES];
        for net in points.chunks(per_patch.max(1)) {
            for (c, at) in normals.iter_mut().zip(&self.samples) {
                let (du, dv) = partials(&self.layout, net, at);
                *c = du.cross(&dv);
            }
            for c in &normals[..self.samples.len()] {
                match unit(c) {
                    Some(n) => worst = worst.min(n.dot(&face_normal)),
                    None => report.singular_samples += 1,
                }
            }
        }
        if worst.is_finite() {
            report.worst_cosine = Some(report.worst_cosine.map_or(worst, |w| w.min(worst)));
            if worst <= 0.0 {
                report.folded.push(f);
            }
        }
    }
}

/// `v / |v|`, `None` for a zero or non-finite vector.
fn unit(v: &Vector3<f64>) -> Option<Vector3<f64>> {
    let len = v.norm();
    (len > 0.0 && len.is_finite()).then(|| v / len)
}

/// The folds of a whole fit of `mesh` (module docs).
pub fn measure(mesh: &Mesh, fit: &Fit) -> FoldReport {
    let plan = FoldPlan::new(&fit.layout);
    let per_face = fit.layout.points_per_face();
    let mut report = FoldReport::default();
    if per_face == 0 {
        return report;
    }
    for (f, points) in fit.points.chunks(per_face).enumerate() {
        plan.face(mesh, f, points, &mut report);
    }
    report
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)] // test fixtures fail loudly by design
    use super::*;
    use crate::scheme::{SchemeOptions, REGISTRY};
    use mesh::{Mesh, Vertex};

    fn chord() -> Box<dyn curves::CurveMethod> {
        curves::method_by_name("chord", &curves::MethodOptions::default()).unwrap()
    }

    /// Every registered scheme on every analytic data set (exact normals): no face folds, and
    /// every patch normal stays within 90° of its face with room to spare.
    #[test]
    fn smooth_data_fitted_by_every_scheme_has_no_folds() {
        for data in mesh::DATASET_NAMES {
            let set = mesh::dataset_by_name(data, None).unwrap();
            for entry in REGISTRY {
                let scheme = (entry.build)(&SchemeOptions::default());
                let fit =
                    crate::fit::fit_scheme(&set.mesh, scheme.as_ref(), chord().as_ref()).unwrap();
                let r = measure(&set.mesh, &fit);
                assert_eq!(r.faces, set.mesh.num_faces());
                assert!(r.folded.is_empty(), "{data}/{}: {:?}", entry.name, r.folded);
                assert!(
                    r.worst_cosine.unwrap() > 0.2,
                    "{data}/{}: {r:?}",
                    entry.name
                );
            }
        }
    }

    /// Nets over the unit triangle (face normal +z): the flat patch turned over (its corners
    /// clockwise) and a quadratic whose edge control point is pulled across the opposite corner
    /// (its normal changes sign over the face) are folded; the untouched ones are not.
    #[test]
    fn a_patch_turned_over_or_folded_onto_itself_is_a_fold() {
        let m = Mesh::new(
            [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]
                .iter()
                .map(|p| Vertex::without_curvature(Point3::new(p[0], p[1], 0.0), Vector3::z()))
                .collect(),
            vec![[0, 1, 2]],
        )
        .unwrap();
        let layout_of = |name: &str| {
            (crate::scheme::entry_by_name(name).unwrap().build)(&SchemeOptions::default()).layout()
        };
        let (p0, p1, p2) = (
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
        );
        let flat = FoldPlan::new(&layout_of("flat"));
        let mut r = FoldReport::default();
        flat.face(&m, 0, &[p0, p1, p2], &mut r);
        assert!(r.folded.is_empty(), "{r:?}");
        assert!((r.worst_cosine.unwrap() - 1.0).abs() < 1e-15);
        let mut r = FoldReport::default();
        flat.face(&m, 0, &[p0, p2, p1], &mut r);
        assert_eq!(r.folded, [0]);
        assert!((r.worst_cosine.unwrap() + 1.0).abs() < 1e-15);

        // The quadratic net b_ijk (i + j + k = 2) of the flat triangle, then b_110 (between the
        // corners over p0 and p1) pulled to (0.5, 2): beyond p2, so r_u × r_v turns over near
        // that edge.
        let quadratic = layout_of("phong");
        let net = |pull: bool| -> Vec<Point3<f64>> {
            let mut pts = vec![Point3::origin(); 6];
            for (i, j, k) in [
                (2, 0, 0),
                (0, 2, 0),
                (0, 0, 2),
                (1, 1, 0),
                (1, 0, 1),
                (0, 1, 1),
            ] {
                let w = [i as f64 / 2.0, j as f64 / 2.0, k as f64 / 2.0];
                pts[crate::beztri::index(2, i, j, k)] =
                    Point3::from(p0.coords * w[0] + p1.coords * w[1] + p2.coords * w[2]);
            }
            if pull {
                pts[crate::beztri::index(2, 1, 1, 0)] = Point3::new(0.5, 2.0, 0.0);
            }
            pts
        };
        let plan = FoldPlan::new(&quadratic);
        let mut r = FoldReport::default();
        plan.face(&m, 0, &net(false), &mut r);
        assert!(r.folded.is_empty(), "{r:?}");
        let mut r = FoldReport::default();
        plan.face(&m, 0, &net(true), &mut r);
        assert_eq!(r.folded, [0], "{r:?}");
    }

    /// The streamed fit (windows of 5 faces, many borders) reports the folds the whole fit's
    /// measure gives, faces in order.
    #[test]
    fn the_streamed_fit_reports_the_same_folds() {
        let set = mesh::dataset_by_name("capsule", Some(8)).unwrap();
        // Lean every normal by a quarter turn about a fixed axis so that some faces fold.
        let mut m = set.mesh.clone();
        let turn = nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), 1.4);
        for v in m.vertices_mut() {
            v.data.n = turn * v.data.n;
        }
        let mut folded = 0;
        for name in ["shirman-sequin", "pn-triangles"] {
            let scheme =
                (crate::scheme::entry_by_name(name).unwrap().build)(&SchemeOptions::default());
            let whole = crate::fit::fit_scheme(&m, scheme.as_ref(), chord().as_ref()).unwrap();
            let want = measure(&m, &whole);
            let streamed =
                crate::stream::fit_streamed_with(&m, scheme.as_ref(), chord().as_ref(), 4, None, 5)
                    .unwrap();
            assert_eq!(streamed.folds, want, "{name}");
            folded += want.folded.len();
        }
        assert!(folded > 0, "the leaning normals fold some faces");
    }

    #[test]
    fn parts_merge_in_order_with_the_worst_cosine() {
        let mut a = FoldReport {
            faces: 2,
            folded: vec![1],
            worst_cosine: Some(-0.5),
            faces_without_normal: 0,
            singular_samples: 3,
        };
        a.merge(FoldReport {
            faces: 3,
            folded: vec![4],
            worst_cosine: Some(0.1),
            faces_without_normal: 1,
            singular_samples: 0,
        });
        assert_eq!(a.faces, 5);
        assert_eq!(a.folded, [1, 4]);
        assert_eq!(a.worst_cosine, Some(-0.5));
        assert_eq!(a.faces_without_normal, 1);
        assert_eq!(a.singular_samples, 3);
    }
}

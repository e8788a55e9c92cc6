//! The testbed's `G1` module: measured continuity of a fitted surface.
//!
//! Along every boundary shared by two patches — the interior boundaries inside a macro-patch and
//! the exterior edges between faces — the unit normals of both patches are compared at `samples`
//! equally spaced points (ends included), and the largest angle is reported with where it
//! occurred. The angle is `atan2(|n₁ × n₂|, n₁ · n₂)`, accurate near zero where `acos` is not.
//! Interpolation is measured at the same time: patch corners against vertex positions and
//! normals.
//!
//! Faces fitted with the fallback patch ([`crate::fit::Fit::face_fallbacks`]) promise only C0:
//! their interior boundaries and every exterior edge touching them are measured separately
//! (`fallback_*`), so the regular figures stay what the scheme guarantees; their corner normals
//! are left out of the interpolation error.

use nalgebra::Vector3;

use crate::beztri::index;
use crate::fit::Fit;
use crate::mesh::Mesh;
use crate::shirman_sequin::QuarticNet;

/// Where a G1 defect was measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Boundary {
    /// The interior boundary from corner `corner` of face `face` to its split point.
    Interior {
        /// Face index.
        face: usize,
        /// Corner index in the face.
        corner: usize,
    },
    /// The exterior edge between two faces.
    Exterior {
        /// Mesh edge index.
        edge: usize,
    },
}

/// The result of a G1 measurement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct G1Report {
    /// Largest normal angle (radians) along interior boundaries of regular faces.
    pub interior_max: f64,
    /// Where it occurred.
    pub interior_at: Option<(Boundary, f64)>,
    /// Largest normal angle (radians) along exterior edges between two regular faces.
    pub exterior_max: f64,
    /// Where it occurred (boundary and curve parameter).
    pub exterior_at: Option<(Boundary, f64)>,
    /// Largest distance between a patch corner and its data vertex.
    pub position_error: f64,
    /// Largest angle (radians) between a patch's corner normal and its data vertex normal.
    pub normal_error: f64,
    /// Samples where a patch normal was undefined (degenerate derivatives), skipped.
    pub undefined_normals: usize,
    /// Largest normal angle (radians) along interior boundaries of fallback faces.
    pub fallback_interior_max: f64,
    /// Largest normal angle (radians) along exterior edges touching a fallback face.
    pub fallback_exterior_max: f64,
    /// Exterior edges touching a fallback face (shared by two faces).
    pub fallback_edges: usize,
}

impl G1Report {
    /// The largest normal angle anywhere.
    pub fn max_angle(&self) -> f64 {
        self.interior_max.max(self.exterior_max)
    }
}

fn angle(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

/// Unit normal of a quartic net at `(u, v, 1 − u − v)`: the cross product of the two first
/// partials, each from one de Casteljau pass down to degree 1 (no allocation).
fn normal(net: &QuarticNet, u: f64, v: f64) -> Option<Vector3<f64>> {
    let w = 1.0 - u - v;
    // Reduce to the degree-1 net b100, b010, b001 by de Casteljau at (u, v, w).
    let mut pts: [Vector3<f64>; 15] = std::array::from_fn(|i| net[i].coords);
    let mut n = 4;
    while n > 1 {
        let mut next = [Vector3::zeros(); 15];
        for k in 0..n {
            for i in 0..n - k {
                let j = n - 1 - k - i;
                next[index(n - 1, i, j, k)] = pts[index(n, i + 1, j, k)] * u
                    + pts[index(n, i, j + 1, k)] * v
                    + pts[index(n, i, j, k + 1)] * w;
            }
        }
        pts = next;
        n -= 1;
    }
    // Partials along u and v with w = 1 − u − v: 4(b100 − b001), 4(b010 − b001).
    let du = pts[index(1, 1, 0, 0)] - pts[index(1, 0, 0, 1)];
    let dv = pts[index(1, 0, 1, 0)] - pts[index(1, 0, 0, 1)];
    let c = du.cross(&dv);
    let len = c.norm();
    (len > 0.0 && len.is_finite()).then(|| c / len)
}

/// Position of a quartic net at a corner.
fn corner(net: &QuarticNet, i: usize) -> nalgebra::Point3<f64> {
    net[[index(4, 4, 0, 0), index(4, 0, 4, 0), index(4, 0, 0, 4)][i]]
}

/// Measures G1 continuity and interpolation of `fit` over `mesh` at `samples ≥ 2` points per
/// boundary.
pub fn measure(mesh: &Mesh, fit: &Fit, samples: usize) -> G1Report {
    let samples = samples.max(2);
    let mut r = G1Report {
        interior_max: 0.0,
        interior_at: None,
        exterior_max: 0.0,
        exterior_at: None,
        position_error: 0.0,
        normal_error: 0.0,
        undefined_normals: 0,
        fallback_interior_max: 0.0,
        fallback_exterior_max: 0.0,
        fallback_edges: 0,
    };
    let fallback = fit.fallback_mask(mesh.num_faces());
    let ts: Vec<f64> = (0..samples)
        .map(|s| s as f64 / (samples - 1) as f64)
        .collect();
    for (f, face) in mesh.faces().iter().enumerate() {
        for (i, &vi) in face.iter().enumerate() {
            // Interior boundary V_i → S: sub-patch i at (1−t, 0), sub-patch i−1 at (0, 1−t).
            let l = &fit.patches[3 * f + i];
            let rt = &fit.patches[3 * f + (i + 2) % 3];
            for &t in &ts {
                match (normal(l, 1.0 - t, 0.0), normal(rt, 0.0, 1.0 - t)) {
                    (Some(a), Some(b)) if fallback[f] => {
                        r.fallback_interior_max = r.fallback_interior_max.max(angle(&a, &b));
                    }
                    (Some(a), Some(b)) => {
                        let d = angle(&a, &b);
                        if d > r.interior_max || r.interior_at.is_none() {
                            r.interior_max = r.interior_max.max(d);
                            r.interior_at = Some((Boundary::Interior { face: f, corner: i }, t));
                        }
                    }
                    _ => r.undefined_normals += 1,
                }
            }
            // Interpolation at the corner V_i of sub-patch i.
            let v = &mesh.vertices()[vi].data;
            r.position_error = r.position_error.max((corner(l, 0) - v.p).norm());
            if fallback[f] {
                continue;
            }
            match normal(l, 1.0, 0.0) {
                Some(n) => r.normal_error = r.normal_error.max(angle(&n, &v.n.normalize())),
                None => r.undefined_normals += 1,
            }
        }
    }
    for (ei, e) in mesh.edges().iter().enumerate() {
        let (Some((g, lg)), (f, lf)) = (e.second, e.first) else {
            continue;
        };
        let pf = &fit.patches[3 * f + lf];
        let pg = &fit.patches[3 * g + lg];
        let touches_fallback = fallback[f] || fallback[g];
        r.fallback_edges += usize::from(touches_fallback);
        for &t in &ts {
            // Face f's edge runs from its corner lf (u = 1) to lf+1 (v = 1); g's runs backwards.
            match (normal(pf, 1.0 - t, t), normal(pg, t, 1.0 - t)) {
                (Some(a), Some(b)) if touches_fallback => {
                    r.fallback_exterior_max = r.fallback_exterior_max.max(angle(&a, &b));
                }
                (Some(a), Some(b)) => {
                    let d = angle(&a, &b);
                    if d > r.exterior_max || r.exterior_at.is_none() {
                        r.exterior_max = r.exterior_max.max(d);
                        r.exterior_at = Some((Boundary::Exterior { edge: ei }, t));
                    }
                }
                _ => r.undefined_normals += 1,
            }
        }
    }
    r
}

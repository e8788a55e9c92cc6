//! The boundary curve of a crease edge: one curve shared by the faces on both sides, running
//! along the crease, so that each side's patch can keep its own tangent plane.
//!
//! # The end data of a crease
//!
//! At an end `p` of a crease edge the two faces belong to different sectors, with unit normals
//! `n_A`, `n_B` and shape tensors `S_A`, `S_B`. The curve must lie in **both** tangent planes at
//! `p` (each face's patch interpolates its own sector's tangent plane there, and its boundary
//! tangent is in it), so its tangent is along their intersection:
//!
//! `t = ±(n_A × n_B)/|n_A × n_B|`, the sign chosen so that `t · (q − p) > 0`, `q` the other end.
//!
//! The curve's curvature vector `k` at `p` (`k ⊥ t`) has normal components fixed by Meusnier's
//! theorem on each side: `k · n_A = κ_A = tᵀ S_A t` and `k · n_B = κ_B = tᵀ S_B t`. As `n_A` and
//! `n_B` span the plane `⊥ t`, these two equations fix `k`. Writing `k = x n_A + y n_B` and
//! `c = n_A · n_B`: `x + c y = κ_A`, `c x + y = κ_B`, so `x + y = (κ_A + κ_B)/(1 + c)` and
//! `k · (n_A + n_B) = (1 + c)(x + y) = κ_A + κ_B`.
//!
//! The curve constructions of this crate work on a planar problem built from one normal and one
//! shape tensor per end ([`crate::BoundaryProblem`]). A crease end is given to them as the
//! **bisector** data: `n* = (n_A + n_B)/|n_A + n_B|` (which is `⊥ t`, as both normals are) with
//! the tensor `S* = κ* t tᵀ`, `κ* = k · n* = (κ_A + κ_B)/|n_A + n_B|`: the normal curvature of
//! the crease curve with respect to the bisector, which is what Meusnier's theorem gives for the
//! curve on a surface with normal `n*`. (Coplanar sectors, `n_A = n_B`: `n* = n_A`,
//! `κ* = κ_A`, the smooth data.) A construction then chooses the end-derivative lengths `α` on
//! that problem, and the curve is built with the **true** crease tangents `t` at those lengths
//! ([`apply_tangents`]): for a plane crease (a box's edge, a cylinder's rim) the problem's own
//! tangents are `t` already; for a crease that twists out of the plane the lengths are the
//! planar problem's and the directions the crease's.
//!
//! # Degenerate crease ends ([`CreaseEnd`])
//!
//! * `|n_A × n_B| < sin(`[`MIN_CREASE_ANGLE`]`)`: the sectors are (nearly) coplanar and `t` is
//!   undefined; the end is taken as smooth with the bisector data (`S*` the mean of the two
//!   tensors projected on `n*`) and the problem's tangent ([`CreaseEnd::Coplanar`]).
//! * `|n_A + n_B| < 2 sin(`[`MIN_CREASE_ANGLE`]`/2)`: the sectors fold flat onto each other (a knife
//!   edge, dihedral within [`MIN_CREASE_ANGLE`] of π): `n*` is undefined, and so is `t` (then
//!   `|n_A × n_B|` is as small); the end gets `n_A`'s part `⊥` the chord (the problem's tangent is
//!   then the chord) and `S* = 0` ([`CreaseEnd::Knife`]). Checked first.
//! * `|t · ĉ| < `[`MIN_TANGENT_COSINE`] (`ĉ` the unit chord): the crease leaves the edge
//!   sideways (the edge is not along the crease line: a sliver across a corner); a curve with
//!   that tangent would loop out of both faces. The end keeps the bisector data and the
//!   problem's tangent (the chord projected into the bisector plane, [`CreaseEnd::Sideways`]),
//!   and is counted: the two faces' patches then meet at a curve that is not in both tangent
//!   planes at that end.

use nalgebra::{Matrix3, Point3, Vector3};

use crate::cubicbez::CubicBez3;
use crate::problem::VertexData;

/// Smallest angle (radians) between two sectors' tangent planes for their intersection to be
/// the crease tangent: below 1e-6 rad the cross product of the unit normals has lost six of its
/// sixteen digits (and a crease that turns by a millionth of a radian is a smooth surface).
pub const MIN_CREASE_ANGLE: f64 = 1e-6;

/// Smallest `|cos|` of the angle between a crease tangent and the chord of its edge: past
/// about 84° (cos 0.1) a cubic with that end tangent leaves the strip of its two faces.
pub const MIN_TANGENT_COSINE: f64 = 0.1;

/// How a crease end was given to the curve problem (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CreaseEnd {
    /// The crease tangent `t`: the curve runs along the crease.
    Along(Vector3<f64>),
    /// The sectors are coplanar: smooth bisector data, the problem's tangent.
    Coplanar,
    /// The sectors fold onto each other (no tangent is defined): a normal ⊥ the chord, no
    /// curvature, the problem's tangent (the chord).
    Knife,
    /// The crease leaves the edge sideways: bisector data, the problem's tangent.
    Sideways,
}

impl CreaseEnd {
    /// The tangent the curve must take at this end, if the crease fixes one.
    pub fn tangent(&self) -> Option<Vector3<f64>> {
        match self {
            CreaseEnd::Along(t) => Some(*t),
            CreaseEnd::Coplanar | CreaseEnd::Knife | CreaseEnd::Sideways => None,
        }
    }
}

/// The data a crease end is given to the curve problem as, and how ([`CreaseEnd`]): `a`, `b` the
/// two sectors' data at the same point `a.p`, `other` the edge's other end.
pub fn crease_end(a: &VertexData, b: &VertexData, other: &Point3<f64>) -> (VertexData, CreaseEnd) {
    let unit = |v: Vector3<f64>| {
        let l = v.norm();
        (l > 0.0 && l.is_finite()).then(|| v / l)
    };
    let (Some(na), Some(nb)) = (unit(a.n), unit(b.n)) else {
        return (*a, CreaseEnd::Coplanar);
    };
    let chord = other - a.p;
    let sum = na + nb;
    let cross = na.cross(&nb);
    let project = |s: &Matrix3<f64>, n: &Vector3<f64>| {
        let p = Matrix3::identity() - n * n.transpose();
        p * s * p
    };
    let coplanar = |n: Vector3<f64>| {
        let shape = project(&((a.shape + b.shape) * 0.5), &n);
        (VertexData::new(a.p, n, shape), CreaseEnd::Coplanar)
    };
    if sum.norm() < 2.0 * (MIN_CREASE_ANGLE / 2.0).sin() {
        // A knife edge: `n_A × n_B` is as small as `n_A + n_B`, no tangent is defined. The
        // normal: `n_A`'s part ⊥ the chord (so the problem's tangent is the chord), no curvature.
        let n = unit(na - chord * (na.dot(&chord) / chord.norm_squared().max(f64::MIN_POSITIVE)))
            .unwrap_or(na);
        return (VertexData::new(a.p, n, Matrix3::zeros()), CreaseEnd::Knife);
    }
    if cross.norm() < MIN_CREASE_ANGLE.sin() {
        // (Nearly) coplanar sectors with (nearly) equal normals: their sum is ~2.
        return coplanar(unit(sum).unwrap_or(na));
    }
    let Some(mut t) = unit(cross) else {
        return coplanar(na);
    };
    if t.dot(&chord) < 0.0 {
        t = -t;
    }
    let along = unit(chord).map_or(0.0, |c| t.dot(&c));
    let n_star = sum / sum.norm();
    if along < MIN_TANGENT_COSINE {
        let (d, _) = coplanar(n_star);
        return (d, CreaseEnd::Sideways);
    }
    let kappa = (t.dot(&(a.shape * t)) + t.dot(&(b.shape * t))) / sum.norm();
    (
        VertexData::new(a.p, n_star, t * t.transpose() * kappa),
        CreaseEnd::Along(t),
    )
}

/// `curve` with its end tangents turned to `tangents` where given (unit vectors along the
/// direction of travel, from the start's and towards the end's), keeping each end derivative's
/// length.
pub fn apply_tangents(curve: &CubicBez3, tangents: [Option<Vector3<f64>>; 2]) -> CubicBez3 {
    let mut p = curve.points;
    if let Some(t) = tangents[0] {
        let len = (p[1] - p[0]).norm();
        p[1] = p[0] + t * len;
    }
    if let Some(t) = tangents[1] {
        let len = (p[3] - p[2]).norm();
        p[2] = p[3] - t * len;
    }
    CubicBez3::new(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Closed forms evaluated in double precision: rounding only.
    const ROUNDING: f64 = 1e-14;

    fn data(p: [f64; 3], n: [f64; 3], s: Matrix3<f64>) -> VertexData {
        VertexData::new(Point3::from(p), Vector3::from(n), s)
    }

    #[test]
    fn a_box_edge_runs_along_the_intersection_with_no_curvature() {
        let a = data([0.0; 3], [0.0, 0.0, 1.0], Matrix3::zeros());
        let b = data([0.0; 3], [0.0, -1.0, 0.0], Matrix3::zeros());
        let (d, how) = crease_end(&a, &b, &Point3::new(1.0, 0.0, 0.0));
        let t = how.tangent().expect("a tangent");
        assert!((t - Vector3::x()).norm() < ROUNDING);
        let bis = Vector3::new(0.0, -1.0, 1.0) / 2f64.sqrt();
        assert!((d.n - bis).norm() < ROUNDING);
        assert!(d.shape.norm() < ROUNDING);
        // Towards the other end the tangent flips to keep pointing along the chord.
        let (_, how) = crease_end(&a, &b, &Point3::new(-1.0, 0.0, 0.0));
        assert!((how.tangent().expect("a tangent") + Vector3::x()).norm() < ROUNDING);
    }

    #[test]
    fn a_cylinder_rim_gives_the_circle_curvature_about_the_bisector() {
        // Rim of the unit cylinder x² + y² = 1 at (1, 0, 0), top face z = 0 with normal +z, side
        // with normal +x; tangent +y. Side: κ_B = tᵀ S_B t = −1 (the side bends away from its
        // outward normal); top: κ_A = 0. The circle's curvature vector is k = −x (towards the
        // axis): k · n* = −1/√2 = (κ_A + κ_B)/|n_A + n_B| = −1/√2.
        let top = data([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], Matrix3::zeros());
        let side_s = -(Matrix3::identity()
            - Vector3::x() * Vector3::x().transpose()
            - Vector3::z() * Vector3::z().transpose());
        let side = data([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], side_s);
        let other = Point3::new(0.5f64.cos(), 0.5f64.sin(), 0.0);
        let (d, how) = crease_end(&top, &side, &other);
        let t = how.tangent().expect("a tangent");
        assert!((t - Vector3::y()).norm() < ROUNDING);
        let k = -Vector3::x();
        assert!((d.normal_curvature(&t) - k.dot(&d.n)).abs() < ROUNDING);
        assert!((d.normal_curvature(&t) + 0.5f64.sqrt()).abs() < ROUNDING);
    }

    #[test]
    fn coplanar_sectors_are_smooth_data() {
        let s = Matrix3::identity() * -1.0;
        let a = data([0.0; 3], [0.0, 0.0, 1.0], s);
        let (d, how) = crease_end(&a, &a, &Point3::new(1.0, 0.0, 0.0));
        assert_eq!(how, CreaseEnd::Coplanar);
        assert!((d.n - Vector3::z()).norm() < ROUNDING);
        // The projected tensor: the tangent-plane part of −I.
        assert!((d.normal_curvature(&Vector3::x()) + 1.0).abs() < ROUNDING);
        assert!(d.normal_curvature(&Vector3::z()).abs() < ROUNDING);
    }

    #[test]
    fn a_crease_across_the_edge_falls_back_to_the_bisector_plane() {
        // The crease runs along y; the edge goes along x: the tangent is ⊥ the chord.
        let a = data([0.0; 3], [0.0, 0.0, 1.0], Matrix3::zeros());
        let b = data([0.0; 3], [1.0, 0.0, 0.0], Matrix3::zeros());
        let (d, how) = crease_end(&a, &b, &Point3::new(1.0, 0.0, 0.0));
        assert_eq!(how, CreaseEnd::Sideways);
        assert!((d.n - Vector3::new(1.0, 0.0, 1.0) / 2f64.sqrt()).norm() < ROUNDING);
    }

    #[test]
    fn a_knife_edge_keeps_its_tangent_and_drops_curvature() {
        let a = data([0.0; 3], [0.0, 0.0, 1.0], Matrix3::identity());
        let b = data([0.0; 3], [0.0, 1e-9, -1.0], Matrix3::identity());
        let (d, how) = crease_end(&a, &b, &Point3::new(1.0, 0.0, 0.0));
        assert_eq!(how, CreaseEnd::Knife);
        assert_eq!(d.shape, Matrix3::zeros());
        assert!(d.n.dot(&Vector3::x()).abs() < ROUNDING, "⊥ the chord");
    }

    #[test]
    fn tangents_are_turned_at_their_lengths() {
        let c = CubicBez3::new([
            Point3::origin(),
            Point3::new(1.0, 1.0, 0.0),
            Point3::new(2.0, 1.0, 0.0),
            Point3::new(3.0, 0.0, 0.0),
        ]);
        let out = apply_tangents(&c, [Some(Vector3::x()), None]);
        assert!((out.points[1] - Point3::new(2f64.sqrt(), 0.0, 0.0)).norm() < ROUNDING);
        assert_eq!(out.points[2], c.points[2]);
    }
}

//! Principal curvatures and directions of a shape tensor, in the convention written files and
//! the Python package use (libigl's, trimesh's and MeshLab's: `κ1 ≥ κ2`, positive where the
//! surface bends away from its normal, so the unit sphere with outward normals has
//! `κ1 = κ2 = +1`; `meshio::convention`).
//!
//! Derivation. With `n` the unit normal and `(t1, t2)` an orthonormal tangent basis
//! ([`crate::fit::tangent_basis`]), the workbench's normal curvature is
//! `κn(d) = dᵀ S d` for a unit tangent `d` (positive towards `n`). In the basis it is the
//! quadratic form of `M = [[a, b], [b, c]]`, `a = t1ᵀ S t1`, `c = t2ᵀ S t2` and
//! `b = (t1ᵀ S t2 + t2ᵀ S t1)/2` (the symmetric part: a tensor estimated to rounding need not
//! be exactly symmetric). The exported curvature is `−κn`, the form of `−M`, whose eigenvalues
//! are `κ1 = −m + r ≥ κ2 = −m − r` with `m = (a + c)/2`, `r = √(((a − c)/2)² + b²)`. The
//! direction of `κ1` is the eigenvector of `M` for its smaller eigenvalue `λ = m − r`: either
//! row of `M − λI` is orthogonal to it, giving the two candidates `(b, λ − a)` and
//! `(λ − c, b)`; one of them vanishes when `b = 0`, so the longer is taken. At an umbilic
//! (`r` zero to rounding, [`UMBILIC_RELATIVE`]) every tangent is principal and `d1 = t1`.
//! `d2 = n × d1`, so `(d1, d2, n)` is right-handed.

use nalgebra::{Matrix3, Vector3};

/// Below this ratio of `r` to the tensor's size (`|a| + |b| + |c|`) the two principal
/// curvatures are equal to rounding (a few units of `f64`'s 2.2e-16 in the sums that form
/// `a`, `b`, `c`): the directions are then any pair, and `t1, t2` are given.
pub const UMBILIC_RELATIVE: f64 = 1e-12;

/// Principal curvatures and their unit directions at one point (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Principal {
    /// The larger principal curvature (exported convention).
    pub k1: f64,
    /// The smaller principal curvature.
    pub k2: f64,
    /// Unit tangent direction of `k1`.
    pub d1: Vector3<f64>,
    /// Unit tangent direction of `k2`, `n × d1`.
    pub d2: Vector3<f64>,
}

/// The principal curvatures and directions of shape tensor `s` at normal `n` (need not be
/// unit; a zero or non-finite normal gives non-finite values, never a plausible number).
pub fn principal_frame(s: &Matrix3<f64>, n: &Vector3<f64>) -> Principal {
    let n = n.normalize();
    let (t1, t2) = crate::fit::tangent_basis(&n);
    let a = t1.dot(&(s * t1));
    let b = 0.5 * (t1.dot(&(s * t2)) + t2.dot(&(s * t1)));
    let c = t2.dot(&(s * t2));
    let m = 0.5 * (a + c);
    let r = (0.5 * (a - c)).hypot(b);
    let lambda = m - r;
    let size = a.abs() + b.abs() + c.abs();
    let (u, v) = if r <= UMBILIC_RELATIVE * size || r == 0.0 {
        (1.0, 0.0)
    } else {
        let (p, q) = ((b, lambda - a), (lambda - c, b));
        if p.0.hypot(p.1) >= q.0.hypot(q.1) {
            p
        } else {
            q
        }
    };
    let d1 = (t1 * u + t2 * v).normalize();
    Principal {
        k1: -m + r,
        k2: -m - r,
        d1,
        d2: n.cross(&d1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    /// Rounding of the few products and sums above, relative to the curvatures' size.
    const TOL: f64 = 1e-13;

    #[test]
    fn cylinder_bends_round_its_axis() {
        // Radius 2 about z, at (2, 0, 0) with the outward normal: the surface bends away from
        // n along y (κn = −1/2 in the workbench's sign), not at all along z.
        let s = Matrix3::new(0.0, 0.0, 0.0, 0.0, -0.5, 0.0, 0.0, 0.0, 0.0);
        let p = principal_frame(&s, &Vector3::x());
        assert!((p.k1 - 0.5).abs() < TOL && p.k2.abs() < TOL, "{p:?}");
        assert!((p.d1.dot(&Vector3::y()).abs() - 1.0).abs() < TOL, "{p:?}");
        assert!((p.d2.dot(&Vector3::z()).abs() - 1.0).abs() < TOL, "{p:?}");
    }

    #[test]
    fn sphere_is_umbilic_with_positive_curvature() {
        let n = Vector3::new(1.0, 2.0, -2.0) / 3.0;
        let s = -(Matrix3::identity() - n * n.transpose());
        let p = principal_frame(&s, &n);
        assert!(
            (p.k1 - 1.0).abs() < TOL && (p.k2 - 1.0).abs() < TOL,
            "{p:?}"
        );
        assert!(p.d1.dot(&n).abs() < TOL && (p.d1.norm() - 1.0).abs() < TOL);
        assert!((p.d1.cross(&p.d2) - n).norm() < TOL, "right-handed");
    }

    #[test]
    fn rotated_saddle_gives_its_eigenpairs_in_order() {
        // κn = 3 along e1, −1.5 along e2 (workbench sign), turned about an arbitrary axis.
        let rot = Rotation3::from_axis_angle(
            &nalgebra::Unit::new_normalize(Vector3::new(0.3, -1.0, 0.7)),
            1.1,
        );
        let (e1, e2, n) = (rot * Vector3::x(), rot * Vector3::y(), rot * Vector3::z());
        let s = 3.0 * e1 * e1.transpose() - 1.5 * e2 * e2.transpose();
        let p = principal_frame(&s, &n);
        // Exported: κ = −κn, so κ1 = 1.5 along e2, κ2 = −3 along e1.
        assert!(
            (p.k1 - 1.5).abs() < TOL && (p.k2 + 3.0).abs() < TOL,
            "{p:?}"
        );
        assert!((p.d1.dot(&e2).abs() - 1.0).abs() < TOL, "{p:?}");
        assert!((p.d2.dot(&e1).abs() - 1.0).abs() < TOL, "{p:?}");
        // The same values as the curvatures alone.
        let [lo, hi] = crate::principal_curvatures(&s, &n);
        assert!((p.k1 + lo).abs() < TOL && (p.k2 + hi).abs() < TOL);
    }

    #[test]
    fn zero_normal_is_not_a_number() {
        let p = principal_frame(&Matrix3::zeros(), &Vector3::zeros());
        assert!(!p.d1.x.is_finite());
    }
}

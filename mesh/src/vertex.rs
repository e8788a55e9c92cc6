//! The data a surface carries at a point: position, unit normal and second fundamental form.
//!
//! Conventions (docs/conventions.md, "Geometry"): the second fundamental form is a symmetric
//! 3×3 shape tensor `S` in world coordinates with `S n = 0`, so that the normal curvature in a
//! unit tangent direction `d` is `κn(d) = dᵀ S d`, positive where the surface bends towards `n`
//! (the unit sphere with outward normals has `κn = −1`).

use nalgebra::{Matrix3, Point3, Vector3};

/// A point of the surface with its normal and second fundamental form: the data of a mesh
/// vertex, and of each end of a boundary curve (the `curves` crate's `BoundaryProblem`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexData {
    /// Position.
    pub p: Point3<f64>,
    /// Normal (normalized where it is used, e.g. by the boundary-curve problem; need not be
    /// unit on input).
    pub n: Vector3<f64>,
    /// Shape tensor `S` in world coordinates: `κn(d) = dᵀ S d` for unit tangent `d`.
    pub shape: Matrix3<f64>,
}

impl VertexData {
    /// Data from position, normal and shape tensor.
    pub fn new(p: Point3<f64>, n: Vector3<f64>, shape: Matrix3<f64>) -> Self {
        VertexData { p, n, shape }
    }

    /// Normal curvature `dᵀ S d` in the unit direction `d`.
    pub fn normal_curvature(&self, d: &Vector3<f64>) -> f64 {
        d.dot(&(self.shape * d))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rounding of a 3×3 quadratic form with entries of order 1.
    const FORM_TOLERANCE: f64 = 1e-15;

    #[test]
    fn normal_curvature_of_the_unit_sphere_is_minus_one_in_every_direction() {
        // Outward normal z at the north pole: S = −(I − n nᵀ).
        let n = Vector3::z();
        let s = -(Matrix3::identity() - n * n.transpose());
        let v = VertexData::new(Point3::new(0.0, 0.0, 1.0), n, s);
        for k in 0..8 {
            let a = f64::from(k) * std::f64::consts::FRAC_PI_4;
            let d = Vector3::new(a.cos(), a.sin(), 0.0);
            assert!((v.normal_curvature(&d) + 1.0).abs() < FORM_TOLERANCE);
        }
    }
}

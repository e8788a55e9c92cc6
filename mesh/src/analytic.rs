//! Points of analytic surfaces with exact normals and shape tensors: ground truth for tests,
//! benchmarks and sample problems of the curve layer. (The data sets, [`crate::datasets`], build whole
//! meshes on these.)
//!
//! Normals point outward and the shape tensor follows docs/conventions.md: `κn(d) = dᵀ S d`, positive where
//! the surface bends towards `n`, so convex parts of closed surfaces have negative curvatures.

use nalgebra::{Matrix3, Point3, Vector3};

use crate::vertex::VertexData;

/// The point of the sphere of radius `radius` about the origin in direction `dir`:
/// `S = −(I − n nᵀ)/radius`, so `κn = −1/radius` in every direction.
pub fn sphere_point(dir: &Vector3<f64>, radius: f64) -> VertexData {
    let n = dir.normalize();
    VertexData::new(
        Point3::from(n * radius),
        n,
        -(Matrix3::identity() - n * n.transpose()) / radius,
    )
}

/// The point of the torus about the z axis with major radius `big` and tube radius `small` at
/// angles `u` (around the axis) and `v` (around the tube, `v = 0` on the outer equator).
///
/// Position `((R + r cos v) cos u, (R + r cos v) sin u, r sin v)`, outward normal
/// `(cos v cos u, cos v sin u, sin v)`; the principal directions `e_u`, `e_v` have normal
/// curvatures `−cos v/(R + r cos v)` and `−1/r` (do Carmo, *Differential Geometry of Curves and
/// Surfaces*, §3-3), so the inner half (`cos v < 0`) is saddle-shaped.
pub fn torus_point(u: f64, v: f64, big: f64, small: f64) -> VertexData {
    let (su, cu, sv, cv) = (u.sin(), u.cos(), v.sin(), v.cos());
    let p = Point3::new((big + small * cv) * cu, (big + small * cv) * su, small * sv);
    let n = Vector3::new(cv * cu, cv * su, sv);
    let eu = Vector3::new(-su, cu, 0.0);
    let ev = Vector3::new(-sv * cu, -sv * su, cv);
    let ku = -cv / (big + small * cv);
    let kv = -1.0 / small;
    VertexData::new(p, n, eu * eu.transpose() * ku + ev * ev.transpose() * kv)
}

/// The edges of the regular `nu × nv` triangulation of the torus (each grid quad split along its
/// `(i, j)–(i+1, j+1)` diagonal), as pairs of grid angles `((u_a, v_a), (u_b, v_b))`: `3 nu nv`
/// edges, each once.
pub fn torus_grid_edges(nu: usize, nv: usize) -> Vec<((f64, f64), (f64, f64))> {
    let (du, dv) = (
        std::f64::consts::TAU / nu as f64,
        std::f64::consts::TAU / nv as f64,
    );
    let angle = |i: usize, j: usize| (i as f64 * du, j as f64 * dv);
    let mut out = Vec::with_capacity(3 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let a = angle(i, j);
            out.push((a, angle(i + 1, j)));
            out.push((a, angle(i, j + 1)));
            out.push((a, angle(i + 1, j + 1)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact identities in floating point.
    const EXACT: f64 = 1e-14;

    #[test]
    fn shape_tensors_annihilate_the_normal() {
        let s = sphere_point(&Vector3::new(1.0, 2.0, 2.0), 3.0);
        assert!((s.shape * s.n).norm() < EXACT);
        assert!((s.p.coords.norm() - 3.0).abs() < EXACT);
        let t = torus_point(0.7, 2.1, 1.0, 0.4);
        assert!((t.shape * t.n).norm() < EXACT);
        assert!((t.n.norm() - 1.0).abs() < EXACT);
        // Gaussian curvature of the torus: cos v / (r (R + r cos v)).
        let e = t.shape.symmetric_eigenvalues();
        let mut nz: Vec<f64> = e.iter().copied().filter(|x| x.abs() > 1e-12).collect();
        nz.sort_by(f64::total_cmp);
        let k = nz[0] * nz[1];
        let cv = 2.1f64.cos();
        assert!((k - cv / (0.4 * (1.0 + 0.4 * cv))).abs() < 1e-12);
        assert_eq!(torus_grid_edges(16, 8).len(), 384);
    }
}

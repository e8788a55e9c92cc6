//! `flat` (the testbed's Fitter0): the net is the triangle, and the measured normal jump
//! across an edge is the dihedral angle.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions, VertexData};
use nalgebra::{Matrix3, Point3, Vector3};
use surface::mesh::Vertex;
use surface::{fit_scheme, measure_g1, scheme_by_name, Mesh, SchemeOptions};

/// An angle from atan2 of exact-ish cross and dot products: rounding only.
const ANGLE: f64 = 1e-14;

#[test]
fn the_normal_jump_is_the_dihedral_angle() {
    for h in [0.1, 0.5, 1.0, 3.0] {
        // Two triangles over the edge (0,0,0)–(1,0,0), the second one folded up by atan(h).
        let p = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.5, 1.0, 0.0),
            Point3::new(0.5, -1.0, h),
        ];
        let verts = p
            .iter()
            .map(|q| Vertex::new(VertexData::new(*q, Vector3::z(), Matrix3::zeros())))
            .collect();
        let mesh = Mesh::new(verts, vec![[0, 1, 2], [1, 0, 3]]).unwrap();
        let s = scheme_by_name("flat", &SchemeOptions::default()).unwrap();
        let m = method_by_name("chord", &MethodOptions::default()).unwrap();
        let f = fit_scheme(&mesh, s.as_ref(), m.as_ref()).unwrap();
        assert_eq!(f.points.len(), 6);
        assert_eq!(f.net(1).unwrap(), &[p[1], p[0], p[3]]);
        let g1 = measure_g1(&mesh, &f, 5);
        assert!(
            (g1.exterior_max - h.atan()).abs() < ANGLE,
            "h = {h}: {}",
            g1.exterior_max
        );
        assert!(f.curves.is_empty(), "flat builds no curves");
    }
}

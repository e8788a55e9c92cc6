//! `estimate::facing`: flat sectors get their plane, and a normal facing away from a face of
//! its sector is turned to the nearest one that faces them all. The nearest normal is checked
//! against an independent solver of the same quadratic program (Dykstra's alternating
//! projections), and through `prepare` on a mesh like a user's.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use estimate::facing::{facing_normal, facing_normal_across, widest_margin, FACING_SHARE};
use estimate::{prepare, EstimateChoice};
use meshio::RawMesh;
use nalgebra::{Point3, Vector3};
use proptest::prelude::*;

/// Dykstra's projections on the intersection of half-spaces converge linearly; after
/// [`DYKSTRA_ROUNDS`] rounds on these small problems the iterate is within 1e-7 of the
/// projection (checked by its own stall), so the exact solver must agree to that.
const AGREE: f64 = 1e-6;
/// Rounds of Dykstra's method.
const DYKSTRA_ROUNDS: usize = 20_000;
/// The exact solver's constraints hold to its feasibility tolerance (1e-12) and a normalization.
const HOLDS: f64 = 1e-10;

/// The projection of `n0` onto `{x : a·x ≥ δ for every a}` by Dykstra's method.
fn dykstra(n0: &Vector3<f64>, cons: &[Vector3<f64>], delta: f64) -> Vector3<f64> {
    let mut x = *n0;
    let mut incr = vec![Vector3::zeros(); cons.len()];
    for _ in 0..DYKSTRA_ROUNDS {
        for (a, p) in cons.iter().zip(incr.iter_mut()) {
            let y = x + *p;
            let gap = delta - a.dot(&y);
            let proj = if gap > 0.0 {
                y + a * (gap / a.norm_squared())
            } else {
                y
            };
            *p = y - proj;
            x = proj;
        }
    }
    x
}

/// A unit vector from spherical angles.
fn unit(theta: f64, phi: f64) -> Vector3<f64> {
    Vector3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

proptest! {
    #[test]
    fn the_turned_normal_is_the_nearest_that_faces_every_face(
        faces in prop::collection::vec((0.0f64..1.3, 0.0f64..std::f64::consts::TAU), 1..10),
        start in (0.0f64..3.1, 0.0f64..std::f64::consts::TAU),
    ) {
        // Face normals within 75° of +z: they lie in an open hemisphere.
        let cons: Vec<Vector3<f64>> = faces.iter().map(|(t, p)| unit(*t, *p)).collect();
        let n0 = unit(start.0, start.1);
        let delta = widest_margin(&cons).expect("an open hemisphere") * FACING_SHARE;
        let n = facing_normal(&n0, &cons, delta).expect("an open hemisphere holds them");
        prop_assert!((n.norm() - 1.0).abs() < HOLDS);
        for a in &cons {
            prop_assert!(a.dot(&n) > 0.0);
        }
        let x = dykstra(&n0, &cons, delta);
        let want = x.normalize();
        prop_assert!((n - want).norm() < AGREE, "{n:?} vs {want:?}");
        // A normal that already faces every face by the margin is kept.
        if cons.iter().all(|a| a.dot(&n0) >= delta) {
            prop_assert!((n - n0).norm() < HOLDS);
        }
    }
}

#[test]
fn faces_in_no_hemisphere_have_no_facing_normal() {
    let cons = [Vector3::z(), -Vector3::z(), Vector3::x()];
    assert!(facing_normal(&Vector3::x(), &cons, 0.01).is_none());
    // Four normals of a tetrahedron's faces: every direction is behind one of them.
    let tet = [
        Vector3::new(1.0, 1.0, 1.0),
        Vector3::new(1.0, -1.0, -1.0),
        Vector3::new(-1.0, 1.0, -1.0),
        Vector3::new(-1.0, -1.0, 1.0),
    ]
    .map(|v| v.normalize());
    assert!(facing_normal(&Vector3::z(), &tet, 0.01).is_none());
}

/// A flat square `[-1, 1]²` of `(2m)²` quads at `z = 0`, with a bump of height `h` on the
/// vertices within `r` of `(0.6, 0.6)`, as a raw mesh (positions only).
fn plate_with_bump(m: usize, h: f64, r: f64) -> RawMesh {
    let n = 2 * m + 1;
    let mut positions = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let x = i as f64 / m as f64 - 1.0;
            let y = j as f64 / m as f64 - 1.0;
            let d = ((x - 0.6).powi(2) + (y - 0.6).powi(2)).sqrt();
            let z = if d < r {
                h * (1.0 - d / r).powi(2)
            } else {
                0.0
            };
            positions.push(Point3::new(x, y, z));
        }
    }
    let idx = |i: usize, j: usize| j * n + i;
    let mut tris = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            tris.push([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]);
            tris.push([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]);
        }
    }
    RawMesh::from_triangles(positions, &tris)
}

#[test]
fn a_flat_star_gets_its_plane_next_to_a_bump() {
    let raw = plate_with_bump(10, 0.3, 0.35);
    let choice = EstimateChoice::parse(estimate::DEFAULT_ESTIMATOR).unwrap();
    let prepared = prepare(&raw, choice, false).expect("prepared");
    let mesh = &prepared.mesh;
    assert!(prepared.facing.flat_sectors > 0);
    // Every vertex whose whole star is in the plane (its faces all at z = 0 in the working
    // frame's orientation: the frame only scales and shifts) has the plane's normal exactly
    // and no curvature, however close the bump is.
    let mut flat = 0;
    for (v, vert) in mesh.vertices().iter().enumerate() {
        let star = mesh.faces_around_vertex(v);
        let planar = star.iter().all(|&f| {
            mesh.faces()[f]
                .iter()
                .all(|&w| mesh.vertices()[w].data.p.z == mesh.vertices()[v].data.p.z)
        });
        if !planar || star.len() < 2 {
            continue;
        }
        flat += 1;
        let n = vert.data.n;
        assert!(
            n.x == 0.0 && n.y == 0.0 && n.z.abs() == 1.0,
            "vertex {v}: {n:?}"
        );
        assert!(vert.data.shape.iter().all(|s| *s == 0.0), "vertex {v}");
    }
    assert!(flat > 100, "{flat}");
}

/// A normal perpendicular to a line is within rounding of it.
const PERPENDICULAR: f64 = 1e-12;

proptest! {
    /// With one line, the normal is the nearest to `n0` in the plane `⊥ ℓ` that faces every face
    /// by half the widest margin there: checked against Dykstra's projections on the face
    /// normals projected onto that plane (for `x` in the plane, `N · x = (P N) · x`).
    #[test]
    fn the_normal_across_one_line_is_the_nearest_in_its_plane(
        faces in prop::collection::vec((0.0f64..1.0, 0.0f64..std::f64::consts::TAU), 1..10),
        start in (0.0f64..3.1, 0.0f64..std::f64::consts::TAU),
        azimuth in 0.0f64..std::f64::consts::TAU,
    ) {
        // Face normals within 57° of +z and a horizontal line: +z is perpendicular to it and
        // faces them all, so the problem is feasible.
        let cons: Vec<Vector3<f64>> = faces.iter().map(|(t, p)| unit(*t, *p)).collect();
        let line = Vector3::new(azimuth.cos(), azimuth.sin(), 0.0) * 2.5;
        let n0 = unit(start.0, start.1);
        let n = facing_normal_across(&n0, &cons, &[line]).expect("feasible");
        prop_assert!((n.norm() - 1.0).abs() < HOLDS);
        prop_assert!(n.dot(&line).abs() < PERPENDICULAR * line.norm());
        for a in &cons {
            prop_assert!(a.dot(&n) > 0.0);
        }
        let l = line.normalize();
        let p = |v: &Vector3<f64>| v - l * v.dot(&l);
        let projected: Vec<Vector3<f64>> = cons.iter().map(p).collect();
        let delta = widest_margin(&projected).expect("feasible") * FACING_SHARE;
        let want = dykstra(&p(&n0), &projected, delta).normalize();
        prop_assert!((n - want).norm() < AGREE, "{n:?} vs {want:?}");
    }
}

#[test]
fn the_normal_across_two_lines_is_their_cross_product_facing_the_faces() {
    let faces = [Vector3::new(0.2, 0.1, 1.0).normalize(), Vector3::z()];
    let lines = [Vector3::new(1.0, 0.0, 0.1), Vector3::new(0.0, 2.0, -0.1)];
    let n = facing_normal_across(&-Vector3::z(), &faces, &lines).expect("feasible");
    let want = lines[0].cross(&lines[1]).normalize();
    assert!((n - want).norm() < HOLDS, "{n:?}");
    assert!(faces.iter().all(|f| f.dot(&n) > 0.0));
    // A third line off that normal, and faces no normal across the lines faces: none.
    let three = [lines[0], lines[1], Vector3::z()];
    assert!(facing_normal_across(&Vector3::z(), &faces, &three).is_none());
    let away = [Vector3::z(), -Vector3::z()];
    assert!(facing_normal_across(&Vector3::z(), &away, &[Vector3::x()]).is_none());
}

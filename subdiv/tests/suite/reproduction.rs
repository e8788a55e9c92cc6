//! Exact polynomial reproduction on regular grids, planarity, and affine invariance.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use nalgebra::{Matrix3, Point3, Vector3};
use proptest::prelude::*;
use rng::SplitMix64;
use subdiv::shapes::{irregular_small, quad_grid, triangle_grid};
use subdiv::{subdivide, CatmullClark, Loop, LoopWeights, PolyMesh, Subdivision, VertexKind};

/// Coordinates of order 10 after a few exact-in-binary steps; rounding stays below this.
const EXACT: f64 = 1e-12;

fn with_height(mesh: &PolyMesh, f: impl Fn(f64, f64) -> f64) -> PolyMesh {
    let pos = mesh
        .positions()
        .iter()
        .map(|p| Point3::new(p.x, p.y, f(p.x, p.y)))
        .collect();
    mesh.with_positions(pos).unwrap()
}

fn jittered(mesh: &PolyMesh, seed: u64) -> PolyMesh {
    let mut rng = SplitMix64::new(seed);
    let pos = mesh
        .positions()
        .iter()
        .map(|p| {
            Point3::new(
                p.x + 0.3 * (rng.next_f64() - 0.5),
                p.y + 0.3 * (rng.next_f64() - 0.5),
                p.z,
            )
        })
        .collect();
    mesh.with_positions(pos).unwrap()
}

/// Interior vertices whose whole one-ring is regular and interior (`margin` rings from the
/// border of an `n × n` grid).
fn inner(mesh: &PolyMesh, n: usize, margin: f64) -> Vec<usize> {
    (0..mesh.num_vertices())
        .filter(|&v| {
            let p = mesh.positions()[v];
            p.x >= margin && p.y >= margin && p.x <= n as f64 - margin && p.y <= n as f64 - margin
        })
        .collect()
}

#[test]
fn planes_stay_planes() {
    let plane = |x: f64, y: f64| 0.3 * x - 0.2 * y + 1.0;
    let cases: Vec<(Box<dyn Subdivision>, PolyMesh)> = vec![
        (Box::new(Loop::default()), triangle_grid(5, 4)),
        (
            Box::new(Loop {
                weights: LoopWeights::Warren,
            }),
            triangle_grid(5, 4),
        ),
        (Box::new(CatmullClark), quad_grid(5, 4)),
        (Box::new(CatmullClark), triangle_grid(5, 4)),
    ];
    for (scheme, grid) in cases {
        let mesh = with_height(&jittered(&grid, 4), plane);
        let out = subdivide(scheme.as_ref(), &mesh, 3, 1 << 20).unwrap();
        for p in out.positions() {
            assert!(
                (p.z - plane(p.x, p.y)).abs() < EXACT,
                "{}: {p}",
                scheme.name()
            );
        }
        let n0 = Vector3::new(-0.3, 0.2, 1.0).normalize();
        for (p, n) in scheme
            .limit_positions(&out)
            .unwrap()
            .iter()
            .zip(scheme.limit_normals(&out).unwrap())
        {
            assert!(
                (p.z - plane(p.x, p.y)).abs() < EXACT,
                "{}: limit {p}",
                scheme.name()
            );
            assert!((n - n0).norm() < 1e-8, "{}: normal {n}", scheme.name());
        }
    }
}

/// Regular grids of a linear function: the limit at an interior vertex is the vertex itself
/// (cubic B-splines and the quartic box spline reproduce linear functions at the nodes).
#[test]
fn linear_functions_are_their_own_limit() {
    let f = |x: f64, y: f64| 2.0 * x - 0.5 * y + 3.0;
    for (scheme, grid) in [
        (&Loop::default() as &dyn Subdivision, triangle_grid(6, 6)),
        (&CatmullClark, quad_grid(6, 6)),
    ] {
        let mesh = with_height(&grid, f);
        let lim = scheme.limit_positions(&mesh).unwrap();
        for v in inner(&mesh, 6, 1.0) {
            assert!(
                (lim[v] - mesh.positions()[v]).norm() < EXACT,
                "{} v{v}",
                scheme.name()
            );
        }
    }
}

/// Loop on the regular triangulation is the three-direction quartic box spline, whose values
/// at the nodes are 1/2 (centre) and 1/12 (six neighbours): the limit of random heights is
/// that mask; for z = x² + xy the limit is x² + xy + 1/3 + 1/6 (Σ over the six neighbour
/// offsets of dx² is 4, of dx·dy is 2, divided by 12).
#[test]
fn loop_is_the_box_spline_on_regular_triangulations() {
    let grid = triangle_grid(6, 6);
    let mut rng = SplitMix64::new(11);
    let heights: Vec<f64> = (0..grid.num_vertices()).map(|_| rng.next_f64()).collect();
    let pos = grid
        .positions()
        .iter()
        .zip(&heights)
        .map(|(p, h)| Point3::new(p.x, p.y, *h))
        .collect();
    let mesh = grid.with_positions(pos).unwrap();
    let lim = Loop::default().limit_positions(&mesh).unwrap();
    let id = |i: usize, j: usize| j * 7 + i;
    for v in inner(&mesh, 6, 1.0) {
        let (i, j) = (v % 7, v / 7);
        let ring = [
            id(i + 1, j),
            id(i - 1, j),
            id(i, j + 1),
            id(i, j - 1),
            id(i + 1, j + 1),
            id(i - 1, j - 1),
        ];
        let expect = 0.5 * heights[v] + ring.iter().map(|&q| heights[q]).sum::<f64>() / 12.0;
        assert!((lim[v].z - expect).abs() < 1e-15, "v{v}");
    }
    let quad = with_height(&grid, |x, y| x * x + x * y);
    let lim = Loop::default().limit_positions(&quad).unwrap();
    for v in inner(&quad, 6, 1.0) {
        let p = quad.positions()[v];
        assert!(
            (lim[v].z - (p.x * p.x + p.x * p.y + 0.5)).abs() < EXACT,
            "v{v}"
        );
    }
}

/// Catmull–Clark on a regular quad grid is the bicubic B-spline: at a node the limit applies
/// (1, 4, 1)/6 in each direction, so x² ↦ x² + 1/3, x³ ↦ x³ + x, and x²y ↦ (x² + 1/3) y.
#[test]
fn catmull_clark_is_the_bicubic_b_spline_on_regular_grids() {
    let grid = quad_grid(6, 6);
    for (f, g) in [
        (
            (|x: f64, _y: f64| x * x) as fn(f64, f64) -> f64,
            (|x: f64, _y: f64| x * x + 1.0 / 3.0) as fn(f64, f64) -> f64,
        ),
        (|x, _| x * x * x, |x, _| x * x * x + x),
        (|x, y| x * x * y, |x, y| (x * x + 1.0 / 3.0) * y),
    ] {
        let mesh = with_height(&grid, f);
        let lim = CatmullClark.limit_positions(&mesh).unwrap();
        for v in inner(&mesh, 6, 1.0) {
            let p = mesh.positions()[v];
            assert!(
                (lim[v].z - g(p.x, p.y)).abs() < 1e-11,
                "v{v}: {} vs {}",
                lim[v].z,
                g(p.x, p.y)
            );
        }
        // And one step is the B-spline refinement: refined nodes keep reproducing.
        let fine = CatmullClark.step(&mesh).unwrap();
        let lim_fine = CatmullClark.limit_positions(&fine).unwrap();
        for v in inner(&mesh, 6, 1.0) {
            assert!((lim_fine[v] - lim[v]).norm() < 1e-11);
        }
    }
}

fn affine(m: &Matrix3<f64>, t: &Vector3<f64>, p: &Point3<f64>) -> Point3<f64> {
    Point3::from(m * p.coords + t)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Subdividing an affinely transformed mesh is transforming the subdivided mesh; the same
    /// for limit positions (every rule is an affine combination).
    #[test]
    fn affine_invariance(
        seed in 0u64..1000,
        entries in proptest::array::uniform9(-2.0f64..2.0),
        shift in proptest::array::uniform3(-10.0f64..10.0),
    ) {
        let m = Matrix3::from_row_slice(&entries);
        let t = Vector3::from(shift);
        let mesh = irregular_small(seed);
        let creased = PolyMesh::with_creases(
            mesh.positions().to_vec(), &mesh.to_raw().polygons, &[[0, 11], [4, 9], [9, 8]],
        ).unwrap();
        for scheme in [
            &Loop::default() as &dyn Subdivision,
            &Loop { weights: LoopWeights::Warren },
            &CatmullClark,
        ] {
            let moved = creased
                .with_positions(creased.positions().iter().map(|p| affine(&m, &t, p)).collect())
                .unwrap();
            let a = scheme.step(&moved).unwrap();
            let b = scheme.step(&creased).unwrap();
            let scale = 1.0 + m.norm() + t.norm();
            for (p, q) in a.positions().iter().zip(b.positions()) {
                prop_assert!((p - affine(&m, &t, q)).norm() < 1e-13 * scale * 10.0);
            }
            let la = scheme.limit_positions(&moved).unwrap();
            let lb = scheme.limit_positions(&creased).unwrap();
            for (v, (p, q)) in la.iter().zip(&lb).enumerate() {
                let tol = if creased.vertex_kind(v) == VertexKind::Dart { 1e-10 } else { 1e-12 };
                prop_assert!((p - affine(&m, &t, q)).norm() < tol * scale, "v{}", v);
            }
        }
    }
}

//! `gregory-charrot` (`surface::scheme::gregory_charrot`): every partial against finite
//! differences, the boundary curves and the edges' Chiyokura–Kimura tangent planes reproduced,
//! the vertices' position and tangent plane, G1 measured on the four data sets and on noisy and
//! irregular meshes, the same surface under a relabelling of the corners, linear data, and the
//! sphere approximated with its curvature through the tessellation.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, CubicBez3, MethodOptions};
use fixtures::analytic::Irregular;
use fixtures::SplitMix64;
use nalgebra::{Point3, Vector3};
use surface::patch::SampledForm;
use surface::repair::{repair, RepairOptions};
use surface::scheme::gregory_charrot::{face_points, GregoryCharrot, GREGORY_CHARROT};
use surface::scheme::Bary;
use surface::{
    compare_with_truth, dataset_by_name, fit_scheme, measure_g1, tessellate_fit, Derivatives, Fit,
    Mesh, Sphere,
};

/// The bound for a G1 claim (docs/conventions.md), also for normals compared by angle.
const G1_TOL: f64 = 1e-9;
/// Positions of order one through Bernstein evaluation and the blend: rounding.
const POSITION: f64 = 1e-12;
/// Finite-difference step in the local parameters.
const H: f64 = 1e-5;
/// Central differences of order h² (h = 1e-5) on data of order one: agreement to ~1e-8 of the
/// magnitudes, bounded with margin.
const FD_TOL: f64 = 1e-6;
/// A relabelled face evaluates the same formulas in another order: rounding.
const RELABEL: f64 = 1e-12;

fn fit_of(mesh: &Mesh, method: &str) -> Fit {
    let m = method_by_name(method, &MethodOptions::default()).unwrap();
    fit_scheme(mesh, &GregoryCharrot, m.as_ref()).unwrap()
}

fn eval(pts: &[Point3<f64>], x: Bary) -> Derivatives {
    GREGORY_CHARROT.eval(pts, &GREGORY_CHARROT.prepare(x))
}

/// A random curved face: corners, unit normals within ~30° of the plane normal, curve
/// tangents in the vertex tangent planes at random lengths.
fn random_face(seed: u64) -> ([CubicBez3; 3], [Vector3<f64>; 3]) {
    let mut rng = SplitMix64::new(seed);
    let v: [Vector3<f64>; 3] = [
        Vector3::new(0.0, 0.0, rng.uniform(-0.2, 0.2)),
        Vector3::new(1.0 + rng.uniform(-0.2, 0.2), 0.1, rng.uniform(-0.2, 0.2)),
        Vector3::new(0.4, 0.9 + rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)),
    ];
    let up = (v[1] - v[0]).cross(&(v[2] - v[0])).normalize();
    let n: [Vector3<f64>; 3] = std::array::from_fn(|_| {
        (up + Vector3::new(
            rng.uniform(-0.3, 0.3),
            rng.uniform(-0.3, 0.3),
            rng.uniform(-0.3, 0.3),
        ))
        .normalize()
    });
    let edges = std::array::from_fn(|l| {
        let (a, b) = (v[l], v[(l + 1) % 3]);
        let (na, nb) = (n[l], n[(l + 1) % 3]);
        let chord = b - a;
        let ta = (chord - na * na.dot(&chord)) * rng.uniform(0.25, 0.4);
        let tb = (chord - nb * nb.dot(&chord)) * rng.uniform(0.25, 0.4);
        CubicBez3::new([a, a + ta, b - tb, b].map(Point3::from))
    });
    (edges, n)
}

fn local(u: f64, v: f64) -> Bary {
    [u, v, 1.0 - u - v]
}

#[test]
fn partials_match_finite_differences() {
    for seed in 0..20 {
        let (edges, n) = random_face(seed);
        let pts = face_points(&edges, n);
        for (u, v) in [
            (0.2, 0.3),
            (0.6, 0.2),
            (0.1, 0.1),
            (0.45, 0.45),
            (0.05, 0.9),
        ] {
            let d = eval(&pts, local(u, v));
            let at = |du: f64, dv: f64| eval(&pts, local(u + du, v + dv));
            let (pu, mu, pv, mv) = (at(H, 0.0), at(-H, 0.0), at(0.0, H), at(0.0, -H));
            let fd = |a: Vector3<f64>, b: Vector3<f64>| (a - b) / (2.0 * H);
            let checks = [
                ("du", d.du, fd(pu.p.coords, mu.p.coords)),
                ("dv", d.dv, fd(pv.p.coords, mv.p.coords)),
                ("duu", d.duu, fd(pu.du, mu.du)),
                ("duv", d.duv, fd(pv.du, mv.du)),
                ("dvu", d.duv, fd(pu.dv, mu.dv)),
                ("dvv", d.dvv, fd(pv.dv, mv.dv)),
            ];
            for (name, got, want) in checks {
                assert!(
                    (got - want).norm() < FD_TOL * want.norm().max(1.0),
                    "seed {seed} ({u}, {v}) {name}: {got:?} vs {want:?}"
                );
            }
        }
    }
}

/// Along every edge the patch is the curve, and its normal is that of the edge's
/// Chiyokura–Kimura plane `span(E'(s), A(s))`, `A` the linear blend of `unit(n × E')` at the
/// ends (computed here from the curve and normals, not from the form).
#[test]
fn edges_carry_their_curves_and_chiyokura_kimura_planes() {
    for seed in 0..20 {
        let (edges, n) = random_face(seed);
        let pts = face_points(&edges, n);
        for l in 0..3 {
            let c = &edges[l];
            let (na, nb) = (n[l], n[(l + 1) % 3]);
            let d = |s: f64| {
                let p = c.points;
                let t = 1.0 - s;
                ((p[1] - p[0]) * (t * t) + (p[2] - p[1]) * (2.0 * s * t) + (p[3] - p[2]) * (s * s))
                    * 3.0
            };
            let (a0, a1) = (na.cross(&d(0.0)).normalize(), nb.cross(&d(1.0)).normalize());
            for s in [0.0, 0.1, 0.35, 0.5, 0.8, 1.0] {
                let mut x = [0.0; 3];
                x[l] = 1.0 - s;
                x[(l + 1) % 3] = s;
                let e = eval(&pts, x);
                assert!(
                    (e.p - c.eval(s)).norm() < POSITION,
                    "seed {seed} edge {l} s {s}"
                );
                let want = d(s).cross(&(a0 * (1.0 - s) + a1 * s)).normalize();
                let got = e.du.cross(&e.dv).normalize();
                let angle = got.cross(&want).norm().atan2(got.dot(&want));
                assert!(angle < G1_TOL, "seed {seed} edge {l} s {s}: {angle:e}");
            }
        }
    }
}

#[test]
fn vertices_take_their_position_and_tangent_plane_with_finite_curvature() {
    for seed in 0..10 {
        let (edges, n) = random_face(seed);
        let pts = face_points(&edges, n);
        for i in 0..3 {
            let mut x = [0.0; 3];
            x[i] = 1.0;
            let d = eval(&pts, x);
            assert!((d.p - edges[i].points[0]).norm() < POSITION);
            let normal = d.du.cross(&d.dv).normalize();
            assert!(normal.dot(&n[i]) > 1.0 - G1_TOL, "seed {seed} vertex {i}");
            assert!([d.duu, d.duv, d.dvv]
                .iter()
                .all(|h| h.iter().all(|c| c.is_finite())));
        }
    }
}

#[test]
fn relabelling_the_corners_gives_the_same_surface() {
    for seed in 0..10 {
        let (edges, n) = random_face(seed);
        let pts = face_points(&edges, n);
        // Corner i of the relabelled face is corner i + 1 of the original.
        let rot_edges = std::array::from_fn(|l| edges[(l + 1) % 3]);
        let rot_n = std::array::from_fn(|l| n[(l + 1) % 3]);
        let rot = face_points(&rot_edges, rot_n);
        for x in [[0.2, 0.3, 0.5], [0.7, 0.1, 0.2], [0.0, 0.4, 0.6]] {
            let a = eval(&pts, x);
            let b = eval(&rot, [x[1], x[2], x[0]]);
            assert!((a.p - b.p).norm() < RELABEL, "seed {seed} {x:?}");
        }
    }
}

#[test]
fn linear_data_is_reproduced() {
    let v = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(1.3, 0.2, 0.1),
        Vector3::new(0.3, 1.1, -0.2),
    ];
    let n = (v[1] - v[0]).cross(&(v[2] - v[0])).normalize();
    let edges = std::array::from_fn(|l| {
        let (a, b) = (v[l], v[(l + 1) % 3]);
        CubicBez3::new([a, a + (b - a) / 3.0, b - (b - a) / 3.0, b].map(Point3::from))
    });
    let pts = face_points(&edges, [n; 3]);
    for x in [
        [0.2, 0.3, 0.5],
        [0.6, 0.2, 0.2],
        [0.1, 0.8, 0.1],
        [1.0, 0.0, 0.0],
    ] {
        let d = eval(&pts, x);
        let want = v[0] * x[0] + v[1] * x[1] + v[2] * x[2];
        assert!((d.p.coords - want).norm() < POSITION, "{x:?}");
        assert!((d.du - (v[0] - v[2])).norm() < POSITION, "{x:?}");
        assert!((d.dv - (v[1] - v[2])).norm() < POSITION, "{x:?}");
        assert!(
            d.duu.norm() + d.duv.norm() + d.dvv.norm() < POSITION,
            "{x:?}"
        );
    }
}

#[test]
fn g1_on_every_data_set_and_on_noisy_irregular_meshes() {
    for name in ["sphere", "ring", "capsule", "octa"] {
        let data = dataset_by_name(name, None).unwrap();
        for method in ["chord", "dbhs", "optimized"] {
            let f = fit_of(&data.mesh, method);
            let g1 = measure_g1(&data.mesh, &f, 9);
            eprintln!(
                "{name}/{method}: exterior {:.2e} rad, {} fallback faces",
                g1.exterior_max,
                f.face_fallbacks.len()
            );
            assert!(g1.position_error < POSITION, "{name}/{method}: {g1:?}");
            assert_eq!(g1.undefined_normals, 0, "{name}/{method}");
            assert!(g1.max_angle() < G1_TOL, "{name}/{method}: {g1:?}");
        }
    }
    let irregular = Irregular {
        noise: 0.01,
        normals: true,
        seed: 7,
        ..Irregular::default()
    };
    for (name, raw) in [
        (
            "noisy sphere",
            fixtures::analytic::sphere(14, 9, &irregular),
        ),
        (
            "noisy torus",
            fixtures::analytic::torus(18, 9, 1.0, 0.35, &irregular),
        ),
    ] {
        let mesh = repair(&raw, &RepairOptions::default()).unwrap().mesh;
        let f = fit_of(&mesh, "chord");
        let g1 = measure_g1(&mesh, &f, 9);
        eprintln!("{name}: exterior {:.2e} rad", g1.exterior_max);
        assert!(g1.max_angle() < G1_TOL, "{name}: {g1:?}");
    }
}

/// The unit sphere at the default resolution with optimized curves, through the tessellation:
/// curvature finite at every sample (vertices a step inside); the errors measured (position
/// 3.8e-4 max, normal 0.105° max, K 0.025 RMS) bounded at about 2.5× so a regression in the
/// evaluation or its second derivatives shows.
#[test]
fn approximates_the_sphere_with_its_curvature() {
    let data = dataset_by_name("sphere", None).unwrap();
    let f = fit_of(&data.mesh, "optimized");
    let t = tessellate_fit(&data.mesh, &f, 6).unwrap();
    assert!(t.gaussian.iter().all(|k| k.is_finite()));
    let e = compare_with_truth(&t, &Sphere::unit());
    eprintln!("gregory-charrot on the sphere: {e:?}");
    assert!(e.position_max < 1e-3, "{e:?}");
    assert!(e.normal_max_degrees < 0.3, "{e:?}");
    assert!(e.gaussian_rms < 0.06, "{e:?}");
}

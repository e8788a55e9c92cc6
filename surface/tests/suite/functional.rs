//! The functional forms of `clough-tocher` and `powell-sabin` on height fields: C1 across every
//! interior edge measured (value and both partials compared from both faces at many points of
//! each edge, and the workbench's G1 normal-jump measure), on a regular grid, a jittered grid
//! with exact normals, and Franke's six test functions on their grid and scattered samplings;
//! linear and quadratic precision, no cubic precision; the height-field detection's rules; and
//! the parametric schemes left as they are on other data.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use fixtures::SplitMix64;
use nalgebra::{Matrix2, Matrix3, Point3, Vector2, Vector3};
use surface::scheme::functional::{self, detect, HeightFieldMode, NotHeightField};
use surface::scheme::Scheme;
use surface::{
    dataset_by_name, fit_scheme, measure_g1, scheme_by_name, BezierTriangle, Continuity, Fit, Mesh,
    SchemeOptions, Vertex, VertexData,
};

/// C1 across edges: values and partials from both sides agree to rounding (the patches'
/// coordinates and slopes are of order one to ten; de Casteljau and a 2 × 2 solve lose a few
/// digits), far below the parametric schemes' measured jumps (1e-3 and more).
const C1_TOL: f64 = 1e-9;
/// The G1 claim of docs/conventions.md.
const G1_TOL: f64 = 1e-9;
/// Precision: a reproduced polynomial differs from the patches by rounding only.
const EXACT: f64 = 1e-12;
/// A cubic is not reproduced: the error is of the order of the cubic's third derivative times
/// the cube of the grid step (1e-4 on a 5 × 5 grid), far above rounding.
const NOT_REPRODUCED: f64 = 1e-6;
/// Cubic precision of the least-squares cross-boundary rule: a 12 × 10 least-squares solve
/// (condition ~1e2) and de Casteljau on values of order one, rounding only.
const CUBIC_EXACT: f64 = 1e-10;
/// Samples per interior edge of the C1 comparison.
const EDGE_SAMPLES: usize = 16;

type Function = dyn Fn(f64, f64) -> (f64, Vector2<f64>);

/// A vertex of the graph of `f` at `(x, y)`: exact value and normal `(−∇f, 1)/|·|`.
fn graph_vertex(f: &Function, x: f64, y: f64) -> Vertex {
    let (z, g) = f(x, y);
    let n = Vector3::new(-g.x, -g.y, 1.0).normalize();
    Vertex::new(VertexData::new(Point3::new(x, y, z), n, Matrix3::zeros()))
}

/// The `n × n` grid on `[0, 1]²`, each square split along its rising diagonal, interior points
/// moved by up to `jitter` of a step (seeded).
fn grid(n: usize, jitter: f64, f: &Function) -> Mesh {
    let mut rng = SplitMix64::new(27);
    let h = 1.0 / (n - 1) as f64;
    let mut vertices = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let interior = i > 0 && j > 0 && i < n - 1 && j < n - 1;
            let (dx, dy) = if interior && jitter > 0.0 {
                (
                    rng.uniform(-jitter, jitter) * h,
                    rng.uniform(-jitter, jitter) * h,
                )
            } else {
                (0.0, 0.0)
            };
            vertices.push(graph_vertex(f, i as f64 * h + dx, j as f64 * h + dy));
        }
    }
    let mut faces = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = j * n + i;
            faces.push([a, a + 1, a + n + 1]);
            faces.push([a, a + n + 1, a + n]);
        }
    }
    Mesh::new(vertices, faces).unwrap()
}

fn smooth(x: f64, y: f64) -> (f64, Vector2<f64>) {
    let z = (2.0 * x).sin() * (3.0 * y).cos() + 0.5 * x * y;
    let g = Vector2::new(
        2.0 * (2.0 * x).cos() * (3.0 * y).cos() + 0.5 * y,
        -3.0 * (2.0 * x).sin() * (3.0 * y).sin() + 0.5 * x,
    );
    (z, g)
}

/// The scheme's functional form for `mesh` with `options`, checked to be detected.
fn functional_scheme_with(name: &str, options: &SchemeOptions, mesh: &Mesh) -> Box<dyn Scheme> {
    let s = scheme_by_name(name, options).unwrap();
    let (f, note) = functional::choose(s, mesh, HeightFieldMode::On).unwrap();
    assert!(note.unwrap().starts_with("detected a height field"));
    assert_eq!(f.continuity(), Continuity::C1);
    f
}

fn fit(name: &str, mesh: &Mesh) -> Fit {
    fit_with(name, &SchemeOptions::default(), mesh)
}

fn fit_with(name: &str, options: &SchemeOptions, mesh: &Mesh) -> Fit {
    let s = functional_scheme_with(name, options, mesh);
    let method = curves::method_by_name("chord", &curves::MethodOptions::default()).unwrap();
    let f = fit_scheme(mesh, s.as_ref(), method.as_ref()).unwrap();
    assert!(f.face_fallbacks.is_empty(), "{:?}", f.face_fallbacks);
    f
}

/// The patch of face `f` whose xy sub-triangle holds `q`, with `q`'s local `(u, v)`.
fn locate(fit: &Fit, f: usize, q: &Vector2<f64>) -> (BezierTriangle, f64, f64) {
    let per = fit.layout.patches_per_face();
    let n = fit.layout.degree;
    for s in 0..per {
        let patch = fit.patch(f * per + s).unwrap();
        let pts = patch.points();
        let c = [pts[0], pts[n], pts[pts.len() - 1]].map(|p| Vector2::new(p.x, p.y));
        let m = Matrix2::from_columns(&[c[0] - c[2], c[1] - c[2]]);
        let uv = m.try_inverse().unwrap() * (q - c[2]);
        if uv.x >= -1e-9 && uv.y >= -1e-9 && uv.x + uv.y <= 1.0 + 1e-9 {
            return (patch, uv.x, uv.y);
        }
    }
    panic!("no patch of face {f} holds {q:?}");
}

/// Value and gradient `(z_x, z_y)` of face `f`'s surface over `q`.
fn value_and_gradient(fit: &Fit, f: usize, q: &Vector2<f64>) -> (f64, Vector2<f64>) {
    let (patch, u, v) = locate(fit, f, q);
    let d = patch.derivatives(u, v);
    assert!(
        (Vector2::new(d.p.x, d.p.y) - q).norm() < 1e-12,
        "xy is affine"
    );
    let j = Matrix2::new(d.du.x, d.dv.x, d.du.y, d.dv.y);
    let g = j.transpose().try_inverse().unwrap() * Vector2::new(d.du.z, d.dv.z);
    (d.p.z, g)
}

/// The largest jump of the value and of the gradient across the interior edges of `mesh`.
fn c1_jumps(mesh: &Mesh, fit: &Fit) -> (f64, f64) {
    let (mut dz, mut dg) = (0.0f64, 0.0f64);
    for e in mesh.edges() {
        let Some((g, _)) = e.second else { continue };
        let f = e.first.0;
        let [a, b] = e.vertices.map(|v| {
            let p = mesh.vertices()[v].data.p;
            Vector2::new(p.x, p.y)
        });
        for k in 0..EDGE_SAMPLES {
            let t = (k as f64 + 0.5) / EDGE_SAMPLES as f64;
            let q = a + (b - a) * t;
            let (z1, g1) = value_and_gradient(fit, f, &q);
            let (z2, g2) = value_and_gradient(fit, g, &q);
            dz = dz.max((z1 - z2).abs());
            dg = dg.max((g1 - g2).norm());
        }
    }
    (dz, dg)
}

fn assert_c1(label: &str, mesh: &Mesh, fit: &Fit) {
    let (dz, dg) = c1_jumps(mesh, fit);
    let g1 = measure_g1(mesh, fit, 9);
    println!(
        "{label}: value jump {dz:.2e}, gradient jump {dg:.2e}, G1 interior {:.2e} exterior {:.2e} rad",
        g1.interior_max, g1.exterior_max
    );
    assert!(dz < C1_TOL && dg < C1_TOL, "{label}: {dz:e} {dg:e}");
    assert!(
        g1.interior_max < G1_TOL && g1.exterior_max < G1_TOL,
        "{label}: {g1:?}"
    );
    assert!(
        g1.position_error < EXACT,
        "{label}: interpolates the values"
    );
}

#[test]
fn c1_across_edges_on_a_regular_and_a_jittered_grid() {
    for (label, jitter) in [("regular 8 × 8", 0.0), ("jittered 8 × 8", 0.3)] {
        let mesh = grid(8, jitter, &smooth);
        for name in ["clough-tocher", "powell-sabin"] {
            let f = fit(name, &mesh);
            assert_eq!(f.continuity, Continuity::C1);
            assert_c1(&format!("{name} {label}"), &mesh, &f);
        }
    }
}

#[test]
fn c1_across_edges_on_franke_data() {
    for k in 1..=6 {
        for (suffix, resolution) in [("", Some(9)), ("@scattered", None)] {
            let name = format!("franke{k}{suffix}");
            let data = dataset_by_name(&name, resolution).unwrap();
            for scheme in ["clough-tocher", "powell-sabin"] {
                let f = fit(scheme, &data.mesh);
                assert_c1(&format!("{scheme} {name}"), &data.mesh, &f);
            }
        }
    }
}

/// The largest `|z − p(x, y)|` over many points of every face.
fn max_error(mesh: &Mesh, fit: &Fit, p: &Function) -> f64 {
    let mut err = 0.0f64;
    for (f, face) in mesh.faces().iter().enumerate() {
        let c = face.map(|v| {
            let q = mesh.vertices()[v].data.p;
            Vector2::new(q.x, q.y)
        });
        for (i, j) in [
            (1, 1),
            (2, 1),
            (1, 2),
            (4, 1),
            (1, 4),
            (3, 3),
            (2, 5),
            (5, 2),
        ] {
            let (a, b) = (i as f64 / 10.0, j as f64 / 10.0);
            let q = c[0] * (1.0 - a - b) + c[1] * a + c[2] * b;
            let (z, _) = value_and_gradient(fit, f, &q);
            err = err.max((z - p(q.x, q.y).0).abs());
        }
    }
    err
}

#[test]
fn planes_and_quadratics_are_reproduced_cubics_are_not() {
    let plane = |x: f64, y: f64| (0.3 * x - 0.7 * y + 0.2, Vector2::new(0.3, -0.7));
    let quadratic = |x: f64, y: f64| {
        (
            0.3 * x * x - 0.7 * x * y + 0.5 * y * y + x - 2.0 * y + 0.1,
            Vector2::new(0.6 * x - 0.7 * y + 1.0, -0.7 * x + y - 2.0),
        )
    };
    let cubic = |x: f64, y: f64| (x * x * y, Vector2::new(2.0 * x * y, x * x));
    for name in ["clough-tocher", "powell-sabin"] {
        for jitter in [0.0, 0.3] {
            let m = grid(5, jitter, &plane);
            assert!(
                max_error(&m, &fit(name, &m), &plane) < EXACT,
                "{name} plane"
            );
            let m = grid(5, jitter, &quadratic);
            let e = max_error(&m, &fit(name, &m), &quadratic);
            assert!(e < EXACT, "{name} quadratic {e:e}");
            let m = grid(5, jitter, &cubic);
            let e = max_error(&m, &fit(name, &m), &cubic);
            println!("{name} jitter {jitter}: cubic x²y error {e:.3e}");
            assert!(e > NOT_REPRODUCED, "{name} cubic {e:e}");
        }
    }
}

#[test]
fn detection_accepts_height_fields_and_names_why_not() {
    let mesh = grid(6, 0.3, &smooth);
    let hf = detect(&mesh).unwrap();
    assert_eq!(hf.faces, 50);
    assert!(hf.note().contains("n_z > 0"));
    // The sphere's lower half faces down.
    let sphere = dataset_by_name("sphere", None).unwrap().mesh;
    assert!(matches!(
        detect(&sphere),
        Err(NotHeightField::NormalNotUp { .. })
    ));
    // A vertex dragged across its neighbours folds the projection: a flipped face.
    let mut folded = grid(6, 0.0, &smooth);
    folded.vertices_mut()[14].data.p.x += 0.5;
    assert!(matches!(
        detect(&folded),
        Err(NotHeightField::Flipped { .. })
    ));
    // Two sheets over the same square: every face is fine locally, they overlap.
    let a = grid(3, 0.0, &smooth);
    let mut vertices: Vec<Vertex> = a.vertices().to_vec();
    let mut faces = a.faces().to_vec();
    let offset = vertices.len();
    vertices.extend(a.vertices().iter().map(|v| {
        let mut v = v.clone();
        v.data.p.z += 1.0;
        v
    }));
    faces.extend(a.faces().iter().map(|f| f.map(|v| v + offset)));
    let two = Mesh::new(vertices, faces).unwrap();
    assert!(matches!(detect(&two), Err(NotHeightField::Overlap(..))));
    // Asked for, a non-height field is an error; by default the scheme stays parametric.
    let s = scheme_by_name("clough-tocher", &SchemeOptions::default()).unwrap();
    assert!(functional::choose(s, &sphere, HeightFieldMode::On).is_err());
    let s = scheme_by_name("clough-tocher", &SchemeOptions::default()).unwrap();
    let (kept, note) = functional::choose(s, &sphere, HeightFieldMode::Auto).unwrap();
    assert!(note.is_none());
    assert_eq!(kept.continuity(), Continuity::C0);
    // Off keeps the parametric scheme on a height field too.
    let s = scheme_by_name("powell-sabin", &SchemeOptions::default()).unwrap();
    let (kept, note) = functional::choose(s, &mesh, HeightFieldMode::Off).unwrap();
    assert!(note.is_none());
    assert_eq!(kept.continuity(), Continuity::C0);
    // A scheme without a functional form keeps its own.
    let s = scheme_by_name("shirman-sequin", &SchemeOptions::default()).unwrap();
    let (kept, note) = functional::choose(s, &mesh, HeightFieldMode::Auto).unwrap();
    assert!(note.unwrap().contains("no functional form"));
    assert_eq!(kept.continuity(), Continuity::G1);
}

#[test]
fn the_parametric_schemes_are_c0_on_the_same_height_field() {
    // What the issue measured: the parametric schemes jump across edges even on a height field.
    let mesh = grid(8, 0.3, &smooth);
    let method = curves::method_by_name("chord", &curves::MethodOptions::default()).unwrap();
    for name in ["clough-tocher", "powell-sabin"] {
        let s = scheme_by_name(name, &SchemeOptions::default()).unwrap();
        let f = fit_scheme(&mesh, s.as_ref(), method.as_ref()).unwrap();
        let g1 = measure_g1(&mesh, &f, 9);
        println!(
            "parametric {name}: exterior normal jump {:.3e} rad",
            g1.exterior_max
        );
        assert_eq!(f.continuity, Continuity::C0);
        assert!(g1.exterior_max > 100.0 * G1_TOL);
    }
}

#[test]
fn powell_sabin_splits_at_incentres_collinear_across_edges() {
    let mesh = grid(5, 0.3, &smooth);
    let f = fit("powell-sabin", &mesh);
    let xy = |p: &Point3<f64>| Vector2::new(p.x, p.y);
    // Net 2e of a face: (V_e, M_e, Z); its corners b200, b020, b002 are V_e, M_e, Z.
    let split = |face: usize, e: usize| {
        let n = f.net(face * 6 + 2 * e).unwrap();
        (xy(&n[2]), xy(&n[5]))
    };
    for (face, tri) in mesh.faces().iter().enumerate() {
        let p = tri.map(|v| xy(&mesh.vertices()[v].data.p));
        let z = functional::powell_sabin::incentre(&p);
        assert!((split(face, 0).1 - z).norm() < EXACT);
    }
    for e in mesh.edges() {
        let Some((g, lg)) = e.second else { continue };
        let (f1, l1) = e.first;
        let (m1, z1) = split(f1, l1);
        let (m2, z2) = split(g, lg);
        assert!((m1 - m2).norm() < EXACT, "shared edge split point");
        let collinear = (z1 - m1).perp(&(z2 - m1)).abs();
        assert!(collinear < EXACT, "Z, M, Z' collinear: {collinear:e}");
    }
}

/// `clough-tocher` with the least-squares cubic's cross-boundary derivative blended in by `w`.
fn ct_cubic(w: f64) -> SchemeOptions {
    SchemeOptions::default().with(&surface::scheme::clough_tocher::CUBIC_WEIGHT, w)
}

#[test]
fn the_least_squares_cubic_rule_is_c1_and_reproduces_cubics_inside() {
    let cubic = |x: f64, y: f64| {
        (
            x * x * x - 2.0 * x * x * y + 0.5 * x * y * y + y * y * y + 0.3 * x * y - y,
            Vector2::new(
                3.0 * x * x - 4.0 * x * y + 0.5 * y * y + 0.3 * y,
                -2.0 * x * x + x * y + 3.0 * y * y + 0.3 * x - 1.0,
            ),
        )
    };
    for jitter in [0.0, 0.3] {
        let mesh = grid(6, jitter, &cubic);
        // Faces whose three edges are interior.
        let inner: Vec<usize> = (0..mesh.num_faces())
            .filter(|&f| (0..3).all(|l| mesh.neighbour(f, l).unwrap().is_some()))
            .collect();
        assert!(inner.len() > 10);
        let err_on = |fit: &Fit| {
            let mut err = 0.0f64;
            for &f in &inner {
                let c = mesh.faces()[f].map(|v| {
                    let q = mesh.vertices()[v].data.p;
                    Vector2::new(q.x, q.y)
                });
                for (a, b) in [(0.1, 0.1), (0.2, 0.5), (0.45, 0.1), (0.3, 0.3), (0.6, 0.2)] {
                    let q = c[0] * (1.0 - a - b) + c[1] * a + c[2] * b;
                    err = err.max((value_and_gradient(fit, f, &q).0 - cubic(q.x, q.y).0).abs());
                }
            }
            err
        };
        let classical = err_on(&fit("clough-tocher", &mesh));
        let lsq = fit_with("clough-tocher", &ct_cubic(1.0), &mesh);
        let e = err_on(&lsq);
        println!(
            "jitter {jitter}: cubic error inside, classical {classical:.3e}, least squares {e:.3e}"
        );
        assert!(classical > NOT_REPRODUCED);
        assert!(e < CUBIC_EXACT, "{e:e}");
        assert_c1(&format!("ct-cubic 1 jitter {jitter}"), &mesh, &lsq);
    }
    for w in [0.5, 1.0] {
        let data = dataset_by_name("franke1@scattered", None).unwrap();
        let f = fit_with("clough-tocher", &ct_cubic(w), &data.mesh);
        assert_c1(&format!("ct-cubic {w} franke1@scattered"), &data.mesh, &f);
        let mesh = grid(8, 0.3, &smooth);
        let f = fit_with("clough-tocher", &ct_cubic(w), &mesh);
        assert_c1(&format!("ct-cubic {w} jittered"), &mesh, &f);
    }
}

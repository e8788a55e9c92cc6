//! The gradient estimators of functional data (`estimate::gradients`): exactness on the
//! polynomials each rule reproduces, measured orders of convergence on a smooth function, the
//! minimum-norm network's optimality, fallbacks on tiny meshes, and the normals and shape
//! tensors `apply_gradients` writes.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::support::k_h;

use estimate::gradients::GradientEstimator;
use estimate::gradients::{
    apply_gradients, gradient_estimator_by_name, minimum_norm, GradientFallback, CUBIC,
    GRADIENT_ESTIMATORS, MINIMUM_NORM,
};
use mesh::analytic_franke::Franke;
use mesh::{Mesh, Vertex};
use nalgebra::{Point3, Vector2, Vector3};

/// Scattered points of `[0, 1]²` (the Franke sampling with `n` points) with heights `f`.
fn scattered(n: usize, f: impl Fn(f64, f64) -> f64) -> Mesh {
    let mut m = mesh::datasets::franke_scattered(Franke::F1, "scattered", n)
        .expect("points")
        .mesh;
    for v in m.vertices_mut() {
        v.data.p.z = f(v.data.p.x, v.data.p.y);
    }
    m
}

/// The `n × n` grid of `[0, 1]²` with heights `f`.
fn grid(n: usize, f: impl Fn(f64, f64) -> f64) -> Mesh {
    let mut m = mesh::datasets::franke_grid(Franke::F1, "grid", n)
        .expect("grid")
        .mesh;
    for v in m.vertices_mut() {
        v.data.p.z = f(v.data.p.x, v.data.p.y);
    }
    m
}

/// A cubic with every monomial, and its gradient and Hessian.
fn cubic(x: f64, y: f64) -> (f64, Vector2<f64>, [f64; 3]) {
    let f = 0.3 + 1.1 * x - 0.7 * y + 0.9 * x * x - 1.3 * x * y + 0.4 * y * y + 0.8 * x * x * x
        - 0.6 * x * x * y
        + 1.7 * x * y * y
        - 0.5 * y * y * y;
    let fx = 1.1 + 1.8 * x - 1.3 * y + 2.4 * x * x - 1.2 * x * y + 1.7 * y * y;
    let fy = -0.7 - 1.3 * x + 0.8 * y - 0.6 * x * x + 3.4 * x * y - 1.5 * y * y;
    let hess = [
        1.8 + 4.8 * x - 1.2 * y,
        -1.3 - 1.2 * x + 3.4 * y,
        0.8 + 3.4 * x - 3.0 * y,
    ];
    (f, Vector2::new(fx, fy), hess)
}

/// A smooth non-polynomial function for the convergence tests, and its gradient.
fn smooth(x: f64, y: f64) -> (f64, Vector2<f64>) {
    let (e, s, c) = ((0.5 * x).exp(), (2.0 * y).sin(), (2.0 * y).cos());
    (
        e * s + x * y * y,
        Vector2::new(0.5 * e * s + y * y, 2.0 * e * c + 2.0 * x * y),
    )
}

#[test]
fn every_estimator_is_registered_once_and_found_by_name() {
    let names: Vec<&str> = GRADIENT_ESTIMATORS.iter().map(|e| e.name()).collect();
    assert_eq!(names, ["cubic", "minimum-norm"]);
    for e in GRADIENT_ESTIMATORS {
        assert_eq!(
            gradient_estimator_by_name(e.name()).expect("found").name(),
            e.name()
        );
        assert!(!e.description().is_empty());
    }
}

#[test]
fn cubic_reproduces_a_cubic_on_scattered_points() {
    /// The fit interpolates a cubic exactly; what remains is least-squares rounding, amplified
    /// by the conditioning of the scaled system (observed gradient errors ≤ 2.1e-12).
    const EXACT: f64 = 1e-9;
    let m = scattered(300, |x, y| cubic(x, y).0);
    let g = CUBIC.gradients(&m);
    assert!(g.fallbacks.is_empty(), "{:?}", g.fallbacks);
    for (v, vert) in m.vertices().iter().enumerate() {
        let (_, grad, hess) = cubic(vert.data.p.x, vert.data.p.y);
        assert!(
            (g.grad[v] - grad).norm() < EXACT,
            "vertex {v}: {} vs {grad}",
            g.grad[v]
        );
        let h = g.hess[v].expect("a Hessian");
        for k in 0..3 {
            assert!(
                (h[k] - hess[k]).abs() < EXACT,
                "vertex {v}: {h:?} vs {hess:?}"
            );
        }
    }
}

/// Largest gradient error over the vertices at least `margin` inside the square.
fn max_gradient_error(est: &dyn GradientEstimator, n: usize, margin: f64) -> f64 {
    let m = grid(n, |x, y| smooth(x, y).0);
    let g = est.gradients(&m);
    m.vertices()
        .iter()
        .enumerate()
        .filter(|(_, v)| {
            let p = v.data.p;
            p.x.min(p.y).min(1.0 - p.x).min(1.0 - p.y) >= margin
        })
        .map(|(i, v)| (g.grad[i] - smooth(v.data.p.x, v.data.p.y).1).norm())
        .fold(0.0, f64::max)
}

/// Asserts that `est`'s largest gradient error (vertices at least `margin` inside) on the grids
/// 17, 33, 65 falls at an observed order above `min_order` at each halving of the spacing.
fn assert_converges(est: &dyn GradientEstimator, margin: f64, min_order: f64) {
    let errs: Vec<f64> = [17, 33, 65]
        .iter()
        .map(|&n| max_gradient_error(est, n, margin))
        .collect();
    let o: Vec<f64> = errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    assert!(
        o.iter().all(|&k| k > min_order),
        "{} margin {margin}: errors {errs:?}, orders {o:?}",
        est.name()
    );
}

#[test]
fn cubic_gradients_converge_at_third_order() {
    /// Third order in theory, boundary included (observed 3.01 and 3.01 on the grids 17, 33,
    /// 65: errors 2.1e-3, 2.6e-4, 3.2e-5). Below 2.7 the rule would have lost an order.
    const MIN_ORDER: f64 = 2.7;
    assert_converges(&CUBIC, 0.0, MIN_ORDER);
}

#[test]
fn minimum_norm_reproduces_linear_data() {
    /// The solver stops at a relative residual of 1e-10; the gradients are then exact to about
    /// that relative to their size (observed 1e-12).
    const LINEAR: f64 = 1e-8;
    let m = scattered(200, |x, y| 0.4 + 1.5 * x - 2.25 * y);
    let g = MINIMUM_NORM.gradients(&m);
    assert!(g.fallbacks.is_empty());
    for (v, grad) in g.grad.iter().enumerate() {
        assert!(
            (grad - Vector2::new(1.5, -2.25)).norm() < LINEAR,
            "vertex {v}: {grad}"
        );
    }
}

#[test]
fn minimum_norm_gradients_minimize_the_network_energy() {
    /// The first-order change of the energy in any direction vanishes at the minimum: the
    /// central difference over ±ε, relative to the second-order change, is at the solver's
    /// residual (1e-10) plus rounding of the sums (observed ≤ 4e-8 at ε = 1e-3).
    const STATIONARY: f64 = 1e-4;
    let m = scattered(100, |x, y| Franke::F1.jet(x, y).f);
    let g = MINIMUM_NORM.gradients(&m);
    let e0 = minimum_norm::energy(&m, &g.grad);
    for seed in 0..5u32 {
        let dir: Vec<Vector2<f64>> = (0..g.grad.len())
            .map(|i| {
                let t = (i as f64 + 1.0) * (seed as f64 + 1.7);
                Vector2::new(t.sin(), (1.3 * t).cos())
            })
            .collect();
        let eps = 1e-3;
        let moved = |s: f64| -> Vec<Vector2<f64>> {
            g.grad.iter().zip(&dir).map(|(a, d)| a + d * s).collect()
        };
        let (plus, minus) = (
            minimum_norm::energy(&m, &moved(eps)),
            minimum_norm::energy(&m, &moved(-eps)),
        );
        let second = plus + minus - 2.0 * e0;
        assert!(
            second > 0.0,
            "the energy is not a minimum: {plus} {minus} {e0}"
        );
        assert!(
            (plus - minus).abs() <= STATIONARY * second,
            "not stationary: {plus} vs {minus}, second-order change {second}"
        );
    }
}

#[test]
fn minimum_norm_gradients_converge_at_first_order_at_the_boundary_and_faster_inside() {
    /// Along the square's sides the network's edges are one-sided: first order there (observed
    /// 1.00 on the grids 17, 33, 65); below 0.9 an order would have been lost.
    const MIN_ORDER_ALL: f64 = 0.9;
    /// A quarter of the side inside, the regular grid's symmetric stencils cancel error terms:
    /// observed orders 8.7 and 5.6 (errors 2.8e-4, 6.6e-7, 1.3e-8); second order is the least a
    /// consistent network of cubics gives.
    const MIN_ORDER_INSIDE: f64 = 2.0;
    assert_converges(&MINIMUM_NORM, 0.0, MIN_ORDER_ALL);
    assert_converges(&MINIMUM_NORM, 0.25, MIN_ORDER_INSIDE);
}

#[test]
fn tiny_meshes_fall_back_to_lower_degrees_and_stay_exact_on_planes() {
    /// Two equations in two unknowns, or one face's linear interpolant: rounding only.
    const PLANE: f64 = 1e-12;
    let plane = |p: Point3<f64>| Point3::new(p.x, p.y, 2.0 - 0.5 * p.x + 3.0 * p.y);
    let verts = [
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.1, 0.0),
        Point3::new(0.2, 0.9, 0.0),
        Point3::new(5.0, 5.0, 0.0),
    ]
    .map(|p| Vertex::without_curvature(plane(p), Vector3::z()));
    let m = Mesh::new(verts.to_vec(), vec![[0, 1, 2]]).expect("valid");
    for est in GRADIENT_ESTIMATORS {
        let g = est.gradients(&m);
        assert!(
            g.fallbacks.contains(&(3, GradientFallback::Isolated)),
            "{}: {:?}",
            est.name(),
            g.fallbacks
        );
        assert_eq!(g.grad[3], Vector2::zeros());
        for v in 0..3 {
            assert!(
                (g.grad[v] - Vector2::new(-0.5, 3.0)).norm() < PLANE,
                "{}: vertex {v}: {}",
                est.name(),
                g.grad[v]
            );
        }
    }
    // The cubic rule had two neighbours at each corner: the linear fit, recorded.
    let g = CUBIC.gradients(&m);
    assert!(g
        .fallbacks
        .contains(&(0, GradientFallback::LowerDegree { from: 3, to: 1 })));
    assert_eq!(g.hess[0], None);
}

#[test]
fn applied_gradients_give_the_graph_normals_and_curvatures() {
    /// The cubic fit is exact on the cubic; the normal and tensor are closed forms of its
    /// derivatives: rounding amplified by the fit (see the reproduction test).
    const EXACT: f64 = 1e-8;
    let mut m = scattered(300, |x, y| cubic(x, y).0);
    let g = CUBIC.gradients(&m);
    apply_gradients(&mut m, &g);
    for (v, vert) in m.vertices().iter().enumerate() {
        let (_, grad, [r, s, t]) = cubic(vert.data.p.x, vert.data.p.y);
        let (p, q) = (grad.x, grad.y);
        let w2 = 1.0 + p * p + q * q;
        let n = Vector3::new(-p, -q, 1.0) / w2.sqrt();
        assert!((vert.data.n - n).norm() < EXACT, "vertex {v}");
        assert!(vert.curvature_known);
        // The graph's curvatures (do Carmo §3-3, Monge patch), sign: towards the upward normal.
        let k = (r * t - s * s) / (w2 * w2);
        let h = ((1.0 + q * q) * r - 2.0 * p * q * s + (1.0 + p * p) * t) / (2.0 * w2.powf(1.5));
        let (k_est, h_est) = k_h(&vert.data.shape, &vert.data.n);
        assert!(
            (k_est - k).abs() < EXACT * (1.0 + k.abs()),
            "vertex {v}: K {k_est} vs {k}"
        );
        assert!(
            (h_est - h).abs() < EXACT * (1.0 + h.abs()),
            "vertex {v}: H {h_est} vs {h}"
        );
    }
    // Without a Hessian (minimum-norm) the curvature is unknown and the tensor zero.
    let g = MINIMUM_NORM.gradients(&m);
    apply_gradients(&mut m, &g);
    assert!(m
        .vertices()
        .iter()
        .all(|v| !v.curvature_known && v.data.shape == nalgebra::Matrix3::zeros()));
}

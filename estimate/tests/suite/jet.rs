//! The jet estimators: exact on quadrics, convergence orders on the sphere and the ring, the
//! sign convention.

use crate::support;

use estimate::{Estimator, JET, JET2, JET3, JET4};
use nalgebra::Matrix3;
use support::*;

#[test]
fn jets_reproduce_a_quadric_exactly() {
    for est in [&JET2, &JET3, &JET4] {
        assert_reproduces_quadric(est);
    }
}

#[test]
fn jets_reproduce_a_quartic_jet_of_degree_4_exactly() {
    /// Degree 4 fits a quartic height exactly: rounding only.
    const EXACT: f64 = 1e-9;
    let (a, b, c) = (0.9, 0.3, -0.5);
    let f = |x: f64, y: f64| {
        quad_height(a, b, c, x, y) + 0.7 * x * x * x - 0.2 * x * y * y + 0.4 * x * x * y * y
    };
    let (mesh, centre) = height_grid(4, 0.1, f);
    // Odd terms make the angle-weighted normal inexact: give the exact one (+z at the origin).
    let given = vec![nalgebra::Vector3::z(); mesh.num_vertices()];
    let e = run(&JET4, &mesh, Some(&given));
    let want = quad_tensor(a, b, c, &nalgebra::Rotation3::identity());
    assert!(
        (e.shapes[centre] - want).norm() < EXACT,
        "{:?}",
        e.shapes[centre]
    );
    // (Without the given normal the frame is tilted by the odd terms and the quartic is no
    // longer a quartic graph over it: close, not exact.)
}

#[test]
fn sphere_sign_convention() {
    /// Level 4: curvature errors ≈ 0.04 (jet2), tensor error per vertex below 0.2.
    const SIGN_TENSOR: f64 = 0.2;
    let d = mesh::datasets::sphere(4).expect("valid");
    let e = run(&JET, &d.mesh, None);
    for v in 0..d.mesh.num_vertices() {
        let n = e.normals[v];
        let (k, h) = k_h(&e.shapes[v], &n);
        assert!(h < 0.0 && k > 0.0, "vertex {v}: H = {h}, K = {k}");
        let want = -(Matrix3::identity() - n * n.transpose());
        assert!((e.shapes[v] - want).norm() < SIGN_TENSOR);
    }
}

/// Observed (RMS; sphere levels 3→4→5, ring 32→64→128):
///
/// | | normal ° | K | H | orders |
/// |---|---|---|---|---|
/// | jet2 sphere | 4.8e-2, 6.7e-3, 6.6e-4 | 0.151, 0.036, 8.8e-3 | 0.073, 0.018, 4.4e-3 | n 2.8–3.3, K/H 2.0 |
/// | jet2 ring | 2.73, 0.69, 0.17 | 0.348, 0.085, 0.021 | 0.254, 0.060, 0.015 | 2.0 |
/// | jet3 sphere | 0.38, 0.075, 7.9e-3 | 0.33, 0.071, 0.018 | 0.155, 0.035, 8.8e-3 | n 2.3–3.2, K/H 2.0–2.2 |
/// | jet3 ring | 2.06, 0.117, 7.5e-3 | 1.09, 0.224, 0.053 | 0.60, 0.132, 0.032 | n 4.0, K/H 2.0–2.3 |
/// | jet4 sphere | 2.0e-2, 1.1e-3, 3.2e-5 | 0.059, 3.7e-3, 2.3e-4 | 0.030, 1.9e-3, 1.2e-4 | n 4.1–5.2, K/H 4.0 |
/// | jet4 ring | 1.74, 0.109, 7.6e-3 | 0.397, 0.026, 2.0e-3 | 0.224, 0.013, 9.2e-4 | 3.7–4.0 |
///
/// Cazals–Pouget predict `O(h^{d−1})` for curvatures and `O(h^d)` for normals; the regular,
/// nearly symmetric neighbourhoods gain an order for even `d` (jet2: 2, jet4: 4).
#[test]
fn jets_converge_at_the_observed_orders() {
    // (estimator, min normal order, min curvature order): the observed orders less a margin.
    for (est, n_order, k_order) in [
        (&JET2, ORDER_2, ORDER_2),
        (&JET3, ORDER_2, ORDER_2),
        (&JET4, ORDER_4, ORDER_4),
    ] {
        let (sphere, ring) = convergence(est);
        for (set, errs) in [("sphere", &sphere), ("ring", &ring)] {
            let name = format!("{} {set}", est.name());
            assert_order(
                &errs.iter().map(|e| e.normal_deg).collect::<Vec<_>>(),
                n_order,
                &format!("{name} normal"),
            );
            assert_order(
                &errs.iter().map(|e| e.k).collect::<Vec<_>>(),
                k_order,
                &format!("{name} K"),
            );
            assert_order(
                &errs.iter().map(|e| e.h).collect::<Vec<_>>(),
                k_order,
                &format!("{name} H"),
            );
        }
        // And small at the finest level.
        /// Finest level: curvature RMS below 6e-2 for every jet (observed ≤ 5.3e-2).
        const FINE_CURVATURE: f64 = 6e-2;
        assert!(sphere[2].k < FINE_CURVATURE && ring[2].k < FINE_CURVATURE);
        assert!(sphere[2].h < FINE_CURVATURE && ring[2].h < FINE_CURVATURE);
    }
}

#[test]
fn jet_is_the_degree_2_jet() {
    assert_eq!(JET.degree, 2);
    let d = mesh::datasets::ring(16, 8).expect("valid");
    assert_eq!(JET.estimate(&d.mesh, None), JET2.estimate(&d.mesh, None));
}

#[test]
fn degree_falls_back_where_the_neighbourhood_is_small() {
    // A 2×2-quad grid: every neighbourhood holds at most 9 points, fewer than the 10
    // coefficients of degree 3: degree 2 everywhere, recorded.
    let (mesh, _) = height_grid(1, 1.0, |x, y| 0.1 * x * x + 0.05 * y * y);
    let e = run(&JET3, &mesh, None);
    assert!(e
        .fallbacks
        .iter()
        .all(|f| f.kind == estimate::FallbackKind::LowerDegree { from: 3, to: 2 }));
    assert_eq!(e.fallbacks.len(), mesh.num_vertices());
}

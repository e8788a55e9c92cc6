//! Section 4's corner measures: gradients against central differences at random points where
//! they do not vanish.

use cost::corner::{corner_curvature, corner_twist};
use nalgebra::{Matrix3, Vector3};

/// Central differences with step 1e-6 on O(1) quantities: truncation ~1e-12, rounding ~1e-10.
const FD: f64 = 1e-7;
const STEP: f64 = 1e-6;

use crate::common;
use common::Rng;

/// Checks `grad` against central differences of `f` along each coordinate of the vector at
/// `slot` of `args`.
fn check(
    f: &dyn Fn(&[Vector3<f64>]) -> f64,
    args: &[Vector3<f64>],
    slot: usize,
    grad: &Vector3<f64>,
) {
    assert!(grad.norm() > 1e-3, "a vanishing gradient tests nothing");
    for k in 0..3 {
        let (mut p, mut m) = (args.to_vec(), args.to_vec());
        p[slot][k] += STEP;
        m[slot][k] -= STEP;
        let fd = (f(&p) - f(&m)) / (2.0 * STEP);
        assert!(
            (fd - grad[k]).abs() < FD * grad[k].abs().max(1.0),
            "slot {slot} coordinate {k}: {fd} vs {}",
            grad[k]
        );
    }
}

#[test]
fn curvature_and_twist_gradients_match_finite_differences() {
    let mut rng = Rng::new(42);
    for _ in 0..200 {
        let n = (rng.vec() + Vector3::z() * 2.0).normalize();
        let p = Matrix3::identity() - n * n.transpose();
        let m = Matrix3::from_fn(|_, _| rng.next());
        let s = p * (m + m.transpose()) * p;
        let a = rng.vec() + Vector3::x() * 1.5;
        let b = rng.vec();
        let (_, ga, gb) = corner_curvature(&n, &s, &a, &b);
        let fk = |x: &[Vector3<f64>]| corner_curvature(&n, &s, &x[0], &x[1]).0;
        check(&fk, &[a, b], 0, &ga);
        check(&fk, &[a, b], 1, &gb);
        let (u, v, w) = (
            rng.vec() + Vector3::x() * 1.5,
            rng.vec() + Vector3::y() * 1.5,
            rng.vec(),
        );
        let (_, gu, gv, gw) = corner_twist(&n, &s, &u, &v, &w);
        let ft = |x: &[Vector3<f64>]| corner_twist(&n, &s, &x[0], &x[1], &x[2]).0;
        check(&ft, &[u, v, w], 0, &gu);
        check(&ft, &[u, v, w], 1, &gv);
        check(&ft, &[u, v, w], 2, &gw);
    }
}

#[test]
fn a_sphere_patch_has_zero_measures() {
    // On the unit sphere at the north pole (outward n, S = −(I − nnᵀ)): the great circle
    // x(θ) = (sin θ, 0, cos θ) has A = (1, 0, 0), B = (0, 0, −1): κn = −1 = tᵀ S t.
    let n = Vector3::z();
    let s = -(Matrix3::identity() - n * n.transpose());
    let (k, _, _) = corner_curvature(&n, &s, &Vector3::x(), &(-Vector3::z()));
    assert!(k.abs() < 1e-15);
    // Orthogonal directions on the sphere, no mixed derivative: the twist vanishes.
    let (t, _, _, _) = corner_twist(&n, &s, &Vector3::x(), &Vector3::y(), &Vector3::zeros());
    assert!(t.abs() < 1e-15);
}

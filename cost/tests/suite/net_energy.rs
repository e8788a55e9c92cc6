//! Net objectives: the Sobolev energies against closed forms, their invariance and gradients,
//! the corner measures on nets, and the composition's chain rule, each against finite
//! differences at random nets where the derivative is not zero.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use cost::corner::{corner_curvature, CornerMeasure, CornerOnNet};
use cost::net::{index, multi_indices, num_points};
use cost::{
    BuiltNets, Composed, NetConstruction, NetEnergy, NetEnergyError, NetObjective, SobolevEnergy,
};
use nalgebra::{Matrix3, Rotation3, SMatrix, SVector, Vector2, Vector3};
use solver::{check_jacobian_with, CheckOptions, LeastSquaresProblem};

/// Energies are sums of a few hundred products of O(1) numbers: rounding near 1e-13 relative.
const CLOSED_FORM: f64 = 1e-11;
/// Central differences with step 1e-6 on O(1)–O(100) quantities: truncation ~1e-10, rounding
/// ~1e-9 relative.
const FD: f64 = 1e-6;
const STEP: f64 = 1e-6;
/// Relative rounding of a sum of a few hundred terms: 100 ε.
const ROUNDING: f64 = 100.0 * f64::EPSILON;

use crate::common;
use common::Rng;

/// A random domain triangle of area above 0.3.
fn triangle(rng: &mut Rng) -> [Vector2<f64>; 3] {
    loop {
        let t = [
            Vector2::new(rng.next(), rng.next()) * 3.0,
            Vector2::new(rng.next(), rng.next()) * 3.0,
            Vector2::new(rng.next(), rng.next()) * 3.0,
        ];
        if area(t) > 0.3 {
            return t;
        }
    }
}

fn area(t: [Vector2<f64>; 3]) -> f64 {
    let (a, b) = (t[1] - t[0], t[2] - t[0]);
    0.5 * (a.x * b.y - a.y * b.x).abs()
}

/// The degree-`n` net of the polynomial map `x ↦ (xᵀQ₀x, xᵀQ₁x, xᵀQ₂x) + L x` (quadratic
/// forms `Q_c`, linear part `L`) over `t`, by blossoming: with `i`, `j`, `k` copies of the
/// corners, `f[x₁…x_n] = Σ_{a<b} x_aᵀQx_b / C(n,2) + Σ_a L x_a / n`.
fn polynomial_net(
    n: usize,
    t: [Vector2<f64>; 3],
    q: [Matrix3<f64>; 3],
    l: SMatrix<f64, 3, 2>,
) -> Vec<Vector3<f64>> {
    multi_indices(n)
        .into_iter()
        .map(|(i, j, k)| {
            let args: Vec<Vector2<f64>> = std::iter::repeat_n(t[0], i)
                .chain(std::iter::repeat_n(t[1], j))
                .chain(std::iter::repeat_n(t[2], k))
                .collect();
            let mut v = Vector3::zeros();
            let pairs = (n * (n - 1) / 2) as f64;
            for a in 0..n {
                v += l * args[a] / n as f64;
                for b in a + 1..n {
                    for c in 0..3 {
                        let qa = q[c].fixed_view::<2, 2>(0, 0);
                        v[c] += (args[a].transpose() * qa * args[b])[0] / pairs;
                    }
                }
            }
            v
        })
        .collect()
}

/// `∫_T x^a y^b dA` for a + b ≤ 2 by the degree-2 exact rule at the edge midpoints.
fn integrate(t: [Vector2<f64>; 3], f: impl Fn(Vector2<f64>) -> f64) -> f64 {
    let mids = [
        (t[0] + t[1]) / 2.0,
        (t[1] + t[2]) / 2.0,
        (t[2] + t[0]) / 2.0,
    ];
    area(t) * mids.iter().map(|m| f(*m)).sum::<f64>() / 3.0
}

#[test]
fn membrane_of_the_identity_is_twice_the_area() {
    let mut rng = Rng::new(7);
    for n in 1..=6 {
        let t = triangle(&mut rng);
        let e = NetEnergy::<200>::new(SobolevEnergy::Membrane, n, &[t]).unwrap();
        let net: Vec<Vector3<f64>> = multi_indices(n)
            .into_iter()
            .map(|(i, j, k)| {
                let p = (t[0] * i as f64 + t[1] * j as f64 + t[2] * k as f64) / n as f64;
                Vector3::new(p.x, p.y, 0.0)
            })
            .collect();
        let want = 2.0 * area(t);
        assert!((e.value(&net) - want).abs() < CLOSED_FORM * want, "n = {n}");
    }
}

/// Both energies of quadratic maps at degrees 2–6 (the net is the degree-elevated quadratic)
/// against their closed forms: thin plate `A(|2Q_xx|² + 2|2Q_xy|² + |2Q_yy|²)` is constant,
/// the membrane's integrand is quadratic and integrated exactly by the midpoint rule.
#[test]
fn energies_of_quadratic_maps_match_closed_forms() {
    let mut rng = Rng::new(11);
    for n in 2..=6 {
        for _ in 0..5 {
            let t = triangle(&mut rng);
            let q: [Matrix3<f64>; 3] = std::array::from_fn(|_| {
                let m = Matrix3::from_fn(|_, _| rng.next());
                m + m.transpose()
            });
            let l = SMatrix::<f64, 3, 2>::from_fn(|_, _| rng.next());
            let net = polynomial_net(n, t, q, l);
            // r_xx = 2 Q_c[0,0], r_xy = 2 Q_c[0,1], r_yy = 2 Q_c[1,1] per coordinate c.
            let tp: f64 = (0..3)
                .map(|c| {
                    let (xx, xy, yy) = (2.0 * q[c][(0, 0)], 2.0 * q[c][(0, 1)], 2.0 * q[c][(1, 1)]);
                    xx * xx + 2.0 * xy * xy + yy * yy
                })
                .sum::<f64>()
                * area(t);
            let e = NetEnergy::<200>::new(SobolevEnergy::ThinPlate, n, &[t]).unwrap();
            assert!(
                (e.value(&net) - tp).abs() < CLOSED_FORM * tp.max(1.0),
                "thin plate n = {n}"
            );
            let grad = |x: Vector2<f64>| -> [Vector3<f64>; 2] {
                std::array::from_fn(|d| {
                    Vector3::from_fn(|c, _| {
                        let qa = q[c].fixed_view::<2, 2>(0, 0);
                        2.0 * (qa * x)[d] + l[(c, d)]
                    })
                })
            };
            let mem = integrate(t, |x| {
                let g = grad(x);
                g[0].norm_squared() + g[1].norm_squared()
            });
            let e = NetEnergy::<200>::new(SobolevEnergy::Membrane, n, &[t]).unwrap();
            assert!(
                (e.value(&net) - mem).abs() < CLOSED_FORM * mem.max(1.0),
                "membrane n = {n}"
            );
        }
    }
}

#[test]
fn energies_are_invariant_under_rigid_motions_and_linear_in_scale_squared() {
    let mut rng = Rng::new(13);
    for kind in [SobolevEnergy::Membrane, SobolevEnergy::ThinPlate] {
        let domains = [triangle(&mut rng), triangle(&mut rng)];
        let e = NetEnergy::<200>::new(kind, 4, &domains).unwrap();
        let net: Vec<Vector3<f64>> = (0..2 * num_points(4)).map(|_| rng.vec()).collect();
        let rot = Rotation3::from_axis_angle(&Vector3::y_axis(), 0.7)
            * Rotation3::from_axis_angle(&Vector3::x_axis(), -1.3);
        let shift = rng.vec() * 10.0;
        let moved: Vec<Vector3<f64>> = net.iter().map(|p| rot * p + shift).collect();
        let scaled: Vec<Vector3<f64>> = net.iter().map(|p| p * 3.0).collect();
        let v = e.value(&net);
        assert!((e.value(&moved) - v).abs() < CLOSED_FORM * v, "{kind:?}");
        assert!(
            (e.value(&scaled) - 9.0 * v).abs() < CLOSED_FORM * 9.0 * v,
            "{kind:?}"
        );
    }
}

/// Central differences of `f` at every coordinate of every point against `grad`.
fn check_gradient(f: &dyn Fn(&[Vector3<f64>]) -> f64, net: &[Vector3<f64>], grad: &[Vector3<f64>]) {
    assert!(
        grad.iter().any(|g| g.norm() > 1e-3),
        "a vanishing gradient tests nothing"
    );
    // Rounding of f itself, amplified by the division by the step.
    let noise = ROUNDING * f(net).abs() / STEP;
    for (p, g) in grad.iter().enumerate() {
        for c in 0..3 {
            let (mut a, mut b) = (net.to_vec(), net.to_vec());
            a[p][c] += STEP;
            b[p][c] -= STEP;
            let fd = (f(&a) - f(&b)) / (2.0 * STEP);
            let scale = g[c].abs().max(1.0);
            assert!(
                (fd - g[c]).abs() < FD * scale + noise,
                "point {p} coord {c}: {fd} vs {}",
                g[c]
            );
        }
    }
}

#[test]
fn energy_gradients_match_finite_differences_at_random_nets() {
    let mut rng = Rng::new(17);
    for kind in [SobolevEnergy::Membrane, SobolevEnergy::ThinPlate] {
        for n in 2..=5 {
            let domains = [triangle(&mut rng), triangle(&mut rng), triangle(&mut rng)];
            let e = NetEnergy::<300>::new(kind, n, &domains).unwrap();
            assert_eq!(e.residuals_used(), 3 * kind.residuals_per_net(n));
            let net: Vec<Vector3<f64>> = (0..3 * num_points(n)).map(|_| rng.vec()).collect();
            check_gradient(&|p| e.value(p), &net, &e.gradient(&net));
        }
    }
}

#[test]
fn energy_setup_errors_are_typed() {
    let flat = [
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::new(2.0, 0.0),
    ];
    let good = [
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::new(0.0, 1.0),
    ];
    assert_eq!(
        NetEnergy::<200>::new(SobolevEnergy::ThinPlate, 4, &[good, flat]).unwrap_err(),
        NetEnergyError::DegenerateDomain(1)
    );
    assert_eq!(
        NetEnergy::<50>::new(SobolevEnergy::Membrane, 4, &[good]).unwrap_err(),
        NetEnergyError::TooManyResiduals {
            needed: 60,
            capacity: 50
        }
    );
}

fn random_shape(rng: &mut Rng, n: &Vector3<f64>) -> Matrix3<f64> {
    let p = Matrix3::identity() - n * n.transpose();
    let m = Matrix3::from_fn(|_, _| rng.next());
    p * (m + m.transpose()) * p
}

#[test]
fn corner_measures_on_nets_agree_with_the_vector_form_and_finite_differences() {
    let mut rng = Rng::new(19);
    for degree in [2usize, 3, 4, 5] {
        for corner in 0..3 {
            let (d, e) = ((corner + 1) % 3, (corner + 2) % 3);
            // A net near a flat triangle, so the first derivatives stay away from zero.
            let net: Vec<Vector3<f64>> = multi_indices(degree)
                .into_iter()
                .map(|(i, j, k)| {
                    Vector3::new(j as f64, k as f64, 0.0) / degree as f64 * 2.0
                        + Vector3::new(0.0, 0.0, i as f64 * 0.1)
                        + rng.vec() * 0.1
                })
                .collect();
            let normal = Vector3::new(rng.next(), rng.next(), 3.0).normalize();
            let shape = random_shape(&mut rng, &normal);
            for measure in [
                CornerMeasure::Curvature { toward: d },
                CornerMeasure::Twist { u: d, v: e },
            ] {
                let obj = CornerOnNet::new(degree, 0, corner, measure, normal, shape).unwrap();
                let value = |p: &[Vector3<f64>]| NetObjective::<1>::residuals(&obj, p)[0];
                check_gradient(
                    &value,
                    &net,
                    &obj.gradient(&net)
                        .iter()
                        .map(|g| g / (2.0 * value(&net)))
                        .collect::<Vec<_>>(),
                );
                if let CornerMeasure::Curvature { toward } = measure {
                    // The vector form on the hand-computed derivatives.
                    let at = |s: usize| {
                        let mut m = [0usize; 3];
                        m[corner] = degree - s;
                        m[toward] = s;
                        net[index(degree, m[0], m[1], m[2])]
                    };
                    let nf = degree as f64;
                    let a = (at(1) - at(0)) * nf;
                    let b = (at(2) - at(1) * 2.0 + at(0)) * nf * (nf - 1.0);
                    let k = corner_curvature(&normal, &shape, &a, &b).0;
                    assert!((value(&net) - k).abs() < CLOSED_FORM * k.abs().max(1.0));
                }
            }
        }
    }
    assert!(CornerOnNet::new(
        1,
        0,
        0,
        CornerMeasure::Curvature { toward: 1 },
        Vector3::z(),
        Matrix3::zeros()
    )
    .is_none());
    assert!(CornerOnNet::new(
        3,
        0,
        0,
        CornerMeasure::Twist { u: 1, v: 1 },
        Vector3::z(),
        Matrix3::zeros()
    )
    .is_none());
}

/// A nonlinear construction: `P_p(x) = P⁰_p + Σ_k x_k L_{pk} + (xᵀx) Q_p`.
struct Random<const N: usize> {
    base: Vec<Vector3<f64>>,
    linear: Vec<SMatrix<f64, 3, N>>,
    quad: Vec<Vector3<f64>>,
}

impl<const N: usize> NetConstruction<N> for Random<N> {
    fn build(&self, x: &SVector<f64, N>) -> Option<BuiltNets<N>> {
        let points = (0..self.base.len())
            .map(|p| self.base[p] + self.linear[p] * x + self.quad[p] * x.norm_squared())
            .collect();
        let jacobian = (0..self.base.len())
            .map(|p| self.linear[p] + self.quad[p] * (x.transpose() * 2.0))
            .collect();
        Some(BuiltNets { points, jacobian })
    }
}

#[test]
fn composition_applies_the_chain_rule() {
    let mut rng = Rng::new(23);
    let n = 4;
    let points = 3 * num_points(n);
    let construction = Random::<6> {
        base: (0..points).map(|_| rng.vec()).collect(),
        linear: (0..points)
            .map(|_| SMatrix::<f64, 3, 6>::from_fn(|_, _| rng.next()))
            .collect(),
        quad: (0..points).map(|_| rng.vec() * 0.3).collect(),
    };
    let domains = [triangle(&mut rng), triangle(&mut rng), triangle(&mut rng)];
    let energy = NetEnergy::<162>::new(SobolevEnergy::ThinPlate, n, &domains).unwrap();
    let problem = Composed::new(energy, construction);
    let x = SVector::<f64, 6>::from_fn(|_, _| rng.next());
    let check = check_jacobian_with(
        |x| problem.residuals(x),
        |x| problem.jacobian(x),
        &x,
        &problem.lower_bounds(),
        &CheckOptions { floor: 1e-3 },
    );
    assert!(check.max_error() < FD, "{check}");
    assert!(
        problem.jacobian(&x).amax() > 1.0,
        "a vanishing Jacobian tests nothing"
    );
}

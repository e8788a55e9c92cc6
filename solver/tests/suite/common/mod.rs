//! Test problems with known optima.
#![allow(dead_code)]

use nalgebra::{SMatrix, SVector, Vector2};
use solver::LeastSquaresProblem;

/// Rosenbrock as least squares, `r = (10(x₂ − x₁²), 1 − x₁)`, with an optional lower bound on
/// `x₂`: unbounded it is the classic problem, with `x₂ ≥ −1.5` Hock–Schittkowski problem 1 (bound
/// inactive at the optimum (1, 1)), with `x₂ ≥ 1.5` HS problem 2 (bound active).
pub struct Rosenbrock {
    pub lower_x2: f64,
}

impl LeastSquaresProblem<2, 2> for Rosenbrock {
    fn residuals(&self, x: &SVector<f64, 2>) -> SVector<f64, 2> {
        Vector2::new(10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0])
    }
    fn jacobian(&self, x: &SVector<f64, 2>) -> SMatrix<f64, 2, 2> {
        SMatrix::<f64, 2, 2>::new(-20.0 * x[0], 10.0, -1.0, 0.0)
    }
    fn lower_bounds(&self) -> SVector<f64, 2> {
        Vector2::new(f64::NEG_INFINITY, self.lower_x2)
    }
}

/// HS 2's optimum: `x₂ = 1.5` on the bound and `x₁` the root near 1.22 of the stationarity
/// condition `∂/∂x₁ [100(1.5 − x₁²)² + (1 − x₁)²] = 0`, i.e. `400x₁³ − 598x₁ − 2 = 0`, found by
/// Newton's method.
pub fn hs2_optimum() -> Vector2<f64> {
    let mut t: f64 = 1.2;
    for _ in 0..50 {
        t -= (400.0 * t * t * t - 598.0 * t - 2.0) / (1200.0 * t * t - 598.0);
    }
    Vector2::new(t, 1.5)
}

/// NIST StRD Misra1a: `y = b₁(1 − exp(−b₂ x))`, 14 observations (lower difficulty).
pub struct Misra1a;

pub const MISRA1A_X: [f64; 14] = [
    77.6, 114.9, 141.1, 190.8, 239.9, 289.0, 332.8, 378.4, 434.8, 477.3, 536.8, 593.1, 689.1, 760.0,
];
pub const MISRA1A_Y: [f64; 14] = [
    10.07, 14.73, 17.94, 23.93, 29.61, 35.18, 40.02, 44.82, 50.76, 55.05, 61.01, 66.40, 75.47,
    81.78,
];
/// Certified values (NIST StRD): b₁, b₂ and the residual sum of squares.
pub const MISRA1A_B: [f64; 2] = [2.3894212918E+02, 5.5015643181E-04];
pub const MISRA1A_RSS: f64 = 1.2455138894E-01;

impl LeastSquaresProblem<2, 14> for Misra1a {
    fn residuals(&self, b: &SVector<f64, 2>) -> SVector<f64, 14> {
        SVector::from_fn(|i, _| b[0] * (1.0 - (-b[1] * MISRA1A_X[i]).exp()) - MISRA1A_Y[i])
    }
    fn jacobian(&self, b: &SVector<f64, 2>) -> SMatrix<f64, 14, 2> {
        SMatrix::from_fn(|i, k| {
            let e = (-b[1] * MISRA1A_X[i]).exp();
            if k == 0 {
                1.0 - e
            } else {
                b[0] * MISRA1A_X[i] * e
            }
        })
    }
}

/// The representative client problem: end-derivative lengths `α ≥ 0.05` of a planar cubic, with
/// residuals `(α₀ − 1, α₁ − 1, κ₀(α) − k₀, κ₁(α) − k₁)`,
/// `κ₀ = 2(3d₀ − α₁c)/α₀²`, `κ₁ = 2(−3d₁ − α₀c)/α₁²`.
pub struct EndCurvature {
    pub c: f64,
    pub d0: f64,
    pub d1: f64,
    pub k0: f64,
    pub k1: f64,
    pub alpha_min: f64,
}

impl EndCurvature {
    /// `t₀ = (cos 0.3, sin 0.3)`, `t₁ = (cos 0.2, −sin 0.2)`, `c = t₀×t₁`, `d₀ = −t₀.y`,
    /// `d₁ = −t₁.y`, targets `k = (−0.5, −0.3)`.
    pub fn representative() -> Self {
        let t0 = (0.3f64.cos(), 0.3f64.sin());
        let t1 = (0.2f64.cos(), -(0.2f64.sin()));
        Self {
            c: t0.0 * t1.1 - t0.1 * t1.0,
            d0: -t0.1,
            d1: -t1.1,
            k0: -0.5,
            k1: -0.3,
            alpha_min: 0.05,
        }
    }
}

impl LeastSquaresProblem<2, 4> for EndCurvature {
    fn residuals(&self, a: &SVector<f64, 2>) -> SVector<f64, 4> {
        let k0 = 2.0 * (3.0 * self.d0 - a[1] * self.c) / (a[0] * a[0]);
        let k1 = 2.0 * (-3.0 * self.d1 - a[0] * self.c) / (a[1] * a[1]);
        SVector::<f64, 4>::new(a[0] - 1.0, a[1] - 1.0, k0 - self.k0, k1 - self.k1)
    }
    fn jacobian(&self, a: &SVector<f64, 2>) -> SMatrix<f64, 4, 2> {
        let (a0, a1) = (a[0], a[1]);
        let n0 = 2.0 * (3.0 * self.d0 - a1 * self.c);
        let n1 = 2.0 * (-3.0 * self.d1 - a0 * self.c);
        SMatrix::<f64, 4, 2>::new(
            1.0,
            0.0,
            0.0,
            1.0,
            -2.0 * n0 / (a0 * a0 * a0),
            -2.0 * self.c / (a0 * a0),
            -2.0 * self.c / (a1 * a1),
            -2.0 * n1 / (a1 * a1 * a1),
        )
    }
    fn lower_bounds(&self) -> SVector<f64, 2> {
        SVector::from_element(self.alpha_min)
    }

    /// `S = r₂ ∇²κ₀ + r₃ ∇²κ₁`: `∂²κ₀/∂α₀² = 12A₀/α₀⁴`, `∂²κ₀/∂α₀∂α₁ = 4c/α₀³`,
    /// `∂²κ₁/∂α₁² = 12A₁/α₁⁴`, `∂²κ₁/∂α₀∂α₁ = 4c/α₁³` (`A₀ = 3d₀ − α₁c`, `A₁ = −3d₁ − α₀c`).
    fn second_order_term(
        &self,
        a: &SVector<f64, 2>,
        r: &SVector<f64, 4>,
    ) -> Option<SMatrix<f64, 2, 2>> {
        let (i0, i1) = (1.0 / a[0], 1.0 / a[1]);
        let (q0, q1) = (i0 * i0 * i0, i1 * i1 * i1);
        let n0 = 3.0 * self.d0 - a[1] * self.c;
        let n1 = -3.0 * self.d1 - a[0] * self.c;
        let cross = 4.0 * self.c * (r[2] * q0 + r[3] * q1);
        Some(SMatrix::<f64, 2, 2>::new(
            12.0 * r[2] * n0 * q0 * i0,
            cross,
            cross,
            12.0 * r[3] * n1 * q1 * i1,
        ))
    }
}

/// A linear least-squares problem `r = A x − b` with lower bounds.
pub struct Linear<const M: usize> {
    pub a: SMatrix<f64, M, 2>,
    pub b: SVector<f64, M>,
    pub lower: Vector2<f64>,
}

impl<const M: usize> LeastSquaresProblem<2, M> for Linear<M> {
    fn residuals(&self, x: &SVector<f64, 2>) -> SVector<f64, M> {
        self.a * x - self.b
    }
    fn jacobian(&self, _x: &SVector<f64, 2>) -> SMatrix<f64, M, 2> {
        self.a
    }
    fn lower_bounds(&self) -> SVector<f64, 2> {
        self.lower
    }
}

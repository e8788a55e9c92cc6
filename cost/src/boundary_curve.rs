//! Mann's boundary-curve objective (Mann 1994, techreport §3 eqs 8–10, conference eqs 7–9).
//!
//! On the unit chord from `P0 = (0, 0)` to `P3 = (1, 0)` with unit end tangents `t0, t1` the
//! cubic has `f'(0) = α0 t0`, `f'(1) = α1 t1`. The objective trades tangent length against end
//! curvature:
//!
//! ```text
//! F(α) = w_t [(α0 − 1)² + (α1 − 1)²] + w_k [(κ(0) − k0)² + (κ(1) − k1)²]
//! ```
//!
//! Eq 8 is the pair of tangent terms, eqs 9 and 10 the curvature terms (their expansions
//! `κ² − 2kκ + k²` are `(κ − k)²`). The sum is kept unhalved so its gradient compares term by term
//! with eqs 11–14.
//!
//! # End curvatures and their derivatives
//!
//! With `c = t0 × t1`, `d0 = t0 × D`, `d1 = t1 × D`, `D = P3 − P0` (2D cross products),
//! `A0 = 3 d0 − α1 c` and `A1 = −3 d1 − α0 c` (the techreport's `3 t0 × (P3 − P0) − α1 t0 × t1`
//! and `3 t1 × (P0 − P3) − α0 t0 × t1`):
//!
//! ```text
//! κ0 = 2 A0 / α0²      ∂κ0/∂α0 = −4 A0 / α0³     ∂κ0/∂α1 = −2c / α0²
//! κ1 = 2 A1 / α1²      ∂κ1/∂α0 = −2c / α1²       ∂κ1/∂α1 = −4 A1 / α1³
//! ```
//!
//! (`f'(0) × f''(0) = 2 α0 A0` and `f'(1) × f''(1) = 2 α1 A1`, divided by `α³`; see
//! `curves::UnitProblem::end_curvatures` for the derivation.) The residuals are
//! `r = [√w_t (α0 − 1), √w_t (α1 − 1), √w_k (κ0 − k0), √w_k (κ1 − k1)]`, so `F = ‖r‖²` and
//! `∇F = 2 Jᵀ r`.
//!
//! # Eqs 11–14 as printed
//!
//! The partials of the curvature terms, `∂(κ0 − k0)²/∂α0 = 2(κ0 − k0) ∂κ0/∂α0
//! = −16 A0²/α0⁵ + 8 k0 A0/α0³` and so on, are exactly the techreport's summarized eqs 11–14;
//! [`printed_eqs_11_to_14`] evaluates them verbatim and a test holds them against finite
//! differences. Two typos of the seed's derivation do not reach the summary: `f''(1)` is written
//! with `α2` (read `α1`), and one line of the derivation of eq 14 has `(P0 − P1)` for
//! `(P0 − P3)`.

use nalgebra::{SMatrix, SVector, Vector2};
use solver::LeastSquaresProblem;

/// Weights of the tangent-length and curvature terms (default 1 and 1, as in the seeds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weights {
    /// `w_t`, weight of `(α − 1)²`.
    pub tangent: f64,
    /// `w_k`, weight of `(κ − k)²`.
    pub curvature: f64,
}

impl Default for Weights {
    fn default() -> Self {
        Weights {
            tangent: 1.0,
            curvature: 1.0,
        }
    }
}

/// The objective's data is unusable.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum CostError {
    /// A datum is NaN or infinite.
    #[error("non-finite {0}")]
    NonFinite(&'static str),
    /// A weight is negative (or both are zero).
    #[error("weights must be non-negative and not both zero (got w_t = {0}, w_k = {1})")]
    BadWeights(f64, f64),
    /// The lower bound on α must be positive: κ is undefined at α = 0.
    #[error("alpha_min must be positive and finite (got {0})")]
    BadAlphaMin(f64),
}

/// `F(α)` for one unit-chord problem, with bounds `α ≥ α_min`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryCurveObjective {
    c: f64,
    d0: f64,
    d1: f64,
    k0: f64,
    k1: f64,
    sqrt_wt: f64,
    sqrt_wk: f64,
    alpha_min: f64,
}

impl BoundaryCurveObjective {
    /// The objective for unit tangents `t0, t1`, target curvatures `k0, k1`, weights and the
    /// lower bound `alpha_min > 0` on both lengths.
    pub fn new(
        t0: Vector2<f64>,
        t1: Vector2<f64>,
        k: [f64; 2],
        weights: Weights,
        alpha_min: f64,
    ) -> Result<Self, CostError> {
        if !t0.iter().all(|x| x.is_finite()) {
            return Err(CostError::NonFinite("t0"));
        }
        if !t1.iter().all(|x| x.is_finite()) {
            return Err(CostError::NonFinite("t1"));
        }
        if !k.iter().all(|x| x.is_finite()) {
            return Err(CostError::NonFinite("target curvature"));
        }
        let Weights { tangent, curvature } = weights;
        let total = tangent + curvature;
        if !(tangent >= 0.0 && curvature >= 0.0 && total > 0.0 && total.is_finite()) {
            return Err(CostError::BadWeights(tangent, curvature));
        }
        if !(alpha_min > 0.0 && alpha_min.is_finite()) {
            return Err(CostError::BadAlphaMin(alpha_min));
        }
        Ok(BoundaryCurveObjective {
            c: t0.x * t1.y - t0.y * t1.x,
            d0: -t0.y,
            d1: -t1.y,
            k0: k[0],
            k1: k[1],
            sqrt_wt: tangent.sqrt(),
            sqrt_wk: curvature.sqrt(),
            alpha_min,
        })
    }

    /// End curvatures `[κ(0), κ(1)]` of the cubic with lengths `alpha` ([`end_curvatures`]).
    pub fn end_curvatures(&self, alpha: &SVector<f64, 2>) -> [f64; 2] {
        end_curvatures(self.d0, self.d1, self.c, [alpha[0], alpha[1]])
    }

    /// The lower bound on both lengths.
    pub fn alpha_min(&self) -> f64 {
        self.alpha_min
    }
}

impl LeastSquaresProblem<2, 4> for BoundaryCurveObjective {
    fn residuals(&self, x: &SVector<f64, 2>) -> SVector<f64, 4> {
        let [k0, k1] = self.end_curvatures(x);
        SVector::<f64, 4>::new(
            self.sqrt_wt * (x[0] - 1.0),
            self.sqrt_wt * (x[1] - 1.0),
            self.sqrt_wk * (k0 - self.k0),
            self.sqrt_wk * (k1 - self.k1),
        )
    }

    fn jacobian(&self, x: &SVector<f64, 2>) -> SMatrix<f64, 4, 2> {
        let (a0, a1) = (x[0], x[1]);
        let a0_term = 3.0 * self.d0 - a1 * self.c;
        let a1_term = -3.0 * self.d1 - a0 * self.c;
        let (wt, wk) = (self.sqrt_wt, self.sqrt_wk);
        SMatrix::<f64, 4, 2>::new(
            wt,
            0.0,
            0.0,
            wt,
            wk * (-4.0 * a0_term / (a0 * a0 * a0)),
            wk * (-2.0 * self.c / (a0 * a0)),
            wk * (-2.0 * self.c / (a1 * a1)),
            wk * (-4.0 * a1_term / (a1 * a1 * a1)),
        )
    }

    fn lower_bounds(&self) -> SVector<f64, 2> {
        SVector::<f64, 2>::from_element(self.alpha_min)
    }

    /// `S = r₂ ∇²r₂ + r₃ ∇²r₃` (the tangent residuals are linear), from
    /// `∂²κ0/∂α0² = 12 A0/α0⁴`, `∂²κ0/∂α0∂α1 = 4c/α0³`, `∂²κ0/∂α1² = 0` and
    /// `∂²κ1/∂α1² = 12 A1/α1⁴`, `∂²κ1/∂α0∂α1 = 4c/α1³`, `∂²κ1/∂α0² = 0`, each times `√w_k`.
    fn second_order_term(
        &self,
        x: &SVector<f64, 2>,
        r: &SVector<f64, 4>,
    ) -> Option<SMatrix<f64, 2, 2>> {
        let (a0, a1) = (x[0], x[1]);
        let (i0, i1) = (1.0 / a0, 1.0 / a1);
        let (c0, c1) = (i0 * i0 * i0, i1 * i1 * i1);
        let a0_term = 3.0 * self.d0 - a1 * self.c;
        let a1_term = -3.0 * self.d1 - a0 * self.c;
        let (w2, w3) = (self.sqrt_wk * r[2], self.sqrt_wk * r[3]);
        let cross = 4.0 * self.c * (w2 * c0 + w3 * c1);
        Some(SMatrix::<f64, 2, 2>::new(
            12.0 * w2 * a0_term * c0 * i0,
            cross,
            cross,
            12.0 * w3 * a1_term * c1 * i1,
        ))
    }
}

/// The techreport's eqs 11–14 evaluated exactly as printed, for unit tangents `t0, t1`, targets
/// `k0, k1` and lengths `α0, α1` on the unit chord (`P3 − P0 = (1, 0)`):
/// `[∂(9)/∂α0, ∂(9)/∂α1, ∂(10)/∂α0, ∂(10)/∂α1]`, where (9) and (10) are the curvature terms
/// `(κ(0) − k0)²` and `(κ(1) − k1)²`.
pub fn printed_eqs_11_to_14(
    t0: Vector2<f64>,
    t1: Vector2<f64>,
    k0: f64,
    k1: f64,
    alpha: [f64; 2],
) -> [f64; 4] {
    let cross = |a: Vector2<f64>, b: Vector2<f64>| a.x * b.y - a.y * b.x;
    let d = Vector2::new(1.0, 0.0); // P3 − P0
    let (a0, a1) = (alpha[0], alpha[1]);
    let t01 = cross(t0, t1);
    // [3 t0 × (P3 − P0) − α1 t0 × t1]
    let b0 = 3.0 * cross(t0, d) - a1 * t01;
    // [3 t1 × (P0 − P3) − α0 t0 × t1]
    let b1 = 3.0 * cross(t1, -d) - a0 * t01;
    [
        -16.0 * b0 * b0 / a0.powi(5) + 8.0 * k0 * b0 / a0.powi(3), // eq 11
        -8.0 * b0 * t01 / a0.powi(4) + 4.0 * k0 * t01 / a0.powi(2), // eq 12
        -8.0 * b1 * t01 / a1.powi(4) + 4.0 * k1 * t01 / a1.powi(2), // eq 13
        -16.0 * b1 * b1 / a1.powi(5) + 8.0 * k1 * b1 / a1.powi(3), // eq 14
    ]
}

/// End curvatures `[κ(0), κ(1)]` of the unit-chord cubic `P0 = (0, 0)`, `P1 = α0 t0 / 3`,
/// `P2 = (1, 0) − α1 t1 / 3`, `P3 = (1, 0)`, given `d0 = t0 × D`, `d1 = t1 × D` (`D = (1, 0)`)
/// and `c = t0 × t1` — the one copy of the formula (curves' `UnitProblem::end_curvatures`
/// calls it).
///
/// Derivation (techreport §3, with its `α2` typo in `f''(1)` read as `α1`):
/// `f''(0) = 6D − 2α1 t1 − 4α0 t0`, so `f'(0) × f''(0) = 2α0(3 t0×D − α1 t0×t1)`, divided by
/// `|f'(0)|³ = α0³`; likewise `f'(1) × f''(1) = 2α1(3 t1×(−D) + α0 t1×t0)`, divided by `α1³`.
pub fn end_curvatures(d0: f64, d1: f64, c: f64, alpha: [f64; 2]) -> [f64; 2] {
    let [a0, a1] = alpha;
    [
        2.0 * (3.0 * d0 - a1 * c) / (a0 * a0),
        2.0 * (-3.0 * d1 - a0 * c) / (a1 * a1),
    ]
}

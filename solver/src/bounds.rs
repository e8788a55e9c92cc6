//! Simple lower bounds: validation, projection, the projected gradient, and the change of
//! variables `x = l + y²` used by the adapters whose backends have no bounds.
//!
//! # Why `x = l + y²`
//!
//! L-BFGS (argmin) and Levenberg–Marquardt (`levenberg-marquardt`) have no bounds, so those
//! adapters solve over `y ∈ ℝᴺ` with `xᵢ = lᵢ + yᵢ²` for bounded unknowns and `xᵢ = yᵢ` for free
//! ones. Compared with `x = l + exp(y)`:
//!
//! - the bound itself is reachable (`y = 0`), and near it the error in `x` is the *square* of the
//!   error in `y`, so an optimum on the bound is approached to `x − l ≈ (tolerance-limited y)²`;
//!   with `exp` the bound is only reached as `y → −∞`, where the gradient `exp(y)·g` vanishes and
//!   the solver stops wherever its tests first pass;
//! - the map is a polynomial, so it never overflows.
//!
//! The price: `∂x/∂y = 2y` vanishes at `y = 0`, so `y = 0` is a stationary point of the
//! transformed problem whatever the true gradient. A start on or very near a bound is therefore moved
//! inside by [`START_OFFSET`] (relative) before the change of variables, and the report always
//! states the projected gradient in the original unknowns, so a spurious stop at a bound whose
//! multiplier is negative is visible there. When the optimum is on the bound with a positive
//! multiplier `g`, the transformed cost behaves like `g·y²` near `y = 0`: a regular minimum, but
//! one the Gauss–Newton model sees only through its damping, so the change-of-variables adapters
//! reach the bound only to within a small distance (measured in the tests), never exactly. The
//! exact-penalty adapter lands on it exactly.

use nalgebra::SVector;

use crate::SolveError;

/// Relative distance by which a start on a bound is moved inside before `x = l + y²`.
pub const START_OFFSET: f64 = 1e-4;

/// Checks `x0` finite, `lower` finite or `-∞`, and `x0 ≥ lower`.
///
/// # Errors
/// The first violated condition, naming the coordinate.
pub fn validate_start<const N: usize>(
    x0: &SVector<f64, N>,
    lower: &SVector<f64, N>,
) -> Result<(), SolveError> {
    for i in 0..N {
        if !x0[i].is_finite() {
            return Err(SolveError::NonFiniteStart {
                index: i,
                value: x0[i],
            });
        }
        if lower[i].is_nan() || lower[i] == f64::INFINITY {
            return Err(SolveError::InvalidLowerBound {
                index: i,
                value: lower[i],
            });
        }
        if x0[i] < lower[i] {
            return Err(SolveError::StartBelowBound {
                index: i,
                value: x0[i],
                lower: lower[i],
            });
        }
    }
    Ok(())
}

/// The projection onto `{x ≥ l}`.
#[must_use]
pub fn project<const N: usize>(x: &SVector<f64, N>, lower: &SVector<f64, N>) -> SVector<f64, N> {
    x.zip_map(lower, |xi, li| xi.max(li))
}

/// Max-norm of the projected gradient `x − P(x − g)`: zero exactly at a KKT point of
/// `min f s.t. x ≥ l`.
#[must_use]
pub fn projected_gradient_norm<const N: usize>(
    x: &SVector<f64, N>,
    g: &SVector<f64, N>,
    lower: &SVector<f64, N>,
) -> f64 {
    let mut m: f64 = 0.0;
    for i in 0..N {
        let pg = x[i] - (x[i] - g[i]).max(lower[i]);
        if pg.is_nan() {
            return f64::NAN;
        }
        m = m.max(pg.abs());
    }
    m
}

/// The change of variables `xᵢ = lᵢ + yᵢ²` (bounded) / `xᵢ = yᵢ` (free).
#[derive(Debug, Clone, Copy)]
pub struct SquareMap<const N: usize> {
    lower: SVector<f64, N>,
}

impl<const N: usize> SquareMap<N> {
    /// The map for the bounds `lower` (entries `-∞` are free).
    #[must_use]
    pub fn new(lower: SVector<f64, N>) -> Self {
        Self { lower }
    }

    fn bounded(&self, i: usize) -> bool {
        self.lower[i].is_finite()
    }

    /// `x(y)`.
    #[must_use]
    pub fn to_x(&self, y: &SVector<f64, N>) -> SVector<f64, N> {
        SVector::from_fn(|i, _| {
            if self.bounded(i) {
                self.lower[i] + y[i] * y[i]
            } else {
                y[i]
            }
        })
    }

    /// A `y` with `x(y) = x`, taking `yᵢ ≥ 0`; a start on (or closer than the offset to) a bound is
    /// first moved inside to
    /// [`START_OFFSET`]`·max(|lᵢ|, 1)`.
    #[must_use]
    pub fn to_y(&self, x: &SVector<f64, N>) -> SVector<f64, N> {
        SVector::from_fn(|i, _| {
            if self.bounded(i) {
                let d = (x[i] - self.lower[i]).max(START_OFFSET * self.lower[i].abs().max(1.0));
                d.sqrt()
            } else {
                x[i]
            }
        })
    }

    /// The diagonal of `∂x/∂y`: `2yᵢ` (bounded) or 1 (free).
    #[must_use]
    pub fn dx_dy(&self, y: &SVector<f64, N>) -> SVector<f64, N> {
        SVector::from_fn(|i, _| if self.bounded(i) { 2.0 * y[i] } else { 1.0 })
    }
}

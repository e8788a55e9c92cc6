//! Finite-difference checks of analytic derivatives, in the manner of Ceres Solver's
//! `GradientChecker`.
//!
//! Each entry of an analytic gradient or Jacobian is compared with a finite difference and the
//! worst entry is reported with its position, both values and the error
//!
//! ```text
//! error = |analytic − numeric| / max(|analytic|, |numeric|, floor)
//! ```
//!
//! a relative error that becomes an absolute one (scaled by `1/floor`) where both derivatives are
//! smaller than `floor`, so that entries that should be zero are not judged by round-off noise.
//!
//! # Steps
//!
//! - **Central differences** `(f(x + hᵢeᵢ) − f(x − hᵢeᵢ)) / 2hᵢ` with `hᵢ = ε^{1/3}·max(|xᵢ|, 1)`
//!   (`ε` the machine epsilon, so `ε^{1/3} ≈ 6·10⁻⁶`). The truncation error of a central difference
//!   is `O(h²)` and its round-off error `O(ε/h)`; they balance at `h ∝ ε^{1/3}`, which gives about
//!   ten correct digits for well-scaled functions. The factor `max(|xᵢ|, 1)` makes the step relative
//!   for large unknowns and absolute near zero.
//! - **Near a lower bound** (`xᵢ − hᵢ < lᵢ`) the backward point would be infeasible, where the
//!   function may be undefined, so a **forward difference** `(f(x + hᵢeᵢ) − f(x)) / hᵢ` is used,
//!   with its own balanced step `hᵢ = √ε·max(|xᵢ|, 1)` (truncation `O(h)`, round-off `O(ε/h)`);
//!   expect about eight correct digits there. [`WorstEntry::one_sided`] says when this happened.
//!
//! Steps are rounded so that `xᵢ + hᵢ` is exactly representable (`h = (x + h) − x`).
//!
//! # Reference
//!
//! Nocedal & Wright, *Numerical Optimization*, 2nd ed., §8.1 (finite-difference derivative
//! approximations and the choice of step).

use nalgebra::{SMatrix, SVector};
use serde::{Deserialize, Serialize};

use crate::LeastSquaresProblem;

/// Settings of a derivative check.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CheckOptions {
    /// Absolute floor of the denominator of the relative error (default `1e-6`): entries whose
    /// analytic and numeric values are both below it are compared absolutely, scaled by `1/floor`.
    pub floor: f64,
}

impl Default for CheckOptions {
    fn default() -> Self {
        Self { floor: 1e-6 }
    }
}

/// The entry of a gradient or Jacobian check with the largest error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WorstEntry {
    /// Row: the residual index of a Jacobian entry, or the component of a gradient.
    pub row: usize,
    /// Column: the unknown of a Jacobian entry (always 0 for a gradient).
    pub column: usize,
    /// The analytic derivative.
    pub analytic: f64,
    /// The finite-difference derivative.
    pub numeric: f64,
    /// `|analytic − numeric| / max(|analytic|, |numeric|, floor)`; infinite if either is not
    /// finite.
    pub error: f64,
    /// Whether a one-sided (forward) difference was used because of a lower bound.
    pub one_sided: bool,
}

/// The outcome of a derivative check.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DerivativeCheck {
    /// The entry with the largest error (`None` only when there are no entries).
    pub worst: Option<WorstEntry>,
}

impl DerivativeCheck {
    /// The largest error over all entries (0 when there are no entries).
    #[must_use]
    pub fn max_error(&self) -> f64 {
        self.worst.map_or(0.0, |w| w.error)
    }

    /// Whether every entry's error is at most `tolerance` (NaN-safe: a NaN error fails).
    #[must_use]
    pub fn passes(&self, tolerance: f64) -> bool {
        self.max_error() <= tolerance
    }
}

impl std::fmt::Display for DerivativeCheck {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.worst {
            None => write!(f, "no entries to check"),
            Some(w) => write!(
                f,
                "worst entry ({}, {}): analytic {:.12e}, numeric {:.12e}, error {:.3e}{}",
                w.row,
                w.column,
                w.analytic,
                w.numeric,
                w.error,
                if w.one_sided {
                    " (forward difference at a bound)"
                } else {
                    ""
                }
            ),
        }
    }
}

/// Step for unknown `i` and whether it is one-sided; the step is exactly representable.
fn step(x: f64, lower: f64) -> (f64, bool) {
    let scale = x.abs().max(1.0);
    let central = f64::EPSILON.cbrt() * scale;
    if x - central >= lower {
        (((x + central) - x), false)
    } else {
        let forward = f64::EPSILON.sqrt() * scale;
        (((x + forward) - x), true)
    }
}

fn entry_error(analytic: f64, numeric: f64, floor: f64) -> f64 {
    if !analytic.is_finite() || !numeric.is_finite() {
        return f64::INFINITY;
    }
    (analytic - numeric).abs() / analytic.abs().max(numeric.abs()).max(floor)
}

fn keep_worst(worst: &mut Option<WorstEntry>, candidate: WorstEntry) {
    let replace = match worst {
        None => true,
        // Errors are never NaN (`entry_error` maps non-finite values to +∞).
        Some(w) => candidate.error > w.error,
    };
    if replace {
        *worst = Some(candidate);
    }
}

/// Checks an analytic gradient `grad` of `f` at `x` by finite differences, respecting lower bounds
/// `lower` (pass `f64::NEG_INFINITY` entries for free unknowns).
pub fn check_gradient_with<const N: usize>(
    f: impl Fn(&SVector<f64, N>) -> f64,
    grad: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
    x: &SVector<f64, N>,
    lower: &SVector<f64, N>,
    options: &CheckOptions,
) -> DerivativeCheck {
    let analytic = grad(x);
    let f0 = f(x);
    let mut worst = None;
    for i in 0..N {
        let (h, one_sided) = step(x[i], lower[i]);
        let mut xp = *x;
        xp[i] += h;
        let numeric = if one_sided {
            (f(&xp) - f0) / h
        } else {
            let mut xm = *x;
            xm[i] -= h;
            (f(&xp) - f(&xm)) / (2.0 * h)
        };
        keep_worst(
            &mut worst,
            WorstEntry {
                row: i,
                column: 0,
                analytic: analytic[i],
                numeric,
                error: entry_error(analytic[i], numeric, options.floor),
                one_sided,
            },
        );
    }
    DerivativeCheck { worst }
}

/// Checks an analytic gradient of `f` at `x` with central differences and default options.
pub fn check_gradient<const N: usize>(
    f: impl Fn(&SVector<f64, N>) -> f64,
    grad: impl Fn(&SVector<f64, N>) -> SVector<f64, N>,
    x: &SVector<f64, N>,
) -> DerivativeCheck {
    check_gradient_with(
        f,
        grad,
        x,
        &SVector::from_element(f64::NEG_INFINITY),
        &CheckOptions::default(),
    )
}

/// Checks an analytic Jacobian `jac` of the residuals `res` at `x` by finite differences,
/// respecting lower bounds `lower`.
pub fn check_jacobian_with<const N: usize, const M: usize>(
    res: impl Fn(&SVector<f64, N>) -> SVector<f64, M>,
    jac: impl Fn(&SVector<f64, N>) -> SMatrix<f64, M, N>,
    x: &SVector<f64, N>,
    lower: &SVector<f64, N>,
    options: &CheckOptions,
) -> DerivativeCheck {
    let analytic = jac(x);
    let r0 = res(x);
    let mut worst = None;
    for j in 0..N {
        let (h, one_sided) = step(x[j], lower[j]);
        let mut xp = *x;
        xp[j] += h;
        let column = if one_sided {
            (res(&xp) - r0) / h
        } else {
            let mut xm = *x;
            xm[j] -= h;
            (res(&xp) - res(&xm)) / (2.0 * h)
        };
        for i in 0..M {
            keep_worst(
                &mut worst,
                WorstEntry {
                    row: i,
                    column: j,
                    analytic: analytic[(i, j)],
                    numeric: column[i],
                    error: entry_error(analytic[(i, j)], column[i], options.floor),
                    one_sided,
                },
            );
        }
    }
    DerivativeCheck { worst }
}

/// Checks an analytic Jacobian of `res` at `x` with central differences and default options.
pub fn check_jacobian<const N: usize, const M: usize>(
    res: impl Fn(&SVector<f64, N>) -> SVector<f64, M>,
    jac: impl Fn(&SVector<f64, N>) -> SMatrix<f64, M, N>,
    x: &SVector<f64, N>,
) -> DerivativeCheck {
    check_jacobian_with(
        res,
        jac,
        x,
        &SVector::from_element(f64::NEG_INFINITY),
        &CheckOptions::default(),
    )
}

/// Checks a [`LeastSquaresProblem`]'s Jacobian at `x`, using one-sided differences next to its
/// lower bounds.
pub fn check_problem<P, const N: usize, const M: usize>(
    problem: &P,
    x: &SVector<f64, N>,
    options: &CheckOptions,
) -> DerivativeCheck
where
    P: LeastSquaresProblem<N, M>,
{
    check_jacobian_with(
        |x| problem.residuals(x),
        |x| problem.jacobian(x),
        x,
        &problem.lower_bounds(),
        options,
    )
}

/// Checks a [`LeastSquaresProblem`]'s second-order term at `x` (if it provides one): the
/// Hessian of the cost `JᵀJ + S` against finite differences of its gradient `Jᵀr`, one-sided
/// next to the lower bounds. `None` when [`LeastSquaresProblem::second_order_term`] is `None`.
pub fn check_second_order<P, const N: usize, const M: usize>(
    problem: &P,
    x: &SVector<f64, N>,
    options: &CheckOptions,
) -> Option<DerivativeCheck>
where
    P: LeastSquaresProblem<N, M>,
{
    problem.second_order_term(x, &problem.residuals(x))?;
    let hessian = |x: &SVector<f64, N>| {
        let j = problem.jacobian(x);
        let r = problem.residuals(x);
        let s = problem
            .second_order_term(x, &r)
            .unwrap_or_else(SMatrix::zeros);
        j.transpose() * j + s
    };
    Some(check_jacobian_with(
        |x| problem.jacobian(x).transpose() * problem.residuals(x),
        hessian,
        x,
        &problem.lower_bounds(),
        options,
    ))
}

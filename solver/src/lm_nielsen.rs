//! The fast path of the Levenberg–Marquardt adapter for two unknowns: a hand-written
//! Levenberg–Marquardt iteration with Marquardt's diagonal scaling and Nielsen's damping update,
//! its 2×2 damped normal equations solved in closed form.
//!
//! # Algorithm
//!
//! Madsen, Nielsen and Tingleff, *Methods for non-linear least squares problems*, 2nd ed., IMM
//! DTU 2004, Algorithm 3.16, with the damping update of H. B. Nielsen, "Damping parameter in
//! Marquardt's method", IMM-REP-1999-05, and Marquardt's scaling of the damping term (as MINPACK's
//! `lmder` with `scale_diag`). With `F = ½‖r‖²`, `g = Jᵀr`, `A = JᵀJ` at the current `y`:
//!
//! 1. `D = diag(dᵢ)`, `dᵢ` the largest `Aᵢᵢ` seen so far (1 for a zero column), so the damping
//!    is invariant under a scaling of the unknowns;
//! 2. the step solves `(A + μD) h = −g` (closed form, one division);
//! 3. the gain ratio `ϱ = (F(y) − F(y + h)) / (L(0) − L(h))` with the model decrease
//!    `L(0) − L(h) = ½ hᵀ(μDh − g)`; the step is taken when `ϱ > 0`, and then
//!    `μ ← μ·max(⅓, 1 − (2ϱ − 1)³)`, `ν ← 2` (Nielsen), else `μ ← μν`, `ν ← 2ν`;
//! 4. start `μ₀ = τ = 10⁻³` (relative to `D`, MNT04's recommendation for a start of unknown
//!    quality).
//!
//! # Termination
//!
//! The tests are MINPACK's, with the adapter's tolerances, and end with the same
//! [`TerminationReason`]s as the `levenberg-marquardt` crate (which the adapter maps to its
//! report exactly as for the crate):
//!
//! - `gtol` at every new Jacobian: `maxₖ |Jₖᵀr| / (‖Jₖ‖‖r‖) ≤ gtol` → `Orthogonal`;
//! - after every trial: `‖r‖` below the smallest normal number → `ResidualsZero`; the relative
//!   actual and predicted reductions `|F − F₊|/F` and `(L(0) − L(h))/F` both `≤ ftol` (and
//!   `ϱ ≤ 2`) on **two successive trials** → `Converged { ftol }`; the scaled step `‖D^½h‖ ≤ xtol·‖D^½y‖` → `Converged {
//!   xtol }`; the residual evaluations reaching `patience·(N + 1)` → `LostPatience`; the same
//!   tests at machine precision → `NoImprovementPossible`;
//! - a non-finite Jacobian → `Numerical("jacobian")`; a target refusing an evaluation (the
//!   adapter's iteration limit) → `User`.
//!
//! The function-tolerance test on two trials instead of MINPACK's one: Gauss–Newton converges
//! only linearly on a nonzero-residual problem (by a factor near 0.04 a step on the boundary
//! curves), so one small relative reduction can be passed by a step whose successor still moves
//! `x` by 1e-8; on the benchmark problem the single test stopped 2.6e-8 from the Newton optimum
//! (MINPACK, by the luck of its trust-region steps, 5e-9), the double test 5e-9, at one more
//! iteration.
//!
//! The iterates differ from MINPACK's (no trust region, no QR): the optima agree to the
//! adapter's tolerances, not bit for bit (`tests/suite/fast_paths.rs`, `curves/tests/suite/optimized.rs`).
//! Every comparison is multiplied out, so an iteration has two divisions (the solve and the gain
//! ratio) and no square root.

use levenberg_marquardt::TerminationReason;
use nalgebra::SVector;

use crate::lm_fixed::{Config, FixedTarget};

/// Initial damping relative to the diagonal scaling (MNT04 §3.2: 10⁻³ when the start is not
/// known to be close to the solution).
const TAU: f64 = 1e-3;
/// Nielsen's smallest factor by which a very good step (`ϱ → 1`) reduces the damping.
const MIN_DAMPING_FACTOR: f64 = 1.0 / 3.0;
/// Costs at or below this are zero residuals (MINPACK's `dwarf`, squared and halved: `½‖r‖²`
/// with `‖r‖ ≤ f64::MIN_POSITIVE` underflows to zero, so the cost test is `F = 0` in effect).
const ZERO_COST: f64 = 0.5 * f64::MIN_POSITIVE * f64::MIN_POSITIVE;

/// `F = ½‖r‖²`.
#[inline]
fn half_norm_squared<const M: usize>(r: &SVector<f64, M>) -> f64 {
    0.5 * r.norm_squared()
}

/// Runs the iteration on `target` from `y0` for `N = 2` unknowns and `M ≥ 2` residuals.
///
/// # Panics
/// In debug builds, unless `N == 2 && M >= 2` (the caller's check).
pub(crate) fn minimize<T, const N: usize, const M: usize>(
    config: &Config,
    target: &mut T,
    y0: SVector<f64, N>,
) -> TerminationReason
where
    T: FixedTarget<N, M>,
{
    debug_assert!(N == 2 && M >= N);
    let mut nfev = 1usize;
    let Some(mut r) = target.residuals() else {
        return TerminationReason::User("residuals");
    };
    let mut cost = half_norm_squared(&r);
    if !cost.is_finite() {
        return TerminationReason::Numerical("residuals norm");
    }
    if cost <= ZERO_COST {
        return TerminationReason::ResidualsZero;
    }
    let max_fev = config.patience * (N + 1);
    let (ftol, xtol, gtol) = (config.ftol, config.xtol, config.gtol);
    let mut y = [y0[0], y0[1]];
    let mut d = [0.0f64; 2];
    let mut mu = TAU;
    let mut nu = 2.0;
    // Whether the previous trial step passed the function-tolerance test.
    let mut ftol_before = false;

    loop {
        let Some(jac) = target.jacobian() else {
            return TerminationReason::User("jacobian");
        };
        if !jac.iter().all(|v| v.is_finite()) {
            return TerminationReason::Numerical("jacobian");
        }
        // A = JᵀJ and g = Jᵀr, summed over even and odd rows separately (half the dependent
        // additions).
        let mut sums = [[0.0f64; 5]; 2];
        for i in 0..M {
            let (j0, j1, ri) = (jac[(i, 0)], jac[(i, 1)], r[i]);
            let s = &mut sums[i % 2];
            s[0] += j0 * j0;
            s[1] += j0 * j1;
            s[2] += j1 * j1;
            s[3] += j0 * ri;
            s[4] += j1 * ri;
        }
        let [a00, a01, a11, g0, g1]: [f64; 5] = std::array::from_fn(|k| sums[0][k] + sums[1][k]);
        // MINPACK's gradient test, squared: (Jₖᵀr)² ≤ gtol²‖Jₖ‖²‖r‖² (‖r‖² = 2F).
        let gtol2 = gtol * gtol * (2.0 * cost);
        if g0 * g0 <= gtol2 * a00 && g1 * g1 <= gtol2 * a11 {
            return TerminationReason::Orthogonal;
        }
        for (dk, akk) in d.iter_mut().zip([a00, a11]) {
            *dk = dk.max(if akk == 0.0 { 1.0 } else { akk });
        }

        r = loop {
            // (A + μD) h = −g by Cramer's rule: μD > 0, so the matrix is positive definite.
            let (b00, b11) = (a00 + mu * d[0], a11 + mu * d[1]);
            let inv = 1.0 / (b00 * b11 - a01 * a01);
            let h = [(a01 * g1 - b11 * g0) * inv, (a01 * g0 - b00 * g1) * inv];
            // L(0) − L(h) = ½ hᵀ(μDh − g).
            let predicted = 0.5 * (h[0] * (mu * d[0] * h[0] - g0) + h[1] * (mu * d[1] * h[1] - g1));
            let step2 = d[0] * h[0] * h[0] + d[1] * h[1] * h[1];
            let y2 = d[0] * y[0] * y[0] + d[1] * y[1] * y[1];
            if !(predicted.is_finite() && step2.is_finite()) {
                return TerminationReason::Numerical("subproblem ||Dp||");
            }

            let trial = [y[0] + h[0], y[1] + h[1]];
            target.set_params(&SVector::from_fn(|i, _| trial[i]));
            nfev += 1;
            let Some(r_trial) = target.residuals() else {
                return TerminationReason::User("residuals");
            };
            let cost_trial = half_norm_squared(&r_trial);
            let actual = cost - cost_trial;
            let good = actual > 0.0 && predicted > 0.0;
            if good {
                // Nielsen: μ·max(⅓, 1 − (2ϱ − 1)³), ϱ = actual / predicted.
                let t = 2.0 * (actual / predicted) - 1.0;
                mu *= (1.0 - t * t * t).max(MIN_DAMPING_FACTOR);
                nu = 2.0;
                y = trial;
            } else {
                mu *= nu;
                nu *= 2.0;
            }
            let previous = cost;
            if good {
                cost = cost_trial;
            }
            let finish = |target: &mut T, reason| {
                if !good {
                    target.set_params(&SVector::from_fn(|i, _| y[i]));
                }
                reason
            };
            if cost <= ZERO_COST {
                return finish(target, TerminationReason::ResidualsZero);
            }
            // Relative reductions and ϱ ≤ 2, multiplied out by the old cost and `predicted`.
            let reductions_below =
                |tol: f64| actual.abs() <= tol * previous && predicted <= tol * previous;
            let ratio_ok = actual <= 2.0 * predicted;
            let ftol_now = reductions_below(ftol) && ratio_ok;
            let ftol_check = ftol_now && ftol_before;
            ftol_before = ftol_now;
            let xtol_check = step2 <= xtol * xtol * y2;
            if ftol_check || xtol_check {
                return finish(
                    target,
                    TerminationReason::Converged {
                        ftol: ftol_check,
                        xtol: xtol_check,
                    },
                );
            }
            if nfev >= max_fev {
                return finish(target, TerminationReason::LostPatience);
            }
            if reductions_below(f64::EPSILON) && ratio_ok {
                return finish(target, TerminationReason::NoImprovementPossible("ftol"));
            }
            if step2 <= f64::EPSILON * f64::EPSILON * y2 {
                return finish(target, TerminationReason::NoImprovementPossible("xtol"));
            }
            if good {
                break r_trial;
            }
        };
    }
}

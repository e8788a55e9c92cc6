//! The fixed-size fast path of the Levenberg–Marquardt adapter: the `levenberg-marquardt` 0.15
//! crate's MINPACK `lmder` port (`LevenbergMarquardt::minimize`, its pivoted QR, `lmpar` and
//! `qrsolv`), transcribed over fixed-size arrays for `M ≥ N` residuals.
//!
//! Every floating-point operation is the crate's, in the crate's order (its own dot product and
//! scaled norm `enorm`, nalgebra's `axpy` with `β = 1`, `Signed::is_negative` as the sign bit), so
//! the iterates, the evaluations and the termination are bit for bit those of
//! [`LevenbergMarquardt::minimize`](levenberg_marquardt::LevenbergMarquardt::minimize) on the
//! same target (`tests/suite/fast_paths.rs` holds them equal). What is gone is the generic machinery:
//! nalgebra views and dimension types, the `Option`-returning trait calls through the
//! `LeastSquaresProblem` of the crate, and copies of the factorisation's work vectors.
//!
//! The crate's configuration is the adapter's: `stepbound = 100`, `scale_diag = true`, the
//! tolerances and patience given; no `minpack-compat` feature.

use levenberg_marquardt::TerminationReason;
use nalgebra::{SMatrix, SVector};

/// What the transcription needs of a target: the crate's `LeastSquaresProblem` calls.
pub(crate) trait FixedTarget<const N: usize, const M: usize> {
    /// Moves the target to `y` (the crate's `set_params`).
    fn set_params(&mut self, y: &SVector<f64, N>);
    /// Residuals at the current parameters; `None` ends the run (`User("residuals")`).
    fn residuals(&self) -> Option<SVector<f64, M>>;
    /// Jacobian at the current parameters; `None` ends the run (`User("jacobian")`).
    fn jacobian(&self) -> Option<SMatrix<f64, M, N>>;
}

/// The crate's settings the adapter uses.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Config {
    pub ftol: f64,
    pub xtol: f64,
    pub gtol: f64,
    pub patience: usize,
}

/// The crate's default `stepbound`.
const STEPBOUND: f64 = 100.0;
const P1: f64 = 0.1;
const P0001: f64 = 1.0e-4;
const EPSMCH: f64 = f64::EPSILON;
const DWARF: f64 = f64::MIN_POSITIVE;

/// MINPACK's scaled Euclidean norm as the crate writes it (`utils::enorm`).
#[inline]
fn enorm(v: &[f64]) -> f64 {
    let mut s1 = 0.0f64;
    let mut s2 = 0.0f64;
    let mut s3 = 0.0f64;
    let mut x1max = 0.0f64;
    let mut x3max = 0.0f64;
    let agiant = f64::MAX.sqrt() / (v.len() as f64);
    let rdwarf = DWARF.sqrt();
    for xi in v {
        let xabs = xi.abs();
        if xabs.is_nan() {
            return xabs;
        }
        if xabs >= agiant || xabs <= rdwarf {
            if xabs > rdwarf {
                if xabs > x1max {
                    s1 = 1.0 + s1 * (x1max / xabs).powi(2);
                    x1max = xabs;
                } else {
                    s1 += (xabs / x1max).powi(2);
                }
            } else if xabs > x3max {
                s3 = 1.0 + s3 * (x3max / xabs).powi(2);
                x3max = xabs;
            } else if xabs != 0.0 {
                s3 += (xabs / x3max).powi(2);
            }
        } else {
            s2 += xabs * xabs;
        }
    }
    if s1 != 0.0 {
        x1max * (s1 + (s2 / x1max) / x1max).sqrt()
    } else if s2 != 0.0 {
        if x3max == 0.0 {
            // No tiny components: `s2 · (1 + (0/s2)·(0·s3))` is `s2` exactly; skipping the
            // division shortens every norm's dependency chain.
            return s2.sqrt();
        }
        (if s2 >= x3max {
            s2 * (1.0 + (x3max / s2) * (x3max * s3))
        } else {
            x3max * ((s2 / x3max) + (x3max * s3))
        })
        .sqrt()
    } else {
        x3max * s3.sqrt()
    }
}

/// The crate's dot product (`utils::dot`): left to right from zero.
#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut d = 0.0;
    for (x, y) in a.iter().zip(b) {
        d += *x * *y;
    }
    d
}

/// `y ← a x + y` (nalgebra's `axpy` with `β = 1`; `y + a x` is the same sum).
#[inline]
fn axpy(a: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * *xi;
    }
}

/// The factorisation and the linear least-squares problem of one outer iteration (the crate's
/// `PivotedQR` turned into `LinearLeastSquaresDiagonalProblem`). `r` holds `M × N` column-major:
/// `R` in the upper triangle, Householder vectors (then `L`) below.
struct Lls<const N: usize, const M: usize> {
    r: SMatrix<f64, M, N>,
    qt_b: [f64; N],
    l_diag: [f64; N],
    permutation: [usize; N],
    column_norms: [f64; N],
    work: [f64; N],
}

#[inline]
fn col<const N: usize, const M: usize>(r: &SMatrix<f64, M, N>, j: usize) -> &[f64] {
    &r.as_slice()[j * M..(j + 1) * M]
}

#[inline]
fn col_mut<const N: usize, const M: usize>(r: &mut SMatrix<f64, M, N>, j: usize) -> &mut [f64] {
    &mut r.as_mut_slice()[j * M..(j + 1) * M]
}

impl<const N: usize, const M: usize> Lls<N, M> {
    /// `PivotedQR::new(a).into_least_squares_diagonal_problem(b)`.
    fn new(mut a: SMatrix<f64, M, N>, mut b: SVector<f64, M>) -> Self {
        let mut column_norms = [0.0; N];
        for (j, c) in column_norms.iter_mut().enumerate() {
            *c = enorm(col(&a, j));
        }
        let mut r_diag = column_norms;
        let mut work = column_norms;
        let mut permutation = [0usize; N];
        for (j, p) in permutation.iter_mut().enumerate() {
            *p = j;
        }
        for j in 0..N {
            // pivot: nalgebra's `imax` (first largest)
            let mut kmax = j;
            let mut the_max = r_diag[j];
            for (i, &v) in r_diag.iter().enumerate().skip(j + 1) {
                if v > the_max {
                    the_max = v;
                    kmax = i;
                }
            }
            if kmax != j {
                a.swap_columns(j, kmax);
                permutation.swap(j, kmax);
                r_diag[kmax] = r_diag[j];
                work[kmax] = work[j];
            }
            // Householder vector of column j, rows j..
            let mut aj_norm = enorm(&col(&a, j)[j..]);
            if aj_norm == 0.0 {
                r_diag[j] = 0.0;
                continue;
            }
            if col(&a, j)[j].is_sign_negative() {
                aj_norm = -aj_norm;
            }
            r_diag[j] = -aj_norm;
            {
                let axis = &mut col_mut(&mut a, j)[j..];
                for v in axis.iter_mut() {
                    *v /= aj_norm;
                }
                axis[0] += 1.0;
            }
            let (left, right) = a.as_mut_slice().split_at_mut((j + 1) * M);
            let w_j = &left[j * M + j..];
            for k in j + 1..N {
                let c = &mut right[(k - j - 1) * M + j..(k - j) * M];
                let t = -(dot(c, w_j) / w_j[0]);
                axpy(t, w_j, c);
                if r_diag[k] == 0.0 {
                    continue;
                }
                let temp = (c[0] / r_diag[k]).powi(2);
                r_diag[k] *= (1.0 - temp).max(0.0).sqrt();
                if 0.05 * (r_diag[k] / work[k]).powi(2) <= EPSMCH {
                    r_diag[k] = enorm(&c[1..]);
                    work[k] = r_diag[k];
                }
            }
        }
        // Qᵀb, first N entries
        let mut qt_b = [0.0; N];
        qt_b.copy_from_slice(&b.as_slice()[..N]);
        for (j, q) in qt_b.iter_mut().enumerate() {
            let axis = &col(&a, j)[j..];
            if axis[0] != 0.0 {
                let temp = -dot(&b.as_slice()[j..], axis) / axis[0];
                axpy(temp, axis, &mut b.as_mut_slice()[j..]);
            }
            *q = b[j];
        }
        for (j, &d) in r_diag.iter().enumerate() {
            a[(j, j)] = d;
        }
        Lls {
            r: a,
            qt_b,
            l_diag: r_diag,
            permutation,
            column_norms,
            work,
        }
    }

    /// `max_a_t_b_scaled`.
    fn max_a_t_b_scaled(&mut self, b_norm: f64) -> Option<f64> {
        self.work = self.qt_b;
        for v in &mut self.work {
            *v /= b_norm;
        }
        let mut max = 0.0f64;
        for j in 0..N {
            let scale = self.column_norms[self.permutation[j]];
            if scale == 0.0 {
                continue;
            }
            let sum = dot(&col(&self.r, j)[..=j], &self.work[..=j]);
            let temp = (sum / scale).abs();
            if temp.is_nan() {
                return None;
            }
            max = max.max(temp);
        }
        Some(max)
    }

    /// `a_x_norm`: `‖R Pᵀ x‖`.
    fn a_x_norm(&mut self, x: &[f64; N]) -> f64 {
        self.work = [0.0; N];
        for i in 0..N {
            let idx = self.permutation[i];
            axpy(x[idx], &col(&self.r, i)[..=i], &mut self.work[..=i]);
        }
        enorm(&self.work)
    }

    /// `is_non_singular` (`M ≥ N` here).
    fn is_non_singular(&self) -> bool {
        !(0..N).any(|j| self.r[(j, j)] == 0.0)
    }

    /// `solve_with_zero_diagonal`: the Gauss–Newton step; the factor is `R` (upper).
    fn solve_with_zero_diagonal(&mut self) -> [f64; N] {
        self.work = self.qt_b;
        let rank = (0..N).position(|i| self.r[(i, i)] == 0.0).unwrap_or(N);
        for v in &mut self.work[rank..] {
            *v = 0.0;
        }
        // nalgebra's `solve_upper_triangular_mut` on the leading rank × rank block
        for i in (0..rank).rev() {
            let coeff = self.work[i] / self.r[(i, i)];
            self.work[i] = coeff;
            axpy(-coeff, &col(&self.r, i)[..i], &mut self.work[..i]);
        }
        let mut x = [0.0; N];
        for j in 0..N {
            x[self.permutation[j]] = self.work[j];
        }
        x
    }

    /// `solve_with_diagonal`: `eliminate_diag` then `solve_after_elimination`; the factor is
    /// `L` (lower, diagonal in `l_diag`).
    #[allow(clippy::needless_range_loop)] // index loops as in the crate, for checking line by line
    fn solve_with_diagonal(&mut self, diag: &[f64; N]) -> [f64; N] {
        let mut rhs = self.qt_b;
        // eliminate_diag: Rᵀ into the lower triangle, then Givens rotations
        for j in 0..N {
            for i in j + 1..N {
                self.r[(i, j)] = self.r[(j, i)];
            }
        }
        for j in 0..N {
            self.work[j] = self.r[(j, j)];
        }
        for j in 0..N {
            let diag_entry = diag[self.permutation[j]];
            if diag_entry != 0.0 {
                self.l_diag[j] = diag_entry;
                for v in &mut self.l_diag[j + 1..] {
                    *v = 0.0;
                }
                let mut qtbpj = 0.0;
                for k in j..N {
                    if self.l_diag[k] == 0.0 {
                        continue;
                    }
                    let r_kk = self.r[(k, k)];
                    let (sin, cos) = if r_kk.abs() < self.l_diag[k].abs() {
                        let cot = r_kk / self.l_diag[k];
                        let sin = 0.5 / (0.25 + 0.25 * (cot * cot)).sqrt();
                        (sin, sin * cot)
                    } else {
                        let tan = self.l_diag[k] / r_kk;
                        let cos = 0.5 / (0.25 + 0.25 * (tan * tan)).sqrt();
                        (cos * tan, cos)
                    };
                    self.r[(k, k)] = cos * r_kk + sin * self.l_diag[k];
                    let rhs_k = rhs[k];
                    let temp = cos * rhs_k + sin * qtbpj;
                    qtbpj = -sin * rhs_k + cos * qtbpj;
                    rhs[k] = temp;
                    for i in k + 1..N {
                        let r_ik = self.r[(i, k)];
                        let temp = cos * r_ik + sin * self.l_diag[i];
                        self.l_diag[i] = -sin * r_ik + cos * self.l_diag[i];
                        self.r[(i, k)] = temp;
                    }
                }
            }
            self.l_diag[j] = self.r[(j, j)];
            self.r[(j, j)] = self.work[j];
        }
        // the crate swaps: work ← eliminated rhs
        self.work = rhs;
        // solve_after_elimination
        let rank = self.l_diag.iter().position(|v| *v == 0.0).unwrap_or(N);
        for v in &mut self.work[rank..] {
            *v = 0.0;
        }
        for j in (0..rank).rev() {
            let d = dot(&col(&self.r, j)[j + 1..rank], &self.work[j + 1..rank]);
            self.work[j] = (self.work[j] - d) / self.l_diag[j];
        }
        let mut x = [0.0; N];
        for j in 0..N {
            x[self.permutation[j]] = self.work[j];
        }
        x
    }

    /// `CholeskyFactor::solve` for the factor of the latest solve (`lower`: after
    /// `solve_with_diagonal`, else after `solve_with_zero_diagonal`). The crate swaps its work
    /// vector with the right-hand side; `work` ends holding `rhs` as there.
    fn factor_solve(&mut self, lower: bool, rhs: [f64; N]) -> [f64; N] {
        for i in 0..N {
            self.work[i] = rhs[self.permutation[i]];
        }
        if lower {
            for j in 0..N {
                self.work[j] /= self.l_diag[j];
                let x = self.work[j];
                axpy(-x, &col(&self.r, j)[j + 1..N], &mut self.work[j + 1..]);
            }
        } else {
            for j in 0..N {
                let sum = dot(&self.work[..j], &col(&self.r, j)[..j]);
                self.work[j] = (self.work[j] - sum) / self.r[(j, j)];
            }
        }
        std::mem::replace(&mut self.work, rhs)
    }

    /// `CholeskyFactor::mul_qt_b` for the upper factor (the only use in `lmpar`).
    fn mul_qt_b_upper(&self) -> [f64; N] {
        let mut out = [0.0; N];
        for (i, o) in out.iter_mut().enumerate() {
            *o = dot(&self.qt_b[..=i], &col(&self.r, i)[..=i]);
        }
        out
    }
}

/// `lmpar` (`determine_lambda_and_parameter_update`): the step, `λ` and `‖D p‖`.
fn lmpar<const N: usize, const M: usize>(
    lls: &mut Lls<N, M>,
    diag: &[f64; N],
    delta: f64,
    initial_lambda: f64,
) -> ([f64; N], f64, f64) {
    let is_non_singular = lls.is_non_singular();
    let mut p = lls.solve_with_zero_diagonal();
    let mut lower = false;
    let mut diag_p: [f64; N] = std::array::from_fn(|i| p[i] * diag[i]);
    let mut diag_p_norm = enorm(&diag_p);
    let mut fp = diag_p_norm - delta;
    if fp <= delta * P1 {
        return (p, 0.0, diag_p_norm);
    }
    let newton = |lls: &mut Lls<N, M>, lower: bool, diag_p: &[f64; N], diag_p_norm: f64, fp| {
        let mut q = *diag_p;
        for v in &mut q {
            *v /= diag_p_norm;
        }
        for (v, d) in q.iter_mut().zip(diag) {
            *v *= *d;
        }
        let q = lls.factor_solve(lower, q);
        let norm = enorm(&q);
        ((fp / delta) / norm) / norm
    };
    let mut lambda_lower = if is_non_singular {
        newton(lls, lower, &diag_p, diag_p_norm, fp)
    } else {
        0.0
    };
    let gnorm;
    let mut lambda_upper = {
        p = lls.mul_qt_b_upper();
        for j in 0..N {
            p[j] /= diag[lls.permutation[j]];
        }
        gnorm = enorm(&p);
        let upper = gnorm / delta;
        if upper == 0.0 {
            DWARF / delta.min(P1)
        } else {
            upper
        }
    };
    let mut lambda = initial_lambda.max(lambda_lower).min(lambda_upper);
    if lambda == 0.0 {
        lambda = gnorm / diag_p_norm;
    }
    for iteration in 1.. {
        if lambda == 0.0 {
            lambda = DWARF.max(lambda_upper * 0.001);
        }
        let l_sqrt = lambda.sqrt();
        for (dp, d) in diag_p.iter_mut().zip(diag) {
            *dp = l_sqrt * *d;
        }
        p = lls.solve_with_diagonal(&diag_p);
        lower = true;
        diag_p = std::array::from_fn(|i| p[i] * diag[i]);
        diag_p_norm = enorm(&diag_p);
        if iteration == 10 {
            break;
        }
        let fp_old = fp;
        fp = diag_p_norm - delta;
        if fp.abs() <= delta * P1 || (lambda_lower == 0.0 && fp <= fp_old && fp_old < 0.0) {
            break;
        }
        let newton_correction = newton(lls, lower, &diag_p, diag_p_norm, fp);
        if fp.is_sign_positive() {
            lambda_lower = lambda_lower.max(lambda);
        } else {
            lambda_upper = lambda_upper.min(lambda);
        }
        lambda = lambda_lower.max(lambda + newton_correction);
    }
    (p, lambda, diag_p_norm)
}

/// `LevenbergMarquardt::minimize` on `target` from its current parameters `x0`; returns the
/// crate's termination reason (the adapter reads everything else from the target).
pub(crate) fn minimize<T, const N: usize, const M: usize>(
    config: &Config,
    target: &mut T,
    x0: SVector<f64, N>,
) -> TerminationReason
where
    T: FixedTarget<N, M>,
{
    debug_assert!(M >= N && N > 0);
    // LM::new
    let mut nfev = 1usize;
    let Some(mut residuals) = target.residuals() else {
        return TerminationReason::User("residuals");
    };
    let mut residuals_norm = enorm(residuals.as_slice());
    if !residuals_norm.is_finite() {
        return TerminationReason::Numerical("residuals norm");
    }
    if residuals_norm <= DWARF {
        return TerminationReason::ResidualsZero;
    }
    let mut x: [f64; N] = std::array::from_fn(|i| x0[i]);
    let mut diag = [1.0f64; N];
    let mut delta = 0.0f64;
    let mut lambda = 0.0f64;
    let mut xnorm = 0.0f64;
    let mut first_trust_region_iteration = true;
    let mut first_update = true;
    let max_fev = config.patience * (N + 1);

    loop {
        let Some(jacobian) = target.jacobian() else {
            return TerminationReason::User("jacobian");
        };
        let mut lls = Lls::<N, M>::new(jacobian, residuals);

        // update_diag
        let Some(gnorm) = lls.max_a_t_b_scaled(residuals_norm) else {
            return TerminationReason::Numerical("jacobian");
        };
        if gnorm <= config.gtol {
            return TerminationReason::Orthogonal;
        }
        if first_update {
            for (d, c) in diag.iter_mut().zip(&lls.column_norms) {
                *d = if *c == 0.0 { 1.0 } else { *c };
            }
            let tmp: [f64; N] = std::array::from_fn(|i| diag[i] * x[i]);
            xnorm = enorm(&tmp);
            if !xnorm.is_finite() {
                return TerminationReason::Numerical("subproblem x");
            }
            delta = if xnorm == 0.0 {
                STEPBOUND
            } else {
                STEPBOUND * xnorm
            };
            first_update = false;
        } else {
            for (d, c) in diag.iter_mut().zip(&lls.column_norms) {
                *d = c.max(*d);
            }
        }

        residuals = loop {
            let (step, param_lambda, pnorm) = lmpar(&mut lls, &diag, delta, lambda);
            // trust_region_iteration
            lambda = param_lambda;
            if !pnorm.is_finite() {
                return TerminationReason::Numerical("subproblem ||Dp||");
            }
            let temp1 = (lls.a_x_norm(&step) / residuals_norm).powi(2);
            if !temp1.is_finite() {
                return TerminationReason::Numerical("trust-region reduction");
            }
            let temp2 = ((lambda.sqrt() * pnorm) / residuals_norm).powi(2);
            if !temp2.is_finite() {
                return TerminationReason::Numerical("trust-region reduction");
            }
            let predicted_reduction = temp1 + temp2 / 0.5;
            let dir_der = -(temp1 + temp2);
            if first_trust_region_iteration && pnorm < delta {
                delta = pnorm;
            }
            first_trust_region_iteration = false;

            let tmp: [f64; N] = std::array::from_fn(|i| -step[i] + x[i]);
            target.set_params(&SVector::from(tmp));
            nfev += 1;
            let Some(new_residuals) = target.residuals() else {
                return TerminationReason::User("residuals");
            };
            let new_residuals_norm = enorm(new_residuals.as_slice());

            let actual_reduction = if new_residuals_norm * P1 < residuals_norm {
                1.0 - (new_residuals_norm / residuals_norm).powi(2)
            } else {
                -1.0
            };
            let ratio = if predicted_reduction == 0.0 {
                0.0
            } else {
                actual_reduction / predicted_reduction
            };
            if ratio <= 0.25 {
                let mut temp = if !actual_reduction.is_sign_negative() {
                    0.5
                } else {
                    0.5 * dir_der / (dir_der + 0.5 * actual_reduction)
                };
                if new_residuals_norm * P1 >= residuals_norm || temp < P1 {
                    temp = P1;
                }
                delta = temp * delta.min(pnorm * 10.0);
                lambda /= temp;
            } else if lambda == 0.0 || ratio >= 0.75 {
                delta = pnorm / 0.5;
                lambda *= 0.5;
            }

            let good = ratio >= P0001;
            if good {
                x = tmp;
                let scaled: [f64; N] = std::array::from_fn(|i| diag[i] * x[i]);
                xnorm = enorm(&scaled);
                if !xnorm.is_finite() {
                    return TerminationReason::Numerical("new x");
                }
                residuals_norm = new_residuals_norm;
            }
            let mut finish = |reason| {
                if !good {
                    target.set_params(&SVector::from(x));
                }
                reason
            };
            if residuals_norm <= DWARF {
                return finish(TerminationReason::ResidualsZero);
            }
            let ftol_check = actual_reduction.abs() <= config.ftol
                && predicted_reduction <= config.ftol
                && ratio * 0.5 <= 1.0;
            let xtol_check = delta <= config.xtol * xnorm;
            if ftol_check || xtol_check {
                return finish(TerminationReason::Converged {
                    ftol: ftol_check,
                    xtol: xtol_check,
                });
            }
            if nfev >= max_fev {
                return finish(TerminationReason::LostPatience);
            }
            if actual_reduction.abs() <= EPSMCH
                && predicted_reduction <= EPSMCH
                && ratio * 0.5 <= 1.0
            {
                return finish(TerminationReason::NoImprovementPossible("ftol"));
            }
            if delta <= EPSMCH * xnorm {
                return finish(TerminationReason::NoImprovementPossible("xtol"));
            }
            if gnorm <= EPSMCH {
                return finish(TerminationReason::NoImprovementPossible("gtol"));
            }
            if good {
                break new_residuals;
            }
        };
    }
}

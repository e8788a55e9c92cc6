//! Fixed-size kernels for the fast paths: the operations of nalgebra (and of the backends'
//! own loops) the adapters use, written out over fixed-size arrays in **the same floating-point
//! order**, so a fast path returns bit for bit what the general path returns, without the
//! generic machinery (views, strides, non-inlined calls) around a handful of flops.
//!
//! Every function states which operation it reproduces; the tests in `tests/fast_paths.rs` hold
//! the fast paths to exact equality with the reference paths.

use nalgebra::{SMatrix, SVector};

/// Longest vector for which nalgebra's dot product is the plain left-to-right sum (nalgebra
/// unrolls by 8 beyond that, which changes the order of the additions).
pub(crate) const PLAIN_DOT_MAX: usize = 7;

/// `B h = rhs` for symmetric positive definite `B` by Cholesky, exactly as
/// `b.cholesky()?.solve(&rhs)` of nalgebra 0.34 computes it (`None` where nalgebra's
/// factorisation fails: a zero, negative or NaN pivot). Only the lower triangle of `b` is read.
#[inline]
pub(crate) fn cholesky_solve<const N: usize>(
    b: &SMatrix<f64, N, N>,
    rhs: &SVector<f64, N>,
) -> Option<SVector<f64, N>> {
    if N > PLAIN_DOT_MAX {
        return b.cholesky().map(|c| c.solve(rhs));
    }
    let mut l = *b;
    // nalgebra's `Cholesky::new_internal`: column j updated by the earlier columns (axpy with
    // factor −l[j][k], β = 1: `y ← a x + y`, the same sum as `y += a x`), then its pivot square-rooted and the column below divided by it.
    for j in 0..N {
        for k in 0..j {
            let factor = -l[(j, k)];
            for i in j..N {
                l[(i, j)] += factor * l[(i, k)];
            }
        }
        let diag = l[(j, j)];
        // `is_zero` then simba's `try_sqrt` (`None` below zero and for NaN): only a positive
        // pivot passes.
        if diag.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        let denom = diag.sqrt();
        l[(j, j)] = denom;
        for i in j + 1..N {
            l[(i, j)] /= denom;
        }
    }
    let mut x = *rhs;
    // `solve_lower_triangular_unchecked_mut`: forward substitution by columns (axpy).
    for i in 0..N {
        let coeff = x[i] / l[(i, i)];
        x[i] = coeff;
        for r in i + 1..N {
            x[r] += -coeff * l[(r, i)];
        }
    }
    // `ad_solve_lower_triangular_unchecked_mut`: back substitution with dot products, which
    // nalgebra sums from zero left to right for these lengths.
    for i in (0..N).rev() {
        let mut dot = 0.0;
        for r in i + 1..N {
            dot += l[(r, i)] * x[r];
        }
        x[i] = (x[i] - dot) / l[(i, i)];
    }
    Some(x)
}

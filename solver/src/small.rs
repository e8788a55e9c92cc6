//! Fixed-size kernels for the fast paths: the operations of nalgebra (and of the backends'
//! own loops) the adapters use, written out over fixed-size arrays in **the same floating-point
//! order**, so a fast path returns bit for bit what the general path returns, without the
//! generic machinery (views, strides, non-inlined calls) around a handful of flops.
//!
//! Every function states which operation it reproduces; the tests in `tests/suite/fast_paths.rs` hold
//! the fast paths to exact equality with the reference paths. The exception is
//! [`solve_2x2_spd`], the exact-penalty adapter's closed-form 2×2 solve, which is not a
//! transcription: it computes the same solution in fewer dependent operations (one division, no
//! square root) and differs from the Cholesky solve in the last bits.

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

/// `B h = rhs` for a symmetric positive definite 2×2 `B` in closed form (Cramer's rule with one
/// division): `h = [b₁₁ r₀ − b₁₀ r₁, b₀₀ r₁ − b₁₀ r₀] / det B`. `None` unless `b₀₀ > 0` and
/// `det B = b₀₀ b₁₁ − b₁₀² > 0` (the conditions for the Cholesky pivots `b₀₀` and `det B / b₀₀` to
/// be positive; a NaN entry fails them). Only the lower triangle of `b` is read.
///
/// Only for `N = 2` (the caller checks); the solution agrees with [`cholesky_solve`]'s to
/// rounding (a few units in the last place times the condition number), not bit for bit.
#[inline]
pub(crate) fn solve_2x2_spd<const N: usize>(
    b: &SMatrix<f64, N, N>,
    rhs: &SVector<f64, N>,
) -> Option<SVector<f64, N>> {
    debug_assert_eq!(N, 2);
    let (b00, b10, b11) = (b[(0, 0)], b[(1, 0)], b[(1, 1)]);
    let det = b00 * b11 - b10 * b10;
    if !(b00 > 0.0 && det > 0.0) {
        return None;
    }
    let inv = 1.0 / det;
    let (r0, r1) = (rhs[0], rhs[1]);
    let h = [(b11 * r0 - b10 * r1) * inv, (b00 * r1 - b10 * r0) * inv];
    Some(SVector::from_fn(|i, _| h[i]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A symmetric positive definite `N × N` matrix and a right-hand side from the workbench's
    /// seeded generator (`AᵀA + 10⁻³ I` with `A` of entries in [−1, 1)).
    fn spd<const N: usize>(seed: u64) -> (SMatrix<f64, N, N>, SVector<f64, N>) {
        let mut rng = rng::SplitMix64::new(seed);
        let mut next = || rng.uniform(-1.0, 1.0);
        let a = SMatrix::<f64, N, N>::from_fn(|_, _| next());
        let b = SVector::<f64, N>::from_fn(|_, _| next());
        (a.transpose() * a + SMatrix::identity() * 1e-3, b)
    }

    fn same_as_nalgebra<const N: usize>() {
        for seed in 0..200 {
            let (m, b) = spd::<N>(seed);
            let ours = cholesky_solve(&m, &b);
            let theirs = m.cholesky().map(|c| c.solve(&b));
            assert_eq!(
                format!("{ours:?}"),
                format!("{theirs:?}"),
                "N = {N}, seed {seed}"
            );
        }
        // Not positive definite: both refuse.
        let (m, b) = spd::<N>(7);
        assert!(cholesky_solve(&(-m), &b).is_none());
        assert!((-m).cholesky().is_none());
    }

    /// The closed-form 2×2 solve against nalgebra's Cholesky on the same generator: both refuse
    /// the same matrices, and the solutions agree to a relative `CLOSED_FORM_REL` (rounding: the
    /// generator's condition numbers stay below about 10⁴, so a few hundred ulps at most).
    #[test]
    fn closed_form_2x2_agrees_with_cholesky() {
        const CLOSED_FORM_REL: f64 = 1e-11;
        for seed in 0..2000 {
            let (m, b) = spd::<2>(seed);
            let ours = solve_2x2_spd(&m, &b).expect("positive definite");
            let theirs = m
                .cholesky()
                .map(|c| c.solve(&b))
                .expect("positive definite");
            assert!(
                (ours - theirs).amax() <= CLOSED_FORM_REL * theirs.amax(),
                "seed {seed}: {ours} vs {theirs}"
            );
            assert!(solve_2x2_spd(&(-m), &b).is_none());
        }
        let singular = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 4.0);
        assert!(solve_2x2_spd(&singular, &SVector::<f64, 2>::new(1.0, 1.0)).is_none());
        let nan = SMatrix::<f64, 2, 2>::new(f64::NAN, 0.0, 0.0, 1.0);
        assert!(solve_2x2_spd(&nan, &SVector::<f64, 2>::new(1.0, 1.0)).is_none());
    }

    #[test]
    fn bit_for_bit_nalgebra_for_every_size_it_replaces() {
        same_as_nalgebra::<1>();
        same_as_nalgebra::<2>();
        same_as_nalgebra::<3>();
        same_as_nalgebra::<4>();
        same_as_nalgebra::<5>();
        same_as_nalgebra::<6>();
        same_as_nalgebra::<7>();
        same_as_nalgebra::<9>();
    }
}

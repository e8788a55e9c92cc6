//! Shared machinery of the fitting estimators ([`crate::jet`], [`crate::quadric`]): tangent
//! frames, least-squares fits of bivariate polynomial heights by Householder QR with column
//! pivoting, and the normal and shape tensor of a height field at the origin.
//!
//! # Height field → normal and shape tensor
//!
//! In an orthonormal frame `(t1, t2, n0)` at the vertex, a surface `X(x, y) = o + x t1 + y t2 +
//! f(x, y) n0` with `f_x = p`, `f_y = q`, `f_xx = r`, `f_xy = s`, `f_yy = t` at the origin has
//! (do Carmo, *Differential Geometry of Curves and Surfaces*, §3-3, Monge patch):
//!
//! * tangents `X_x = t1 + p n0`, `X_y = t2 + q n0`, unit normal `N = (n0 − p t1 − q t2)/W`,
//!   `W = √(1 + p² + q²)` (on the side of `n0`);
//! * first fundamental form `I = [[1 + p², pq], [pq, 1 + q²]]`;
//! * second fundamental form `II = [[r, s], [s, t]]/W` (`X_xx · N` etc.; positive where the
//!   surface bends towards `N`, the workspace's sign).
//!
//! With `J = [X_x X_y]` (3×2), the world tensor `S = J I⁻¹ II I⁻¹ Jᵀ` is symmetric, has `S N = 0`
//! (as `Jᵀ N = 0`) and satisfies `Jᵀ S J = II`, i.e. `(J a)ᵀ S (J a) = aᵀ II a` for every tangent
//! vector `J a`: it is the Weingarten map `I⁻¹ II` written as a bilinear form in world
//! coordinates. Its eigenvalues on the tangent plane are those of `I⁻¹ II`, the principal
//! curvatures. The gradient terms matter whenever the frame normal `n0` is not the fitted
//! surface's normal `N`.
//!
//! # Least squares
//!
//! Coordinates are divided by the neighbourhood radius `h` (Cazals & Pouget 2005, §5.1: the
//! Vandermonde matrix is then well scaled), the columns of the Vandermonde matrix are
//! equilibrated to unit norm, and the system is solved by Householder QR with column pivoting
//! (Golub & Van Loan, *Matrix Computations*, §5.4.1). The condition number is estimated as
//! `max |r_ii| / min |r_ii|` of the pivoted `R` (a lower bound of the 2-norm condition number,
//! usually within a small factor of it); a fit above [`MAX_CONDITION`] is refused.
//!
//! **Fast path.** The QR's short dot products dominate the per-vertex cost, so the system is
//! first solved through the Jacobi-equilibrated normal equations `AᵀA c = Aᵀb` by Cholesky
//! ([`solve_normal_equations`]): the Cholesky factor is the `R` of the unpivoted QR of `A`, so
//! its diagonal gives the same kind of condition estimate, and the solution is accepted only
//! below [`NORMAL_EQUATIONS_CONDITION`] (squared: `1e4 ε` relative error); otherwise the pivoted
//! QR decides. Both paths solve the same least-squares problem.

use mesh::Mesh;
use nalgebra::{Matrix2, Matrix3, Vector3};

use crate::Topology;

/// Largest accepted condition-number estimate of the equilibrated, scaled Vandermonde system.
/// Well-spread neighbourhoods give 10¹–10³ at degree 4; near-collinear ones 10⁸ and more, where
/// the curvature coefficients have lost more than half their digits.
pub const MAX_CONDITION: f64 = 1e7;

/// Largest degree supported by the fixed-size buffers.
pub const MAX_DEGREE: usize = 4;

/// Largest number of coefficients (degree 4 with constant term).
pub const MAX_COEFFS: usize = 15;

/// Length of a row of [`Workspace`]'s monomial table: the coefficients, then the height.
const ROW: usize = MAX_COEFFS + 1;

/// Number of coefficients of a bivariate polynomial of degree `d`, with or without the
/// constant term.
pub fn num_coeffs(degree: usize, constant: bool) -> usize {
    (degree + 1) * (degree + 2) / 2 - usize::from(!constant)
}

/// An orthonormal tangent basis `(t1, t2)` with `t1 × t2 = n` for a unit `n`, branch-free of
/// singularities (Duff et al., *Building an Orthonormal Basis, Revisited*, JCGT 2017).
pub fn tangent_basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let sign = 1.0_f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vector3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vector3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// The derivatives of a fitted height at the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightDerivatives {
    /// `f_x`, `f_y`.
    pub grad: [f64; 2],
    /// `f_xx`, `f_xy`, `f_yy`.
    pub hess: [f64; 3],
}

impl HeightDerivatives {
    /// Unit normal and world shape tensor of the height field over the frame `(t1, t2, n0)`
    /// (module docs). `None` if `I` is singular or a value is not finite (not expected: `I` is
    /// positive definite for finite gradients).
    pub fn normal_and_shape(
        &self,
        t1: &Vector3<f64>,
        t2: &Vector3<f64>,
        n0: &Vector3<f64>,
    ) -> Option<(Vector3<f64>, Matrix3<f64>)> {
        let [p, q] = self.grad;
        let [r, s, t] = self.hess;
        let w = (1.0 + p * p + q * q).sqrt();
        let normal = (n0 - t1 * p - t2 * q) / w;
        let first = Matrix2::new(1.0 + p * p, p * q, p * q, 1.0 + q * q);
        let second = Matrix2::new(r, s, s, t) / w;
        let inv = first.try_inverse()?;
        let core = inv * second * inv;
        let xx = t1 + n0 * p;
        let xy = t2 + n0 * q;
        let shape = xx * xx.transpose() * core[(0, 0)]
            + (xx * xy.transpose()) * core[(0, 1)]
            + (xy * xx.transpose()) * core[(1, 0)]
            + xy * xy.transpose() * core[(1, 1)];
        (normal.iter().all(|c| c.is_finite()) && shape.iter().all(|c| c.is_finite()))
            .then_some((normal, shape))
    }
}

/// Why a fit was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FitFailure {
    /// Fewer points than coefficients.
    TooFewPoints,
    /// Rank-deficient or condition number above [`MAX_CONDITION`].
    IllConditioned,
}

/// Reusable buffers of one thread: local coordinates of the neighbourhood, the Vandermonde
/// matrix (column-major) and the right-hand side. Allocated once per rayon work item, never per
/// vertex once grown.
#[derive(Clone, Debug, Default)]
pub struct Workspace {
    /// Neighbourhood vertex indices.
    pub ring: Vec<usize>,
    /// Local coordinates `(x, y, z)/h`.
    pub local: Vec<[f64; 3]>,
    /// Weights of the points of `local` in the least-squares sum (weighted least squares:
    /// minimize `Σ wₖ (zₖ − p(xₖ, yₖ))²`, each row of the system scaled by `√wₖ`); empty for
    /// unit weights. Must be empty or as long as `local`, with finite `wₖ ≥ 0`.
    pub weights: Vec<f64>,
    /// Per point: the monomials of degree ≤ 4 in the order of [`fit_height`], then the height
    /// (entry [`MAX_COEFFS`]).
    rows: Vec<[f64; ROW]>,
    a: Vec<f64>,
    b: Vec<f64>,
    marks: crate::topology::RingMarks,
}

/// Fits `z ≈ Σ c_ij x^i y^j` (total degree `1..=degree`, or `0..=degree` with `constant`) to the
/// points in `ws.local` (already scaled) by least squares, and returns the derivatives at the
/// origin in the scaled coordinates. Monomials are ordered by total degree, then by the power
/// of `y`: `1, x, y, x², xy, y², x³, …`.
pub fn fit_height(
    ws: &mut Workspace,
    degree: usize,
    constant: bool,
) -> Result<HeightDerivatives, FitFailure> {
    let degree = degree.clamp(1, MAX_DEGREE);
    let n = num_coeffs(degree, constant);
    let m = ws.local.len();
    if m < n {
        return Err(FitFailure::TooFewPoints);
    }
    // Every point's monomials (all of degree ≤ 4: a lower degree uses a prefix, without the
    // constant term from the second) and height, computed once before the sums: written and
    // read in one pass, the short stores of a row stall the wide loads that read it back.
    ws.rows.clear();
    ws.rows.extend(ws.local.iter().map(monomials));
    if !ws.weights.is_empty() {
        if ws.weights.len() != m || ws.weights.iter().any(|w| !(w.is_finite() && *w >= 0.0)) {
            return Err(FitFailure::IllConditioned);
        }
        for (row, w) in ws.rows.iter_mut().zip(&ws.weights) {
            let r = w.sqrt();
            row.iter_mut().for_each(|c| *c *= r);
        }
    }
    let first = usize::from(!constant);
    let mut coeffs = [0.0; MAX_COEFFS];
    // Fast path: the equilibrated normal equations, accepted only when well conditioned.
    let mut gram = [[0.0; MAX_COEFFS]; MAX_COEFFS];
    let mut rhs = [0.0; MAX_COEFFS];
    // The upper triangle of `AᵀA` and `Aᵀz`, point by point in order (each entry is its own
    // sequential sum, so the sizes the jets use are unrolled at compile time with the same
    // results to the bit).
    let rows = &ws.rows;
    match (n, first) {
        (15, 0) => accumulate_normal_equations::<15, 0>(rows, &mut gram, &mut rhs),
        (14, 1) => accumulate_normal_equations::<14, 1>(rows, &mut gram, &mut rhs),
        (10, 0) => accumulate_normal_equations::<10, 0>(rows, &mut gram, &mut rhs),
        (9, 1) => accumulate_normal_equations::<9, 1>(rows, &mut gram, &mut rhs),
        (6, 0) => accumulate_normal_equations::<6, 0>(rows, &mut gram, &mut rhs),
        (5, 1) => accumulate_normal_equations::<5, 1>(rows, &mut gram, &mut rhs),
        _ => {
            for row in rows.iter() {
                let cols = &row[first..first + n];
                for i in 0..n {
                    let ri = cols[i];
                    rhs[i] += ri * row[MAX_COEFFS];
                    for (g, rj) in gram[i][i..n].iter_mut().zip(&cols[i..n]) {
                        *g += ri * rj;
                    }
                }
            }
        }
    }
    if solve_normal_equations(&mut gram, &mut rhs, n, &mut coeffs[..n]).is_none() {
        // Robust path: pivoted QR of the Vandermonde matrix.
        ws.a.clear();
        ws.a.resize(m * n, 0.0);
        ws.b.clear();
        ws.b.extend(ws.rows.iter().map(|r| r[MAX_COEFFS]));
        for (i, row) in ws.rows.iter().enumerate() {
            for (j, rj) in row[first..first + n].iter().enumerate() {
                ws.a[j * m + i] = *rj;
            }
        }
        solve_least_squares(&mut ws.a, &mut ws.b, m, n, &mut coeffs[..n])?;
    }
    let off = usize::from(constant);
    let c = |i: usize| coeffs.get(off + i).copied().unwrap_or(0.0);
    if degree < 2 {
        return Ok(HeightDerivatives {
            grad: [c(0), c(1)],
            hess: [0.0; 3],
        });
    }
    Ok(HeightDerivatives {
        grad: [c(0), c(1)],
        hess: [2.0 * c(2), c(3), 2.0 * c(4)],
    })
}

/// The monomials of degree ≤ 4 at `p` (`x = p[0]`, `y = p[1]`) in the order of [`fit_height`],
/// then the height `p[2]`: `xᵃ yᵇ` as `xᵃ · yᵇ`, each power by repeated multiplication
/// (`x⁴ = ((x·x)·x)·x`, no `powi`; `x⁰ = 1`, `x¹ = 1 · x`, both exact).
fn monomials(p: &[f64; 3]) -> [f64; ROW] {
    let powers = |v: f64| {
        let v2 = v * v;
        let v3 = v2 * v;
        [1.0, v, v2, v3, v3 * v]
    };
    let ([x0, x1, x2, x3, x4], [y0, y1, y2, y3, y4]) = (powers(p[0]), powers(p[1]));
    [
        x0 * y0,
        x1 * y0,
        x0 * y1,
        x2 * y0,
        x1 * y1,
        x0 * y2,
        x3 * y0,
        x2 * y1,
        x1 * y2,
        x0 * y3,
        x4 * y0,
        x3 * y1,
        x2 * y2,
        x1 * y3,
        x0 * y4,
        p[2],
    ]
}

/// Adds `rowᵀ row` (upper triangle) and `row · z` of every point to `gram` and `rhs`, for the
/// `N` monomial columns from `FIRST` on, both known at compile time (the loops unroll; each
/// entry is still its own sum over the points in order).
#[allow(clippy::needless_range_loop)] // triangular index arithmetic reads clearer with indices
fn accumulate_normal_equations<const N: usize, const FIRST: usize>(
    rows: &[[f64; ROW]],
    gram: &mut [[f64; MAX_COEFFS]; MAX_COEFFS],
    rhs: &mut [f64; MAX_COEFFS],
) {
    for row in rows {
        for i in 0..N.min(MAX_COEFFS - FIRST) {
            let ri = row[FIRST + i];
            rhs[i] += ri * row[MAX_COEFFS];
            for j in i..N.min(MAX_COEFFS - FIRST) {
                gram[i][j] += ri * row[FIRST + j];
            }
        }
    }
}

/// `Σ xᵢ yᵢ` over the shorter of the two slices, with four independent accumulators (a serial
/// sum waits on the adder's latency at every term; the QR's dot products are its hot spot).
fn dot(x: &[f64], y: &[f64]) -> f64 {
    let len = x.len().min(y.len());
    let (x, y) = (&x[..len], &y[..len]);
    let mut acc = [0.0; 4];
    let (xc, yc) = (x.chunks_exact(4), y.chunks_exact(4));
    let (xr, yr) = (xc.remainder(), yc.remainder());
    for (a, b) in xc.zip(yc) {
        acc[0] += a[0] * b[0];
        acc[1] += a[1] * b[1];
        acc[2] += a[2] * b[2];
        acc[3] += a[3] * b[3];
    }
    let mut tail = 0.0;
    for (a, b) in xr.iter().zip(yr) {
        tail += a * b;
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// Condition-number limit of the fast path ([`solve_normal_equations`]): squaring it in the
/// normal equations leaves `1e4 · ε ≈ 2e-12` relative accuracy; above it the pivoted QR
/// ([`solve_least_squares`]) takes over.
pub const NORMAL_EQUATIONS_CONDITION: f64 = 1e2;

/// Solves the normal equations `G c = r` (upper triangle of `G = AᵀA` filled, `r = Aᵀb`) after
/// Jacobi equilibration, by Cholesky; `None` when `G` is not numerically positive definite or
/// the estimated condition number of `A` (ratio of the largest to the smallest diagonal entry of
/// the Cholesky factor, which is `R`'s diagonal of the unpivoted QR of `A`) exceeds
/// [`NORMAL_EQUATIONS_CONDITION`]. Returns the estimate.
pub fn solve_normal_equations(
    g: &mut [[f64; MAX_COEFFS]; MAX_COEFFS],
    r: &mut [f64; MAX_COEFFS],
    n: usize,
    out: &mut [f64],
) -> Option<f64> {
    // The sizes the jets and the quadric use with `n` a constant, so that the inlined solver's
    // loops unroll (the same operations in the same order).
    match n {
        15 => cholesky_solve(g, r, 15, out),
        14 => cholesky_solve(g, r, 14, out),
        10 => cholesky_solve(g, r, 10, out),
        9 => cholesky_solve(g, r, 9, out),
        6 => cholesky_solve(g, r, 6, out),
        5 => cholesky_solve(g, r, 5, out),
        _ => cholesky_solve(g, r, n, out),
    }
}

/// The body of [`solve_normal_equations`].
#[inline(always)]
#[allow(clippy::needless_range_loop)] // triangular index arithmetic reads clearer with indices
fn cholesky_solve(
    g: &mut [[f64; MAX_COEFFS]; MAX_COEFFS],
    r: &mut [f64; MAX_COEFFS],
    n: usize,
    out: &mut [f64],
) -> Option<f64> {
    if n == 0 || n > MAX_COEFFS || out.len() < n {
        return None;
    }
    let mut d = [0.0; MAX_COEFFS];
    for i in 0..n {
        let gii = g[i][i];
        if !(gii > 0.0 && gii.is_finite()) {
            return None;
        }
        d[i] = gii.sqrt();
    }
    for i in 0..n {
        for j in i..n {
            g[i][j] /= d[i] * d[j];
        }
        r[i] /= d[i];
    }
    // Cholesky G = Uᵀ U in the upper triangle.
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for k in 0..n {
        let mut piv = g[k][k];
        for i in 0..k {
            piv -= g[i][k] * g[i][k];
        }
        if !(piv > 0.0 && piv.is_finite()) {
            return None;
        }
        let ukk = piv.sqrt();
        g[k][k] = ukk;
        lo = lo.min(ukk);
        hi = hi.max(ukk);
        for j in k + 1..n {
            let mut acc = g[k][j];
            for i in 0..k {
                acc -= g[i][k] * g[i][j];
            }
            g[k][j] = acc / ukk;
        }
    }
    let cond = hi / lo;
    if cond.is_nan() || cond > NORMAL_EQUATIONS_CONDITION {
        return None;
    }
    // Uᵀ y = r, then U c = y.
    let mut y = [0.0; MAX_COEFFS];
    for i in 0..n {
        let mut acc = r[i];
        for k in 0..i {
            acc -= g[k][i] * y[k];
        }
        y[i] = acc / g[i][i];
    }
    for i in (0..n).rev() {
        let mut acc = y[i];
        for k in i + 1..n {
            acc -= g[i][k] * out[k];
        }
        out[i] = acc;
        out[i] /= g[i][i];
    }
    for i in 0..n {
        out[i] /= d[i];
    }
    out.iter().take(n).all(|c| c.is_finite()).then_some(cond)
}

/// Least squares `min ‖A c − b‖` for `A` (`m × n`, column-major, overwritten) by column
/// equilibration and Householder QR with column pivoting; `out` (length `n`) receives `c`.
pub fn solve_least_squares(
    a: &mut [f64],
    b: &mut [f64],
    m: usize,
    n: usize,
    out: &mut [f64],
) -> Result<f64, FitFailure> {
    if n == 0 || n > MAX_COEFFS || m < n || a.len() < m * n || b.len() < m || out.len() < n {
        return Err(FitFailure::TooFewPoints);
    }
    // Equilibrate: unit column norms.
    let mut scale = [1.0; MAX_COEFFS];
    for (j, s) in scale.iter_mut().enumerate().take(n) {
        let col = &mut a[j * m..(j + 1) * m];
        let norm = dot(col, col).sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(FitFailure::IllConditioned);
        }
        col.iter_mut().for_each(|x| *x /= norm);
        *s = norm;
    }
    let mut perm = [0usize; MAX_COEFFS];
    for (j, p) in perm.iter_mut().enumerate() {
        *p = j;
    }
    let mut rdiag = [0.0; MAX_COEFFS];
    for k in 0..n {
        // Pivot: the remaining column of largest norm below row k.
        let mut best = k;
        let mut best_norm = -1.0;
        for j in k..n {
            let col = &a[j * m + k..(j + 1) * m];
            let nj = dot(col, col);
            if nj > best_norm {
                best_norm = nj;
                best = j;
            }
        }
        if best != k {
            let (lo_cols, hi_cols) = a.split_at_mut(best * m);
            lo_cols[k * m..(k + 1) * m].swap_with_slice(&mut hi_cols[..m]);
            perm.swap(k, best);
            scale.swap(k, best);
        }
        let norm = best_norm.max(0.0).sqrt();
        if norm == 0.0 || !norm.is_finite() {
            return Err(FitFailure::IllConditioned);
        }
        let (left, right) = a.split_at_mut((k + 1) * m);
        let v = &mut left[k * m + k..];
        let x0 = v[0];
        let alpha = if x0 > 0.0 { -norm } else { norm };
        // v = x − α e1, stored in place of column k on and below the diagonal.
        v[0] = x0 - alpha;
        let v = &*v;
        let vnorm2 = dot(v, v);
        rdiag[k] = alpha;
        if vnorm2 > 0.0 {
            for col in right.chunks_exact_mut(m).take(n - k - 1) {
                let col = &mut col[k..];
                let f = 2.0 * dot(v, col) / vnorm2;
                col.iter_mut().zip(v).for_each(|(c, x)| *c -= f * x);
            }
            let rhs = &mut b[k..m];
            let f = 2.0 * dot(v, rhs) / vnorm2;
            rhs.iter_mut().zip(v).for_each(|(c, x)| *c -= f * x);
        }
    }
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for r in rdiag.iter().take(n) {
        lo = lo.min(r.abs());
        hi = hi.max(r.abs());
    }
    let cond = hi / lo;
    if !(lo > 0.0 && cond.is_finite() && cond <= MAX_CONDITION) {
        return Err(FitFailure::IllConditioned);
    }
    // Back substitution R y = Qᵀ b; R's strict upper part is a[j*m + i], i < j.
    let mut y = [0.0; MAX_COEFFS];
    for i in (0..n).rev() {
        let mut acc = b[i];
        for j in i + 1..n {
            acc -= a[j * m + i] * y[j];
        }
        y[i] = acc / rdiag[i];
    }
    for k in 0..n {
        out[perm[k]] = y[k] / scale[k];
    }
    if out.iter().take(n).all(|c| c.is_finite()) {
        Ok(cond)
    } else {
        Err(FitFailure::IllConditioned)
    }
}

/// How a vertex's neighbourhood is gathered for a fit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RingRule {
    /// Grow rings until the neighbourhood (the vertex included) has this many points…
    pub min_points: usize,
    /// …but add at most this many rings…
    pub max_rings: usize,
    /// …and at most this many points.
    pub max_points: usize,
}

/// A successful local fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalFit {
    /// Degree of the polynomial that was fitted.
    pub degree: usize,
    /// Unit normal of the fitted height field at the origin.
    pub normal: Vector3<f64>,
    /// World shape tensor of the fitted height field at the origin (`S normal = 0`).
    pub shape: Matrix3<f64>,
}

/// What to fit: degree, constant term, neighbourhood.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FitSpec {
    /// Highest degree tried (2..=4).
    pub degree: usize,
    /// Include the constant term (Cazals–Pouget jets approximate the vertex; libigl's quadric
    /// interpolates it).
    pub constant: bool,
    /// The neighbourhood.
    pub rule: RingRule,
}

/// Fits a height field of degree `degree` (falling back to lower degrees down to 2) over the
/// neighbourhood of vertex `v` chosen by `rule`, in the frame of the unit normal `n0`, and
/// returns its normal and shape tensor at `v` (module docs). `Err` when
/// even degree 2 fails: too few points or ill-conditioned.
pub fn fit_vertex(
    mesh: &Mesh,
    topo: &Topology,
    v: usize,
    n0: &Vector3<f64>,
    spec: &FitSpec,
    ws: &mut Workspace,
) -> Result<LocalFit, FitFailure> {
    let verts = mesh.vertices();
    let Some(origin) = verts.get(v).map(|x| x.data.p) else {
        return Err(FitFailure::TooFewPoints);
    };
    let rule = spec.rule;
    topo.rings_into_marked(
        v,
        rule.min_points,
        rule.max_rings,
        rule.max_points,
        &mut ws.ring,
        &mut ws.marks,
    );
    let FitSpec {
        degree, constant, ..
    } = *spec;
    let (t1, t2) = tangent_basis(n0);
    ws.local.clear();
    let mut h = 0.0_f64;
    for &u in ws.ring.iter() {
        if u == v && !constant {
            continue;
        }
        let d = verts[u].data.p - origin;
        h = h.max(d.norm());
        ws.local.push([d.dot(&t1), d.dot(&t2), d.dot(n0)]);
    }
    if !(h > 0.0 && h.is_finite()) {
        return Err(FitFailure::TooFewPoints);
    }
    for p in ws.local.iter_mut() {
        p.iter_mut().for_each(|c| *c /= h);
    }
    let mut last = FitFailure::TooFewPoints;
    for d in (2..=degree.clamp(2, MAX_DEGREE)).rev() {
        match fit_height(ws, d, constant) {
            Ok(mut der) => {
                der.hess.iter_mut().for_each(|c| *c /= h);
                match der.normal_and_shape(&t1, &t2, n0) {
                    Some((normal, shape)) => {
                        return Ok(LocalFit {
                            degree: d,
                            normal,
                            shape,
                        })
                    }
                    None => last = FitFailure::IllConditioned,
                }
            }
            Err(e) => last = e,
        }
    }
    Err(last)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_basis_is_orthonormal_and_right_handed() {
        /// A handful of products and one division: rounding only.
        const ROUNDING: f64 = 1e-15;
        for n in [
            Vector3::z(),
            -Vector3::z(),
            Vector3::x(),
            Vector3::new(1.0, -2.0, 0.5).normalize(),
            Vector3::new(1e-20, 0.0, -1.0).normalize(),
        ] {
            let (t1, t2) = tangent_basis(&n);
            assert!((t1.norm() - 1.0).abs() < ROUNDING);
            assert!((t2.norm() - 1.0).abs() < ROUNDING);
            assert!(t1.dot(&t2).abs() < ROUNDING);
            assert!((t1.cross(&t2) - n).norm() < ROUNDING);
        }
    }

    #[test]
    fn gradient_terms_give_the_sphere_in_a_tilted_frame() {
        // The unit sphere through the origin with outward normal N (centre −N), seen as a graph
        // over a frame whose normal n0 is 0.3 rad off N. Implicit differentiation of
        // |X + N|² = 1, X = x t1 + y t2 + f n0, at the origin (g = X + N = N there):
        // f_x = −N·t1 / N·n0, f_xx = −|X_x|² / N·n0, f_xy = −X_x·X_y / N·n0, etc.
        /// Closed-form derivatives: rounding only.
        const EXACT: f64 = 1e-13;
        let big_n = Vector3::new(0.2, -0.3, 0.9).normalize();
        let n0 = (big_n + Vector3::new(0.25, 0.1, 0.0)).normalize();
        let (t1, t2) = tangent_basis(&n0);
        let gn = big_n.dot(&n0);
        let (p, q) = (-big_n.dot(&t1) / gn, -big_n.dot(&t2) / gn);
        let (xx, xy) = (t1 + n0 * p, t2 + n0 * q);
        let d = HeightDerivatives {
            grad: [p, q],
            hess: [-xx.dot(&xx) / gn, -xx.dot(&xy) / gn, -xy.dot(&xy) / gn],
        };
        let (normal, shape) = d.normal_and_shape(&t1, &t2, &n0).expect("regular");
        assert!((normal - big_n).norm() < EXACT);
        let want = -(Matrix3::identity() - big_n * big_n.transpose());
        assert!((shape - want).norm() < EXACT, "{shape} vs {want}");
    }

    #[test]
    fn least_squares_recovers_an_exact_polynomial() {
        let mut ws = Workspace::default();
        for i in -2..=2 {
            for j in -2..=2 {
                let (x, y) = (i as f64 / 2.0, j as f64 / 2.0);
                let z = 0.1 + 0.2 * x - 0.3 * y + 0.5 * x * x - 0.25 * x * y + 0.75 * y * y;
                ws.local.push([x, y, z]);
            }
        }
        let d = fit_height(&mut ws, 2, true).expect("well posed");
        /// An exact fit of a 25×6 well-conditioned system.
        const TOL: f64 = 1e-13;
        assert!((d.grad[0] - 0.2).abs() < TOL && (d.grad[1] + 0.3).abs() < TOL);
        assert!((d.hess[0] - 1.0).abs() < TOL);
        assert!((d.hess[1] + 0.25).abs() < TOL);
        assert!((d.hess[2] - 1.5).abs() < TOL);
        // Collinear points: refused.
        ws.local = (0..10).map(|i| [i as f64, 2.0 * i as f64, 1.0]).collect();
        assert_eq!(
            fit_height(&mut ws, 2, true),
            Err(FitFailure::IllConditioned)
        );
    }
}

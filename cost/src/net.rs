//! Objectives stated on triangular Bézier nets, constructions that build nets from parameters,
//! and their composition.
//!
//! # Net order
//!
//! A degree-`n` net has `(n + 1)(n + 2)/2` control points `b_{ijk}`, `i + j + k = n`, stored row
//! by row in `k` (the third corner's index) and, within a row, by increasing `j`:
//! `index(n, i, j, k) = k(n + 1) − k(k − 1)/2 + j` (docs/conventions.md, "Bézier triangles";
//! `surface::beztri` uses these same functions). Several nets (a macro-patch's three
//! sub-patches) are concatenated: an objective reads one slice of points and says which of them
//! it uses.
//!
//! # The chain rule, once
//!
//! An objective gives its residuals `r(P)` and the non-zero blocks `∂r_a/∂P_p` (one row vector
//! over the three coordinates of a control point) — [`NetObjective`]. A construction gives the
//! points `P(x)` and, per point, the 3 × N matrix `∂P_p/∂x` — [`NetConstruction`]. The
//! [`Composed`] problem is then a [`LeastSquaresProblem`] in `x` with
//! `∂r_a/∂x = Σ_p (∂r_a/∂P_p)(∂P_p/∂x)`, so a solver adapter can minimize any objective over
//! any construction, and neither side writes the chain rule.

use nalgebra::{SMatrix, SVector, Vector3};
use solver::LeastSquaresProblem;

/// Number of control points of a degree-`n` net, `(n + 1)(n + 2)/2`.
pub fn num_points(n: usize) -> usize {
    (n + 1) * (n + 2) / 2
}

/// Position of `b_{ijk}` (with `i + j + k = n`) in net order (module docs).
pub fn index(n: usize, i: usize, j: usize, k: usize) -> usize {
    debug_assert_eq!(i + j + k, n);
    k * (n + 1) - k * k.saturating_sub(1) / 2 + j
}

/// The multi-indices `(i, j, k)` of degree `n` in net order.
pub fn multi_indices(n: usize) -> Vec<(usize, usize, usize)> {
    let mut out = Vec::with_capacity(num_points(n));
    for k in 0..=n {
        for i in (0..=n - k).rev() {
            out.push((i, n - k - i, k));
        }
    }
    out
}

/// An objective `‖r(P)‖²` on control points `P` (one or several concatenated nets), with the
/// exact derivative of every residual with respect to every control point it reads.
pub trait NetObjective<const M: usize> {
    /// The residuals at the points `P`.
    fn residuals(&self, points: &[Vector3<f64>]) -> SVector<f64, M>;

    /// Calls `f(a, p, d)` for each non-zero block `d = ∂r_a/∂P_p` (the derivative of residual
    /// `a` with respect to the three coordinates of point `p`). A pair may be reported more
    /// than once; the blocks then add.
    fn for_each_derivative(
        &self,
        points: &[Vector3<f64>],
        f: &mut dyn FnMut(usize, usize, Vector3<f64>),
    );

    /// The objective `‖r(P)‖²`.
    fn value(&self, points: &[Vector3<f64>]) -> f64 {
        self.residuals(points).norm_squared()
    }

    /// The gradient of [`value`](Self::value) with respect to each control point:
    /// `∂‖r‖²/∂P_p = 2 Σ_a r_a ∂r_a/∂P_p`.
    fn gradient(&self, points: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
        let r = self.residuals(points);
        let mut g = vec![Vector3::zeros(); points.len()];
        self.for_each_derivative(points, &mut |a, p, d| {
            if let Some(slot) = g.get_mut(p) {
                *slot += d * (2.0 * r[a]);
            }
        });
        g
    }
}

/// Control points built from `N` parameters, with the exact derivative of each point.
#[derive(Clone, Debug, PartialEq)]
pub struct BuiltNets<const N: usize> {
    /// The points, nets concatenated in the order the objective expects.
    pub points: Vec<Vector3<f64>>,
    /// Per point, `∂P_p/∂x` (row: coordinate, column: parameter).
    pub jacobian: Vec<SMatrix<f64, 3, N>>,
}

/// A construction of control points from `N` parameters (a surface scheme with its free
/// parameters), with bounds on the parameters.
pub trait NetConstruction<const N: usize> {
    /// The points and their derivatives at `x`; `None` where the construction is undefined
    /// (the composed problem then reports non-finite residuals, which the solvers treat as a
    /// rejected trial point).
    fn build(&self, x: &SVector<f64, N>) -> Option<BuiltNets<N>>;

    /// Lower bounds on the parameters (`f64::NEG_INFINITY` for a free one, the default).
    fn lower_bounds(&self) -> SVector<f64, N> {
        SVector::from_element(f64::NEG_INFINITY)
    }
}

/// An objective on nets composed with a construction: a least-squares problem in the
/// construction's parameters (module docs).
#[derive(Clone, Debug)]
pub struct Composed<O, C> {
    /// What is measured on the nets (named so that it does not hide
    /// [`LeastSquaresProblem::objective`]).
    pub measure: O,
    /// How the nets follow from the parameters.
    pub construction: C,
}

impl<O, C> Composed<O, C> {
    /// The composition `objective ∘ construction`.
    pub fn new(measure: O, construction: C) -> Self {
        Composed {
            measure,
            construction,
        }
    }

    /// Residuals and Jacobian in one evaluation of the construction.
    pub fn evaluate<const N: usize, const M: usize>(
        &self,
        x: &SVector<f64, N>,
    ) -> Option<(SVector<f64, M>, SMatrix<f64, M, N>)>
    where
        O: NetObjective<M>,
        C: NetConstruction<N>,
    {
        let built = self.construction.build(x)?;
        let r = self.measure.residuals(&built.points);
        let mut jac = SMatrix::<f64, M, N>::zeros();
        self.measure
            .for_each_derivative(&built.points, &mut |a, p, d| {
                if let (true, Some(dp)) = (a < M, built.jacobian.get(p)) {
                    let row = d.transpose() * dp;
                    for k in 0..N {
                        jac[(a, k)] += row[k];
                    }
                }
            });
        Some((r, jac))
    }
}

impl<O, C, const N: usize, const M: usize> LeastSquaresProblem<N, M> for Composed<O, C>
where
    O: NetObjective<M>,
    C: NetConstruction<N>,
{
    fn residuals(&self, x: &SVector<f64, N>) -> SVector<f64, M> {
        match self.construction.build(x) {
            Some(built) => self.measure.residuals(&built.points),
            None => SVector::from_element(f64::NAN),
        }
    }

    fn jacobian(&self, x: &SVector<f64, N>) -> SMatrix<f64, M, N> {
        self.evaluate(x)
            .map(|e| e.1)
            .unwrap_or_else(|| SMatrix::from_element(f64::NAN))
    }

    fn lower_bounds(&self) -> SVector<f64, N> {
        self.construction.lower_bounds()
    }
}

//! Problem traits: bound-constrained nonlinear least squares and smooth objectives.
//!
//! The solvers of this crate minimise over `x ∈ ℝᴺ` subject to simple lower bounds `x ≥ l`
//! (an entry of `l` equal to `f64::NEG_INFINITY` leaves that unknown free).
//!
//! # Which number is which
//!
//! For a least-squares problem with residuals `r(x) ∈ ℝᴹ` there are two customary scalings:
//!
//! - the **objective** `F(x) = ‖r(x)‖²`, the unhalved sum of squares used by the seed papers;
//!   [`LeastSquaresProblem::objective`] and [`LeastSquaresProblem::gradient`] (`∇F = 2 Jᵀ r`)
//!   return this one;
//! - the **cost** `½‖r(x)‖²`, the Ceres Solver / SciPy `least_squares` convention. Every
//!   [`SolveReport`](crate::SolveReport) prints and serialises *costs* (`initial_cost`,
//!   `final_cost`, `cost_history`) and the gradient of the cost, `Jᵀ r`
//!   (`final_gradient_norm`). [`LeastSquaresProblem::cost`] returns it, and
//!   [`SolveReport::final_objective`](crate::SolveReport::final_objective) converts back.
//!
//! Both have the same minimisers; only the reported numbers differ by the factor 2.

use nalgebra::{SMatrix, SVector};

/// A nonlinear least-squares problem with `N` unknowns, `M` residuals and lower bounds.
///
/// Implementors give the residual vector and its Jacobian analytically (check them with
/// [`check_jacobian`](crate::check_jacobian)). Evaluations may return non-finite numbers where the
/// model is undefined; the solvers treat such points as failed trial points, never as a panic.
pub trait LeastSquaresProblem<const N: usize, const M: usize> {
    /// The residual vector `r(x)`.
    fn residuals(&self, x: &SVector<f64, N>) -> SVector<f64, M>;

    /// The Jacobian `J(x) = ∂r/∂x`, one row per residual and one column per unknown.
    fn jacobian(&self, x: &SVector<f64, N>) -> SMatrix<f64, M, N>;

    /// Simple lower bounds `x ≥ l`; `f64::NEG_INFINITY` marks a free unknown.
    ///
    /// The default leaves every unknown free.
    fn lower_bounds(&self) -> SVector<f64, N> {
        SVector::from_element(f64::NEG_INFINITY)
    }

    /// The objective `F(x) = ‖r(x)‖²` (unhalved, as in the seed papers).
    fn objective(&self, x: &SVector<f64, N>) -> f64 {
        self.residuals(x).norm_squared()
    }

    /// The cost `½‖r(x)‖²` that reports print (Ceres / SciPy convention).
    fn cost(&self, x: &SVector<f64, N>) -> f64 {
        0.5 * self.residuals(x).norm_squared()
    }

    /// The gradient of the objective, `∇F(x) = 2 J(x)ᵀ r(x)`.
    fn gradient(&self, x: &SVector<f64, N>) -> SVector<f64, N> {
        2.0 * self.jacobian(x).transpose() * self.residuals(x)
    }

    /// The second-order term `S(x) = Σᵢ rᵢ(x) ∇²rᵢ(x)` of the Hessian of the cost,
    /// `∇²(½‖r‖²) = JᵀJ + S`, given the residuals `r = r(x)` already evaluated at `x`; `None` (the
    /// default) when the problem does not provide second derivatives.
    ///
    /// The exact-penalty adapter uses it, where given, in place of its structured secant
    /// approximation of `S` (a Newton model instead of a quasi-Newton one: fewer iterations on
    /// nonzero-residual problems). Check it with
    /// [`check_second_order`](crate::check_second_order).
    fn second_order_term(
        &self,
        _x: &SVector<f64, N>,
        _r: &SVector<f64, M>,
    ) -> Option<SMatrix<f64, N, N>> {
        None
    }
}

/// A smooth objective `f: ℝᴺ → ℝ` with its gradient and simple lower bounds.
///
/// This is what the L-BFGS adapter minimises; least-squares problems are presented to it through
/// [`HalfSumOfSquares`].
pub trait ObjectiveProblem<const N: usize> {
    /// The value `f(x)`.
    fn value(&self, x: &SVector<f64, N>) -> f64;

    /// The gradient `∇f(x)`.
    fn gradient(&self, x: &SVector<f64, N>) -> SVector<f64, N>;

    /// `(f(x), ∇f(x))` in one call, for solvers that need both at the same point; the default
    /// calls [`value`](Self::value) and [`gradient`](Self::gradient). Implementations that share
    /// work between the two must return exactly the same numbers as the separate calls.
    fn value_and_gradient(&self, x: &SVector<f64, N>) -> (f64, SVector<f64, N>) {
        (self.value(x), self.gradient(x))
    }

    /// Simple lower bounds `x ≥ l`; `f64::NEG_INFINITY` marks a free unknown (the default).
    fn lower_bounds(&self) -> SVector<f64, N> {
        SVector::from_element(f64::NEG_INFINITY)
    }
}

/// A least-squares problem seen as the smooth objective `f(x) = ½‖r(x)‖²` (the *cost*) with
/// gradient `Jᵀ r`, so that every adapter's tolerances and reports refer to the same number.
#[derive(Debug, Clone, Copy)]
pub struct HalfSumOfSquares<'a, P, const M: usize>(
    /// The wrapped least-squares problem.
    pub &'a P,
);

impl<P, const N: usize, const M: usize> ObjectiveProblem<N> for HalfSumOfSquares<'_, P, M>
where
    P: LeastSquaresProblem<N, M>,
{
    fn value(&self, x: &SVector<f64, N>) -> f64 {
        0.5 * self.0.residuals(x).norm_squared()
    }

    fn gradient(&self, x: &SVector<f64, N>) -> SVector<f64, N> {
        self.0.jacobian(x).transpose() * self.0.residuals(x)
    }

    /// The residuals evaluated once for both.
    fn value_and_gradient(&self, x: &SVector<f64, N>) -> (f64, SVector<f64, N>) {
        let r = self.0.residuals(x);
        (0.5 * r.norm_squared(), self.0.jacobian(x).transpose() * r)
    }

    fn lower_bounds(&self) -> SVector<f64, N> {
        self.0.lower_bounds()
    }
}

/// A least-squares problem with its second derivatives hidden: the exact-penalty adapter then
/// approximates the second-order term `S` by the Dennis–Gay–Welsch structured secant update, as
/// Mahdavi-Amiri and Bartels (1989) do, instead of taking Newton steps with the problem's exact
/// [`LeastSquaresProblem::second_order_term`]. For reproducing the seeds' quasi-Newton
/// convergence (iteration counts, cost histories); the optima agree to the adapters' tolerances.
#[derive(Debug, Clone, Copy)]
pub struct SecantModel<'a, P>(
    /// The wrapped least-squares problem.
    pub &'a P,
);

impl<P, const N: usize, const M: usize> LeastSquaresProblem<N, M> for SecantModel<'_, P>
where
    P: LeastSquaresProblem<N, M>,
{
    fn residuals(&self, x: &SVector<f64, N>) -> SVector<f64, M> {
        self.0.residuals(x)
    }
    fn jacobian(&self, x: &SVector<f64, N>) -> SMatrix<f64, M, N> {
        self.0.jacobian(x)
    }
    fn lower_bounds(&self) -> SVector<f64, N> {
        self.0.lower_bounds()
    }
    fn objective(&self, x: &SVector<f64, N>) -> f64 {
        self.0.objective(x)
    }
    fn cost(&self, x: &SVector<f64, N>) -> f64 {
        self.0.cost(x)
    }
    fn gradient(&self, x: &SVector<f64, N>) -> SVector<f64, N> {
        self.0.gradient(x)
    }
    // `second_order_term` keeps the default: `None`.
}

//! The objectives of the workbench, each stated four ways — value, gradient, residual vector and
//! Jacobian — analytically, on plain vectors and scalars (the geometry crates decide what the
//! vectors mean). Every objective implements [`solver::LeastSquaresProblem`] so any solver
//! adapter can minimize it, and every derivative is checked by finite differences in tests.
//!
//! * [`boundary_curve`] — Mann's boundary-curve objective on the unit chord (techreport eqs 8–10
//!   with gradients 11–14; conference eqs 7–9 and "(A)");
//! * [`corner`] — Section 4's corner curvature and twist measures on a patch's derivative
//!   vectors, with their gradients with respect to those vectors.

pub mod boundary_curve;
pub mod corner;

pub use boundary_curve::{BoundaryCurveObjective, CostError, Weights};

//! The objectives of the workbench, each stated four ways — value, gradient, residual vector and
//! Jacobian — analytically, on plain vectors, scalars and control nets (the geometry crates
//! decide what the vectors mean). Every objective implements [`solver::LeastSquaresProblem`]
//! (directly, or composed with a construction through [`net::Composed`]) so any solver adapter
//! can minimize it, and every derivative is checked by finite differences in tests.
//!
//! * [`boundary_curve`] — Mann's boundary-curve objective on the unit chord (techreport eqs 8–10
//!   with gradients 11–14; conference eqs 7–9 and "(A)");
//! * [`corner`] — Section 4's corner curvature and twist measures, on a patch's derivative
//!   vectors and on a control net ([`corner::CornerOnNet`]);
//! * [`net_energy`] — thin-plate and membrane energies of control nets over planar domains;
//! * [`net`] — the net order, the [`net::NetObjective`] and [`net::NetConstruction`] traits,
//!   and their composition [`net::Composed`], which applies the chain rule once.

pub mod boundary_curve;
pub mod corner;
pub mod net;
pub mod net_energy;

pub use boundary_curve::{BoundaryCurveObjective, CostError, Weights};
pub use net::{BuiltNets, Composed, NetConstruction, NetObjective};
pub use net_energy::{NetEnergy, NetEnergyError, SobolevEnergy};

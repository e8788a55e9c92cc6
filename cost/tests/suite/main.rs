//! The integration tests of `cost`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod boundary_curve;
mod common;
mod corner;
mod net_energy;

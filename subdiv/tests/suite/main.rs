//! The integration tests of `subdiv`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod common;
mod golden;
mod limits;
mod reproduction;
mod robustness;
mod shapes;

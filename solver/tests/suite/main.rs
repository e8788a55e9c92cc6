//! The integration tests of `solver`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod adapters;
mod agreement;
mod check;
mod common;
mod fast_paths;
mod lm_reference;

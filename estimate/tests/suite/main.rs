//! The integration tests of `estimate`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod common;
mod facing;
mod fold_split;
mod gradients;
mod hybrid;
mod jet;
mod multiscale;
mod normals;
mod quadric;
mod rusinkiewicz;
mod support;

//! The integration tests of `mesh`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod datasets;
mod franke;
mod repair;
mod repair_creases;

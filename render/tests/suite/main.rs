//! The integration tests of `render`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod chart;
mod curve_figure;
mod interrogation;

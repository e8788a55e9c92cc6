//! The integration tests of `curves`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod boundary_problem;
mod dbhs;
mod dbhs_guarded;
mod extreme_problems;
mod optimized;
mod projection_rules;
mod tweak_rules;

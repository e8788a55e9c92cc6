//! The integration tests of `fitjob`, one test binary for all of them: a module a topic.

mod heightfield;
mod job;
mod mesh_output;

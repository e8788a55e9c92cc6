//! The integration tests of `experiments`, one test binary for all of them (one link, not one a
//! file): a module a topic.

mod common;
mod curve_cli;
mod exit_status;
mod hostile_cli;
mod mesh_cli;
mod page_cli;
mod schemes_cli;
mod shell_docs;
mod studies_cli;
mod sweep_cli;
mod sweep_lib;

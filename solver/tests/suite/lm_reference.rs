//! The tests of `solver/examples/lm_reference.rs`, the native reference of issue 28
//! (`scripts/end_to_end.sh`): the example's own `#[cfg(test)]` module, compiled here because
//! `cargo test` builds examples as programs only (`test = true` in `Cargo.toml` would build it as
//! a test instead, and `scripts/end_to_end.sh --quick` needs the program `cargo test` leaves).
//! Its `main` and the items only `main` uses are dead code in this crate.

#[allow(dead_code)]
#[path = "../../examples/lm_reference.rs"]
mod example;

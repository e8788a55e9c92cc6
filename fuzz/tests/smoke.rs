//! The fuzz harness in the test suite: twenty thousand mutated inputs of every target, no panic,
//! none slower than a second.

use std::time::Duration;

/// Inputs per target in the test suite (the recorded long runs are in docs/hostile-input.md).
const RUNS: u64 = 20_000;
/// A single input slower than this is a hang in the making: seeds and their mutants are small.
const SLOW: Duration = Duration::from_secs(1);

#[test]
fn every_target_survives_a_smoke_run() {
    for t in fuzz::TARGETS {
        assert!(!fuzz::seeds(t.name).is_empty(), "{}: no seeds", t.name);
        let out = fuzz::fuzz(t, RUNS, 7, SLOW);
        assert_eq!(out.executions, RUNS);
        assert!(
            out.panics.is_empty(),
            "{}: {} panics, first: {:?}",
            t.name,
            out.panics.len(),
            out.panics
                .first()
                .map(|(i, m)| (String::from_utf8_lossy(i).into_owned(), m))
        );
        assert!(
            out.slow.is_empty(),
            "{}: {} slow inputs",
            t.name,
            out.slow.len()
        );
    }
}

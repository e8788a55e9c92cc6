//! `merge` joins only shards of one run: shards whose options differ are refused by name.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

fn run(args: &[&str]) -> (i32, String) {
    let (code, _, err) = common::run(args, "");
    (code, err)
}

#[test]
fn shards_of_different_runs_are_not_merged() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let (code, err) = run(&["sweep", "--shard", "0/2", "--out", out]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = run(&[
        "sweep",
        "--shard",
        "1/2",
        "--interior",
        "membrane",
        "--out",
        out,
    ]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = run(&["merge", "--out", out]);
    assert_ne!(code, 0);
    assert!(err.contains("come from different runs"), "{err}");
    // The same options merge.
    let (code, err) = run(&["sweep", "--shard", "1/2", "--out", out]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = run(&["merge", "--out", out]);
    assert_eq!(code, 0, "{err}");
    let report = std::fs::read_to_string(dir.path().join("report.json")).unwrap();
    assert!(report.contains("\"options\""));
}

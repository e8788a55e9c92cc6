//! The hostile inputs of the reliability review, each a regression test: options out of range,
//! allocations the machine cannot hold, a closed standard error, upper-case and OFF files,
//! antiparallel tangents, the curve lines that used to take seconds, an output that is the input.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use std::process::Command;

use common::run;

#[test]
fn options_out_of_range_are_refused_with_the_range() {
    for (args, want) in [
        (
            vec!["fit", "--beta", "1e-308"],
            "--beta 1e-308: outside its valid range [0.01, 10]",
        ),
        (
            vec!["fit", "--c", "1e300"],
            "--c 1e300: outside its valid range [0.01, 100]",
        ),
        (
            vec!["fit", "--segments", "18446744073709551615"],
            "outside its valid range [1, 256]",
        ),
        (
            vec!["fit", "--segments", "1000"],
            "outside its valid range [1, 256]",
        ),
        (
            vec!["ring", "--segments", "0", "--output", "/tmp/x"],
            "outside its valid range [1, 256]",
        ),
    ] {
        let (code, _, err) = run(&args, "");
        assert_ne!(code, 0, "{args:?}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

#[test]
fn allocations_beyond_the_machine_are_refused_before_they_are_tried() {
    let (code, _, err) = run(
        &["ring", "--resolution", "4096", "--output", "/tmp/never"],
        "",
    );
    assert_ne!(code, 0);
    assert!(
        err.contains("would need about") && err.contains("GB"),
        "{err}"
    );
}

#[cfg(unix)]
#[test]
fn a_closed_standard_error_does_not_abort_the_run() {
    // `2>&-` closes the descriptor: every write to standard error fails.
    let status = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "'{}' fit --data octa >/dev/null 2>&-",
            env!("CARGO_BIN_EXE_experiments")
        ))
        .status()
        .unwrap();
    assert!(status.success(), "{status:?}");
}

#[test]
fn upper_case_extensions_and_off_files_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let off = dir.path().join("tetra.OFF");
    std::fs::write(
        &off,
        "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n",
    )
    .unwrap();
    let (code, _, err) = run(&["fit", "--data", off.to_str().unwrap()], "");
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("4 faces"), "{err}");
}

#[test]
fn antiparallel_tangents_are_flagged_and_slow_lines_answered() {
    let input = concat!(
        r#"{"t0":[1,0],"t1":[-1,0],"k0":0,"k1":0}"#,
        "\n",
        // Took 24 s before the quadrature had a budget.
        r#"{"t0":[0.9950041652780258,0.09983341664682815],"t1":[0.9950041652780258,-0.09983341664682815],"k0":10,"k1":0}"#,
        "\n",
        // Ran past five minutes.
        r#"{"t0":[0.6,0.8],"t1":[0.6,0.8],"k0":1.2e29,"k1":-3}"#,
        "\n"
    );
    let (code, out, err) = run(&["curve"], input);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[0]["methods"]["chord"]["overshoots_chord"], true);
    assert!(err.contains("curves overshooting their chord"), "{err}");
}

#[test]
fn curve_output_may_not_be_its_input() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("problems.jsonl");
    std::fs::write(&f, "{\"t0\":[1,0],\"t1\":[1,0],\"k0\":0,\"k1\":0}\n").unwrap();
    let f = f.to_str().unwrap();
    let (code, _, err) = run(&["curve", "--input", f, "--output", f], "");
    assert_ne!(code, 0);
    assert!(err.contains("the output is the input"), "{err}");
    assert!(std::fs::read_to_string(f).unwrap().contains("\"k0\":0"));
}

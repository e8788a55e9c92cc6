//! The exit status and the standard streams of the command language (docs/conventions.md, "The
//! command language"): 0 success, 1 a runtime error, 2 a usage error; `-` is standard output.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common::run;

/// Exit status of a usage error (the command line is wrong whatever the input).
const USAGE: i32 = 2;
/// Exit status of a runtime error (the input, the machine or an output refused).
const RUNTIME: i32 = 1;

#[test]
fn usage_errors_exit_with_status_2() {
    for args in [
        vec!["fit", "--no-such-option"],
        vec!["fit", "--data", "octa", "--segments", "1000"],
        vec!["fit", "--data", "octa", "--beta", "1e-308"],
        vec![
            "fit",
            "--data",
            "octa",
            "--scheme",
            "phong",
            "--phong-alpha",
            "1e308",
        ],
        vec!["fit", "--data", "torus"],
        vec!["fit", "--data", "octa", "--scheme", "no-such-scheme"],
        vec!["fit", "--data", "octa", "--mesh-output", "/tmp/x.xyz"],
        vec!["fit", "--data", "octa", "--output", "-", "--report", "-"],
        vec!["ring", "--segments", "0", "--output", "/tmp/never"],
        vec!["convert", "--data", "octa", "--output", "/tmp/x.unknown"],
    ] {
        let (code, _, err) = run(&args, "");
        assert_eq!(code, USAGE, "{args:?}: {err}");
        assert!(err.contains("error"), "{args:?}: {err}");
    }
}

#[test]
fn runtime_errors_exit_with_status_1() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.obj");
    std::fs::write(&empty, "v 0 0 0\nv 1 0 0\n").unwrap();
    for args in [
        vec!["fit", "--data", "no/such/file.obj"],
        vec!["fit", "--data", empty.to_str().unwrap()],
        vec!["ring", "--resolution", "4096", "--output", "/tmp/never"],
        vec!["fit", "--data", "octa", "--output", "/dev/null"],
    ] {
        let (code, _, err) = run(&args, "");
        assert_eq!(code, RUNTIME, "{args:?}: {err}");
    }
}

#[test]
fn a_dash_sends_the_patches_or_the_report_to_standard_output() {
    let (code, out, err) = run(&["fit", "--data", "octa", "--output", "-"], "");
    assert_eq!(code, 0, "{err}");
    let records: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect();
    // The octahedron's 8 faces, three Shirman–Séquin sub-patches each.
    assert_eq!(records.len(), 24);
    assert!(records.iter().all(|r| r["type"] == "BezierTriangle"));

    let (code, out, err) = run(&["fit", "--data", "octa", "--report", "-"], "");
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&out).expect("the report is JSON");
    assert_eq!(report["faces"], 8);
    assert_eq!(report["input"], "octa");
    // The human summary stays on standard error, with no progress drawn on it (it is not a
    // terminal here): no escape sequences.
    assert!(err.contains("G1"), "{err}");
    assert!(!err.contains('\u{1b}'), "{err:?}");
}

/// `ring -o LINK` where LINK is a symbolic link to a directory writes the results into the
/// directory the link names (it was refused as "exists and is not a directory"); the link
/// stays a link.
#[cfg(unix)]
#[test]
fn a_study_writes_through_a_link_to_a_directory() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("target");
    std::fs::create_dir(&target).unwrap();
    let link = dir.path().join("link");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let (code, _, err) = run(
        &[
            "ring",
            "--resolution",
            "6",
            "--segments",
            "2",
            "-o",
            link.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert!(target.join("report.json").is_file(), "{err}");
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
}

//! The pipeline's `fit` takes the curve constructions' options and the height-field mode as
//! `experiments fit` does (`fitjob::cli::CurveOptions`, `fitjob::cli::HeightFieldArgs`), and
//! they reach the fit.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use crate::support::{json_records, ok, testbed};

/// The first BezierTriangle's control points, flattened.
fn first_net(out: &[u8]) -> Vec<f64> {
    let recs = json_records(out);
    let t = recs
        .iter()
        .find(|r| r["type"] == "BezierTriangle")
        .expect("a patch");
    let mut v = Vec::new();
    for p in t["points"].as_array().expect("points") {
        for c in p.as_array().expect("a point") {
            v.push(c.as_f64().expect("a number"));
        }
    }
    v
}

#[test]
fn tweak_t_and_four_ninths_change_the_patches() {
    for (curves, option) in [
        ("tweak", ["--tweak-t", "0.3"].as_slice()),
        ("piper", &["--four-ninths"]),
    ] {
        let base = ["fit", "--data", "ring", "--curves", curves];
        let default = first_net(&ok(&base, b""));
        let args: Vec<&str> = base.iter().chain(option).copied().collect();
        let chosen = first_net(&ok(&args, b""));
        assert_eq!(default.len(), chosen.len());
        assert_ne!(default, chosen, "{curves} {option:?} changed nothing");
    }
}

#[test]
fn a_tweak_t_outside_its_range_is_a_usage_error() {
    let out = testbed(
        &[
            "fit",
            "--data",
            "ring",
            "--curves",
            "tweak",
            "--tweak-t",
            "1.5",
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("tweak-t"));
}

#[test]
fn heightfield_is_detected_required_and_refused() {
    let run = |extra: &[&str]| {
        let args: Vec<&str> = ["fit", "--data", "franke1", "--scheme", "clough-tocher"]
            .iter()
            .chain(extra)
            .copied()
            .collect();
        testbed(&args, b"")
    };
    let auto = run(&[]);
    let on = run(&["--heightfield"]);
    let off = run(&["--no-heightfield"]);
    for o in [&auto, &on, &off] {
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let said = |o: &std::process::Output| {
        String::from_utf8_lossy(&o.stderr).contains("detected a height field")
    };
    assert!(said(&auto) && said(&on) && !said(&off));
    assert_eq!(first_net(&auto.stdout), first_net(&on.stdout));
    assert_ne!(first_net(&on.stdout), first_net(&off.stdout));
    // The ring is no height field: required, it is an error.
    let ring = testbed(
        &[
            "fit",
            "--data",
            "ring",
            "--scheme",
            "clough-tocher",
            "--heightfield",
        ],
        b"",
    );
    assert_eq!(
        ring.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&ring.stderr)
    );
    assert!(String::from_utf8_lossy(&ring.stderr).contains("height field"));
}

//! Shell completions and man pages, generated from the parser's own command line.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common::run;

#[test]
fn completions_list_every_experiment_and_the_registry_names() {
    for shell in ["bash", "zsh", "fish"] {
        let (code, out, err) = run(&["completions", shell], "");
        assert_eq!(code, 0, "{shell}: {err}");
        for word in ["fit", "sweep", "segments", "mesh-output", "shirman-sequin"] {
            assert!(out.contains(word), "{shell}: no {word}");
        }
    }
    let (code, _, _) = run(&["completions", "tcsh-nope"], "");
    assert_eq!(code, 2, "an unknown shell is a usage error");
}

#[test]
fn man_pages_are_written_for_the_binary_and_each_experiment() {
    let dir = tempfile::tempdir().unwrap();
    let (code, _, err) = run(&["man", "--output", dir.path().to_str().unwrap()], "");
    assert_eq!(code, 0, "{err}");
    for page in ["experiments.1", "experiments-fit.1", "experiments-ring.1"] {
        let text = std::fs::read_to_string(dir.path().join(page)).expect(page);
        assert!(text.contains(".TH"), "{page}");
    }
    let fit = std::fs::read_to_string(dir.path().join("experiments-fit.1")).unwrap();
    assert!(fit.contains("segments"), "the fit page lists its options");
}

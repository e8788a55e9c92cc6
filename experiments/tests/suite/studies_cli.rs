//! The studies on hostile surroundings: a FIFO in a corpus directory, a golden-numbers file that
//! is not there, a study run outside the repository.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// How long a refusal may take: it comes before any mesh is read (a blocked read never ends).
const REFUSAL_WITHIN: Duration = Duration::from_secs(60);

/// Runs `experiments ARGS` in `cwd` with no standard input, killed after `limit`: exit code
/// (`None` when it had to be killed) and stderr.
fn run_within(args: &[&str], cwd: &Path, limit: Duration) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_experiments"))
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("runs");
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().expect("waits") {
            let out = child.wait_with_output().expect("finishes");
            return (
                status.code(),
                String::from_utf8_lossy(&out.stderr).into_owned(),
            );
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return (None, String::new());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// A FIFO named like a mesh in a corpus directory is refused by name before anything is
/// opened (reading it would block forever).
#[cfg(unix)]
#[test]
fn a_fifo_in_a_corpus_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let corpus = dir.path().join("corpus");
    std::fs::create_dir(&corpus).unwrap();
    std::fs::copy(
        crate::common::root().join("data/octa.m"),
        corpus.join("octa.m"),
    )
    .unwrap();
    let fifo = corpus.join("waiting.ply");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let out = dir.path().join("out");
    let (code, err) = run_within(
        &[
            "realmesh",
            "--corpus",
            corpus.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        dir.path(),
        REFUSAL_WITHIN,
    );
    let code = code.expect("refused, not blocked on the FIFO");
    assert_ne!(code, 0);
    assert!(
        err.contains("waiting.ply: not a regular file (a FIFO)"),
        "{err}"
    );
    assert!(!out.exists());
}

/// A golden-numbers file that is not there is an error naming it (it used to be dropped with
/// a warning, the libigl columns left empty and the run ending "goal missed on []").
#[test]
fn a_missing_golden_file_is_an_error_not_empty_columns() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let (code, err) = run_within(
        &[
            "estimation",
            "--golden",
            "/nonexistent/golden.json",
            "-o",
            out.to_str().unwrap(),
        ],
        dir.path(),
        REFUSAL_WITHIN,
    );
    assert_ne!(code.expect("refused at once"), 0);
    assert!(
        err.contains("cannot read /nonexistent/golden.json"),
        "{err}"
    );
    assert!(!out.exists());
}

/// `realmesh` run outside the repository finds its committed corpus (and lists it) before it
/// refuses an output that is a regular file, which it leaves as it was.
#[test]
fn realmesh_outside_the_repository_finds_its_corpus_before_refusing_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("a-file");
    std::fs::write(&file, "mine\n").unwrap();
    let (code, err) = run_within(
        &["realmesh", "-o", file.to_str().unwrap()],
        dir.path(),
        REFUSAL_WITHIN,
    );
    assert_ne!(code.expect("refused at once"), 0);
    // Not "cannot read data/meshes": the corpus was found and listed; the output is refused.
    assert!(err.contains("exists and is not a directory"), "{err}");
    assert!(!err.contains("data/meshes"), "{err}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine\n");
}

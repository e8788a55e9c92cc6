//! What the pipeline's integration tests share: running the `testbed` binary on bytes, and
//! reading JSON Lines back.

#![allow(clippy::expect_used)] // test fixtures fail loudly by design

use std::io::Write;
use std::process::{Command, Output, Stdio};

use serde_json::Value;

/// `args` in the forms most tests read as text: `fit` writes JSON Lines unless `--format` is
/// given (its default into a pipe is the binary form), and `tess` and a sampling `fit` the
/// seed's `Triangle` records unless `--mesh` or `--triangles` is (their default is one
/// `TriangleMesh` per patch).
/// The defaults themselves are tested with [`testbed_as_given`].
pub fn seed_forms<'a>(args: &[&'a str]) -> Vec<&'a str> {
    let mut out = args.to_vec();
    let has = |flag: &str| {
        args.iter()
            .any(|a| *a == flag || a.starts_with(&format!("{flag}=")))
    };
    match args.first() {
        Some(&"fit") => {
            if !has("--format") {
                out.extend(["--format", "json"]);
            }
            if !has("--mesh") && !has("--triangles") {
                out.push("--triangles");
            }
        }
        Some(&"tess") if !has("--mesh") && !has("--triangles") => out.push("--triangles"),
        _ => {}
    }
    out
}

/// `testbed ARGS` (in the seed's forms, [`seed_forms`]) with `input` on its standard input
/// (written from another thread, so a filter that fails early and closes its input cannot
/// block the test).
pub fn testbed(args: &[&str], input: &[u8]) -> Output {
    testbed_as_given(&seed_forms(args), input)
}

/// `testbed ARGS` exactly as given, with `input` on its standard input.
pub fn testbed_as_given(args: &[&str], input: &[u8]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_testbed"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    let mut stdin = child.stdin.take().expect("stdin");
    let data = input.to_vec();
    let writer = std::thread::spawn(move || {
        // A filter that fails early closes its input: a broken pipe here is expected.
        let _ = stdin.write_all(&data);
    });
    let out = child.wait_with_output().expect("runs");
    let _ = writer.join();
    out
}

/// `testbed ARGS` (in the seed's forms, [`seed_forms`]) that must succeed: its standard
/// output.
pub fn ok(args: &[&str], input: &[u8]) -> Vec<u8> {
    ok_as_given(&seed_forms(args), input)
}

/// `testbed ARGS` exactly as given, which must succeed: its standard output.
pub fn ok_as_given(args: &[&str], input: &[u8]) -> Vec<u8> {
    let out = testbed_as_given(args, input);
    assert!(
        out.status.success(),
        "testbed {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// The records of a JSON Lines stream.
pub fn json_records(bytes: &[u8]) -> Vec<Value> {
    bytes
        .split(|&c| c == b'\n')
        .filter(|l| !l.is_empty())
        .map(|l| serde_json::from_slice(l).expect("json line"))
        .collect()
}

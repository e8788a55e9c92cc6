//! Bounded work on every stream: what a stream can make a filter hold or produce is checked
//! against a stated limit, named in the refusal. Each hostile stream is built here, at the
//! size of the limit itself (nothing is lowered for the test): a line or record longer than a
//! record may be, a binary template of constants that would expand a 5-byte record to a
//! megabyte, schemas that would hold more than their budget, a record the output format
//! would make too long; the colouring filters pass records through at once while they hold
//! nothing, hold the rest within their budget, and fail on a stream with nothing to colour.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use std::io::{Read, Write};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use serde_json::Value;
use testbed::binary::{EXPANSION_ALLOWANCE, MAGIC, MAX_EXPANSION, MAX_SCHEMA_MEMORY};
use testbed::hold::HELD_BYTES;
use testbed::stream::{Format, RecordWriter, MAX_RECORD_BYTES, MAX_RECORD_TOKENS};
use testbed::Position;

use crate::support::{json_records, ok, testbed};

fn octa() -> Vec<u8> {
    std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m")).expect("octa.m")
}

/// The stderr of a run, as text.
fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A binary stream block declaring a schema (`S`, its length, its JSON text).
fn schema_block(template: &str, slots: &str) -> Vec<u8> {
    let doc = format!("{{\"template\":{template},\"slots\":\"{slots}\"}}");
    let mut out = vec![b'S'];
    out.extend_from_slice(&(doc.len() as u32).to_le_bytes());
    out.extend_from_slice(doc.as_bytes());
    out
}

/// A binary record block of schema `id` with `slots` bytes.
fn record_block(id: u32, slots: &[u8]) -> Vec<u8> {
    let mut out = vec![b'R'];
    out.extend_from_slice(&id.to_le_bytes());
    out.extend_from_slice(slots);
    out
}

/// Records written in `format` by the library's writer.
fn stream_of(records: &[Value], format: Format) -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut w = RecordWriter::new(&mut bytes, Some(format));
    for r in records {
        w.write(r, Position::default()).expect("writes");
    }
    w.finish().expect("flushes");
    drop(w);
    bytes
}

/// A Triangle with a Gaussian curvature at each vertex (what `kcolor` colours).
fn triangle(k: f64) -> Value {
    let v = |x: f64| serde_json::json!({"pos": [x, 0.0, 1.0], "norm": [0.0, 0.0, 1.0], "kg": k});
    serde_json::json!({"type": "Triangle", "vertex1": v(0.0), "vertex2": v(1.0), "vertex3": v(2.0)})
}

/// `fit | kcolor`, `tess` forgotten: every colouring filter passes the patches through
/// unchanged and then fails (exit 1), naming what the stream held and the likely cause; an
/// empty stream is said to be empty. The filters exited 0 with the patches (or nothing).
#[test]
fn a_colouring_filter_with_nothing_to_colour_passes_the_records_and_fails_naming_tess() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let n = json_records(&patches).len();
    for args in [
        &["kcolor"][..],
        &["kcolor", "--range", "-1:1"],
        &["radial", "--surface", "sphere"],
        &["mat0"],
    ] {
        let out = testbed(args, &patches);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(&format!("the stream held {n} BezierTriangle"))
                && err.contains(&format!("put `tess` before `{}`", args[0])),
            "{args:?}: {err}"
        );
        assert_eq!(out.stdout, patches, "{args:?}: the records pass through");
        let out = testbed(args, b"");
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(
            stderr(&out).contains("the stream is empty"),
            "{}",
            stderr(&out)
        );
    }
}

/// While it holds nothing, `kcolor` writes records of other kinds as they come: the first of
/// them reach its output while its input is still open (it held the whole stream until its
/// end, waiting for triangles that never came).
#[test]
fn kcolor_writes_records_it_need_not_hold_before_its_input_ends() {
    /// Bytes written before waiting: four times the 64 KiB the writer buffers, so output is
    /// due.
    const BEFORE_WAITING: usize = 4 << 16;
    /// How long the output may take to appear (a debug build under load answers in
    /// milliseconds; the old filter never answered before the end of its input).
    const PATIENCE: Duration = Duration::from_secs(60);
    let patches = ok(&["fit", "--scheme", "flat"], &octa());
    let copies = BEFORE_WAITING / patches.len() + 1;
    let mut child = Command::new(env!("CARGO_BIN_EXE_testbed"))
        .arg("kcolor")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    let mut stdin = child.stdin.take().expect("stdin");
    let mut stdout = child.stdout.take().expect("stdout");
    let (first_tx, first_rx) = mpsc::channel();
    let reader = std::thread::spawn(move || {
        let mut buf = vec![0u8; 1024];
        let n = stdout.read(&mut buf).unwrap_or(0);
        let _ = first_tx.send(n);
        let mut rest = Vec::new();
        let _ = stdout.read_to_end(&mut rest);
        n + rest.len()
    });
    for _ in 0..copies {
        stdin.write_all(&patches).expect("written");
    }
    stdin.flush().expect("flushed");
    let first = first_rx.recv_timeout(PATIENCE);
    drop(stdin);
    let total = reader.join().expect("reader");
    let status = child.wait().expect("waits");
    assert!(
        matches!(first, Ok(n) if n > 0),
        "no output before the end of the input: {first:?}"
    );
    assert_eq!(total, copies * patches.len(), "every record passed");
    assert_eq!(status.code(), Some(1), "nothing to colour");
}

/// A triangle, then more than the budget of other records: what `kcolor` holds until its range
/// is fixed past [`HELD_BYTES`] goes to a temporary file (said on stderr), which is gone when
/// the filter ends; the records come out in order, the triangle coloured. The filter held
/// them all in memory.
#[test]
fn records_held_past_the_budget_wait_in_a_temporary_file_and_keep_their_order() {
    /// Size of each note's string: a mebibyte, so the budget is passed after 64 notes.
    const NOTE_BYTES: usize = 1 << 20;
    let notes = HELD_BYTES / NOTE_BYTES + 8;
    let text = "n".repeat(NOTE_BYTES);
    let mut records = vec![triangle(1.0)];
    records.extend((0..notes).map(|i| serde_json::json!({"type": "Note", "i": i, "s": text})));
    records.push(triangle(-1.0));
    let input = stream_of(&records, Format::Binary);
    let tmp = tempfile::tempdir().expect("dir");
    let out = {
        let mut child = Command::new(env!("CARGO_BIN_EXE_testbed"))
            .args(["kcolor", "--format", "json"])
            .env("TMPDIR", tmp.path())
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawns");
        let mut stdin = child.stdin.take().expect("stdin");
        let writer = std::thread::spawn(move || {
            let _ = stdin.write_all(&input);
        });
        let out = child.wait_with_output().expect("runs");
        writer.join().expect("writer");
        out
    };
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains(&format!("passed {} MiB", HELD_BYTES >> 20)) && err.contains("temporary file"),
        "{err}"
    );
    let back = json_records(&out.stdout);
    assert_eq!(back.len(), records.len());
    assert!(back[0]["vertex1"]["color"].is_array());
    assert!(back[notes + 1]["vertex3"]["color"].is_array());
    for (i, r) in back[1..=notes].iter().enumerate() {
        assert_eq!(r["i"], i, "in order");
        assert_eq!(r["s"].as_str().map(str::len), Some(NOTE_BYTES));
    }
    let left: Vec<_> = std::fs::read_dir(tmp.path()).expect("dir").collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

/// A 1 MiB template of `null`s with no slot: every 5-byte record of it would be 5 MB in memory
/// and 1 MiB of JSON (2 000 of them held 8 GB in `kcolor` and aborted; 20 000 became 21 GB of
/// JSON through `mat0`). Refused when the schema is declared, naming the limit, before any
/// record is decoded, by every filter.
#[test]
fn a_binary_template_of_constants_is_refused_before_its_records_expand() {
    /// Records of the hostile schema in the stream (each 5 bytes).
    const RECORDS: usize = 20;
    /// The schema's text: 1 MiB, the most the former limit allowed.
    const SCHEMA_TEXT: usize = 1 << 20;
    let nulls = vec!["null"; (SCHEMA_TEXT - 64) / 5].join(",");
    let mut input = MAGIC.to_vec();
    input.extend(schema_block(
        &format!("{{\"type\":\"X\",\"a\":[{nulls}]}}"),
        "",
    ));
    assert!(input.len() <= MAGIC.len() + 5 + SCHEMA_TEXT);
    for _ in 0..RECORDS {
        input.extend(record_block(0, &[]));
    }
    let limit = format!("at most {MAX_EXPANSION} × its size + {EXPANSION_ALLOWANCE} bytes");
    for args in [
        &["kcolor"][..],
        &["mat0", "--format", "json"],
        &["g1", "--format", "json"],
    ] {
        let out = testbed(args, &input);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains("record 1: schema 0: a record of 5 bytes (0 slots)")
                && err.contains(&limit),
            "{args:?}: {err}"
        );
        assert!(out.stdout.is_empty(), "{args:?}: nothing written");
    }
}

/// Schemas that each pass but together would hold more than [`MAX_SCHEMA_MEMORY`]: refused at
/// the first past the budget, naming it (65 536 schemas of 1 MiB of text each were allowed,
/// 12.6 MB each in memory: over 800 GB of templates).
#[test]
fn schemas_holding_more_than_their_budget_are_refused() {
    /// Numbers in each template: 2 bytes of text each, 24 bytes in memory as tokens.
    const NUMBERS: usize = 1 << 18;
    let zeros = vec!["0"; NUMBERS].join(",");
    let slots = "i".repeat(NUMBERS);
    let per_schema = NUMBERS * (std::mem::size_of::<testbed::tape::Tok>() + 13);
    let count = MAX_SCHEMA_MEMORY / per_schema + 1;
    let mut input = MAGIC.to_vec();
    for k in 0..count {
        input.extend(schema_block(
            &format!("{{\"type\":\"X{k}\",\"a\":[{zeros}]}}"),
            &slots,
        ));
    }
    let out = testbed(&["g1", "--format", "json"], &input);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(&format!(
            "more than the {MAX_SCHEMA_MEMORY} bytes ({} MiB) a stream's schemas may hold together",
            MAX_SCHEMA_MEMORY >> 20
        )),
        "{err}"
    );
}

/// A binary record whose strings together pass [`MAX_RECORD_BYTES`] (each within the 16 MiB
/// a string may have): refused before the last is read.
#[test]
fn binary_strings_past_the_record_limit_are_refused() {
    /// String slots of the record, each a quarter of the limit (16 MiB, the most a string
    /// may have): together more than the limit.
    const STRINGS: usize = 5;
    let each = MAX_RECORD_BYTES / (STRINGS - 1);
    let mut input = MAGIC.to_vec();
    let template = format!("{{\"type\":\"X\",\"s\":[{}]}}", ["\"\""; STRINGS].join(","));
    input.extend(schema_block(&template, &"s".repeat(STRINGS)));
    let mut slots = Vec::new();
    for _ in 0..STRINGS {
        slots.extend_from_slice(&(each as u32).to_le_bytes());
        slots.extend(std::iter::repeat_n(b'a', each));
    }
    input.extend(record_block(0, &slots));
    let out = testbed(&["g1", "--format", "json"], &input);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(&format!(
            "record 1: the record's strings and keys exceed {MAX_RECORD_BYTES} bytes"
        )),
        "{err}"
    );
}

/// A JSON line one byte longer than a record may be, between two good ones: refused as it is
/// read, naming the record, its line and the limit; with `--keep-going` it is passed over and
/// the lines after it keep their numbers. (A 300 MB line took 4.3 GB.)
#[test]
fn a_json_line_longer_than_a_record_may_be_is_refused_and_passed_over() {
    let good = serde_json::to_string(&triangle(1.0)).unwrap();
    let prefix = "{\"type\":\"Note\",\"s\":\"";
    let suffix = "\"}";
    let fill = MAX_RECORD_BYTES + 1 - prefix.len() - suffix.len();
    let mut input = format!("{good}\n").into_bytes();
    input.extend_from_slice(prefix.as_bytes());
    input.extend(std::iter::repeat_n(b'a', fill));
    input.extend_from_slice(suffix.as_bytes());
    input.extend_from_slice(format!("\n{{\"type\":\n{good}\n").as_bytes());
    let limit = format!("the line is longer than {MAX_RECORD_BYTES} bytes");
    let out = testbed(&["mat0"], &input);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(&format!("record 2 (line 2): {limit}")),
        "{err}"
    );
    let out = testbed(&["mat0", "--keep-going"], &input);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains(&format!("skipped record 2 (line 2): {limit}"))
            && err.contains("record 3 (line 3): bad JSON")
            && err.contains("2 bad record(s) skipped"),
        "{err}"
    );
    assert_eq!(json_records(&out.stdout).len(), 2);
    // A line of exactly the limit is a record like any other.
    let mut exact = prefix.as_bytes().to_vec();
    exact.extend(std::iter::repeat_n(b'a', fill - 1));
    exact.extend_from_slice(suffix.as_bytes());
    assert_eq!(exact.len(), MAX_RECORD_BYTES);
    exact.extend_from_slice(format!("\n{good}\n").as_bytes());
    let out = testbed(&["mat0"], &exact);
    assert!(out.status.success(), "{}", stderr(&out));
}

/// The same for a dstruct record (any layout: the record runs from its `(` to its `;`, here
/// over two lines), passed over up to its `;` with `--keep-going`.
#[test]
fn a_dstruct_record_longer_than_a_record_may_be_is_refused_and_passed_over() {
    let good = "(Triangle . (vertex1 . (pos . [0, 0, 0])) (vertex2 . (pos . [1, 0, 0])) (vertex3 . (pos . [0, 1, 0])));";
    let mut input = format!("{good}\n(Note . (s . \"").into_bytes();
    input.extend(std::iter::repeat_n(b'a', MAX_RECORD_BYTES));
    // A `;` inside the string does not end the record.
    input.extend_from_slice(b";\")\n (t . 1));\n(Bad . (x . ));\n");
    input.extend_from_slice(good.as_bytes());
    let limit = format!("the record is longer than {MAX_RECORD_BYTES} bytes");
    let out = testbed(&["mat0"], &input);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(&format!("record 2 (line 2): {limit}")),
        "{err}"
    );
    let out = testbed(&["mat0", "--keep-going"], &input);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains(&format!("skipped record 2 (line 2): {limit}"))
            && err.contains("record 3 (line 4)")
            && err.contains("2 bad record(s) skipped"),
        "{err}"
    );
    assert_eq!(out.stdout.iter().filter(|&&c| c == b';').count(), 2);
}

/// A short line of many values: one more token than a record may hold is refused in both
/// text formats, naming the limit (it parsed, 24 bytes a token for 2 bytes of text).
#[test]
fn a_record_of_more_tokens_than_the_limit_is_refused_in_every_text_format() {
    // The object, `type` and its value, the key `a` and the array: 5 tokens besides the zeros.
    let zeros = vec!["0"; MAX_RECORD_TOKENS - 4].join(",");
    let json = format!("{{\"type\":\"Note\",\"a\":[{zeros}]}}\n");
    let dstruct = format!("(Note . (a . [{zeros}]));\n");
    for input in [json, dstruct] {
        let out = testbed(&["g1"], input.as_bytes());
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(
            err.contains("record 1 (line 1)")
                && err.contains(&format!("more than {MAX_RECORD_TOKENS} values")),
            "{err}"
        );
    }
    // One token fewer is a record.
    let zeros = vec!["0"; MAX_RECORD_TOKENS - 5].join(",");
    let json = format!("{{\"type\":\"Note\",\"a\":[{zeros}]}}\n");
    assert_eq!(ok(&["g1"], json.as_bytes()), json.as_bytes());
}

/// A record the output format would make longer than a record may be (a 12 MiB string of
/// control characters: 12 MiB in binary, 72 MiB escaped in JSON) is not written: no reader
/// would take it back. It was written.
#[test]
fn a_record_too_long_for_the_output_format_is_not_written() {
    /// Characters of the string: each `\u0001` is 6 bytes of JSON.
    const CHARS: usize = 12 << 20;
    let note = serde_json::json!({"type": "Note", "s": "\u{1}".repeat(CHARS)});
    let input = stream_of(&[note], Format::Binary);
    let out = testbed(&["g1", "--format", "json"], &input);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("record 1: cannot write as json: the record would be")
            && err.contains(&format!("longer than the {MAX_RECORD_BYTES} bytes")),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}

/// `--block` beyond the most a block holds is a usage error naming the range (exit 2); the
/// held budget `--help` states is the one the filters use.
#[test]
fn block_sizes_are_bounded_and_the_budget_is_stated() {
    let max = testbed::binders::MAX_BLOCK;
    for filter in [&["kcolor"][..], &["radial", "--surface", "sphere"]] {
        let too_many = (max + 1).to_string();
        let args = [filter, &["--block", &too_many]].concat();
        let out = testbed(&args, b"");
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&out).contains(&format!("0..={max}")),
            "{}",
            stderr(&out)
        );
        let help = ok(&[filter, &["--help"]].concat(), b"");
        let help = String::from_utf8_lossy(&help);
        assert!(
            help.contains(&format!("{} MiB", HELD_BYTES >> 20)) && help.contains(&max.to_string()),
            "{help}"
        );
    }
}

/// `tess --mesh -s 256` in the binary form writes a 1.5 MB template, which the former 1 MiB
/// schema limit refused: every filter now reads it.
#[test]
fn large_mesh_records_in_the_binary_form_read_back() {
    let patch: Vec<u8> = ok(&["fit", "--scheme", "flat"], &octa())
        .split_inclusive(|&c| c == b'\n')
        .next()
        .unwrap()
        .to_vec();
    let mesh = ok(
        &["tess", "-s", "256", "--kg", "--mesh", "--format", "binary"],
        &patch,
    );
    let coloured = ok(&["mat0", "--format", "json"], &mesh);
    let r = &json_records(&coloured)[0];
    assert_eq!(r["pos"].as_array().map(Vec::len), Some(257 * 258 / 2));
    assert_eq!(r["color"].as_array().map(Vec::len), Some(257 * 258 / 2));
}

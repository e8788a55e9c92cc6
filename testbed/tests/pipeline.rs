//! The filters as processes: pass-through of unknown fields, formats, errors naming the record,
//! `--keep-going`, and hostile streams (truncated, mutated) that must never panic.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use std::io::Write;
use std::process::{Command, Output, Stdio};

use serde_json::Value;

fn testbed(args: &[&str], input: &[u8]) -> Output {
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

fn ok(args: &[&str], input: &[u8]) -> Vec<u8> {
    let out = testbed(args, input);
    assert!(
        out.status.success(),
        "testbed {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

fn octa() -> Vec<u8> {
    std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m")).expect("octa.m")
}

fn json_records(bytes: &[u8]) -> Vec<Value> {
    bytes
        .split(|&c| c == b'\n')
        .filter(|l| !l.is_empty())
        .map(|l| serde_json::from_slice(l).expect("json line"))
        .collect()
}

/// Patches of the octahedron with a `provenance` field added after the known ones.
fn patches_with_provenance() -> Vec<u8> {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let mut out = Vec::new();
    for mut v in json_records(&patches) {
        v.as_object_mut()
            .expect("object")
            .insert("provenance".into(), Value::from("octa.m via test"));
        serde_json::to_writer(&mut out, &v).expect("json");
        out.push(b'\n');
    }
    out
}

#[test]
fn a_field_added_at_the_head_arrives_at_the_end_in_every_format() {
    let patches = patches_with_provenance();
    for format in ["json", "dstruct", "binary"] {
        let s1 = ok(&["g1", "--format", format], &patches);
        let s2 = ok(&["tess", "-s", "2", "--kg"], &s1);
        let s3 = ok(&["mat0"], &s2);
        let s4 = ok(&["kcolor"], &s3);
        let s5 = ok(&["radial", "--surface", "sphere", "--format", "json"], &s4);
        let recs = json_records(&s5);
        assert_eq!(recs.len(), 24 * 4, "{format}");
        for r in &recs {
            let keys: Vec<&str> = r
                .as_object()
                .expect("object")
                .keys()
                .map(String::as_str)
                .collect();
            assert_eq!(
                keys,
                [
                    "type",
                    "vertex1",
                    "vertex2",
                    "vertex3",
                    "face",
                    "subpatch",
                    "scheme",
                    "provenance"
                ],
                "{format}"
            );
            assert_eq!(r["provenance"], "octa.m via test");
            let v: Vec<&str> = r["vertex2"]
                .as_object()
                .expect("vertex")
                .keys()
                .map(String::as_str)
                .collect();
            assert_eq!(v, ["pos", "norm", "kg", "color", "dist"], "{format}");
        }
    }
}

/// Records of a kind no filter knows, and unknown fields before, between and inside the
/// vertices of Triangles, in every format and through every filter: unchanged, in order.
#[test]
fn unknown_records_and_fields_pass_every_filter_in_every_format() {
    let note = r#"{"type":"Note","text":"a \"quoted\" note","n":[1,-2,18446744073709551615],"o":{"deep":[[],{}]},"b":true,"z":null}"#;
    let tri = r#"{"type":"Triangle","name":"t0","vertex1":{"label":"a","pos":[0,0,0],"kg":0.5,"norm":[0,0,1]},"vertex2":{"pos":[1,0,0],"kg":-0.25,"extra":{"k":[1.5]}},"vertex3":{"pos":[0,1,0],"kg":0.0},"provenance":"head"}"#;
    let patch = r#"{"type":"BezierTriangle","note":"first","degree":1,"points":[[0,0,0],[1,0,0],[0,1,0]],"provenance":"head"}"#;
    let input = format!("{note}\n{tri}\n{patch}\n{note}\n");
    let expected_note: Value = serde_json::from_str(note).expect("json");
    for format in ["json", "dstruct", "binary"] {
        let start = ok(&["g1", "--format", format], input.as_bytes());
        for args in [
            &["g1"][..],
            &["tess", "-s", "1", "--kg"],
            &["mat0"],
            &["kcolor"],
            &["kcolor", "--range", "-1:1"],
            &["radial", "--surface", "sphere"],
        ] {
            let out = ok(args, &start);
            let recs = json_records(&ok(&["g1", "--format", "json"], &out));
            let kinds: Vec<&str> = recs.iter().map(|r| r["type"].as_str().unwrap()).collect();
            let expect_kinds = if args[0] == "tess" {
                ["Note", "Triangle", "Triangle", "Note"]
            } else {
                ["Note", "Triangle", "BezierTriangle", "Note"]
            };
            assert_eq!(kinds, expect_kinds, "{format} {args:?}");
            assert_eq!(recs[0], expected_note, "{format} {args:?}");
            assert_eq!(recs[3], expected_note, "{format} {args:?}");
            let t = &recs[1];
            let keys: Vec<&str> = t.as_object().unwrap().keys().map(String::as_str).collect();
            assert_eq!(
                keys,
                [
                    "type",
                    "name",
                    "vertex1",
                    "vertex2",
                    "vertex3",
                    "provenance"
                ],
                "{format} {args:?}"
            );
            assert_eq!(t["vertex1"]["label"], "a");
            assert_eq!(t["vertex2"]["extra"]["k"][0], 1.5);
            let v1: Vec<&str> = t["vertex1"]
                .as_object()
                .unwrap()
                .keys()
                .map(String::as_str)
                .collect();
            assert_eq!(
                &v1[..4],
                ["label", "pos", "kg", "norm"],
                "{format} {args:?}"
            );
            if args[0] == "tess" {
                // The patch's triangle: vertices first, then the patch's other fields.
                let keys: Vec<&str> = recs[2]
                    .as_object()
                    .unwrap()
                    .keys()
                    .map(String::as_str)
                    .collect();
                assert_eq!(
                    keys,
                    [
                        "type",
                        "vertex1",
                        "vertex2",
                        "vertex3",
                        "note",
                        "provenance"
                    ]
                );
            } else {
                assert_eq!(recs[2]["note"], "first");
                assert_eq!(recs[2]["provenance"], "head");
            }
        }
    }
}

/// `kcolor` without `--range` fixes the range from the first `--block` triangles and streams
/// the rest; records keep their order; `--block 0` (the whole stream) matches the range of
/// a block as long as the stream.
#[test]
fn kcolor_fixes_its_range_from_a_first_block_and_keeps_the_order() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let tris = ok(&["tess", "-s", "2", "--kg"], &patches);
    let n = json_records(&tris).len();
    let note = b"{\"type\":\"Note\",\"i\":1}\n";
    let mut input = note.to_vec();
    input.extend_from_slice(&tris);
    input.extend_from_slice(note);
    let whole = testbed(&["kcolor", "--block", "0"], &input);
    let long = testbed(&["kcolor", "--block", &n.to_string()], &input);
    assert_eq!(whole.stdout, long.stdout);
    assert!(String::from_utf8_lossy(&whole.stderr).contains("over the whole stream"));
    let small = testbed(&["kcolor", "--block", "5"], &input);
    assert!(small.status.success());
    assert!(String::from_utf8_lossy(&small.stderr).contains("over the first 5 triangles"));
    let recs = json_records(&small.stdout);
    assert_eq!(recs.len(), n + 2);
    assert_eq!(recs[0]["type"], "Note");
    assert_eq!(recs[n + 1]["type"], "Note");
    assert!(recs[1..=n].iter().all(|r| r["vertex1"]["color"]
        .as_array()
        .is_some_and(|c| c.len() == 3)));
}

#[test]
fn g1_passes_records_unchanged_and_strict_fails_only_on_creases() {
    let patches = patches_with_provenance();
    assert_eq!(ok(&["g1", "--strict"], &patches), patches);
    let out = testbed(&["g1"], &patches);
    assert!(String::from_utf8_lossy(&out.stderr).contains("within tolerance"));
    let flat = ok(&["fit", "--scheme", "flat"], &octa());
    let out = testbed(&["g1", "--strict"], &flat);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("not G1"));
    assert_eq!(out.stdout, flat, "records still pass through");
}

#[test]
fn dstruct_of_figure_1_is_read() {
    let fig1 = br#"(Triangle . (name . "tri-0")
           (vertex1 . (pos . [-1, 0, 0]) (norm . [-1, 0, 0]))
           (vertex2 . (pos . [0, 0, -1]) (norm . [0, 0, -1]))
           (vertex3 . (pos . [0, -1, 0]) (norm . [0, -1, 0])));"#;
    let out = ok(&["mat0"], fig1);
    let text = String::from_utf8(out.clone()).expect("utf-8");
    assert!(text.starts_with("(Triangle . (name . \"tri-0\") (vertex1 . (pos . [-1, 0, 0]) (norm . [-1, 0, 0]) (color . ["), "{text}");
    let json = ok(&["mat0", "--format", "json"], &out);
    let r = &json_records(&json)[0];
    assert_eq!(r["name"], "tri-0");
    assert!(r["vertex3"]["color"].is_array());
}

#[test]
fn malformed_records_are_named_and_skipped_with_keep_going() {
    let good = r#"{"type":"Triangle","vertex1":{"pos":[0,0,0]},"vertex2":{"pos":[1,0,0]},"vertex3":{"pos":[0,1,0]}}"#;
    let missing = r#"{"type":"Triangle","vertex1":{"pos":[0,0,0]},"vertex2":{"pos":[1,0]},"vertex3":{"pos":[0,1,0]}}"#;
    let input = format!("{good}\n{missing}\n{{\"type\":\n{good}\n");
    let out = testbed(&["mat0"], input.as_bytes());
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("record 2 (line 2)") && err.contains("vertex2.pos"),
        "{err}"
    );
    let out = testbed(&["mat0", "--keep-going"], input.as_bytes());
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("record 3 (line 3)") && err.contains("2 bad record(s) skipped"),
        "{err}"
    );
    assert_eq!(json_records(&out.stdout).len(), 2);
    let out = testbed(&["kcolor"], good.as_bytes());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("kg") && err.contains("record 1"),
        "{err}"
    );
}

/// Deterministic pseudo-random numbers (xorshift), so failures reproduce.
fn xorshift(state: &mut u64) -> u64 {
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    *state
}

#[test]
fn truncated_and_mutated_streams_never_panic() {
    let patches = ok(&["fit", "--scheme", "flat"], &octa());
    let mut streams = Vec::new();
    for format in ["json", "dstruct", "binary"] {
        let tris = ok(&["tess", "-s", "1", "--kg", "--format", format], &patches);
        streams.push(tris);
        streams.push(ok(&["g1", "--format", format], &patches));
    }
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    // Panics exit with 101; errors with 1.
    const PANIC_STATUS: i32 = 101;
    for s in &streams {
        let mut cases: Vec<Vec<u8>> = (1..8).map(|k| s[..s.len() * k / 8].to_vec()).collect();
        for _ in 0..12 {
            let mut m = s.clone();
            for _ in 0..4 {
                let i = (xorshift(&mut seed) as usize) % m.len();
                m[i] = (xorshift(&mut seed) & 0xff) as u8;
            }
            cases.push(m);
        }
        for case in &cases {
            for args in [
                &["tess", "-s", "2", "--keep-going"][..],
                &["g1"],
                &["kcolor", "--keep-going"],
                &["render", "--size", "40x30"],
            ] {
                let out = testbed(args, case);
                assert_ne!(
                    out.status.code(),
                    Some(PANIC_STATUS),
                    "{args:?} panicked: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
            }
        }
    }
}

#[test]
fn fit_reads_any_mesh_format_from_standard_input() {
    let tris = ok(&["fit", "--scheme", "flat", "--sample", "1"], &octa());
    let dir = tempfile::tempdir().expect("dir");
    let ply = dir.path().join("octa.ply");
    ok(&["to-mesh", "--out", ply.to_str().expect("utf-8")], &tris);
    let bytes = std::fs::read(&ply).expect("ply written");
    let again = ok(&["fit", "--scheme", "flat"], &bytes);
    assert_eq!(json_records(&again).len(), 8);
}

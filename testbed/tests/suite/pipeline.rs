//! The filters as processes: pass-through of unknown fields, formats, errors naming the record,
//! `--keep-going`, and hostile streams (truncated, mutated) that must never panic.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use serde_json::Value;

use crate::support::{json_records, ok, ok_as_given, testbed};

fn octa() -> Vec<u8> {
    std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m")).expect("octa.m")
}

/// The top-level keys of record `r`, in order.
fn keys(r: &Value) -> Vec<&str> {
    r.as_object()
        .expect("object")
        .keys()
        .map(String::as_str)
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
        // Shared-vertex records: the columns first, the carried fields, the colours appended.
        let s1 = ok(&["g1", "--format", format], &patches);
        let s2 = ok(&["tess", "-s", "2", "--kg", "--mesh"], &s1);
        let s3 = ok(&["mat0"], &s2);
        let s4 = ok(&["kcolor"], &s3);
        let s5 = ok(&["radial", "--surface", "sphere", "--format", "json"], &s4);
        let recs = json_records(&s5);
        assert_eq!(recs.len(), 24, "{format}");
        for r in &recs {
            assert_eq!(
                keys(r),
                [
                    "type",
                    "pos",
                    "norm",
                    "kg",
                    "triangles",
                    "face",
                    "subpatch",
                    "scheme",
                    "provenance",
                    "color",
                    "dist"
                ],
                "{format}"
            );
            assert_eq!(r["type"], "TriangleMesh");
            assert_eq!(r["provenance"], "octa.m via test");
            // s = 2: 6 vertices, 4 triangles; one colour and one distance per vertex.
            assert_eq!(r["pos"].as_array().map(Vec::len), Some(6), "{format}");
            assert_eq!(r["triangles"].as_array().map(Vec::len), Some(4), "{format}");
            assert_eq!(r["color"].as_array().map(Vec::len), Some(6), "{format}");
            assert_eq!(r["dist"].as_array().map(Vec::len), Some(6), "{format}");
        }
    }
    for format in ["json", "dstruct", "binary"] {
        let s1 = ok(&["g1", "--format", format], &patches);
        let s2 = ok(&["tess", "-s", "2", "--kg"], &s1);
        let s3 = ok(&["mat0"], &s2);
        let s4 = ok(&["kcolor"], &s3);
        let s5 = ok(&["radial", "--surface", "sphere", "--format", "json"], &s4);
        let recs = json_records(&s5);
        assert_eq!(recs.len(), 24 * 4, "{format}");
        for r in &recs {
            assert_eq!(
                keys(r),
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
            assert_eq!(
                keys(&r["vertex2"]),
                ["pos", "norm", "kg", "color", "dist"],
                "{format}"
            );
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
    let mesh = r#"{"type":"TriangleMesh","name":"m0","pos":[[0,0,0],[1,0,0],[0,1,0],[1,1,0]],"uv":[[0,0],[1,0],[0,1],[1,1]],"kg":[0.5,-0.25,0.0,1e-3],"triangles":[[0,1,2],[1,3,2]],"provenance":"head"}"#;
    let input = format!("{note}\n{tri}\n{mesh}\n{patch}\n{note}\n");
    let expected_mesh: Value = serde_json::from_str(mesh).expect("json");
    let expected_note: Value = serde_json::from_str(note).expect("json");
    for format in ["json", "dstruct", "binary"] {
        let start = ok(&["g1", "--format", format], input.as_bytes());
        for args in [
            &["g1"][..],
            &["tess", "-s", "1", "--kg"],
            &["tess", "-s", "1", "--kg", "--mesh"],
            &["mat0"],
            &["kcolor"],
            &["kcolor", "--range", "-1:1"],
            &["radial", "--surface", "sphere"],
        ] {
            let out = ok(args, &start);
            let recs = json_records(&ok(&["g1", "--format", "json"], &out));
            let kinds: Vec<&str> = recs.iter().map(|r| r["type"].as_str().unwrap()).collect();
            let mesh_out = args.contains(&"--mesh");
            let expect_kinds = match args[0] {
                "tess" if mesh_out => ["Note", "Triangle", "TriangleMesh", "TriangleMesh", "Note"],
                "tess" => ["Note", "Triangle", "TriangleMesh", "Triangle", "Note"],
                _ => ["Note", "Triangle", "TriangleMesh", "BezierTriangle", "Note"],
            };
            assert_eq!(kinds, expect_kinds, "{format} {args:?}");
            assert_eq!(recs[0], expected_note, "{format} {args:?}");
            assert_eq!(recs[4], expected_note, "{format} {args:?}");
            // The TriangleMesh: its fields in order, unknown ones (a column `uv` too)
            // unchanged; the colour filters set `color` (and `dist`) after the last field.
            let m = &recs[2];
            let mk = keys(m);
            let known = ["type", "name", "pos", "uv", "kg", "triangles", "provenance"];
            assert_eq!(&mk[..7], known, "{format} {args:?}");
            for k in known {
                assert_eq!(m[k], expected_mesh[k], "{format} {args:?} {k}");
            }
            let extra: &[&str] = match args[0] {
                "g1" | "tess" => &[],
                "radial" => &["color", "dist"],
                _ => &["color"],
            };
            assert_eq!(&mk[7..], extra, "{format} {args:?}");
            if !extra.is_empty() {
                assert_eq!(m["color"].as_array().map(Vec::len), Some(4));
            }
            let t = &recs[1];
            assert_eq!(
                keys(t),
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
            assert_eq!(
                &keys(&t["vertex1"])[..4],
                ["label", "pos", "kg", "norm"],
                "{format} {args:?}"
            );
            if mesh_out {
                // The patch's mesh: columns and triangles first, then the patch's other fields.
                assert_eq!(
                    keys(&recs[3]),
                    [
                        "type",
                        "pos",
                        "norm",
                        "kg",
                        "triangles",
                        "note",
                        "provenance"
                    ]
                );
                assert_eq!(recs[3]["triangles"], serde_json::json!([[1, 2, 0]]));
            } else if args[0] == "tess" {
                // The patch's triangle: vertices first, then the patch's other fields.
                assert_eq!(
                    keys(&recs[3]),
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
                assert_eq!(recs[3]["note"], "first");
                assert_eq!(recs[3]["provenance"], "head");
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
    // A density no memory holds is a usage error (exit status 2), not a crash.
    let patch = ok(&["fit", "--scheme", "flat"], &octa());
    for s in ["0", "4097", "10000000000"] {
        let out = testbed(&["tess", "-s", s], &patch);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "-s {s}: {err}");
        assert!(
            err.contains("from 1 to 4096 segments per patch edge"),
            "{err}"
        );
    }
}

/// A TriangleMesh with an index out of range, one with a column too short, one with a
/// non-integer index: errors naming the record and the field, skipped with `--keep-going`
/// by every filter that reads them.
#[test]
fn malformed_mesh_records_are_named_and_skipped_with_keep_going() {
    let good = r#"{"type":"TriangleMesh","pos":[[0,0,0],[1,0,0],[0,1,0]],"norm":[[0,0,1],[0,0,1],[0,0,1]],"kg":[1,2,3],"triangles":[[0,1,2]]}"#;
    let out_of_range = good.replace("[[0,1,2]]", "[[0,1,2],[2,1,3]]");
    let short = good.replace("\"kg\":[1,2,3]", "\"kg\":[1,2]");
    let float_index = good.replace("[[0,1,2]]", "[[0,1.0,2]]");
    let input = format!("{good}\n{out_of_range}\n{short}\n{float_index}\n{good}\n");
    let cases = [
        (
            "record 2 (line 2)",
            "triangles[1][2]",
            "index 3 out of range (3 vertices)",
        ),
        ("record 3 (line 3)", "kg", "2 entries for 3 vertices"),
        (
            "record 4 (line 4)",
            "triangles[0][1]",
            "expected a vertex index",
        ),
    ];
    for (k, (_, field, message)) in cases.iter().enumerate() {
        // Each bad record alone after a good one: the error names it (record 2, line 2).
        let one = format!("{good}\n{}\n", input.lines().nth(k + 1).unwrap());
        for args in [&["mat0"][..], &["kcolor"], &["render", "--size", "40x30"]] {
            let out = testbed(args, one.as_bytes());
            assert!(!out.status.success(), "{args:?} {field}");
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(
                err.contains("record 2 (line 2)")
                    && err.contains("TriangleMesh")
                    && err.contains(&format!("field `{field}`"))
                    && err.contains(message),
                "{args:?}: {err}"
            );
        }
    }
    for args in [&["mat0", "--keep-going"][..], &["kcolor", "--keep-going"]] {
        let out = testbed(args, input.as_bytes());
        assert!(out.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        for (at, field, _) in cases {
            assert!(err.contains(at) && err.contains(field), "{args:?}: {err}");
        }
        assert!(err.contains("3 bad record(s) skipped"), "{err}");
        let recs = json_records(&out.stdout);
        assert_eq!(recs.len(), 2);
        assert!(recs
            .iter()
            .all(|r| r["color"].as_array().map(Vec::len) == Some(3)));
    }
    let out = testbed(
        &["render", "--size", "40x30", "--keep-going"],
        input.as_bytes(),
    );
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("3 bad record(s) skipped"));
    // kcolor needs the curvature column.
    let no_kg = good.replace(",\"kg\":[1,2,3]", "");
    let out = testbed(&["kcolor"], no_kg.as_bytes());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("field `kg`") && err.contains("record 1"),
        "{err}"
    );
}

/// The same surface through `Triangle` and `TriangleMesh` records, in every format: the
/// same colour range, the same pictures byte for byte, the same welded mesh file.
#[test]
fn mesh_records_give_the_pictures_and_meshes_of_triangle_records() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let dir = tempfile::tempdir().expect("dir");
    let mut outputs = Vec::new();
    for format in ["json", "dstruct", "binary"] {
        for mesh in [false, true] {
            let mut tess = vec!["tess", "-s", "4", "--kg", "--format", format];
            if mesh {
                tess.push("--mesh");
            }
            let tris = ok(&tess, &patches);
            // The whole stream (384 triangles), then a block of 4 patches' triangles: a
            // mesh record is held whole, so the ranges agree when the block ends between
            // patches.
            let mut ranges = Vec::new();
            let mut coloured = Vec::new();
            for block in ["8192", "64"] {
                let out = testbed(&["kcolor", "--block", block], &tris);
                assert!(out.status.success());
                ranges.push(String::from_utf8_lossy(&out.stderr).into_owned());
                coloured = out.stdout;
            }
            let shaded = ok(&["render"], &coloured);
            let wire = ok(&["wire"], &coloured);
            let file = dir.path().join(format!("octa-{format}-{mesh}.obj"));
            ok(&["to-mesh", "--output", file.to_str().unwrap()], &coloured);
            let welded = std::fs::read(&file).expect("written");
            assert!(shaded.len() > 1000 && wire.len() > 1000);
            outputs.push((format, mesh, ranges, shaded, wire, welded));
        }
    }
    let first = &outputs[0];
    assert!(
        first.2[0].contains("over the whole stream"),
        "{}",
        first.2[0]
    );
    assert!(
        first.2[1].contains("over the first 64 triangles"),
        "{}",
        first.2[1]
    );
    for o in &outputs[1..] {
        assert_eq!(o.2, first.2, "{} mesh: {}", o.0, o.1);
        assert!(o.3 == first.3, "shaded picture, {} mesh: {}", o.0, o.1);
        assert!(o.4 == first.4, "wire frame, {} mesh: {}", o.0, o.1);
        assert!(o.5 == first.5, "mesh file, {} mesh: {}", o.0, o.1);
    }
}

/// `fit -s N` (Example 5's path) writes one `TriangleMesh` per patch by default and with
/// `--mesh`: its records hold the patch's samples once each, and they colour and draw as the
/// `Triangle` records of `fit -s N --triangles` do, byte for byte; without `-s` `--mesh` is
/// refused.
#[test]
fn sampled_fits_write_mesh_records_that_draw_as_their_triangles() {
    for scheme in ["nielson", "shirman-sequin"] {
        let args = ["fit", "--scheme", scheme, "-s", "3", "--kg"];
        let tris = ok(&[&args[..], &["--triangles"]].concat(), &octa());
        let meshes = ok(&[&args[..], &["--mesh"]].concat(), &octa());
        // TriangleMesh records are the default (issue 28: the fast form), as for `tess`.
        assert_eq!(
            ok_as_given(&[&args[..], &["--format", "json"]].concat(), &octa()),
            meshes,
            "{scheme}"
        );
        let recs = json_records(&meshes);
        let patches = if scheme == "nielson" { 8 } else { 24 };
        assert_eq!(recs.len(), patches, "{scheme}");
        assert_eq!(json_records(&tris).len(), patches * 9, "{scheme}");
        for r in &recs {
            assert_eq!(
                keys(r),
                [
                    "type",
                    "pos",
                    "norm",
                    "kg",
                    "triangles",
                    "face",
                    "subpatch",
                    "scheme"
                ]
            );
            // s = 3: 10 samples, 9 triangles a patch.
            assert_eq!(r["pos"].as_array().map(Vec::len), Some(10), "{scheme}");
            assert_eq!(r["kg"].as_array().map(Vec::len), Some(10), "{scheme}");
            assert_eq!(r["triangles"].as_array().map(Vec::len), Some(9), "{scheme}");
        }
        let draw = |stream: &[u8]| {
            let coloured = ok(&["kcolor"], stream);
            (ok(&["render"], &coloured), ok(&["wire"], &coloured))
        };
        let (a, b) = (draw(&tris), draw(&meshes));
        assert!(a.0 == b.0, "{scheme}: shaded pictures differ");
        assert!(a.1 == b.1, "{scheme}: wire frames differ");
    }
    let out = testbed(&["fit", "--mesh"], &octa());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("-s N"), "{err}");
}

/// The next of the workspace's seeded pseudo-random numbers (`rng::SplitMix64`), so failures
/// reproduce.
fn draw(state: &mut rng::SplitMix64) -> u64 {
    state.next_u64()
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
    let mut seed = rng::SplitMix64::new(0x9e37_79b9_7f4a_7c15);
    // Panics exit with 101; errors with 1.
    const PANIC_STATUS: i32 = 101;
    for s in &streams {
        let mut cases: Vec<Vec<u8>> = (1..8).map(|k| s[..s.len() * k / 8].to_vec()).collect();
        for _ in 0..12 {
            let mut m = s.clone();
            for _ in 0..4 {
                let i = (draw(&mut seed) as usize) % m.len();
                m[i] = (draw(&mut seed) & 0xff) as u8;
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

/// Every filter, in process, on 2000 damaged copies per format of a stream holding every
/// record kind (patches, Triangles, TriangleMeshes, an unknown record): no panic; whatever is
/// written reads back.
#[test]
fn damaged_streams_with_mesh_records_never_panic_in_any_filter() {
    use testbed::filters::{self, CurvatureFields, Pipe, TessRecords};
    /// Damaged copies per format: every reader branch and the mesh checks many times over,
    /// fast in a debug build.
    const CASES: usize = 2000;
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let patches: Vec<u8> = patches
        .split_inclusive(|&c| c == b'\n')
        .take(2)
        .flatten()
        .copied()
        .collect();
    let note = b"{\"type\":\"Note\",\"x\":[1,2]}\n";
    let mut seed = rng::SplitMix64::new(0x5851_f42d_4c95_7f2d);
    let fields = CurvatureFields {
        kg: true,
        km: true,
        kp: false,
    };
    for format in ["json", "dstruct", "binary"] {
        let tris = ok(
            &["tess", "-s", "1", "--kg", "--km", "--format", format],
            &patches,
        );
        let meshes = ok(
            &["tess", "-s", "2", "--kg", "--mesh", "--format", format],
            &patches,
        );
        // Every part through JSON, then the whole in the format (binary parts cannot be
        // concatenated).
        let stream = ok(&["g1", "--format", format], &{
            let mut j = ok(&["g1", "--format", "json"], &tris);
            j.extend(ok(&["g1", "--format", "json"], &meshes));
            j.extend_from_slice(note);
            j.extend_from_slice(&patches);
            j
        });
        for _ in 0..CASES {
            let mut m = stream.clone();
            for _ in 0..1 + draw(&mut seed) % 4 {
                let at = (draw(&mut seed) as usize) % m.len();
                match draw(&mut seed) % 3 {
                    0 => m[at] = draw(&mut seed) as u8,
                    1 => {
                        m.remove(at);
                    }
                    _ => {
                        let bytes = b"{}[]()\",.;%:-0e9\n";
                        m.insert(at, bytes[(draw(&mut seed) as usize) % bytes.len()])
                    }
                }
            }
            let run = |f: &mut dyn FnMut(&mut Pipe) -> Result<(), testbed::FilterError>| {
                let mut input = &m[..];
                let mut out = Vec::new();
                {
                    let mut pipe = Pipe::new("test", &mut input, &mut out, None, true);
                    let _ = f(&mut pipe);
                }
                // What a filter wrote is a stream again (possibly cut short by an error).
                let mut input = &out[..];
                let mut sink = std::io::sink();
                let mut pipe = Pipe::new("test", &mut input, &mut sink, None, true);
                let _ = testbed::draw::collect_triangles(&mut pipe);
            };
            run(&mut |p| filters::tess(p, 2, fields, TessRecords::Mesh).map(|_| ()));
            run(&mut |p| filters::tess(p, 1, fields, TessRecords::Triangles).map(|_| ()));
            run(&mut |p| filters::colour(p, &filters::KColor, "kg", None, 5));
            run(&mut |p| filters::colour(p, &filters::Mat0, "", None, 0));
            run(&mut |p| testbed::g1::g1(p, false, 3).map(|_| ()));
            run(&mut |p| testbed::draw::collect_mesh(p).map(|_| ()));
        }
    }
}

#[test]
fn fit_reads_any_mesh_format_from_standard_input() {
    let tris = ok(&["fit", "--scheme", "flat", "-s", "1"], &octa());
    let dir = tempfile::tempdir().expect("dir");
    let ply = dir.path().join("octa.ply");
    ok(
        &["to-mesh", "--output", ply.to_str().expect("utf-8")],
        &tris,
    );
    let bytes = std::fs::read(&ply).expect("ply written");
    let again = ok(&["fit", "--scheme", "flat"], &bytes);
    assert_eq!(json_records(&again).len(), 8);
}

/// `-` names the standard streams for `--input` and `--output` (docs/conventions.md, "The
/// command language"): the same bytes as leaving the options out.
#[test]
fn a_dash_is_standard_input_and_output() {
    let octa = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m")).unwrap();
    let plain = ok(&["fit"], &octa);
    assert_eq!(ok(&["fit", "--input", "-", "--output", "-"], &octa), plain);
    let tess = ok(&["tess", "-s", "2"], &plain);
    assert_eq!(
        ok(&["tess", "-s", "2", "--input", "-", "-o", "-"], &plain),
        tess
    );
}

/// `fit` marks the patch edges on the mesh's creases in its records (`"creases"`), and `g1`
/// leaves those boundaries out: the CAD box (152 crease edges at 90°) is G1 everywhere else,
/// so `g1 --strict` passes, and says how many crease boundaries it left out.
#[test]
fn g1_leaves_out_the_creases_fit_marks() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let box_ply = root.join("data/cad/box.ply");
    let patches = ok(&["fit", "--data", box_ply.to_str().unwrap()], b"");
    let records = json_records(&patches);
    let marked: usize = records
        .iter()
        .filter_map(|r| r["creases"].as_array().map(Vec::len))
        .sum();
    // Each crease edge has a patch edge on it from each of its two faces.
    assert_eq!(marked, 2 * 152);
    let out = testbed(&["g1", "--strict"], &patches);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("152 shared boundaries on creases"), "{err}");
    // A record whose mark is not a patch edge is named.
    let bad = String::from_utf8_lossy(&patches).replacen("\"creases\":[", "\"creases\":[7,", 1);
    let out = testbed(&["g1"], bad.as_bytes());
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("creases[0]"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn the_default_pipeline_is_binary_triangle_meshes_and_draws_what_the_seeds_forms_draw() {
    // Into a pipe `fit` writes the binary form, and `tess` one TriangleMesh per patch in it.
    let patches = ok_as_given(&["fit"], &octa());
    assert!(
        patches.starts_with(b"TBIN1"),
        "fit's default into a pipe is binary"
    );
    let meshes = ok_as_given(&["tess", "-s", "4", "--kg"], &patches);
    assert!(
        meshes.starts_with(b"TBIN1"),
        "tess follows its input's format"
    );
    let as_json = json_records(&ok_as_given(
        &["tess", "-s", "4", "--kg", "--format", "json"],
        &patches,
    ));
    // Shirman–Séquin splits each of the octahedron's 8 faces into 3 patches.
    assert_eq!(as_json.len(), 24, "one record per patch of the octahedron");
    assert!(
        as_json.iter().all(|r| r["type"] == "TriangleMesh"),
        "{:?}",
        as_json[0]["type"]
    );
    // The same picture as the seed's forms (JSON Lines, Triangle records) give.
    let draw = |tris: &[u8]| {
        let coloured = ok_as_given(&["kcolor"], tris);
        ok_as_given(&["render", "--size", "96x96"], &coloured)
    };
    let seed = ok_as_given(
        &["tess", "-s", "4", "--kg", "--triangles"],
        &ok_as_given(&["fit", "--format", "json"], &octa()),
    );
    assert!(seed.starts_with(b"{"), "JSON Lines by request");
    assert_eq!(
        draw(&meshes),
        draw(&seed),
        "the default pipeline draws the seed's picture"
    );
}

#[test]
fn fit_writes_json_lines_for_an_output_named_jsonl() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("patches.jsonl");
    ok_as_given(&["fit", "--output", out.to_str().expect("utf-8")], &octa());
    let text = std::fs::read(&out).expect("written");
    assert_eq!(json_records(&text).len(), 24, "the octahedron's 24 patches");
}

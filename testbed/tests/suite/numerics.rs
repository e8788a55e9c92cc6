//! The testbed's sizes, numbers and verdicts on hostile input: every size a user sets is
//! bounded and estimated before allocating, `tess` gives the same figures at any scale and
//! writes no number that is not finite, nothing is dropped without a count, `g1 --strict`
//! fails on anything unmeasured, a picture with nothing on it is an error, and usage errors
//! exit 2. Each test is a hostile case that passed silently (or exhausted the machine) before;
//! the figures it gave then are in the comments and in docs/hostile-input.md.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use std::io::Write;
use std::process::{Command, Output, Stdio};

use serde_json::{json, Value};

use crate::support::{json_records, ok, testbed};

/// Normals and curvatures of a patch evaluated at another scale, against the unit patch's
/// mapped by the scale (`K/σ²`, `H/σ`): the unit frame makes them the same computation up to
/// the rounding of the translation, a few ulps relative.
const SCALED: f64 = 1e-12;

fn octa() -> Vec<u8> {
    std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m")).unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The patches of `stream` with every control point multiplied by `scale`.
fn scaled(stream: &[u8], scale: f64) -> Vec<u8> {
    let mut out = Vec::new();
    for mut r in json_records(stream) {
        let pts: Vec<Value> = r["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let c: Vec<f64> = p
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap() * scale)
                    .collect();
                json!(c)
            })
            .collect();
        r["points"] = Value::Array(pts);
        out.extend_from_slice(r.to_string().as_bytes());
        out.push(b'\n');
    }
    out
}

/// Each vertex's normal, kg and km in stream order.
fn vertices(stream: &[u8]) -> Vec<([f64; 3], Option<f64>, Option<f64>)> {
    let mut v = Vec::new();
    for r in json_records(stream) {
        for k in ["vertex1", "vertex2", "vertex3"] {
            let x = &r[k];
            let n = x["norm"].as_array().unwrap();
            let n = [0, 1, 2].map(|i| n[i].as_f64().unwrap());
            v.push((n, x["kg"].as_f64(), x["km"].as_f64()));
        }
    }
    v
}

/// `tess` on the octahedron's patches scaled by 1e100 wrote zero normals and a NaN `kg` as
/// -2.696539702293474e308; at 1e-100 every normal was (0, 0, 1) with `kg` 0; at 1e160 and
/// 1e200 every patch was dropped without a word. Now the figures are the unit patches'
/// mapped by the scale, at every scale where they are doubles.
#[test]
fn tess_gives_the_same_figures_at_every_scale() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let unit = vertices(&ok(&["tess", "-s", "2", "--kg", "--km"], &patches));
    assert_eq!(unit.len(), 24 * 4 * 3);
    for scale in [1e100, 1e-100, 1e160, 1e200, 1e-150] {
        let out = ok(
            &["tess", "-s", "2", "--kg", "--km"],
            &scaled(&patches, scale),
        );
        let got = vertices(&out);
        assert_eq!(got.len(), unit.len(), "scale {scale:e}: no patch dropped");
        for ((n, kg, km), (n1, kg1, km1)) in got.iter().zip(&unit) {
            for i in 0..3 {
                assert!(
                    (n[i] - n1[i]).abs() < SCALED,
                    "scale {scale:e}: {n:?} vs {n1:?}"
                );
            }
            let (kg, km, kg1, km1) = (kg.unwrap(), km.unwrap(), kg1.unwrap(), km1.unwrap());
            // K/σ² where it is a normal double (at 1e160 it is subnormal, at 1e200 zero).
            let want_kg = kg1 / scale / scale;
            if want_kg.abs() > f64::MIN_POSITIVE {
                assert!(
                    (kg - want_kg).abs() <= SCALED * want_kg.abs(),
                    "scale {scale:e}: kg {kg} vs {want_kg}"
                );
            }
            let want_km = km1 / scale;
            assert!(
                (km - want_km).abs() <= SCALED * want_km.abs(),
                "scale {scale:e}: km {km} vs {want_km}"
            );
        }
    }
}

/// At 1e-200 the Gaussian curvature is about 1e400, beyond a double: tess wrote half the
/// patches with normal (0, 0, 1) and `kg` 0 and dropped the rest. Now `--kg` is an error
/// naming the record (exit 1), `--keep-going` skips every patch and counts them, and `--km`
/// alone (about 1e200) is written right.
#[test]
fn a_curvature_beyond_a_double_is_an_error_naming_the_patch() {
    let patches = scaled(&ok(&["fit", "--scheme", "shirman-sequin"], &octa()), 1e-200);
    let out = testbed(&["tess", "-s", "2", "--kg"], &patches);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("record 1") && err.contains("Gaussian curvature") && err.contains("inf"),
        "{err}"
    );
    assert!(json_records(&out.stdout).is_empty(), "nothing written");
    let out = testbed(&["tess", "-s", "2", "--kg", "--keep-going"], &patches);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("24 bad record(s) skipped"),
        "{}",
        stderr(&out)
    );
    let km = vertices(&ok(&["tess", "-s", "2", "--km"], &patches));
    assert_eq!(km.len(), 24 * 4 * 3);
    assert!(km.iter().all(|(n, _, km)| {
        let km = km.unwrap();
        km.is_finite()
            && km.abs() > 1e199
            && (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0).abs() < SCALED
    }));
}

/// A patch whose control points are all equal was dropped without a word (its triangles all
/// welded away). Now it is counted and named on standard error; the other patch is written.
#[test]
fn a_patch_that_is_a_point_is_counted() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let mut first = json_records(&patches)[0].clone();
    first["points"] = json!(vec![[0.5, 0.5, 0.5]; 15]);
    let stream = format!("{first}\n{}\n", json_records(&patches)[1]);
    let out = testbed(&["tess", "-s", "2"], stream.as_bytes());
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert_eq!(
        json_records(&out.stdout).len(),
        4,
        "the other patch's s² triangles"
    );
    let err = stderr(&out);
    assert!(
        err.contains("1 of 2 patches not tessellated")
            && err.contains("control points are equal")
            && err.contains("record 1"),
        "{err}"
    );
}

/// `testbed fit -s N --kg` on a mesh 1e-200 across wrote `"kg": null` silently. Now it is
/// an error naming the patch.
#[test]
fn fit_sampled_curvature_beyond_a_double_is_an_error() {
    let mut obj = String::new();
    for v in [
        [1, 0, 0],
        [0, 1, 0],
        [0, 0, 1],
        [-1, 0, 0],
        [0, -1, 0],
        [0, 0, -1],
    ] {
        obj += &format!(
            "v {:e} {:e} {:e}\n",
            v[0] as f64 * 1e-200,
            v[1] as f64 * 1e-200,
            v[2] as f64 * 1e-200
        );
    }
    for f in [
        [1, 2, 3],
        [3, 5, 1],
        [4, 3, 2],
        [4, 5, 3],
        [2, 1, 6],
        [1, 5, 6],
        [4, 2, 6],
        [6, 5, 4],
    ] {
        obj += &format!("f {} {} {}\n", f[0], f[1], f[2]);
    }
    let out = testbed(&["fit", "-s", "1", "--kg", "--triangles"], obj.as_bytes());
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(
        err.contains("face 0") && err.contains("Gaussian curvature"),
        "{err}"
    );
    let out = ok(&["fit", "-s", "1", "--km", "--triangles"], obj.as_bytes());
    for r in json_records(&out) {
        assert!(
            r["vertex1"]["km"].as_f64().is_some_and(f64::is_finite),
            "{r}"
        );
    }
}

/// `testbed ARGS > /dev/null` under an address-space limit of `limit_kb` kB (`ulimit -v`), fed
/// `input` on its standard input.
fn under_address_limit(limit_kb: u32, args: &str, input: &str) -> Output {
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v {limit_kb} && exec \"$0\" {args} > /dev/null"
        ))
        .arg(env!("CARGO_BIN_EXE_testbed"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(input.as_bytes())
        .unwrap();
    child.wait_with_output().expect("runs")
}

/// `tess -s 700` on one quartic held its 0.4 GB weight table (290 bytes × s² a patch in all:
/// `-s 4096` took 18 GB): under a 400 MB address space it aborted. Now a table beyond
/// 64 MiB is not kept and one patch's Triangles take 88 bytes a sample.
#[test]
fn tess_at_a_large_s_holds_the_samples_alone() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let one = json_records(&patches)[0].to_string();
    let out = under_address_limit(400_000, "tess -s 700 --triangles --format binary", &one);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    // The estimate is the honest one: 0.7 GB at the largest -s, not 18 GB.
    let bytes =
        testbed::filters::tess::tess_bytes(4096, 4, testbed::filters::TessRecords::Triangles);
    assert!(bytes < 1 << 30, "{bytes}");
}

/// `tess -s 700` with its default `TriangleMesh` records needs about 0.39 GB (the record is
/// built whole): under an address-space limit of 200–500 MB it passed the memory check with
/// the old estimate and aborted on a failed allocation (exit 134). The check now counts the
/// room under the limit and the record's measured size: a clear error, exit 1, at every limit
/// where the tessellation does not fit, and the tessellation where it does.
#[test]
fn tess_under_an_address_space_limit_is_refused_not_aborted() {
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa());
    let one = json_records(&patches)[0].to_string();
    for limit_kb in [200_000, 360_000, 420_000, 900_000] {
        let out = under_address_limit(limit_kb, "tess -s 700 --format binary", &one);
        let err = stderr(&out);
        match out.status.code() {
            Some(0) => assert!(limit_kb >= 420_000, "fitted under {limit_kb} kB: {err}"),
            Some(1) => assert!(
                err.contains("tess -s 700 --mesh") && err.contains("would need about"),
                "{limit_kb} kB: {err}"
            ),
            other => panic!("{limit_kb} kB: exit {other:?} (an abort?): {err}"),
        }
        if limit_kb == 900_000 {
            assert_eq!(out.status.code(), Some(0), "{err}");
        }
    }
}

/// Sizes out of their range are usage errors naming the range, exit 2: `tess -s`, `fit -s`
/// (unbounded before: `--sample N`), `g1 --samples` (unbounded: 10⁶ took over a minute),
/// `render --size` (16384 × 16384 was allowed and took 5.9 GB).
#[test]
fn sizes_out_of_range_are_usage_errors_naming_the_range() {
    let patches = ok(&["fit", "--scheme", "flat"], &octa());
    let cases: [(&[&str], &[u8], &str); 5] = [
        (&["tess", "-s", "4097"], &patches, "from 1 to 4096"),
        (&["fit", "-s", "4097"], &octa(), "from 1 to 4096"),
        (&["fit", "-s", "0"], &octa(), "from 1 to 4096"),
        (&["g1", "--samples", "1000000"], &patches, "from 3 to 4097"),
        (
            &["render", "--size", "16384x16384"],
            b"",
            "each side from 1 to 8192",
        ),
    ];
    for (args, input, range) in cases {
        let t = std::time::Instant::now();
        let out = testbed(args, input);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(range), "{args:?}: {}", stderr(&out));
        assert!(t.elapsed().as_secs() < 10, "{args:?}: refused at once");
    }
    // The largest g1 --samples is quick on the octahedron's 36 boundaries.
    let out = testbed(&["g1", "--samples", "4097"], &ok(&["fit"], &octa()));
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

/// Two flat patches sharing an edge, one with a sample whose normal is undefined (its `r_u`
/// vanishes at the middle of the edge, exactly): `g1 --strict` reported "G1 within tolerance"
/// and exited 0 with the sample skipped. Now the unmeasured sample fails `--strict`.
#[test]
fn g1_strict_fails_on_an_unmeasured_sample() {
    let net = |u: [f64; 3], v: [f64; 3], w: [f64; 3]| {
        let mut pts = Vec::new();
        for k in 0..=4 {
            for i in (0..=4 - k).rev() {
                let j = 4 - k - i;
                pts.push(
                    [0, 1, 2].map(|c| (i as f64 * u[c] + j as f64 * v[c] + k as f64 * w[c]) / 4.0),
                );
            }
        }
        pts
    };
    let mut a = net([3.0, 0.0, 0.0], [0.0, 3.0, 0.0], [0.0; 3]);
    // b211 and b121 moved by (U − W)/3: r_u(1/2) on the edge w = 0 is exactly zero.
    a[6][0] += 1.0;
    a[7][0] += 1.0;
    let b = net([0.0, 3.0, 0.0], [3.0, 0.0, 0.0], [3.0, 3.0, 0.0]);
    let stream = format!(
        "{}\n{}\n",
        json!({"type": "BezierTriangle", "degree": 4, "points": a}),
        json!({"type": "BezierTriangle", "degree": 4, "points": b})
    );
    let out = testbed(&["g1"], stream.as_bytes());
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("1 samples unmeasured"),
        "{}",
        stderr(&out)
    );
    let out = testbed(&["g1", "--strict"], stream.as_bytes());
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("1 samples left unmeasured"),
        "{}",
        stderr(&out)
    );
    assert_eq!(out.stdout, stream.as_bytes(), "records still pass through");
}

/// A picture with no triangles (a forgotten `tess`, `kcolor` before `tess`, an empty
/// stream) was a blank PNG with exit 0. Now it is an error naming the cause, for `render` and
/// `wire`.
#[test]
fn a_blank_picture_is_an_error_naming_the_cause() {
    let patches = ok(&["fit"], &octa());
    // `kcolor` before `tess` passes the patches through (and exits 1: nothing to colour).
    let coloured = testbed(&["kcolor", "--range", "0:1"], &patches).stdout;
    for picture in ["render", "wire"] {
        for (input, cause) in [
            (&patches[..], "put `tess` before"),
            (&coloured[..], "put `tess` before"),
            (&b""[..], "the stream is empty"),
        ] {
            let out = testbed(&[picture], input);
            assert_eq!(out.status.code(), Some(1), "{picture}: {}", stderr(&out));
            let err = stderr(&out);
            assert!(
                err.contains("no triangles") && err.contains(cause),
                "{picture}: {err}"
            );
            assert!(out.stdout.is_empty(), "{picture}: no PNG");
        }
    }
    // A shaded picture of triangles that cover no pixel (all at one point) is blank too.
    let point = json!({"type": "Triangle", "vertex1": {"pos": [1, 1, 1]},
        "vertex2": {"pos": [1, 1, 1]}, "vertex3": {"pos": [1, 1, 1]}});
    let out = testbed(&["render"], format!("{point}\n").as_bytes());
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("the picture is blank"),
        "{}",
        stderr(&out)
    );
    // With triangles, a picture.
    let tris = ok(&["tess", "-s", "2"], &patches);
    assert!(ok(&["render"], &tris).starts_with(b"\x89PNG"));
}

/// The command language: `-s, --segments` for `tess` and `fit` (`fit --sample` is gone),
/// `--data NAME|FILE` with `--resolution N` for `fit` (`--dataset NAME:RES` is gone), and a
/// usage error exits 2 where every testbed error exited 1.
#[test]
fn one_spelling_and_usage_errors_exit_two() {
    let long = ok(
        &["tess", "--segments", "2"],
        &ok(&["fit", "--scheme", "flat"], &octa()),
    );
    assert_eq!(json_records(&long).len(), 8 * 4);
    let sampled = ok(&["fit", "--scheme", "flat", "--segments", "1"], &octa());
    assert_eq!(json_records(&sampled).len(), 8);
    let ring = ok(&["fit", "--data", "ring", "--resolution", "8"], b"");
    assert_eq!(
        json_records(&ring).len(),
        2 * 8 * 4 * 3,
        "ring(8): 64 faces, 3 patches each"
    );
    let file = ok(
        &[
            "fit",
            "--data",
            concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m"),
        ],
        b"",
    );
    assert_eq!(json_records(&file).len(), 24);
    for args in [
        &["fit", "--sample", "2"][..],
        &["fit", "--dataset", "ring"][..],
        &["fit", "--resolution", "8"][..],
        &["fit", "--data", "ring", "--input", "x.obj"][..],
        &["fit", "--scheme", "no-such-scheme"][..],
        &["tess", "-s", "0"][..],
    ] {
        let out = testbed(args, &octa());
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
    }
    // A runtime error is 1: a malformed record.
    let out = testbed(&["tess"], b"{\"type\": \"BezierTriangle\"}\n");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
}

//! The testbed on the library: `g1` matches boundaries within the library's tolerance and
//! measures them with its G1 sampling, `to-mesh` welds with its weld, `fit -s` checks its
//! memory estimate. Each test reproduces a failure of the bit-exact testbed first (the figures
//! in the comments are what it gave), then checks the figures now.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use std::collections::{HashMap, HashSet};
use std::io::Write;
use std::process::{Command, Output, Stdio};

use serde_json::Value;

use crate::support::{json_records, ok, testbed};
use testbed::filters::Pipe;

/// The built-in ring (`ring(16, 8)`): 256 faces, 768 quartic patches, 1152 boundaries between
/// them (a torus is closed: every patch edge is shared).
const RING_PATCHES: usize = 768;
const RING_BOUNDARIES: usize = 1152;

/// The built-in capsule (resolution 16): 194 vertices, 576 edges, 384 faces. At `s = 8` each
/// face's three patches give 85 samples inside the face and each edge 7 inside it, so the
/// welded tessellation has 194 + 576 · 7 + 384 · 85 = 36 866 vertices — what `experiments fit
/// --data capsule --tess 8 --mesh-out` writes (welded by topology), checked below against the
/// library's `tessellate_fit`.
const CAPSULE_VERTICES_AT_8: usize = 36_866;

/// A C0 scheme's normal jump along the ring's boundaries is a visible crease: more than a
/// hundredth of a radian (Clough–Tocher with chord curves: 5.7e-2 rad measured), ten thousand
/// times the G1 tolerance.
const C0_JUMP_AT_LEAST: f64 = 1e-2;

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// `g1` run in this process on a stream, for its summary.
fn g1_summary(stream: &[u8], samples: usize) -> testbed::g1::G1Summary {
    let mut input = stream;
    let mut out = Vec::new();
    let mut pipe = Pipe::new("g1", &mut input, &mut out, None, false);
    testbed::g1::g1(&mut pipe, false, samples).expect("g1 runs")
}

/// The patch edges of a patch stream no other edge matches bit for bit (`-0` = `0`), in
/// either direction: what the old `g1` called unshared.
fn unshared_by_bits(stream: &[u8]) -> usize {
    let mut count: HashMap<Vec<[u64; 3]>, usize> = HashMap::new();
    for r in json_records(stream) {
        let n = r["degree"].as_u64().unwrap() as usize;
        let pts: Vec<[u64; 3]> = r["points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let c = |k: usize| (p[k].as_f64().unwrap() + 0.0).to_bits();
                [c(0), c(1), c(2)]
            })
            .collect();
        let patch = surface::BezierTriangle::from_fn(n, |i, j, k| {
            let [x, y, z] = pts[surface::beztri::index(n, i, j, k)];
            nalgebra::Point3::new(f64::from_bits(x), f64::from_bits(y), f64::from_bits(z))
        });
        for e in 0..3 {
            let fwd: Vec<[u64; 3]> = patch
                .boundary_curve(e)
                .unwrap()
                .points
                .iter()
                .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
                .collect();
            let mut rev = fwd.clone();
            rev.reverse();
            *count.entry(fwd.min(rev)).or_default() += 1;
        }
    }
    count.values().filter(|&&n| n == 1).count()
}

#[test]
fn ring_g1_shares_and_measures_every_boundary() {
    let patches = ok(&["fit", "--data", "ring"], b"");
    // The reproduction: 152 boundaries' control points differ in the last bits between the
    // two patches (by at most 1.1e-16), so bit equality left 304 edges unshared and 152
    // boundaries unmeasured, and still said "G1 within tolerance".
    assert_eq!(unshared_by_bits(&patches), 304);
    let s = g1_summary(&patches, testbed::g1::DEFAULT_SAMPLES);
    let r = &s.report;
    assert_eq!(r.patches, RING_PATCHES);
    assert_eq!(r.shared, RING_BOUNDARIES);
    assert_eq!(r.measured, RING_BOUNDARIES);
    assert_eq!((s.unshared(), r.border, r.mismatched), (0, 0, 0));
    assert_eq!((r.unmeasurable, r.undefined, r.collapsed), (0, 0, 0));
    assert_eq!(r.orientation_mismatches, 0);
    let worst = s.worst().expect("measured");
    // 2.2e-14 rad measured: rounding.
    assert!(worst.angle < testbed::g1::G1_TOLERANCE, "{worst:?}");
    assert!(worst.angle < 1e-12, "{worst:?}");
    // The filter says so, and --strict passes with the records unchanged.
    let out = testbed(&["g1", "--strict"], &patches);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(out.stdout, patches);
    let text = stderr(&out);
    assert!(
        text.contains("768 patches, 1152 shared boundaries (1152 measured), 0 unshared"),
        "{text}"
    );
    assert!(text.contains("G1 within tolerance"), "{text}");
}

#[test]
fn c0_scheme_reports_its_jump_and_strict_fails() {
    let patches = ok(&["fit", "--data", "ring", "--scheme", "clough-tocher"], b"");
    // Bit equality left 256 of its edges unshared too.
    assert_eq!(unshared_by_bits(&patches), 256);
    let s = g1_summary(&patches, testbed::g1::DEFAULT_SAMPLES);
    assert_eq!(
        (s.report.shared, s.report.measured),
        (RING_BOUNDARIES, RING_BOUNDARIES)
    );
    assert_eq!(s.unshared(), 0);
    let jump = s.worst().expect("measured").angle;
    assert!(jump > C0_JUMP_AT_LEAST, "{jump}");
    let out = testbed(&["g1"], &patches);
    assert!(out.status.success());
    assert!(stderr(&out).contains("warning: not G1"), "{}", stderr(&out));
    let out = testbed(&["g1", "--strict"], &patches);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("exceeds the tolerance"),
        "{}",
        stderr(&out)
    );
    assert_eq!(out.stdout, patches, "records still pass through");
    // Two samples (the ends, where every scheme interpolates the vertex normal) measured 9.9e-15
    // rad here and passed --strict: now a usage error naming the option.
    for n in ["2", "0"] {
        let out = testbed(&["g1", "--strict", "--samples", n], &patches);
        assert_eq!(
            out.status.code(),
            Some(2),
            "--samples {n}: {}",
            stderr(&out)
        );
        assert!(stderr(&out).contains("--samples"), "{}", stderr(&out));
    }
}

#[test]
fn strict_fails_on_unmeasured_boundaries_and_on_nothing_measured() {
    let patches = ok(&["fit", "--data", "ring"], b"");
    // Move one inner control point of the first patch's edge 0 (`w = 0`: b_{3,1,0} of the
    // quartic): its neighbour meets it at both ends along another curve, a C0 defect.
    let mut recs = json_records(&patches);
    let inner = surface::beztri::index(4, 3, 1, 0);
    let p = &mut recs[0]["points"][inner][2];
    *p = Value::from(p.as_f64().unwrap() + 0.01);
    let mut broken = Vec::new();
    for r in &recs {
        serde_json::to_writer(&mut broken, r).unwrap();
        broken.push(b'\n');
    }
    let s = g1_summary(&broken, testbed::g1::DEFAULT_SAMPLES);
    assert_eq!(s.report.mismatched, 2);
    assert_eq!(s.report.unmeasured(), 2);
    assert_eq!(s.report.measured, RING_BOUNDARIES - 1);
    assert_eq!(s.report.mismatched_at.first(), Some(&(0, 0)));
    let out = testbed(&["g1", "--strict"], &broken);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("left unmeasured"), "{}", stderr(&out));
    assert!(stderr(&out).contains("record 1 edge 0"), "{}", stderr(&out));
    // No patches at all: nothing measured.
    let out = testbed(&["g1", "--strict"], b"{\"type\":\"Note\"}\n");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("nothing measured"),
        "{}",
        stderr(&out)
    );
}

/// `(vertices, edges, faces, edges not in exactly two triangles)` of a mesh file.
fn topology(path: &std::path::Path) -> (usize, usize, usize, usize) {
    let bytes = std::fs::read(path).expect("written");
    let raw = meshio::read_bytes(path, &bytes).expect("reads back");
    let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
    for f in raw.polygons.iter() {
        assert_eq!(f.len(), 3);
        for k in 0..3 {
            let (a, b) = (f[k], f[(k + 1) % 3]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    let bad = edges.values().filter(|&&n| n != 2).count();
    (raw.num_vertices(), edges.len(), raw.polygons.len(), bad)
}

#[test]
fn capsule_to_mesh_is_watertight_with_the_topological_vertex_count() {
    // The library's count, welded by topology (`experiments fit --mesh-out`'s tessellation).
    let data = surface::dataset_by_name("capsule", None).unwrap();
    let scheme =
        surface::scheme_by_name("shirman-sequin", &surface::SchemeOptions::default()).unwrap();
    let method = curves::method_by_name("chord", &curves::MethodOptions::default()).unwrap();
    let fitted = surface::fit_scheme(&data.mesh, scheme.as_ref(), method.as_ref()).unwrap();
    let t = surface::tessellate_fit(&data.mesh, &fitted, 8).unwrap();
    assert_eq!(t.positions.len(), CAPSULE_VERTICES_AT_8);

    let patches = ok(&["fit", "--data", "capsule"], b"");
    let dir = tempfile::tempdir().expect("dir");
    for mesh in [false, true] {
        let mut tess = vec!["tess", "-s", "8", "--kg"];
        if mesh {
            tess.push("--mesh");
        }
        let tris = ok(&tess, &patches);
        if !mesh {
            // The reproduction: by bit-identical positions the samples of a shared boundary,
            // evaluated once from each side, did not all weld: 40 187 vertices, χ = −1 097,
            // 8 840 edges not in two triangles.
            let mut distinct = HashSet::new();
            for r in json_records(&tris) {
                for v in ["vertex1", "vertex2", "vertex3"] {
                    let p = &r[v]["pos"];
                    let c = |k: usize| (p[k].as_f64().unwrap() + 0.0).to_bits();
                    distinct.insert([c(0), c(1), c(2)]);
                }
            }
            assert!(
                distinct.len() > CAPSULE_VERTICES_AT_8 + 1000,
                "{}",
                distinct.len()
            );
        }
        let file = dir.path().join(format!("capsule-{mesh}.ply"));
        let out = testbed(&["to-mesh", "--output", file.to_str().unwrap()], &tris);
        assert!(out.status.success(), "{}", stderr(&out));
        assert!(stderr(&out).contains("36866 vertices"), "{}", stderr(&out));
        let (v, e, f, bad) = topology(&file);
        assert_eq!(v, CAPSULE_VERTICES_AT_8, "mesh records: {mesh}");
        assert_eq!(f, 384 * 3 * 64);
        assert_eq!(bad, 0, "every edge in exactly two triangles");
        assert_eq!(
            v as i64 - e as i64 + f as i64,
            2,
            "Euler characteristic of a sphere"
        );
    }
}

#[test]
fn fit_sample_beyond_memory_is_refused_before_allocating() {
    let octa = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m")).unwrap();
    // Under a 4 GB address space: the old fit asked for 120 GB at once and aborted (SIGABRT);
    // the estimate (32 GB for 24 patches at s = 4096, the largest -s) is refused first.
    let mut child = Command::new("sh")
        .arg("-c")
        .arg("ulimit -v 4000000 && exec \"$0\" fit -s 4096")
        .arg(env!("CARGO_BIN_EXE_testbed"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawns");
    child.stdin.take().expect("stdin").write_all(&octa).unwrap();
    let out = child.wait_with_output().expect("runs");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = stderr(&out);
    assert!(text.contains("fit -s 4096"), "{text}");
    assert!(text.contains("would need about"), "{text}");
    assert!(out.stdout.is_empty());
}

#[test]
fn to_mesh_writes_its_mesh_to_output_and_needs_it() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = dir.path().join("m.ply");
    let tris = ok(&["tess", "-s", "1"], &ok(&["fit", "--data", "octa"], b""));
    // No mesh file: refused before anything is read, a usage error (exit status 2).
    let out = testbed(&["to-mesh"], &tris);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("-o, --output FILE"),
        "{}",
        stderr(&out)
    );
    // An extension no writer takes: refused the same way, nothing written.
    let bad = dir.path().join("m.xyz");
    let out = testbed(&["to-mesh", "--output", bad.to_str().unwrap()], &tris);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(!bad.exists());
    // `--output` (and `-o`) is the mesh file; nothing goes to standard output.
    let out = testbed(&["to-mesh", "-o", mesh.to_str().unwrap()], &tris);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out.stdout.is_empty());
    assert!(std::fs::read(&mesh).unwrap().starts_with(b"ply\n"));
    // The old spelling is gone.
    let out = testbed(&["to-mesh", "--out", mesh.to_str().unwrap()], &tris);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}

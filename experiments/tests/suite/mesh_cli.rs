//! Mesh files through the command line as a user runs it: `convert` between formats with
//! estimation, the testbed format carrying the estimates back into `fit --estimate none`,
//! `fit` on a real mesh writing glTF, and bad input named with a non-zero exit.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use std::process::Command;

fn run(args: &[&str]) -> (i32, String) {
    let (code, _, err) = common::run(args, "");
    (code, err)
}

use common::root;

fn tmp(name: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name).to_string_lossy().into_owned();
    (dir, path)
}

#[test]
fn estimates_written_as_testbed_fields_are_read_back_as_exact_data() {
    let (_dir, m) = tmp("teapot.m");
    let (code, err) = run(&[
        "convert",
        "--data",
        "data/meshes/teapot.ply",
        "--output",
        &m,
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&m).unwrap();
    assert!(text.contains("(norm . [") && text.contains("(shape . ["));
    // With the file's normals and shape tensors, curvature-based curves run without
    // estimation, and nothing is estimated.
    let (code, err) = run(&[
        "fit",
        "--data",
        &m,
        "--estimate",
        "none",
        "--curves",
        "optimized",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("estimated"), "{err}");
}

#[test]
fn a_real_mesh_is_fitted_and_written_as_gltf() {
    let (_dir, glb) = tmp("bunny.glb");
    let (code, err) = run(&[
        "fit",
        "--data",
        "data/meshes/bunny.ply",
        "--curves",
        "optimized",
        "--segments",
        "2",
        "--mesh-output",
        &glb,
    ]);
    assert_eq!(code, 0, "{err}");
    let bytes = std::fs::read(&glb).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    assert!(
        err.contains("estimated normals and curvature by `hybrid`"),
        "{err}"
    );
}

#[test]
fn every_format_converts_to_every_writable_one() {
    let (dir, _) = tmp("x");
    let mut sources = Vec::new();
    for ext in ["ply", "obj", "off", "stl", "m"] {
        let out = dir.path().join(format!("bunny.{ext}"));
        let out = out.to_string_lossy().into_owned();
        let (code, err) = run(&[
            "convert",
            "--data",
            "data/meshes/bunny.ply",
            "--output",
            &out,
        ]);
        assert_eq!(code, 0, "{ext}: {err}");
        sources.push(out);
    }
    for src in &sources {
        let out = dir.path().join("again.glb").to_string_lossy().into_owned();
        let (code, err) = run(&["convert", "--data", src, "--output", &out]);
        assert_eq!(code, 0, "{src}: {err}");
        // STL welds by exact position; every format keeps the bunny's 3674 faces.
        assert!(err.contains("3674 faces"), "{src}: {err}");
    }
}

#[test]
fn bad_files_are_named_and_fail() {
    let (dir, _) = tmp("x");
    let truncated = dir.path().join("cut.ply");
    let bytes = std::fs::read(root().join("data/meshes/bunny.ply")).unwrap();
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    let (code, err) = run(&["fit", "--data", truncated.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("cut.ply") && err.contains("element"), "{err}");

    let empty = dir.path().join("empty.obj");
    std::fs::write(&empty, "# nothing here\n").unwrap();
    let (code, err) = run(&["fit", "--data", empty.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(
        err.contains("empty.obj") && err.contains("nothing to fit"),
        "{err}"
    );

    let unknown = dir.path().join("mesh.xyz");
    std::fs::write(&unknown, "1 2 3\n").unwrap();
    let (code, err) = run(&["fit", "--data", unknown.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(err.contains("unsupported format"), "{err}");

    // A PLY named .obj is read as PLY, with a note.
    let lying = dir.path().join("bunny.obj");
    std::fs::write(&lying, &bytes).unwrap();
    let (code, err) = run(&["fit", "--data", lying.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("content is ply"), "{err}");

    // The output may not be the input.
    let (code, err) = run(&[
        "convert",
        "--data",
        lying.to_str().unwrap(),
        "--output",
        lying.to_str().unwrap(),
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("the output is the input"), "{err}");
}

#[test]
fn outputs_that_are_not_regular_files_are_refused() {
    let (dir, _) = tmp("x");
    let sub = dir.path().join("a-directory");
    std::fs::create_dir(&sub).unwrap();
    let (code, err) = run(&[
        "convert",
        "--data",
        "octa",
        "--output",
        sub.to_str().unwrap(),
    ]);
    // A directory has no extension: refused as an unsupported output before anything is read.
    assert_ne!(code, 0, "{err}");
    let glb_dir = dir.path().join("dir.glb");
    std::fs::create_dir(&glb_dir).unwrap();
    let (code, err) = run(&[
        "convert",
        "--data",
        "octa",
        "--output",
        glb_dir.to_str().unwrap(),
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("a directory, not a regular file"), "{err}");
    assert!(glb_dir.is_dir());
    #[cfg(unix)]
    {
        let (code, err) = run(&["fit", "--data", "octa", "--output", "/dev/null"]);
        assert_ne!(code, 0);
        assert!(err.contains("a device"), "{err}");
        // `fit` refuses an unwritable output before it reads or fits anything (no stage times
        // printed), for the patches and for the tessellation alike.
        for option in ["--output", "--mesh-output"] {
            let out = dir.path().join(format!("{option}.ply"));
            std::fs::create_dir(&out).unwrap();
            let (code, err) = run(&["fit", "--data", "octa", option, out.to_str().unwrap()]);
            assert_ne!(code, 0, "{option}");
            assert!(
                err.contains("a directory, not a regular file"),
                "{option}: {err}"
            );
            assert!(
                !err.contains("time:"),
                "{option}: refused only after the work: {err}"
            );
        }
        // A link to a regular file writes through to the file and keeps the link.
        let target = dir.path().join("target.jsonl");
        std::fs::write(&target, "old\n").unwrap();
        let link = dir.path().join("link.jsonl");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let (code, err) = run(&["fit", "--data", "octa", "--output", link.to_str().unwrap()]);
        assert_eq!(code, 0, "{err}");
        assert!(std::fs::read_to_string(&target)
            .unwrap()
            .contains("BezierTriangle"));
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
    }
}

#[cfg(unix)]
#[test]
fn an_interrupted_study_leaves_the_old_results_and_nothing_else() {
    let (dir, _) = tmp("x");
    let out = dir.path().join("estimation");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("report.md"), "previous run\n").unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_experiments"))
        .args(["estimation", "-o", out.to_str().unwrap()])
        .current_dir(root())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(700));
    let _ = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status();
    let status = child.wait().unwrap();
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, vec!["estimation".to_string()], "left: {names:?}");
    if status.code() == Some(130) {
        // Interrupted: the previous results are untouched.
        assert_eq!(
            std::fs::read_to_string(out.join("report.md")).unwrap(),
            "previous run\n"
        );
    } else {
        // It finished first: the directory holds one whole new run.
        assert!(status.success());
        assert!(!out.join("report.md").exists() || out.join("report.json").exists());
    }
}

#[test]
fn coordinates_from_1e_minus_100_to_1e154_fit_the_same() {
    let raw = meshio::read_file(root().join("data/meshes/bunny.ply")).unwrap();
    let (dir, _) = tmp("x");
    let mut summaries = Vec::new();
    for scale in [1.0, 1e154, 1e-100] {
        let mut text = String::new();
        for p in &raw.positions {
            text.push_str(&format!(
                "v {:e} {:e} {:e}\n",
                p.x * scale,
                p.y * scale,
                p.z * scale
            ));
        }
        for f in raw.polygons.iter() {
            text.push_str(&format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1));
        }
        let path = dir.path().join(format!("bunny-{scale:e}.obj"));
        std::fs::write(&path, text).unwrap();
        let out = dir.path().join(format!("bunny-{scale:e}.jsonl"));
        let (code, err) = run(&[
            "fit",
            "--data",
            path.to_str().unwrap(),
            "--curves",
            "optimized",
            "--output",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{scale:e}: {err}");
        let first = std::fs::read_to_string(&out).unwrap();
        let rec: serde_json::Value = serde_json::from_str(first.lines().next().unwrap()).unwrap();
        let x = rec["points"][0][0].as_f64().unwrap();
        // The first control point is the first face's first vertex, in the file's units.
        assert!(
            (x / (f64::from(raw.positions[raw.polygons.get(0)[0]].x as f32) * scale) - 1.0).abs()
                < 1e-6
        );
        let fallback = err
            .lines()
            .find(|l| l.contains("fallback:"))
            .map(str::to_string);
        summaries.push(fallback);
    }
    // The fit is similarity-invariant: the same fallback faces at every scale.
    assert_eq!(summaries[0], summaries[1]);
    assert_eq!(summaries[0], summaries[2]);
}

/// `fit --out` streams its patches, with `--mesh-out` too (its tessellation builds each face's
/// nets again; `tests/tests/suite/streamed_fit.rs` checks it is the whole fit's, bit for bit): with
/// and without a tessellation it prints the same report — G1 figures, fallback faces by name,
/// curve counts — and writes the same bytes, in both patch forms, on a real mesh with fallback
/// faces.
/// An OBJ of a 6 × 6 grid on the paraboloid `z = (x² + y²)/4`, with vertex `(2, 1)` moved to the
/// midpoint of `(1, 1)` and `(2, 2)`: their face `((1, 1), (2, 1), (2, 2))` has zero area.
fn grid_with_a_zero_area_face() -> String {
    let n = 6;
    let z = |x: f64, y: f64| (x * x + y * y) / 4.0;
    let mut p: Vec<[f64; 3]> = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (i as f64 / 5.0 - 0.5, j as f64 / 5.0 - 0.5);
            p.push([x, y, z(x, y)]);
        }
    }
    let idx = |i: usize, j: usize| j * n + i;
    // Face (a, b, c) with b on the segment from a to c.
    let (a, b, c) = (idx(1, 1), idx(2, 1), idx(2, 2));
    p[b] = std::array::from_fn(|k| (p[a][k] + p[c][k]) / 2.0);
    let mut out = String::new();
    for q in &p {
        out += &format!("v {} {} {}\n", q[0], q[1], q[2]);
    }
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let (a, b, c, d) = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
            out += &format!(
                "f {} {} {}\nf {} {} {}\n",
                a + 1,
                b + 1,
                c + 1,
                a + 1,
                c + 1,
                d + 1
            );
        }
    }
    out
}

#[test]
fn fit_prints_and_writes_the_same_with_and_without_a_tessellation() {
    let dir = tempfile::tempdir().unwrap();
    // What depends on the run, not the fit: times, memory, where things were written.
    let report = |err: &str| -> Vec<String> {
        err.lines()
            .filter(|l| {
                ![
                    "time",
                    "peak memory",
                    "written to",
                    "streamed",
                    "tessellation",
                ]
                .iter()
                .any(|k| l.contains(k))
            })
            .map(str::to_string)
            .collect()
    };
    for ext in ["bzp", "jsonl"] {
        let streamed = dir.path().join(format!("streamed.{ext}"));
        let with_mesh = dir.path().join(format!("with-mesh.{ext}"));
        let mesh = dir.path().join("tess.obj");
        // A mesh with a fallback face (a zero-area face: one corner moved onto the segment
        // between the other two), whose path both runs must take alike.
        let obj = dir.path().join("sliver.obj");
        std::fs::write(&obj, grid_with_a_zero_area_face()).unwrap();
        let base = [
            "fit",
            "--data",
            obj.to_str().unwrap(),
            "--curves",
            "optimized",
        ];
        let (code, err_s) = run(&[&base[..], &["--output", streamed.to_str().unwrap()]].concat());
        assert_eq!(code, 0, "{err_s}");
        assert!(err_s.contains("streamed:"), "{err_s}");
        let (code, err_m) = run(&[
            &base[..],
            &[
                "--output",
                with_mesh.to_str().unwrap(),
                "--mesh-output",
                mesh.to_str().unwrap(),
            ],
        ]
        .concat());
        assert_eq!(code, 0, "{err_m}");
        assert!(err_m.contains("streamed:"), "{err_m}");
        assert!(err_s.contains("fallback: 1 faces"), "{err_s}");
        assert_eq!(report(&err_s), report(&err_m));
        assert!(
            std::fs::read(&streamed).unwrap() == std::fs::read(&with_mesh).unwrap(),
            "{ext}: the files differ"
        );
    }
}

/// The CAD box of the committed corpus: `fit` finds its creases by default, says so, keeps them
/// (the report's G1 leaves crease edges out and counts them), and `--no-creases` and
/// `--crease-angle` change what is found; bad angles and both options at once are usage errors.
#[test]
fn fit_finds_creases_on_a_cad_part_and_takes_the_crease_options() {
    let (_dir, report) = tmp("report.json");
    let box_ply = root().join("data/cad/box.ply");
    let data = box_ply.to_str().unwrap();
    let (code, err) = run(&["fit", "--data", data, "--report", &report]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("creases (auto): 152 edges"), "{err}");
    assert!(err.contains("creases: 152 edges C0"), "{err}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["creases"]["creases"], 152);
    assert_eq!(json["g1"]["crease_edges"], 152);
    assert_eq!(json["curve_counts"]["crease_edges"], 152);
    let (code, err) = run(&["fit", "--data", data, "--no-creases"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("creases (none): none"), "{err}");
    // At 100° the box's 90° edges are not creases.
    let (code, err) = run(&["fit", "--data", data, "--crease-angle", "100"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("creases (angle 100°): none"), "{err}");
    for bad in [
        vec!["--crease-angle", "0"],
        vec!["--crease-angle", "181"],
        vec!["--crease-angle", "x"],
        vec!["--crease-angle", "30", "--no-creases"],
    ] {
        let (code, err) = run(&[&["fit", "--data", data][..], &bad[..]].concat());
        assert_eq!(code, 2, "{bad:?}: {err}");
    }
}

/// `-o DIR` on a directory of the user's (issue 43's `thesis/thesis.tex`): every study that
/// writes a results directory refuses it with exit status 1, naming the file, and leaves it as
/// it was; a directory a run wrote is rewritten by the next run.
#[test]
fn a_study_refuses_a_directory_of_the_users_and_rewrites_its_own() {
    let dir = tempfile::tempdir().unwrap();
    let thesis = dir.path().join("thesis");
    std::fs::create_dir(&thesis).unwrap();
    std::fs::write(thesis.join("thesis.tex"), "x\n").unwrap();
    let t = thesis.to_str().unwrap();
    for args in [
        &["sweep", "--data", "octa", "--curves", "chord", "-o", t][..],
        &[
            "curve",
            "--input",
            "data/curve-problems.jsonl",
            "--curves",
            "chord",
            "--plot",
            t,
        ][..],
    ] {
        let (code, err) = run(args);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert!(err.contains("thesis.tex"), "{args:?}: {err}");
        assert_eq!(
            std::fs::read_to_string(thesis.join("thesis.tex")).unwrap(),
            "x\n"
        );
    }
    let own = dir.path().join("own");
    let o = own.to_str().unwrap();
    for _ in 0..2 {
        let (code, err) = run(&["sweep", "--data", "octa", "--curves", "chord", "-o", o]);
        assert_eq!(code, 0, "{err}");
    }
    assert!(own.join(".triwb-results").exists());
}

//! The fit job end to end: the streamed and the whole fit report the same numbers, the report
//! holds every fallback face, a raw mesh in memory is fitted as its file is, the outputs are
//! checked before any work, and the report serializes with its timings apart.

#![allow(clippy::expect_used)] // test fixtures fail loudly by design

use std::path::PathBuf;

use fitjob::{FitOptions, FitReport, InputOptions, JobError, Source};
use nalgebra::{Rotation3, Vector3};

fn data(name: &str) -> InputOptions {
    InputOptions {
        source: Source::Data {
            data: name.into(),
            resolution: None,
        },
        ..InputOptions::default()
    }
}

fn repo_file(rel: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(rel)
        .to_string_lossy()
        .into_owned()
}

fn quiet(options: FitOptions) -> Result<fitjob::FitOutcome, Box<JobError>> {
    fitjob::run(options, &mut |_| {}).map_err(Box::new)
}

/// The report without what differs between two runs of the same fit by design: the timings,
/// the memory, whether it was streamed, and the notes' timing line.
fn comparable(mut r: FitReport) -> FitReport {
    r.time = Default::default();
    r.peak_memory.clear();
    r.streamed = false;
    r.notes.retain(|n| !n.starts_with("time:"));
    if let Some(c) = &mut r.creases {
        c.time_seconds = 0.0;
    }
    r
}

#[test]
fn the_streamed_fit_and_the_kept_fit_report_the_same_numbers() {
    for (name, curves) in [
        ("ring", "optimized"),
        ("capsule", "dbhs"),
        ("octa", "chord"),
    ] {
        let options = FitOptions {
            input: data(name),
            curves: curves.into(),
            ..FitOptions::default()
        };
        let streamed = quiet(options.clone()).expect("streamed");
        assert!(streamed.report.streamed, "{name}: streamed by default");
        assert!(
            streamed.kept.fit.is_none(),
            "{name}: nothing kept unless asked"
        );
        let kept = quiet(FitOptions {
            keep: true,
            ..options
        })
        .expect("kept");
        assert!(!kept.report.streamed);
        let fit = kept.kept.fit.as_ref().expect("the fit is kept");
        let mesh = kept.kept.mesh.as_ref().expect("the mesh is kept");
        assert_eq!(
            fit.nets().count(),
            mesh.num_faces() * fit.layout.patches_per_face(),
            "{name}"
        );
        // Bit for bit: the same G1 figures, counts and settings.
        assert_eq!(
            comparable(streamed.report),
            comparable(kept.report),
            "{name}/{curves}"
        );
    }
}

#[test]
fn the_ring_is_g1_to_rounding_and_the_summary_says_so() {
    /// The G1 defect of the Shirman–Séquin ring is rounding: measured at about 1e-14 rad.
    const G1_ROUNDING: f64 = 1e-12;
    let outcome = quiet(FitOptions::default()).expect("fit");
    let r = &outcome.report;
    let g1 = r.g1.expect("measured");
    assert!(
        g1.interior_max < G1_ROUNDING && g1.exterior_max < G1_ROUNDING,
        "{g1:?}"
    );
    assert_eq!((r.vertices, r.edges, r.faces), (128, 384, 256));
    assert!(r.departures().is_empty());
    let lines = r.summary_lines();
    assert!(
        lines[0].starts_with("fit: ring (128 vertices, 384 edges, 256 faces), scheme shirman-sequin (G1), curves chord"),
        "{lines:?}"
    );
    assert!(lines[1].starts_with("  G1 defect: interior "), "{lines:?}");
}

/// A sphere whose given normals are turned by 120° at every third vertex: the faces around
/// them cannot be fitted G1 and fall back to the C0 patch, each with its reason.
fn spoiled_sphere() -> meshio::RawMesh {
    let d = mesh::dataset_by_name("sphere", None).expect("sphere");
    let positions: Vec<_> = d.mesh.vertices().iter().map(|v| v.data.p).collect();
    let mut raw = meshio::RawMesh::from_triangles(positions, d.mesh.faces());
    let turn = Rotation3::from_axis_angle(&Vector3::x_axis(), 2.0 * std::f64::consts::FRAC_PI_3);
    raw.normals = Some(
        d.mesh
            .vertices()
            .iter()
            .enumerate()
            .map(|(i, v)| {
                if i % 3 == 0 {
                    turn * v.data.n
                } else {
                    v.data.n
                }
            })
            .collect(),
    );
    raw
}

#[test]
fn the_report_holds_every_fallback_face_and_the_summary_the_first_ten() {
    let options = FitOptions {
        input: InputOptions {
            source: Source::Raw {
                label: "spoiled sphere".into(),
                raw: Box::new(spoiled_sphere()),
            },
            ..InputOptions::default()
        },
        keep: true,
        ..FitOptions::default()
    };
    let outcome = quiet(options).expect("fit");
    let r = &outcome.report;
    let fit = outcome.kept.fit.as_ref().expect("kept");
    let n = fit.face_fallbacks.len();
    assert!(n > fitjob::report::FALLBACKS_LISTED, "{n} fallbacks");
    assert_eq!(r.fallback_faces.len(), n);
    for (entry, fb) in r.fallback_faces.iter().zip(&fit.face_fallbacks) {
        assert_eq!(entry.face, fb.face);
        assert_eq!(entry.reason, fb.reason.to_string());
        assert_eq!(
            entry.file_face,
            Some(fb.face),
            "no face was dropped or reordered"
        );
    }
    let lines = r.summary_lines();
    let listed = lines.iter().filter(|l| l.starts_with("    face ")).count();
    assert_eq!(listed, fitjob::report::FALLBACKS_LISTED);
    assert!(
        lines.iter().any(|l| l == &format!("    … ({n} in all)")),
        "{lines:?}"
    );
    assert!(r
        .departures()
        .iter()
        .any(|(k, what)| *k == n && *what == "fallback faces"));
    // The JSON report carries them all, with the timings under `time` only.
    let json: serde_json::Value =
        serde_json::from_str(&r.to_json().expect("json")).expect("parses");
    assert_eq!(json["fallback_faces"].as_array().map(Vec::len), Some(n));
    assert!(json["time"]["fit"].is_number());
}

#[test]
fn a_raw_mesh_in_memory_is_fitted_as_its_file_is() {
    let path = repo_file("data/meshes/teapot.ply");
    let from_file = quiet(FitOptions {
        input: data(&path),
        ..FitOptions::default()
    })
    .expect("file");
    let raw = meshio::read_file(std::path::Path::new(&path)).expect("read");
    let from_memory = quiet(FitOptions {
        input: InputOptions {
            source: Source::Raw {
                label: path.clone(),
                raw: Box::new(raw),
            },
            ..InputOptions::default()
        },
        ..FitOptions::default()
    })
    .expect("memory");
    assert_eq!(comparable(from_file.report), comparable(from_memory.report));
}

#[test]
fn outputs_are_refused_before_any_work() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut stages = 0;
    let e = fitjob::run(
        FitOptions {
            patches_out: Some(dir.path().to_path_buf()),
            ..FitOptions::default()
        },
        &mut |_| stages += 1,
    )
    .err()
    .expect("a directory is no patch file");
    assert!(e.to_string().contains("a directory"), "{e}");
    let e = quiet(FitOptions {
        mesh_out: Some(dir.path().join("x.unknown")),
        ..FitOptions::default()
    })
    .err()
    .expect("no writer for .unknown");
    assert!(
        matches!(*e, JobError::UnsupportedOutputFormat { .. }),
        "{e}"
    );
    assert_eq!(stages, 0, "nothing ran");
    let e = quiet(FitOptions {
        scheme_options: surface::SchemeOptions::default()
            .with(&surface::scheme::shirman_sequin::BETA, 100.0),
        ..FitOptions::default()
    })
    .err()
    .expect("β out of range");
    assert!(
        e.to_string()
            .starts_with("--beta 100: outside its valid range"),
        "{e}"
    );
}

#[test]
fn the_outputs_written_are_those_reported() {
    let dir = tempfile::tempdir().expect("tempdir");
    let patches = dir.path().join("ring.bzp");
    let tess = dir.path().join("ring.ply");
    let outcome = quiet(FitOptions {
        patches_out: Some(patches.clone()),
        mesh_out: Some(tess.clone()),
        tess: 3,
        ..FitOptions::default()
    })
    .expect("fit");
    let t = outcome.report.tessellation.expect("tessellated");
    let written = meshio::read_file(&tess).expect("the mesh reads back");
    assert_eq!(written.num_vertices(), t.vertices);
    assert_eq!(written.num_faces(), t.triangles);
    // 256 faces × 3 sub-patches × 3² triangles.
    assert_eq!(t.triangles, 256 * 3 * 9);
    assert!(std::fs::metadata(&patches).expect("patches").len() > 0);
    // The sampling is timed on its own (scripts/compare_tessellation.py reads it), a part of
    // the tessellation stage, which also converts and writes.
    let time = outcome.report.time;
    assert!(
        time.sample > 0.0 && time.sample <= time.tessellate,
        "{time:?}"
    );
}

#[test]
fn a_subdivision_scheme_reports_its_approximation() {
    let outcome = quiet(FitOptions {
        scheme: "loop".into(),
        levels: 2,
        ..FitOptions::default()
    })
    .expect("loop");
    let s = outcome.report.subdivision.expect("subdivision");
    // Loop: every level multiplies the triangles by four.
    assert_eq!(s.faces, 256 * 16);
    assert!(s.approximation_max > 0.0 && s.approximation_max < s.model_size);
    assert!(outcome.report.g1.is_none());
}

/// Folds are measured with G1, named in the report and the summary, and are a departure that
/// fails `--strict`: the spoiled sphere (normals turned at random on some vertices) folds
/// faces; the exact sphere folds none.
#[test]
fn folded_faces_are_reported_and_count_as_departures() {
    let spoiled = quiet(FitOptions {
        input: InputOptions {
            source: Source::Raw {
                label: "spoiled sphere".into(),
                raw: Box::new(spoiled_sphere()),
            },
            ..InputOptions::default()
        },
        ..FitOptions::default()
    })
    .expect("fit");
    let r = &spoiled.report;
    let folds = r.folds.as_ref().expect("measured with G1");
    assert_eq!(folds.faces_measured, r.faces);
    assert!(!folds.folded_faces.is_empty());
    assert!(folds.worst_cosine.expect("measured") <= 0.0);
    let n = folds.folded_faces.len();
    assert!(r
        .departures()
        .iter()
        .any(|(k, what)| *k == n && *what == "folded faces"));
    assert!(r
        .summary_lines()
        .iter()
        .any(|l| l.starts_with(&format!("  folds: {n} of {} faces", r.faces))));

    let exact = quiet(FitOptions {
        input: InputOptions {
            source: Source::Data {
                data: "sphere".into(),
                resolution: None,
            },
            ..InputOptions::default()
        },
        ..FitOptions::default()
    })
    .expect("fit");
    let folds = exact.report.folds.as_ref().expect("measured");
    assert!(folds.folded_faces.is_empty());
    assert!(!exact
        .report
        .departures()
        .iter()
        .any(|(_, what)| *what == "folded faces"));
}

/// The subdivision schemes get the detected creases as crease tags. On the fixture cube (4 × 4
/// cells a side, evenly spaced) the tagged rules reproduce the data at the original vertices:
/// corners stay, a crease vertex's limit `(a + 4p + b)/6` is `p` for evenly spaced collinear
/// neighbours, and a regular vertex of a flat side has its valence-6 ring centrally symmetric
/// in the plane, so Loop's limit stencil gives `p`. Untagged, the smooth rules round the cube
/// off; Catmull–Clark (quads after its first step) is at least far closer tagged than not.
#[test]
fn subdivision_gets_the_detected_creases_as_tags() {
    /// Loop's limit stencils on the tagged cube: affine combinations of a few points of size
    /// one, rounding only.
    const LIMIT_ROUNDING: f64 = 1e-12;
    /// Untagged, the corners are pulled in by a sizeable fraction of the cube (measured: the
    /// tagged Catmull–Clark error is below a tenth of the untagged one).
    const IMPROVEMENT: f64 = 10.0;
    for scheme in ["loop", "catmull-clark"] {
        let run_with = |creases| {
            let outcome = quiet(FitOptions {
                input: InputOptions {
                    source: Source::Raw {
                        label: "the fixture cube".into(),
                        raw: Box::new(fixtures::creases::cube(4)),
                    },
                    creases,
                    ..InputOptions::default()
                },
                scheme: scheme.into(),
                levels: 2,
                ..FitOptions::default()
            })
            .expect("subdivides");
            outcome.report.subdivision.expect("a subdivision summary")
        };
        let tagged = run_with(mesh::features::CreaseRule::Auto);
        let smooth = run_with(mesh::features::CreaseRule::None);
        if scheme == "loop" {
            assert!(
                tagged.approximation_max <= LIMIT_ROUNDING * tagged.model_size,
                "{tagged:?}"
            );
        }
        assert!(
            tagged.approximation_max * IMPROVEMENT < smooth.approximation_max,
            "{scheme}: tagged {tagged:?}, smooth {smooth:?}"
        );
    }
}

/// A crease only the file marks (smoothing groups on a 23° ridge, below the geometric
/// threshold) is a crease tag of the subdivision schemes too: Catmull–Clark then keeps the
/// ridge, where the smooth rule rounds it off.
#[test]
fn subdivision_gets_the_files_creases_as_tags() {
    /// Far above rounding, far below the 4e-3 the ridge makes: the two runs differ only there.
    const RMS_RESOLUTION: f64 = 1e-3;
    let mut obj = String::new();
    for y in -2i32..=2 {
        for x in 0..=3 {
            obj += &format!("v {x} {y} {}\n", 0.2 * f64::from(2 - y.abs()));
        }
    }
    let id = |x: i32, y: i32| (y + 2) * 4 + x + 1;
    for y in -2..2 {
        obj += &format!("s {}\n", if y < 0 { 1 } else { 2 });
        for x in 0..3 {
            obj += &format!(
                "f {} {} {} {}\n",
                id(x, y),
                id(x + 1, y),
                id(x + 1, y + 1),
                id(x, y + 1)
            );
        }
    }
    let raw = meshio::read_bytes(std::path::Path::new("tent.obj"), obj.as_bytes()).unwrap();
    assert_eq!(raw.crease_edges.len(), 3, "the ridge's three edges");
    let run_with = |creases| {
        quiet(FitOptions {
            input: InputOptions {
                source: Source::Raw {
                    label: "tent.obj".into(),
                    raw: Box::new(raw.clone()),
                },
                creases,
                ..InputOptions::default()
            },
            scheme: "catmull-clark".into(),
            levels: 2,
            ..FitOptions::default()
        })
        .expect("subdivides")
        .report
        .subdivision
        .expect("a subdivision summary")
    };
    let tagged = run_with(mesh::features::CreaseRule::Auto);
    let smooth = run_with(mesh::features::CreaseRule::None);
    // The ridge's two inner vertices keep their place under the crease rule (evenly spaced
    // collinear neighbours); the rest of the tent (its open corners move under the boundary
    // rule either way) is the same, so only the RMS can tell — measured 0.1065 against 0.1106.
    assert!(
        tagged.approximation_rms + RMS_RESOLUTION < smooth.approximation_rms,
        "tagged {tagged:?}, smooth {smooth:?}"
    );
}

#[test]
fn a_radius_estimates_on_balls_and_a_bad_one_is_a_usage_error() {
    let path = repo_file("data/meshes/teapot.ply");
    let with = |estimate: &str, radius: Option<f64>| {
        fitjob::input::load(&InputOptions {
            estimate: estimate.into(),
            radius,
            ..data(&path)
        })
        .map_err(Box::new)
    };
    let balls = with("hybrid", Some(4.0)).expect("radius 4");
    assert!(
        balls
            .notes
            .iter()
            .any(|n| n.contains(estimate::multiscale::BALL_NAME)),
        "{:?}",
        balls.notes
    );
    let rings = with("hybrid", None).expect("default");
    let differs = balls
        .mesh
        .vertices()
        .iter()
        .zip(rings.mesh.vertices())
        .any(|(a, b)| a.data.shape != b.data.shape);
    assert!(differs, "the ball estimate is not the default's");
    for (estimate, radius) in [
        ("hybrid", 0.0),
        ("hybrid", -1.0),
        ("hybrid", f64::NAN),
        ("none", 3.0),
    ] {
        let err = with(estimate, Some(radius)).err().expect("refused");
        assert!(err.is_usage(), "{estimate} --radius {radius}: {err}");
        assert!(err.to_string().contains("--radius"), "{err}");
    }
}

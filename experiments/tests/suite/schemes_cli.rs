//! `schemes`: every registered scheme on every data set; the report lists each pair once, every
//! G1 claim holds, and the pictures are written.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

#[test]
fn the_study_covers_every_scheme_and_data_set_and_g1_claims_hold() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("schemes");
    let (code, _, err) = common::run(
        &[
            "schemes",
            "--curves",
            "chord",
            "--face-segments",
            "3",
            "-o",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let all = report["results"].as_array().unwrap();
    let (subdivision, results): (Vec<_>, Vec<_>) =
        all.iter().partition(|r| r["kind"] == "subdivision");
    assert_eq!(
        results.len(),
        surface::scheme::REGISTRY.len() * surface::DATASET_NAMES.len()
    );
    // Loop and Catmull–Clark (Warren's Loop differs from Loop only in β) on every data set,
    // approximating: the limit moves off the data points, by less than the model size.
    assert_eq!(subdivision.len(), 2 * surface::DATASET_NAMES.len());
    for r in &subdivision {
        let d = r["data_to_limit_max"].as_f64().unwrap();
        assert!(d > 0.0 && d < 1.0, "{r}");
    }
    for r in results {
        assert_eq!(r["claim_holds"], true, "{r}");
        assert!(
            r["interpolation_position_error"].as_f64().unwrap() < 1e-9,
            "{r}"
        );
        if r["continuity"] == "g1" {
            assert!(r["g1_exterior_radians"].as_f64().unwrap() < 1e-9, "{r}");
        }
    }
    for name in surface::DATASET_NAMES {
        let png = std::fs::metadata(out.join(format!("{name}.png"))).unwrap();
        assert!(png.len() > 10_000, "{name}.png is {} bytes", png.len());
    }
}

/// `schemes --data` takes the user's own meshes beside the data sets (comma-separated): each
/// file repaired, completed by the estimator and fitted by every scheme, its error columns
/// empty (no true surface), its picture named after the file.
#[test]
fn the_study_takes_the_users_own_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("schemes");
    let (code, _, err) = common::run(
        &[
            "schemes",
            "--data",
            "data/octa.m,octa",
            "--curves",
            "chord",
            "--face-segments",
            "2",
            "-o",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let all = report["results"].as_array().unwrap();
    let per_mesh = surface::scheme::REGISTRY.len() + 2;
    assert_eq!(all.len(), 2 * per_mesh);
    let (file, set): (Vec<_>, Vec<_>) = all.iter().partition(|r| r["dataset"] == "data/octa.m");
    assert_eq!(file.len(), per_mesh);
    assert_eq!(set.len(), per_mesh);
    for r in &file {
        assert!(r["errors"].is_null(), "no true surface: {r}");
        assert!(r["triangles"].as_u64().unwrap() > 0, "{r}");
        if r["kind"] != "subdivision" {
            assert_eq!(r["claim_holds"], true, "{r}");
        }
    }
    for r in &set {
        assert!(r["errors"]["position_max"].as_f64().is_some(), "{r}");
    }
    assert_eq!(
        report["options"]["data"],
        serde_json::json!(["data/octa.m", "octa"])
    );
    assert_eq!(report["options"]["face_segments"], 2);
    assert!(out.join("octa.png").is_file() && out.join("octa-2.png").is_file());
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("## data/octa.m (8 faces)"), "{md}");
    assert!(md.contains("— | — | — | —"), "{md}");
}

/// `fit --scheme` writes the scheme's layout (degree, sub-patches per face) and refuses interior
/// parameters a scheme does not have, naming the scheme.
#[test]
fn fit_writes_any_scheme_and_refuses_interior_choices_it_lacks() {
    let dir = tempfile::tempdir().unwrap();
    for (scheme, degree, per_face) in [
        ("flat", 1, 1),
        ("pn-triangles", 3, 1),
        ("phong", 2, 1),
        ("clough-tocher", 3, 3),
        ("powell-sabin", 2, 6),
        ("shirman-sequin", 4, 3),
    ] {
        let out = dir.path().join(format!("{scheme}.jsonl"));
        let (code, _, err) = common::run(
            &[
                "fit",
                "--data",
                "octa",
                "--scheme",
                scheme,
                "--output",
                out.to_str().unwrap(),
            ],
            "",
        );
        assert_eq!(code, 0, "{scheme}: {err}");
        let text = std::fs::read_to_string(&out).unwrap();
        let lines: Vec<serde_json::Value> = text
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(lines.len(), 8 * per_face, "{scheme}");
        for l in &lines {
            assert_eq!(l["degree"], degree, "{scheme}");
            assert_eq!(
                l["points"].as_array().unwrap().len(),
                (degree + 1) * (degree + 2) / 2
            );
        }
    }
    let (code, _, err) = common::run(
        &[
            "fit",
            "--data",
            "octa",
            "--scheme",
            "phong",
            "--interior",
            "thin-plate",
        ],
        "",
    );
    assert_ne!(code, 0);
    assert!(
        err.contains("`phong` scheme has no interior parameters"),
        "{err}"
    );
    let (code, _, err) = common::run(&["fit", "--data", "octa", "--scheme", "bogus"], "");
    assert_ne!(code, 0);
    assert!(err.contains("clough-tocher"), "{err}");
}

/// `fit --scheme loop|catmull-clark --levels N --mesh-out` writes the control mesh after N
/// steps (4ᴺ times the faces), keeps an OBJ's quads for Catmull–Clark, reports the distance to
/// the limit, and refuses a level count whose output would not fit.
#[test]
fn fit_subdivides_with_levels_and_refuses_what_would_not_fit() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("octa-loop.obj");
    let (code, _, err) = common::run(
        &[
            "fit",
            "--data",
            "octa",
            "--scheme",
            "loop",
            "--levels",
            "2",
            "--mesh-output",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("data point to limit surface"), "{err}");
    let raw = meshio::read_file(&out).unwrap();
    assert_eq!(raw.polygons.len(), 8 * 16);
    // A cube of quads: one Catmull–Clark step gives 24 quads.
    let cube = dir.path().join("cube.obj");
    std::fs::write(
        &cube,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
         f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n",
    )
    .unwrap();
    let out = dir.path().join("cube-cc.obj");
    let (code, _, err) = common::run(
        &[
            "fit",
            "--data",
            cube.to_str().unwrap(),
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "--mesh-output",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let raw = meshio::read_file(&out).unwrap();
    assert_eq!(raw.polygons.len(), 24);
    assert!(raw.polygons.iter().all(|p| p.len() == 4));
    let (code, _, err) = common::run(
        &[
            "fit", "--data", "octa", "--scheme", "loop", "--levels", "40",
        ],
        "",
    );
    assert_ne!(code, 0);
    assert!(err.contains("over the limit"), "{err}");
}

//! Height fields through the fit job: detected by default and fitted with the functional C1
//! forms (the note says so and the G1 measure holds the claim), required with
//! `HeightFieldMode::On` (an error on other data), refused with `Off`.

#![allow(clippy::expect_used)] // test fixtures fail loudly by design

use fitjob::{FitOptions, InputOptions, JobError, Source};
use surface::scheme::functional::HeightFieldMode;

/// The G1 claim of docs/conventions.md.
const G1_TOL: f64 = 1e-9;

fn franke(
    name: &str,
    scheme: &str,
    heightfield: HeightFieldMode,
) -> Result<fitjob::FitOutcome, Box<JobError>> {
    fitjob::run(
        FitOptions {
            input: InputOptions {
                source: Source::Data {
                    data: name.into(),
                    resolution: None,
                },
                ..InputOptions::default()
            },
            scheme: scheme.into(),
            heightfield,
            ..FitOptions::default()
        },
        &mut |_| {},
    )
    .map_err(Box::new)
}

#[test]
fn franke_data_is_detected_and_fitted_c1() {
    for scheme in ["clough-tocher", "powell-sabin"] {
        for name in ["franke1", "franke3@scattered"] {
            let r = franke(name, scheme, HeightFieldMode::Auto)
                .expect("fit")
                .report;
            assert_eq!(r.continuity, "C1", "{scheme} {name}");
            assert!(
                r.notes
                    .iter()
                    .any(|n| n.starts_with("detected a height field")),
                "{:?}",
                r.notes
            );
            let g1 = r.g1.expect("measured");
            assert!(
                g1.interior_max < G1_TOL && g1.exterior_max < G1_TOL,
                "{scheme} {name}: {g1:?}"
            );
            assert!(r.summary_lines().iter().any(|l| l.contains("G1 defect")));
        }
    }
}

#[test]
fn off_keeps_the_parametric_scheme_and_on_refuses_other_data() {
    let r = franke("franke1", "clough-tocher", HeightFieldMode::Off)
        .expect("fit")
        .report;
    assert_eq!(r.continuity, "C0");
    assert!(!r.notes.iter().any(|n| n.contains("height field")));
    let e = franke("ring", "clough-tocher", HeightFieldMode::On)
        .err()
        .expect("not a height field");
    assert!(matches!(*e, JobError::HeightField { .. }));
    assert!(
        fitjob::error::chain(&*e).contains("n_z"),
        "{}",
        fitjob::error::chain(&*e)
    );
    let e = franke("franke2", "shirman-sequin", HeightFieldMode::On)
        .err()
        .expect("no functional form");
    assert!(fitjob::error::chain(&*e).contains("no functional form"));
}

#[test]
fn a_file_of_points_is_triangulated_in_xy_and_fitted_as_a_height_field() {
    // F4's gentle hill sampled at 7 × 7 points, written with positions only (no faces, no
    // normals): Delaunay in (x, y), normals estimated, then the functional C1 schemes.
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("points.ply");
    let mut raw = meshio::RawMesh::default();
    let mut rng = fixtures::SplitMix64::new(4);
    for j in 0..7 {
        for i in 0..7 {
            // Interior points moved off the grid: no four on a circle.
            let interior = i % 6 != 0 && j % 6 != 0;
            let jitter = |r: &mut fixtures::SplitMix64| {
                if interior {
                    r.uniform(-0.03, 0.03)
                } else {
                    0.0
                }
            };
            let (x, y) = (
                i as f64 / 6.0 + jitter(&mut rng),
                j as f64 / 6.0 + jitter(&mut rng),
            );
            let z = mesh::analytic_franke::Franke::F4.jet(x, y).f;
            raw.positions.push(nalgebra::Point3::new(x, y, z));
        }
    }
    let bytes = meshio::write_bytes(
        &raw,
        meshio::format_by_name("ply").expect("ply"),
        &meshio::WriteOptions::default(),
    )
    .expect("encode");
    std::fs::write(&path, bytes).expect("write");
    let r = fitjob::run(
        FitOptions {
            input: InputOptions {
                source: Source::Data {
                    data: path.to_string_lossy().into_owned(),
                    resolution: None,
                },
                ..InputOptions::default()
            },
            scheme: "powell-sabin".into(),
            heightfield: HeightFieldMode::On,
            ..FitOptions::default()
        },
        &mut |_| {},
    )
    .expect("fit")
    .report;
    assert!(
        r.notes
            .iter()
            .any(|n| n.starts_with("no faces in the file")),
        "{:?}",
        r.notes
    );
    assert_eq!(
        r.faces, 72,
        "2V − h − 2 Delaunay triangles, 24 points on the hull"
    );
    assert_eq!(r.continuity, "C1");
    let g1 = r.g1.expect("measured");
    assert!(g1.exterior_max < G1_TOL, "{g1:?}");
}

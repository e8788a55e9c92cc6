//! `schemes`: every registered scheme on every data set; the report lists each pair once, every
//! G1 claim holds, and the pictures are written.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

mod common;

#[test]
fn the_study_covers_every_scheme_and_data_set_and_g1_claims_hold() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("schemes");
    let (code, _, err) = common::run(
        &[
            "schemes",
            "--curves",
            "chord",
            "--density",
            "3",
            "--out",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let results = report["results"].as_array().unwrap();
    assert_eq!(
        results.len(),
        surface::scheme::REGISTRY.len() * surface::DATASET_NAMES.len()
    );
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

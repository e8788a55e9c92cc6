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

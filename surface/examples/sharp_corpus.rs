//! The sharp-feature measure ([`surface::sharp`]) of the committed scans fitted the default
//! way: `cargo run --release -p surface --example sharp_corpus [FILE.ply ...]` (default:
//! `bunny.ply`, `teapot.ply` and `dragon_res4.ply` of `data/meshes/`).
//!
//! Each file is read, repaired and completed by the default estimator in its working frame
//! (`estimate::prepare`, the fit job's input) and fitted with the default scheme on `chord`
//! curves (the fit job's defaults, `fitjob::FitOptions::default`); the report is printed as one
//! JSON line a file, after a summary line.

// A measurement driver on committed files: a failed step should stop it loudly.
#![allow(clippy::expect_used)]

use std::path::PathBuf;
use std::time::Instant;

use curves::{method_by_name, MethodOptions};
use estimate::{prepare_owned, EstimateChoice, DEFAULT_ESTIMATOR};
use surface::{fit_scheme, scheme_by_name, sharp, SchemeOptions, DEFAULT_SCHEME};

fn main() {
    let given: Vec<PathBuf> = std::env::args().skip(1).map(PathBuf::from).collect();
    let files = if given.is_empty() {
        let dir = fixtures::corpus::corpus_dir();
        ["bunny.ply", "teapot.ply", "dragon_res4.ply"]
            .iter()
            .map(|f| dir.join(f))
            .collect()
    } else {
        given
    };
    let choice = EstimateChoice::parse(DEFAULT_ESTIMATOR).expect("the default estimator");
    let scheme = scheme_by_name(DEFAULT_SCHEME, &SchemeOptions::default()).expect("the scheme");
    let method = method_by_name(
        &std::env::var("CURVES").unwrap_or("chord".into()),
        &MethodOptions::default(),
    )
    .expect("chord");
    for path in files {
        let raw = meshio::read_file(&path).expect("a readable mesh");
        let mesh = prepare_owned(raw, choice, false)
            .expect("a repairable mesh")
            .mesh;
        let fit = fit_scheme(&mesh, scheme.as_ref(), method.as_ref()).expect("a fit");
        let t = Instant::now();
        let r = sharp::measure(&mesh, &fit).expect("the fit of this mesh");
        let seconds = t.elapsed().as_secs_f64();
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        println!(
            "{name}: {} faces ({} fallback), {} interior edges; smooth {} (kinked {}, severe {}, worst {:.3e} rad); creases kept {} ({} at a fallback) of {}; flat regions {} ({} faces, largest {}, {} rejected, {} blended), deviation {:.3e}; measured in {:.3} s",
            mesh.num_faces(),
            fit.face_fallbacks.len(),
            r.interior_edges,
            r.smooth.edges,
            r.smooth.kinked,
            r.smooth.severe,
            r.smooth.worst.map_or(0.0, |w| w.fitted),
            r.creases.kept,
            r.creases.kept_at_fallback,
            r.creases.candidates,
            r.flat.regions,
            r.flat.faces,
            r.flat.largest_region,
            r.flat.rejected_regions,
            r.flat.blended_regions,
            r.flat.deviation,
            seconds,
        );
        println!(
            "{}",
            serde_json::to_string(&r).expect("a report serializes")
        );
    }
}

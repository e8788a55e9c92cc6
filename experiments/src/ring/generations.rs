//! The three generations of the Shirman–Séquin split-domain scheme on the ring, side by side:
//! the original 1987 construction (`shirman-sequin-1987`, α₂ = 9/4) on Furth's planar tangents
//! (the workbench's `chord`, the original fitter's default), the original testbed's modified
//! fitter (`shirman-sequin-testbed`) on the tangent-plane projection (its default), and Mann's
//! modified scheme (`shirman-sequin`, β = 1/3, c = 1) on optimized curves (his report's
//! proposal). Each is fitted by the fit job on the study's ring, tessellated, measured against
//! the torus (as the main table) with its G1 defect, and drawn beside the true ring in
//! `generations/` (shaded, K, distance; the main pictures' cameras and colour rules).

use std::fmt::Write as _;
use std::path::Path;

use curves::MethodOptions;
use serde_json::{json, Value};
use surface::{compare_with_truth, AnalyticSurface, Mesh};

use super::render::render_all;
use super::surfaces::{surfaces_view, Surface};
use crate::error::ExperimentError;

/// The generations: file stem, scheme, curve construction, label.
pub(super) const GENERATIONS: [(&str, &str, &str, &str); 3] = [
    (
        "ss-1987",
        "shirman-sequin-1987",
        "chord",
        "Shirman–Séquin 1987, Furth (chord) curves",
    ),
    (
        "ss-testbed",
        "shirman-sequin-testbed",
        "projection",
        "testbed's modified fitter, projection curves",
    ),
    (
        "ss-mann",
        "shirman-sequin",
        "optimized",
        "Mann's modified scheme, optimized curves",
    ),
];

/// Fits, measures and draws the generations into `out/generations/`; returns the report's
/// `generations` entry and the markdown section.
pub(super) fn run(
    out: &Path,
    mesh: &Mesh,
    truth: &dyn AnalyticSurface,
    true_ring: &Surface,
    resolution: usize,
    segments: usize,
    options: &MethodOptions,
) -> Result<(Value, String), ExperimentError> {
    let mut surfaces = Vec::with_capacity(GENERATIONS.len());
    let mut rows = Vec::new();
    for (stem, scheme, curves, label) in GENERATIONS {
        let kept = crate::input::fit_kept(fitjob::FitOptions {
            input: fitjob::InputOptions {
                source: fitjob::Source::DataSet {
                    name: "ring".into(),
                    resolution: Some(resolution),
                },
                ..fitjob::InputOptions::default()
            },
            scheme: scheme.into(),
            curves: curves.into(),
            method_options: *options,
            ..fitjob::FitOptions::default()
        })?;
        let tess = surface::tessellate_fit(mesh, &kept.fit, segments).map_err(|source| {
            ExperimentError::Tessellate {
                subject: format!("ring/{stem}"),
                source,
            }
        })?;
        let errors = compare_with_truth(&tess, truth);
        rows.push((stem, scheme, curves, label, kept.g1.max_angle(), errors));
        surfaces.push(Surface {
            name: stem,
            label: label.into(),
            tess,
            flat: false,
            errors,
        });
    }
    let dir = out.join("generations");
    crate::output::ensure_dir(&dir)?;
    // The true ring first, then the generations.
    let mut views = surfaces_view(std::slice::from_ref(true_ring));
    views.extend(surfaces_view(&surfaces));
    let pictures = render_all(&dir, &views)?;
    let json = json!({
        "pictures": pictures,
        "fits": rows.iter().map(|(stem, scheme, curves, _, g1, e)| json!({
            "name": stem,
            "scheme": scheme,
            "curves": curves,
            "g1_max_rad": g1,
            "position_max": e.position_max,
            "normal_max_degrees": e.normal_max_degrees,
            "gaussian_rms": e.gaussian_rms,
            "gaussian_max": e.gaussian_max,
            "mean_rms": e.mean_rms,
            "mean_max": e.mean_max,
        })).collect::<Vec<_>>(),
    });
    let mut md = String::new();
    let _ = writeln!(
        md,
        "\n## Three generations of Shirman–Séquin\n\nThe 1987 construction on Furth's tangents, the original testbed's modified fitter on its projection tangents, and Mann's modified scheme on optimized curves, each with its own defaults, on the same ring at s = {segments}.\n"
    );
    let _ = writeln!(
        md,
        "| surface | scheme | curves | G1 defect (rad) | position max | normal max (°) | K RMS | K max | H RMS | H max |"
    );
    let _ = writeln!(md, "|---|---|---|---:|---:|---:|---:|---:|---:|---:|");
    for (_, scheme, curves, label, g1, e) in &rows {
        let _ = writeln!(
            md,
            "| {label} | `{scheme}` | `{curves}` | {g1:.1e} | {:.2e} | {:.3} | {:.4} | {:.3} | {:.4} | {:.3} |",
            e.position_max,
            e.normal_max_degrees,
            e.gaussian_rms,
            e.gaussian_max,
            e.mean_rms,
            e.mean_max
        );
    }
    let _ = writeln!(
        md,
        "\n![generations, K](generations/kcolor.png)\n\nAlso [shaded](generations/shaded.png) and [distance](generations/radial.png)."
    );
    Ok((json, md))
}

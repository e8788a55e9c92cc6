//! The ring study's report: `report.json` (stable keys; timings only under keys that say
//! `time`), `report.md` with its tables, pictures and findings, and the summary printed on
//! standard output.

use std::fmt::Write as _;

use curves::MethodOptions;
use serde_json::{json, Map, Value};
use surface::{Mesh, SurfaceErrors};

use super::surfaces::{FittedMethod, Surface};
use super::RingArgs;

fn errors_json(e: &SurfaceErrors) -> Value {
    serde_json::to_value(e).unwrap_or(Value::Null)
}

/// Each construction's record: fit time, G1 defect, interpolation error, curve measures.
fn method_records(fits: &[FittedMethod]) -> Map<String, Value> {
    let mut method_records = Map::new();
    for FittedMethod {
        name,
        g1,
        curves: cs,
        fit_time_seconds: fit_time,
        ..
    } in fits
    {
        method_records.insert(
            name.to_string(),
            json!({
                "fit_time_seconds": fit_time,
                "g1_defect_interior_radians": g1.interior_max,
                "g1_defect_exterior_radians": g1.exterior_max,
                "interpolation_position_error": g1.position_error,
                "interpolation_normal_error_radians": g1.normal_error,
                "curves": {
                    "end_curvature_error_max": cs.end_curvature_error_max,
                    "end_curvature_error_rms": cs.end_curvature_error_rms,
                    "shortest_alpha": cs.shortest_alpha,
                    "curvature_variation_max": cs.curvature_variation_max,
                    "curvature_variation_median": cs.curvature_variation_median,
                    "fallbacks_to_chord": cs.fallbacks,
                    "unconverged_optimizations": cs.unconverged,
                },
            }),
        );
    }
    method_records
}

/// The content of `report.json`.
pub(super) fn report_json(
    args: &RingArgs,
    mesh: &Mesh,
    surfaces: &[Surface],
    fits: &[FittedMethod],
    figure2: Value,
    pictures: Value,
    times: Map<String, Value>,
) -> Value {
    let defaults = MethodOptions::default();
    let (big, small) = (
        surface::datasets::RING_MAJOR_RADIUS,
        surface::datasets::RING_TUBE_RADIUS,
    );
    let surface_records: Vec<Value> = surfaces
        .iter()
        .map(|s| {
            json!({
                "surface": s.name,
                "label": s.label,
                "samples": s.tess.positions.len(),
                "triangles": s.tess.faces.len(),
                "errors": errors_json(&s.errors),
            })
        })
        .collect();
    json!({
        "experiment": "ring",
        "data": {
            "torus": {"major_radius": big, "minor_radius": small},
            "resolution": [args.resolution, (args.resolution / 2).max(3)],
            "vertices": mesh.num_vertices(), "edges": mesh.num_edges(), "faces": mesh.num_faces(),
        },
        "settings": {
            "segments": args.segments, "solver": args.curve.solver.name(), "dbhs_pick": args.curve.dbhs_pick.to_string(),
            "interior": args.interior.choice.to_string(),
            "optimized_weights": [defaults.weights.tangent, defaults.weights.curvature],
            "optimized_alpha_min": defaults.alpha_min,
        },
        "surfaces": surface_records,
        "methods": method_records(fits),
        "figure2": figure2,
        "pictures": pictures,
        "times": times,
    })
}

fn fmt_e(x: f64) -> String {
    format!("{x:.3e}")
}

/// The summary printed on standard output: the surfaces' errors and the curves' measures.
pub(super) fn summary(surfaces: &[Surface], fits: &[FittedMethod], total: f64) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<12} {:>11} {:>11} {:>9} {:>9} {:>9} {:>9}",
        "surface", "pos max", "pos rms", "nrm max°", "nrm rms°", "K rms", "H rms"
    );
    for x in surfaces {
        let e = &x.errors;
        let _ = writeln!(
            s,
            "{:<12} {:>11} {:>11} {:>9.3} {:>9.3} {:>9.4} {:>9.4}",
            x.name,
            fmt_e(e.position_max),
            fmt_e(e.position_rms),
            e.normal_max_degrees,
            e.normal_rms_degrees,
            e.gaussian_rms,
            e.mean_rms
        );
    }
    let _ = writeln!(
        s,
        "\n{:<12} {:>10} {:>12} {:>12} {:>14} {:>9}",
        "curves", "G1 (rad)", "κ err max", "shortest α", "∫κ'² ds max", "fallback"
    );
    for FittedMethod {
        name,
        g1,
        curves: cs,
        ..
    } in fits
    {
        let _ = writeln!(
            s,
            "{:<12} {:>10} {:>12.4} {:>12.4} {:>14} {:>9}",
            name,
            fmt_e(g1.max_angle()),
            cs.end_curvature_error_max,
            cs.shortest_alpha,
            fmt_e(cs.curvature_variation_max),
            cs.fallbacks
        );
    }
    let _ = writeln!(s, "\ntotal {total:.2} s");
    s
}

/// The content of `report.md`.
pub(super) fn markdown(
    args: &RingArgs,
    report: &Value,
    surfaces: &[Surface],
    fits: &[FittedMethod],
) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# The ring study\n");
    let _ = writeln!(
        md,
        "Written by `cargo run --release -p experiments -- ring --resolution {} --segments {} --solver {} --dbhs-pick {} --interior {} --scheme {}{} --output {}`.\n",
        args.resolution,
        args.segments,
        args.curve.solver,
        args.curve.dbhs_pick,
        args.interior.choice,
        args.scheme.scheme,
        // The scheme parameters set away from their defaults (the registry's).
        surface::scheme::parameters_of(surface::scheme::REGISTRY)
            .iter()
            .filter(|(p, _)| args.scheme.options.value(p) != p.default)
            .map(|(p, _)| format!(" --{} {}", p.name, args.scheme.options.value(p)))
            .collect::<String>(),
        args.output.display()
    );
    let _ = writeln!(
        md,
        "Data: a torus with R = 1, r = 0.4 sampled {} × {} with exact positions, normals and shape tensors \
         ({} vertices, {} edges, {} faces). Surfaces tessellated at s = {} segments per patch edge and \
         measured at every tessellation vertex against the torus. Interior parameters: β = 1/3, c = 1 \
         (the Shirman–Séquin defaults) unless `--interior` says otherwise. Optimized curves: weights (1, 1), α ≥ 0.05, solver {}.\n",
        args.resolution,
        (args.resolution / 2).max(3),
        report["data"]["vertices"],
        report["data"]["edges"],
        report["data"]["faces"],
        args.segments,
        args.curve.solver
    );
    let _ = writeln!(md, "## Surfaces against the true ring\n");
    let _ = writeln!(md, "| surface | samples | position max | position RMS | normal max (°) | normal RMS (°) | K RMS | K max | H RMS | H max |");
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for s in surfaces {
        let e = &s.errors;
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.3} | {:.3} | {:.4} | {:.3} | {:.4} | {:.3} |",
            s.label,
            e.samples,
            fmt_e(e.position_max),
            fmt_e(e.position_rms),
            e.normal_max_degrees,
            e.normal_rms_degrees,
            e.gaussian_rms,
            e.gaussian_max,
            e.mean_rms,
            e.mean_max
        );
    }
    let _ = writeln!(md, "\n## Boundary curves and continuity\n");
    let _ = writeln!(md, "| curves | G1 defect (rad) | end-curvature error max | RMS | shortest α | ∫(dκ/ds)² ds max | median | fallbacks | unconverged |");
    let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for FittedMethod {
        name,
        g1,
        curves: cs,
        ..
    } in fits
    {
        let _ = writeln!(
            md,
            "| {} | {} | {:.4} | {:.4} | {:.4} | {} | {} | {} | {} |",
            name,
            fmt_e(g1.max_angle()),
            cs.end_curvature_error_max,
            cs.end_curvature_error_rms,
            cs.shortest_alpha,
            fmt_e(cs.curvature_variation_max),
            fmt_e(cs.curvature_variation_median),
            cs.fallbacks,
            cs.unconverged
        );
    }
    let _ = writeln!(md, "\nCurve measures are on the unit chord (curvature × chord length). dBHS falls back to the chord curve where no cubic matches the data (the edges along the top and bottom circles of the tube).\n");
    let _ = writeln!(md, "## Pictures (the seeds' Pictures 1–3)\n");
    let _ = writeln!(
        md,
        "Each row is one view; left to right: true ring, flat triangles, chord, dBHS, optimized.\n"
    );
    let _ = writeln!(md, "![shaded](shaded.png)\n\n### Gaussian curvature (KColor)\n\n![Gaussian curvature](kcolor.png)\n\n### Distance to the true surface (Radial)\n\n![distance](radial.png)\n");
    let _ = writeln!(
        md,
        "## Figure 2\n\n{}\n\n![figure 2](figure2.png)\n",
        report["figure2"]["rule"].as_str().unwrap_or("")
    );
    let _ = writeln!(md, "## Findings\n");
    md.push_str(&findings(surfaces, fits));
    let _ = writeln!(md, "\n## Time of each stage (s)\n");
    if let Some(t) = report["times"].as_object() {
        for (k, v) in t {
            let _ = writeln!(
                md,
                "- {}: {:.3}",
                k.trim_end_matches("_time_seconds"),
                v.as_f64().unwrap_or(f64::NAN)
            );
        }
    }
    let _ = writeln!(md, "\nFiles: `report.json`; `<surface>.ply` for every surface (binary, Gaussian-curvature colours, K as quality: MeshLab shows it); `optimized.obj`; `patches-optimized.jsonl` (quartic nets, the row order of docs/conventions.md; the other surfaces' nets come from `experiments -- fit --curves chord|dbhs --out FILE`).");
    md
}

/// The findings section: what the numbers say about the seeds' claims.
fn findings(surfaces: &[Surface], fits: &[FittedMethod]) -> String {
    let err = |name: &str| surfaces.iter().find(|s| s.name == name).map(|s| s.errors);
    let cs = |name: &str| fits.iter().find(|f| f.name == name).map(|f| &f.curves);
    let mut md = String::new();
    if let (Some(c), Some(d), Some(o)) = (err("chord"), err("dbhs"), err("optimized")) {
        let _ = writeln!(
            md,
            "- Gaussian-curvature RMS error: chord {:.4}, dBHS {:.4}, optimized {:.4}; mean curvature: {:.4}, {:.4}, {:.4}; \
             normal RMS error (°): {:.3}, {:.3}, {:.3}; position max: {}, {}, {}.",
            c.gaussian_rms, d.gaussian_rms, o.gaussian_rms, c.mean_rms, d.mean_rms, o.mean_rms,
            c.normal_rms_degrees, d.normal_rms_degrees, o.normal_rms_degrees,
            fmt_e(c.position_max), fmt_e(d.position_max), fmt_e(o.position_max)
        );
        let best = [
            ("chord", c.gaussian_rms),
            ("dbhs", d.gaussian_rms),
            ("optimized", o.gaussian_rms),
        ]
        .into_iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|x| x.0)
        .unwrap_or("?");
        let _ = writeln!(
            md,
            "- By Gaussian-curvature RMS the best of the three is `{best}`."
        );
    }
    if let (Some(d), Some(o)) = (cs("dbhs"), cs("optimized")) {
        let _ = writeln!(
            md,
            "- The seeds blame dBHS's lumps on short end derivatives: the shortest dBHS α here is {:.4} (one \
             end derivative of {:.1}% of the chord choice), the shortest optimized α is {:.4}; the largest \
             curvature variation ∫(dκ/ds)² ds is {} for dBHS and {} for optimized curves.",
            d.shortest_alpha,
            100.0 * d.shortest_alpha,
            o.shortest_alpha,
            fmt_e(d.curvature_variation_max),
            fmt_e(o.curvature_variation_max)
        );
    }
    let _ = writeln!(
        md,
        "- All three fitted surfaces are G1 to rounding (table above), so every visible defect is a shape \
         defect, not a continuity one. Remaining \"wrinkles\" come from the interior construction \
         (β, c), which these runs leave at the Shirman–Séquin defaults."
    );
    md
}

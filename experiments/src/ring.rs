//! `experiments -- ring`: the seeds' ring study (Mann 1994, Figures 2 and 5, Pictures 1–3),
//! reproduced and measured.
//!
//! Five surfaces: the true ring (a torus, R = 1, r = 0.4), the sampled triangulation (flat
//! triangles), and the modified Shirman–Séquin surface with `chord`, `dbhs` and `optimized`
//! boundary curves. Each is tessellated, measured against the torus (docs/conventions.md's quality
//! measures), rendered from three views shaded, coloured by Gaussian curvature (the testbed's
//! KColor) and by distance to the true surface (the testbed's Radial), and written as PLY and
//! OBJ. Figure 2: the boundary curves of the two edges where the constructions differ most.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use curves::analytic::torus_point;
use curves::{method_by_name, BoundaryProblem, MethodOptions};
use render::{CurveFigure, CurvePanel};
use serde_json::{json, Map, Value};
use surface::{
    compare_with_truth, fit, measure_g1, tessellate, AnalyticSurface, BezierTriangle, Fit,
    InteriorParameters, Mesh, SurfaceErrors, Tessellation,
};

use crate::curve_args::CurveOptions;
use crate::error::ExperimentError;
use crate::output::{write_result, Staged};
use surface::curve_stats::CurveStats;

/// The constructions compared, in the order of the seeds' Figure 5.
const METHODS: [&str; 3] = ["chord", "dbhs", "optimized"];

/// Grid of the "true ring" picture: fine enough that smooth shading shows no facets.
const TRUE_GRID: (usize, usize) = (96, 48);

/// Options of the `ring` experiment.
#[derive(clap::Args, Debug)]
pub struct RingArgs {
    /// Samples around the axis of the torus (the tube gets half as many): 16 gives the seeds'
    /// coarse 16 × 8 ring.
    #[arg(long, default_value_t = 16)]
    resolution: usize,
    /// Tessellation density: segments per patch edge (the testbed's `Tess -s`).
    #[arg(long, default_value_t = 4)]
    sampling: usize,
    /// The curve constructions' options.
    #[command(flatten)]
    curve: CurveOptions,
    /// Interior parameters of the fitted surfaces: default (β = 1/3, c = 1), thin-plate or
    /// membrane (per-triangle minimizers).
    #[arg(long, default_value_t = surface::fairing::InteriorChoice::Default)]
    interior: surface::fairing::InteriorChoice,
    /// Output directory.
    #[arg(long, default_value = "results/ring")]
    out: PathBuf,
}

/// One of the five surfaces.
struct Surface {
    name: &'static str,
    label: String,
    tess: Tessellation,
    /// Draw with per-face normals (the flat triangulation).
    flat: bool,
    errors: SurfaceErrors,
}

/// The true torus, tessellated on a fine grid with exact normals and curvatures.
fn true_ring(big: f64, small: f64) -> Tessellation {
    let (nu, nv) = TRUE_GRID;
    let mut positions = Vec::with_capacity(nu * nv);
    let mut normals = Vec::with_capacity(nu * nv);
    let mut gaussian = Vec::with_capacity(nu * nv);
    let mut mean = Vec::with_capacity(nu * nv);
    let mut shapes = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let (u, v) = (
                std::f64::consts::TAU * i as f64 / nu as f64,
                std::f64::consts::TAU * j as f64 / nv as f64,
            );
            let d = torus_point(u, v, big, small);
            let (ku, kv) = (-v.cos() / (big + small * v.cos()), -1.0 / small);
            positions.push(d.p);
            normals.push(d.n);
            gaussian.push(ku * kv);
            mean.push(0.5 * (ku + kv));
            shapes.push(d.shape);
        }
    }
    let id = |i: usize, j: usize| (i % nu) * nv + (j % nv);
    let mut faces = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let n = faces.len();
    Tessellation {
        positions,
        normals,
        gaussian,
        mean,
        shapes,
        faces,
        patch_of_face: vec![0; n],
        welds: 0,
        max_weld_normal_angle: 0.0,
        singular_samples: 0,
        collapsed_faces: 0,
    }
}

/// The sampled triangulation as flat linear patches, tessellated like the fitted surfaces.
fn flat_triangles(mesh: &Mesh, s: usize) -> Result<Tessellation, ExperimentError> {
    let patches: Vec<BezierTriangle> = mesh
        .faces()
        .iter()
        .filter_map(|f| {
            let v = mesh.vertices();
            BezierTriangle::new(1, vec![v[f[0]].data.p, v[f[1]].data.p, v[f[2]].data.p]).ok()
        })
        .collect();
    tessellate(&patches, s).map_err(|source| ExperimentError::Tessellate {
        subject: "ring/flat".into(),
        source,
    })
}

fn errors_json(e: &SurfaceErrors) -> Value {
    serde_json::to_value(e).unwrap_or(Value::Null)
}

/// Runs the experiment.
pub fn run(args: &RingArgs) -> Result<ExitCode, ExperimentError> {
    let t_all = Instant::now();
    let mut times = Map::new();
    let mut stage = |name: &str, t: Instant| {
        times.insert(
            format!("{name}_time_seconds"),
            json!(t.elapsed().as_secs_f64()),
        );
    };
    let t = Instant::now();
    crate::limits::check_usize("sampling", args.sampling, &crate::limits::SAMPLING_RANGE)?;
    let faces = crate::limits::dataset_faces("ring", args.resolution);
    crate::limits::check_memory(
        &format!(
            "--resolution {} --sampling {}",
            args.resolution, args.sampling
        ),
        faces * crate::limits::FIT_BYTES_PER_FACE as u128 * 5
            + 5 * crate::limits::tessellation_bytes(3 * faces, args.sampling),
    )?;
    let data = surface::dataset_by_name("ring", Some(args.resolution)).map_err(|source| {
        ExperimentError::DataOption {
            given: format!("--resolution {}", args.resolution),
            source,
        }
    })?;
    let mesh = &data.mesh;
    let truth: &dyn AnalyticSurface = data.surface.as_ref();
    let (big, small) = (
        surface::datasets::RING_MAJOR_RADIUS,
        surface::datasets::RING_TUBE_RADIUS,
    );
    let problems = surface::curve_stats::edge_problems(mesh).map_err(|source| {
        ExperimentError::EdgeProblems {
            subject: "ring".into(),
            source,
        }
    })?;
    stage("data", t);

    // Fits.
    let defaults = MethodOptions::default();
    let options = args.curve.method_options();
    let mut fits = Vec::new();
    let mut method_records = Map::new();
    for name in METHODS {
        let t = Instant::now();
        let m = method_by_name(name, &options).map_err(ExperimentError::from)?;
        let fit_error = |source| ExperimentError::Fit {
            subject: format!("ring/{name}"),
            source,
        };
        let f = fit(mesh, m.as_ref(), &|_| InteriorParameters::default()).map_err(fit_error)?;
        let (f, _) =
            surface::fairing::refit_interior(mesh, m.as_ref(), f, args.interior, args.curve.solver)
                .map_err(fit_error)?;
        let fit_time = t.elapsed().as_secs_f64();
        let g1 = measure_g1(mesh, &f, 9);
        let cs = surface::curve_stats::curve_stats(&problems, &f);
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
        fits.push((name, f, g1, cs));
    }
    stage("fit_and_g1", t_all);

    // Tessellations and errors.
    let t = Instant::now();
    let mut surfaces = Vec::new();
    let tt = true_ring(big, small);
    let te = compare_with_truth(&tt, truth);
    surfaces.push(Surface {
        name: "true",
        label: "true ring".into(),
        tess: tt,
        flat: false,
        errors: te,
    });
    let ft = flat_triangles(mesh, args.sampling)?;
    let fe = compare_with_truth(&ft, truth);
    surfaces.push(Surface {
        name: "flat",
        label: format!(
            "sampled {}×{} triangulation",
            args.resolution,
            (args.resolution / 2).max(3)
        ),
        tess: ft,
        flat: true,
        errors: fe,
    });
    for (name, f, _, _) in &fits {
        let tess = tessellate(&f.bezier_patches(), args.sampling).map_err(|source| {
            ExperimentError::Tessellate {
                subject: format!("ring/{name}"),
                source,
            }
        })?;
        let errors = compare_with_truth(&tess, truth);
        surfaces.push(Surface {
            name,
            label: format!("Shirman–Séquin, {name} curves"),
            tess,
            flat: false,
            errors,
        });
    }
    stage("tessellate_and_measure", t);

    let staged = Staged::begin(&args.out)?;
    let out = staged.path().to_path_buf();
    let t = Instant::now();
    let pictures = crate::ring_render::render_all(&out, &surfaces_view(&surfaces))?;
    stage("render", t);

    let t = Instant::now();
    crate::ring_render::write_meshes(&out, &surfaces_view(&surfaces))?;
    // Patch nets of the optimized surface (the others: `experiments -- fit --out`), to keep the
    // committed results small.
    for (name, f, _, _) in fits.iter().filter(|f| f.0 == "optimized") {
        let mut text = String::new();
        for (i, net) in f.patches.iter().enumerate() {
            let pts: Vec<[f64; 3]> = net.iter().map(|q| [q.x, q.y, q.z]).collect();
            let _ = writeln!(
                text,
                "{}",
                json!({"type": "BezierTriangle", "degree": 4, "points": pts, "face": i / 3, "subpatch": i % 3})
            );
        }
        write_result(
            Some(&out.join(format!("patches-{name}.jsonl"))),
            text.as_bytes(),
        )?;
    }
    stage("write_meshes", t);

    let t = Instant::now();
    let figure2 = figure2(&out, &problems, &fits)?;
    stage("figure2", t);
    times.insert(
        "total_time_seconds".into(),
        json!(t_all.elapsed().as_secs_f64()),
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
    let report = json!({
        "experiment": "ring",
        "data": {
            "torus": {"major_radius": big, "minor_radius": small},
            "resolution": [args.resolution, (args.resolution / 2).max(3)],
            "vertices": mesh.num_vertices(), "edges": mesh.num_edges(), "faces": mesh.num_faces(),
        },
        "settings": {
            "sampling": args.sampling, "solver": args.curve.solver.name(), "dbhs_pick": args.curve.dbhs_pick.to_string(),
            "interior": args.interior.to_string(),
            "optimized_weights": [defaults.weights.tangent, defaults.weights.curvature],
            "optimized_alpha_min": defaults.alpha_min,
        },
        "surfaces": surface_records,
        "methods": method_records,
        "figure2": figure2,
        "pictures": pictures,
        "times": times,
    });
    let text = crate::output::pretty_json(&report, "the ring report")?;
    write_result(Some(&out.join("report.json")), text.as_bytes())?;
    let md = markdown(args, &report, &surfaces, &fits);
    write_result(Some(&out.join("report.md")), md.as_bytes())?;
    print!(
        "{}",
        summary(&surfaces, &fits, t_all.elapsed().as_secs_f64())
    );
    staged.commit()?;
    Ok(ExitCode::SUCCESS)
}

/// What the renderer needs of a surface.
pub struct SurfaceView<'a> {
    /// File-name stem.
    pub name: &'a str,
    /// Label on pictures.
    pub label: &'a str,
    /// The tessellation.
    pub tess: &'a Tessellation,
    /// Per-face normals (flat shading).
    pub flat: bool,
    /// Distance of each sample to the true surface.
    pub distance: Vec<f64>,
}

fn surfaces_view(surfaces: &[Surface]) -> Vec<SurfaceView<'_>> {
    let torus = surface::Torus {
        big: surface::datasets::RING_MAJOR_RADIUS,
        small: surface::datasets::RING_TUBE_RADIUS,
    };
    surfaces
        .iter()
        .map(|s| SurfaceView {
            name: s.name,
            label: &s.label,
            tess: &s.tess,
            flat: s.flat,
            distance: s
                .tess
                .positions
                .iter()
                .map(|p| torus.signed_distance(p).abs())
                .collect(),
        })
        .collect()
}

/// Figure 2: the two edges where the constructions differ most, by a stated rule.
fn figure2(
    out: &Path,
    problems: &[BoundaryProblem],
    fits: &[(&str, Fit, surface::G1Report, CurveStats)],
) -> Result<Value, ExperimentError> {
    let alpha = |m: usize, e: usize| fits[m].1.alphas[e];
    let short = |a: [f64; 2]| a[0].min(a[1]);
    // Rule 1: the shortest dBHS end derivative; rule 2: the largest chord end-curvature error
    // among the remaining edges.
    let e1 = (0..problems.len())
        .min_by(|&a, &b| short(alpha(1, a)).total_cmp(&short(alpha(1, b))))
        .unwrap_or(0);
    let chord_err = |e: usize| {
        let k = problems[e].unit.end_curvatures(alpha(0, e));
        (k[0] - problems[e].unit.k0)
            .abs()
            .max((k[1] - problems[e].unit.k1).abs())
    };
    let e2 = (0..problems.len())
        .filter(|&e| e != e1)
        .max_by(|&a, &b| chord_err(a).total_cmp(&chord_err(b)))
        .unwrap_or(0);
    let rows: Vec<Vec<CurvePanel>> = [e1, e2]
        .iter()
        .map(|&e| {
            let p = &problems[e];
            fits.iter()
                .enumerate()
                .map(|(m, (name, _, _, _))| {
                    let a = alpha(m, e);
                    CurvePanel {
                        title: format!("{name}, edge {}–{}", p.edge.0, p.edge.1),
                        curve: p.unit.curve(a),
                        targets: [p.unit.k0, p.unit.k1],
                        notes: vec![format!("α = ({:.4}, {:.4})", a[0], a[1])],
                    }
                })
                .collect()
        })
        .collect();
    render::write_curve_figure(
        &CurveFigure {
            title:
                "Ring boundary curves (unit chord) and their curvature, as in Figure 2 of Mann 1994"
                    .into(),
            rows,
        },
        &out.join("figure2.png"),
        &out.join("figure2.svg"),
    )?;
    Ok(json!({
        "rule": "row 1: the edge with the shortest dBHS end derivative; row 2: among the others, the edge with the largest chord end-curvature error",
        "edges": [[problems[e1].edge.0, problems[e1].edge.1], [problems[e2].edge.0, problems[e2].edge.1]],
        "file": "figure2.png",
    }))
}

fn fmt_e(x: f64) -> String {
    format!("{x:.3e}")
}

fn summary(
    surfaces: &[Surface],
    fits: &[(&str, Fit, surface::G1Report, CurveStats)],
    total: f64,
) -> String {
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
    for (name, _, g1, cs) in fits {
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

fn markdown(
    args: &RingArgs,
    report: &Value,
    surfaces: &[Surface],
    fits: &[(&str, Fit, surface::G1Report, CurveStats)],
) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "# The ring study\n");
    let _ = writeln!(
        md,
        "Written by `cargo run --release -p experiments -- ring --resolution {} --sampling {} --solver {} --dbhs-pick {} --interior {} --out {}`.\n",
        args.resolution,
        args.sampling,
        args.curve.solver,
        args.curve.dbhs_pick,
        args.interior,
        args.out.display()
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
        args.sampling,
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
    for (name, _, g1, cs) in fits {
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
fn findings(surfaces: &[Surface], fits: &[(&str, Fit, surface::G1Report, CurveStats)]) -> String {
    let err = |name: &str| surfaces.iter().find(|s| s.name == name).map(|s| s.errors);
    let cs = |name: &str| fits.iter().find(|f| f.0 == name).map(|f| &f.3);
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

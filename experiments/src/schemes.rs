//! `experiments -- schemes`: every registered surface scheme on every data set, side by side
//! with the same measures and the same pictures (the testbed seed's purpose).
//!
//! For each mesh of `--data` (by default every data set, `surface::DATASET_NAMES`, at its
//! default resolution, exact vertex data; or the user's mesh files, repaired and completed by
//! an estimator, with no true surface to compare with) and each scheme (`surface::scheme::REGISTRY`; schemes on cubic edge curves get the
//! `--curves` construction): fit, measure G1 (9 samples per boundary) against the scheme's
//! claimed continuity, tessellate with about the same number of triangles per data face for
//! every layout (`s = round(S / √patches)`, `S = --face-segments`), and compare with the true surface
//! (position, normal, Gaussian and mean curvature; docs/conventions.md). The subdivision schemes
//! (`subdiv`: Loop, Catmull–Clark) join the table at the limit of three levels, with curvature
//! estimated on that mesh (they approximate, and are C2 away from extraordinary points, so the
//! G1 columns do not apply). Pictures: per data set
//! one composite, the schemes in columns of five, each row of shaded pictures followed by the
//! same schemes coloured by Gaussian curvature (KColor, one scale per data set: the true
//! surface's largest |K|).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use curves::method_by_name;
use render::colors as colormap;
use render::{
    render, write_composite, Camera, Legend, LegendKind, RenderMesh, RenderOptions, Tile,
};
use serde_json::{json, Value};
use surface::scheme::REGISTRY;
use surface::{
    compare_with_truth, scheme_by_name, Continuity, SchemeOptions, Tessellation, DATASET_NAMES,
};

use crate::curve_args::CurveOptions;
use crate::error::ExperimentError;
use crate::output::{write_result, Staged};
use experiments::subdivision::{subdivision_surface, SUBDIVISION_LEVELS};

/// Schemes per row of a composite (ten schemes in one row were 3000 pixels wide).
const COLUMNS: usize = 5;

/// Size of one picture in a composite.
const TILE: (u32, u32) = (300, 230);

/// The view of every picture (azimuth°, elevation°).
const VIEW: (f64, f64) = (35.0, 35.0);

/// A G1 claim holds when the measured angle is below this (rounding; the scheme tests' bound).
const G1_CLAIM: f64 = 1e-9;

/// The default `--data`: every data set in the registry's order (the committed results' order).
fn all_data_sets() -> &'static str {
    static ALL: std::sync::LazyLock<String> = std::sync::LazyLock::new(|| DATASET_NAMES.join(","));
    &ALL
}

/// Arguments of `schemes`.
#[derive(clap::Args, Debug)]
pub struct SchemesArgs {
    /// The meshes: data sets (ring, sphere, capsule, octa) or mesh files (any format `meshio`
    /// reads), comma-separated or the option repeated, each once. A file is repaired, moved
    /// into its working frame (centred, largest side 1) and completed by `--estimate`; it has
    /// no true surface, so its error columns are empty and its pictures' curvature scale is
    /// the 95th percentile of the schemes' |K|.
    #[arg(long, value_delimiter = ',', default_value = all_data_sets(), value_name = "NAME|FILE")]
    data: Vec<String>,
    /// Resolution of the named data sets (each its default when absent).
    #[arg(long)]
    resolution: Option<usize>,
    /// How to estimate what a mesh file lacks (normals, shape tensors).
    #[arg(long, default_value = estimate::DEFAULT_ESTIMATOR, value_parser = fitjob::cli::estimator_names())]
    estimate: String,
    /// Curve construction of the schemes on cubic edge curves.
    #[arg(long, default_value = "optimized")]
    curves: String,
    #[command(flatten)]
    curve: CurveOptions,
    /// Tessellation density: segments per data-face edge (each patch gets
    /// round(N / √patches-per-face)).
    #[arg(long, default_value_t = 8, value_name = "N")]
    face_segments: usize,
    /// Output directory.
    #[arg(short = 'o', long, default_value = "results/schemes")]
    output: PathBuf,
}

/// The K colour limit of a mesh without a true surface: this quantile of the schemes' |K| at
/// their samples (the largest would be one spike of a scanned mesh).
const K_QUANTILE_WITHOUT_TRUTH: f64 = 0.95;

/// The name of a subject's composite picture: its name for a data set, the file's stem
/// (letters, digits and `-` kept) for a file, with `-2`, `-3` … where two would be the same.
fn picture_name(subject: &str, taken: &[String]) -> String {
    let stem = std::path::Path::new(subject)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| subject.to_string());
    let stem: String = stem
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let mut name = format!("{stem}.png");
    let mut k = 1;
    while taken.contains(&name) {
        k += 1;
        name = format!("{stem}-{k}.png");
    }
    name
}

/// Segments per patch edge for a layout of `patches` patches per face.
fn segments(density: usize, patches: usize) -> usize {
    ((density as f64 / (patches as f64).sqrt()).round() as usize).max(1)
}

fn coloured(t: &Tessellation, colour: impl Fn(usize) -> [f32; 3]) -> RenderMesh {
    RenderMesh {
        positions: t.positions.clone(),
        normals: t.normals.clone(),
        colors: (0..t.positions.len()).map(colour).collect(),
        faces: t.faces.clone(),
    }
}

fn fmt_e(x: f64) -> String {
    format!("{x:.2e}")
}

/// The table's error cells (position max, normal RMS, K RMS, H RMS), dashes without a true
/// surface.
fn error_cells(errors: Option<&surface::SurfaceErrors>) -> String {
    match errors {
        Some(e) => format!(
            "{} | {:.3} | {:.4} | {:.4}",
            fmt_e(e.position_max),
            e.normal_rms_degrees,
            e.gaussian_rms,
            e.mean_rms
        ),
        None => "— | — | — | —".into(),
    }
}

/// Segments a face of the interactive page's tessellations (the pictures use `--face-segments`):
/// 16 triangles a face keeps the ring's page of eight schemes near 2 MB.
const PAGE_FACE_SEGMENTS: usize = 4;

/// The measures the schemes are ranked by: the record key (a path of `/`-separated keys), how
/// the report names it, lower is better for all.
const RANKED: [(&str, &str); 5] = [
    ("errors/gaussian_rms", "K RMS"),
    ("errors/mean_rms", "H RMS"),
    ("errors/normal_rms_degrees", "normal RMS (°)"),
    ("errors/position_max", "position max"),
    ("g1_exterior_radians", "G1 across edges (rad)"),
];

/// A record's number at `path` (`errors/gaussian_rms`).
fn at(r: &Value, path: &str) -> Option<f64> {
    path.split('/').try_fold(r, |v, k| v.get(k))?.as_f64()
}

/// The data set's ranking per measure and what the numbers say, in words: the best and worst
/// scheme of each measure, which schemes are G1 to rounding and which break G1 by how much,
/// and whether the seeds' end-curvature finding shows (`surface::ends`).
fn ranking(records: &[&Value]) -> String {
    let mut md = String::from("\n**Ranking per measure** (best first; subdivision schemes have no G1 figure):\n\n| measure | ranking |\n|---|---|\n");
    let mut words = Vec::new();
    for (key, label) in RANKED {
        let mut v: Vec<(&str, f64)> = records
            .iter()
            .filter_map(|r| Some((r["scheme"].as_str()?, at(r, key)?)))
            .filter(|(_, x)| x.is_finite())
            .collect();
        if v.is_empty() {
            continue;
        }
        v.sort_by(|a, b| a.1.total_cmp(&b.1));
        let list: Vec<String> = v.iter().map(|(s, x)| format!("{s} ({x:.3e})")).collect();
        md.push_str(&format!("| {label} | {} |\n", list.join(" < ")));
        if key.starts_with("errors/") && v.len() > 1 {
            let (best, worst) = (v[0], v[v.len() - 1]);
            words.push(format!(
                "{label}: {} is best ({:.3e}), {} worst ({:.3e}, {:.1}× the best)",
                best.0,
                best.1,
                worst.0,
                worst.1,
                if best.1 > 0.0 {
                    worst.1 / best.1
                } else {
                    f64::INFINITY
                }
            ));
        }
    }
    let g1: Vec<&str> = records
        .iter()
        .filter(|r| {
            at(r, "g1_exterior_radians").is_some_and(|x| x < G1_CLAIM)
                && at(r, "g1_interior_radians").is_some_and(|x| x < G1_CLAIM)
        })
        .filter_map(|r| r["scheme"].as_str())
        .collect();
    let broken: Vec<String> = records
        .iter()
        .filter_map(|r| {
            let x = at(r, "g1_exterior_radians")?.max(at(r, "g1_interior_radians")?);
            (x >= G1_CLAIM)
                .then(|| format!("{} ({x:.1e} rad)", r["scheme"].as_str().unwrap_or("?")))
        })
        .collect();
    words.push(format!(
        "G1 to rounding (below {G1_CLAIM:e} rad, where reflection lines run on across patch boundaries): {}; normals jump across boundaries (the lines break there, the shaded pictures show creases) for {}",
        if g1.is_empty() { "none".into() } else { g1.join(", ") },
        if broken.is_empty() { "none".into() } else { broken.join(", ") }
    ));
    let ends: Vec<String> = records
        .iter()
        .filter_map(|r| {
            let c = at(r, "ends/surface/median")?;
            let t = at(r, "ends/truth/median");
            Some(format!(
                "{} {c:.3}{}",
                r["scheme"].as_str().unwrap_or("?"),
                t.map(|t| format!(" (truth {t:.3})")).unwrap_or_default()
            ))
        })
        .collect();
    if !ends.is_empty() {
        words.push(format!(
            "Surface curvature at the ends of the edges against their middle (median ratio; above the truth's where curvature gathers at the ends, the seeds' finding): {}",
            ends.join(", ")
        ));
    }
    md.push('\n');
    for w in words {
        md.push_str(&format!("- {w}.\n"));
    }
    md
}

/// Runs the study.
pub fn run(args: &SchemesArgs) -> Result<ExitCode, ExperimentError> {
    let start = Instant::now();
    crate::limits::check_usize(
        "face-segments",
        args.face_segments,
        &crate::limits::SAMPLING_RANGE,
    )?;
    crate::study::refuse_duplicate_names("--data", &args.data)?;
    // An unknown construction is refused before any work.
    method_by_name(&args.curves, &args.curve.method_options())?;
    let staged = Staged::begin(&args.output)?;
    let out = staged.path().to_path_buf();
    let mut records = Vec::new();
    let mut pictures: Vec<String> = Vec::new();
    let mut md = String::new();
    let resolution = args
        .resolution
        .map(|r| format!(" --resolution {r}"))
        .unwrap_or_default();
    let _ = writeln!(
        md,
        "# Surface schemes side by side\n\nWritten by `cargo run --release -p experiments -- schemes --data {}{resolution} --curves {} --solver {} --face-segments {} --output {}`.\n\n\
         Every registered scheme on every mesh (exact vertex data for the data sets; a mesh file repaired, in its working frame, completed by `{}`); schemes on cubic edge curves use `{}` curves. \
         Tessellation: round({} / √patches) segments per patch edge, so every layout gets about the same number of triangles per data face. \
         Errors against the true surface at the tessellation's vertices (docs/conventions.md; a mesh file has no true surface: —). \
         G1: largest normal angle across patch boundaries (9 samples per boundary); a scheme that claims G1 must measure below {G1_CLAIM:e} rad.\n",
        args.data.join(","), args.curves, args.curve.solver, args.face_segments, args.output.display(), args.estimate, args.curves, args.face_segments
    );
    // The bar counts the meshes begun; its message names the one being compared.
    let bar = progress::Progress::bar("schemes", args.data.len() as u64);
    // The mesh whose page is written: the ring, the seeds' subject, when it is among them.
    let page_item = args
        .data
        .iter()
        .position(|d| d.trim() == "ring")
        .unwrap_or(0);
    for (item, data_item) in args.data.iter().enumerate() {
        bar.inc(1);
        bar.stage(data_item);
        let subject_data =
            crate::datasets::load_subject(data_item.trim(), args.resolution, &args.estimate)?;
        let name = subject_data.name.as_str();
        let mesh = &subject_data.mesh;
        let truth = subject_data.truth.as_deref();
        // Every scheme's tessellation is kept for the pictures: about the same triangle count
        // a scheme (a face at `face_segments` segments), estimated before any is made.
        let schemes = REGISTRY.len() + subdiv::SCHEMES.len();
        crate::limits::check_memory(
            &format!(
                "schemes --data {name} --face-segments {}",
                args.face_segments
            ),
            (mesh.num_faces() as u128)
                .saturating_mul(crate::limits::FIT_BYTES_PER_FACE as u128)
                .saturating_add(
                    crate::limits::tessellation_bytes(mesh.num_faces() as u128, args.face_segments)
                        .saturating_mul(schemes as u128),
                ),
        )?;
        let _ = writeln!(
            md,
            "\n## {name} ({} faces)\n\n| scheme | claims | G1 across edges (rad) | inside faces (rad) | claim holds | position max | normal RMS (°) | K RMS | H RMS | triangles |\n|---|---|---:|---:|---|---:|---:|---:|---:|---:|",
            mesh.num_faces()
        );
        let mut tiles_shaded = Vec::new();
        let mut tiles_k = Vec::new();
        let mut tiles_zebra = Vec::new();
        let mut tessellations = Vec::new();
        // One mesh's page (the ring's) shows every scheme at PAGE_FACE_SEGMENTS (a page is a few
        // megabytes; one a study keeps the results small).
        let mut page_views = Vec::new();
        for entry in REGISTRY {
            let scheme = scheme_by_name(entry.name, &SchemeOptions::default())?;
            let subject = format!("{name}/{}", entry.name);
            let crate::input::KeptFit {
                fit: f,
                g1,
                seconds: fit_seconds,
                ..
            } = crate::input::fit_prepared(
                &subject,
                mesh,
                surface::Frame::identity(),
                entry.name,
                &args.curves,
                args.curve.method_options(),
            )?;
            let fit_ms = fit_seconds * 1e3;
            let s = segments(args.face_segments, f.layout.patches_per_face());
            let tess = surface::tessellate_fit(mesh, &f, s)
                .map_err(|source| ExperimentError::Tessellate { subject, source })?;
            let errors = truth.map(|t| compare_with_truth(&tess, t));
            let holds = match f.continuity {
                Continuity::G1 | Continuity::C1 => g1.max_angle() < G1_CLAIM,
                _ => true,
            };
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} | {} | {} |",
                entry.name,
                f.continuity,
                fmt_e(g1.exterior_max),
                fmt_e(g1.interior_max),
                if holds { "yes" } else { "**no**" },
                error_cells(errors.as_ref()),
                tess.faces.len(),
            );
            records.push(json!({
                "dataset": name,
                "faces": mesh.num_faces(),
                "scheme": entry.name,
                "summary": entry.summary,
                "continuity": f.continuity,
                "layout": {"degree": f.layout.degree, "patches_per_face": f.layout.patches_per_face()},
                "uses_curves": scheme.uses_curves(),
                "curves": scheme.uses_curves().then_some(args.curves.as_str()),
                "g1_exterior_radians": g1.exterior_max,
                "g1_interior_radians": g1.interior_max,
                "claim_holds": holds,
                "interpolation_position_error": g1.position_error,
                "interpolation_normal_error_radians": g1.normal_error,
                "face_fallbacks": f.face_fallbacks.len(),
                "segments_per_patch_edge": s,
                "triangles": tess.faces.len(),
                "errors": serde_json::to_value(errors).unwrap_or(Value::Null),
                "ends": serde_json::to_value(surface::ends::measure(mesh, &f, truth)).unwrap_or(Value::Null),
                "fit_time_seconds": fit_ms / 1e3,
            }));
            if item == page_item {
                let coarse = segments(PAGE_FACE_SEGMENTS, f.layout.patches_per_face());
                let t = surface::tessellate_fit(mesh, &f, coarse).map_err(|source| {
                    ExperimentError::Tessellate {
                        subject: format!("{name}/{} (page)", entry.name),
                        source,
                    }
                })?;
                page_views.push(crate::pages::fit_view(
                    &format!("{name}/{}", entry.name),
                    &t,
                    Some((mesh, &surface::Frame::identity())),
                    None,
                    truth,
                ));
            }
            tessellations.push((entry.name, tess));
        }
        for entry in subdiv::SCHEMES.iter().filter(|e| e.name != "loop-warren") {
            let subject = format!("{name}/{}", entry.name);
            let (tess, to_limit) = subdivision_surface(mesh, entry.name, SUBDIVISION_LEVELS)
                .map_err(|source| ExperimentError::Subdivision {
                    subject: subject.clone(),
                    source,
                })?;
            let errors = truth.map(|t| compare_with_truth(&tess, t));
            let _ = writeln!(
                md,
                "| {} ({SUBDIVISION_LEVELS} levels, at the limit) | C1 at extraordinary points, approximates | — | — | — | {} | {} |",
                entry.name,
                error_cells(errors.as_ref()),
                tess.faces.len(),
            );
            records.push(json!({
                "dataset": name,
                "faces": mesh.num_faces(),
                "scheme": entry.name,
                "summary": entry.summary,
                "kind": "subdivision",
                "levels": SUBDIVISION_LEVELS,
                "data_to_limit_max": to_limit,
                "triangles": tess.faces.len(),
                "errors": serde_json::to_value(errors).unwrap_or(Value::Null),
            }));
            tessellations.push((entry.name, tess));
        }
        // One colour scale per mesh: the true surface's largest |K| at the samples, or without
        // a true surface a high quantile of the schemes' |K|.
        let k_limit = match truth {
            Some(t) => tessellations
                .first()
                .map(|(_, tess)| {
                    tess.positions
                        .iter()
                        .map(|p| t.closest(p).gaussian().abs())
                        .fold(0.0f64, f64::max)
                })
                .unwrap_or(1.0),
            None => {
                let mut k: Vec<f64> = tessellations
                    .iter()
                    .flat_map(|(_, tess)| tess.gaussian.iter().map(|k| k.abs()))
                    .filter(|k| k.is_finite())
                    .collect();
                k.sort_by(f64::total_cmp);
                let at = ((k.len() as f64 - 1.0) * K_QUANTILE_WITHOUT_TRUTH).round() as usize;
                k.get(at).copied().unwrap_or(1.0)
            }
        }
        .max(1e-12);
        // Framing: every scheme's vertices at once, so no picture is clipped and all are seen
        // from the same camera.
        let all: Vec<nalgebra::Point3<f64>> = tessellations
            .iter()
            .flat_map(|(_, t)| t.positions.iter().copied())
            .collect();
        let cam = Camera::framing_points(&all, VIEW.0, VIEW.1, TILE.0 as f64 / TILE.1 as f64);
        let options = RenderOptions {
            width: TILE.0,
            height: TILE.1,
            ..RenderOptions::default()
        };
        let zebra = RenderOptions {
            shading: render::interrogation::Shading::REFLECTION,
            ..options.clone()
        };
        for (scheme, t) in &tessellations {
            tiles_zebra.push(Tile {
                image: render(&coloured(t, |_| colormap::MATERIAL), &cam, &zebra)?,
                label: format!("{scheme} — reflection lines"),
            });
            tiles_shaded.push(Tile {
                image: render(&coloured(t, |_| colormap::MATERIAL), &cam, &options)?,
                label: format!("{scheme} — shaded"),
            });
            tiles_k.push(Tile {
                image: render(
                    &coloured(t, |i| colormap::diverging(t.gaussian[i], k_limit)),
                    &cam,
                    &options,
                )?,
                label: format!("{scheme} — K"),
            });
        }
        // Blocks of COLUMNS schemes: a shaded row, the same schemes' K row, then their
        // reflection lines (continuous across patch boundaries on a G1 surface, broken on C0).
        let columns = COLUMNS.min(tiles_shaded.len()).max(1);
        let mut tiles = Vec::with_capacity(3 * tiles_shaded.len());
        let mut k_tiles = tiles_k.into_iter();
        let mut zebra_tiles = tiles_zebra.into_iter();
        let blank = |t: &Tile| Tile {
            image: render::Image {
                width: t.image.width,
                height: t.image.height,
                rgb: vec![255; t.image.rgb.len()],
            },
            label: String::new(),
        };
        for block in tiles_shaded.chunks(columns) {
            // A short last block is padded with blank tiles so its K row starts a row.
            let pad = columns - block.len();
            tiles.extend(block.iter().cloned());
            tiles.extend(std::iter::repeat_with(|| blank(&block[0])).take(pad));
            tiles.extend(k_tiles.by_ref().take(block.len()));
            tiles.extend(std::iter::repeat_with(|| blank(&block[0])).take(pad));
            tiles.extend(zebra_tiles.by_ref().take(block.len()));
            tiles.extend(std::iter::repeat_with(|| blank(&block[0])).take(pad));
        }
        let file = picture_name(name, &pictures);
        pictures.push(file.clone());
        write_composite(
            &tiles,
            columns,
            &format!("{name}: every scheme, shaded, Gaussian curvature K and reflection lines (rows by threes)"),
            Some(&Legend {
                title: "Gaussian curvature K (the K rows)".into(),
                kind: LegendKind::Diverging { limit: k_limit },
            }),
            &out.join(&file),
        )?;
        let _ = writeln!(md, "\n![{name}]({file})");
        // Curvature along the data set's paths, every scheme against the truth.
        let sampled: Vec<(String, Vec<crate::sweep::curvature::Sampled>)> = tessellations
            .iter()
            .map(|(scheme, t)| {
                (
                    scheme.to_string(),
                    crate::sweep::curvature::sample_paths(name, t, truth),
                )
            })
            .filter(|(_, p)| !p.is_empty())
            .collect();
        if !sampled.is_empty() {
            let stem = format!("curvature-{}", file.trim_end_matches(".png"));
            let rows: Vec<(String, &[crate::sweep::curvature::Sampled])> = sampled
                .iter()
                .map(|(l, p)| (l.clone(), p.as_slice()))
                .collect();
            let stems = crate::sweep::curvature::figure(
                &out,
                &stem,
                &format!("{name}: curvature along paths, every scheme against the true surface"),
                &rows,
            )?;
            let _ = writeln!(md, "\n{}\n", crate::sweep::curvature::description());
            for s in stems {
                let _ = writeln!(md, "![{name}: curvature along paths]({s}.png)\n");
            }
        }
        // The interactive page of that mesh: every patch scheme side by side.
        if !page_views.is_empty() {
            let page = format!("{}.html", file.trim_end_matches(".png"));
            let bytes = crate::pages::write(
                &out.join(&page),
                &format!("{name}: every scheme"),
                std::mem::take(&mut page_views),
            )?;
            let _ = writeln!(
                md,
                "\nInteractive: [{page}]({page}) ({:.1} MB, works offline): every patch scheme side by side with linked cameras, tessellated at {PAGE_FACE_SEGMENTS} segments a face; shaded, K, H, κ1, κ2, reflection lines, isophotes, distance to the true surface; patch boundaries and the data mesh.",
                bytes as f64 / 1e6
            );
        }
        let mine: Vec<&Value> = records.iter().filter(|r| r["dataset"] == name).collect();
        md.push_str(&ranking(&mine));
    }
    let report = json!({
        "experiment": "schemes",
        "options": {"data": args.data, "resolution": args.resolution, "estimate": args.estimate,
                    "curves": args.curves, "solver": args.curve.solver.to_string(), "face_segments": args.face_segments},
        "schemes": REGISTRY.iter().map(|e| json!({"name": e.name, "summary": e.summary})).collect::<Vec<_>>(),
        "results": records,
        "time_seconds": start.elapsed().as_secs_f64(),
    });
    let text = crate::output::pretty_json(&report, "the schemes report")?;
    write_result(Some(&out.join("report.json")), text.as_bytes())?;
    write_result(Some(&out.join("report.md")), md.as_bytes())?;
    staged.commit()?;
    say!("schemes: written to {}", args.output.display());
    Ok(ExitCode::SUCCESS)
}

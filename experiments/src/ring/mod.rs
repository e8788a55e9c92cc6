//! `experiments -- ring`: the seeds' ring study (Mann 1994, Figures 2 and 5, Pictures 1–3),
//! reproduced and measured.
//!
//! Five surfaces: the true ring (a torus, R = 1, r = 0.4), the sampled triangulation (flat
//! triangles), and the modified Shirman–Séquin surface with `chord`, `dbhs` and `optimized`
//! boundary curves. Each is tessellated, measured against the torus (docs/conventions.md's quality
//! measures), rendered from three views shaded, coloured by Gaussian curvature (the testbed's
//! KColor) and by distance to the true surface (the testbed's Radial), and written as PLY and
//! OBJ. Figure 2: the boundary curves of the two edges where the constructions differ most.
//!
//! Here: the options and the run, stage by stage (each stage's time goes into the report);
//! [`surfaces`] builds and measures the five surfaces, [`render`] draws the pictures and writes
//! the mesh files, [`figures`] draws Figure 2, [`report`] writes `report.json`, `report.md` and
//! the terminal summary.

mod figures;
mod generations;
mod principal;
mod render;
mod report;
mod surfaces;

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use serde_json::{json, Map};
use surface::AnalyticSurface;

use crate::curve_args::{CurveOptions, InteriorOption};
use crate::error::ExperimentError;
use crate::output::{pretty_json, write_result, Staged};

/// The constructions the study compares by default: the seeds' three, in the order of their
/// Figure 5 (`chord` — Shirman–Séquin's, which is also the original testbed's Furth rule —,
/// `dbhs`, `optimized`). `--curves` takes any registered ones; the `sweep` compares every
/// registered construction on every data set. `estimation` rebuilds the study with these.
pub const SEED_METHODS: &str = "chord,dbhs,optimized";

/// [`SEED_METHODS`] one by one.
pub fn methods() -> impl Iterator<Item = &'static str> {
    SEED_METHODS.split(',')
}

/// Options of the `ring` experiment.
#[derive(clap::Args, Debug)]
pub struct RingArgs {
    /// Samples around the axis of the torus (the tube gets half as many): 16 gives the seeds'
    /// coarse 16 × 8 ring.
    #[arg(long, default_value_t = 16)]
    resolution: usize,
    /// Tessellation density: segments per patch edge (the testbed's `Tess -s`).
    #[arg(short = 's', long, default_value_t = 4)]
    segments: usize,
    /// Comma-separated curve constructions to compare, each once (one surface a construction;
    /// default the seeds' three).
    #[arg(long, value_delimiter = ',', default_value = SEED_METHODS,
          value_parser = fitjob::cli::curve_method_names())]
    curves: Vec<String>,
    /// The curve constructions' options.
    #[command(flatten)]
    curve: CurveOptions,
    /// The interior parameters of the fitted surfaces.
    #[command(flatten)]
    interior: InteriorOption,
    /// The surface scheme of the fitted surfaces (each with every construction of [`methods`]
    /// where it takes curves).
    #[command(flatten)]
    scheme: fitjob::cli::SchemeArgs<fitjob::cli::PatchesOnly>,
    /// Output directory.
    #[arg(short = 'o', long, default_value = "results/ring")]
    output: PathBuf,
}

/// Segments per patch edge of the interactive page's surfaces (the pictures use `--segments`).
const PAGE_SEGMENTS: usize = 4;

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
    crate::limits::check_usize("segments", args.segments, &crate::limits::SAMPLING_RANGE)?;
    let faces = crate::limits::dataset_faces("ring", args.resolution);
    crate::limits::check_memory(
        &format!(
            "--resolution {} --segments {}",
            args.resolution, args.segments
        ),
        faces * crate::limits::FIT_BYTES_PER_FACE as u128 * 5
            + 5 * crate::limits::tessellation_bytes(3 * faces, args.segments),
    )?;
    let data = surface::dataset_by_name("ring", Some(args.resolution)).map_err(|source| {
        ExperimentError::DataOption {
            given: format!("--resolution {}", args.resolution),
            source: Box::new(source),
        }
    })?;
    let mesh = &data.mesh;
    let truth: &dyn AnalyticSurface = data.surface.as_ref();
    let problems = surface::curve_stats::edge_problems(mesh).map_err(|source| {
        ExperimentError::EdgeProblems {
            subject: "ring".into(),
            source,
        }
    })?;
    stage("data", t);

    // Fits.
    if let Some(twice) = args
        .curves
        .iter()
        .enumerate()
        .find_map(|(i, m)| args.curves[..i].contains(m).then_some(m))
    {
        return Err(ExperimentError::Usage(format!(
            "--curves: `{twice}` is listed twice"
        )));
    }
    let fits = surfaces::fit_methods(
        &args.curves,
        args.resolution,
        &args.scheme,
        &problems,
        &args.curve.method_options(),
        args.interior.choice,
    )?;
    stage("fit_and_g1", t_all);

    // Tessellations and errors.
    let t = Instant::now();
    let surfaces = surfaces::measure_surfaces(mesh, truth, &fits, args.resolution, args.segments)?;
    stage("tessellate_and_measure", t);

    let staged = Staged::begin(&args.output)?;
    let out = staged.path().to_path_buf();
    let t = Instant::now();
    let pictures = render::render_all(&out, &surfaces::surfaces_view(&surfaces))?;
    // The principal directions of the true ring, the optimized fit and a fit of the sphere.
    let sphere =
        surface::dataset_by_name("sphere", None).map_err(|source| ExperimentError::DataOption {
            given: "--data sphere".into(),
            source: Box::new(source),
        })?;
    let sphere_fit = crate::input::fit_kept(fitjob::FitOptions {
        input: fitjob::InputOptions {
            source: fitjob::Source::DataSet {
                name: "sphere".into(),
                resolution: None,
            },
            ..fitjob::InputOptions::default()
        },
        scheme: args.scheme.scheme.clone(),
        scheme_options: args.scheme.options.clone(),
        curves: "optimized".into(),
        method_options: args.curve.method_options(),
        ..fitjob::FitOptions::default()
    })?;
    let sphere_tess = surface::tessellate_fit(&sphere.mesh, &sphere_fit.fit, args.segments)
        .map_err(|source| ExperimentError::Tessellate {
            subject: "sphere".into(),
            source,
        })?;
    let mut glyphs: Vec<(String, &surface::Tessellation)> = surfaces
        .iter()
        .filter(|s| s.name == "true" || s.name == "optimized")
        .map(|s| (s.label.clone(), &s.tess))
        .collect();
    glyphs.push((
        format!(
            "sphere, {} (umbilic)",
            surfaces::fit_label(sphere_fit.fit.scheme, "optimized")
        ),
        &sphere_tess,
    ));
    let principal_picture = principal::write(&out, &glyphs)?;
    // The interactive page: every construction's surface side by side (cameras linked), at
    // PAGE_SEGMENTS so the page stays near 2 MB, with the data mesh and the distance to the
    // torus.
    let mut views = Vec::new();
    for m in &fits {
        let tess = surface::tessellate_fit(mesh, &m.fit, PAGE_SEGMENTS.min(args.segments))
            .map_err(|source| ExperimentError::Tessellate {
                subject: format!("ring/{} (page)", m.name),
                source,
            })?;
        views.push(crate::pages::fit_view(
            &surfaces::fit_label(m.fit.scheme, m.name),
            &tess,
            Some((mesh, &surface::Frame::identity())),
            None,
            Some(truth),
        ));
    }
    let page_bytes = crate::pages::write(
        &out.join("ring.html"),
        "The ring: every boundary-curve construction",
        views,
    )?;
    stage("render", t);

    let t = Instant::now();
    render::write_meshes(&out, &surfaces::surfaces_view(&surfaces))?;
    render::write_patches(&out, &fits)?;
    stage("write_meshes", t);

    let t = Instant::now();
    let figure2 = figures::figure2(&out, &problems, &fits)?;
    stage("figure2", t);

    let t = Instant::now();
    let (generations_json, generations_md) = generations::run(
        &out,
        mesh,
        truth,
        &surfaces[0],
        args.resolution,
        args.segments,
        &args.curve.method_options(),
    )?;
    stage("generations", t);
    times.insert(
        "total_time_seconds".into(),
        json!(t_all.elapsed().as_secs_f64()),
    );

    let mut report = report::report_json(args, mesh, &surfaces, &fits, figure2, pictures, times);
    if let Some(map) = report.as_object_mut() {
        map.insert("generations".into(), generations_json);
    }
    let text = pretty_json(&report, "the ring report")?;
    write_result(Some(&out.join("report.json")), text.as_bytes())?;
    let mut md = report::markdown(args, &report, &surfaces, &fits);
    md.push_str(&format!(
        "\nInteractive: [ring.html](ring.html) ({:.1} MB, works offline): the surfaces of every construction side by side with linked cameras; shaded, K, H, κ1, κ2, reflection lines, isophotes, distance to the torus; patch boundaries and the data mesh.\n",
        page_bytes as f64 / 1e6
    ));
    md.push_str(&generations_md);
    md.push_str(&format!(
        "\n## Principal directions\n\nShort glyphs on the shaded surfaces along each sample's principal directions (red: κ1, the larger principal curvature; blue: κ2; from the tessellations' exact shape tensors). On the true ring they follow the meridians and the parallels; the sphere is umbilic, so its fit's glyphs point wherever its small departures from the sphere send them.\n\n![principal directions]({principal_picture})\n"
    ));
    write_result(Some(&out.join("report.md")), md.as_bytes())?;
    print!(
        "{}",
        report::summary(&surfaces, &fits, t_all.elapsed().as_secs_f64())
    );
    staged.commit()?;
    Ok(ExitCode::SUCCESS)
}

//! `experiments -- fit`: fit a data set or mesh file with a surface scheme (`--scheme`, default
//! the modified Shirman–Séquin, or a subdivision scheme with `--levels`), streamed a window of
//! faces at a time unless `--interior` needs the whole fit, and write the patches to `--output`
//! (JSON Lines, or the binary `.bzp` form) and the tessellation to `--mesh-output` (any mesh
//! format, by extension).
//!
//! Each JSON Lines output line is one record, `{"type": "BezierTriangle", "degree": n, "points":
//! [[x, y, z], …], "face": f, "subpatch": e}` (points in the row order of docs/conventions.md;
//! sub-patch `e` of face `f` spans the scheme's sub-triangle `e` of the face: for
//! Shirman–Séquin, the face's corners `e`, `e + 1` and the split point). stderr gets the G1
//! defect, the interpolation error, the curve statistics and the time of each stage.

use std::path::PathBuf;
use std::process::ExitCode;

use crate::curve_args::FitOptions;
use crate::error::ExperimentError;
use crate::input::InputArgs;
use crate::output::write_result;

/// Options of the `fit` experiment.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// The input mesh and how to complete it.
    #[command(flatten)]
    input: InputArgs,
    /// The construction, its options and the interior parameters.
    #[command(flatten)]
    fit: FitOptions,
    /// Where to write the patches: JSON Lines (`-`: standard output), or the compact binary form
    /// when the name ends in `.bzp` (`surface::patch_io`); none are written when absent. Without `--interior`, the
    /// patches are streamed: built, measured and written a window of faces at a time, never all
    /// held (`surface::stream`; the same report and file); a `--mesh-output` tessellation then
    /// builds each face's patches again where it samples them (the same mesh).
    #[arg(short = 'o', long)]
    output: Option<PathBuf>,
    /// Tessellate the patches at this many segments per patch edge (the testbed's `Tess -s`)
    /// and write the welded triangle mesh to `--mesh-output`.
    #[arg(short = 's', long, default_value_t = fitjob::options::DEFAULT_TESS)]
    segments: usize,
    /// Subdivision steps for `--scheme loop|loop-warren|catmull-clark` (the control mesh after
    /// them goes to `--mesh-output`).
    #[arg(long, default_value_t = fitjob::options::DEFAULT_LEVELS)]
    levels: u32,
    /// Exit with status 1 when anything was not as asked: a repaired file, a fallback face, a
    /// degenerate edge, a curve that fell back to the chord choice, an optimization that did
    /// not converge (all are counted in the summary either way).
    #[arg(long)]
    strict: bool,
    /// Where to write the tessellation, in the format its extension names (.obj, .ply, .off,
    /// .stl, .glb, .m): positions, normals, vertex colours by Gaussian curvature (the testbed's
    /// KColor; sRGB in PLY, OBJ and OFF, linear in glTF); PLY and glTF also the curvature, in
    /// libigl's, trimesh's and MeshLab's convention (H > 0 on a sphere with outward normals):
    /// PLY `quality` (K), `gaussian_curvature`, `mean_curvature`, `k1`, `k2` and the principal
    /// directions `pd1x` … `pd2z`; glTF `_GAUSSIAN_CURVATURE`, `_MEAN_CURVATURE`,
    /// `_PRINCIPAL_CURVATURE_1/2`, `_PRINCIPAL_DIRECTION_1/2`.
    #[arg(long)]
    mesh_output: Option<PathBuf>,
    /// How the mesh file is written.
    #[command(flatten)]
    mesh_options: fitjob::output::MeshOutputOptions,
    /// Write the whole report as JSON here: every count the summary prints, every fallback face
    /// with its reason and every degenerate edge (the summary lists the first ten), the G1
    /// split, the timings (under `time`) and the peak memory. `-`: standard output.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Write an interactive page of the fitted surface here: one self-contained HTML file that
    /// works offline (turn, zoom, pan; shaded, K, H, κ1, κ2, reflection lines, isophotes;
    /// patch boundaries, control nets and the data mesh), tessellated at `--segments`. The fit
    /// is then held whole, not streamed (the same numbers).
    #[arg(long, value_name = "PAGE.html")]
    html: Option<PathBuf>,
    /// `--heightfield`, `--no-heightfield`.
    #[command(flatten)]
    heightfield: fitjob::cli::HeightFieldArgs,
}

impl FitArgs {
    /// The fit job these options ask for.
    pub fn job(&self) -> fitjob::FitOptions {
        fitjob::FitOptions {
            input: self.input.job_input(),
            scheme: self.fit.scheme.scheme.clone(),
            scheme_options: self.fit.scheme.options.clone(),
            curves: self.fit.curves.clone(),
            method_options: self.fit.curve.method_options(),
            interior: self.fit.interior.choice,
            tess: self.segments,
            levels: self.levels,
            g1_samples: fitjob::options::DEFAULT_G1_SAMPLES,
            measure_g1: true,
            patches_out: self.output.clone(),
            mesh_out: self.mesh_output.clone(),
            mesh_options: self.mesh_options,
            heightfield: self.heightfield.mode(),
            keep: self.html.is_some(),
        }
    }
}

/// Runs the experiment: the fit job ([`fitjob::run`]), its progress and summary on stderr,
/// the report to `--report`.
pub fn run(args: &FitArgs) -> Result<ExitCode, ExperimentError> {
    let report_to = args.report.as_deref().map(fitjob::destination);
    if let Some(Some(path)) = report_to {
        crate::output::refuse_unwritable("--report", path, &args.input.data)?;
    }
    if report_to == Some(None) && args.output.as_deref().map(fitjob::destination) == Some(None) {
        return Err(ExperimentError::Usage(
            "--output - and --report - both name standard output; send one to a file".into(),
        ));
    }
    if let Some(page) = &args.html {
        crate::output::refuse_unwritable("--html", page, &args.input.data)?;
        if args.fit.scheme.is_subdivision() {
            return Err(ExperimentError::Usage(
                "--html draws patches: a subdivision scheme has none (view its --mesh-output with `experiments view`)".into(),
            ));
        }
    }
    let outcome = fitjob::run(args.job(), &mut |line| say!("{line}"))?;
    if let (
        Some(page),
        fitjob::Kept {
            mesh: Some(mesh),
            frame: Some(frame),
            fit: Some(fit),
            ..
        },
    ) = (&args.html, &outcome.kept)
    {
        let mut tess = surface::tessellate_fit(mesh, fit, args.segments).map_err(|source| {
            ExperimentError::Tessellate {
                subject: args.input.data.clone(),
                source,
            }
        })?;
        tess.to_world(frame);
        // A data set's true surface gives the page its distance mode.
        let truth = (!fitjob::input::is_file_input(&args.input.data))
            .then(|| surface::dataset_by_name(&args.input.data, args.input.resolution).ok())
            .flatten();
        let view = crate::pages::fit_view(
            &format!("{} — {}", args.input.data, fit.scheme),
            &tess,
            Some((mesh, frame)),
            Some(fit),
            truth.as_ref().map(|d| d.surface.as_ref()),
        );
        let bytes = crate::pages::write(page, &args.input.data, vec![view])?;
        say!("  page: {} ({bytes} bytes)", page.display());
    }
    let report = outcome.report;
    for line in report.summary_lines() {
        say!("{line}");
    }
    if let Some(path) = report_to {
        let text = report.to_json().map_err(|source| ExperimentError::Json {
            what: "the fit report",
            source,
        })?;
        write_result(path, text.as_bytes())?;
    }
    let found: Vec<String> = report
        .departures()
        .iter()
        .map(|(n, what)| format!("{n} {what}"))
        .collect();
    if args.strict && !found.is_empty() {
        say!("strict: {}", found.join(", "));
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

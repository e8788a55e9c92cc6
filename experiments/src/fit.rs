//! `experiments -- fit`: fit a data set or mesh file with the modified Shirman–Séquin scheme and
//! write the patches as JSON Lines.
//!
//! Each output line is one record, `{"type": "BezierTriangle", "degree": 4, "points":
//! [[x, y, z], …15], "face": f, "subpatch": e}` (points in DESIGN.md's row order; sub-patch `e`
//! of face `f` spans the face's corners `e`, `e + 1` and the split point). stderr gets the G1
//! defect, the interpolation error, the curve statistics and the time of each stage.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use curves::{method_by_name, DbhsPick, MethodOptions};
use serde_json::json;
use solver::SolverKind;
use surface::fairing::{choose_interior, InteriorChoice, InteriorStats};
use surface::{fit, measure_g1, Fit, InteriorParameters, Mesh};

use crate::datasets::load;
use crate::error::ExperimentError;
use crate::output::write_result;

/// Options of the `fit` experiment.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// A data set (ring, sphere, capsule, octa) or a mesh file (`.m` testbed format, `.obj`).
    #[arg(long, default_value = "ring")]
    data: String,
    /// Resolution of a named data set (its default when absent).
    #[arg(long)]
    resolution: Option<usize>,
    /// Boundary-curve construction: chord, dbhs or optimized.
    #[arg(long, default_value = "chord")]
    curves: String,
    /// Solver of the optimized construction.
    #[arg(long, default_value_t = SolverKind::ExactPenalty)]
    solver: SolverKind,
    /// Which dBHS solution to take (closest, longest-short, or an index).
    #[arg(long, default_value_t = DbhsPick::Closest)]
    dbhs_pick: DbhsPick,
    /// β at every corner (1/3: the Shirman–Séquin default, C1 inside each triangle).
    #[arg(long, default_value_t = surface::shirman_sequin::DEFAULT_BETA)]
    beta: f64,
    /// Jensen's c on every edge (1: Chiyokura–Kimura).
    #[arg(long, default_value_t = surface::shirman_sequin::DEFAULT_C)]
    c: f64,
    /// Interior parameters: `default` (the --beta and --c values), or per triangle the β and c
    /// minimizing the macro-patch's `thin-plate` or `membrane` energy.
    #[arg(long, default_value_t = InteriorChoice::Default)]
    interior: InteriorChoice,
    /// Where to write the patches (JSON Lines); none are written when absent.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Tessellate the patches at this many segments per patch edge (the testbed's `Tess -s`)
    /// and write the welded triangle mesh with normals as OBJ to `--mesh-out`.
    #[arg(long, default_value_t = 4)]
    tess: usize,
    /// Where to write the tessellation (OBJ); none is made when absent.
    #[arg(long)]
    mesh_out: Option<PathBuf>,
}

fn read_mesh(arg: &str, resolution: Option<usize>) -> Result<Mesh, ExperimentError> {
    let path = Path::new(arg);
    let usage = |e: String| ExperimentError::Usage(e);
    match path.extension().and_then(|e| e.to_str()) {
        Some("m") => surface::read_testbed_file(path).map_err(|e| usage(e.to_string())),
        Some("obj") => surface::read_obj_file(path).map_err(|e| usage(e.to_string())),
        _ => {
            if resolution.is_some() {
                surface::dataset_by_name(arg, resolution)
                    .map(|d| d.mesh)
                    .map_err(|e| usage(e.to_string()))
            } else {
                load(arg).map(|d| d.mesh)
            }
        }
    }
}

/// Runs the experiment.
pub fn run(args: &FitArgs) -> Result<ExitCode, ExperimentError> {
    let t0 = Instant::now();
    let mesh = read_mesh(&args.data, args.resolution)?;
    let t_read = t0.elapsed().as_secs_f64();
    let options = MethodOptions {
        dbhs_pick: args.dbhs_pick,
        solver: args.solver,
        ..MethodOptions::default()
    };
    let method = method_by_name(&args.curves, &options)
        .map_err(|e| ExperimentError::Usage(e.to_string()))?;
    let params = InteriorParameters {
        beta: [args.beta; 3],
        c: [args.c; 3],
    };
    let t1 = Instant::now();
    let fitted = fit(&mesh, method.as_ref(), &|_| params)
        .map_err(|e| ExperimentError::Usage(format!("{}: {e}", args.data)))?;
    let (fitted, stats) = refit_interior(&mesh, method.as_ref(), fitted, args.interior)
        .map_err(|e| ExperimentError::Usage(format!("{}: {e}", args.data)))?;
    let t_fit = t1.elapsed().as_secs_f64();
    if args.interior != InteriorChoice::Default {
        eprintln!(
            "  interior {}: {} faces, {} converged, {} kept at defaults, energy {:.4e} → {:.4e}",
            args.interior,
            stats.faces,
            stats.converged,
            stats.kept_default,
            stats.energy_default,
            stats.energy_chosen
        );
    }
    let t2 = Instant::now();
    let g1 = measure_g1(&mesh, &fitted, 9);
    let t_g1 = t2.elapsed().as_secs_f64();

    if let Some(out) = &args.out {
        let mut text = String::new();
        for (i, p) in fitted.patches.iter().enumerate() {
            let pts: Vec<[f64; 3]> = p.iter().map(|q| [q.x, q.y, q.z]).collect();
            let rec = json!({"type": "BezierTriangle", "degree": 4, "points": pts,
                              "face": i / 3, "subpatch": i % 3});
            let _ = writeln!(text, "{rec}");
        }
        write_result(Some(out), text.as_bytes())?;
    }
    if let Some(path) = &args.mesh_out {
        let t3 = Instant::now();
        let tess = surface::tessellate(&fitted.bezier_patches(), args.tess)
            .map_err(|e| ExperimentError::Usage(format!("tessellation: {e}")))?;
        let mut bytes = Vec::new();
        tess.write_obj(&mut bytes)
            .map_err(|source| ExperimentError::Write {
                path: path.clone(),
                source,
            })?;
        write_result(Some(path), &bytes)?;
        eprintln!(
            "  tessellation: s = {}, {} vertices, {} triangles, {} seam welds, in {:.3} s → {}",
            args.tess,
            tess.positions.len(),
            tess.faces.len(),
            tess.welds,
            t3.elapsed().as_secs_f64(),
            path.display()
        );
    }
    let faces = mesh.num_faces();
    eprintln!(
        "fit: {} ({} vertices, {} edges, {} faces), curves {}, β = {}, c = {}",
        args.data,
        mesh.num_vertices(),
        mesh.num_edges(),
        faces,
        method.name(),
        args.beta,
        args.c
    );
    eprintln!(
        "  G1 defect: interior {:.3e} rad, exterior {:.3e} rad; interpolation: position {:.3e}, normal {:.3e} rad",
        g1.interior_max, g1.exterior_max, g1.position_error, g1.normal_error
    );
    eprintln!(
        "  curves: {} fallbacks to chord, {} unconverged optimizations, {} flipped tangents",
        fitted.fallbacks, fitted.unconverged, fitted.flipped_tangents
    );
    eprintln!(
        "  time: read {:.3} s, fit {:.3} s ({:.0} triangles/s), G1 {:.3} s",
        t_read,
        t_fit,
        faces as f64 / t_fit.max(1e-12),
        t_g1
    );
    Ok(ExitCode::SUCCESS)
}

/// Refits `mesh` with interior parameters chosen by `choice` from the curves of a first fit
/// (the curves do not depend on β and c, so they are reused).
pub fn refit_interior(
    mesh: &Mesh,
    method: &dyn curves::CurveMethod,
    first: Fit,
    choice: InteriorChoice,
) -> Result<(Fit, InteriorStats), surface::FitError> {
    let (params, stats) = choose_interior(mesh, &first, choice);
    if choice == InteriorChoice::Default {
        return Ok((first, stats));
    }
    let refit = fit(mesh, method, &|f| params[f])?;
    Ok((refit, stats))
}

//! `experiments -- fit`: fit a data set or mesh file with a surface scheme (`--scheme`, default
//! the modified Shirman–Séquin, or a subdivision scheme with `--levels`), streamed a window of
//! faces at a time unless `--interior` needs the whole fit, and write the patches to `--out`
//! (JSON Lines, or the binary `.bzp` form) and the tessellation to `--mesh-out` (any mesh
//! format, by extension).
//!
//! Each JSON Lines output line is one record, `{"type": "BezierTriangle", "degree": n, "points":
//! [[x, y, z], …], "face": f, "subpatch": e}` (points in the row order of docs/conventions.md;
//! sub-patch `e` of face `f` spans the scheme's sub-triangle `e` of the face: for
//! Shirman–Séquin, the face's corners `e`, `e + 1` and the split point). stderr gets the G1
//! defect, the interpolation error, the curve statistics and the time of each stage.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use curves::method_by_name;
use surface::fairing::InteriorChoice;
use surface::{measure_g1, InteriorParameters};

use crate::curve_args::FitOptions;
use crate::error::ExperimentError;
use crate::input::{load, InputArgs};
use crate::limits::{
    self, check_f64, check_memory, check_usize, BETA_RANGE, C_RANGE, SAMPLING_RANGE,
};
use crate::output::write_result;

/// How many fallback faces and degenerate edges the terminal summary lists by name.
const FALLBACKS_LISTED: usize = 10;

/// Options of the `fit` experiment.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// The input mesh and how to complete it.
    #[command(flatten)]
    input: InputArgs,
    /// The construction, its options and the interior parameters.
    #[command(flatten)]
    fit: FitOptions,
    /// β at every corner (1/3: the Shirman–Séquin default, C1 inside each triangle).
    #[arg(long, default_value_t = surface::shirman_sequin::DEFAULT_BETA)]
    beta: f64,
    /// Jensen's c on every edge (1: Chiyokura–Kimura).
    #[arg(long, default_value_t = surface::shirman_sequin::DEFAULT_C)]
    c: f64,
    /// Where to write the patches: JSON Lines, or the compact binary form when the name ends in
    /// `.bzp` (`surface::patch_io`); none are written when absent. Without `--interior`, the
    /// patches are streamed: built, measured and written a window of faces at a time, never all
    /// held (`surface::stream`; the same report and file); a `--mesh-out` tessellation then
    /// builds each face's patches again where it samples them (the same mesh).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Tessellate the patches at this many segments per patch edge (the testbed's `Tess -s`)
    /// and write the welded triangle mesh to `--mesh-out`.
    #[arg(long, default_value_t = 4)]
    tess: usize,
    /// Subdivision steps for `--scheme loop|loop-warren|catmull-clark` (the control mesh after
    /// them goes to `--mesh-out`).
    #[arg(long, default_value_t = 3)]
    levels: u32,
    /// Exit with status 1 when anything was not as asked: a repaired file, a fallback face, a
    /// degenerate edge, a curve that fell back to the chord choice, an optimization that did
    /// not converge (all are counted in the summary either way).
    #[arg(long)]
    strict: bool,
    /// Where to write the tessellation, in the format its extension names (.obj, .ply, .off,
    /// .stl, .glb, .m): positions and normals; PLY and glTF also get vertex colours by Gaussian
    /// curvature (the testbed's KColor), PLY the curvatures as properties `gaussian`, `mean`.
    #[arg(long)]
    mesh_out: Option<PathBuf>,
}

/// Runs the experiment.
pub fn run(args: &FitArgs) -> Result<ExitCode, ExperimentError> {
    if subdiv::SCHEMES
        .iter()
        .any(|e| e.name == args.fit.scheme.scheme)
    {
        return crate::subdivide::run(
            &args.input.data,
            args.input.resolution,
            &args.fit.scheme.scheme,
            args.levels,
            args.mesh_out.as_deref(),
        );
    }
    check_f64(
        "beta",
        args.beta,
        &BETA_RANGE,
        "the interior points move by ~1/β",
    )?;
    check_f64(
        "c",
        args.c,
        &C_RANGE,
        "the cross-boundary field changes by c along an edge",
    )?;
    check_usize("tess", args.tess, &SAMPLING_RANGE)?;
    if let Some(r) = args.input.resolution {
        check_memory(
            &format!("--data {} --resolution {r}", args.input.data),
            limits::dataset_faces(&args.input.data, r) * limits::FIT_BYTES_PER_FACE as u128,
        )?;
    }
    if let Some(out) = &args.out {
        crate::output::refuse_unwritable("--out", out, &args.input.data)?;
    }
    // The tessellation's format, checked with its path before any work.
    let mesh_format = match &args.mesh_out {
        Some(out) => {
            crate::output::refuse_unwritable("--mesh-out", out, &args.input.data)?;
            Some(crate::output::mesh_format_for("--mesh-out", out)?)
        }
        None => None,
    };
    let t0 = Instant::now();
    let loaded = load(&args.input)?;
    for note in &loaded.notes {
        say!("  {note}");
    }
    let repaired = loaded.repairs.as_ref().is_some_and(|r| !r.is_clean());
    let mesh = loaded.mesh;
    let frame = loaded.frame;
    let face_source = loaded.face_source;
    let vertex_source = loaded.vertex_source;
    let t_read = t0.elapsed().as_secs_f64();
    // Peak resident memory after each stage (where the system says), for the summary.
    let mut peaks: Vec<(&str, u64)> = Vec::new();
    if let Some(b) = loaded.peak_after_read {
        peaks.push(("read", b));
    }
    let mut peak_after = |stage| {
        if let Some(b) = limits::peak_resident_bytes() {
            peaks.push((stage, b));
        }
    };
    peak_after(if loaded.peak_after_read.is_some() {
        "repair and estimation"
    } else {
        "data set"
    });
    let options = args.fit.curve.method_options();
    let method = method_by_name(&args.fit.curves, &options).map_err(ExperimentError::from)?;
    let params = InteriorParameters {
        beta: [args.beta; 3],
        c: [args.c; 3],
    };
    let t1 = Instant::now();
    let fit_error = |source| ExperimentError::Fit {
        subject: args.input.data.clone(),
        source,
    };
    let scheme = args.fit.scheme.build(params)?;
    // Streamed when nothing needs the whole fit's nets afterwards (no tessellation, no interior
    // optimization, which refits from a first fit): the same report and file, bit for bit,
    // without the nets in memory (`surface::stream`).
    // With `--mesh-out` too, when the layout is welded by topology: the tessellation then
    // builds each face's nets again where it evaluates them (`tessellate_fit_rebuilt`, the
    // same mesh), so the whole fit's nets are never held.
    let stream = args.fit.interior.choice == InteriorChoice::Default
        && (args.mesh_out.is_none() || surface::welds_by_topology(&scheme.layout(), args.tess));
    let (fitted, g1, stats, t_fit, t_g1) = if stream {
        let to_world = |q: &nalgebra::Point3<f64>| frame.to_world(q);
        let mut streamed: Option<Result<surface::stream::Streamed, surface::stream::StreamError>> =
            None;
        let run = |output: Option<surface::stream::Output<'_>>| {
            surface::stream::fit_streamed(&mesh, scheme.as_ref(), method.as_ref(), 9, output)
        };
        match &args.out {
            Some(out) => {
                let format = surface::patch_io::PatchFormat::for_path(out);
                let written = crate::output::write_result_with(Some(out), &mut |w| {
                    let r = run(Some(surface::stream::Output {
                        format,
                        to_world: &to_world,
                        out: w,
                    }));
                    let io = match &r {
                        Err(surface::stream::StreamError::Io(e)) => {
                            Err(std::io::Error::new(e.kind(), e.to_string()))
                        }
                        Err(surface::stream::StreamError::Fit(_)) => {
                            Err(std::io::Error::other("the fit failed"))
                        }
                        Ok(_) => Ok(()),
                    };
                    streamed = Some(r);
                    io
                });
                // A failed fit is reported as such, not as the write it interrupted.
                if let Some(Err(surface::stream::StreamError::Fit(source))) = streamed {
                    return Err(fit_error(source));
                }
                written?;
            }
            None => streamed = Some(run(None)),
        }
        let s = match streamed {
            Some(Ok(s)) => s,
            Some(Err(surface::stream::StreamError::Fit(source))) => return Err(fit_error(source)),
            Some(Err(surface::stream::StreamError::Io(source))) => {
                return Err(ExperimentError::Write {
                    path: args.out.clone().unwrap_or_default(),
                    source,
                })
            }
            None => {
                return Err(ExperimentError::Write {
                    path: args.out.clone().unwrap_or_default(),
                    source: std::io::Error::other("the fit did not run"),
                })
            }
        };
        let total = t1.elapsed().as_secs_f64();
        say!(
            "  streamed: curves {:.3} s, then patches, G1{} a window of faces at a time {:.3} s",
            s.curves_seconds,
            if args.out.is_some() {
                " and writing"
            } else {
                ""
            },
            total - s.curves_seconds
        );
        peak_after(if args.out.is_some() {
            "fit, G1 and write"
        } else {
            "fit and G1"
        });
        let stats = surface::fairing::InteriorStats {
            faces: mesh.num_faces(),
            ..Default::default()
        };
        (
            s.fit,
            s.g1,
            stats,
            s.curves_seconds,
            total - s.curves_seconds,
        )
    } else {
        let (fitted, stats) = surface::fairing::fit_surface(
            &mesh,
            scheme.as_ref(),
            method.as_ref(),
            args.fit.interior.choice,
            args.fit.curve.solver,
        )
        .map_err(fit_error)?;
        let t_fit = t1.elapsed().as_secs_f64();
        peak_after("fit");
        let t2 = Instant::now();
        let g1 = measure_g1(&mesh, &fitted, 9);
        let t_g1 = t2.elapsed().as_secs_f64();
        peak_after("G1");
        if let Some(out) = &args.out {
            let t_out = Instant::now();
            let format = surface::patch_io::PatchFormat::for_path(out);
            let to_world = |q: &nalgebra::Point3<f64>| frame.to_world(q);
            crate::output::write_result_with(Some(out), &mut |w| {
                surface::patch_io::write_patches(&fitted, format, &to_world, w)
            })?;
            say!(
                "  patches written to {} in {:.3} s",
                out.display(),
                t_out.elapsed().as_secs_f64()
            );
            peak_after("write");
        }
        (fitted, g1, stats, t_fit, t_g1)
    };
    if args.fit.interior.choice != InteriorChoice::Default {
        say!(
            "  interior {}: {} faces, {} converged, {} kept at defaults, energy {:.4e} → {:.4e}",
            args.fit.interior.choice,
            stats.faces,
            stats.converged,
            stats.kept_default,
            stats.energy_default,
            stats.energy_chosen
        );
    }
    if let (Some(path), Some(format)) = (&args.mesh_out, mesh_format) {
        check_memory(
            &format!("--tess {}", args.tess),
            // Patches counted from the mesh: a streamed fit holds no nets to count.
            limits::tessellation_bytes(
                (mesh.num_faces() * fitted.layout.patches_per_face()) as u128,
                args.tess,
            ),
        )?;
        let t3 = Instant::now();
        let tessellated = if stream {
            surface::tessellate_fit_rebuilt(&mesh, &fitted, scheme.as_ref(), args.tess)
        } else {
            surface::tessellate_fit(&mesh, &fitted, args.tess)
        };
        let mut tess = tessellated.map_err(|source| ExperimentError::Tessellate {
            subject: args.input.data.clone(),
            source,
        })?;
        let tessellate_time = t3.elapsed().as_secs_f64();
        tess.to_world(&frame);
        let raw = tessellation_to_raw(&tess);
        let bytes =
            meshio::write_bytes(&raw, format, &meshio::WriteOptions::new()).map_err(|source| {
                ExperimentError::MeshWrite {
                    path: path.clone(),
                    source,
                }
            })?;
        write_result(Some(path), &bytes)?;
        say!(
            "  tessellation: s = {}, {} vertices, {} triangles, {} seam welds, in {:.3} s (tessellate {:.3} s, convert and write the rest) → {}",
            args.tess,
            tess.positions.len(),
            tess.faces.len(),
            tess.welds,
            t3.elapsed().as_secs_f64(),
            tessellate_time,
            path.display()
        );
        peak_after("tessellate");
    }
    let faces = mesh.num_faces();
    let settings = match (fitted.scheme, scheme.uses_curves()) {
        ("shirman-sequin", _) => {
            format!(
                "curves {}, β = {}, c = {}",
                method.name(),
                args.beta,
                args.c
            )
        }
        (_, true) => format!("curves {}", method.name()),
        (_, false) => "its own boundaries".to_string(),
    };
    say!(
        "fit: {} ({} vertices, {} edges, {} faces), scheme {} ({}), {settings}",
        args.input.data,
        mesh.num_vertices(),
        mesh.num_edges(),
        faces,
        fitted.scheme,
        fitted.continuity,
    );
    say!(
        "  {}: interior {:.3e} rad, exterior {:.3e} rad; interpolation: position {:.3e}, normal {:.3e} rad",
        if fitted.continuity == surface::Continuity::G1 { "G1 defect" } else { "normal jump (the scheme claims only C0)" },
        g1.interior_max, g1.exterior_max, g1.position_error * frame.scale, g1.normal_error
    );
    if !fitted.face_fallbacks.is_empty() {
        say!(
            "  fallback: {} faces fitted C0 ({} edges touch them; G1 defect there: interior {:.3e} rad, exterior {:.3e} rad)",
            fitted.face_fallbacks.len(),
            g1.fallback_edges,
            g1.fallback_interior_max,
            g1.fallback_exterior_max
        );
        for fb in fitted.face_fallbacks.iter().take(FALLBACKS_LISTED) {
            // In the file's numbering where the mesh came from a file (0-based).
            let v = mesh.faces()[fb.face].map(|i| {
                vertex_source
                    .as_ref()
                    .and_then(|s| s.get(i).copied())
                    .unwrap_or(i)
            });
            let file_face = face_source
                .as_ref()
                .and_then(|s| s.get(fb.face))
                .map(|f| format!(", file face {f}"))
                .unwrap_or_default();
            say!(
                "    face {} (file vertices {}, {}, {}{file_face}): {}",
                fb.face,
                v[0],
                v[1],
                v[2],
                fb.reason
            );
        }
        if fitted.face_fallbacks.len() > FALLBACKS_LISTED {
            say!("    … ({} in all)", fitted.face_fallbacks.len());
        }
    }
    if !fitted.degenerate_edges.is_empty() {
        say!(
            "  degenerate edges: {} fitted with straight cubics",
            fitted.degenerate_edges.len()
        );
        for d in fitted.degenerate_edges.iter().take(FALLBACKS_LISTED) {
            say!("    edge {}: {}", d.edge, d.error);
        }
    }
    if scheme.uses_curves() {
        say!(
            "  curves: {} fallbacks to chord, {} unconverged optimizations, {} flipped tangents",
            fitted.fallbacks,
            fitted.unconverged,
            fitted.flipped_tangents
        );
    }
    if stream {
        say!(
            "  time: read {:.3} s, curves {:.3} s, patches, G1{} {:.3} s ({:.0} triangles/s)",
            t_read,
            t_fit,
            if args.out.is_some() {
                " and writing"
            } else {
                ""
            },
            t_g1,
            faces as f64 / (t_fit + t_g1).max(1e-12),
        );
    } else {
        say!(
            "  time: read {:.3} s, fit {:.3} s ({:.0} triangles/s), G1 {:.3} s",
            t_read,
            t_fit,
            faces as f64 / t_fit.max(1e-12),
            t_g1
        );
    }
    say!(
        "  peak memory: {}",
        peaks
            .iter()
            .map(|(stage, b)| format!(
                "{stage} {:.0} MB ({:.0} bytes/triangle)",
                *b as f64 / 1e6,
                *b as f64 / faces.max(1) as f64
            ))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let departures = [
        (usize::from(repaired), "repaired input"),
        (fitted.face_fallbacks.len(), "fallback faces"),
        (fitted.degenerate_edges.len(), "degenerate edges"),
        (fitted.fallbacks, "curves fallen back to chord"),
        (fitted.unconverged, "unconverged optimizations"),
    ];
    let found: Vec<String> = departures
        .iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, what)| format!("{n} {what}"))
        .collect();
    if args.strict && !found.is_empty() {
        say!("strict: {}", found.join(", "));
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

/// A tessellation as a raw mesh for the writers: positions, normals, colours by Gaussian
/// curvature (diverging map, limit the 95th percentile of |K| so a few spikes do not wash the
/// picture out) and the curvatures as properties `gaussian`, `mean`.
pub fn tessellation_to_raw(tess: &surface::Tessellation) -> meshio::RawMesh {
    let mut raw = tess.to_raw();
    let mut abs: Vec<f64> = tess
        .gaussian
        .iter()
        .map(|k| k.abs())
        .filter(|k| k.is_finite())
        .collect();
    abs.sort_by(f64::total_cmp);
    let limit = abs
        .get(abs.len().saturating_sub(1) * 95 / 100)
        .copied()
        .filter(|l| *l > 0.0)
        .unwrap_or(1.0);
    raw.colors = Some(
        tess.gaussian
            .iter()
            .map(|k| render::colors::diverging(*k, limit))
            .collect(),
    );
    raw
}

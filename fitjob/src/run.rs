//! The job itself: read → repair → estimate → curves → patches → G1 → (stream) → tessellate →
//! write, with the memory estimates checked before the large allocations and every output path
//! checked before any work.

use std::time::Instant;

use mesh::{Frame, Mesh};
use surface::fairing::InteriorChoice;
use surface::stream::{StreamError, Streamed};
use surface::{Fit, G1Report, Tessellation};

use crate::error::JobError;
use crate::input::{load_owned, Source};
use crate::limits::{self, check_memory, check_usize};
use crate::options::FitOptions;
use crate::output::{destination, mesh_format_for, refuse_unwritable, write_result_with};

use crate::report::{
    CurveCounts, DegenerateEdge, FaceRef, FallbackFace, FitReport, FoldSummary, G1Summary,
    InteriorSummary, PeakMemory, TessellationSummary, Timings,
};

/// What a job leaves besides its report, when [`FitOptions::keep`] asks for it.
#[derive(Default)]
pub struct Kept {
    /// The mesh fitted, in its working frame.
    pub mesh: Option<Mesh>,
    /// The way back from the working frame to the input's coordinates.
    pub frame: Option<Frame>,
    /// The fit, every net held (in the working frame).
    pub fit: Option<Fit>,
    /// The tessellation (in world coordinates), when one was made.
    pub tessellation: Option<Tessellation>,
    /// The whole G1 measurement (with where its maxima are), when it was made.
    pub g1: Option<G1Report>,
    /// For each mesh face, the input's face it came from (`None` for a data set).
    pub face_source: Option<Vec<usize>>,
    /// For each mesh vertex, the input's vertex it came from (`None` for a data set).
    pub vertex_source: Option<Vec<usize>>,
}

/// A finished job: its report, and what [`FitOptions::keep`] asked to keep.
pub struct FitOutcome {
    /// The report.
    pub report: FitReport,
    /// The mesh, fit and tessellation (empty unless kept).
    pub kept: Kept,
}

/// Runs the fit job: `log` receives the progress lines as the stages finish (the input's notes,
/// the stream's timing, the outputs written); the summary is
/// [`FitReport::summary_lines`] of the returned report.
///
/// The options are taken, so that a raw mesh in memory ([`Source::Raw`]) is repaired without a
/// copy.
pub fn run(mut options: FitOptions, log: &mut dyn FnMut(&str)) -> Result<FitOutcome, JobError> {
    // A spinner naming the stage on a terminal once the job has run a moment (silent in pipes
    // and files); the job's lines are printed above it.
    let progress = progress::Progress::spinner("fit");
    let log = &mut |line: &str| progress.suspend(|| log(line));
    if options.is_subdivision() {
        progress.stage("subdividing");
        return crate::subdivision::run(&options).map(|report| FitOutcome {
            report,
            kept: Kept::default(),
        });
    }
    let entry = surface::scheme::entry_by_name(&options.scheme)?;
    limits::check_scheme_parameters(entry, &options.scheme_options)?;
    check_usize("segments", options.tess, &limits::SAMPLING_RANGE)?;
    let label = options.input.source.label().to_string();
    if let Source::Data {
        data,
        resolution: Some(r),
    }
    | Source::DataSet {
        name: data,
        resolution: Some(r),
    } = &options.input.source
    {
        check_memory(
            &format!("--data {data} --resolution {r}"),
            limits::dataset_faces(data, *r) * limits::FIT_BYTES_PER_FACE as u128,
        )?;
    }
    let input_file = options
        .input
        .source
        .file()
        .map(|p| p.to_string_lossy().into_owned())
        .unwrap_or_default();
    if let Some(out) = options.patches_out.as_deref().and_then(destination) {
        refuse_unwritable("--output", out, &input_file)?;
    }
    // The tessellation's format, checked with its path before any work.
    let mesh_format = match &options.mesh_out {
        Some(out) => {
            refuse_unwritable("--mesh-output", out, &input_file)?;
            Some(mesh_format_for("--mesh-output", out)?)
        }
        None => None,
    };
    let t0 = Instant::now();
    // The input is taken (a raw mesh moves into the repair); what follows reads only its label.
    let input = std::mem::take(&mut options.input);
    progress.stage("reading, repairing and estimating the input");
    let loaded = load_owned(input)?;
    for note in &loaded.notes {
        log(&format!("  {note}"));
    }
    let repaired = loaded.repairs.as_ref().is_some_and(|r| !r.is_clean());
    let mesh = loaded.mesh;
    let frame = loaded.frame;
    if let (Some(path), Some(format)) = (&options.mesh_out, mesh_format) {
        // Curvature no float of the format holds is refused now, not after the fit.
        crate::output::refuse_unstorable_curvature("--mesh-output", path, format, frame.scale)?;
    }
    let t_read = t0.elapsed().as_secs_f64();
    // Peak resident memory after each stage (where the system says), for the summary.
    let mut peaks: Vec<PeakMemory> = Vec::new();
    if let Some(bytes) = loaded.peak_after_read {
        peaks.push(PeakMemory {
            stage: "read".into(),
            bytes,
        });
    }
    let mut peak_after = |stage: &str| {
        if let Some(bytes) = limits::peak_resident_bytes() {
            peaks.push(PeakMemory {
                stage: stage.into(),
                bytes,
            });
        }
    };
    peak_after(if loaded.peak_after_read.is_some() {
        "repair and estimation"
    } else {
        "data set"
    });
    let method = curves::method_by_name(&options.curves, &options.method_options)?;
    progress.stage("fitting the patches and measuring G1");
    let t1 = Instant::now();
    let fit_error = |source| JobError::Fit {
        subject: label.clone(),
        source,
    };
    let scheme = (entry.build)(&options.scheme_options);
    // A height field gets the scheme's functional form (C1 for clough-tocher and powell-sabin),
    // said in a note with the rule that detected it.
    let (scheme, heightfield_note) =
        surface::scheme::functional::choose(scheme, &mesh, options.heightfield).map_err(
            |source| JobError::HeightField {
                subject: label.clone(),
                source,
            },
        )?;
    if let Some(note) = &heightfield_note {
        log(&format!("  {note}"));
    }
    // Streamed when nothing needs the whole fit's nets afterwards (no interior optimization,
    // which refits from a first fit; nothing kept): the same report and file, bit for bit,
    // without the nets in memory (`surface::stream`). With a tessellation too, when the layout
    // is welded by topology: the tessellation then builds each face's nets again where it
    // evaluates them (`tessellate_fit_rebuilt`, the same mesh).
    let stream = options.interior == InteriorChoice::Default
        && !options.keep
        && (options.mesh_out.is_none()
            || surface::welds_by_topology(&scheme.layout(), options.tess));
    let samples = options.g1_samples;
    // The fold test, measured with G1 (surface::folds).
    let mut folds: Option<surface::folds::FoldReport> = None;
    let (mut fitted, g1, stats, t_fit, t_g1): (Fit, G1Report, _, f64, f64) = if stream {
        let to_world = |q: &nalgebra::Point3<f64>| frame.to_world(q);
        let mut streamed: Option<Result<Streamed, StreamError>> = None;
        let run = |output: Option<surface::stream::Output<'_>>| {
            surface::stream::fit_streamed(&mesh, scheme.as_ref(), method.as_ref(), samples, output)
        };
        match &options.patches_out {
            Some(out) => {
                let format = surface::patch_io::PatchFormat::for_path(out);
                let written = write_result_with(destination(out), &mut |w| {
                    let r = run(Some(surface::stream::Output {
                        format,
                        to_world: &to_world,
                        out: w,
                    }));
                    let io = match &r {
                        Err(StreamError::Io(e)) => {
                            Err(std::io::Error::new(e.kind(), e.to_string()))
                        }
                        Err(StreamError::Fit(_)) => Err(std::io::Error::other("the fit failed")),
                        Ok(_) => Ok(()),
                    };
                    streamed = Some(r);
                    io
                });
                // A failed fit is reported as such, not as the write it interrupted.
                if let Some(Err(StreamError::Fit(source))) = streamed {
                    return Err(fit_error(source));
                }
                written?;
            }
            None => streamed = Some(run(None)),
        }
        let s = match streamed {
            Some(Ok(s)) => s,
            Some(Err(StreamError::Fit(source))) => return Err(fit_error(source)),
            Some(Err(StreamError::Io(source))) => {
                return Err(JobError::Write {
                    path: options.patches_out.clone().unwrap_or_default(),
                    source,
                })
            }
            None => {
                return Err(JobError::Write {
                    path: options.patches_out.clone().unwrap_or_default(),
                    source: std::io::Error::other("the fit did not run"),
                })
            }
        };
        let total = t1.elapsed().as_secs_f64();
        log(&format!(
            "  streamed: curves {:.3} s, then patches, G1{} a window of faces at a time {:.3} s",
            s.curves_seconds,
            if options.patches_out.is_some() {
                " and writing"
            } else {
                ""
            },
            total - s.curves_seconds
        ));
        peak_after(if options.patches_out.is_some() {
            "fit, G1 and write"
        } else {
            "fit and G1"
        });
        let stats = surface::fairing::InteriorStats {
            faces: mesh.num_faces(),
            ..Default::default()
        };
        folds = Some(s.folds);
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
            options.interior,
            options.method_options.solver,
        )
        .map_err(fit_error)?;
        let t_fit = t1.elapsed().as_secs_f64();
        peak_after("fit");
        let t2 = Instant::now();
        let g1 = if options.measure_g1 {
            folds = Some(surface::folds::measure(&mesh, &fitted));
            surface::measure_g1(&mesh, &fitted, samples)
        } else {
            G1Report::default()
        };
        let t_g1 = t2.elapsed().as_secs_f64();
        peak_after("G1");
        if let Some(out) = &options.patches_out {
            let t_out = Instant::now();
            let format = surface::patch_io::PatchFormat::for_path(out);
            let to_world = |q: &nalgebra::Point3<f64>| frame.to_world(q);
            write_result_with(destination(out), &mut |w| {
                surface::patch_io::write_patches(&fitted, format, &to_world, w)
            })?;
            log(&format!(
                "  patches written to {} in {:.3} s",
                out.display(),
                t_out.elapsed().as_secs_f64()
            ));
            peak_after("write");
        }
        (fitted, g1, stats, t_fit, t_g1)
    };
    let interior = (options.interior != InteriorChoice::Default).then(|| InteriorSummary {
        choice: options.interior.to_string(),
        faces: stats.faces,
        converged: stats.converged,
        kept_default: stats.kept_default,
        energy_default: stats.energy_default,
        energy_chosen: stats.energy_chosen,
    });
    if let Some(i) = &interior {
        log(&format!(
            "  interior {}: {} faces, {} converged, {} kept at defaults, energy {:.4e} → {:.4e}",
            i.choice, i.faces, i.converged, i.kept_default, i.energy_default, i.energy_chosen
        ));
    }
    let mut tessellation = None;
    let mut kept_tessellation = None;
    let mut t_tess = 0.0;
    let mut t_sample = 0.0;
    if let (Some(path), Some(format)) = (&options.mesh_out, mesh_format) {
        check_memory(
            &format!("--segments {}", options.tess),
            // Patches counted from the mesh: a streamed fit holds no nets to count.
            limits::tessellation_bytes(
                (mesh.num_faces() * fitted.layout.patches_per_face()) as u128,
                options.tess,
            ),
        )?;
        progress.stage("tessellating");
        let t3 = Instant::now();
        if !options.keep {
            // The curves' end-derivative lengths are the report's no more (and the faces are
            // built from the curves alone): 16 B an edge let go before the tessellation's peak.
            fitted.alphas = Vec::new();
        }
        let tessellated = if stream {
            // A caller that keeps the tessellation gets every array; the file needs only the
            // principal directions, where its format stores them (48 B a vertex, where the
            // shape tensors they come from take 72), and not the triangles' patches.
            let keep = if options.keep {
                surface::tessellate_fit::Keep::ALL
            } else {
                surface::tessellate_fit::Keep {
                    shapes: false,
                    directions: format.writes_curvature().then_some(frame.scale),
                    patches: false,
                }
            };
            if options.keep {
                surface::tessellate_fit_rebuilt_with(
                    &mesh,
                    &fitted,
                    scheme.as_ref(),
                    options.tess,
                    keep,
                )
            } else {
                // The curves are the report's no more: freed once the samples are evaluated.
                surface::tessellate_fit_rebuilt_taking(
                    &mesh,
                    &mut fitted,
                    scheme.as_ref(),
                    options.tess,
                    keep,
                )
            }
        } else {
            surface::tessellate_fit(&mesh, &fitted, options.tess)
        };
        let mut tess = tessellated.map_err(|source| JobError::Tessellate {
            subject: label.clone(),
            source,
        })?;
        let tessellate_time = t3.elapsed().as_secs_f64();
        if !options.keep {
            // Only the tessellation needed the boundary curves (96 B an edge: 0.14 GB at 10⁶
            // faces) and the nets (1080 B a face when not streamed); the report reads neither,
            // so they go before the file's mesh is built beside the tessellation.
            fitted.curves = Vec::new();
            fitted.points = Vec::new();
        }
        t_sample = tessellate_time;
        tess.to_world(&frame);
        let (vertices, triangles, welds) = (tess.positions.len(), tess.faces.len(), tess.welds);
        // The mesh takes the tessellation's arrays unless it is kept.
        let raw = if options.keep {
            let raw = crate::output::tessellation_mesh(&tess, format);
            kept_tessellation = Some(tess);
            raw
        } else {
            crate::output::into_tessellation_mesh(tess, format)
        };
        let write_options = options.mesh_options.write_options();
        crate::output::write_mesh_result(path, format, &raw, &write_options)?;
        drop(raw);
        t_tess = t3.elapsed().as_secs_f64();
        log(&format!(
            "  tessellation: s = {}, {} vertices, {} triangles, {} seam welds, in {:.3} s (tessellate {:.3} s, convert and write the rest) → {}",
            options.tess,
            vertices,
            triangles,
            welds,
            t_tess,
            tessellate_time,
            path.display()
        ));
        peak_after("tessellate");
        tessellation = Some(TessellationSummary {
            segments: options.tess,
            vertices,
            triangles,
            welds,
            path: path.display().to_string(),
        });
    }
    let faces = mesh.num_faces();
    let uses_curves = scheme.uses_curves();
    // The curves (or not), then every parameter the scheme declares, as set.
    let mut settings = if uses_curves {
        format!("curves {}", method.name())
    } else {
        "its own boundaries".to_string()
    };
    for p in entry.parameters {
        settings.push_str(&format!(
            ", {} = {}",
            p.symbol,
            options.scheme_options.value(p)
        ));
    }
    let face_source = loaded.face_source.as_deref();
    let vertex_source = loaded.vertex_source.as_deref();
    // A face with its corners and its face in the file's numbering where the mesh came from a
    // file (0-based).
    let file_face = |f: usize| FaceRef {
        face: f,
        file_vertices: mesh.faces()[f]
            .map(|i| vertex_source.and_then(|s| s.get(i).copied()).unwrap_or(i)),
        file_face: face_source.and_then(|s| s.get(f).copied()),
    };
    let fallback_faces = fitted
        .face_fallbacks
        .iter()
        .map(|fb| {
            let at = file_face(fb.face);
            FallbackFace {
                face: at.face,
                file_vertices: at.file_vertices,
                file_face: at.file_face,
                reason: fb.reason.to_string(),
            }
        })
        .collect();
    let folds = folds.map(|r| FoldSummary {
        faces_measured: r.faces,
        folded_faces: r.folded.iter().map(|&f| file_face(f)).collect(),
        worst_cosine: r.worst_cosine,
        faces_without_normal: r.faces_without_normal,
        singular_samples: r.singular_samples,
    });
    let report = FitReport {
        input: label,
        vertices: mesh.num_vertices(),
        edges: mesh.num_edges(),
        faces,
        notes: loaded.notes.into_iter().chain(heightfield_note).collect(),
        creases: loaded.creases,
        repaired,
        scheme: fitted.scheme.to_string(),
        continuity: fitted.continuity.to_string(),
        curves: uses_curves.then(|| method.name().to_string()),
        settings,
        streamed: stream,
        g1: (stream || options.measure_g1).then_some(G1Summary {
            samples,
            interior_max: g1.interior_max,
            exterior_max: g1.exterior_max,
            fallback_edges: g1.fallback_edges,
            crease_edges: g1.crease_edges,
            fallback_interior_max: g1.fallback_interior_max,
            fallback_exterior_max: g1.fallback_exterior_max,
            position_error: g1.position_error * frame.scale,
            normal_error: g1.normal_error,
            undefined_normals: g1.undefined_normals,
        }),
        fallback_faces,
        folds,
        degenerate_edges: fitted
            .degenerate_edges
            .iter()
            .map(|d| DegenerateEdge {
                edge: d.edge,
                error: d.error.to_string(),
            })
            .collect(),
        curve_counts: uses_curves.then_some(CurveCounts {
            fallbacks: fitted.fallbacks,
            unconverged: fitted.unconverged,
            flipped_tangents: fitted.flipped_tangents,
            clamped_tangents: fitted.clamped_tangents,
            shortened_curves: fitted.shortened_curves,
            crease_edges: fitted.crease_edges,
            crease_ends_off_line: fitted.crease_ends_off_line,
            fan: fitted.fan,
        }),
        interior,
        tessellation,
        subdivision: None,
        patches_out: options
            .patches_out
            .as_ref()
            .map(|p| p.display().to_string()),
        time: Timings {
            read: t_read,
            fit: t_fit,
            g1: t_g1,
            tessellate: t_tess,
            sample: t_sample,
        },
        peak_memory: peaks,
    };
    let kept = if options.keep {
        Kept {
            mesh: Some(mesh),
            frame: Some(frame),
            fit: Some(fitted),
            tessellation: kept_tessellation,
            g1: (stream || options.measure_g1).then_some(g1),
            face_source: loaded.face_source.clone(),
            vertex_source: loaded.vertex_source.clone(),
        }
    } else {
        Kept::default()
    };
    Ok(FitOutcome { report, kept })
}

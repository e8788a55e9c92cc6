//! A fit streamed to its output: the boundary curves of the whole mesh first, then the faces a
//! window at a time — their patches built into one reused buffer, G1 measured on them, the
//! patches formatted and written in order — so the whole [`Fit`]'s nets (about 1.1 kB a
//! triangle for three quartics) are never held, and no gigabyte of fresh pages is touched.
//!
//! What it gives is what [`crate::fit::fit_scheme`], [`crate::g1::measure`] and
//! [`crate::patch_io::write_patches`] give, bit for bit and byte for byte: the same [`Fit`]
//! (without [`Fit::points`]), the same [`G1Report`] (locations of maxima and ties included),
//! the same file. That rests on one property of the schemes: a face's patches depend only on
//! its own corners' vertex data, its three edge curves and the scheme
//! ([`crate::fit::build_face`]), so an exterior edge whose other face lies outside the window
//! is measured against that face built again, locally, to the same bits.
//!
//! Memory: the mesh, the curves, one window of nets and the formatted bytes of up to three
//! windows (one being formatted, one queued, one being written).

use std::io::Write;
use std::sync::mpsc;

use curves::CurveMethod;
use nalgebra::Point3;
use rayon::prelude::*;

use crate::fit::{build_face, fit_curves_into, FaceFallback, FaceFallbackReason, Fit, FitError};
use crate::folds::{FoldPlan, FoldReport};
use crate::g1::{G1Report, StreamingG1};
use crate::mesh::Mesh;
use crate::patch_io::PatchFormat;
use crate::scheme::Scheme;

/// Faces per window: their nets (three quartics: 1080 bytes a face) are held at once, about
/// 35 MB; large enough that few exterior edges cross a window's border (their outside face is
/// built twice), small enough to stay a small part of the mesh's own memory at 10⁶ faces.
pub const WINDOW_FACES: usize = 32_768;

/// Faces per parallel task inside a window.
const TASK_FACES: usize = 1024;

/// Why a streamed fit stopped.
#[derive(Debug, thiserror::Error)]
pub enum StreamError {
    /// The fit itself failed (a bad parameter, missing curvature, an inconsistent mesh).
    #[error(transparent)]
    Fit(#[from] FitError),
    /// Writing the output failed.
    #[error("writing the patches: {0}")]
    Io(#[from] std::io::Error),
}

/// Where streamed patches go: the form and the map to world coordinates.
pub struct Output<'a> {
    /// The form.
    pub format: PatchFormat,
    /// Applied to every point before it is written (the identity, or a working frame's way
    /// back).
    pub to_world: &'a (dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
    /// The destination.
    pub out: &'a mut dyn Write,
}

/// The result of one window's task: its faces' G1 part, its edges' G1 part, its formatted
/// bytes.
struct Task {
    /// The folds of its faces.
    folds: FoldReport,
    faces: G1Report,
    edges: G1Report,
    /// How many exterior edges it measured (all of them are, once: checked at the end).
    measured: usize,
    bytes: Vec<u8>,
}

/// What a streamed fit gives back.
#[derive(Clone, Debug)]
pub struct Streamed {
    /// The fit as [`crate::fit::fit_scheme`] gives it, but for [`Fit::points`], left empty.
    pub fit: Fit,
    /// The G1 report as [`crate::g1::measure`] gives it for the whole fit.
    pub g1: G1Report,
    /// Seconds spent on the boundary curves (the rest went to the windows of faces).
    pub curves_seconds: f64,
    /// The folds of the whole fit, as [`crate::folds::measure`] gives them.
    pub folds: FoldReport,
}

/// Fits `mesh` with `scheme` (curves from `method`), measures G1 at `samples` points per
/// boundary, and writes the patches to `output` if given ([`Output`]; none are formatted
/// otherwise), without holding all the nets (module docs). Returns the fit without its points
/// and the G1 report, both as the non-streamed path gives them.
pub fn fit_streamed(
    mesh: &Mesh,
    scheme: &dyn Scheme,
    method: &dyn CurveMethod,
    samples: usize,
    output: Option<Output<'_>>,
) -> Result<Streamed, StreamError> {
    fit_streamed_with(mesh, scheme, method, samples, output, WINDOW_FACES)
}

/// [`fit_streamed`] with `window` faces per window (tests use small windows to cross many
/// borders).
pub fn fit_streamed_with(
    mesh: &Mesh,
    scheme: &dyn Scheme,
    method: &dyn CurveMethod,
    samples: usize,
    output: Option<Output<'_>>,
    window: usize,
) -> Result<Streamed, StreamError> {
    let t0 = std::time::Instant::now();
    let mut fit = Fit::default();
    fit_curves_into(mesh, scheme, method, &mut fit)?;
    let curves_seconds = t0.elapsed().as_secs_f64();
    let layout = fit.layout;
    let faces = mesh.num_faces();
    let window = window.max(1);
    let per_face = layout.points_per_face().max(1);
    let patches_per_face = layout.patches_per_face().max(1);
    let format = output.as_ref().map(|o| (o.format, o.to_world));
    let mut g1 = StreamingG1::new(&layout, samples);
    let fold_plan = FoldPlan::new(&layout);
    let mut folds = FoldReport::default();
    let mut fallbacks: Vec<FaceFallback> = Vec::new();
    let mut measured_edges = 0usize;
    let curves = &fit.curves;

    // The windows are computed on one thread (with rayon inside) while the caller's thread
    // writes the previous window's bytes; spent buffers come back to be refilled, so the
    // formatted output does not touch fresh pages after the first windows either.
    let (full_tx, full_rx) = mpsc::sync_channel::<Vec<Vec<u8>>>(1);
    let (empty_tx, empty_rx) = mpsc::channel::<Vec<u8>>();
    let result = std::thread::scope(|s| -> Result<(), StreamError> {
        let g1 = &mut g1;
        let folds = &mut folds;
        let fold_plan = &fold_plan;
        let fallbacks = &mut fallbacks;
        let measured_edges = &mut measured_edges;
        let compute = s.spawn(move || -> Result<(), FitError> {
            let mut nets = vec![Point3::origin(); per_face * window.min(faces.max(1))];
            let mut reasons: Vec<Option<FaceFallbackReason>> = vec![None; window];
            for first in (0..faces).step_by(window) {
                let n = window.min(faces - first);
                let nets = &mut nets[..n * per_face];
                let reasons = &mut reasons[..n];
                nets.par_chunks_mut(per_face)
                    .zip(reasons.par_iter_mut())
                    .enumerate()
                    .try_for_each(|(i, (out, reason))| -> Result<(), FitError> {
                        *reason = build_face(mesh, scheme, curves, first + i, out)?;
                        Ok(())
                    })?;
                let mask: Vec<bool> = reasons.iter().map(Option::is_some).collect();
                let (nets, mask) = (&*nets, &mask[..]);
                let spare: Vec<Vec<u8>> = (0..n.div_ceil(TASK_FACES))
                    .map(|_| empty_rx.try_recv().unwrap_or_default())
                    .collect();
                let tasks: Vec<Task> = spare
                    .into_par_iter()
                    .enumerate()
                    .map(|(t, mut bytes)| -> Result<Task, FitError> {
                        let lo = t * TASK_FACES;
                        let hi = (lo + TASK_FACES).min(n);
                        let pts = &nets[lo * per_face..hi * per_face];
                        let faces_part = g1.faces(mesh, first + lo, pts, &mask[lo..hi]);
                        let mut edges_part = StreamingG1::empty_part();
                        let mut measured = 0;
                        let mut other = vec![Point3::origin(); per_face];
                        let mut task_folds = FoldReport::default();
                        for i in lo..hi {
                            let f = first + i;
                            fold_plan.face(
                                mesh,
                                f,
                                &nets[i * per_face..(i + 1) * per_face],
                                &mut task_folds,
                            );
                            for l in 0..3 {
                                let ei = mesh
                                    .edge_index(f, l)
                                    .map_err(|e| FitError::Mesh(e.to_string()))?;
                                let e = &mesh.edge(ei);
                                let (Some((g, _)), true) = (e.second, e.first == (f, l)) else {
                                    continue;
                                };
                                let (pg, fg) = if (first..first + n).contains(&g) {
                                    let j = g - first;
                                    (&nets[j * per_face..(j + 1) * per_face], mask[j])
                                } else {
                                    let why = build_face(mesh, scheme, curves, g, &mut other)?;
                                    (&other[..], why.is_some())
                                };
                                let mut part = StreamingG1::empty_part();
                                g1.edge(
                                    mesh,
                                    ei,
                                    [&nets[i * per_face..(i + 1) * per_face], pg],
                                    [mask[i], fg],
                                    &mut part,
                                );
                                edges_part = StreamingG1::merge_edges(edges_part, part);
                                measured += 1;
                            }
                        }
                        bytes.clear();
                        if let Some((format, to_world)) = format {
                            format.format(
                                &layout,
                                (first + lo) * patches_per_face,
                                pts,
                                to_world,
                                &mut bytes,
                            );
                        }
                        Ok(Task {
                            folds: task_folds,
                            faces: faces_part,
                            edges: edges_part,
                            measured,
                            bytes,
                        })
                    })
                    .collect::<Result<_, _>>()?;
                let mut out = Vec::with_capacity(tasks.len());
                for task in tasks {
                    *measured_edges += task.measured;
                    folds.merge(task.folds);
                    g1.add_faces(task.faces);
                    g1.add_edges(task.edges);
                    out.push(task.bytes);
                }
                fallbacks.extend(reasons.iter().enumerate().filter_map(|(i, r)| {
                    r.map(|reason| FaceFallback {
                        face: first + i,
                        reason,
                    })
                }));
                if format.is_some() && full_tx.send(out).is_err() {
                    // The writer stopped (its error is reported there).
                    break;
                }
            }
            Ok(())
        });
        let mut written: std::io::Result<()> = Ok(());
        if let Some(o) = output {
            written = o.out.write_all(&o.format.header(&layout, faces));
            for buffers in full_rx.iter() {
                for b in buffers {
                    if written.is_ok() {
                        written = o.out.write_all(&b);
                    }
                    let _ = empty_tx.send(b);
                }
                if written.is_err() {
                    break;
                }
            }
        }
        drop(full_rx);
        let computed = compute
            .join()
            .unwrap_or_else(|p| std::panic::resume_unwind(p));
        computed?;
        written?;
        Ok(())
    });
    result?;
    // Every edge between two faces was measured exactly once (by the window of its first
    // face), or the report would not be the whole fit's.
    let shared = mesh.edges().filter(|e| e.second.is_some()).count();
    if measured_edges != shared {
        return Err(StreamError::Fit(FitError::Mesh(format!(
            "the streamed G1 measured {measured_edges} of {shared} shared edges"
        ))));
    }
    fit.face_fallbacks = fallbacks;
    Ok(Streamed {
        fit,
        g1: g1.finish(),
        curves_seconds,
        folds,
    })
}

//! Fitting a mesh with the modified Shirman–Séquin scheme: one boundary curve per mesh edge
//! (built once, shared by both faces on it), then one macro-patch of three quartics per face.
//!
//! Both stages are local and run in parallel (rayon) with results collected in mesh order, so
//! the output is deterministic.
//!
//! # One bad face never sinks a mesh
//!
//! * An edge whose boundary-curve problem is degenerate (coincident ends, opposite normals, a
//!   chord along the average normal, a normal along the chord: [`curves::Degeneracy`]) gets the
//!   straight cubic at thirds of the chord, and is listed in [`Fit::degenerate_edges`].
//! * A face whose macro-patch cannot be built (a corner cross vector that does not point into
//!   the patch — folded data, a normal turned against the winding —, a zero end derivative,
//!   non-finite control points), and every face of zero area, gets
//!   [`crate::fallback::fallback_patch`]: C0, on the same boundary curves as its neighbours.
//!   It is listed in [`Fit::face_fallbacks`] with the reason; [`crate::g1::measure`] reports
//!   the edges touching it separately.
//!
//! Only a bad parameter (β or c not positive and finite) and a method needing curvature the
//! mesh lacks stop the whole fit: those are the caller's settings, not the data.

use curves::{BoundaryProblem, CubicBez3, CurveMethod, EdgeError};
use rayon::prelude::*;

use crate::beztri::BezierTriangle;
use crate::fallback::fallback_patch;
use crate::mesh::Mesh;
use crate::shirman_sequin::{macro_patch, InteriorParameters, QuarticNet, SchemeError};

/// Why a face was fitted with the fallback patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FaceFallbackReason {
    /// The face has (relatively) zero area.
    ZeroArea,
    /// The split-domain construction failed.
    Scheme(SchemeError),
    /// The construction gave non-finite control points (extreme data).
    NonFinite,
}

impl std::fmt::Display for FaceFallbackReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FaceFallbackReason::ZeroArea => write!(f, "zero area"),
            FaceFallbackReason::Scheme(e @ SchemeError::NoCrossComponent { .. }) => write!(
                f,
                "{e} (the normals there lean against the face's winding: folded data, inward normals or a needle)"
            ),
            FaceFallbackReason::Scheme(e) => write!(f, "{e}"),
            FaceFallbackReason::NonFinite => write!(f, "non-finite control points"),
        }
    }
}

/// A face fitted with the fallback patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceFallback {
    /// The face index.
    pub face: usize,
    /// Why.
    pub reason: FaceFallbackReason,
}

/// An edge whose boundary-curve problem was degenerate, fitted with the straight cubic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DegenerateEdge {
    /// The mesh edge index.
    pub edge: usize,
    /// What was degenerate (names the edge's vertices).
    pub error: EdgeError,
}

/// Why a mesh could not be fitted.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FitError {
    /// An edge's boundary-curve problem is degenerate (names the edge's vertices).
    #[error("cannot build the boundary curve of {0}")]
    Edge(#[from] EdgeError),
    /// A face's macro-patch could not be built.
    #[error("face {face}: {source}")]
    Face {
        /// The face index.
        face: usize,
        /// What went wrong.
        source: SchemeError,
    },
    /// The curve construction needs per-vertex curvature the mesh does not have.
    #[error("the `{method}` curves need per-vertex curvature, which vertex {vertex} does not have (OBJ input, or a testbed file without `shape`): use `chord`")]
    NeedsCurvature {
        /// The construction's name.
        method: &'static str,
        /// The first vertex without curvature.
        vertex: usize,
    },
    /// A patch came out with non-finite control points (extreme data).
    #[error("face {face}: the patch has non-finite control points")]
    NonFinite {
        /// The face index.
        face: usize,
    },
    /// The mesh structure disagreed with itself (a bug, reported rather than panicking).
    #[error("internal mesh inconsistency: {0}")]
    Mesh(String),
}

/// A fitted surface.
#[derive(Clone, Debug, Default)]
pub struct Fit {
    /// The boundary curve of each mesh edge, in `mesh.edges()` order, running from
    /// `edge.vertices[0]` to `edge.vertices[1]`.
    pub curves: Vec<CubicBez3>,
    /// End-derivative lengths `[α0, α1]` chosen for each edge (unit-chord form).
    pub alphas: Vec<[f64; 2]>,
    /// Edges whose construction fell back to the chord choice (e.g. dBHS without solution).
    pub fallbacks: usize,
    /// Edges whose optimization did not converge (the best point was used).
    pub unconverged: usize,
    /// Edges whose tangent had to be flipped to point along the chord (a normal turned past
    /// 90°), summed over both ends.
    pub flipped_tangents: usize,
    /// Edges whose curve problem was degenerate, fitted with the straight cubic (module docs).
    pub degenerate_edges: Vec<DegenerateEdge>,
    /// Faces fitted with the fallback patch (module docs), in face order.
    pub face_fallbacks: Vec<FaceFallback>,
    /// Three quartic nets per face (the row order of docs/conventions.md): net `3f + e` is sub-patch `e` of face
    /// `f`, over the corners `(V_e, V_{e+1}, S)` of the face. Fixed-size arrays, so a fit of a
    /// million triangles makes no per-patch allocation (about 1.1 kB per triangle).
    pub patches: Vec<QuarticNet>,
}

/// The three edge curves of face `f`, each oriented from the face's corner `l` to `l + 1`
/// (`curves` holds one curve per mesh edge, running along `edge.vertices`).
pub fn face_curves(
    mesh: &Mesh,
    curves: &[CubicBez3],
    f: usize,
) -> Result<[CubicBez3; 3], crate::mesh::MeshError> {
    let face = mesh.face(f)?;
    let mut out = [CubicBez3::new([nalgebra::Point3::origin(); 4]); 3];
    for (l, slot) in out.iter_mut().enumerate() {
        let ei = mesh.edge_index(f, l)?;
        let c = curves[ei];
        *slot = if mesh.edges()[ei].vertices[0] == face[l] {
            c
        } else {
            c.reversed()
        };
    }
    Ok(out)
}

impl Fit {
    /// The edge curves of face `f` oriented along the face (see [`face_curves`]).
    pub fn face_curves(
        &self,
        mesh: &Mesh,
        f: usize,
    ) -> Result<[CubicBez3; 3], crate::mesh::MeshError> {
        face_curves(mesh, &self.curves, f)
    }

    /// Patch `i` (`3f + e`) as a [`BezierTriangle`].
    pub fn patch(&self, i: usize) -> Option<BezierTriangle> {
        self.patches
            .get(i)
            .and_then(|n| BezierTriangle::new(4, n.to_vec()).ok())
    }

    /// For each face, true when it got the fallback patch.
    pub fn fallback_mask(&self, faces: usize) -> Vec<bool> {
        let mut mask = vec![false; faces];
        for fb in &self.face_fallbacks {
            if let Some(m) = mask.get_mut(fb.face) {
                *m = true;
            }
        }
        mask
    }

    /// Every patch as a [`BezierTriangle`], in order (for tessellation and output).
    pub fn bezier_patches(&self) -> Vec<BezierTriangle> {
        (0..self.patches.len())
            .filter_map(|i| self.patch(i))
            .collect()
    }
}

/// Fits every face of `mesh`, with boundary curves from `method` and the interior parameters
/// of face `f` given by `params(f)`.
pub fn fit(
    mesh: &Mesh,
    method: &dyn CurveMethod,
    params: &(dyn Fn(usize) -> InteriorParameters + Sync),
) -> Result<Fit, FitError> {
    let mut out = Fit::default();
    fit_into(mesh, method, params, &mut out)?;
    Ok(out)
}

/// [`fit`] into an existing [`Fit`], reusing its buffers: sweeps that fit many meshes (or one
/// mesh many times) then allocate nothing after the first fit. On error `out` holds partial
/// results and must not be used.
pub fn fit_into(
    mesh: &Mesh,
    method: &dyn CurveMethod,
    params: &(dyn Fn(usize) -> InteriorParameters + Sync),
    out: &mut Fit,
) -> Result<(), FitError> {
    let verts = mesh.vertices();
    if method.name() != "chord" {
        if let Some(v) = verts.iter().position(|v| !v.curvature_known) {
            return Err(FitError::NeedsCurvature {
                method: method.name(),
                vertex: v,
            });
        }
    }
    // Curves, α and per-edge flags are written in place (bit 0: fallback, bit 1: unconverged,
    // bits 2–3: number of flipped tangents), so no intermediate collection is copied.
    let n_edges = mesh.edges().len();
    let Fit {
        curves,
        alphas,
        patches,
        degenerate_edges,
        face_fallbacks,
        ..
    } = &mut *out;
    curves.clear();
    curves.resize(n_edges, CubicBez3::new([nalgebra::Point3::origin(); 4]));
    alphas.clear();
    alphas.resize(n_edges, [0.0; 2]);
    let mut flags = vec![0u8; n_edges];
    let mut edge_errors: Vec<Option<EdgeError>> = vec![None; n_edges];
    curves
        .par_iter_mut()
        .zip(alphas.par_iter_mut())
        .zip(flags.par_iter_mut())
        .zip(edge_errors.par_iter_mut())
        .zip(mesh.edges().par_iter())
        .for_each(|((((curve, alpha), flag), err), e)| {
            let [a, b] = e.vertices;
            match BoundaryProblem::new((a, b), &verts[a].data, &verts[b].data) {
                Ok(p) => {
                    let choice = method.construct(&p.unit);
                    *curve = p.curve(choice.alpha);
                    *alpha = choice.alpha;
                    let unconverged = choice.report.as_ref().is_some_and(|r| !r.converged());
                    let flipped = p.flipped.iter().filter(|f| **f).count() as u8;
                    *flag =
                        u8::from(choice.fallback) | (u8::from(unconverged) << 1) | (flipped << 2);
                }
                Err(error) => {
                    let (pa, pb) = (verts[a].data.p, verts[b].data.p);
                    *curve = CubicBez3::new([
                        pa,
                        pa + (pb - pa) / 3.0,
                        pa + (pb - pa) * (2.0 / 3.0),
                        pb,
                    ]);
                    *alpha = [1.0, 1.0];
                    *flag = 0;
                    *err = Some(error);
                }
            }
        });
    *degenerate_edges = edge_errors
        .into_iter()
        .enumerate()
        .filter_map(|(edge, e)| e.map(|error| DegenerateEdge { edge, error }))
        .collect();

    // Each face writes its three nets straight into the output (no intermediate copies: at a
    // million faces the nets are a gigabyte, and memory traffic dominates the arithmetic).
    patches.clear();
    patches.resize(3 * mesh.num_faces(), [nalgebra::Point3::origin(); 15]);
    let mut reasons: Vec<Option<FaceFallbackReason>> = vec![None; mesh.num_faces()];
    patches
        .par_chunks_mut(3)
        .zip(reasons.par_iter_mut())
        .enumerate()
        .try_for_each(|(f, (out, reason))| -> Result<(), FitError> {
            let face = mesh.face(f).map_err(|e| FitError::Mesh(e.to_string()))?;
            let edges = face_curves(mesh, curves, f).map_err(|e| FitError::Mesh(e.to_string()))?;
            let corners = [
                &verts[face[0]].data,
                &verts[face[1]].data,
                &verts[face[2]].data,
            ];
            let built = if mesh.is_degenerate_face(f) {
                Err(FaceFallbackReason::ZeroArea)
            } else {
                match macro_patch(corners, &edges, &params(f)) {
                    Ok(nets)
                        if nets
                            .iter()
                            .flatten()
                            .all(|p| p.iter().all(|c| c.is_finite())) =>
                    {
                        Ok(nets)
                    }
                    Ok(_) => Err(FaceFallbackReason::NonFinite),
                    Err(source @ SchemeError::BadParameter { .. }) => {
                        return Err(FitError::Face { face: f, source })
                    }
                    Err(e) => Err(FaceFallbackReason::Scheme(e)),
                }
            };
            let nets = built.unwrap_or_else(|why| {
                *reason = Some(why);
                fallback_patch(&edges)
            });
            out.copy_from_slice(&nets);
            Ok(())
        })?;
    *face_fallbacks = reasons
        .into_iter()
        .enumerate()
        .filter_map(|(face, r)| r.map(|reason| FaceFallback { face, reason }))
        .collect();

    out.fallbacks = flags.iter().filter(|f| *f & 1 != 0).count();
    out.unconverged = flags.iter().filter(|f| *f & 2 != 0).count();
    out.flipped_tangents = flags.iter().map(|f| usize::from(f >> 2)).sum();
    Ok(())
}

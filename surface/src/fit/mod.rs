//! Fitting a mesh with a surface scheme ([`crate::scheme`]): one boundary curve per mesh edge
//! (built once, shared by both faces on it; only for schemes with cubic boundaries), then the
//! scheme's patches per face into one flat buffer laid out by the scheme's
//! [`Layout`](crate::scheme::Layout). [`fit`] and [`fit_into`] are the modified Shirman–Séquin
//! scheme with per-face interior parameters; [`fit_scheme`] takes any scheme.
//!
//! Both stages are local and run in parallel (rayon) with results collected in mesh order, so
//! the output is deterministic.
//!
//! # One bad face never sinks a mesh
//!
//! * An edge whose boundary-curve problem is degenerate (coincident ends, opposite normals, a
//!   chord along the average normal, a normal along the chord: [`curves::Degeneracy`]) gets the
//!   straight cubic at thirds of the chord, and is listed in [`Fit::degenerate_edges`].
//! * A face whose patches cannot be built (for Shirman–Séquin: a corner cross vector that does
//!   not point into the patch — folded data, a normal turned against the winding —, a zero end
//!   derivative; for any scheme: non-finite control points), and every face of zero area, gets
//!   the scheme's [`Scheme::fallback`] (Shirman–Séquin: [`crate::fallback::fallback_patch`],
//!   C0 on the same boundary curves as its neighbours).
//!   It is listed in [`Fit::face_fallbacks`] with the reason; [`crate::g1::measure`] reports
//!   the edges touching it separately.
//!
//! Only a bad parameter (β or c not positive and finite) and a method needing curvature the
//! mesh lacks stop the whole fit: those are the caller's settings, not the data.

pub mod fairing;
pub mod fan;
pub mod stream;

use curves::{BoundaryProblem, CubicBez3, CurveMethod, EdgeError};
use rayon::prelude::*;

use crate::beztri::BezierTriangle;
use crate::mesh::Mesh;
use crate::scheme::shirman_sequin::ShirmanSequin;
use crate::scheme::{Continuity, FaceInput, Layout, Scheme, CENTROID_SPLIT};
use crate::shirman_sequin::{InteriorParameters, QuarticNet, SchemeError};

/// Why a face was fitted with the fallback patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FaceFallbackReason {
    /// The face has (relatively) zero area.
    ZeroArea,
    /// The split-domain construction failed.
    Scheme(SchemeError),
    /// The construction gave non-finite control points (extreme data).
    NonFinite,
    /// At corner `corner` the face's two edge tangents turn against the vertex normal: the
    /// face is folded in that vertex's tangent plane (a needle, a pole, a normal turned against
    /// the winding), and a patch through it would fold ([`crate::scheme::folded_corner`]).
    Folded {
        /// The face corner (0, 1, 2).
        corner: usize,
    },
    /// Along face edge `edge` (from corner `edge` to `edge + 1`) the cross-boundary derivative
    /// turns to the wrong side: the patch would fold over the edge
    /// ([`crate::side_vertex::folded_edge`]).
    FoldedEdge {
        /// The face edge (0, 1, 2).
        edge: usize,
    },
}

impl FaceFallbackReason {
    /// A short stable key for counting fallbacks by cause in reports: `zero_area`,
    /// `normal_against_face`, `tangent_off_plane`, `folded_corner`, `folded_edge`,
    /// `no_cross_component`, `folds_over_face`, `zero_end_derivative`, `non_finite`,
    /// `bad_parameter`.
    pub fn kind(&self) -> &'static str {
        match self {
            FaceFallbackReason::ZeroArea => "zero_area",
            FaceFallbackReason::NonFinite => "non_finite",
            FaceFallbackReason::Folded { .. } => "folded_corner",
            FaceFallbackReason::FoldedEdge { .. } => "folded_edge",
            FaceFallbackReason::Scheme(e) => match e {
                SchemeError::BadParameter { .. } => "bad_parameter",
                SchemeError::ZeroEndDerivative { .. } => "zero_end_derivative",
                SchemeError::NormalAgainstFace { .. } => "normal_against_face",
                SchemeError::TangentOffPlane { .. } => "tangent_off_plane",
                SchemeError::FoldsOverFace => "folds_over_face",
                SchemeError::NoCrossComponent { .. } => "no_cross_component",
            },
        }
    }
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
            FaceFallbackReason::Folded { corner } => write!(
                f,
                "folded at corner {corner}: its edge tangents turn against the vertex normal (a needle, a pole or a normal against the winding)"
            ),
            FaceFallbackReason::FoldedEdge { edge } => write!(
                f,
                "folded over edge {edge}: the cross-boundary derivative turns to the wrong side (vertex normals far apart across the edge)"
            ),
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
    /// Interior parameters were to be chosen for a scheme that has none.
    #[error("the `{scheme}` scheme has no interior parameters to choose (only `shirman-sequin` does): drop --interior")]
    NoInteriorParameters {
        /// The scheme's name.
        scheme: &'static str,
    },
    /// The mesh structure disagreed with itself (a bug, reported rather than panicking).
    #[error("internal mesh inconsistency: {0}")]
    Mesh(String),
}

/// A fitted surface.
#[derive(Clone, Debug)]
pub struct Fit {
    /// The scheme's registered name.
    pub scheme: &'static str,
    /// How the patches are laid out per face.
    pub layout: Layout,
    /// What the scheme promises across boundaries.
    pub continuity: Continuity,
    /// The boundary curve of each mesh edge, in `mesh.edges()` order, running from
    /// `edge.vertices[0]` to `edge.vertices[1]`. Empty for schemes that make their own
    /// boundaries ([`Scheme::uses_curves`]).
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
    /// Crease edges ([`Mesh::is_crease`]): their curves run along the crease ([`edge_ends`]).
    pub crease_edges: usize,
    /// Curve ends whose tangent made more than `curves::problem::MAX_TANGENT_ANGLE` with the
    /// chord and was turned to it (the faces there leave the G1 schemes: off the tangent plane).
    pub clamped_tangents: usize,
    /// Curves whose construction's lengths were shortened so the control polygon does not run
    /// back along the chord (`curves::UnitProblem::bounded_alpha`).
    pub shortened_curves: usize,
    /// Crease edges with an end where the crease tangent could not be used (the crease leaves
    /// the edge sideways, or folds flat: [`curves::CreaseEnd`]); the curve there takes the
    /// bisector plane's tangent.
    pub crease_ends_off_line: usize,
    /// What the tangent fans did ([`fan`]): corners failing the corner test before and after,
    /// sectors fanned and left.
    pub fan: fan::FanCounts,
    /// Faces fitted with the fallback patch (module docs), in face order.
    pub face_fallbacks: Vec<FaceFallback>,
    /// The control points of every patch, face after face and within a face patch after patch
    /// ([`Layout::subs`] order), each net in the row order of docs/conventions.md. For
    /// Shirman–Séquin, net `3f + e` is sub-patch `e` of face `f` over `(V_e, V_{e+1}, S)`. One
    /// flat buffer, so a fit of a million triangles makes no per-patch allocation (about
    /// 1.1 kB per triangle for three quartics).
    pub points: Vec<nalgebra::Point3<f64>>,
}

impl Default for Fit {
    /// An empty Shirman–Séquin fit.
    fn default() -> Self {
        Fit {
            scheme: "shirman-sequin",
            layout: Layout::bezier(4, &CENTROID_SPLIT),
            continuity: Continuity::G1,
            curves: Vec::new(),
            alphas: Vec::new(),
            fallbacks: 0,
            unconverged: 0,
            flipped_tangents: 0,
            degenerate_edges: Vec::new(),
            crease_edges: 0,
            clamped_tangents: 0,
            shortened_curves: 0,
            crease_ends_off_line: 0,
            fan: fan::FanCounts::default(),
            face_fallbacks: Vec::new(),
            points: Vec::new(),
        }
    }
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
        *slot = if mesh.edge(ei).vertices[0] == face[l] {
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

    /// Number of patches (faces × patches per face).
    pub fn num_patches(&self) -> usize {
        self.points.len() / self.layout.points_per_patch().max(1)
    }

    /// The control net of patch `i` (patch `s` of face `f` is `i = f · patches_per_face + s`).
    pub fn net(&self, i: usize) -> Option<&[nalgebra::Point3<f64>]> {
        let np = self.layout.points_per_patch();
        self.points.get(i * np..(i + 1) * np)
    }

    /// Every patch's control net, in order.
    pub fn nets(&self) -> std::slice::ChunksExact<'_, nalgebra::Point3<f64>> {
        self.points
            .chunks_exact(self.layout.points_per_patch().max(1))
    }

    /// Patch `i` as a fixed-size quartic net, when the layout is of quartics.
    pub fn quartic_net(&self, i: usize) -> Option<QuarticNet> {
        (self.layout.degree == 4 && self.layout.is_bezier())
            .then(|| self.net(i))
            .flatten()
            .and_then(|n| n.try_into().ok())
    }

    /// Patch `i` as a [`BezierTriangle`].
    /// `None` when the layout's patches are not Bézier nets ([`crate::patch`]).
    pub fn patch(&self, i: usize) -> Option<BezierTriangle> {
        if !self.layout.is_bezier() {
            return None;
        }
        self.net(i)
            .and_then(|n| BezierTriangle::new(self.layout.degree, n.to_vec()).ok())
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
        (0..self.num_patches())
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
    fit_scheme_into(mesh, &ShirmanSequin::per_face(params), method, out)
}

/// Fits every face of `mesh` with `scheme`, its boundary curves (if it uses them) from
/// `method`.
pub fn fit_scheme(
    mesh: &Mesh,
    scheme: &dyn Scheme,
    method: &dyn CurveMethod,
) -> Result<Fit, FitError> {
    let mut out = Fit::default();
    fit_scheme_into(mesh, scheme, method, &mut out)?;
    Ok(out)
}

/// The data a mesh edge's boundary curve is built from ([`edge_ends`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeEnds {
    /// The data at `edge.vertices[0]` and `[1]` for the curve problem: the corner data of the
    /// edge's first face, or at a crease end the bisector data of both sectors
    /// ([`curves::crease_end`]).
    pub data: [curves::VertexData; 2],
    /// The crease tangent the curve takes at each end, where the crease fixes one.
    pub tangents: [Option<nalgebra::Vector3<f64>>; 2],
    /// The edge separates two sectors at an end.
    pub crease: bool,
    /// At a crease end the crease tangent could not be used ([`curves::CreaseEnd`]).
    pub off_line: bool,
    /// The line the boundary leaves each crease end along, for the schemes that make their own
    /// boundaries ([`FaceInput::creases`]): the crease tangent, or the chord where it could not
    /// be used (shared by both faces either way).
    pub lines: [Option<nalgebra::Vector3<f64>>; 2],
}

/// The end data of edge `e`'s boundary curve. On a smooth edge (or a mesh without sectors),
/// both faces see the same data at each end, and that is the data. At an end where the two
/// faces lie in different sectors (a crease), the curve must lie in both tangent planes: it
/// gets the crease's bisector data and tangent ([`curves::crease`]), the same for both faces
/// (the construction is symmetric in the two sectors), so the curve is shared and the surface
/// stays C0 along the crease while each face keeps its own sector's tangent plane.
pub fn edge_ends(mesh: &Mesh, e: usize) -> EdgeEnds {
    let edge = mesh.edge(e);
    let corner = |f: usize, v: usize| mesh.faces()[f].iter().position(|&x| x == v).unwrap_or(0);
    let (f1, _) = edge.first;
    let data_at = |f: usize, v: usize| {
        mesh.corner_data(f, corner(f, v))
            .unwrap_or_else(|| mesh.vertices()[v].data)
    };
    let mut out = EdgeEnds {
        data: edge.vertices.map(|v| data_at(f1, v)),
        tangents: [None, None],
        crease: false,
        off_line: false,
        lines: [None, None],
    };
    let (Some(sectors), Some((f2, _))) = (mesh.sectors(), edge.second) else {
        return out;
    };
    if !sectors.is_crease(e) {
        return out;
    }
    for end in 0..2 {
        let v = edge.vertices[end];
        if sectors.slot(f1, corner(f1, v)) == sectors.slot(f2, corner(f2, v)) {
            continue;
        }
        out.crease = true;
        let other = mesh.vertices()[edge.vertices[1 - end]].data.p;
        let (d, how) = curves::crease_end(&data_at(f1, v), &data_at(f2, v), &other);
        out.data[end] = d;
        out.tangents[end] = how.tangent().map(|t| if end == 0 { t } else { -t });
        out.off_line |= matches!(how, curves::CreaseEnd::Sideways | curves::CreaseEnd::Knife);
        out.lines[end] = how.tangent().or_else(|| (other - d.p).try_normalize(0.0));
    }
    out
}

/// Which edges of patch `sub` of face `f` (patch edges as `crate::patch_g1::PatchEdge`: 0 from
/// the sub-triangle's corner 0 to 1, 1 from 1 to 2, 2 from 2 to 0) lie on a crease edge of the
/// mesh ([`Mesh::is_crease`]): a patch edge lies on face edge `l` when both its ends have
/// barycentric coordinate `λ_{l+2} = 0`. What a patch record marks for the pipeline's G1
/// measure, which sees no mesh.
pub fn patch_crease_edges(mesh: &Mesh, layout: &Layout, f: usize, sub: usize) -> [bool; 3] {
    let mut out = [false; 3];
    let Some(corners) = layout.subs.get(sub) else {
        return out;
    };
    if mesh.sectors().is_none() {
        return out;
    }
    for (k, slot) in out.iter_mut().enumerate() {
        let (a, b) = (corners[k], corners[(k + 1) % 3]);
        *slot = (0..3).any(|l| {
            let opposite = (l + 2) % 3;
            a[opposite] == 0.0
                && b[opposite] == 0.0
                && mesh.edge_index(f, l).is_ok_and(|e| mesh.is_crease(e))
        });
    }
    out
}

/// [`FaceInput::creases`] of face `f`: the crease tangents of its edges, oriented along the
/// face ([`edge_ends`]).
fn face_creases(mesh: &Mesh, f: usize) -> [[Option<nalgebra::Vector3<f64>>; 2]; 3] {
    let mut out = crate::scheme::NO_CREASES;
    if mesh.sectors().is_none() {
        return out;
    }
    let face = mesh.faces()[f];
    for (l, slot) in out.iter_mut().enumerate() {
        let Ok(ei) = mesh.edge_index(f, l) else {
            continue;
        };
        if !mesh.is_crease(ei) {
            continue;
        }
        let t = edge_ends(mesh, ei).lines;
        *slot = if mesh.edge(ei).vertices[0] == face[l] {
            t
        } else {
            [t[1], t[0]]
        };
    }
    out
}

/// The straight cubic at thirds from `a` to `b`.
fn straight(a: nalgebra::Point3<f64>, b: nalgebra::Point3<f64>) -> CubicBez3 {
    CubicBez3::new([a, a + (b - a) / 3.0, a + (b - a) * (2.0 / 3.0), b])
}

/// [`fit_scheme`] into an existing [`Fit`], reusing its buffers (see [`fit_into`]).
pub fn fit_scheme_into(
    mesh: &Mesh,
    scheme: &dyn Scheme,
    method: &dyn CurveMethod,
    out: &mut Fit,
) -> Result<(), FitError> {
    fit_curves_into(mesh, scheme, method, out)?;
    // Each face writes its patches straight into the output (no intermediate copies: at a
    // million faces the nets are a gigabyte, and memory traffic dominates the arithmetic).
    let per_face = out.layout.points_per_face();
    let Fit {
        curves,
        points,
        face_fallbacks,
        ..
    } = &mut *out;
    // Filled by both threads: a fresh gigabyte at 10⁶ faces is first touched (page faults)
    // in parallel rather than by one thread before the parallel build.
    points.clear();
    points.par_extend(rayon::iter::repeat_n(
        nalgebra::Point3::origin(),
        per_face * mesh.num_faces(),
    ));
    let mut reasons: Vec<Option<FaceFallbackReason>> = vec![None; mesh.num_faces()];
    let curves: &[CubicBez3] = curves;
    points
        .par_chunks_mut(per_face.max(1))
        .zip(reasons.par_iter_mut())
        .enumerate()
        .try_for_each(|(f, (out, reason))| -> Result<(), FitError> {
            *reason = build_face(mesh, scheme, curves, f, out)?;
            Ok(())
        })?;
    *face_fallbacks = reasons
        .into_iter()
        .enumerate()
        .filter_map(|(face, r)| r.map(|reason| FaceFallback { face, reason }))
        .collect();
    Ok(())
}

/// The first stage of [`fit_scheme_into`]: everything but the patches. Sets `out`'s scheme,
/// layout and continuity, builds one boundary curve per mesh edge (when the scheme uses
/// curves) with its α, and counts the fallbacks, unconverged optimizations, flipped tangents
/// and degenerate edges; leaves `out.points` and `out.face_fallbacks` empty. The patches of
/// face `f` then come from [`build_face`] with `out.curves`, alone: a face's patches depend
/// only on its own corners' vertex data, its three edge curves and the scheme (its interior
/// rule), never on another face's patches, so they can be built in any order, or again
/// ([`crate::stream`]).
pub fn fit_curves_into(
    mesh: &Mesh,
    scheme: &dyn Scheme,
    method: &dyn CurveMethod,
    out: &mut Fit,
) -> Result<(), FitError> {
    let uses_curves = scheme.uses_curves();
    if uses_curves && method.needs_curvature() {
        if let Some(v) = mesh.vertices().iter().position(|v| !v.curvature_known) {
            return Err(FitError::NeedsCurvature {
                method: method.name(),
                vertex: v,
            });
        }
    }
    out.scheme = scheme.name();
    out.layout = scheme.layout();
    out.continuity = scheme.continuity();
    // Curves, α and per-edge flags are written in place (bit 0: fallback, bit 1: unconverged,
    // bits 2–3: number of flipped tangents, 4: crease, 5: a crease end off the crease line,
    // 6–7: number of clamped tangents, 8: lengths shortened), so no intermediate collection is
    // copied.
    let n_edges = if uses_curves { mesh.num_edges() } else { 0 };
    let Fit {
        curves,
        alphas,
        points,
        degenerate_edges,
        face_fallbacks,
        fan: fan_counts,
        ..
    } = &mut *out;
    points.clear();
    face_fallbacks.clear();
    curves.clear();
    curves.resize(n_edges, CubicBez3::new([nalgebra::Point3::origin(); 4]));
    alphas.clear();
    alphas.resize(n_edges, [0.0; 2]);
    let mut flags = vec![0u16; n_edges];
    let mut edge_errors: Vec<Option<EdgeError>> = vec![None; n_edges];
    curves
        .par_iter_mut()
        .zip(alphas.par_iter_mut())
        .zip(flags.par_iter_mut())
        .zip(edge_errors.par_iter_mut())
        .zip(mesh.par_edges().enumerate())
        .for_each(|((((curve, alpha), flag), err), (ei, e))| {
            let [a, b] = e.vertices;
            let ends = edge_ends(mesh, ei);
            match BoundaryProblem::new((a, b), &ends.data[0], &ends.data[1]) {
                Ok(p) => {
                    // The construction's world cubic (planar via α for most, built in space by
                    // the projection rules), its lengths shortened where the control polygon
                    // would run back along the chord (`UnitProblem::bounded_alpha`), its ends
                    // turned to the crease lines.
                    let built = method.space_curve(&p, ends.tangents);
                    let (choice, shortened) = (&built.choice, built.shortened);
                    *curve = built.curve;
                    *alpha = built.alpha;
                    let unconverged = choice.report.as_ref().is_some_and(|r| !r.converged());
                    let flipped = p.flipped.iter().filter(|f| **f).count() as u16;
                    let clamped = built.clamped.iter().filter(|f| **f).count() as u16;
                    *flag = u16::from(choice.fallback)
                        | (u16::from(unconverged) << 1)
                        | (flipped << 2)
                        | (u16::from(ends.crease) << 4)
                        | (u16::from(ends.off_line) << 5)
                        | (clamped << 6)
                        | (u16::from(shortened) << 8);
                }
                Err(error) => {
                    *curve = straight(ends.data[0].p, ends.data[1].p);
                    *alpha = [1.0, 1.0];
                    *flag = 0;
                    *err = Some(error);
                }
            }
        });
    // The tangent fans (`fan`): sectors whose per-edge tangents leave a corner that is not
    // convex get their tangents chosen together; the rest stay bit for bit.
    *fan_counts = if !uses_curves {
        fan::FanCounts::default()
    } else if method.keeps_own_tangents() {
        fan::count_failing(mesh, curves)
    } else {
        fan::apply_fans(mesh, curves, alphas)
    };
    *degenerate_edges = edge_errors
        .into_iter()
        .enumerate()
        .filter_map(|(edge, e)| e.map(|error| DegenerateEdge { edge, error }))
        .collect();
    out.fallbacks = flags.iter().filter(|f| *f & 1 != 0).count();
    out.unconverged = flags.iter().filter(|f| *f & 2 != 0).count();
    out.flipped_tangents = flags.iter().map(|f| usize::from((f >> 2) & 3)).sum();
    out.crease_edges = flags.iter().filter(|f| *f & 16 != 0).count();
    out.crease_ends_off_line = flags.iter().filter(|f| *f & 32 != 0).count();
    out.clamped_tangents = flags.iter().map(|f| usize::from((f >> 6) & 3)).sum();
    out.shortened_curves = flags.iter().filter(|f| *f & 256 != 0).count();
    Ok(())
}

/// Builds the patches of face `f` into `out` (`scheme.layout().points_per_face()` points) from
/// the mesh's vertex data and `curves` (one per mesh edge, as [`fit_curves_into`] leaves them in
/// [`Fit::curves`]; empty for a scheme that does not use curves: then the face's straight
/// cubics). Returns why the face got the scheme's fallback patch, if it did; errors only for a
/// bad parameter (which stops a whole fit) or an inconsistent mesh. The same inputs give the
/// same bits, whichever thread and whenever.
pub fn build_face(
    mesh: &Mesh,
    scheme: &dyn Scheme,
    curves: &[CubicBez3],
    f: usize,
    out: &mut [nalgebra::Point3<f64>],
) -> Result<Option<FaceFallbackReason>, FitError> {
    let missing = || FitError::Mesh(format!("face {f} does not exist"));
    let data = [
        mesh.corner_data(f, 0).ok_or_else(missing)?,
        mesh.corner_data(f, 1).ok_or_else(missing)?,
        mesh.corner_data(f, 2).ok_or_else(missing)?,
    ];
    let edges = if scheme.uses_curves() {
        face_curves(mesh, curves, f).map_err(|e| FitError::Mesh(e.to_string()))?
    } else {
        std::array::from_fn(|l| straight(data[l].p, data[(l + 1) % 3].p))
    };
    let input = FaceInput {
        face: f,
        vertices: [&data[0], &data[1], &data[2]],
        edges: &edges,
        // The schemes that make their own boundaries project onto the crease lines; the
        // others have them in their (shared) edge curves already, and Shirman–Séquin reads
        // which corners lie between two creases.
        creases: face_creases(mesh, f),
    };
    let built = if mesh.is_degenerate_face(f) {
        Err(FaceFallbackReason::ZeroArea)
    } else {
        match scheme.build(&input, out) {
            Ok(()) if out.iter().all(|p| p.iter().all(|c| c.is_finite())) => Ok(()),
            Ok(()) => Err(FaceFallbackReason::NonFinite),
            Err(FaceFallbackReason::Scheme(source @ SchemeError::BadParameter { .. })) => {
                return Err(FitError::Face { face: f, source })
            }
            Err(e) => Err(e),
        }
    };
    Ok(match built {
        Ok(()) => None,
        Err(why) => {
            scheme.fallback(&input, out);
            Some(why)
        }
    })
}

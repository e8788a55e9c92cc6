//! Sharp features measured on a fit: kinks the fitted surface has across smooth data, data
//! creases it keeps or rounds off, and how flat it stays over the data's flat regions.
//!
//! Everything here is measured from the mesh geometry and the written patches alone, through
//! the layout ([`crate::patch`], [`crate::g1`]'s sample plan), for any scheme and however the
//! fit was built; nothing depends on a crease detection ([`mesh::features`]) or on the vertex
//! normals the fit was given.
//!
//! # Definitions
//!
//! * **Data normal** of face `f`: `N_f = (p₁ − p₀) × (p₂ − p₀) / |…|`; a face of zero area
//!   ([`Mesh::is_degenerate_face`]) has none.
//! * **Data dihedral** of an interior edge between faces `f` and `g`:
//!   `θ_e = atan2(|N_f × N_g|, N_f · N_g)` ∈ [0, π] (the atan2 form is accurate near 0, where
//!   `acos` loses half the digits). An interior edge beside a face without a normal has none and
//!   is counted in [`SharpReport::undefined_dihedrals`]; a boundary edge has none and is not
//!   counted at all.
//! * **Fitted angle** across the edge at parameter `t` (from the edge's first vertex as face
//!   `f` runs it): `φ_e(t) = atan2(|n_f × n_g|, n_f · n_g)` with `n_f`, `n_g` the unit normals
//!   `r_u × r_v / |r_u × r_v|` of the patches of `f` and of `g` that own the edge point (both
//!   oriented like their faces, docs/conventions.md), at the [`EDGE_SAMPLES`] points
//!   `t = k/(EDGE_SAMPLES − 1)`, ends included: the samples of [`crate::g1::measure`] at the
//!   job's default count. Face `g` runs the edge the other way, so `f`'s sample `k` meets `g`'s
//!   sample `EDGE_SAMPLES − 1 − k`. A sample where either patch is singular (`r_u × r_v` zero or
//!   not finite) has no fitted angle: it is counted, never used.
//!
//! # 1. Kinks on smooth edges
//!
//! An interior edge is **smooth** when `θ_e < `[`SMOOTH_DIHEDRAL_DEG`]. Its **kink** is
//! `max_k φ_e(t_k)`; it is **kinked** when the kink exceeds [`KINK_TOLERANCE`] and **severely**
//! kinked over [`SEVERE_KINK`]. A G1 fit has no kinks (its normal jumps are rounding); a C0
//! fit has kinks of about the data's dihedral angles (the `flat` scheme's are exactly `θ_e`).
//!
//! # 2. Creases kept
//!
//! An interior edge is a **crease candidate** when `θ_e > `[`CREASE_CANDIDATE_DEG`] (the
//! threshold of [`mesh::features::DEFAULT_CREASE_ANGLE_DEG`], so the two agree on what a
//! crease is, though neither reads the other). It is **kept** when at each of the probes
//! `t ∈ {¼, ½, ¾}` ([`CREASE_PROBES`]) `φ_e(t) ≥ `[`CREASE_KEPT_FRACTION`]` · θ_e`.
//!
//! Why these probes and this fraction. A surface that keeps the crease turns by about the
//! data's angle all along the edge (exactly `θ_e` for the `flat` scheme; for curved patches
//! by `θ_e` plus the small turn of the patches' normals away from the face planes). A surface
//! that rounds it off is tangent-plane continuous there: `φ_e(t) ≈ 0` at every point inside the
//! edge. The edge's ends are not probed: a scheme given one normal per vertex interpolates that
//! normal on both sides, so `φ_e(0) = φ_e(1) = 0` even for a fit that creases the edge's
//! inside. Probing the quarter points as well as the midpoint asks for the crease along the
//! middle half of the edge: one kept only around the midpoint is not kept. Half of `θ_e` lies
//! midway between the two outcomes, so the rule is decided by which of them the surface is
//! near, not by the patches' curvature. A probe with no fitted angle (a singular patch) leaves
//! the crease not kept and is counted.
//!
//! # 3. Flat regions
//!
//! Two faces are **flat neighbours** across an interior edge with `θ_e ≤ `[`FLAT_DIHEDRAL`]; a
//! **candidate region** is a maximal set of at least two faces connected by flat neighbours
//! (union–find over the edges). Its plane passes through the area-weighted centroid
//! `c = Σ A_f c_f / Σ A_f` (`c_f` the face centroid, `A_f` its area) with the area-weighted
//! mean normal `n = Σ A_f N_f / |Σ A_f N_f|` (the sum of the faces' area vectors, normalized).
//! The region's **data flatness** is `max |(p − c) · n|` over its vertices `p`; a chain of
//! sub-threshold folds can bend (a cylinder of huge radius), so the region is **counted** only
//! when its data flatness is at most [`DATA_FLATNESS`]` · D`, `D` the diagonal of the mesh's
//! bounding box ([`Mesh::size`]); the others are reported as rejected.
//!
//! The fit's **flat deviation** is `max |(P − c) · n| / D` over every patch sample `P` of every
//! face of a counted region, `c` and `n` its region's: on each patch of the face the points
//! `(i/s, j/s)`, `i + j ≤ s`, `s = `[`FLAT_SEGMENTS`], of its local domain, and the
//! [`EDGE_SAMPLES`] points of each face edge. A fit that reproduces planes has a flat deviation
//! of rounding size; one that bulges over a planar face (the vertex normals at its rim leaning
//! over the crease) shows the bulge.
//!
//! Only **planar faces** are held to that: a counted region meets every neighbouring face
//! across a crease candidate (`θ_e > `[`CREASE_CANDIDATE_DEG`]) or the mesh boundary. A flat
//! region that meets a neighbour across a gentler edge (a tessellated cylinder's facet, two
//! coplanar triangles of a quad; a plane blending tangentially into a fillet) is reported as
//! *blended* and not measured: a smooth interpolant rightly curves there.
//!
//! # Cost and determinism
//!
//! Face normals, edges and the flat deviation are computed in parallel (rayon) and merged in
//! mesh order with ties resolved towards the smaller index, so the report is the one a
//! sequential scan gives, bit for bit; the union–find and the regions' sums run sequentially
//! in face order. The work is linear in the faces: a fixed number of patch evaluations per edge
//! and per face, and a union–find with path halving and union by smaller index.

use mesh::features::angle;
use nalgebra::{Point3, Vector3};
use rayon::prelude::*;
use serde::Serialize;

use crate::fit::Fit;
use crate::g1::Plan;
use crate::mesh::Mesh;
use crate::patch::{eval, local_in, prepare, Prepared};
use crate::scheme::{Bary, Layout};

/// Data dihedral angle (degrees) below which an interior edge is smooth. The committed scans'
/// median edge turns by 7–12° ([`mesh::features::DEFAULT_CREASE_ANGLE_DEG`]'s doc; 3 339 of
/// the bunny's 5 511 interior edges are below 10°): 10° keeps the bulk of a smooth surface's
/// edges and leaves out the bends a fit may rightly turn sharply at.
pub const SMOOTH_DIHEDRAL_DEG: f64 = 10.0;

/// Fitted angle (radians) above which a smooth edge is kinked: above the G1 schemes' measured
/// normal jumps (below 1e-9 rad on the data sets, 4.6e-8 rad at worst on the committed real
/// meshes, docs/results.md), far below the jumps of a C0 fit (the data's dihedral angles,
/// degrees).
pub const KINK_TOLERANCE: f64 = 1e-7;

/// Kink (radians, about 20°) above which it is severe: twice the largest data dihedral a
/// smooth edge has, so the fit turns there more sharply than any smooth edge of the data does —
/// a crease made where the data has none.
pub const SEVERE_KINK: f64 = 0.35;

/// Data dihedral angle (degrees) above which an interior edge is a crease candidate: the
/// crease threshold of [`mesh::features::DEFAULT_CREASE_ANGLE_DEG`] (every edge of a box, a
/// chamfer, a hexagonal prism).
pub const CREASE_CANDIDATE_DEG: f64 = 40.0;

/// The fraction of the data dihedral the fitted angle must reach at every probe for a crease
/// to be kept: midway between a kept crease (`φ ≈ θ`) and a rounded one (`φ ≈ 0`; module docs).
pub const CREASE_KEPT_FRACTION: f64 = 0.5;

/// Where a crease is probed along its edge: the midpoint and the quarter points (module docs:
/// the ends are interpolated vertex normals and say nothing).
pub const CREASE_PROBES: [f64; 3] = [0.25, 0.5, 0.75];

/// Data dihedral angle (radians) up to which two faces are flat neighbours.
///
/// Coplanar faces whose vertices are rounded to double precision have normals that differ by
/// rounding only: a vertex off its plane by `δ ≤ 2⁻⁵³ L` (`L` the size of the coordinates,
/// about the bounding-box diagonal in the working frame) tilts a face of altitude `h` by about
/// `δ/h`, and the cross product's own rounding adds about `2⁻⁵³ L/h`, so two coplanar
/// neighbours differ by up to about `6 · 2⁻⁵³ · L/h ≈ 7e-16 · L/h` (measured on a tilted plane
/// with a column of slivers: 1.0e-12 at `h = 1e-4 L`, 2.0e-11 at `1e-5 L`, 9.0e-11 at `1e-6 L`,
/// below the bound). `1e-10` admits faces down to an altitude of about `1e-6 L` (the slivers of
/// a fine CAD tessellation), where `1e-12` would cut a planar face's mesh into pieces at faces
/// thinner than about `1e-4 L`. Any curved surface is far above it: a cylinder cut into `N`
/// segments turns by `2π/N` an edge, more than `1e-10` for every `N` below 6·10¹⁰, and a fillet
/// tangent to a plane turns at the tangency by its first segment's angle, orders of magnitude
/// more for any practical tessellation. Faces that fold by less than this without lying on one
/// plane are caught by [`DATA_FLATNESS`]; the price of the larger angle is that a face whose
/// vertex is off the plane by between `1e-14` and `1e-10` of its size joins the region and gets
/// it rejected, where a smaller angle would have left that face out.
pub const FLAT_DIHEDRAL: f64 = 1e-10;

/// Data flatness (relative to the bounding-box diagonal) up to which a candidate region is
/// counted. Vertices of a plane stored in double precision lie on it to half an ulp of their
/// coordinates, at most `√3 · 2⁻⁵³ · D ≈ 2e-16 · D` in the working frame (centred, coordinates
/// at most `D`), and `|(p − c) · n|` is computed to a few ulps more: 1e-14 leaves a factor of
/// fifty. A region whose vertices leave its plane by more is not flat data, whatever its
/// dihedral angles: a slow bend, or single-precision coordinates of a tilted plane (off by
/// `2⁻²⁴ · D ≈ 6e-8 · D`; axis-aligned planes stay exact in any precision).
pub const DATA_FLATNESS: f64 = 1e-14;

/// Points at which the fitted angle is sampled along an edge, ends included: the fit job's
/// default G1 samples (`t = k/8`), which contain the crease probes ¼, ½, ¾ exactly.
pub const EDGE_SAMPLES: usize = 9;

/// Segments of a patch edge in the grid of samples for the flat deviation: 15 samples a patch,
/// as the fold test ([`crate::folds::FOLD_SEGMENTS`]), enough to see a bulge that spans a
/// quarter of a patch.
pub const FLAT_SEGMENTS: usize = 4;

// The probes must be samples: `t = k/(EDGE_SAMPLES − 1)` at quarters.
const _: () = assert!((EDGE_SAMPLES - 1) % 4 == 0);

/// A fitted angle across one edge, with the data's.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct EdgeAngle {
    /// The mesh edge index.
    pub edge: usize,
    /// Its vertices, as [`mesh::Edge::vertices`].
    pub vertices: [usize; 2],
    /// The data dihedral angle `θ_e`, radians.
    pub dihedral: f64,
    /// The fitted angle, radians: the largest over the samples (a kink) or the smallest over
    /// the probes (a crease).
    pub fitted: f64,
}

/// Smooth edges and their kinks (module docs, 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct SmoothEdges {
    /// Interior edges with `θ_e < SMOOTH_DIHEDRAL_DEG`.
    pub edges: usize,
    /// Those whose kink exceeds [`KINK_TOLERANCE`].
    pub kinked: usize,
    /// Those whose kink exceeds [`SEVERE_KINK`].
    pub severe: usize,
    /// Kinked edges with a fallback face on either side ([`Fit::face_fallbacks`]: C0 by
    /// construction), a part of `kinked`.
    pub kinked_at_fallback: usize,
    /// The largest kink and its edge (the smallest edge index among equal ones; `None` when no
    /// smooth edge has a sample with both normals).
    pub worst: Option<EdgeAngle>,
    /// Samples with a singular patch on either side, skipped.
    pub undefined_normals: usize,
}

/// Crease candidates and how many the fit keeps (module docs, 2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Creases {
    /// Interior edges with `θ_e > CREASE_CANDIDATE_DEG`.
    pub candidates: usize,
    /// Those kept: `φ_e(t) ≥ CREASE_KEPT_FRACTION · θ_e` at every probe.
    pub kept: usize,
    /// Kept creases with a fallback face on either side ([`Fit::face_fallbacks`]: C0 by
    /// construction, so kept whether or not the scheme meant to), a part of `kept`.
    pub kept_at_fallback: usize,
    /// The candidate whose smallest probe angle is the smallest fraction of its dihedral, with
    /// that angle (`None` without a candidate measured at every probe).
    pub weakest: Option<EdgeAngle>,
    /// Probes with a singular patch on either side (the candidate is then not kept).
    pub undefined_normals: usize,
}

/// Flat regions of the data and the fit's distance from them (module docs, 3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct FlatRegions {
    /// Counted regions (flat data, at least two faces).
    pub regions: usize,
    /// Faces in them.
    pub faces: usize,
    /// Candidate regions not counted: their vertices leave their plane by more than
    /// [`DATA_FLATNESS`].
    pub rejected_regions: usize,
    /// Faces in those.
    pub rejected_faces: usize,
    /// Faces of the largest counted region (two for the coplanar pair of a quad split in two).
    pub largest_region: usize,
    /// The largest data flatness of a counted region, relative to the bounding-box diagonal.
    pub data_flatness: f64,
    /// The smallest data flatness of a rejected region, relative to the bounding-box diagonal
    /// (how near the nearest miss came to [`DATA_FLATNESS`]; `None` without one).
    pub closest_rejected: Option<f64>,
    /// Flat regions with flat data not counted because they meet a neighbour across an edge
    /// of at most [`CREASE_CANDIDATE_DEG`]: a facet of a tessellated cylinder (two coplanar
    /// triangles of a quad), a plane blending into a fillet. A smooth interpolant rightly
    /// curves there; only planar faces bounded by creases (or the mesh boundary) must stay flat.
    pub blended_regions: usize,
    /// Faces in those.
    pub blended_faces: usize,
    /// The largest distance of a patch sample from its region's plane, relative to the
    /// bounding-box diagonal.
    pub deviation: f64,
    /// The face where it occurred (the smallest index among equal ones).
    pub worst_face: Option<usize>,
    /// Samples whose position is not finite (counted, not measured).
    pub nonfinite_samples: usize,
}

/// What [`measure`] found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct SharpReport {
    /// Interior edges (two faces).
    pub interior_edges: usize,
    /// Interior edges beside a face of zero area: no data dihedral, in no class.
    pub undefined_dihedrals: usize,
    /// Kinks on smooth edges.
    pub smooth: SmoothEdges,
    /// Creases kept.
    pub creases: Creases,
    /// Flat regions.
    pub flat: FlatRegions,
}

/// Why a fit cannot be measured against a mesh.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SharpError {
    /// The fit holds a different number of faces' patches than the mesh has faces.
    #[error(
        "the fit holds {fit_points} control points ({points_per_face} a face) for a mesh of \
         {mesh_faces} faces: {}",
        match first_missing {
            Some(f) => format!("face {f} has no patches"),
            None => "it is the fit of a larger mesh".to_string(),
        }
    )]
    WrongSize {
        /// Faces of the mesh.
        mesh_faces: usize,
        /// Points in the fit.
        fit_points: usize,
        /// Points a face of the fit's layout.
        points_per_face: usize,
        /// The first face of the mesh without a full set of patches (`None`: the fit has more).
        first_missing: Option<usize>,
    },
    /// The fit's layout has no patches, or does not cover its face: a face-edge point lies in
    /// no sub-triangle.
    #[error(
        "the fit's layout ({patches} patches a face) leaves points of the face's edges uncovered"
    )]
    Layout {
        /// Patches a face of the layout.
        patches: usize,
    },
}

/// The unit normal of face `f`; `None` for a face of zero area.
fn data_normal(mesh: &Mesh, f: usize) -> Option<Vector3<f64>> {
    if mesh.is_degenerate_face(f) {
        return None;
    }
    mesh.face_unit_normal(f)
}

/// What the edge scan gathers; merged in edge order.
#[derive(Clone, Copy, Debug, Default)]
struct EdgeScan {
    interior: usize,
    undefined: usize,
    smooth: SmoothEdges,
    creases: Creases,
    /// The weakest crease's `φ/θ` (compared exactly, not recomputed from the rounded pair).
    weakest_ratio: f64,
}

impl EdgeScan {
    /// `self` then `later`: counts add; a later maximum (minimum) replaces only a strictly
    /// larger (smaller) one, so among equals the smaller edge stays.
    fn merge(mut self, later: EdgeScan) -> EdgeScan {
        self.interior += later.interior;
        self.undefined += later.undefined;
        let (s, l) = (&mut self.smooth, later.smooth);
        s.edges += l.edges;
        s.kinked += l.kinked;
        s.severe += l.severe;
        s.kinked_at_fallback += l.kinked_at_fallback;
        s.undefined_normals += l.undefined_normals;
        if let Some(w) = l.worst {
            if s.worst.is_none_or(|m| w.fitted > m.fitted) {
                s.worst = Some(w);
            }
        }
        let (c, l) = (&mut self.creases, later.creases);
        c.candidates += l.candidates;
        c.kept += l.kept;
        c.kept_at_fallback += l.kept_at_fallback;
        c.undefined_normals += l.undefined_normals;
        if l.weakest.is_some() && (c.weakest.is_none() || later.weakest_ratio < self.weakest_ratio)
        {
            c.weakest = l.weakest;
            self.weakest_ratio = later.weakest_ratio;
        }
        self
    }
}

/// Everything about the layout that does not depend on a face.
struct Samples {
    /// The G1 measure's plan: tangents at `EDGE_SAMPLES` points of each face edge.
    edges: Plan,
    /// The flat deviation's samples of one face: (patch of the face, prepared local point).
    flat: Vec<(usize, Prepared)>,
}

impl Samples {
    fn new(layout: &Layout) -> Option<Samples> {
        let edges = Plan::new(layout, EDGE_SAMPLES)?;
        let s = FLAT_SEGMENTS;
        let mut flat = Vec::new();
        for patch in 0..layout.patches_per_face() {
            for i in 0..=s {
                for j in 0..=s - i {
                    let (u, v) = (i as f64 / s as f64, j as f64 / s as f64);
                    flat.push((patch, prepare(layout, [u, v, 1.0 - u - v])));
                }
            }
        }
        let corner = |i: usize| -> Bary { std::array::from_fn(|c| f64::from(u8::from(c == i))) };
        for l in 0..3 {
            let (a, b) = (corner(l), corner((l + 1) % 3));
            for k in 0..EDGE_SAMPLES {
                let t = k as f64 / (EDGE_SAMPLES - 1) as f64;
                let x: Bary = std::array::from_fn(|c| a[c] * (1.0 - t) + b[c] * t);
                let (patch, local) = layout.subs.iter().enumerate().find_map(|(p, sub)| {
                    let l = local_in(sub, x)?;
                    l.iter().all(|c| *c >= -INSIDE).then_some((p, l))
                })?;
                flat.push((patch, prepare(layout, local)));
            }
        }
        Some(Samples { edges, flat })
    }

    /// The fitted angle at sample `k` of face `f`'s local edge `lf` (points `pf`), against
    /// face `g`'s local edge `lg` (points `pg`), which runs the other way.
    fn angle_across(
        &self,
        (pf, lf): (&[Point3<f64>], usize),
        (pg, lg): (&[Point3<f64>], usize),
        k: usize,
    ) -> Option<f64> {
        let np = self.edges.np;
        let (rf, rg) = (self.edges.exterior.get(lf)?, self.edges.exterior.get(lg)?);
        let n = rf.len().min(rg.len());
        let a = rf.get(k)?.1.normal(pf, np)?;
        let b = rg.get(n.checked_sub(k + 1)?)?.1.normal(pg, np)?;
        Some(angle(&a, &b))
    }
}

/// Tolerance on a local barycentric coordinate for "inside the sub-triangle" (the rounding of
/// the inverse of a sub-triangle matrix with entries in sixths, as [`crate::patch`]'s).
const INSIDE: f64 = 1e-12;

/// The largest angle between the two patches' normals across interior mesh edge `e` over the
/// measure's samples (what [`measure`] takes as a smooth edge's kink); `None` for a boundary
/// edge, an edge that does not exist, a fit that does not match the mesh, or an edge with no
/// sample where both normals are defined.
pub fn edge_kink(mesh: &Mesh, fit: &Fit, e: usize) -> Option<f64> {
    let layout = &fit.layout;
    let per_face = layout.points_per_face();
    if per_face == 0 || fit.points.len() != per_face * mesh.num_faces() || e >= mesh.num_edges() {
        return None;
    }
    let samples = Samples::new(layout)?;
    let edge = mesh.edge(e);
    let (f, lf) = edge.first;
    let (g, lg) = edge.second?;
    let points = |f: usize| &fit.points[f * per_face..(f + 1) * per_face];
    (0..EDGE_SAMPLES)
        .filter_map(|k| samples.angle_across((points(f), lf), (points(g), lg), k))
        .reduce(f64::max)
}

/// Measures the sharp features of `fit` against `mesh` (module docs). Errors when the fit does
/// not hold one face's patches for every face of the mesh, or its layout leaves a face edge
/// uncovered.
pub fn measure(mesh: &Mesh, fit: &Fit) -> Result<SharpReport, SharpError> {
    let layout = &fit.layout;
    let per_face = layout.points_per_face();
    let nf = mesh.num_faces();
    let bad_layout = SharpError::Layout {
        patches: layout.patches_per_face(),
    };
    if per_face == 0 {
        return Err(bad_layout);
    }
    if fit.points.len() != per_face * nf {
        return Err(SharpError::WrongSize {
            mesh_faces: nf,
            fit_points: fit.points.len(),
            points_per_face: per_face,
            first_missing: (fit.points.len() < per_face * nf)
                .then_some(fit.points.len() / per_face),
        });
    }
    let samples = Samples::new(layout).ok_or(bad_layout)?;
    let points = |f: usize| &fit.points[f * per_face..(f + 1) * per_face];
    let normals: Vec<Option<Vector3<f64>>> = (0..nf)
        .into_par_iter()
        .map(|f| data_normal(mesh, f))
        .collect();
    let dihedral = |e: &mesh::Edge| -> Option<f64> {
        let (g, _) = e.second?;
        Some(angle(&normals[e.first.0]?, &normals[g]?))
    };
    let fallback = fit.fallback_mask(nf);

    let smooth_below = SMOOTH_DIHEDRAL_DEG.to_radians();
    let crease_above = CREASE_CANDIDATE_DEG.to_radians();
    let probes = CREASE_PROBES.map(|t| (t * (EDGE_SAMPLES - 1) as f64).round() as usize);
    let scan = mesh
        .par_edges()
        .enumerate()
        .fold(EdgeScan::default, |mut s, (ei, e)| {
            let Some((g, lg)) = e.second else {
                return s;
            };
            s.interior += 1;
            let Some(theta) = dihedral(&e) else {
                s.undefined += 1;
                return s;
            };
            let (f, lf) = e.first;
            let (sf, sg) = ((points(f), lf), (points(g), lg));
            let at = |fitted| EdgeAngle {
                edge: ei,
                vertices: e.vertices,
                dihedral: theta,
                fitted,
            };
            if theta < smooth_below {
                s.smooth.edges += 1;
                let mut kink: Option<f64> = None;
                for k in 0..EDGE_SAMPLES {
                    match samples.angle_across(sf, sg, k) {
                        Some(phi) => kink = Some(kink.map_or(phi, |m| m.max(phi))),
                        None => s.smooth.undefined_normals += 1,
                    }
                }
                if let Some(kink) = kink {
                    if kink > KINK_TOLERANCE {
                        s.smooth.kinked += 1;
                        s.smooth.kinked_at_fallback += usize::from(fallback[f] || fallback[g]);
                    }
                    s.smooth.severe += usize::from(kink > SEVERE_KINK);
                    if s.smooth.worst.is_none_or(|w| kink > w.fitted) {
                        s.smooth.worst = Some(at(kink));
                    }
                }
            } else if theta > crease_above {
                s.creases.candidates += 1;
                let mut weakest = Some(f64::INFINITY);
                for &k in &probes {
                    match samples.angle_across(sf, sg, k) {
                        Some(phi) => weakest = weakest.map(|w| w.min(phi)),
                        None => {
                            s.creases.undefined_normals += 1;
                            weakest = None;
                        }
                    }
                }
                if let Some(phi) = weakest {
                    if phi >= CREASE_KEPT_FRACTION * theta {
                        s.creases.kept += 1;
                        s.creases.kept_at_fallback += usize::from(fallback[f] || fallback[g]);
                    }
                    let ratio = phi / theta;
                    if s.creases.weakest.is_none() || ratio < s.weakest_ratio {
                        s.creases.weakest = Some(at(phi));
                        s.weakest_ratio = ratio;
                    }
                }
            }
            s
        })
        .reduce(EdgeScan::default, EdgeScan::merge);

    let flat = flat_regions(mesh, fit, &samples, &dihedral);
    Ok(SharpReport {
        interior_edges: scan.interior,
        undefined_dihedrals: scan.undefined,
        smooth: scan.smooth,
        creases: scan.creases,
        flat,
    })
}

/// A candidate region's plane and whether it is counted.
#[derive(Clone, Copy, Debug)]
struct Region {
    centroid: Point3<f64>,
    normal: Vector3<f64>,
    counted: bool,
}

/// Section 3 of the module docs.
fn flat_regions(
    mesh: &Mesh,
    fit: &Fit,
    samples: &Samples,
    dihedral: &(dyn Fn(&mesh::Edge) -> Option<f64> + Sync),
) -> FlatRegions {
    let nf = mesh.num_faces();
    let diagonal = mesh.size();
    let mut out = FlatRegions::default();
    // Union by smaller root: every root is its component's smallest face.
    let flat_edges: Vec<bool> = mesh
        .par_edges()
        .map(|e| dihedral(&e).is_some_and(|t| t <= FLAT_DIHEDRAL))
        .collect();
    let mut sets = mesh::disjoint::DisjointSets::new(nf);
    for (e, _) in mesh.edges().zip(&flat_edges).filter(|(_, f)| **f) {
        let Some((g, _)) = e.second else { continue };
        sets.union(e.first.0, g);
    }
    let root: Vec<usize> = (0..nf).map(|f| sets.find(f)).collect();
    let mut size = vec![0usize; nf];
    for &r in &root {
        size[r] += 1;
    }
    // Regions numbered by their smallest face; sums in face order.
    let mut region_of = vec![usize::MAX; nf];
    let mut sums: Vec<(Vector3<f64>, f64, Vector3<f64>)> = Vec::new();
    let verts = mesh.vertices();
    for f in 0..nf {
        let r = root[f];
        if size[r] < 2 {
            continue;
        }
        if r == f {
            region_of[f] = sums.len();
            sums.push((Vector3::zeros(), 0.0, Vector3::zeros()));
        } else {
            region_of[f] = region_of[r];
        }
        let Some(s) = sums.get_mut(region_of[f]) else {
            continue;
        };
        let face = mesh.faces()[f];
        let area_vector = mesh
            .face_area_normal(f)
            .unwrap_or_else(|_| Vector3::zeros());
        let weight = area_vector.norm();
        let centroid = (verts[face[0]].data.p.coords
            + verts[face[1]].data.p.coords
            + verts[face[2]].data.p.coords)
            / 3.0;
        s.0 += area_vector;
        s.1 += weight;
        s.2 += centroid * weight;
    }
    let mut regions: Vec<Region> = sums
        .iter()
        .map(|(n, w, c)| Region {
            centroid: Point3::from(c / *w),
            normal: n.normalize(),
            counted: true,
        })
        .collect();
    let mut flatness = vec![0.0f64; regions.len()];
    for f in 0..nf {
        let Some(r) = regions.get(region_of[f]) else {
            continue;
        };
        for v in mesh.faces()[f] {
            let d = (verts[v].data.p - r.centroid).dot(&r.normal).abs();
            flatness[region_of[f]] = flatness[region_of[f]].max(d);
        }
    }
    let mut faces_in = vec![0usize; regions.len()];
    for &r in region_of.iter().filter(|r| **r != usize::MAX) {
        faces_in[r] += 1;
    }
    // Regions that meet a neighbour across an edge that is not sharp (a blend).
    let crease = CREASE_CANDIDATE_DEG.to_radians();
    let mut blended = vec![false; regions.len()];
    for e in mesh.edges() {
        let Some((g, _)) = e.second else { continue };
        let (rf, rg) = (region_of[e.first.0], region_of[g]);
        if rf == rg || dihedral(&e).is_some_and(|t| t > crease) {
            continue;
        }
        for r in [rf, rg] {
            if let Some(b) = blended.get_mut(r) {
                *b = true;
            }
        }
    }
    for (((region, flat), faces), blend) in regions
        .iter_mut()
        .zip(&flatness)
        .zip(&faces_in)
        .zip(&blended)
    {
        // A NaN flatness (a region of zero total area) compares false: not flat data.
        let flat_data = diagonal > 0.0 && *flat <= DATA_FLATNESS * diagonal;
        region.counted = flat_data && !blend;
        if flat_data && *blend {
            out.blended_regions += 1;
            out.blended_faces += faces;
        } else if region.counted {
            out.regions += 1;
            out.faces += faces;
            out.largest_region = out.largest_region.max(*faces);
            out.data_flatness = out.data_flatness.max(flat / diagonal);
        } else {
            out.rejected_regions += 1;
            out.rejected_faces += faces;
            let relative = flat / diagonal;
            out.closest_rejected = Some(out.closest_rejected.map_or(relative, |c| c.min(relative)));
        }
    }

    let layout = &fit.layout;
    let (np, per_face) = (layout.points_per_patch(), layout.points_per_face());
    // (largest distance, its face, non-finite samples), merged in face order.
    let (worst, worst_face, nonfinite) = (0..nf)
        .into_par_iter()
        .fold(
            || (0.0f64, None::<usize>, 0usize),
            |mut acc, f| {
                let Some(r) = regions.get(region_of[f]).filter(|r| r.counted) else {
                    return acc;
                };
                let pts = &fit.points[f * per_face..(f + 1) * per_face];
                let mut d_face = 0.0f64;
                for (patch, at) in &samples.flat {
                    let net = &pts[patch * np..(patch + 1) * np];
                    let p = eval(layout, net, at).p;
                    let d = (p - r.centroid).dot(&r.normal).abs();
                    if d.is_finite() {
                        d_face = d_face.max(d);
                    } else {
                        acc.2 += 1;
                    }
                }
                if acc.1.is_none() || d_face > acc.0 {
                    acc = (d_face, Some(f), acc.2);
                }
                acc
            },
        )
        .reduce(
            || (0.0, None, 0),
            |a, b| {
                let n = a.2 + b.2;
                if b.1.is_some() && (a.1.is_none() || b.0 > a.0) {
                    (b.0, b.1, n)
                } else {
                    (a.0, a.1, n)
                }
            },
        );
    out.deviation = if diagonal > 0.0 {
        worst / diagonal
    } else {
        0.0
    };
    out.worst_face = worst_face;
    out.nonfinite_samples = nonfinite;
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)] // test fixtures fail loudly by design
    use super::*;
    use crate::scheme::{scheme_by_name, SchemeOptions};
    use mesh::Vertex;

    /// Angles from atan2 of cross and dot products of rounded unit normals: rounding only.
    const ANGLE: f64 = 1e-14;
    /// A plane's patches, sampled and measured against the region's plane relative to the
    /// diagonal: coordinates of order one, so rounding of a few ulps.
    const PLANE_ROUNDING: f64 = 1e-14;

    fn fit(mesh: &Mesh, scheme: &str) -> Fit {
        let s = scheme_by_name(scheme, &SchemeOptions::default()).unwrap();
        let m = curves::method_by_name("chord", &curves::MethodOptions::default()).unwrap();
        crate::fit::fit_scheme(mesh, s.as_ref(), m.as_ref()).unwrap()
    }

    /// Two triangles on the edge (0,0,0)–(1,0,0): the first in `z = 0`, the second turned about
    /// the edge so that its normal is `(0, sin φ, cos φ)`: the data dihedral is `φ`.
    fn folded(phi: f64) -> Mesh {
        let p = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.5, 1.0, 0.0),
            Point3::new(0.5, -phi.cos(), phi.sin()),
        ];
        let verts = p
            .iter()
            .map(|q| Vertex::without_curvature(*q, Vector3::z()))
            .collect();
        Mesh::new(verts, vec![[0, 1, 2], [1, 0, 3]]).unwrap()
    }

    /// The flat scheme's patches are the data triangles, so the fitted angle across the edge is
    /// the data dihedral at every point: the crease is kept, at exactly its angle.
    #[test]
    fn the_flat_scheme_keeps_a_fold_at_its_dihedral_angle() {
        for deg in [45.0f64, 60.0, 90.0, 135.0, 170.0] {
            let phi = deg.to_radians();
            let m = folded(phi);
            let r = measure(&m, &fit(&m, "flat")).unwrap();
            assert_eq!(r.interior_edges, 1);
            assert_eq!((r.creases.candidates, r.creases.kept), (1, 1), "{deg}°");
            let w = r.creases.weakest.unwrap();
            assert_eq!((w.edge, w.vertices), (0, [0, 1]));
            assert!((w.dihedral - phi).abs() < ANGLE, "{deg}°: {w:?}");
            assert!((w.fitted - phi).abs() < ANGLE, "{deg}°: {w:?}");
            assert_eq!(r.smooth, SmoothEdges::default());
            assert_eq!(r.flat.regions, 0);
        }
    }

    /// A fold of 3° is a smooth edge, and the flat scheme kinks it by exactly 3°, not severely;
    /// a fold of 25° is neither smooth nor a crease candidate.
    #[test]
    fn the_flat_scheme_kinks_a_smooth_edge_by_its_dihedral_angle() {
        let phi = 3f64.to_radians();
        let m = folded(phi);
        let r = measure(&m, &fit(&m, "flat")).unwrap();
        assert_eq!(
            (r.smooth.edges, r.smooth.kinked, r.smooth.severe),
            (1, 1, 0)
        );
        let w = r.smooth.worst.unwrap();
        assert!((w.fitted - phi).abs() < ANGLE, "{w:?}");
        assert!((w.dihedral - phi).abs() < ANGLE, "{w:?}");
        assert_eq!(r.smooth.undefined_normals, 0);
        assert_eq!(r.creases.candidates, 0);

        let m = folded(25f64.to_radians());
        let r = measure(&m, &fit(&m, "flat")).unwrap();
        assert_eq!((r.smooth.edges, r.creases.candidates), (0, 0));
        assert_eq!(r.interior_edges, 1);
    }

    /// A grid of `n × n` squares (two triangles each) on a tilted plane through `o` spanned by
    /// `a` and `b`, every vertex normal the plane's.
    fn tilted_grid(n: usize) -> Mesh {
        let us: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
        tilted_grid_at(&us)
    }

    /// [`tilted_grid`] with the columns at parameters `us` along `a` (rows uniform).
    fn tilted_grid_at(us: &[f64]) -> Mesh {
        let n = us.len() - 1;
        let o = Point3::new(0.3, -0.2, 0.7);
        let a = Vector3::new(0.8, 0.35, -0.2);
        let b = Vector3::new(-0.15, 0.7, 0.45);
        let normal = a.cross(&b).normalize();
        let mut verts = Vec::new();
        for j in 0..=n {
            for u in us {
                let p = o + a * *u + b * (j as f64 / n as f64);
                verts.push(Vertex::without_curvature(p, normal));
            }
        }
        let id = |i: usize, j: usize| j * (n + 1) + i;
        let mut faces = Vec::new();
        for j in 0..n {
            for i in 0..n {
                faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        Mesh::new(verts, faces).unwrap()
    }

    /// A tilted planar grid is one flat region of every face; the flat scheme (the triangles
    /// themselves) and Shirman–Séquin on the plane's normals (planes are reproduced) stay on it
    /// to rounding and kink no edge.
    #[test]
    fn a_plane_fitted_by_a_scheme_that_reproduces_planes_is_flat_and_unkinked() {
        let m = tilted_grid(6);
        let interior = m.edges().filter(|e| !e.is_boundary()).count();
        for scheme in ["flat", "shirman-sequin"] {
            let r = measure(&m, &fit(&m, scheme)).unwrap();
            assert_eq!(r.interior_edges, interior);
            assert_eq!(r.smooth.edges, interior, "{scheme}");
            assert_eq!((r.smooth.kinked, r.creases.candidates), (0, 0), "{scheme}");
            assert!(r.smooth.worst.unwrap().fitted < KINK_TOLERANCE, "{scheme}");
            assert_eq!(
                (r.flat.regions, r.flat.faces),
                (1, m.num_faces()),
                "{scheme}"
            );
            assert_eq!(r.flat.rejected_regions, 0);
            assert!(r.flat.data_flatness <= DATA_FLATNESS, "{scheme}: {r:?}");
            assert!(r.flat.deviation <= PLANE_ROUNDING, "{scheme}: {r:?}");
            assert_eq!(r.flat.nonfinite_samples, 0);
        }
    }

    /// A strip of `n` unit-width squares along `x`, square `k` turned about `y` by `k · δ`: every
    /// fold is `δ`, so the strip bends by `n δ` in all.
    fn bent_strip(n: usize, delta: f64) -> Mesh {
        let h = 1.0 / n as f64;
        let mut p = Point3::origin();
        let mut verts = Vec::new();
        for k in 0..=n {
            verts.push(Vertex::without_curvature(p, Vector3::z()));
            verts.push(Vertex::without_curvature(
                p + Vector3::new(0.0, 0.2, 0.0),
                Vector3::z(),
            ));
            let turn = k as f64 * delta;
            p += Vector3::new(turn.cos(), 0.0, turn.sin()) * h;
        }
        let mut faces = Vec::new();
        for k in 0..n {
            let (a, b, c, d) = (2 * k, 2 * k + 2, 2 * k + 3, 2 * k + 1);
            faces.push([a, b, c]);
            faces.push([a, c, d]);
        }
        Mesh::new(verts, faces).unwrap()
    }

    /// Folds each far below `FLAT_DIHEDRAL` that add up to a bend (sagitta about `L · nδ / 8`,
    /// 1e-8 here) connect the strip into one candidate region, whose vertices leave its plane
    /// by far more than `DATA_FLATNESS`: rejected. The same strip unbent is counted.
    #[test]
    fn a_region_bent_by_folds_below_the_threshold_is_not_counted() {
        let (n, delta) = (400, 2e-13);
        let m = bent_strip(n, delta);
        let r = measure(&m, &fit(&m, "flat")).unwrap();
        assert_eq!((r.flat.regions, r.flat.faces), (0, 0), "{r:?}");
        assert_eq!((r.flat.rejected_regions, r.flat.rejected_faces), (1, 2 * n));
        assert_eq!(r.flat.worst_face, None);
        // About the sagitta, well above the tolerance and below the bend's first-order size.
        let missed = r.flat.closest_rejected.unwrap();
        assert!(missed > 1e-12 && missed < n as f64 * delta, "{missed:e}");
        let m = bent_strip(n, 0.0);
        let r = measure(&m, &fit(&m, "flat")).unwrap();
        assert_eq!((r.flat.regions, r.flat.faces), (1, 2 * n), "{r:?}");
        assert_eq!((r.flat.largest_region, r.flat.rejected_regions), (2 * n, 0));
        assert_eq!(r.flat.closest_rejected, None);
    }

    /// Two coplanar triangles are a region of two faces; a fold of 1e-6 rad splits them (each a
    /// single face, no region).
    #[test]
    fn coplanar_neighbours_make_a_region_and_a_small_fold_splits_it() {
        let m = folded(0.0);
        let r = measure(&m, &fit(&m, "flat")).unwrap();
        assert_eq!((r.flat.regions, r.flat.faces), (1, 2), "{r:?}");
        assert!(r.flat.deviation <= PLANE_ROUNDING);
        let m = folded(1e-6);
        let r = measure(&m, &fit(&m, "flat")).unwrap();
        assert_eq!((r.flat.regions, r.flat.rejected_regions), (0, 0), "{r:?}");
    }

    /// A tilted plane with a column of slivers `1e-5` of its size wide: rounding alone folds
    /// its faces by more than `1e-12` (measured 2.0e-11), and `FLAT_DIHEDRAL` still keeps the
    /// plane one region of every face.
    #[test]
    fn a_plane_with_slivers_is_one_region() {
        let mut us = vec![0.0, 1e-5];
        us.extend((1..=6).map(|i| f64::from(i) / 6.0));
        let m = tilted_grid_at(&us);
        let normals: Vec<_> = (0..m.num_faces())
            .map(|f| data_normal(&m, f).unwrap())
            .collect();
        let folds = m.edges().filter_map(|e| {
            e.second
                .map(|(g, _)| angle(&normals[e.first.0], &normals[g]))
        });
        let largest = folds.fold(0.0f64, f64::max);
        assert!(largest > 1e-12 && largest <= FLAT_DIHEDRAL, "{largest:e}");
        let r = measure(&m, &fit(&m, "flat")).unwrap();
        assert_eq!((r.flat.regions, r.flat.faces), (1, m.num_faces()), "{r:?}");
        assert!(r.flat.data_flatness <= DATA_FLATNESS);
    }

    /// One thread or many, the same report bit for bit (ties resolved by index).
    #[test]
    fn the_parallel_scan_reports_what_one_thread_does() {
        let set = mesh::dataset_by_name("capsule", Some(24)).unwrap();
        for scheme in ["flat", "clough-tocher", "nielson"] {
            let f = fit(&set.mesh, scheme);
            let many = measure(&set.mesh, &f).unwrap();
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .build()
                .unwrap();
            let one = pool.install(|| measure(&set.mesh, &f)).unwrap();
            assert_eq!(one, many, "{scheme}");
            assert!(many.smooth.edges > 0, "{scheme}");
        }
    }

    /// A fit of another mesh is an error naming the first face without patches.
    #[test]
    fn a_fit_of_another_mesh_is_an_error() {
        let small = folded(1.0);
        let big = tilted_grid(2);
        let err = measure(&big, &fit(&small, "flat")).unwrap_err();
        assert_eq!(
            err,
            SharpError::WrongSize {
                mesh_faces: 8,
                fit_points: 6,
                points_per_face: 3,
                first_missing: Some(2),
            }
        );
        assert!(err.to_string().contains("face 2 has no patches"), "{err}");
        let err = measure(&small, &fit(&big, "flat")).unwrap_err();
        assert!(err.to_string().contains("larger mesh"), "{err}");
    }

    /// The report serializes (the reports' JSON) with every section.
    #[test]
    fn the_report_serializes_with_its_sections() {
        let m = folded(1.0);
        let r = measure(&m, &fit(&m, "flat")).unwrap();
        let v = serde_json::to_value(r).unwrap();
        for key in [
            "interior_edges",
            "undefined_dihedrals",
            "smooth",
            "creases",
            "flat",
        ] {
            assert!(v.get(key).is_some(), "{key}: {v}");
        }
        assert_eq!(v["creases"]["kept"], 1);
    }
}

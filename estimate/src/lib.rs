//! Per-vertex unit normals and shape tensors estimated from a triangle mesh.
//!
//! Every estimator implements [`Estimator`] and is registered by name in [`ESTIMATORS`]
//! ([`estimator_by_name`]); one estimator a file:
//!
//! * [`jet`] — osculating jets (Cazals & Pouget, SGP 2003 / CAGD 2005): a degree-`d` bivariate
//!   polynomial height fitted by least squares over an adaptive k-ring (`jet2`, `jet3`, `jet4`,
//!   and `jet`, the degree-2 jet);
//! * [`quadric`] — the local quadric fit of libigl's `principal_curvature` (Panozzo et al. 2010);
//! * [`rusinkiewicz`] — per-face second fundamental forms from vertex-normal differences,
//!   averaged at the vertices (Rusinkiewicz, 3DPVT 2004);
//! * [`hybrid`] — the default ([`DEFAULT_ESTIMATOR`]): per vertex `jet4` where the sampling
//!   resolves the surface, `rusinkiewicz` elsewhere.
//!
//! Gradients of functional data `z = f(x, y)` (height fields over a planar triangulation), the
//! input of the functional Clough–Tocher and Powell–Sabin interpolants, have their own family in
//! [`gradients`] (`cubic`, `minimum-norm`).
//!
//! Vertex normals alone (angle-, area- and Max-weighted) are in [`normals`]; they are the first
//! normal estimate of the fitting estimators and the input of `rusinkiewicz`.
//!
//! # Conventions
//!
//! A vertex carries a unit normal `n` and a symmetric shape tensor `S` in world coordinates with
//! `S n = 0`; the normal curvature in the unit tangent direction `d` is `κn(d) = dᵀ S d`, positive
//! where the surface bends **towards** `n` (the unit sphere with outward normals has
//! `S = −(I − n nᵀ)`, `K = 1`, `H = −1`). For a height field `z = ½(a x² + 2b xy + c y²)` over the
//! tangent plane with `n = +z` the tensor restricted to the plane is `[[a, b], [b, c]]`.
//!
//! # Robustness
//!
//! The estimators accept any [`Mesh`]: open boundaries, isolated vertices, any valence,
//! zero-area faces (made after construction through [`Mesh::vertices_mut`]), several
//! components. They never panic and never return a non-finite number: where a neighbourhood is
//! degenerate they fall back to a stated lower-order estimate and record it as a [`Fallback`].
//! The normals stored in the mesh are never read; pass them as `given` to keep them.

use std::collections::BTreeMap;

use mesh::Mesh;
use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

pub mod facing;
pub mod fit;
pub mod fold_split;
pub mod gradients;
pub mod hybrid;
pub mod jet;
pub mod multiscale;
pub mod normals;
pub mod prepare;
pub mod principal;
pub mod quadric;
pub mod rusinkiewicz;
pub mod topology;

pub use hybrid::{Hybrid, HYBRID};
pub use jet::{Jet, JET, JET2, JET3, JET4};
pub use multiscale::{Multiscale, MULTISCALE};
pub use normals::{vertex_normals, NormalWeighting, Normals};
pub use prepare::{
    attach_creases, prepare, prepare_owned, prepare_with, ChoiceError, CreaseSummary,
    EstimateChoice, PrepareError, Prepared,
};
pub use principal::{principal_frame, Principal};
pub use quadric::{Quadric, QUADRIC};
pub use rusinkiewicz::{Rusinkiewicz, RUSINKIEWICZ};
pub use topology::{RingMarks, Topology};

/// A way to estimate per-vertex normals and shape tensors.
pub trait Estimator: Send + Sync {
    /// The registered name (`"jet"`, `"quadric"`, …).
    fn name(&self) -> &'static str;

    /// One line for `--help` and reports.
    fn description(&self) -> &'static str;

    /// Per-vertex unit normals and shape tensors. `given`: normals to keep (one per vertex,
    /// unit) — then only `S` is estimated, in the tangent plane of the given normal (`S n = 0`);
    /// `None`: the normals are estimated too. A given normal that is missing (slice too short),
    /// non-finite or zero is replaced by an estimate and recorded
    /// ([`FallbackKind::InvalidGivenNormal`]); a non-unit one is normalized.
    fn estimate(&self, mesh: &Mesh, given: Option<&[Vector3<f64>]>) -> Estimate;
}

/// Why a vertex got a zero shape tensor.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PlanarReason {
    /// Too few distinct neighbours for even the lowest-degree fit.
    TooFewNeighbours,
    /// The lowest-degree least-squares system was rank-deficient or its condition number was
    /// above [`fit::MAX_CONDITION`] (all neighbours on a line, coincident points, …).
    IllConditioned,
    /// Every face around the vertex has zero area (or there are none): no face curvature.
    NoArea,
    /// The computation produced a non-finite number (a safety net; not expected).
    NonFinite,
}

/// A lower-order estimate used at one vertex, and why.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum FallbackKind {
    /// The vertex belongs to no face: normal `+z` (or the given one), `S = 0`.
    Isolated,
    /// Every face around the vertex has zero area: the normal is the average of the normals of
    /// the nearest vertices (in rings) that have one.
    NormalFromNeighbours {
        /// How many rings away the nearest vertices with a normal were.
        rings: usize,
    },
    /// No vertex of the vertex's connected component has a normal (all faces zero-area): `+z`.
    DefaultNormal,
    /// The given normal was missing, non-finite or zero; it was estimated instead.
    InvalidGivenNormal,
    /// A jet of lower degree than asked was fitted (too few points, rank deficiency or
    /// condition number above [`fit::MAX_CONDITION`]).
    LowerDegree {
        /// The degree asked for.
        from: usize,
        /// The degree used.
        to: usize,
    },
    /// No Euclidean ball around the vertex gave an admissible fit (on an anisotropic mesh a
    /// ball either wraps around the surface or holds a single row of points): the adaptive
    /// k-ring jet of degree 2 ([`JET`]) was used ([`multiscale`]).
    RingNeighbourhood,
    /// The shape tensor is zero: the surface is taken as planar at the vertex.
    Planar {
        /// Why.
        reason: PlanarReason,
    },
}

impl FallbackKind {
    /// A short stable label for summaries (`"isolated"`, `"lower_degree"`, …).
    pub fn label(&self) -> &'static str {
        match self {
            FallbackKind::Isolated => "isolated",
            FallbackKind::NormalFromNeighbours { .. } => "normal_from_neighbours",
            FallbackKind::DefaultNormal => "default_normal",
            FallbackKind::InvalidGivenNormal => "invalid_given_normal",
            FallbackKind::LowerDegree { .. } => "lower_degree",
            FallbackKind::RingNeighbourhood => "ring_neighbourhood",
            FallbackKind::Planar { .. } => "planar",
        }
    }
}

/// One fallback at one vertex (a vertex may have several, e.g. a normal fallback and a planar
/// tensor).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Fallback {
    /// The vertex.
    pub vertex: usize,
    /// What was used instead.
    pub kind: FallbackKind,
}

/// The result of an estimator: one unit normal and one shape tensor per vertex, all finite.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Estimate {
    /// Unit normals.
    pub normals: Vec<Vector3<f64>>,
    /// Symmetric shape tensors with `S n = 0` (to rounding).
    pub shapes: Vec<Matrix3<f64>>,
    /// Every fallback, sorted by vertex.
    pub fallbacks: Vec<Fallback>,
}

impl Estimate {
    /// Principal curvatures `κ1 ≤ κ2` at vertex `v` (the two eigenvalues of `S` in the tangent
    /// plane), `None` when there is no such vertex.
    pub fn principal(&self, v: usize) -> Option<[f64; 2]> {
        Some(principal_curvatures(
            self.shapes.get(v)?,
            self.normals.get(v)?,
        ))
    }

    /// Gaussian curvature `K = κ1 κ2` at vertex `v`.
    pub fn gaussian(&self, v: usize) -> Option<f64> {
        self.principal(v).map(|[a, b]| a * b)
    }

    /// Mean curvature `H = (κ1 + κ2)/2` at vertex `v`.
    pub fn mean(&self, v: usize) -> Option<f64> {
        self.principal(v).map(|[a, b]| 0.5 * (a + b))
    }

    /// How many fallbacks of each kind ([`FallbackKind::label`]).
    pub fn fallback_counts(&self) -> BTreeMap<&'static str, usize> {
        let mut out = BTreeMap::new();
        for f in &self.fallbacks {
            *out.entry(f.kind.label()).or_insert(0) += 1;
        }
        out
    }
}

/// Principal curvatures `κ1 ≤ κ2` of a shape tensor with unit normal `n`: the eigenvalues of
/// `S` restricted to the plane `⊥ n`, from the 2×2 matrix `[[t1ᵀ S t1, t1ᵀ S t2], [·, t2ᵀ S t2]]`
/// in an orthonormal tangent basis (closed form of a symmetric 2×2 eigenproblem).
pub fn principal_curvatures(s: &Matrix3<f64>, n: &Vector3<f64>) -> [f64; 2] {
    let (t1, t2) = fit::tangent_basis(n);
    let a = t1.dot(&(s * t1));
    let b = 0.5 * (t1.dot(&(s * t2)) + t2.dot(&(s * t1)));
    let c = t2.dot(&(s * t2));
    let mid = 0.5 * (a + c);
    let rad = (0.5 * (a - c)).hypot(b);
    [mid - rad, mid + rad]
}

/// A name that is not in the registry.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown estimator `{name}` (known: {known})")]
pub struct UnknownEstimator {
    /// The name asked for.
    pub name: String,
    /// The registered names, comma-separated.
    pub known: String,
}

/// Every registered estimator, in the order `--help` and the studies list them (the default is
/// [`DEFAULT_ESTIMATOR`], `hybrid`, not the first).
pub static ESTIMATORS: &[&dyn Estimator] = &[
    &JET,
    &JET2,
    &JET3,
    &JET4,
    &QUADRIC,
    &RUSINKIEWICZ,
    &HYBRID,
    &MULTISCALE,
];

/// The recommended default estimator's name: `hybrid`, the most accurate in the `estimation`
/// study (at least as accurate as the best of libigl's estimators on 30 of 32 meshes for the
/// normals, 18 for K and 31 for H, against 14, 0 and 0 for `jet`).
pub const DEFAULT_ESTIMATOR: &str = "hybrid";

/// Looks an estimator up by name.
pub fn estimator_by_name(name: &str) -> Result<&'static dyn Estimator, UnknownEstimator> {
    ESTIMATORS
        .iter()
        .copied()
        .find(|e| e.name() == name)
        .ok_or_else(|| UnknownEstimator {
            name: name.to_string(),
            known: ESTIMATORS
                .iter()
                .map(|e| e.name())
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// What [`apply`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct EstimateSummary {
    /// The estimator's name.
    pub estimator: &'static str,
    /// Vertices written (sectors, on a mesh with sectors: one estimate each).
    pub vertices: usize,
    /// Whether the mesh's normals were kept.
    pub kept_normals: bool,
    /// Every fallback.
    pub fallbacks: Vec<Fallback>,
    /// Fallback counts by [`FallbackKind::label`].
    pub fallback_counts: BTreeMap<&'static str, usize>,
}

/// Estimates with `est` and writes the normals (unless kept) and shape tensors into the mesh's
/// vertices, marking their curvature known. `keep_given_normals`: pass the mesh's current
/// normals as `given` (invalid ones are re-estimated and reported).
///
/// A mesh with sectors ([`mesh::sectors`]) is estimated per sector: the estimator runs on the
/// mesh cut open along its creases ([`mesh::Sectors::split_mesh`]), so each sector's normal and
/// shape tensor come from its own faces only, by whichever estimator. The results go to the
/// slots; a vertex of one slot gets its slot's data, a vertex of several (on a crease) the
/// normalized sum of their normals and the mean of their tensors projected on it (what a
/// per-vertex output shows; the fit reads the slots). A given normal is kept only at a vertex of
/// one slot: a file's single normal at a crease vertex describes neither side.
pub fn apply(mesh: &mut Mesh, est: &dyn Estimator, keep_given_normals: bool) -> EstimateSummary {
    let given: Option<Vec<Vector3<f64>>> =
        keep_given_normals.then(|| mesh.vertices().iter().map(|v| v.data.n).collect());
    if mesh.sectors().is_some() {
        if let Some(summary) = apply_per_sector(mesh, est, given.as_deref()) {
            return summary;
        }
        // The cut mesh did not validate (not expected): the slots would keep stale data, so
        // the mesh is estimated and fitted per vertex instead.
        let _ = mesh.set_sectors(None);
    }
    let e = est.estimate(mesh, given.as_deref());
    for (i, v) in mesh.vertices_mut().iter_mut().enumerate() {
        if let (Some(n), Some(s)) = (e.normals.get(i), e.shapes.get(i)) {
            v.data.n = *n;
            v.data.shape = *s;
            v.curvature_known = true;
        }
    }
    let fallback_counts = e.fallback_counts();
    EstimateSummary {
        estimator: est.name(),
        vertices: e.normals.len(),
        kept_normals: keep_given_normals,
        fallbacks: e.fallbacks,
        fallback_counts,
    }
}

/// [`apply`] on a mesh with sectors; `None` (nothing done) when it has none, or when the cut
/// mesh does not validate (not expected: the caller then estimates per vertex).
fn apply_per_sector(
    mesh: &mut Mesh,
    est: &dyn Estimator,
    given: Option<&[Vector3<f64>]>,
) -> Option<EstimateSummary> {
    let sectors = mesh.sectors()?;
    let split = sectors.split_mesh(mesh).ok()?;
    let slot_vertex = sectors.slot_vertices().to_vec();
    let nv = mesh.num_vertices();
    let per_vertex = sectors.slots_per_vertex(nv);
    // A given normal is kept at vertices of one slot only (a zero vector asks for an estimate).
    let slot_given: Option<Vec<Vector3<f64>>> = given.map(|g| {
        slot_vertex
            .iter()
            .map(|&v| match (per_vertex[v], g.get(v)) {
                (1, Some(n)) => *n,
                _ => Vector3::zeros(),
            })
            .collect()
    });
    let e = est.estimate(&split, slot_given.as_deref());
    // Per vertex: the sum of its slots' normals and tensors.
    let mut n_sum = vec![Vector3::<f64>::zeros(); nv];
    let mut s_sum = vec![Matrix3::<f64>::zeros(); nv];
    for (s, &v) in slot_vertex.iter().enumerate() {
        if let (Some(n), Some(sh)) = (e.normals.get(s), e.shapes.get(s)) {
            n_sum[v] += n;
            s_sum[v] += sh;
        }
    }
    let slots = e.normals.len();
    if let Some(sec) = mesh.sectors_mut() {
        sec.set_slot_data(e.normals, e.shapes).ok()?;
    }
    for (v, vert) in mesh.vertices_mut().iter_mut().enumerate() {
        if per_vertex[v] == 0 {
            continue;
        }
        let len = n_sum[v].norm();
        if len > 0.0 && len.is_finite() {
            let n = unit(&n_sum[v], len);
            vert.data.n = n;
            vert.data.shape = project_shape(&(s_sum[v] / per_vertex[v] as f64), &n);
        } else {
            // Opposite sectors (a knife edge): no mean direction; the vertex keeps its normal
            // (the fit reads the slots).
            vert.data.shape = Matrix3::zeros();
        }
        vert.curvature_known = true;
    }
    let mut fallbacks: Vec<Fallback> = e
        .fallbacks
        .into_iter()
        .filter_map(|f| {
            let vertex = *slot_vertex.get(f.vertex)?;
            // The normals withheld at crease vertices are not a fault of the input.
            let withheld = f.kind == FallbackKind::InvalidGivenNormal && per_vertex[vertex] > 1;
            (!withheld).then_some(Fallback { vertex, ..f })
        })
        .collect();
    fallbacks.sort();
    fallbacks.dedup();
    let mut fallback_counts = BTreeMap::new();
    for f in &fallbacks {
        *fallback_counts.entry(f.kind.label()).or_insert(0) += 1;
    }
    Some(EstimateSummary {
        estimator: est.name(),
        vertices: slots,
        kept_normals: given.is_some(),
        fallbacks,
        fallback_counts,
    })
}

/// The given normal of vertex `v`, normalized, if it is present and usable.
pub(crate) fn given_normal(given: Option<&[Vector3<f64>]>, v: usize) -> Option<Vector3<f64>> {
    let n = given?.get(v)?;
    let len = n.norm();
    (len.is_finite() && len > 0.0 && n.iter().all(|c| c.is_finite())).then(|| unit(n, len))
}

/// Within this of 1 a length is taken as unit and the vector kept bit for bit (so that given
/// normals come back exactly as given).
pub(crate) const UNIT_SLACK: f64 = 1e-14;

/// `n / len`, or `n` itself when `len` is 1 to [`UNIT_SLACK`].
pub(crate) fn unit(n: &Vector3<f64>, len: f64) -> Vector3<f64> {
    if (len - 1.0).abs() <= UNIT_SLACK {
        *n
    } else {
        n / len
    }
}

/// Symmetrizes `s` and projects it onto the plane `⊥ n`: `P ½(S + Sᵀ) P`, `P = I − n nᵀ`, so
/// that `S n = 0` to rounding.
pub(crate) fn project_shape(s: &Matrix3<f64>, n: &Vector3<f64>) -> Matrix3<f64> {
    let p = Matrix3::identity() - n * n.transpose();
    let sym = (s + s.transpose()) * 0.5;
    let out = p * sym * p;
    (out + out.transpose()) * 0.5
}

/// [`finish`] at one vertex: `n` normalized (replaced by `first`, else `+z`, when it has no
/// length), `s` symmetrized and projected; true when `s` had a non-finite entry and was zeroed
/// (a [`PlanarReason::NonFinite`] fallback).
pub(crate) fn finish_vertex(
    n: &mut Vector3<f64>,
    s: &mut Matrix3<f64>,
    first: Option<&Vector3<f64>>,
) -> bool {
    let len = n.norm();
    if !(len.is_finite() && len > 0.0) {
        *n = first.copied().unwrap_or_else(Vector3::z);
    } else {
        *n = unit(n, len);
    }
    *s = project_shape(s, n);
    if s.iter().all(|c| c.is_finite()) {
        return false;
    }
    *s = Matrix3::zeros();
    true
}

/// The last step of every estimator: given normals are kept exactly, every tensor is symmetric
/// and projected (`S n = 0`), and any non-finite value (not expected) is replaced by the first
/// normal estimate and `S = 0`, recorded as [`PlanarReason::NonFinite`]. Sorts the fallbacks.
pub(crate) fn finish(
    mut normals: Vec<Vector3<f64>>,
    mut shapes: Vec<Matrix3<f64>>,
    mut fallbacks: Vec<Fallback>,
    first: &Normals,
) -> Estimate {
    let bad: Vec<Fallback> = normals
        .par_iter_mut()
        .zip(shapes.par_iter_mut())
        .enumerate()
        .with_min_len(1024)
        .filter_map(|(v, (n, s))| {
            finish_vertex(n, s, first.normals.get(v)).then_some(Fallback {
                vertex: v,
                kind: FallbackKind::Planar {
                    reason: PlanarReason::NonFinite,
                },
            })
        })
        .collect();
    fallbacks.extend(bad);
    fallbacks.sort();
    fallbacks.dedup();
    Estimate {
        normals,
        shapes,
        fallbacks,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_names_are_unique_and_resolve() {
        for e in ESTIMATORS {
            let found = estimator_by_name(e.name()).expect("registered");
            assert_eq!(found.name(), e.name());
            assert_eq!(
                ESTIMATORS.iter().filter(|f| f.name() == e.name()).count(),
                1
            );
            assert!(!e.description().is_empty());
        }
        assert!(estimator_by_name(DEFAULT_ESTIMATOR).is_ok());
        let err = estimator_by_name("bogus").err().expect("unknown");
        assert!(err
            .to_string()
            .contains("jet, jet2, jet3, jet4, quadric, rusinkiewicz"));
    }

    #[test]
    fn principal_curvatures_of_the_sphere_tensor() {
        let n = Vector3::new(1.0, 2.0, 2.0) / 3.0;
        let s = -(Matrix3::identity() - n * n.transpose());
        /// A 2×2 eigenproblem in closed form: rounding only.
        const ROUNDING: f64 = 1e-14;
        let [a, b] = principal_curvatures(&s, &n);
        assert!((a + 1.0).abs() < ROUNDING && (b + 1.0).abs() < ROUNDING);
    }
}

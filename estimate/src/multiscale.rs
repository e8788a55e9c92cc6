//! `multiscale`: degree-2 jets on Euclidean balls of several radii, robustly weighted, with the
//! radius chosen per vertex from the data; and `jet-r<R>`, the same jet on one fixed radius
//! (`--radius`). The estimators for noisy meshes (scans).
//!
//! # The fit at one radius
//!
//! At vertex `v` with first normal `n0` (angle-weighted, [`crate::normals`]) and frame
//! `(t1, t2, n0)` ([`crate::fit::tangent_basis`]), the neighbourhood is the ball of radius `r`
//! around `v` walked along the edges ([`Topology::ball_into`]), and the height
//! `z(x, y) = c₀ + c₁x + c₂y + c₃x² + c₄xy + c₅y²` is fitted by least squares (the osculating
//! jet of degree 2 of Cazals & Pouget, *Estimating differential quantities using polynomial
//! fitting of osculating jets*, CAGD 22(2), 2005; the constant term lets the jet pass below
//! a noisy vertex instead of through it). The normal and shape tensor follow from the gradient
//! and Hessian at the origin with the gradient terms ([`crate::fit`] module docs), so a tilted
//! first normal costs no accuracy.
//!
//! **Why degree 2.** A noisy mesh needs wide neighbourhoods, and the variance of a jet's
//! second derivatives grows quickly with its degree at a fixed radius (each higher monomial is
//! nearly collinear with the lower ones over a disc). Degree 2 is the lowest degree that carries
//! curvature; its bias is `O(r)` (`O(r²)` on symmetric neighbourhoods, Cazals–Pouget Theorem 2).
//!
//! # Noise and standard errors
//!
//! With heights `zₖ = f(xₖ, yₖ) + εₖ`, independent `εₖ` of variance `σ²`, the least-squares
//! coefficients have covariance `σ² (AᵀA)⁻¹` (Gauss–Markov; `A` the Vandermonde matrix), so the
//! standard error of the Hessian entry `f_xx = 2c₃` is `2σ √((AᵀA)⁻¹)₃₃` (and likewise for
//! `f_xy = c₄`, `f_yy = 2c₅`), in the units of the coordinates.
//!
//! **The noise level** `σ` is estimated once per mesh from the residuals of the unweighted fits
//! at two radii `r_a = 2ℓ` and `r_b = 2r_a` (`ℓ` the vertex's mean edge length). The residual
//! variance `s² = RSS/(m − 6)` of a fit is the noise variance plus the misfit of the jet, whose
//! leading term is the cubic part of the surface: `s²(r) ≈ σ² + a r⁶`. Two radii eliminate `a`:
//! `σ² ≈ (2⁶ s_a² − s_b²)/(2⁶ − 1)`, clamped at zero (misfit of higher order, as on symmetric
//! surfaces whose cubic term vanishes, only lowers the estimate). The mesh's `σ̂` is the median
//! over its vertices: noise is a property of the scanner, and the median ignores the minority of
//! vertices on creases or thin parts where the model fails. A mesh of more than
//! [`NOISE_SAMPLE`] vertices is measured on that many, evenly strided.
//!
//! **Is a mesh noisy?** ([`NoiseLevel::is_noisy`], which decides whether [`crate::HYBRID`]
//! hands a mesh to this estimator.) Misfit that grows more slowly than `r⁶` — at creases, on
//! needles and caps of a badly triangulated CAD part, on a coarse scan — leaks into `σ̂`. Two
//! further conditions guard against it. *Coverage*: at least [`MIN_COVERAGE`] of the vertices
//! must give an estimate (a ball that is a height field, with a misfit below
//! [`MAX_NOISE_RESIDUAL`]); noise is everywhere on a scan. *Agreement*: the vertex's offset
//! `e_v = −c₀` from its wider jet is, under noise alone, its own noise less an average of its
//! ball's (variance `σ² (1 − h_vv)`, `h_vv ≈ 6/m` its leverage), nearly independent between
//! neighbours, so the nugget of the offsets' variogram over edges (each sampled vertex with its first neighbour),
//! `γ = median ½(e_u − e_v)² / 0.455` (the χ²₁ median, for normal offsets), measures `σ` too;
//! a smooth misfit makes neighbouring offsets alike and a jumpy one (a needle among good
//! triangles) makes them unlike, and the two measures disagree. The mesh is noisy when
//! `σ̂ >` [`NOISY`] mean edge lengths, the coverage holds and `γ ≤` [`MAX_NUGGET_RATIO`] `σ̂`.
//! Measured: all 24 noisy meshes of the `estimation` study are noisy, none of their 32
//! noise-free twins, and none of the 14 meshes of `data/meshes` and `data/cad`.
//!
//! # Robust weights
//!
//! Scans carry outliers. After the least-squares fit at a radius, every point gets Huber's
//! weight `w = min(1, c σ̂ / |residual|)` with `c =` [`HUBER`] (Huber, *Robust estimation of a
//! location parameter*, Ann. Math. Stat. 35, 1964: 95 % efficiency under Gaussian noise) and
//! the jet is refitted with those weights: one step of iteratively reweighted least squares from
//! the least-squares start, which bounds the pull of a far outlier to `c σ̂`. The standard errors
//! are then taken from `(AᵀWA)⁻¹`, the weighted fit's covariance up to the efficiency factor.
//! The radius rule below compares the unweighted fits (whose standard errors are exactly
//! Gauss–Markov's), and only the fit at the chosen radius is reweighted: on the study's noisy
//! meshes this is 2.2–2.7 times faster than reweighting every radius and as accurate (K RMS
//! within −11 % … +3 % of it, 24 of 24 meshes still within the target).
//!
//! # The radius: intersection of confidence intervals
//!
//! A wider ball averages more noise away (the standard error of the curvature falls like
//! `σ / (r² √m)`, `m ∝ r²` points) but sees more of the surface's change (the bias grows with
//! `r`). The radius is chosen per vertex by Lepski's method in the form of the *intersection of
//! confidence intervals* rule (Goldenshluger & Nemirovski, *On spatially adaptive estimation of
//! nonparametric regression*, Math. Methods Statist. 6, 1997; Katkovnik, *A new method for
//! varying adaptive bandwidth selection*, IEEE Trans. Signal Process. 47(9), 1999): over the
//! radii of [`LADDER`] in increasing order, each Hessian entry's estimate `θⱼ` gives the interval
//! `[θⱼ − Γ seⱼ, θⱼ + Γ seⱼ]` (`Γ =` [`ICI_GAMMA`]); the radius taken is the largest whose
//! intervals, for all three entries, still meet every smaller radius's. While the bias is below
//! the noise the intervals keep meeting and the radius grows; once the bias shows, they part.
//! On a noise-free mesh `σ̂ ≈ 0`, the intervals are points, and the smallest radius is taken.

use mesh::Mesh;
use nalgebra::{Matrix3, Vector3};
use rayon::prelude::*;

use crate::fit::{solve_normal_equations, tangent_basis, HeightDerivatives, MAX_COEFFS};
use crate::jet::{fit_at, VertexResult, FIRST_WEIGHTING};
use crate::normals::{vertex_normals_with, Normals};
use crate::topology::RingMarks;
use crate::{
    finish, given_normal, project_shape, Estimate, Estimator, Fallback, FallbackKind, PlanarReason,
    Topology, JET,
};

/// The radii tried by [`MULTISCALE`], in mean edge lengths at the vertex, increasing: from
/// about the 1-ring (1.5) to about libigl's default neighbourhood of 5 rings and beyond (8.5,
/// about 260 points on a regular mesh), each about 1.35 times the last so that neighbouring
/// radii's estimates are close enough to compare.
pub const LADDER: [f64; 8] = [1.5, 2.0, 2.75, 3.75, 5.0, 6.5, 8.5, 11.0];

/// At most this many points (the vertex included) in a ball: bounds the work where the mesh is
/// much finer than its mean edge length around a vertex (a fan of slivers). The largest
/// [`LADDER`] ball on a regular mesh holds about 440.
pub const MAX_BALL_POINTS: usize = 1000;

/// Width of the confidence intervals of the radius rule, in standard errors: Katkovnik's
/// recommended range is 1.5–3; at 2 an interval holds a noise-only estimate with 95 %
/// probability.
pub const ICI_GAMMA: f64 = 2.0;

/// Huber's constant, in noise standard deviations: 95 % efficiency at Gaussian noise.
pub const HUBER: f64 = 1.345;

/// A fit needs at least this many points per coefficient (as [`crate::jet`]).
const POINTS_PER_COEFFICIENT: usize = 2;

/// Coefficients of the degree-2 jet with constant term.
const COEFFS: usize = 6;

/// The two radii (in mean edge lengths) of the noise estimate; the second is twice the first.
pub const NOISE_RADII: [f64; 2] = [2.0, 4.0];

/// `s²(r) ≈ σ² + a r⁶`: the misfit's growth from the first to the second radius of
/// [`NOISE_RADII`], `2⁶`.
const MISFIT_GROWTH: f64 = 64.0;

/// A vertex whose residual standard deviation at the larger noise radius exceeds this many
/// mean edge lengths is left out of the noise estimate: its ball is not a height field of a
/// smooth surface plus noise below half an edge (on the coarsest data sets, sphere level 1 or
/// the 16 × 8 ring, a ball of four edge lengths spans much of the object and its misfit stops
/// growing like `r⁶`, which the two-radius estimate would take for noise). The study's noisiest
/// meshes (η = 0.2) have about 0.17.
pub const MAX_NOISE_RESIDUAL: f64 = 0.5;

/// The noise level, in mean edge lengths, above which [`crate::HYBRID`] treats a mesh as
/// noisy: a quarter of a scanner's 0.02 edge lengths of uniform noise (standard deviation
/// 0.0115). Noise-free meshes of the `estimation` study measure 0 (the misfit's growth is
/// cancelled exactly) and noisy ones at least 0.0086.
pub const NOISY: f64 = 0.003;

/// A first normal turned by more than 60° from the frame's (`cos 60° = ½`) marks a point
/// beyond a height field over the frame.
const TURNED_COSINE: f64 = 0.5;

/// The largest fraction of turned points ([`TURNED_COSINE`]) in an admissible ball: a few
/// folded triangles of a noisy scan turn single normals, a ball round a tube turns many.
pub const MAX_TURNED_FRACTION: f64 = 0.25;

/// The fraction of a mesh's vertices that must give a noise estimate for the mesh to count as
/// noisy: a scan's noise is everywhere, while on coarse, creased or badly triangulated meshes
/// (the CAD corpus, the coarse scans: 5–78 % of vertices) many balls are not height fields or
/// their misfit exceeds [`MAX_NOISE_RESIDUAL`], and the estimate of the rest is misfit the
/// two-radius model does not cancel. The `estimation` study's noisy meshes: 97–100 %.
pub const MIN_COVERAGE: f64 = 0.9;

/// The largest ratio of the variogram's nugget to the two-radius estimate for a noisy mesh.
/// For noise alone both measure `σ` (the study's noisy meshes: 1.05–1.09 from η = 0.05 on,
/// 1.45–1.79 at η = 0.02, where misfit adds to the nugget); on the CAD corpus they disagree by
/// up to 7×.
pub const MAX_NUGGET_RATIO: f64 = 2.0;

/// At most this many vertices are measured for the noise level (evenly strided over a larger
/// mesh, each with its first neighbour for the variogram): a median and a coverage fraction
/// from 4096 samples are within a few per cent of the whole mesh's, and the estimate's cost
/// stays flat (about 8000 pairs of small fits) however large the mesh.
pub const NOISE_SAMPLE: usize = 4096;

/// The median of the χ² distribution with one degree of freedom: `½(e_u − e_v)²` of two
/// independent normal offsets of variance `σ²` has median `0.455 σ²`.
const CHI2_1_MEDIAN: f64 = 0.454_936_423_119_572_8;

/// The jet at one radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScaleFit {
    /// The radius of the ball.
    pub radius: f64,
    /// Points in the ball (the vertex included).
    pub points: usize,
    /// Gradient and Hessian of the height at the origin, in the units of the mesh.
    pub derivs: HeightDerivatives,
    /// Standard errors of `f_xx`, `f_xy`, `f_yy` per unit noise standard deviation.
    pub unit_se: [f64; 3],
    /// `RSS / (m − 6)` of the unweighted fit, in squared units of the mesh.
    pub residual_variance: f64,
    /// The jet's height at the origin `c₀` (units of the mesh): the vertex lies `−c₀` from
    /// the fitted surface along the frame normal.
    pub offset: f64,
}

/// Per-thread buffers of [`ladder`].
#[derive(Clone, Debug, Default)]
pub struct ScaleWorkspace {
    ring: Vec<usize>,
    marks: RingMarks,
    /// Scaled distance, scaled local coordinates and whether the first normal is turned away
    /// from the frame's ([`ladder`]), sorted by distance.
    points: Vec<(f64, [f64; 3], bool)>,
    /// The ring jet's buffers, for its fallback.
    jet: crate::fit::Workspace,
    /// The fits of the last [`ladder`] call.
    pub fits: Vec<ScaleFit>,
}

type Gram = [[f64; MAX_COEFFS]; MAX_COEFFS];

fn monomials(p: &[f64; 3]) -> [f64; COEFFS] {
    let (x, y) = (p[0], p[1]);
    [1.0, x, y, x * x, x * y, y * y]
}

/// Adds `w · rowᵀ row` (upper triangle) and `w · row z` of point `p`.
fn accumulate(g: &mut Gram, rhs: &mut [f64; MAX_COEFFS], p: &[f64; 3], w: f64) {
    let row = monomials(p);
    for i in 0..COEFFS {
        let wi = w * row[i];
        rhs[i] += wi * p[2];
        for j in i..COEFFS {
            g[i][j] += wi * row[j];
        }
    }
}

/// The coefficients of the normal equations `G c = r`, `None` when `G` is not numerically
/// positive definite or too ill-conditioned ([`solve_normal_equations`]).
fn solve(g: &Gram, rhs: &[f64; MAX_COEFFS]) -> Option<[f64; COEFFS]> {
    let (mut g, mut r) = (*g, *rhs);
    let mut c = [0.0; COEFFS];
    solve_normal_equations(&mut g, &mut r, COEFFS, &mut c)?;
    Some(c)
}

/// `(G⁻¹)ᵢᵢ` for the Hessian coefficients `i = 3, 4, 5`: column `i` of `G⁻¹` solves
/// `G x = eᵢ`.
fn inverse_diagonal(g: &Gram) -> Option<[f64; 3]> {
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let mut e = [0.0; MAX_COEFFS];
        e[3 + k] = 1.0;
        let x = solve(g, &e)?;
        *o = x[3 + k];
    }
    out.iter().all(|x| *x > 0.0 && x.is_finite()).then_some(out)
}

fn residual(c: &[f64; COEFFS], p: &[f64; 3]) -> f64 {
    let row = monomials(p);
    p[2] - row.iter().zip(c).map(|(a, b)| a * b).sum::<f64>()
}

/// The jets of vertex `v` at the radii `radii` (increasing, in units of the mesh) into
/// `ws.fits`, in the frame of the unit normal `n0` (module docs). `sigma > 0` refits each with
/// Huber weights for noise level `sigma`. A radius whose ball holds fewer than twice as many
/// points as coefficients, or whose fit is ill-conditioned, is left out; and with first normals
/// `first`, one whose ball is not a height field over the frame: more than
/// [`MAX_TURNED_FRACTION`] of its points have a first normal turned more than 60° from `n0`
/// (a ball that wraps around a thin tube, or reaches round a sharp bend).
#[allow(clippy::too_many_arguments)]
pub fn ladder(
    mesh: &Mesh,
    topo: &Topology,
    v: usize,
    n0: &Vector3<f64>,
    first: Option<&[Vector3<f64>]>,
    radii: &[f64],
    sigma: f64,
    ws: &mut ScaleWorkspace,
) {
    ws.fits.clear();
    let Some(&outer) = radii.last() else { return };
    let verts = mesh.vertices();
    let Some(origin) = verts.get(v).map(|x| x.data.p) else {
        return;
    };
    if !(outer > 0.0 && outer.is_finite()) {
        return;
    }
    topo.ball_into(v, mesh, outer, MAX_BALL_POINTS, &mut ws.ring, &mut ws.marks);
    let (t1, t2) = tangent_basis(n0);
    ws.points.clear();
    for &u in &ws.ring {
        let d = (verts[u].data.p - origin) / outer;
        let turned = first
            .and_then(|f| f.get(u))
            .is_some_and(|n| n.dot(n0) < TURNED_COSINE);
        ws.points
            .push((d.norm(), [d.dot(&t1), d.dot(&t2), d.dot(n0)], turned));
    }
    ws.points.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let mut g: Gram = [[0.0; MAX_COEFFS]; MAX_COEFFS];
    let mut rhs = [0.0; MAX_COEFFS];
    let mut end = 0;
    let mut turned = 0usize;
    let sigma_scaled = sigma / outer;
    for &r in radii {
        let new_end = ws.points.partition_point(|p| p.0 <= r / outer);
        for (_, p, t) in &ws.points[end..new_end] {
            accumulate(&mut g, &mut rhs, p, 1.0);
            turned += usize::from(*t);
        }
        end = new_end;
        let m = end;
        if m < POINTS_PER_COEFFICIENT * COEFFS || turned as f64 > MAX_TURNED_FRACTION * m as f64 {
            continue;
        }
        let Some(c) = solve(&g, &rhs) else { continue };
        let pts = &ws.points[..m];
        let rss: f64 = pts.iter().map(|(_, p, _)| residual(&c, p).powi(2)).sum();
        let (c, inv) = if sigma_scaled > 0.0 {
            let mut gw: Gram = [[0.0; MAX_COEFFS]; MAX_COEFFS];
            let mut rw = [0.0; MAX_COEFFS];
            let cut = HUBER * sigma_scaled;
            for (_, p, _) in pts {
                let e = residual(&c, p).abs();
                let w = if e > cut { cut / e } else { 1.0 };
                accumulate(&mut gw, &mut rw, p, w);
            }
            match (solve(&gw, &rw), inverse_diagonal(&gw)) {
                (Some(cw), Some(inv)) => (cw, inv),
                _ => continue,
            }
        } else {
            match inverse_diagonal(&g) {
                Some(inv) => (c, inv),
                None => continue,
            }
        };
        let o2 = outer * outer;
        ws.fits.push(ScaleFit {
            radius: r,
            points: m,
            derivs: HeightDerivatives {
                grad: [c[1], c[2]],
                hess: [2.0 * c[3] / outer, c[4] / outer, 2.0 * c[5] / outer],
            },
            unit_se: [
                2.0 * inv[0].sqrt() / o2,
                inv[1].sqrt() / o2,
                2.0 * inv[2].sqrt() / o2,
            ],
            residual_variance: rss / (m - COEFFS) as f64 * o2,
            offset: c[0] * outer,
        });
    }
}

/// Radius (in mean edge lengths) of the plane fit that gives the frame normal
/// ([`frame_normal`]): about two rings, whose normal is `O(σ / (r √m))` off under noise.
pub const FRAME_RADIUS: f64 = 2.5;

/// The normal of the frame of the fits at vertex `v`: the normal of the total-least-squares
/// plane (the eigenvector of the smallest eigenvalue of the covariance, Pearson 1901) of the
/// ball of radius `radius` around `v`, oriented along the sum of the first normals `first` over
/// the ball. On a noisy or folded mesh one vertex's own angle-weighted normal can be far off
/// (tens of degrees where a noisy triangle folds over), and a height field over a badly tilted
/// frame is ill-posed; the plane of two rings is not. Falls back to `first[v]` where the ball
/// is too small or degenerate.
pub fn frame_normal(
    mesh: &Mesh,
    topo: &Topology,
    v: usize,
    first: &[Vector3<f64>],
    radius: f64,
    ws: &mut ScaleWorkspace,
) -> Vector3<f64> {
    let own = first.get(v).copied().unwrap_or_else(Vector3::z);
    topo.ball_into(
        v,
        mesh,
        radius,
        MAX_BALL_POINTS,
        &mut ws.ring,
        &mut ws.marks,
    );
    if ws.ring.len() < 4 {
        return own;
    }
    let verts = mesh.vertices();
    let origin = verts[v].data.p;
    let m = ws.ring.len() as f64;
    let mut mean = Vector3::zeros();
    let mut orient = Vector3::zeros();
    for &u in &ws.ring {
        mean += (verts[u].data.p - origin) / m;
        orient += first.get(u).copied().unwrap_or_else(Vector3::zeros);
    }
    let mut cov = Matrix3::zeros();
    for &u in &ws.ring {
        let d = verts[u].data.p - origin - mean;
        cov += d * d.transpose();
    }
    let eig = cov.symmetric_eigen();
    let (k, _) = eig
        .eigenvalues
        .iter()
        .enumerate()
        .fold(
            (0, f64::INFINITY),
            |b, (i, &x)| if x < b.1 { (i, x) } else { b },
        );
    let n = eig.eigenvectors.column(k).into_owned();
    let sorted = {
        let mut e = [eig.eigenvalues[0], eig.eigenvalues[1], eig.eigenvalues[2]];
        e.sort_by(f64::total_cmp);
        e
    };
    // A ball spread along a line only (or a non-finite one) has no plane.
    if !(sorted[1] > 0.0 && n.iter().all(|c| c.is_finite())) || sorted[0] >= sorted[1] {
        return own;
    }
    let reference = if orient.norm() > 0.0 { orient } else { own };
    if n.dot(&reference) < 0.0 {
        -n
    } else {
        n
    }
}

/// The index into `fits` (increasing radii) that the intersection-of-confidence-intervals rule
/// takes for noise level `sigma` and width `gamma` (module docs); `None` for no fits.
pub fn ici(fits: &[ScaleFit], sigma: f64, gamma: f64) -> Option<usize> {
    if fits.is_empty() {
        return None;
    }
    if !(sigma > 0.0 && sigma.is_finite()) {
        // Noise-free: the intervals are points, and whether two estimates "meet" would be
        // decided by rounding; the smallest radius is the rule's answer by definition.
        return Some(0);
    }
    let mut lo = [f64::NEG_INFINITY; 3];
    let mut hi = [f64::INFINITY; 3];
    let mut chosen = None;
    for (j, f) in fits.iter().enumerate() {
        for i in 0..3 {
            let half = gamma * sigma * f.unit_se[i];
            lo[i] = lo[i].max(f.derivs.hess[i] - half);
            hi[i] = hi[i].min(f.derivs.hess[i] + half);
        }
        if (0..3).any(|i| lo[i] > hi[i]) {
            break;
        }
        chosen = Some(j);
    }
    chosen
}

/// The mean length of the edges at each vertex (0 at an isolated vertex).
pub(crate) fn mean_incident_edge(mesh: &Mesh) -> Vec<f64> {
    let n = mesh.num_vertices();
    let mut len = vec![0.0f64; n];
    let mut count = vec![0usize; n];
    let verts = mesh.vertices();
    for e in mesh.edges() {
        let [a, b] = e.vertices;
        let l = (verts[b].data.p - verts[a].data.p).norm();
        for v in [a, b] {
            len[v] += l;
            count[v] += 1;
        }
    }
    len.iter_mut()
        .zip(&count)
        .for_each(|(l, c)| *l /= (*c).max(1) as f64);
    len
}

/// What [`noise_level`] measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoiseLevel {
    /// The noise standard deviation `σ̂` (units of the mesh): the median of the per-vertex
    /// estimates (module docs).
    pub sigma: f64,
    /// The noise standard deviation from the variogram of the vertices' offsets from their
    /// jets at the larger radius of [`NOISE_RADII`] (its nugget, module docs): blind to misfit
    /// that varies smoothly along the surface, which the two-radius model `sigma` can take
    /// for noise on coarse or badly triangulated meshes.
    pub nugget: f64,
    /// Median residual standard deviation at the smaller radius of [`NOISE_RADII`].
    pub residual_small: f64,
    /// Median residual standard deviation at the larger radius.
    pub residual_large: f64,
    /// Vertices of the sample ([`NOISE_SAMPLE`]) that gave an estimate.
    pub vertices: usize,
    /// Vertices of the sample that could have (those with faces and edges).
    pub candidates: usize,
    /// The median of the vertices' mean edge lengths.
    pub edge: f64,
}

impl NoiseLevel {
    /// True when the mesh is a noisy one (module docs): the noise exceeds [`NOISY`] mean edge
    /// lengths, at least [`MIN_COVERAGE`] of its vertices gave an estimate, and the variogram's
    /// nugget agrees ([`MAX_NUGGET_RATIO`]).
    pub fn is_noisy(&self) -> bool {
        self.sigma > NOISY * self.edge
            && self.vertices as f64 >= MIN_COVERAGE * self.candidates as f64
            && self.nugget <= MAX_NUGGET_RATIO * self.sigma
    }
}

fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let mid = values.len() / 2;
    let (_, m, _) = values.select_nth_unstable_by(mid, f64::total_cmp);
    *m
}

/// The mesh's noise level (module docs), from the first normals `first` and mean edge lengths
/// `ell`.
pub fn noise_level(
    mesh: &Mesh,
    topo: &Topology,
    first: &[Vector3<f64>],
    ell: &[f64],
) -> NoiseLevel {
    // The two-radius variance, the two residual variances and the offset from the wider jet
    // of one vertex; `None` where it gives no estimate.
    let measure = |ws: &mut ScaleWorkspace, v: usize| -> Option<[f64; 4]> {
        let (Some(n0), Some(&l)) = (first.get(v), ell.get(v)) else {
            return None;
        };
        if topo.faces(v).is_empty() || !(l > 0.0 && l.is_finite()) {
            return None;
        }
        let radii = NOISE_RADII.map(|r| r * l);
        ladder(mesh, topo, v, n0, Some(first), &radii, 0.0, ws);
        match ws.fits.as_slice() {
            [a, b]
                if a.radius < b.radius
                    && b.residual_variance <= (MAX_NOISE_RESIDUAL * l).powi(2) =>
            {
                let (sa, sb) = (a.residual_variance, b.residual_variance);
                let s2 = ((MISFIT_GROWTH * sa - sb) / (MISFIT_GROWTH - 1.0)).max(0.0);
                Some([s2, sa, sb, b.offset])
            }
            _ => None,
        }
    };
    // The sample (module docs): every vertex of a small mesh, evenly strided ones of a large
    // one; each with its first neighbour, the pair giving one term of the variogram.
    let nv = mesh.num_vertices();
    let sampled: Vec<usize> = if nv <= NOISE_SAMPLE {
        (0..nv).collect()
    } else {
        (0..NOISE_SAMPLE).map(|k| k * nv / NOISE_SAMPLE).collect()
    };
    let per_vertex: Vec<(bool, Option<[f64; 4]>, Option<f64>)> = sampled
        .par_iter()
        .with_min_len(64)
        .map_init(ScaleWorkspace::default, |ws, &v| {
            let candidate = !topo.faces(v).is_empty() && ell.get(v).is_some_and(|l| *l > 0.0);
            let own = measure(ws, v);
            let pair = own.and_then(|x| {
                let u = *topo.neighbours(v).first()? as usize;
                let y = measure(ws, u)?;
                Some(0.5 * (x[3] - y[3]).powi(2))
            });
            (candidate, own, pair)
        })
        .collect();
    let col = |k: usize| {
        let mut xs: Vec<f64> = per_vertex
            .iter()
            .filter_map(|x| x.1)
            .map(|x| x[k])
            .collect();
        median(&mut xs).sqrt()
    };
    let mut halves: Vec<f64> = per_vertex.iter().filter_map(|x| x.2).collect();
    let nugget = (median(&mut halves) / CHI2_1_MEDIAN).sqrt();
    NoiseLevel {
        sigma: col(0),
        nugget,
        residual_small: col(1),
        residual_large: col(2),
        vertices: per_vertex.iter().filter(|x| x.1.is_some()).count(),
        candidates: per_vertex.iter().filter(|x| x.0).count(),
        edge: median(&mut ell.iter().copied().filter(|l| *l > 0.0).collect::<Vec<_>>()),
    }
}

/// [`noise_level`] of a mesh from scratch (its topology, first normals — angle-weighted where
/// `given` has none — and edge lengths).
pub fn mesh_noise(mesh: &Mesh, given: Option<&[Vector3<f64>]>) -> NoiseLevel {
    let topo = Topology::new(mesh);
    let first = vertex_normals_with(mesh, &topo, FIRST_WEIGHTING, given);
    noise_level(mesh, &topo, &first.normals, &mean_incident_edge(mesh))
}

/// The multi-scale (or fixed-radius) robust jet estimator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Multiscale {
    /// Registered name.
    pub name: &'static str,
    /// One line for reports.
    pub description: &'static str,
    /// `Some(r)`: the one radius `r` (in mean edge lengths at the vertex); `None`: [`LADDER`]
    /// with the radius rule.
    pub radius: Option<f64>,
}

/// `multiscale`: the radius chosen per vertex from [`LADDER`] (module docs).
pub static MULTISCALE: Multiscale = Multiscale {
    name: "multiscale",
    description: "degree-2 jets on balls of 1.5 to 11 edge lengths, Huber-weighted, radius per vertex by intersecting confidence intervals",
    radius: None,
};

/// The name of [`Multiscale::ball`]'s estimators (and of `--radius` in reports).
pub const BALL_NAME: &str = "jet-ball";

impl Multiscale {
    /// The degree-2 jet on one ball of `radius` mean edge lengths at each vertex (`--radius`),
    /// Huber-weighted for the mesh's noise level.
    pub fn ball(radius: f64) -> Self {
        Multiscale {
            name: BALL_NAME,
            description: "degree-2 jet on a Euclidean ball of a chosen radius, Huber-weighted",
            radius: Some(radius),
        }
    }

    /// The normal of vertex `v`'s fitting frame: the given normal where there is one, else
    /// [`frame_normal`] (the first normal where `v` has no faces or edges). Computed once per
    /// vertex and shared by the radius rule and the fit.
    fn frame(
        mesh: &Mesh,
        topo: &Topology,
        first: &[Vector3<f64>],
        given: Option<&[Vector3<f64>]>,
        ell: &[f64],
        v: usize,
        ws: &mut ScaleWorkspace,
    ) -> Vector3<f64> {
        let own = first.get(v).copied().unwrap_or_else(Vector3::z);
        let l = ell.get(v).copied().unwrap_or(0.0);
        if given_normal(given, v).is_some()
            || topo.faces(v).is_empty()
            || !(l > 0.0 && l.is_finite())
        {
            return own;
        }
        frame_normal(mesh, topo, v, first, FRAME_RADIUS * l, ws)
    }

    /// The radius (in mean edge lengths at `v`) the radius rule takes at vertex `v` from
    /// [`LADDER`] in the frame of `n0`, for noise level `sigma`; `None` where no radius gives a
    /// fit.
    #[allow(clippy::too_many_arguments)]
    fn rule_radius(
        mesh: &Mesh,
        topo: &Topology,
        first: &[Vector3<f64>],
        ell: &[f64],
        sigma: f64,
        v: usize,
        n0: &Vector3<f64>,
        ws: &mut ScaleWorkspace,
    ) -> Option<f64> {
        let l = ell.get(v).copied().filter(|l| *l > 0.0)?;
        if topo.faces(v).is_empty() {
            return None;
        }
        let radii = LADDER.map(|r| r * l);
        ladder(mesh, topo, v, n0, Some(first), &radii, 0.0, ws);
        ici(&ws.fits, sigma, ICI_GAMMA).map(|i| ws.fits[i].radius / l)
    }

    /// The fit at vertex `v` on the ball of `radius` mean edge lengths at `v` in the frame of
    /// `n0`, for noise level `sigma` (module docs); the ring jet where no radius was chosen or
    /// the fit fails, planar where that fails too.
    #[allow(clippy::too_many_arguments)]
    fn fit_one(
        mesh: &Mesh,
        topo: &Topology,
        first: &Normals,
        given: Option<&[Vector3<f64>]>,
        ell: &[f64],
        sigma: f64,
        v: usize,
        n0: Vector3<f64>,
        radius: Option<f64>,
        ws: &mut ScaleWorkspace,
    ) -> VertexResult {
        let normals = first.normals.as_slice();
        let own = normals.get(v).copied().unwrap_or_else(Vector3::z);
        let l = ell.get(v).copied().unwrap_or(0.0);
        if topo.faces(v).is_empty() || !(l > 0.0 && l.is_finite()) {
            return (own, Matrix3::zeros(), None);
        }
        let (t1, t2) = tangent_basis(&n0);
        let fitted = radius.and_then(|r| {
            ladder(mesh, topo, v, &n0, Some(normals), &[r * l], sigma, ws);
            ws.fits.first()?.derivs.normal_and_shape(&t1, &t2, &n0)
        });
        let Some((normal, shape)) = fitted else {
            // No admissible ball: the ring jet, whose neighbourhood follows the mesh's
            // connectivity (module docs).
            // Where that fails too, the tensor is planar, for too few points when the last
            // ball gathered (`ws.ring`) had fewer than a fit needs.
            let few = ws.ring.len() < POINTS_PER_COEFFICIENT * COEFFS;
            return match fit_at(mesh, topo, first, given, &JET.spec(), v, &mut ws.jet) {
                Some((n, s)) => (n, s, Some(FallbackKind::RingNeighbourhood)),
                None => (
                    own,
                    Matrix3::zeros(),
                    Some(FallbackKind::Planar {
                        reason: if few {
                            PlanarReason::TooFewNeighbours
                        } else {
                            PlanarReason::IllConditioned
                        },
                    }),
                ),
            };
        };
        let n = if given_normal(given, v).is_some() {
            own
        } else {
            normal
        };
        (n, project_shape(&shape, &n), None)
    }
}

impl Estimator for Multiscale {
    fn name(&self) -> &'static str {
        self.name
    }

    fn description(&self) -> &'static str {
        self.description
    }

    fn estimate(&self, mesh: &Mesh, given: Option<&[Vector3<f64>]>) -> Estimate {
        let topo = Topology::new(mesh);
        let first = vertex_normals_with(mesh, &topo, FIRST_WEIGHTING, given);
        let ell = mean_incident_edge(mesh);
        let sigma = noise_level(mesh, &topo, &first.normals, &ell).sigma;
        self.estimate_with(mesh, &topo, &first, &ell, sigma, given)
    }
}

impl Multiscale {
    /// [`Estimator::estimate`] from the mesh's topology, first normals (under
    /// [`FIRST_WEIGHTING`]), mean edge lengths and noise level.
    pub(crate) fn estimate_with(
        &self,
        mesh: &Mesh,
        topo: &Topology,
        first: &Normals,
        ell: &[f64],
        sigma: f64,
        given: Option<&[Vector3<f64>]>,
    ) -> Estimate {
        let nv = mesh.num_vertices();
        let frames: Vec<Vector3<f64>> = (0..nv)
            .into_par_iter()
            .with_min_len(256)
            .map_init(ScaleWorkspace::default, |ws, v| {
                Self::frame(mesh, topo, &first.normals, given, ell, v, ws)
            })
            .collect();
        // The radius per vertex: the rule's, median-filtered over the vertex and its
        // neighbours (module docs).
        let radius: Vec<Option<f64>> = match self.radius {
            Some(r) => vec![Some(r); nv],
            None => {
                let rule: Vec<Option<f64>> = (0..nv)
                    .into_par_iter()
                    .with_min_len(256)
                    .map_init(ScaleWorkspace::default, |ws, v| {
                        Self::rule_radius(mesh, topo, &first.normals, ell, sigma, v, &frames[v], ws)
                    })
                    .collect();
                (0..nv)
                    .into_par_iter()
                    .with_min_len(1024)
                    .map_init(Vec::new, |buf: &mut Vec<f64>, v| {
                        buf.clear();
                        buf.extend(rule[v]);
                        buf.extend(topo.neighbours(v).iter().filter_map(|&u| rule[u as usize]));
                        (!buf.is_empty()).then(|| median(buf))
                    })
                    .collect()
            }
        };
        let mut normals = vec![Vector3::z(); nv];
        let mut shapes = vec![Matrix3::zeros(); nv];
        let fits: Vec<Fallback> = normals
            .par_iter_mut()
            .zip(shapes.par_iter_mut())
            .enumerate()
            .with_min_len(256)
            .map_init(ScaleWorkspace::default, |ws, (v, (n_out, s_out))| {
                let (n, s, fb) = Self::fit_one(
                    mesh, topo, first, given, ell, sigma, v, frames[v], radius[v], ws,
                );
                *n_out = n;
                *s_out = s;
                fb.map(|kind| Fallback { vertex: v, kind })
            })
            .flatten()
            .collect();
        let mut fallbacks = first.fallbacks.clone();
        fallbacks.extend(fits);
        finish(normals, shapes, fallbacks, first)
    }
}

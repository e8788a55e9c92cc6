//! Tangent fans: the end tangents of a vertex's boundary curves chosen together, from its whole
//! star, wherever the per-edge rule leaves a face corner that is not convex.
//!
//! # Why
//!
//! Each edge's boundary problem ([`curves::BoundaryProblem`]) finds the end tangent at a
//! vertex from that edge's two end normals alone (the plane of the chord and the mean
//! normal, cut with the tangent plane). Nothing keeps the tangents of one vertex in the cyclic
//! order of its edges: where a fan does not project one to one onto the tangent plane (a cap,
//! a needle's tip, a normal leaning along an edge) two consecutive tangents can turn the wrong
//! way round, or a tangent is clamped out of the tangent plane
//! ([`curves::problem::MAX_TANGENT_ANGLE`]). A face corner whose two tangents do not make an
//! angle strictly between 0 and π counter-clockwise about the vertex normal cannot carry a G1
//! patch that interpolates the normal ([`crate::scheme::folded_corner`]): the face fell back to
//! C0.
//!
//! # The fan (Floater's normalized angles, in the tangent plane)
//!
//! For one sector (a vertex's whole star, or its faces between two creases or a crease and the
//! mesh boundary) with unit normal `n`, faces `F_0 … F_{m−1}` in counter-clockwise order and
//! edges `E_0 … E_m` between them (`E_j` leaves through `F_j`, `E_{j+1}` arrives; on a closed
//! star `E_m = E_0`):
//!
//! * the corner angles of the data, `θ_j = ∠(E_j, E_{j+1})` in space (each in `(0, π)` for a
//!   face of non-zero area), are scaled to the sector's total `Φ`: `φ_j = Φ θ_j / Σθ` (the
//!   normalization of geodesic polar maps, Welch & Witkin 1994; Floater 1997, "Parametrization
//!   and smooth approximation of surface triangulations", §5). `Φ = 2π` on a closed star; on an
//!   open one the angle from the first to the last edge's fixed tangent (crease lines, shared
//!   with the next sector) or, where an end is free (a boundary edge), `Σθ`;
//! * no `φ_j` may reach π (a corner would stop being convex): angles over [`MAX_CORNER`] are
//!   set to it and the rest rescaled to keep the total, repeated until none is over (water
//!   filling; feasible while `Φ < m ·` [`MAX_CORNER`], else the sector is counted as
//!   unfannable and left as it was);
//! * the direction of edge `E_j` is the unit vector at angle `c_j = Σ_{i<j} φ_i` from the first
//!   one, turned about `n`. A fixed end fixes the turn. On a free star the turn `ρ` minimizes
//!   `Σ w_j (1 − cos(ψ_j − c_j − ρ))`, `ψ_j` the angle of `E_j`'s chord projected onto the
//!   tangent plane and `w_j` that projection's length (a chord along the normal has no
//!   direction to keep): `ρ = atan2(Σ w_j sin(ψ_j − c_j), Σ w_j cos(ψ_j − c_j))`, the weighted
//!   circular mean.
//!
//! Every tangent is in the tangent plane (`⊥ n` to rounding), consecutive ones are in the
//! edges' cyclic order, and every corner angle is in `(0, π)`: every corner passes the test the
//! schemes apply. On a fan that projects one to one with nearly equal angles the directions are
//! close to the projected chords; where it does not, they are the closest convex fan in this
//! sense.
//!
//! Only sectors with a failing corner get a fan, and of those not the ones whose normal is at
//! 90° or more from one of their faces (the G1 schemes refuse such a face whatever its
//! tangents; the per-edge rule's clamp keeps its curves near the chords, where the fallback
//! patch does not fold): everywhere else the curves are the per-edge rule's, bit for bit.
//! A turned curve keeps its end-derivative length ([`curves::apply_tangents`])
//! shortened, if need be, by the monotone-polygon bound ([`curves::problem::monotone_bound`])
//! for the new tangents.

use curves::{apply_tangents, CubicBez3};
use nalgebra::Vector3;
use rayon::prelude::*;

use crate::mesh::Mesh;
use crate::scheme::OFF_PLANE_SINE;

/// The largest corner angle a fan gives a face: 175°. A corner of π has its two tangents
/// opposite, and the patch's corner cross vector `β(a + b)` no longer points into the face;
/// 5° short of it keeps the Chiyokura–Kimura decomposition's cross component at
/// `sin 5° ≈ 0.087` of the legs' lengths.
pub const MAX_CORNER: f64 = std::f64::consts::PI * 35.0 / 36.0;

/// The smallest data corner angle the normalization uses (radians): a face of zero area has a
/// corner of zero (or NaN) angle, and such a face still needs a positive share of the fan for
/// its neighbours' corners to stay convex. One microradian is far below any corner of a face
/// with area (the mesh's zero-area test, `mesh::mesh::DEGENERATE_FACE_SINE`, is coarser).
pub const MIN_DATA_ANGLE: f64 = 1e-6;

/// What the fans did in one fit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct FanCounts {
    /// Face corners whose two boundary tangents failed the corner test (not strictly convex
    /// about the vertex normal, or off the tangent plane) with the per-edge tangents.
    pub corners_failing_before: usize,
    /// Face corners that fail it after the fans.
    pub corners_failing_after: usize,
    /// Sectors (a vertex's star, or its faces between creases) given a fan.
    pub sectors_fanned: usize,
    /// Sectors with a failing corner that could not be given one: a fixed crease tangent off
    /// the tangent plane, an angle to fill of `m ·` [`MAX_CORNER`] or more, a star the
    /// half-edges do not walk in one piece.
    pub sectors_unfannable: usize,
    /// Straight crease corners: sectors of a single face between two crease edges whose
    /// (fixed) tangents are opposite, so no fan exists. Their two crease curves are given one
    /// direction and one length there (the crease C1 through the vertex), and the scheme builds
    /// the face with its straight-corner form (`surface::shirman_sequin`, "Straight crease
    /// corners"); their corners still fail the corner test, and are counted in
    /// `corners_failing_after`.
    pub sectors_straight: usize,
    /// Sectors with a failing corner whose normal is at 90° or more from one of their faces:
    /// those faces are refused by the G1 schemes whatever the tangents, and the sector keeps
    /// the per-edge rule's (clamped) tangents, which keep the fallback patch's curves close to
    /// the chords.
    pub sectors_facing_away: usize,
    /// Curve ends whose tangent the fans turned.
    pub tangents_turned: usize,
}

/// The smallest sine of a convex corner's angle: `√ε`-size, as the construction's own
/// degeneracy threshold (`surface::shirman_sequin::DEGENERATE`). Two crease tangents on one
/// crease line are opposite to rounding, and their cross product's sign is rounding's: such a
/// straight corner is not convex, whatever that sign (the scheme's decomposition fails there).
pub const CONVEX_SINE: f64 = crate::shirman_sequin::DEGENERATE;

/// The corner test: two tangents at a corner with normal `n`, both in the tangent plane
/// (`|t̂ · n̂| ≤` [`OFF_PLANE_SINE`]) and `(t̂_leaving × t̂_arriving) · n̂ >` [`CONVEX_SINE`]: the
/// angle from the leaving to the arriving tangent counter-clockwise about `n` strictly between
/// 0 and π, by more than rounding. The schemes' own test ([`crate::scheme::folded_corner`]) is
/// the same without the margin.
pub fn corner_is_convex(leaving: &Vector3<f64>, arriving: &Vector3<f64>, n: &Vector3<f64>) -> bool {
    // Squared, so no square root is taken: |t · n| ≤ s |t| |n| ⇔ (t · n)² ≤ s² |t|² |n|².
    let nn = n.norm_squared();
    let in_plane = |t: &Vector3<f64>| {
        let tn = t.dot(n);
        tn * tn <= OFF_PLANE_SINE * OFF_PLANE_SINE * t.norm_squared() * nn
    };
    let turn = leaving.cross(arriving).dot(n);
    in_plane(leaving)
        && in_plane(arriving)
        && turn > 0.0
        && turn * turn
            > CONVEX_SINE * CONVEX_SINE * leaving.norm_squared() * arriving.norm_squared() * nn
}

/// The fan's corner angles (module docs): `theta` the data's corner angles (each floored at
/// [`MIN_DATA_ANGLE`]) scaled to sum to `total`, none above [`MAX_CORNER`]. `None` when that
/// cannot be (`total` not in `(0, m · MAX_CORNER)`, or not finite).
pub fn fan_angles(theta: &[f64], total: f64) -> Option<Vec<f64>> {
    let m = theta.len();
    if m == 0 || !(total > 0.0 && total < m as f64 * MAX_CORNER) {
        return None;
    }
    let mut phi: Vec<f64> = theta
        .iter()
        .map(|t| {
            if t.is_finite() {
                t.max(MIN_DATA_ANGLE)
            } else {
                MIN_DATA_ANGLE
            }
        })
        .collect();
    let mut capped = vec![false; m];
    // Water filling: each round caps at least one more angle or ends, so m rounds suffice.
    for _ in 0..=m {
        let fixed = capped.iter().filter(|&&c| c).count() as f64 * MAX_CORNER;
        let free: f64 = phi
            .iter()
            .zip(&capped)
            .filter(|(_, c)| !**c)
            .map(|(p, _)| p)
            .sum();
        let scale = (total - fixed) / free;
        let mut changed = false;
        for (p, c) in phi.iter_mut().zip(capped.iter_mut()) {
            if *c {
                continue;
            }
            *p *= scale;
            if *p > MAX_CORNER {
                *p = MAX_CORNER;
                *c = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let sum: f64 = phi.iter().sum();
    let ok = phi.iter().all(|p| *p > 0.0 && *p <= MAX_CORNER)
        && (sum - total).abs() <= 1e-12 * total.max(1.0);
    ok.then_some(phi)
}

/// The signed angle of `v` in the tangent-plane basis `(e1, e2)`.
fn angle_in(v: &Vector3<f64>, e1: &Vector3<f64>, e2: &Vector3<f64>) -> f64 {
    v.dot(e2).atan2(v.dot(e1))
}

/// An end of an open sector: its tangent fixed (a crease edge, shared with the next sector) or
/// free (a boundary edge).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FanEnd {
    /// The edge's tangent is fixed: the unit direction leaving the vertex.
    Fixed(Vector3<f64>),
    /// The edge's tangent may turn.
    Free,
}

/// The directions (unit, leaving the vertex, in the plane `⊥ n`) of a sector's edges
/// `E_0 … E_m` (module docs). `chords` are the edges' directions from the vertex (any length),
/// `m + 1` of them; `ends` is `None` for a closed star (then `chords[m]` is `chords[0]` again)
/// and the two ends of an open one otherwise. `None` when no convex fan exists.
pub fn fan_directions(
    n: &Vector3<f64>,
    chords: &[Vector3<f64>],
    ends: Option<[FanEnd; 2]>,
) -> Option<Vec<Vector3<f64>>> {
    let m = chords.len().checked_sub(1)?;
    let n = n.try_normalize(0.0)?;
    // The data's corner angles in space.
    let theta: Vec<f64> = chords
        .windows(2)
        .map(|w| w[0].cross(&w[1]).norm().atan2(w[0].dot(&w[1])))
        .collect();
    let theta_sum: f64 = theta.iter().map(|t| t.max(MIN_DATA_ANGLE)).sum();
    // A tangent-plane basis: the first fixed end, else the first chord with a projection.
    let project = |v: &Vector3<f64>| v - n * v.dot(&n);
    let fixed = |e: &FanEnd| match e {
        FanEnd::Fixed(t) => Some(project(t).try_normalize(0.0)),
        FanEnd::Free => None,
    };
    let (first, last) = match ends {
        None => (None, None),
        Some([a, b]) => (fixed(&a), fixed(&b)),
    };
    // A fixed tangent with no projection (along the normal) cannot start a fan.
    if matches!(first, Some(None)) || matches!(last, Some(None)) {
        return None;
    }
    let (first, last) = (first.flatten(), last.flatten());
    let e1 = match (first, last) {
        (Some(t), _) => t,
        (None, Some(t)) => t,
        (None, None) => {
            // The chord that leans least along the normal (its projection is not rounding
            // noise), else any direction in the plane.
            let best = chords
                .iter()
                .filter_map(|c| {
                    let l = c.norm();
                    (l > 0.0 && l.is_finite()).then(|| (project(c).norm() / l, c))
                })
                .max_by(|a, b| a.0.total_cmp(&b.0))
                .filter(|(r, _)| *r > 1e-6)
                .map(|(_, c)| *c);
            let a = best.unwrap_or(if n.x.abs() < 0.9 {
                Vector3::x()
            } else {
                Vector3::y()
            });
            project(&a).try_normalize(0.0)?
        }
    };
    // Once more into the plane: a projection's rounding is relative to what was projected.
    let e1 = project(&e1).try_normalize(0.0)?;
    let e2 = n.cross(&e1);
    let tau = std::f64::consts::TAU;
    let total = match (ends, first, last) {
        (None, _, _) => tau,
        (Some(_), Some(a), Some(b)) => {
            // Counter-clockwise from the first fixed tangent to the last, in (0, 2π].
            let t = angle_in(&b, &e1, &e2) - angle_in(&a, &e1, &e2);
            let t = t.rem_euclid(tau);
            if t == 0.0 {
                tau
            } else {
                t
            }
        }
        _ => theta_sum.min(m as f64 * MAX_CORNER * (1.0 - 1e-9)),
    };
    let phi = fan_angles(&theta, total)?;
    let mut c = Vec::with_capacity(m + 1);
    let mut acc = 0.0;
    c.push(0.0);
    for p in &phi {
        acc += p;
        c.push(acc);
    }
    let start = match (first, last) {
        (Some(_), _) => 0.0,
        (None, Some(b)) => angle_in(&b, &e1, &e2) - total,
        (None, None) => {
            let (mut s, mut k) = (0.0, 0.0);
            for (chord, cj) in chords
                .iter()
                .zip(&c)
                .take(if ends.is_none() { m } else { m + 1 })
            {
                let p = project(chord);
                let w = p.norm();
                if w > 0.0 && w.is_finite() {
                    let d = angle_in(&p, &e1, &e2) - cj;
                    s += w * d.sin();
                    k += w * d.cos();
                }
            }
            if s == 0.0 && k == 0.0 {
                0.0
            } else {
                s.atan2(k)
            }
        }
    };
    let mut out: Vec<Vector3<f64>> = c
        .iter()
        .map(|cj| {
            let (sn, cs) = (start + cj).sin_cos();
            e1 * cs + e2 * sn
        })
        .collect();
    // Fixed ends exactly as given (projected: the fan's plane is n's).
    if let Some(a) = first {
        out[0] = a;
    }
    if let Some(b) = last {
        out[m] = b;
    }
    if ends.is_none() {
        out[m] = out[0];
    }
    Some(out)
}

/// The unit tangent with which `curve` leaves its start (`end = 0`) or enters its end
/// (`end = 1`), in the direction of travel; zero when that end derivative vanishes.
fn travel_tangent(curve: &CubicBez3, end: usize) -> Vector3<f64> {
    let p = curve.points;
    let d = if end == 0 { p[1] - p[0] } else { p[3] - p[2] };
    d.try_normalize(0.0).unwrap_or_else(Vector3::zeros)
}

/// The tangent of mesh edge `e`'s curve leaving vertex `v` (one of its ends).
fn leaving(mesh: &Mesh, curves: &[CubicBez3], e: usize, v: usize) -> Vector3<f64> {
    let edge = mesh.edge(e);
    if edge.vertices[0] == v {
        travel_tangent(&curves[e], 0)
    } else {
        -travel_tangent(&curves[e], 1)
    }
}

/// The unit normal of corner `c` of face `f` (its sector's, or its vertex's).
fn corner_normal(mesh: &Mesh, f: usize, c: usize) -> Option<Vector3<f64>> {
    match mesh.sectors() {
        Some(s) => s.normal(s.slot(f, c)?).copied(),
        None => mesh
            .vertices()
            .get(*mesh.faces().get(f)?.get(c)?)
            .map(|v| v.data.n),
    }
}

/// Which corners of face `f` fail the corner test with `curves` (a face whose curves cannot
/// be read fails none: it is not the fan's to judge).
fn face_fails(mesh: &Mesh, curves: &[CubicBez3], f: usize) -> [bool; 3] {
    let Ok(edges) = crate::fit::face_curves(mesh, curves, f) else {
        return [false; 3];
    };
    std::array::from_fn(|c| {
        let leaving = edges[c].points[1] - edges[c].points[0];
        let k = (c + 2) % 3;
        let arriving = edges[k].points[2] - edges[k].points[3];
        corner_normal(mesh, f, c).is_some_and(|n| !corner_is_convex(&leaving, &arriving, &n))
    })
}

/// The failing corners of every face, as `3 f + c`.
fn failing_corners(mesh: &Mesh, curves: &[CubicBez3]) -> Vec<usize> {
    (0..mesh.num_faces())
        .into_par_iter()
        .flat_map_iter(|f| {
            let fails = face_fails(mesh, curves, f);
            (0..3).filter(move |&c| fails[c]).map(move |c| 3 * f + c)
        })
        .collect()
}

/// The slot (sector) of corner `c` of face `f`, or 0 without sectors.
fn slot_of(mesh: &Mesh, f: usize, c: usize) -> usize {
    mesh.sectors().and_then(|s| s.slot(f, c)).unwrap_or(0)
}

/// A sector's new tangents: (mesh edge, unit direction leaving the vertex).
type Turns = Vec<(usize, Vector3<f64>)>;

/// Why a sector with a failing corner got no fan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Unfannable {
    /// Its normal is at 90° or more from one of its faces.
    FacingAway,
    /// No convex fan exists on its fixed ends, or its star could not be walked.
    NoFan,
    /// A single face between two crease edges (mesh edges `[0]`, `[1]`) whose fixed tangents
    /// are opposite: a straight crease corner ([`FanCounts::sectors_straight`]).
    Straight([usize; 2]),
}

/// The new tangents (mesh edge, unit direction leaving `v`) of the sector of corner `(f, c)`,
/// or why it has none.
fn sector_fan(mesh: &Mesh, curves: &[CubicBez3], f: usize, c: usize) -> Result<Turns, Unfannable> {
    sector_fan_inner(mesh, curves, f, c).unwrap_or(Err(Unfannable::NoFan))
}

/// [`sector_fan`], `None` where the star cannot be walked or has no fan.
fn sector_fan_inner(
    mesh: &Mesh,
    curves: &[CubicBez3],
    f: usize,
    c: usize,
) -> Option<Result<Turns, Unfannable>> {
    let v = mesh.faces()[f][c];
    let slot = slot_of(mesh, f, c);
    let n = corner_normal(mesh, f, c)?;
    // The star, counter-clockwise, and each face's corner at v.
    let star: Vec<(usize, usize)> = mesh
        .faces_around_vertex(v)
        .into_iter()
        .filter_map(|g| Some((g, mesh.faces()[g].iter().position(|&x| x == v)?)))
        .collect();
    if !star.iter().any(|&(g, _)| g == f) {
        return None;
    }
    let k = star.len();
    // Whether face i is followed by face i + 1 across a shared edge (its arriving edge).
    let joined = |i: usize, j: usize| {
        let (g, gc) = star[i];
        let (h, hc) = star[j];
        mesh.edge_index(g, (gc + 2) % 3).ok() == mesh.edge_index(h, hc).ok()
    };
    let in_slot: Vec<bool> = star
        .iter()
        .map(|&(g, gc)| slot_of(mesh, g, gc) == slot)
        .collect();
    let closed_star = k > 2 && joined(k - 1, 0);
    // The run of the sector's faces: start after a face not in the slot (or not joined).
    let start = if in_slot.iter().all(|&s| s) && closed_star {
        None
    } else {
        let begins = |i: usize| {
            in_slot[i] && {
                let p = (i + k - 1) % k;
                !(in_slot[p] && (i > 0 || closed_star) && joined(p, i))
            }
        };
        Some((0..k).find(|&i| begins(i))?)
    };
    let (run, closed): (Vec<(usize, usize)>, bool) = match start {
        None => (star.clone(), true),
        Some(s) => {
            let mut run = vec![star[s]];
            let mut i = s;
            loop {
                let j = (i + 1) % k;
                if j == s || !in_slot[j] || (j == 0 && !closed_star) || !joined(i, j) {
                    break;
                }
                run.push(star[j]);
                i = j;
            }
            (run, false)
        }
    };
    if !run.iter().any(|&(g, _)| g == f) {
        return None;
    }
    // A normal at 90° or more from a face of its sector: that face is refused by the G1
    // schemes whatever its tangents (`SchemeError::NormalAgainstFace`), and tangents in that
    // tangent plane would stand across the face, where the per-edge rule's clamp keeps them
    // within `MAX_TANGENT_ANGLE` of the chords for the fallback patch.
    if run.iter().any(|&(g, _)| {
        mesh.face_area_normal(g)
            .is_ok_and(|a| a.norm() > 0.0 && a.dot(&n) <= 0.0)
    }) {
        return Some(Err(Unfannable::FacingAway));
    }
    // Edges E_0 … E_m and their chords from v.
    let mut edges: Vec<usize> = Vec::with_capacity(run.len() + 1);
    edges.push(mesh.edge_index(run[0].0, run[0].1).ok()?);
    for &(g, gc) in &run {
        edges.push(mesh.edge_index(g, (gc + 2) % 3).ok()?);
    }
    let p = mesh.vertices()[v].data.p;
    let chords: Vec<Vector3<f64>> = edges
        .iter()
        .map(|&e| {
            let ev = mesh.edge(e).vertices;
            let other = if ev[0] == v { ev[1] } else { ev[0] };
            mesh.vertices()[other].data.p - p
        })
        .collect();
    // An open run ends at a boundary edge (free) or at an edge whose other face is in another
    // sector at v (a crease there: its curve is shared with that sector, so it is fixed).
    let ends = (!closed).then(|| {
        [edges[0], edges[edges.len() - 1]].map(|e| {
            if mesh.edge(e).second.is_some() {
                FanEnd::Fixed(leaving(mesh, curves, e, v))
            } else {
                FanEnd::Free
            }
        })
    });
    if let (1, Some([FanEnd::Fixed(a), FanEnd::Fixed(b)])) = (run.len(), ends) {
        if (a + b).norm() <= crate::shirman_sequin::STRAIGHT_SINE {
            return Some(Err(Unfannable::Straight([edges[0], edges[1]])));
        }
    }
    let dirs = fan_directions(&n, &chords, ends)?;
    let m = edges.len() - 1;
    let take = if closed { m } else { m + 1 };
    let free = |i: usize| match ends {
        None => true,
        Some([a, b]) => (i > 0 || a == FanEnd::Free) && (i < m || b == FanEnd::Free),
    };
    Some(Ok(edges
        .iter()
        .zip(&dirs)
        .take(take)
        .enumerate()
        .filter(|(i, _)| free(*i))
        .map(|(_, (&e, d))| (e, *d))
        .collect()))
}

/// The corner test on `curves` without changing them (for constructions that keep their own
/// tangents, [`curves::CurveMethod::keeps_own_tangents`]): before and after are the same.
pub fn count_failing(mesh: &Mesh, curves: &[CubicBez3]) -> FanCounts {
    let n = if curves.len() == mesh.num_edges() {
        failing_corners(mesh, curves).len()
    } else {
        0
    };
    FanCounts {
        corners_failing_before: n,
        corners_failing_after: n,
        ..FanCounts::default()
    }
}

/// Gives every sector with a failing corner its fan (module docs), turning the end tangents of
/// `curves` (one per mesh edge, along `mesh.edge(e).vertices`) and bounding their lengths;
/// `alphas` follow the curves. Returns what it did.
pub fn apply_fans(mesh: &Mesh, curves: &mut [CubicBez3], alphas: &mut [[f64; 2]]) -> FanCounts {
    let mut counts = FanCounts::default();
    if curves.len() != mesh.num_edges() {
        return counts;
    }
    let failing = failing_corners(mesh, curves);
    counts.corners_failing_before = failing.len();
    if failing.is_empty() {
        return counts;
    }
    // One representative corner per (vertex, slot).
    let mut keys: Vec<(usize, usize, usize)> = failing
        .iter()
        .map(|&fc| {
            let (f, c) = (fc / 3, fc % 3);
            (mesh.faces()[f][c], slot_of(mesh, f, c), fc)
        })
        .collect();
    keys.sort_unstable();
    keys.dedup_by_key(|k| (k.0, k.1));
    type Fan = Result<(usize, Turns), Unfannable>;
    let fans: Vec<Fan> = {
        let shared: &[CubicBez3] = curves;
        keys.par_iter()
            .map(|&(v, _, fc)| sector_fan(mesh, shared, fc / 3, fc % 3).map(|t| (v, t)))
            .collect()
    };
    // The new tangents, each at its (edge, vertex): each edge end belongs to one sector.
    let mut turned: Vec<(usize, usize, Vector3<f64>)> = Vec::new();
    let mut straight: Vec<(usize, [usize; 2])> = Vec::new();
    for (fan, &(v, _, _)) in fans.into_iter().zip(&keys) {
        match fan {
            Err(Unfannable::FacingAway) => counts.sectors_facing_away += 1,
            Err(Unfannable::NoFan) => counts.sectors_unfannable += 1,
            Err(Unfannable::Straight(pair)) => straight.push((v, pair)),
            Ok((v, tangents)) => {
                counts.sectors_fanned += 1;
                turned.extend(tangents.into_iter().map(|(e, d)| (e, v, d)));
            }
        }
    }
    for (e, v, d) in turned {
        if leaving(mesh, curves, e, v) == d {
            continue;
        }
        let end = usize::from(mesh.edge(e).vertices[0] != v);
        let mut lines = [None, None];
        lines[end] = Some(if end == 0 { d } else { -d });
        // The monotone-polygon bound for the new tangents (lengths in unit-chord form); a
        // curve of no chord has no lengths to bound, and is left as it is.
        let [p0, p1, p2, p3] = apply_tangents(&curves[e], lines).points;
        let chord = p3 - p0;
        let len = chord.norm();
        if !(len > 0.0 && len.is_finite()) {
            continue;
        }
        counts.tangents_turned += 1;
        let x = chord / len;
        let legs = [p1 - p0, p3 - p2];
        let alpha = legs.map(|l| 3.0 * l.norm() / len);
        let c = legs.map(|l| l.try_normalize(0.0).map_or(0.0, |t| t.dot(&x)));
        let (bounded, _) = curves::problem::monotone_bound(alpha, c);
        let scale = |i: usize| {
            if alpha[i] > 0.0 {
                bounded[i] / alpha[i]
            } else {
                1.0
            }
        };
        curves[e] = CubicBez3::new([p0, p0 + legs[0] * scale(0), p3 - legs[1] * scale(1), p3]);
        alphas[e] = bounded;
    }
    for (v, pair) in straight {
        if even_straight_corner(mesh, curves, alphas, v, pair) {
            counts.sectors_straight += 1;
        } else {
            counts.sectors_unfannable += 1;
        }
    }
    counts.corners_failing_after = failing_corners(mesh, curves).len();
    counts
}

/// Gives the two crease curves of a straight crease corner at `v` (mesh edges `pair`, whose
/// tangents leave `v` in opposite directions to within
/// [`crate::shirman_sequin::STRAIGHT_SINE`]) exactly opposite directions, their mean, and one
/// length, the shorter leg's: the crease is then C1 through `v`, the legs `a`, `b` of the face
/// between them satisfy `a + b = 0` to the rounding of `E − V`, and the scheme can build it
/// ([`FanCounts::sectors_straight`]). Shortening a leg keeps it within the monotone-polygon
/// bound it met. False (nothing changed) where a leg has no length or a curve no chord.
fn even_straight_corner(
    mesh: &Mesh,
    curves: &mut [CubicBez3],
    alphas: &mut [[f64; 2]],
    v: usize,
    pair: [usize; 2],
) -> bool {
    let end = |e: usize| usize::from(mesh.edge(e).vertices[0] != v);
    let leg = |c: &CubicBez3, end: usize| {
        let p = c.points;
        if end == 0 {
            p[1] - p[0]
        } else {
            p[2] - p[3]
        }
    };
    let legs = pair.map(|e| leg(&curves[e], end(e)));
    let chords = pair.map(|e| (curves[e].points[3] - curves[e].points[0]).norm());
    let len = legs[0].norm().min(legs[1].norm());
    if !(len > 0.0 && len.is_finite() && chords.iter().all(|c| *c > 0.0 && c.is_finite())) {
        return false;
    }
    let Some(d) = (legs[0].normalize() - legs[1].normalize()).try_normalize(0.0) else {
        return false;
    };
    for (k, (&e, sign)) in pair.iter().zip([1.0, -1.0]).enumerate() {
        let end = end(e);
        let p = &mut curves[e].points;
        if end == 0 {
            p[1] = p[0] + d * (sign * len);
        } else {
            p[2] = p[3] + d * (sign * len);
        }
        alphas[e][end] = 3.0 * len / chords[k];
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Closed forms in double precision: rounding only.
    const ROUNDING: f64 = 1e-12;

    #[test]
    fn angles_are_scaled_to_the_total_and_capped_below_pi() {
        let phi = fan_angles(&[1.0, 1.0, 2.0], 2.0).expect("feasible");
        assert!((phi[0] - 0.5).abs() < ROUNDING && (phi[2] - 1.0).abs() < ROUNDING);
        // A wide corner on a star of three: scaled, 3 would exceed MAX_CORNER and is capped.
        let phi = fan_angles(&[0.5, 0.5, 3.0], std::f64::consts::TAU).expect("feasible");
        assert!((phi[2] - MAX_CORNER).abs() < ROUNDING);
        assert!((phi.iter().sum::<f64>() - std::f64::consts::TAU).abs() < ROUNDING);
        assert!(phi.iter().all(|p| *p <= MAX_CORNER));
        // Two faces cannot close a star with convex corners.
        assert!(fan_angles(&[1.0, 1.0], std::f64::consts::TAU).is_none());
    }
}

//! Two rules on every sector's normal and shape tensor after the estimation, from the faces the
//! sector holds: **flat** sectors get their plane, and a normal **facing away** from one of its
//! faces is turned, as little as possible, until it faces all of them.
//!
//! # Flat sectors
//!
//! When every face of a sector (a vertex's star, or its faces between creases) has the same
//! unit normal up to [`FLAT_ANGLE`], the surface there is a plane whatever the estimator says
//! (an estimator that looks past the star — a jet on a ball, a multiscale ladder — sees the
//! curved region two edges away and tilts the normal): the sector gets the area-weighted mean
//! of its face normals and a zero shape tensor. A face whose three corners are so set, on
//! straight edge curves, is fitted by its own plane.
//!
//! # Normals that face their faces
//!
//! Every split-domain patch interpolates its corners' normals, so a normal at 90° or more from
//! a face it touches folds that face's patch at the corner
//! (`surface::shirman_sequin::SchemeError::NormalAgainstFace`): the face got the C0 fallback.
//! On scans this is an estimate that averaged over a thin feature (a fin, a claw, a lip seen
//! from both sides). The normal `n₀` is replaced by the unit vector nearest to it that keeps a
//! margin `δ` from every face's plane, `δ` a share ([`FACING_SHARE`]) of the widest margin any
//! unit vector has ([`widest_margin`]):
//!
//! `x* = argmin |x − n₀|²  subject to  N_f · x ≥ δ` (every face `f`), `n = x*/|x*|`. Every
//! constraint excludes `x = 0` (`δ > 0`), so `x* ≠ 0` and `N_f · n ≥ δ/|x*| > 0`: the turned
//! normal makes less than 90° with every face (`|x*|` need not be 1, so its margin is
//! `δ/|x*|`, not `δ`).
//!
//! The projection onto a polyhedron is a strictly convex quadratic program in three unknowns;
//! it is solved exactly by Seidel's incremental method for LP-type problems (Seidel 1991,
//! "Small-dimensional linear programming and convex hulls made easy"; the same argument holds
//! for a strictly convex objective, whose optimum is unique): constraints are added one at a
//! time, and when the current optimum violates the new one the optimum of the constraints so
//! far lies on its plane, found by the same method one dimension down (on at most three
//! planes, where the point is fixed). In a pseudo-random but fixed order of the faces the
//! expected work is linear in the faces. The problem has no solution exactly when the face
//! normals lie in no open hemisphere (the data folds over itself at the vertex): no normal
//! can face all the faces, the sector keeps its estimate and is counted.
//!
//! The shape tensor is projected onto the new tangent plane (`P S P`, `P = I − n nᵀ`) so that
//! `S n = 0` still holds. Normals the file gives are kept: a conflict is only counted.
//!
//! A sector with no facing normal is cut where the data folds ([`crate::fold_split`]) and the
//! rules run again on its pieces.

use mesh::Mesh;
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

/// The largest angle (radians) between two face normals of a sector for it to be flat:
/// 1e-6 rad. Faces of a plane written in single precision (PLY `float`, 2⁻²⁴ ≈ 6e-8 relative
/// rounding of coordinates in a unit box) on edges down to 1 % of the box tilt by up to
/// about 1e-5 rad… and one part in 10⁶ of a normal is a bump of 1e-8 over an edge of 1 %,
/// invisible, while the faces of a finely tessellated cylinder (the flattest curved CAD surface
/// in the corpus) turn by 1e-2 rad from one to the next. Measured on `data/cad`: the spread of
/// face normals in planar regions is at most 1.2e-7 rad.
pub const FLAT_ANGLE: f64 = 1e-6;

/// What [`face_the_faces`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct FacingSummary {
    /// Sectors whose faces are coplanar, given their plane's normal and a zero shape tensor.
    pub flat_sectors: usize,
    /// Estimated normals at 90° or more from a face of their sector, turned to face them all.
    pub normals_turned: usize,
    /// Sectors whose face normals lie in no open hemisphere: no normal faces them all.
    pub no_facing_normal: usize,
    /// Normals from the file at 90° or more from a face of their sector (kept as given).
    pub given_normals_against_faces: usize,
    /// Sectors with no facing normal cut at their sharpest edges into sectors that each have
    /// one ([`crate::fold_split`]).
    pub fold_sectors_cut: usize,
    /// Edges those cuts made creases.
    pub fold_edges_cut: usize,
}

/// The corners of the mesh grouped by sector: `(slot, face)` pairs, slot `v` for a mesh
/// without sectors.
fn slot_of(mesh: &Mesh, f: usize, c: usize) -> usize {
    match mesh.sectors() {
        Some(s) => s.slot(f, c).unwrap_or(usize::MAX),
        None => mesh.faces()[f][c],
    }
}

/// The number of slots (sectors, or vertices without sectors).
fn num_slots(mesh: &Mesh) -> usize {
    mesh.sectors()
        .map_or(mesh.num_vertices(), |s| s.num_slots())
}

/// The normal and shape tensor of slot `s`.
fn slot_data(mesh: &Mesh, s: usize) -> Option<(Vector3<f64>, Matrix3<f64>)> {
    match mesh.sectors() {
        Some(sec) => Some((*sec.normal(s)?, *sec.shape(s)?)),
        None => mesh.vertices().get(s).map(|v| (v.data.n, v.data.shape)),
    }
}

/// Sets slot `s`'s normal and shape tensor (and its vertex's, when the vertex has one slot).
fn set_slot(mesh: &mut Mesh, s: usize, n: Vector3<f64>, shape: Matrix3<f64>, single: &[bool]) {
    let vertex = match mesh.sectors_mut() {
        Some(sec) => {
            let v = sec.slot_vertex(s);
            sec.set_slot(s, n, shape, true);
            v
        }
        None => Some(s),
    };
    if let Some(v) = vertex {
        if single.get(v).copied().unwrap_or(false) {
            if let Some(vert) = mesh.vertices_mut().get_mut(v) {
                vert.data.n = n;
                vert.data.shape = shape;
                vert.curvature_known = true;
            }
        }
    }
}

/// `P S P` with `P = I − n nᵀ` (`n` unit).
pub(crate) fn project_shape(s: &Matrix3<f64>, n: &Vector3<f64>) -> Matrix3<f64> {
    let p = Matrix3::identity() - n * n.transpose();
    p * s * p
}

/// Applies both rules (module docs) to every sector of `mesh`. `normals_given`: the normals
/// came from the file (then they are kept; flat sectors get a zero shape tensor where the
/// given normal is the plane's to [`FLAT_ANGLE`], and conflicts are counted).
/// `curvature_given`: the shape tensors came from the file (then they are kept).
///
/// Sectors left with no facing normal (their faces in no open hemisphere) are cut where the
/// data folds ([`crate::fold_split`]) and both rules run again on the mesh so cut; the summary
/// counts the flat sectors and the sectors still without a facing normal of that second pass,
/// and the normals turned by both.
pub fn face_the_faces(
    mesh: &mut Mesh,
    normals_given: bool,
    curvature_given: bool,
) -> FacingSummary {
    let (first, unfixable) = facing_pass(mesh, normals_given, curvature_given);
    if unfixable.is_empty() {
        return first;
    }
    let split = crate::fold_split::split_folds(mesh, &unfixable);
    if split.edges_cut == 0 {
        return first;
    }
    let (second, _) = facing_pass(mesh, normals_given, curvature_given);
    FacingSummary {
        normals_turned: first.normals_turned + second.normals_turned,
        fold_sectors_cut: split.sectors_cut,
        fold_edges_cut: split.edges_cut,
        ..second
    }
}

/// One pass of both rules; also returns the slots left with no facing normal.
fn facing_pass(
    mesh: &mut Mesh,
    normals_given: bool,
    curvature_given: bool,
) -> (FacingSummary, Vec<usize>) {
    let mut summary = FacingSummary::default();
    let mut unfixable: Vec<usize> = Vec::new();
    let slots = num_slots(mesh);
    // Per slot: its faces' area vectors summed (then normalized in place: the mean normal, or
    // zero), its number of faces, and the least cosine of a face normal with the mean and with
    // the slot's own normal. 44 bytes a slot, freed on return.
    let mut mean = vec![Vector3::<f64>::zeros(); slots];
    let mut faces_of: Vec<u32> = vec![0; slots];
    for f in 0..mesh.num_faces() {
        let Ok(a) = mesh.face_area_normal(f) else {
            continue;
        };
        if a.norm() <= 0.0 || !a.norm().is_finite() {
            continue;
        }
        for c in 0..3 {
            let s = slot_of(mesh, f, c);
            if let Some(slot) = mean.get_mut(s) {
                *slot += a;
                faces_of[s] = faces_of[s].saturating_add(1);
            }
        }
    }
    for m in &mut mean {
        *m = m.try_normalize(0.0).unwrap_or_else(Vector3::zeros);
    }
    let mut min_mean = vec![f64::INFINITY; slots];
    let mut min_own = vec![f64::INFINITY; slots];
    for f in 0..mesh.num_faces() {
        let Some(nf) = mesh.face_unit_normal(f) else {
            continue;
        };
        for c in 0..3 {
            let s = slot_of(mesh, f, c);
            if s >= slots {
                continue;
            }
            min_mean[s] = min_mean[s].min(nf.dot(&mean[s]));
            let own = slot_data(mesh, s).map_or(Vector3::zeros(), |(n, _)| n);
            let len = own.norm();
            if len > 0.0 {
                min_own[s] = min_own[s].min(nf.dot(&own) / len);
            }
        }
    }
    // Whether each vertex has one slot (its own data then follows its slot's), made when a
    // slot is first set.
    let mut single: Vec<bool> = Vec::new();
    let single_of = |mesh: &Mesh| -> Vec<bool> {
        match mesh.sectors() {
            Some(sec) => sec
                .slots_per_vertex(mesh.num_vertices())
                .iter()
                .map(|&c| c == 1)
                .collect(),
            None => vec![true; mesh.num_vertices()],
        }
    };
    let flat_cos = FLAT_ANGLE.cos();
    let mut against: Vec<usize> = Vec::new();
    for s in 0..slots {
        if faces_of[s] == 0 {
            continue;
        }
        let Some((n0, _)) = slot_data(mesh, s) else {
            continue;
        };
        let m = mean[s];
        // One face is no evidence of a plane (a sector of one face on a curved surface).
        if faces_of[s] >= 2 && m != Vector3::zeros() && min_mean[s] >= flat_cos {
            let n = n0.try_normalize(0.0).unwrap_or(m);
            let set = if !normals_given {
                Some(m)
            } else if !curvature_given && n.dot(&m) >= flat_cos {
                Some(n0)
            } else {
                None
            };
            if let Some(normal) = set {
                if single.is_empty() {
                    single = single_of(mesh);
                }
                summary.flat_sectors += 1;
                set_slot(mesh, s, normal, Matrix3::zeros(), &single);
            }
            continue;
        }
        if min_own[s] <= 0.0 {
            if normals_given {
                summary.given_normals_against_faces += 1;
            } else {
                against.push(s);
            }
        }
    }
    drop((mean, min_mean, min_own, faces_of));
    if against.is_empty() {
        return (summary, unfixable);
    }
    // The faces of the slots whose normal faces away from one of them (few: a map).
    let want: std::collections::HashMap<usize, usize> =
        against.iter().enumerate().map(|(i, &s)| (s, i)).collect();
    let mut lists: Vec<Vec<Vector3<f64>>> = vec![Vec::new(); against.len()];
    for f in 0..mesh.num_faces() {
        let Some(nf) = mesh.face_unit_normal(f) else {
            continue;
        };
        for c in 0..3 {
            if let Some(&i) = want.get(&slot_of(mesh, f, c)) {
                lists[i].push(nf);
            }
        }
    }
    if single.is_empty() {
        single = single_of(mesh);
    }
    for (&s, faces) in against.iter().zip(&lists) {
        // A share of the widest margin any normal has (module docs).
        let Some(widest) = widest_margin(faces) else {
            summary.no_facing_normal += 1;
            unfixable.push(s);
            continue;
        };
        let delta = widest * FACING_SHARE;
        let Some((n0, shape0)) = slot_data(mesh, s) else {
            continue;
        };
        let n0 = n0.try_normalize(0.0).unwrap_or_else(Vector3::zeros);
        match facing_normal(&n0, faces, delta) {
            Some(n) => {
                summary.normals_turned += 1;
                set_slot(mesh, s, n, project_shape(&shape0, &n), &single);
            }
            None => {
                summary.no_facing_normal += 1;
                unfixable.push(s);
            }
        }
    }
    (summary, unfixable)
}

/// The share of the widest margin a turned normal keeps from every face's plane: one half. The
/// nearest normal that merely faces every face stands almost on edge to one of them, and its
/// patch folds near that corner; the normal of the widest margin (the axis of the smallest cone
/// holding the face normals) is the farthest from every face's plane but turns the estimate
/// furthest. Half is between the two. Measured on `dragon_res3` (optimized curves): a fixed
/// margin of 1° left 481 folded faces, half the widest margin 472.
pub const FACING_SHARE: f64 = 0.5;

/// The widest margin `max_{|n| = 1} min_f N_f · n` of `faces` (the cosine of the smallest
/// cone about one axis holding them all), `None` when it is not positive. With
/// `x* = argmin |x|²` subject to `N_f · x ≥ 1` (the projection of 0, by the same solver), the
/// margin is `1/|x*|`: scaling any unit `n` of margin `μ > 0` by `1/μ` is feasible, so
/// `|x*| ≤ 1/μ`, and `x*/|x*|` has margin `1/|x*|`.
pub fn widest_margin(faces: &[Vector3<f64>]) -> Option<f64> {
    let x = seidel(&Vector3::zeros(), &shuffled(faces), &[], 1.0)?;
    let len = x.norm();
    (len > 0.0 && len.is_finite()).then(|| 1.0 / len)
}

/// `faces` in a fixed pseudo-random order (a multiplicative hash of the index): the expected
/// work of the incremental method is linear in this order, and its result does not depend on
/// the order (the optimum is unique).
fn shuffled(faces: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    let mut order: Vec<usize> = (0..faces.len()).collect();
    order.sort_by_key(|&i| {
        (i as u64)
            .wrapping_mul(0x9E37_79B9_7F4A_7C15)
            .rotate_left(17)
    });
    order.iter().map(|&i| faces[i]).collect()
}

/// Tolerance of a constraint's check inside the incremental solver: the solutions are formed
/// from unit vectors by a few dozen operations, so rounding is below 1e-14; 1e-12 leaves room.
const FEASIBLE: f64 = 1e-12;

/// The unit normal nearest `n0` with `N_f · n ≥ δ` for every `faces` normal (module docs), or
/// `None` when the faces' normals lie in no open hemisphere.
pub fn facing_normal(
    n0: &Vector3<f64>,
    faces: &[Vector3<f64>],
    delta: f64,
) -> Option<Vector3<f64>> {
    let x = seidel(n0, &shuffled(faces), &[], delta)?;
    let n = x.try_normalize(0.0)?;
    faces.iter().all(|f| f.dot(&n) > 0.0).then_some(n)
}

/// [`facing_normal`] for a normal that must also be perpendicular to `lines` (unit or not: the
/// chords of a sector's crease edges, so that each crease tangent — the line both sectors'
/// tangent planes share — runs along its chord, [`crate::fold_split`]), with the margin a
/// [`FACING_SHARE`] of the widest such a normal has. One line: the problem restricted to the
/// plane `⊥ ℓ` (the face normals projected onto it; the solver's steps stay in the plane, and
/// with two constraints tight the point is fixed there, so a third violated one is
/// infeasibility). Two or more: the normal is `±ℓ₁ × ℓ₂` (the others must be perpendicular to
/// it), the sign facing the faces. `None` when no such normal faces every face.
pub fn facing_normal_across(
    n0: &Vector3<f64>,
    faces: &[Vector3<f64>],
    lines: &[Vector3<f64>],
) -> Option<Vector3<f64>> {
    let faces_all = |n: &Vector3<f64>| faces.iter().all(|f| f.dot(n) > 0.0);
    match lines {
        [] => {
            let delta = widest_margin(faces)? * FACING_SHARE;
            facing_normal(n0, faces, delta)
        }
        [l] => {
            let l = l.try_normalize(0.0)?;
            let p = |v: &Vector3<f64>| v - l * v.dot(&l);
            let projected: Vec<Vector3<f64>> = faces.iter().map(p).collect();
            let delta = widest_margin(&projected)? * FACING_SHARE;
            let x = seidel(&p(n0), &shuffled(&projected), &[], delta)?;
            let n = p(&x).try_normalize(0.0)?;
            faces_all(&n).then_some(n)
        }
        [a, b, rest @ ..] => {
            let n = a.cross(b).try_normalize(0.0)?;
            if rest.iter().any(|c| c.dot(&n).abs() > OFF_LINES * c.norm()) {
                return None;
            }
            [n, -n].into_iter().find(|n| faces_all(n))
        }
    }
}

/// The largest `|ℓ · n| / |ℓ|` of a third line for a normal `ℓ₁ × ℓ₂` to count as
/// perpendicular to it ([`facing_normal_across`]): `√ε`-size, rounding of the cross product.
const OFF_LINES: f64 = 1e-8;

/// The point of `{x : a·x = δ, a ∈ eq}` nearest `n0`: `x = n0 + Σ λ_a a` with the Gram system
/// `G λ = δ − A n0`. `None` when the planes do not meet in one affine subspace.
fn project_onto(n0: &Vector3<f64>, eq: &[Vector3<f64>], delta: f64) -> Option<Vector3<f64>> {
    match eq {
        [] => Some(*n0),
        [a] => {
            let aa = a.norm_squared();
            (aa > 0.0).then(|| n0 + a * ((delta - a.dot(n0)) / aa))
        }
        [a, b] => {
            let g = Matrix2::new(a.dot(a), a.dot(b), b.dot(a), b.dot(b));
            let r = Vector2::new(delta - a.dot(n0), delta - b.dot(n0));
            let l = g.try_inverse().filter(|_| g.determinant().abs() > 1e-30)? * r;
            Some(n0 + a * l.x + b * l.y)
        }
        [a, b, c] => {
            let m = Matrix3::from_rows(&[a.transpose(), b.transpose(), c.transpose()]);
            if m.determinant().abs() <= 1e-30 {
                return None;
            }
            m.try_inverse()
                .map(|inv| inv * Vector3::new(delta, delta, delta))
        }
        _ => None,
    }
}

/// Seidel's incremental method (module docs): the nearest point to `n0` on the planes `eq`
/// satisfying `a · x ≥ δ` for every `a` of `cons`.
fn seidel(
    n0: &Vector3<f64>,
    cons: &[Vector3<f64>],
    eq: &[Vector3<f64>],
    delta: f64,
) -> Option<Vector3<f64>> {
    let mut x = project_onto(n0, eq, delta)?;
    for i in 0..cons.len() {
        if cons[i].dot(&x) >= delta - FEASIBLE {
            continue;
        }
        if eq.len() == 3 {
            return None;
        }
        let mut tight: Vec<Vector3<f64>> = eq.to_vec();
        tight.push(cons[i]);
        x = seidel(n0, &cons[..i], &tight, delta)?;
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_normal_already_facing_its_faces_is_kept() {
        let faces = [Vector3::new(0.1, 0.0, 1.0).normalize(), Vector3::z()];
        let n = facing_normal(&Vector3::z(), &faces, 0.0).expect("feasible");
        assert!((n - Vector3::z()).norm() < 1e-15);
    }
}

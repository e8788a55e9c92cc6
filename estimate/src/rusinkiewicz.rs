//! Rusinkiewicz, *Estimating curvatures and their derivatives on triangle meshes*, 3DPVT 2004.
//!
//! 1. **Vertex normals** `n_i`: given, else Max-weighted ([`crate::normals`]; the paper's
//!    choice, exact on spheres).
//! 2. **Per face** (unit normal `n_f`, orthonormal face frame `u = e₂/|e₂|`, `w = n_f × u`):
//!    the second fundamental form `M = [[e, f], [f, g]]` of the face is the least-squares
//!    solution of `M (eᵢ·u, eᵢ·w)ᵀ = ((Δnᵢ)·u, (Δnᵢ)·w)ᵀ` over the three edges `eᵢ` (opposite
//!    corner `i`) and the differences `Δnᵢ` of the vertex normals along them (the paper's eq. 3:
//!    six equations, three unknowns; solved by the 3×3 normal equations by Cholesky, as the
//!    paper does by LDLᵀ). Since `Δn ≈ (D_e n)` and the workspace's sign makes
//!    `κn > 0` where the surface bends towards `n` (`dn = −S dp`), the face tensor is
//!    `S_f = −(e uuᵀ + f (uwᵀ + wuᵀ) + g wwᵀ)`. Computed once per face (in parallel) and kept
//!    for step 3, where each of the face's three corners reads it.
//! 3. **Per vertex**: each `S_f` of a face around `p` is rotated into `p`'s tangent plane by the
//!    rotation about `n_f × n_p` taking `n_f` to `n_p` (the paper's `rotate_coord_sys`; `n_f`
//!    is first flipped to the side of `n_p` so the rotation is at most 90°), and the tensors are
//!    averaged with the **Voronoi area** of `p` in each face as weight: Meyer, Desbrun, Schröder &
//!    Barr, *Discrete differential-geometry operators for triangulated 2-manifolds*, 2003, mixed
//!    areas — `(|pq|² cot r + |pr|² cot q)/8` in a non-obtuse triangle `pqr`, half the area when
//!    the angle at `p` is obtuse, a quarter when another is (Rusinkiewicz uses these weights).
//!
//! Zero-area faces, and faces whose normal equations are singular (not expected for a
//! non-degenerate triangle), contribute nothing; a vertex left without any weight gets `S = 0`
//! ([`FallbackKind::Planar`] with [`PlanarReason::NoArea`]).
//!
//! **Order.** Curvature errors are `O(h)` on irregular meshes and `O(h²)` on the regular data
//! sets (measured in `tests/suite/rusinkiewicz.rs`), the normal error that of the Max normals.

use mesh::Mesh;
use nalgebra::{Matrix3, Point3, Vector3};
use rayon::prelude::*;

use crate::normals::{face_unit_normal, vertex_normals_with, NormalWeighting, Normals};
use crate::{finish, Estimate, Estimator, Fallback, FallbackKind, PlanarReason, Topology};

/// The Rusinkiewicz estimator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rusinkiewicz {
    /// Weighting of the vertex normals when they are not given.
    pub weighting: NormalWeighting,
}

/// The registered `rusinkiewicz` (Max-weighted normals, as in the paper).
pub static RUSINKIEWICZ: Rusinkiewicz = Rusinkiewicz {
    weighting: NormalWeighting::Max,
};

/// The frame of step 2 of the face `(p0, p1, p2)`: its unit normal `n_f`, `u = e₂/|e₂|` and
/// `w = n_f × u`; `None` for a zero-area face.
fn face_frame(p: [&Point3<f64>; 3]) -> Option<[Vector3<f64>; 3]> {
    let nf = face_unit_normal(p[0], p[1], p[2])?;
    let u = (p[1] - p[0]).try_normalize(0.0)?;
    Some([nf, u, nf.cross(&u)])
}

/// The world tensor `−(a uuᵀ + b (uwᵀ + wuᵀ) + c wwᵀ)` of the form `(a, b, c)` in the frame
/// `(u, w)` (step 2).
fn form_tensor(u: &Vector3<f64>, w: &Vector3<f64>, [a, b, c]: [f64; 3]) -> Matrix3<f64> {
    -(u * u.transpose() * a + (u * w.transpose() + w * u.transpose()) * b + w * w.transpose() * c)
}

/// The second fundamental form `(e, f, g)` of the face `(p0, p1, p2)` with vertex normals
/// `(n0, n1, n2)` in its [`face_frame`] `[n_f, u, w]` (step 2); `None` for a singular system or
/// a tensor ([`form_tensor`]) with a non-finite entry.
fn face_form(
    p: [&Point3<f64>; 3],
    n: [&Vector3<f64>; 3],
    [_, u, w]: &[Vector3<f64>; 3],
) -> Option<[f64; 3]> {
    let e = [p[2] - p[1], p[0] - p[2], p[1] - p[0]];
    let dn = [n[2] - n[1], n[0] - n[2], n[1] - n[0]];
    // Normal equations of the 6×3 system in (e, f, g).
    let mut ata = Matrix3::zeros();
    let mut atb = Vector3::zeros();
    for i in 0..3 {
        let (eu, ew) = (e[i].dot(u), e[i].dot(w));
        let (du, dw) = (dn[i].dot(u), dn[i].dot(w));
        // Row (eu, ew, 0) → du ; row (0, eu, ew) → dw.
        let r1 = Vector3::new(eu, ew, 0.0);
        let r2 = Vector3::new(0.0, eu, ew);
        ata += r1 * r1.transpose() + r2 * r2.transpose();
        atb += r1 * du + r2 * dw;
    }
    let sol = ata.cholesky()?.solve(&atb);
    let form = [sol[0], sol[1], sol[2]];
    form_tensor(u, w, form)
        .iter()
        .all(|x| x.is_finite())
        .then_some(form)
}

/// The world tensor of a face `(p0, p1, p2)` with vertex normals `(n0, n1, n2)` (step 2) and its
/// unit normal; `None` for a zero-area face or a singular system.
pub fn face_tensor(
    p: [&Point3<f64>; 3],
    n: [&Vector3<f64>; 3],
) -> Option<(Matrix3<f64>, Vector3<f64>)> {
    let frame = face_frame(p)?;
    let form = face_form(p, n, &frame)?;
    let [nf, u, w] = frame;
    Some((form_tensor(&u, &w, form), nf))
}

/// Meyer et al.'s mixed (Voronoi) area of corner `p` in the triangle `(p, q, r)` (module docs).
pub fn mixed_area(p: &Point3<f64>, q: &Point3<f64>, r: &Point3<f64>) -> f64 {
    let (pq, pr, qr) = (q - p, r - p, r - q);
    let area = 0.5 * pq.cross(&pr).norm();
    if !(area > 0.0 && area.is_finite()) {
        return 0.0;
    }
    let dot_p = pq.dot(&pr);
    let dot_q = (-pq).dot(&qr);
    let dot_r = (-pr).dot(&(-qr));
    if dot_p < 0.0 {
        0.5 * area
    } else if dot_q < 0.0 || dot_r < 0.0 {
        0.25 * area
    } else {
        // cot q = dot_q / (2 area), cot r = dot_r / (2 area).
        (pr.norm_squared() * dot_q + pq.norm_squared() * dot_r) / (16.0 * area)
    }
}

/// The rotation taking the unit vector `a` to the unit vector `b` about `a × b` (Rodrigues):
/// `R = I + [v]ₓ + [v]ₓ²/(1 + c)`, `v = a × b`, `c = a·b`; callers ensure `c ≥ 0`.
fn rotation_between(a: &Vector3<f64>, b: &Vector3<f64>) -> Matrix3<f64> {
    let v = a.cross(b);
    let c = a.dot(b);
    let vx = v.cross_matrix();
    Matrix3::identity() + vx + vx * vx / (1.0 + c)
}

impl Estimator for Rusinkiewicz {
    fn name(&self) -> &'static str {
        "rusinkiewicz"
    }

    fn description(&self) -> &'static str {
        "per-face second fundamental forms from normal differences, Voronoi-averaged (Rusinkiewicz 2004)"
    }

    fn estimate(&self, mesh: &Mesh, given: Option<&[Vector3<f64>]>) -> Estimate {
        let topo = Topology::new(mesh);
        let first = vertex_normals_with(mesh, &topo, self.weighting, given);
        self.estimate_with(mesh, &topo, first)
    }
}

impl Rusinkiewicz {
    /// [`Estimator::estimate`] with the mesh's [`Topology`] and the vertex normals of step 1
    /// (`vertex_normals_with` under [`Rusinkiewicz::weighting`]) computed by the caller, who
    /// needs them too.
    pub(crate) fn estimate_with(&self, mesh: &Mesh, topo: &Topology, first: Normals) -> Estimate {
        let verts = mesh.vertices();
        let faces = mesh.faces();
        let normals = &first.normals;
        // Step 2's least-squares solve once per face, kept as the form (e, f, g) alone (24 B a
        // face; the tensor and the normal with it were 80), NaN where the face has none (a form
        // `face_form` gives is finite): each of the face's corners rebuilds the frame and the
        // tensor from it by the same operations (`face_tensor`'s), bit for bit.
        let forms: Vec<[f64; 3]> = faces
            .par_iter()
            .with_min_len(1024)
            .map(|face| {
                let p = face.map(|i| &verts[i].data.p);
                let n = face.map(|i| &normals[i]);
                face_frame(p)
                    .and_then(|frame| face_form(p, n, &frame))
                    .unwrap_or([f64::NAN; 3])
            })
            .collect();
        // Step 3, each vertex's tensor written in place; the vertices left without weight are
        // collected.
        let mut shapes = vec![Matrix3::zeros(); mesh.num_vertices()];
        let no_area: Vec<usize> = shapes
            .par_iter_mut()
            .enumerate()
            .with_min_len(256)
            .filter_map(|(v, out)| {
                if topo.faces(v).is_empty() {
                    return None;
                }
                let np = normals[v];
                let mut sum = Matrix3::zeros();
                let mut weight = 0.0;
                for f in topo.faces(v).iter().map(|&f| f as usize) {
                    let face = faces[f];
                    let Some(c) = face.iter().position(|&x| x == v) else {
                        continue;
                    };
                    let Some(&form) = forms.get(f).filter(|form| !form[0].is_nan()) else {
                        continue;
                    };
                    let p = face.map(|i| &verts[i].data.p);
                    let Some([mut nf, u, w]) = face_frame(p) else {
                        continue;
                    };
                    let s = form_tensor(&u, &w, form);
                    let w = mixed_area(p[c], p[(c + 1) % 3], p[(c + 2) % 3]);
                    if !(w > 0.0 && w.is_finite()) {
                        continue;
                    }
                    if nf.dot(&np) < 0.0 {
                        nf = -nf;
                    }
                    let r = rotation_between(&nf, &np);
                    sum += r * s * r.transpose() * w;
                    weight += w;
                }
                if weight > 0.0 {
                    *out = sum / weight;
                    None
                } else {
                    Some(v)
                }
            })
            .collect();
        // The face forms are used up: they go before the estimate is built.
        drop(forms);
        let mut fallbacks = first.fallbacks.clone();
        fallbacks.extend(no_area.into_iter().map(|vertex| Fallback {
            vertex,
            kind: FallbackKind::Planar {
                reason: PlanarReason::NoArea,
            },
        }));
        finish(normals.clone(), shapes, fallbacks, &first)
    }
}

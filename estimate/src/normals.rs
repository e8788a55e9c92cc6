//! Vertex normals from face normals.
//!
//! The normal at a vertex `v` is `Σ_f w_f n_f` normalized, over the faces `f` around `v`, with
//! `n_f` the unit normal of `f` (from its counter-clockwise orientation) and the weight `w_f`:
//!
//! * [`NormalWeighting::Angle`] — the corner angle of `f` at `v` (Thürmer & Wüthrich, *Computing
//!   vertex normals from polygonal facets*, JGT 3(1), 1998): independent of how the fan is
//!   triangulated;
//! * [`NormalWeighting::Area`] — the area of `f` (Gouraud's average weighted by area);
//! * [`NormalWeighting::Max`] — `sin θ / (|e1| |e2|)` with `θ` the corner angle and `e1`, `e2` the
//!   two edges at `v`, i.e. `(e1 × e2)/(|e1|² |e2|²)` summed (Max, *Weights for computing vertex
//!   normals from facet normals*, JGT 4(2), 1999): exact for vertices of a sphere; the weighting
//!   Rusinkiewicz (2004) uses.
//!
//! A face whose doubled area is at most [`mesh::mesh::DEGENERATE_FACE_SINE`] times the
//! product of its two longest edges (the mesh's own zero-area test) contributes nothing.
//!
//! **Fallbacks.** A vertex with no faces gets `+z` ([`FallbackKind::Isolated`]). A vertex whose
//! faces all have zero area (or whose weighted sum cancels) takes the normalized average of the
//! normals of the nearest vertices, in rings, that have one
//! ([`FallbackKind::NormalFromNeighbours`], spreading ring by ring through the vertex's
//! component); when its whole component has none it gets `+z`
//! ([`FallbackKind::DefaultNormal`]).

use mesh::mesh::DEGENERATE_FACE_SINE;
use mesh::Mesh;
use nalgebra::{Point3, Vector3};
use rayon::prelude::*;

use crate::{given_normal, Fallback, FallbackKind, Topology};

/// How face normals are weighted at a vertex (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum NormalWeighting {
    /// Corner angle (Thürmer & Wüthrich 1998).
    #[default]
    Angle,
    /// Face area.
    Area,
    /// `sin θ / (|e1| |e2|)` (Max 1999).
    Max,
}

/// Vertex normals with their fallbacks.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Normals {
    /// One unit normal per vertex.
    pub normals: Vec<Vector3<f64>>,
    /// Vertices whose normal is a fallback, sorted by vertex.
    pub fallbacks: Vec<Fallback>,
}

/// The unit normal of the triangle `(a, b, c)` (counter-clockwise), `None` when it has zero area
/// by the mesh's test (module docs).
pub fn face_unit_normal(a: &Point3<f64>, b: &Point3<f64>, c: &Point3<f64>) -> Option<Vector3<f64>> {
    unit_normal_and_doubled_area(a, b, c).map(|(n, _)| n)
}

/// [`face_unit_normal`] and the doubled area `|(b − a) × (c − a)|` it divides by.
///
/// The test needs the two longest edges: taken by comparisons rather than a sort of the three
/// lengths (the same two values; when a length is not finite neither is the area and the face
/// is refused either way).
fn unit_normal_and_doubled_area(
    a: &Point3<f64>,
    b: &Point3<f64>,
    c: &Point3<f64>,
) -> Option<(Vector3<f64>, f64)> {
    let (e1, e2) = (b - a, c - a);
    let cross = e1.cross(&e2);
    let (l0, l1, l2) = (e1.norm(), e2.norm(), (c - b).norm());
    let longest = l0.max(l1).max(l2);
    let middle = l0.min(l1).max(l0.max(l1).min(l2));
    let area2 = cross.norm();
    (area2 > DEGENERATE_FACE_SINE * middle * longest && area2.is_finite())
        .then(|| (cross / area2, area2))
}

/// The weighted face-normal sums at vertex `v` under each of `weightings` (not normalized;
/// zero when no face counts). Each corner's face normal, doubled area and edges are computed
/// once for all the weightings.
fn weighted_sums<const K: usize>(
    mesh: &Mesh,
    topo: &Topology,
    v: usize,
    weightings: &[NormalWeighting; K],
) -> [Vector3<f64>; K] {
    let verts = mesh.vertices();
    let faces = mesh.faces();
    let mut sums = [Vector3::zeros(); K];
    for f in topo.faces(v).iter().map(|&f| f as usize) {
        let face = faces[f];
        let Some(c) = face.iter().position(|&x| x == v) else {
            continue;
        };
        let p = &verts[v].data.p;
        let a = &verts[face[(c + 1) % 3]].data.p;
        let b = &verts[face[(c + 2) % 3]].data.p;
        // `area2` is `|e1 × e2|`, the corner's sine times its two edges.
        let Some((n, area2)) = unit_normal_and_doubled_area(p, a, b) else {
            continue;
        };
        let (e1, e2) = (a - p, b - p);
        for (sum, weighting) in sums.iter_mut().zip(weightings) {
            let w = match weighting {
                NormalWeighting::Angle => area2.atan2(e1.dot(&e2)),
                NormalWeighting::Area => 0.5 * area2,
                NormalWeighting::Max => area2 / (e1.norm_squared() * e2.norm_squared()),
            };
            if w.is_finite() {
                *sum += n * w;
            }
        }
    }
    sums
}

/// Vertex normals of `mesh` (module docs).
pub fn vertex_normals(mesh: &Mesh, weighting: NormalWeighting) -> Normals {
    vertex_normals_with(mesh, &Topology::new(mesh), weighting, None)
}

/// Vertex normals with a prebuilt [`Topology`]; `given` normals (when present and usable) are
/// kept as they are, normalized, and an unusable one is recorded
/// ([`FallbackKind::InvalidGivenNormal`]) and estimated.
pub fn vertex_normals_with(
    mesh: &Mesh,
    topo: &Topology,
    weighting: NormalWeighting,
    given: Option<&[Vector3<f64>]>,
) -> Normals {
    let [normals] = vertex_normals_many(mesh, topo, [weighting], given);
    normals
}

/// [`vertex_normals_with`] under several weightings in one pass over the corners (each corner's
/// face normal is computed once for all of them): the same normals and fallbacks, to the bit,
/// as one call per weighting.
pub fn vertex_normals_many<const K: usize>(
    mesh: &Mesh,
    topo: &Topology,
    weightings: [NormalWeighting; K],
    given: Option<&[Vector3<f64>]>,
) -> [Normals; K] {
    let nv = mesh.num_vertices();
    let raw: Vec<[Option<Vector3<f64>>; K]> = (0..nv)
        .into_par_iter()
        .map(|v| {
            if let Some(n) = given_normal(given, v) {
                return [Some(n); K];
            }
            weighted_sums(mesh, topo, v, &weightings).map(|s| {
                let len = s.norm();
                (len > 0.0 && len.is_finite()).then(|| s / len)
            })
        })
        .collect();
    std::array::from_fn(|k| complete(topo, given, raw.iter().map(|r| r[k])))
}

/// The normals of every vertex from the weighted ones (`None` where no face counted): given and
/// isolated vertices recorded, the missing ones spread from their neighbours (module docs).
fn complete(
    topo: &Topology,
    given: Option<&[Vector3<f64>]>,
    raw: impl ExactSizeIterator<Item = Option<Vector3<f64>>>,
) -> Normals {
    let nv = raw.len();
    let mut fallbacks = Vec::new();
    if given.is_some() {
        for v in 0..nv {
            if given_normal(given, v).is_none() {
                fallbacks.push(Fallback {
                    vertex: v,
                    kind: FallbackKind::InvalidGivenNormal,
                });
            }
        }
    }
    let mut known = Vec::with_capacity(nv);
    let mut normals: Vec<Vector3<f64>> = raw
        .map(|n| {
            known.push(n.is_some());
            n.unwrap_or_else(Vector3::z)
        })
        .collect();
    let mut pending: Vec<usize> = (0..nv)
        .filter(|&v| !known[v] && !topo.faces(v).is_empty())
        .collect();
    for v in (0..nv).filter(|&v| !known[v] && topo.faces(v).is_empty()) {
        fallbacks.push(Fallback {
            vertex: v,
            kind: FallbackKind::Isolated,
        });
    }
    // Spread ring by ring (Jacobi sweeps: a sweep only reads normals known before it).
    let mut rings = 0;
    while !pending.is_empty() {
        rings += 1;
        let found: Vec<(usize, Vector3<f64>)> = pending
            .iter()
            .filter_map(|&v| {
                let s: Vector3<f64> = topo
                    .neighbours(v)
                    .iter()
                    .filter(|&&u| known[u as usize])
                    .map(|&u| normals[u as usize])
                    .sum();
                let len = s.norm();
                (len > 0.0 && len.is_finite()).then(|| (v, s / len))
            })
            .collect();
        if found.is_empty() {
            break;
        }
        for &(v, n) in &found {
            normals[v] = n;
            known[v] = true;
            fallbacks.push(Fallback {
                vertex: v,
                kind: FallbackKind::NormalFromNeighbours { rings },
            });
        }
        pending.retain(|&v| !known[v]);
    }
    for v in pending {
        fallbacks.push(Fallback {
            vertex: v,
            kind: FallbackKind::DefaultNormal,
        });
    }
    fallbacks.sort();
    Normals { normals, fallbacks }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn max_weights_are_exact_on_the_sphere() {
        let data = mesh::datasets::sphere(2).expect("valid");
        /// Max's weights reproduce sphere normals up to rounding.
        const TOL: f64 = 1e-13;
        let n = vertex_normals(&data.mesh, NormalWeighting::Max);
        assert!(n.fallbacks.is_empty());
        for (est, v) in n.normals.iter().zip(data.mesh.vertices()) {
            assert!((est - v.data.n).norm() < TOL);
        }
    }
}

//! Loop subdivision (Loop 1987) of triangle meshes, with boundaries and tagged creases.
//!
//! # Rules
//!
//! With `p` a vertex, `q_1 … q_n` its neighbours (`n` = valence = number of edges):
//!
//! - **smooth and dart vertices**: `p' = (1 − nβ) p + β Σ q_i` with, by [`LoopWeights`],
//!   Loop's `β = (1/n)(5/8 − (3/8 + ¼ cos(2π/n))²)` or Warren's `β = 3/(8n)` (`n > 3`),
//!   `3/16` (`n = 3`). Both give `1/16` at the regular valence 6.
//! - **crease and boundary vertices** (exactly two sharp edges, to `a` and `b`):
//!   `p' = ⅛ a + ¾ p + ⅛ b`.
//! - **corners** (more than two sharp edges): `p' = p`.
//! - **smooth edges** `(a, b)` with opposite vertices `c, d`: `⅜(a + b) + ⅛(c + d)`.
//! - **sharp edges** (boundary or crease): `½(a + b)`.
//!
//! # Order of the output
//!
//! Vertices: the `V` old vertices first (same indices), then one per edge, `V + e` for edge `e`
//! in [`PolyMesh::edges`] order. Faces: triangle `(v0, v1, v2)` with edge points `m01, m12,
//! m20` becomes `(v0, m01, m20)`, `(v1, m12, m01)`, `(v2, m20, m12)`, `(m01, m12, m20)`, in that
//! order, face `f`'s children at `4f … 4f + 3`.
//!
//! # Limit stencils
//!
//! The one-ring `(p, q_1 … q_n)` of a smooth vertex is mapped to itself by a step with the
//! circulant subdivision matrix. Its rotationally symmetric part acts on `(p, q̄)`, `q̄` the ring
//! average: the new ring average is `⅜ p + ⅝ q̄` (each edge point is `⅜ p + ⅜ q_i + ⅛(q_{i−1} +
//! q_{i+1})`), so `(p, q̄) ↦ ((1 − nβ) p + nβ q̄, ⅜ p + ⅝ q̄)`, whose
//! left eigenvector for eigenvalue 1 is `(3/8, nβ)` up to scale, i.e. weight
//! `3/(3 + 8nβ) = 1 − nχ` on `p`. The left eigenvectors of the subdominant eigenvalue
//! `3/8 + ¼ cos(2π/n)` are the cosine and sine masks, giving the tangents
//! `t1 = Σ cos(2πi/n) q_i`, `t2 = Σ sin(2πi/n) q_i` and the normal `t1 × t2` (the ring runs
//! counter-clockwise). On a crease or boundary the crease line is a uniform cubic B-spline,
//! whose limit at a vertex is `(a + 4p + b)/6`. Corners stay where they are. Darts and the
//! normals of crease, boundary and corner vertices come from the crate-internal `scheme::local_limit`.

use nalgebra::{Point3, Vector3};

use crate::error::SubdivError;
use crate::mesh::{split_creases, PolyMesh, VertexKind};
use crate::scheme::{local_limit, times_four_pow, Subdivision};

/// Which β the smooth vertex rule uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum LoopWeights {
    /// Loop's original `β = (1/n)(5/8 − (3/8 + ¼ cos(2π/n))²)`.
    #[default]
    Loop,
    /// Warren's simplification `β = 3/(8n)` for `n > 3`, `3/16` for `n = 3`.
    Warren,
}

impl LoopWeights {
    /// β for valence `n` (`n ≥ 1`; valences below 3 only occur on boundaries, where β is not
    /// used, and get Loop's formula).
    pub fn beta(self, n: usize) -> f64 {
        let nf = n as f64;
        match self {
            LoopWeights::Warren if n > 3 => 3.0 / (8.0 * nf),
            LoopWeights::Warren if n == 3 => 3.0 / 16.0,
            _ => {
                let c = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / nf).cos();
                (0.625 - c * c) / nf
            }
        }
    }

    /// The limit weight `χ = 1/(n + 3/(8β))` on each neighbour of a smooth vertex.
    pub fn chi(self, n: usize) -> f64 {
        1.0 / (n as f64 + 3.0 / (8.0 * self.beta(n)))
    }
}

/// Loop subdivision with the given weights (see the module documentation for the rules).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Loop {
    /// The smooth vertex rule's β.
    pub weights: LoopWeights,
}

impl Loop {
    fn check(&self, mesh: &PolyMesh) -> Result<(), SubdivError> {
        match mesh.first_non_triangle() {
            Some((face, corners)) => Err(SubdivError::NotTriangular {
                scheme: self.name(),
                face,
                corners,
            }),
            None => Ok(()),
        }
    }
}

impl Subdivision for Loop {
    fn name(&self) -> &'static str {
        match self.weights {
            LoopWeights::Loop => "loop",
            LoopWeights::Warren => "loop-warren",
        }
    }

    fn faces_after(&self, mesh: &PolyMesh, levels: u32) -> Option<u64> {
        times_four_pow(mesh.num_faces() as u64, levels)
    }

    fn step(&self, mesh: &PolyMesh) -> Result<PolyMesh, SubdivError> {
        self.check(mesh)?;
        let nv = mesh.num_vertices();
        let ne = mesh.num_edges();
        let nf = mesh.num_faces();
        if nv + ne >= u32::MAX as usize {
            return Err(SubdivError::IndexOverflow {
                what: "vertices",
                count: nv + ne,
            });
        }
        let p = mesh.positions();
        let idx = mesh.indices();
        let topo = &mesh.topo;
        // Neighbour sums and valences, and sums over sharp neighbours, by one pass over edges.
        let mut sum = vec![Vector3::<f64>::zeros(); nv];
        let mut sharp_sum = vec![Vector3::<f64>::zeros(); nv];
        let mut valence = vec![0u32; nv];
        let mut out = Vec::with_capacity(nv + ne);
        out.resize(nv, Point3::origin());
        for e in 0..ne {
            let h = topo.edge_half[e] as usize;
            // Triangles: the next corner of h is 3⌊h/3⌋ + (h + 1) mod 3.
            let base = h - h % 3;
            let a = idx[h] as usize;
            let b = idx[base + (h + 1 - base) % 3] as usize;
            let (pa, pb) = (p[a].coords, p[b].coords);
            sum[a] += pb;
            sum[b] += pa;
            valence[a] += 1;
            valence[b] += 1;
            let point = if topo.sharp[e] {
                sharp_sum[a] += pb;
                sharp_sum[b] += pa;
                (pa + pb) * 0.5
            } else {
                let c = idx[base + (h + 2 - base) % 3] as usize;
                let t = topo.twin[h] as usize;
                let tb = t - t % 3;
                let d = idx[tb + (t + 2 - tb) % 3] as usize;
                (pa + pb) * 0.375 + (p[c].coords + p[d].coords) * 0.125
            };
            out.push(Point3::from(point));
        }
        let mut beta_cache = Vec::new();
        for v in 0..nv {
            out[v] = match topo.kind[v] {
                VertexKind::Isolated | VertexKind::Corner => p[v],
                VertexKind::Crease => Point3::from(p[v].coords * 0.75 + sharp_sum[v] * 0.125),
                VertexKind::Smooth | VertexKind::Dart => {
                    let n = valence[v] as usize;
                    if beta_cache.len() <= n {
                        let w = self.weights;
                        beta_cache.extend((beta_cache.len()..=n).map(|k| w.beta(k.max(1))));
                    }
                    let beta = beta_cache[n];
                    Point3::from(p[v].coords * (1.0 - n as f64 * beta) + sum[v] * beta)
                }
            };
        }
        drop((sum, sharp_sum, valence));
        let mut faces = Vec::with_capacity(12 * nf);
        let nvu = nv as u32;
        for f in 0..nf {
            let h = 3 * f;
            let [v0, v1, v2] = [idx[h], idx[h + 1], idx[h + 2]];
            let m01 = nvu + topo.edge[h];
            let m12 = nvu + topo.edge[h + 1];
            let m20 = nvu + topo.edge[h + 2];
            faces.extend_from_slice(&[v0, m01, m20, v1, m12, m01, v2, m20, m12, m01, m12, m20]);
        }
        let offsets = (0..=4 * nf as u32).map(|i| 3 * i).collect();
        let creases = split_creases(mesh, nvu);
        PolyMesh::from_parts(out, faces, offsets, &creases)
    }

    fn limit_positions(&self, mesh: &PolyMesh) -> Result<Vec<Point3<f64>>, SubdivError> {
        self.check(mesh)?;
        let p = mesh.positions();
        let mut ring = Vec::new();
        (0..mesh.num_vertices())
            .map(|v| match mesh.vertex_kind(v) {
                VertexKind::Isolated | VertexKind::Corner => Ok(p[v]),
                VertexKind::Crease => Ok(Point3::from(
                    (p[v].coords * 4.0 + mesh.sharp_neighbour_sum(v)) / 6.0,
                )),
                VertexKind::Smooth => {
                    ring.clear();
                    mesh.ring(v, &mut ring);
                    let n = ring.len();
                    let chi = self.weights.chi(n);
                    let s: Vector3<f64> = ring.iter().map(|&q| p[q as usize].coords).sum();
                    Ok(Point3::from(p[v].coords * (1.0 - n as f64 * chi) + s * chi))
                }
                VertexKind::Dart => local_limit(self, mesh, v, false).map(|(x, _)| x),
            })
            .collect()
    }

    fn limit_normals(&self, mesh: &PolyMesh) -> Result<Vec<Vector3<f64>>, SubdivError> {
        self.check(mesh)?;
        let p = mesh.positions();
        let mut ring = Vec::new();
        (0..mesh.num_vertices())
            .map(|v| match mesh.vertex_kind(v) {
                VertexKind::Isolated => Ok(Vector3::zeros()),
                VertexKind::Smooth => {
                    ring.clear();
                    mesh.ring(v, &mut ring);
                    let n = ring.len();
                    let (mut t1, mut t2) = (Vector3::zeros(), Vector3::zeros());
                    for (i, &q) in ring.iter().enumerate() {
                        let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                        let d = p[q as usize] - p[v];
                        t1 += d * a.cos();
                        t2 += d * a.sin();
                    }
                    Ok(unit(t1.cross(&t2)))
                }
                _ => local_limit(self, mesh, v, true).map(|(_, nrm)| nrm),
            })
            .collect()
    }
}

/// `v / |v|`, or zero for a zero vector.
pub(crate) fn unit(v: Vector3<f64>) -> Vector3<f64> {
    let n = v.norm();
    if n > 0.0 {
        v / n
    } else {
        v
    }
}

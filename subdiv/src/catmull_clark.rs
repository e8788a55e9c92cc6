//! Catmull–Clark subdivision (Catmull and Clark 1978) of polygon meshes of any face size, with
//! boundaries and tagged creases; after one step every face is a quad.
//!
//! # Rules
//!
//! - **face point**: the centroid of the face's corners.
//! - **smooth edge** `(a, b)` between faces with points `f0, f1`: `(a + b + f0 + f1)/4`.
//! - **sharp edge** (boundary or crease): `(a + b)/2`.
//! - **smooth and dart vertices** of valence `n` (edges; as many faces): with `q_j` the edge
//!   neighbours and `f_j` the points of the faces around,
//!   `p' = ((n − 2) p + (Σ q_j + Σ f_j)/n)/n`, which is the textbook `(Q + 2R + (n − 3) p)/n`
//!   (`Q` the average face point, `R` the average edge midpoint).
//! - **crease and boundary vertices** (exactly two sharp edges, to `a` and `b`):
//!   `p' = (a + 6p + b)/8`.
//! - **corners** (more than two sharp edges): `p' = p`.
//!
//! # Order of the output
//!
//! Vertices: the `V` old vertices first (same indices), then one per edge (`V + e`, edge `e` in
//! [`PolyMesh::edges`] order), then one per face (`V + E + f`). Faces: corner `i` of face `f`
//! (corners in order, over the faces in order) gives the quad `(v_i, m_i, c_f, m_{i−1})`, with
//! `m_i` the point of the edge from corner `i` to corner `i + 1` and `c_f` the face point.
//!
//! # Limit stencils (quad meshes)
//!
//! For a smooth vertex of valence `n` on a quad mesh, with edge neighbours `e_i` and diagonal
//! neighbours `f_i` (the far corner of the quad between `e_i` and `e_{i+1}`), counter-clockwise:
//!
//! - limit point `p∞ = (n² p + 4 Σ e_i + Σ f_i)/(n(n + 5))` (Halstead et al. 1993);
//! - tangents `t1 = Σ (A_n cos(2πi/n) e_i + (cos(2πi/n) + cos(2π(i+1)/n)) f_i)` and `t2` with
//!   sines, `A_n = 1 + cos(2π/n) + cos(π/n) √(2(9 + cos(2π/n)))`, normal `t1 × t2`
//!   (`A_4 = 4`: the bicubic B-spline's derivative mask at a regular vertex).
//!
//! A mesh with other faces is stepped once first: the old vertices keep their indices and their
//! limits, and every face of the stepped mesh is a quad. Crease and boundary vertices have the
//! cubic B-spline limit `(a + 4p + b)/6` of their crease line (on any mesh: the crease line's
//! points follow the curve rules alone); corners stay; darts and the normals of crease,
//! boundary and corner vertices come from the crate-internal `scheme::local_limit`.

use std::f64::consts::PI;

use nalgebra::{Point3, Vector3};

use crate::error::SubdivError;
use crate::loop_scheme::unit;
use crate::mesh::{split_creases, PolyMesh, VertexKind};
use crate::scheme::{local_limit, times_four_pow, Subdivision};

/// Catmull–Clark subdivision (see the module documentation for the rules).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CatmullClark;

/// `A_n` of the tangent mask.
fn tangent_a(n: usize) -> f64 {
    let c = (2.0 * PI / n as f64).cos();
    1.0 + c + (PI / n as f64).cos() * (2.0 * (9.0 + c)).sqrt()
}

impl Subdivision for CatmullClark {
    fn name(&self) -> &'static str {
        "catmull-clark"
    }

    fn faces_after(&self, mesh: &PolyMesh, levels: u32) -> Option<u64> {
        if levels == 0 {
            return Some(mesh.num_faces() as u64);
        }
        times_four_pow(mesh.num_corners() as u64, levels - 1)
    }

    fn step(&self, mesh: &PolyMesh) -> Result<PolyMesh, SubdivError> {
        let nv = mesh.num_vertices();
        let ne = mesh.num_edges();
        let nf = mesh.num_faces();
        let nc = mesh.num_corners();
        if nv + ne + nf >= u32::MAX as usize || 4 * nc >= u32::MAX as usize {
            return Err(SubdivError::IndexOverflow {
                what: "vertices",
                count: nv + ne + nf,
            });
        }
        let p = mesh.positions();
        let idx = mesh.indices();
        let off = mesh.offsets();
        let topo = &mesh.topo;
        let mut out = Vec::with_capacity(nv + ne + nf);
        out.resize(nv, Point3::origin());
        // Face points, kept aside until the edge points are in.
        let mut face_pts = Vec::with_capacity(nf);
        for f in 0..nf {
            let (s, e) = (off[f] as usize, off[f + 1] as usize);
            let mut c = Vector3::zeros();
            for &v in &idx[s..e] {
                c += p[v as usize].coords;
            }
            face_pts.push(c / (e - s) as f64);
        }
        // Per vertex: Σ q_j + Σ f_j, valence (edges), Σ over sharp neighbours.
        let mut sum = vec![Vector3::<f64>::zeros(); nv];
        let mut sharp_sum = vec![Vector3::<f64>::zeros(); nv];
        let mut valence = vec![0u32; nv];
        for e in 0..ne {
            let h = topo.edge_half[e];
            let a = idx[h as usize] as usize;
            let b = mesh.head(h) as usize;
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
                let f0 = topo.face_of[h as usize] as usize;
                let f1 = topo.face_of[topo.twin[h as usize] as usize] as usize;
                (pa + pb + face_pts[f0] + face_pts[f1]) * 0.25
            };
            out.push(Point3::from(point));
        }
        for f in 0..nf {
            let fp = face_pts[f];
            for &v in &idx[off[f] as usize..off[f + 1] as usize] {
                sum[v as usize] += fp;
            }
        }
        for v in 0..nv {
            out[v] = match topo.kind[v] {
                VertexKind::Isolated | VertexKind::Corner => p[v],
                VertexKind::Crease => Point3::from(p[v].coords * 0.75 + sharp_sum[v] * 0.125),
                VertexKind::Smooth | VertexKind::Dart => {
                    let n = valence[v] as f64;
                    Point3::from((p[v].coords * (n - 2.0) + sum[v] / n) / n)
                }
            };
        }
        out.extend(face_pts.into_iter().map(Point3::from));
        drop((sum, sharp_sum, valence));
        let nvu = nv as u32;
        let face_base = (nv + ne) as u32;
        let mut faces = Vec::with_capacity(4 * nc);
        for f in 0..nf {
            let (s, e) = (off[f] as usize, off[f + 1] as usize);
            let c = face_base + f as u32;
            for (h, &v) in idx.iter().enumerate().take(e).skip(s) {
                let prev = if h == s { e - 1 } else { h - 1 };
                faces.extend_from_slice(&[v, nvu + topo.edge[h], c, nvu + topo.edge[prev]]);
            }
        }
        let offsets = (0..=nc as u32).map(|i| 4 * i).collect();
        let creases = split_creases(mesh, nvu);
        PolyMesh::from_parts(out, faces, offsets, &creases)
    }

    fn limit_positions(&self, mesh: &PolyMesh) -> Result<Vec<Point3<f64>>, SubdivError> {
        if !mesh.all_quads() {
            let fine = self.step(mesh)?;
            let mut all = self.limit_positions(&fine)?;
            all.truncate(mesh.num_vertices());
            return Ok(all);
        }
        let p = mesh.positions();
        let mut hs = Vec::new();
        (0..mesh.num_vertices())
            .map(|v| match mesh.vertex_kind(v) {
                VertexKind::Isolated | VertexKind::Corner => Ok(p[v]),
                VertexKind::Crease => Ok(Point3::from(
                    (p[v].coords * 4.0 + mesh.sharp_neighbour_sum(v)) / 6.0,
                )),
                VertexKind::Smooth => {
                    hs.clear();
                    mesh.outgoing(v, &mut hs);
                    let n = hs.len() as f64;
                    let mut s = Vector3::zeros();
                    for &h in &hs {
                        let e = mesh.head(h) as usize;
                        let d = mesh.tail(mesh.prev(mesh.prev(h))) as usize;
                        s += p[e].coords * 4.0 + p[d].coords;
                    }
                    Ok(Point3::from((p[v].coords * (n * n) + s) / (n * (n + 5.0))))
                }
                VertexKind::Dart => local_limit(self, mesh, v, false).map(|(x, _)| x),
            })
            .collect()
    }

    fn limit_normals(&self, mesh: &PolyMesh) -> Result<Vec<Vector3<f64>>, SubdivError> {
        if !mesh.all_quads() {
            let fine = self.step(mesh)?;
            let mut all = self.limit_normals(&fine)?;
            all.truncate(mesh.num_vertices());
            return Ok(all);
        }
        let p = mesh.positions();
        let mut hs = Vec::new();
        (0..mesh.num_vertices())
            .map(|v| match mesh.vertex_kind(v) {
                VertexKind::Isolated => Ok(Vector3::zeros()),
                VertexKind::Smooth => {
                    hs.clear();
                    mesh.outgoing(v, &mut hs);
                    let n = hs.len();
                    let a_n = tangent_a(n);
                    let (mut t1, mut t2) = (Vector3::zeros(), Vector3::zeros());
                    for (i, &h) in hs.iter().enumerate() {
                        let e = p[mesh.head(h) as usize] - p[v];
                        let d = p[mesh.tail(mesh.prev(mesh.prev(h))) as usize] - p[v];
                        let a0 = 2.0 * PI * i as f64 / n as f64;
                        let a1 = 2.0 * PI * (i + 1) as f64 / n as f64;
                        t1 += e * (a_n * a0.cos()) + d * (a0.cos() + a1.cos());
                        t2 += e * (a_n * a0.sin()) + d * (a0.sin() + a1.sin());
                    }
                    Ok(unit(t1.cross(&t2)))
                }
                _ => local_limit(self, mesh, v, true).map(|(_, nrm)| nrm),
            })
            .collect()
    }
}

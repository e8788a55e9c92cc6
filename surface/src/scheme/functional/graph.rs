//! A functional fit as the function it is: `z(x, y)` and `∇z(x, y)` at any point of the
//! triangulation's xy domain, for the error measures of the `franke` study.
//!
//! A query point is located in its data face by a bucket grid of the faces' xy bounding boxes
//! (about one face per cell), then in the face's patch whose xy sub-triangle (the corner
//! control points' xy: the patches' xy part is affine) holds it; the patch is evaluated at the
//! point's barycentric coordinates there. The gradient follows from the patch's partials:
//! `(z_u, z_v) = (z_x, z_y) J` with `J` the 2 × 2 xy Jacobian `[r_u r_v]`, so
//! `∇z = J⁻ᵀ (z_u, z_v)`.

use nalgebra::{Matrix2, Vector2};

use crate::fit::Fit;
use crate::mesh::Mesh;

/// Slack of the barycentric inside test: a point on a shared edge is found in either face.
const INSIDE: f64 = 1e-12;

/// The fitted function of a functional fit (module docs).
pub struct Graph<'a> {
    mesh: &'a Mesh,
    fit: &'a Fit,
    lo: Vector2<f64>,
    size: Vector2<f64>,
    cells: usize,
    buckets: Vec<Vec<usize>>,
}

fn xy_of(mesh: &Mesh, v: usize) -> Vector2<f64> {
    super::xy(&mesh.vertices()[v].data.p)
}

/// Barycentric `(u, v)` of `q` in the xy triangle `c` (`w = 1 − u − v` at `c[2]`), `None` for a
/// degenerate triangle.
fn bary(c: &[Vector2<f64>; 3], q: &Vector2<f64>) -> Option<Vector2<f64>> {
    Matrix2::from_columns(&[c[0] - c[2], c[1] - c[2]])
        .try_inverse()
        .map(|m| m * (q - c[2]))
}

fn inside(uv: &Vector2<f64>) -> bool {
    uv.x >= -INSIDE && uv.y >= -INSIDE && uv.x + uv.y <= 1.0 + INSIDE
}

impl<'a> Graph<'a> {
    /// The graph of `fit` (a fit of `mesh` with Bézier patches whose xy parts are affine: the
    /// functional schemes').
    pub fn new(mesh: &'a Mesh, fit: &'a Fit) -> Self {
        let pts: Vec<Vector2<f64>> = (0..mesh.num_vertices()).map(|v| xy_of(mesh, v)).collect();
        let (mut lo, mut hi) = (
            Vector2::repeat(f64::INFINITY),
            Vector2::repeat(f64::NEG_INFINITY),
        );
        for p in &pts {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        let size = (hi - lo).map(|d| d.max(f64::MIN_POSITIVE));
        let cells = (mesh.num_faces() as f64).sqrt().ceil().clamp(1.0, 4096.0) as usize;
        let mut g = Graph {
            mesh,
            fit,
            lo,
            size,
            cells,
            buckets: vec![Vec::new(); cells * cells],
        };
        for (f, face) in mesh.faces().iter().enumerate() {
            let (mut a, mut b) = (pts[face[0]], pts[face[0]]);
            for &v in face {
                a = a.inf(&pts[v]);
                b = b.sup(&pts[v]);
            }
            let ((i0, j0), (i1, j1)) = (g.cell(&a), g.cell(&b));
            for i in i0..=i1 {
                for j in j0..=j1 {
                    g.buckets[i * cells + j].push(f);
                }
            }
        }
        g
    }

    fn cell(&self, p: &Vector2<f64>) -> (usize, usize) {
        let c = (p - self.lo).component_div(&self.size) * self.cells as f64;
        let clamp = |x: f64| (x.max(0.0) as usize).min(self.cells - 1);
        (clamp(c.x), clamp(c.y))
    }

    /// The face holding `q`, if any.
    pub fn face_at(&self, q: &Vector2<f64>) -> Option<usize> {
        let (i, j) = self.cell(q);
        self.buckets[i * self.cells + j].iter().copied().find(|&f| {
            let c = self.mesh.faces()[f].map(|v| xy_of(self.mesh, v));
            bary(&c, q).is_some_and(|uv| inside(&uv))
        })
    }

    /// `z` and `∇z` of face `f`'s patches at `q` (which `f` must hold).
    pub fn in_face(&self, f: usize, q: &Vector2<f64>) -> Option<(f64, Vector2<f64>)> {
        let per = self.fit.layout.patches_per_face();
        let n = self.fit.layout.degree;
        (0..per).find_map(|s| {
            let patch = self.fit.patch(f * per + s)?;
            let p = patch.points();
            let c = [p[0], p[n], p[p.len() - 1]].map(|x| super::xy(&x));
            let uv = bary(&c, q).filter(inside)?;
            let d = patch.derivatives(uv.x, uv.y);
            let j = Matrix2::new(d.du.x, d.dv.x, d.du.y, d.dv.y);
            let g = j.transpose().try_inverse()? * Vector2::new(d.du.z, d.dv.z);
            Some((d.p.z, g))
        })
    }

    /// `z` and `∇z` at `q`, `None` outside the triangulation.
    pub fn at(&self, q: &Vector2<f64>) -> Option<(f64, Vector2<f64>)> {
        self.face_at(q).and_then(|f| self.in_face(f, q))
    }
}

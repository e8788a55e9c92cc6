//! `phong`: Phong tessellation (Boubekeur and Alexa, *Phong Tessellation*, ACM TOG 27(5), 2008).
//!
//! With `π_a(q) = q − ((q − p_a)·n_a) n_a` the projection onto the tangent plane of vertex
//! `a`, the patch is `p*(λ) = (1 − α) Σ_a λ_a p_a + α Σ_a λ_a π_a(Σ_b λ_b p_b)`. Each `π_a` is
//! affine, so `π_a(Σ_b λ_b p_b) = Σ_b λ_b π_a(p_b)` and
//! `p*(λ) = Σ_a λ_a² p_a + Σ_{a<b} λ_a λ_b [(1 − α)(p_a + p_b) + α(π_a(p_b) + π_b(p_a))]`:
//! a quadratic Bézier triangle with corner points `p_a` and edge points
//! `b_ab = (1 − α)(p_a + p_b)/2 + α (π_a(p_b) + π_b(p_a))/2` (the coefficient of the Bernstein
//! polynomial `2λ_aλ_b` is half the bracket).
//!
//! The edge points depend only on the edge's two vertices, so neighbours share their boundary:
//! C0. The normal is not continuous across edges in general; the G1 measurement reports the
//! jump. At `α = 0` the patch is the flat triangle (tested); a vertex normal equal to the face
//! normal leaves the patch flat for every α (the projections are the identity on that plane).

use nalgebra::{Point3, Vector3};

use super::{Continuity, FaceInput, Layout, ParameterSpec, Scheme, WHOLE};
use crate::beztri::index;
use crate::fit::FaceFallbackReason;
use crate::shirman_sequin::SchemeError;

/// The shape factor the paper recommends.
pub const DEFAULT_ALPHA: f64 = 0.75;

/// Phong tessellation with shape factor `alpha`.
#[derive(Clone, Copy, Debug)]
pub struct Phong {
    /// The shape factor α (0: flat, 1: full projection).
    pub alpha: f64,
}

/// The shape factor α. Boubekeur and Alexa (2008) define Phong tessellation for α in [0, 1]: 0
/// is the flat triangle, 1 the full projection onto the vertex tangent planes; beyond 1 the
/// surface overshoots the tangent planes (a 1e308 shape factor sent the patches to 5e307 on a
/// unit octahedron).
pub const ALPHA: ParameterSpec = ParameterSpec {
    name: "phong-alpha",
    symbol: "α",
    default: DEFAULT_ALPHA,
    range: (0.0, 1.0),
    range_reason: "0 is the flat triangle, 1 the full projection onto the tangent planes",
    summary: "shape factor α of `phong` (0: flat triangles; Boubekeur and Alexa: 3/4)",
};

/// The scheme's parameters.
pub const PARAMETERS: &[ParameterSpec] = &[ALPHA];

/// Projection of `q` onto the plane through `p` with unit normal `n`.
fn project(q: &Point3<f64>, p: &Point3<f64>, n: &Vector3<f64>) -> Point3<f64> {
    q - n * (q - p).dot(n)
}

impl Scheme for Phong {
    fn name(&self) -> &'static str {
        "phong"
    }

    fn layout(&self) -> Layout {
        Layout::bezier(2, &WHOLE)
    }

    fn continuity(&self) -> Continuity {
        Continuity::C0
    }

    fn uses_curves(&self) -> bool {
        false
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        if !self.alpha.is_finite() {
            return Err(FaceFallbackReason::Scheme(SchemeError::BadParameter {
                name: "phong-alpha",
                index: 0,
                value: self.alpha,
            }));
        }
        let p = input.vertices.map(|v| v.p);
        let n = input.vertices.map(|v| v.n.normalize());
        let a = self.alpha;
        for c in 0..3 {
            let mut m = [0usize; 3];
            m[c] = 2;
            out[index(2, m[0], m[1], m[2])] = p[c];
        }
        for c in 0..3 {
            let d = (c + 1) % 3;
            let flat = (p[c].coords + p[d].coords) * 0.5;
            // On a crease end the projection is onto the crease line both faces share
            // (`FaceInput::project`).
            let onto = |from: usize, to: usize| match input.crease_line(from, c) {
                Some(t) => p[from] + t * t.dot(&(p[to] - p[from])),
                None => project(&p[to], &p[from], &n[from]),
            };
            let proj = (onto(c, d).coords + onto(d, c).coords) * 0.5;
            let mut m = [0usize; 3];
            m[c] = 1;
            m[d] = 1;
            out[index(2, m[0], m[1], m[2])] = Point3::from(flat * (1.0 - a) + proj * a);
        }
        Ok(())
    }
}

//! Section 4's corner measures (Mann 1994) on the derivative vectors of a patch at a corner,
//! with their exact gradients with respect to those vectors. The construction that produced the
//! patch supplies how the vectors move with its parameters; the chain rule is then one dot
//! product per vector (`surface::interior` does it for the split-domain scheme).
//!
//! # Curvature of a corner
//!
//! With `A` the first and `B` the second derivative of the patch along a direction at a corner,
//! `n` the vertex's unit normal and `S` its symmetric shape tensor, the measure is the patch's
//! normal curvature along `A` minus the vertex's:
//! `κ = ⟨n, B⟩/|A|² − tᵀ S t`, `t = A/|A|`. With `a = |A|²`:
//!
//! * `∂κ/∂B = n / a`;
//! * `∂κ/∂A = −2⟨n, B⟩ A / a² − 2 S A / a + 2 (Aᵀ S A) A / a²` (from `tᵀ S t = Aᵀ S A / a`).
//!
//! # Twist of a corner
//!
//! With `U`, `V` the first derivatives along the two edges at the corner and `W` the mixed
//! second derivative: `τ = ⟨n, W⟩/(|U||V|) − t_uᵀ S t_v`, `t_u = U/|U|`, `t_v = V/|V|`:
//!
//! * `∂τ/∂W = n / (|U||V|)`;
//! * `∂τ/∂U = −⟨n, W⟩ U / (|U|³|V|) − S V / (|U||V|) + (Uᵀ S V) U / (|U|³|V|)`;
//! * `∂τ/∂V` likewise with `U` and `V` exchanged.
//!
//! Both are checked against central differences at random points in `tests/suite/corner.rs`.

use nalgebra::{Matrix3, Vector3};

/// The curvature measure and its gradients `(κ, ∂κ/∂A, ∂κ/∂B)` (module docs).
pub fn corner_curvature(
    n: &Vector3<f64>,
    s: &Matrix3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
) -> (f64, Vector3<f64>, Vector3<f64>) {
    let aa = a.norm_squared();
    let nb = n.dot(b);
    let sa = s * a;
    let asa = a.dot(&sa);
    let value = nb / aa - asa / aa;
    let grad_a = a * (-2.0 * nb / (aa * aa)) - sa * (2.0 / aa) + a * (2.0 * asa / (aa * aa));
    (value, grad_a, n / aa)
}

/// The twist measure and its gradients `(τ, ∂τ/∂U, ∂τ/∂V, ∂τ/∂W)` (module docs).
pub fn corner_twist(
    n: &Vector3<f64>,
    s: &Matrix3<f64>,
    u: &Vector3<f64>,
    v: &Vector3<f64>,
    w: &Vector3<f64>,
) -> (f64, Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let (lu, lv) = (u.norm(), v.norm());
    let nw = n.dot(w);
    let (su, sv) = (s * u, s * v);
    let usv = u.dot(&sv);
    let value = nw / (lu * lv) - usv / (lu * lv);
    let grad_u = u * (-nw / (lu.powi(3) * lv)) - sv / (lu * lv) + u * (usv / (lu.powi(3) * lv));
    let grad_v = v * (-nw / (lu * lv.powi(3))) - su / (lu * lv) + v * (usv / (lu * lv.powi(3)));
    (value, grad_u, grad_v, n / (lu * lv))
}

/// `(point, ∂value/∂point)` pairs.
type Blocks = Vec<(usize, Vector3<f64>)>;

/// Which corner measure a [`CornerOnNet`] takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CornerMeasure {
    /// [`corner_curvature`] of the net's boundary from the corner towards corner `toward`:
    /// `A = n(b₁ − b₀)`, `B = n(n − 1)(b₂ − 2b₁ + b₀)` with `b_s` the point `s` steps along it.
    Curvature {
        /// The other end of the boundary (0, 1 or 2, not the corner).
        toward: usize,
    },
    /// [`corner_twist`] of the net along its two boundaries from the corner, towards corners
    /// `u` and `v`: `U = n(b_u − b₀)`, `V = n(b_v − b₀)`, `W = n(n − 1)(b_uv − b_u − b_v + b₀)`.
    Twist {
        /// The corner the first direction points to.
        u: usize,
        /// The corner the second direction points to.
        v: usize,
    },
}

/// A corner measure of one degree-`n` net (points `offset..` of the concatenated nets) as a
/// one-residual [`NetObjective`](crate::net::NetObjective): the measure is linear-fractional in
/// the few control points next to the corner, so its derivative with respect to each is the
/// gradient of [`corner_curvature`] or [`corner_twist`] through the linear maps in
/// [`CornerMeasure`].
#[derive(Clone, Debug, PartialEq)]
pub struct CornerOnNet {
    degree: usize,
    offset: usize,
    corner: usize,
    measure: CornerMeasure,
    normal: Vector3<f64>,
    shape: Matrix3<f64>,
}

impl CornerOnNet {
    /// The measure at corner `corner` (0, 1, 2: where `i`, `j` or `k` equals `n`) of the net
    /// starting at point `offset`, against the vertex's unit `normal` and `shape` tensor.
    /// `None` for a degree below 2 or corners that are not three distinct ones.
    pub fn new(
        degree: usize,
        offset: usize,
        corner: usize,
        measure: CornerMeasure,
        normal: Vector3<f64>,
        shape: Matrix3<f64>,
    ) -> Option<Self> {
        let ok = match measure {
            CornerMeasure::Curvature { toward } => toward < 3 && toward != corner,
            CornerMeasure::Twist { u, v } => u < 3 && v < 3 && u != v && u != corner && v != corner,
        };
        (degree >= 2 && corner < 3 && ok).then_some(CornerOnNet {
            degree,
            offset,
            corner,
            measure,
            normal,
            shape,
        })
    }

    /// The point `s` steps towards corner `d` and `t` towards corner `e` from the corner.
    fn at(&self, d: usize, s: usize, e: usize, t: usize) -> usize {
        let mut m = [0usize; 3];
        m[self.corner] = self.degree - s - t;
        m[d] += s;
        m[e] += t;
        self.offset + crate::net::index(self.degree, m[0], m[1], m[2])
    }

    /// The third corner, neither the corner nor `d`.
    fn other(&self, d: usize) -> usize {
        3 - self.corner - d
    }

    /// `(value, [(point, ∂value/∂point)])`, or `None` where the points are out of range.
    fn evaluate(&self, points: &[Vector3<f64>]) -> Option<(f64, Blocks)> {
        let n = self.degree as f64;
        let nn = n * (n - 1.0);
        let p = |i: usize| points.get(i).copied();
        match self.measure {
            CornerMeasure::Curvature { toward } => {
                let e = self.other(toward);
                let (i0, i1, i2) = (
                    self.at(toward, 0, e, 0),
                    self.at(toward, 1, e, 0),
                    self.at(toward, 2, e, 0),
                );
                let (b0, b1, b2) = (p(i0)?, p(i1)?, p(i2)?);
                let a = (b1 - b0) * n;
                let b = (b2 - b1 * 2.0 + b0) * nn;
                let (k, ga, gb) = corner_curvature(&self.normal, &self.shape, &a, &b);
                Some((
                    k,
                    vec![
                        (i0, -ga * n + gb * nn),
                        (i1, ga * n - gb * (2.0 * nn)),
                        (i2, gb * nn),
                    ],
                ))
            }
            CornerMeasure::Twist { u, v } => {
                let (i0, iu, iv, iuv) = (
                    self.at(u, 0, v, 0),
                    self.at(u, 1, v, 0),
                    self.at(u, 0, v, 1),
                    self.at(u, 1, v, 1),
                );
                let (b0, bu, bv, buv) = (p(i0)?, p(iu)?, p(iv)?, p(iuv)?);
                let (uu, vv) = ((bu - b0) * n, (bv - b0) * n);
                let w = (buv - bu - bv + b0) * nn;
                let (t, gu, gv, gw) = corner_twist(&self.normal, &self.shape, &uu, &vv, &w);
                Some((
                    t,
                    vec![
                        (i0, -(gu + gv) * n + gw * nn),
                        (iu, gu * n - gw * nn),
                        (iv, gv * n - gw * nn),
                        (iuv, gw * nn),
                    ],
                ))
            }
        }
    }
}

impl crate::net::NetObjective<1> for CornerOnNet {
    /// The measure; non-finite where the points are out of range or the corner is degenerate.
    fn residuals(&self, points: &[Vector3<f64>]) -> nalgebra::SVector<f64, 1> {
        nalgebra::SVector::<f64, 1>::new(self.evaluate(points).map_or(f64::NAN, |e| e.0))
    }

    fn for_each_derivative(
        &self,
        points: &[Vector3<f64>],
        f: &mut dyn FnMut(usize, usize, Vector3<f64>),
    ) {
        if let Some((_, blocks)) = self.evaluate(points) {
            for (p, d) in blocks {
                f(0, p, d);
            }
        }
    }
}

/// Several corner measures as one `M`-residual [`NetObjective`](crate::net::NetObjective):
/// residual `a` is measure `a` (unused residuals are zero).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CornerSet<const M: usize> {
    measures: Vec<CornerOnNet>,
}

impl<const M: usize> CornerSet<M> {
    /// The set, or `None` when there are more measures than `M`.
    pub fn new(measures: Vec<CornerOnNet>) -> Option<Self> {
        (measures.len() <= M).then_some(CornerSet { measures })
    }
}

impl<const M: usize> crate::net::NetObjective<M> for CornerSet<M> {
    fn residuals(&self, points: &[Vector3<f64>]) -> nalgebra::SVector<f64, M> {
        let mut r = nalgebra::SVector::<f64, M>::zeros();
        for (a, m) in self.measures.iter().enumerate() {
            r[a] = m.evaluate(points).map_or(f64::NAN, |e| e.0);
        }
        r
    }

    fn for_each_derivative(
        &self,
        points: &[Vector3<f64>],
        f: &mut dyn FnMut(usize, usize, Vector3<f64>),
    ) {
        for (a, m) in self.measures.iter().enumerate() {
            if let Some((_, blocks)) = m.evaluate(points) {
                for (p, d) in blocks {
                    f(a, p, d);
                }
            }
        }
    }
}

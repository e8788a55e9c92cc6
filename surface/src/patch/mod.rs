//! The patch abstraction: evaluation of any scheme's patch, with first and second derivatives,
//! at points of its domain.
//!
//! A fit stores, per patch, a fixed number of points ([`Layout::points_per_patch`]). For the
//! Bézier schemes they are the control net ([`Form::Bezier`]); for schemes whose patches are
//! not polynomials (Nielson's side-vertex interpolant, the discrete side-vertex interpolant)
//! they are the data the patch is evaluated from, and a [`SampledForm`] says how
//! ([`Form::Sampled`]). Tessellation, G1 measurement, curvature, the renders and the metrics
//! all go through the two functions here:
//!
//! * [`prepare`] — what does not depend on the patch's data at one local point (Bernstein
//!   weights for a net; blending functions and their derivatives for a sampled form), computed
//!   once per sample point of a plan;
//! * [`eval`] — position and the partials `r_u, r_v, r_uu, r_uv, r_vv` of one patch at a
//!   prepared point, with respect to the patch's local barycentric `(u, v)` (`w = 1 − u − v`,
//!   docs/conventions.md).
//!
//! A Bézier patch costs exactly what it cost before the abstraction: the prepared point is its
//! [`SampleWeights`] and the evaluation six weighted sums ([`net_derivatives`]); the
//! dispatch is one `match` per sample.
//!
//! # Adding a patch form
//!
//! One file implementing [`SampledForm`] (module docs with the derivation, finite-difference
//! tests of its derivatives), a static instance, and the scheme that builds its data
//! ([`crate::scheme::Scheme`] with a [`Layout`] whose `form` is `Form::Sampled(&INSTANCE)`).

pub mod beztri;
pub mod side_vertex;

use nalgebra::{Point3, Vector3};

use crate::beztri::SampleWeights;
use crate::beztri::{
    curvature_of, net_derivatives, net_partials, BezierTriangle, Curvature, Derivatives,
};
use crate::fit::Fit;
use crate::scheme::{Bary, Form, Layout};

/// A patch evaluated by its own rule from stored points (module docs).
pub trait SampledForm: Send + Sync {
    /// A name for messages and reports.
    fn name(&self) -> &'static str;

    /// Points stored per patch.
    fn points_per_patch(&self) -> usize;

    /// What does not depend on the patch's data at local barycentric point `local`, as a flat
    /// list of numbers read back by [`SampledForm::eval`].
    fn prepare(&self, local: Bary) -> Vec<f64>;

    /// Position and partials (module docs) of the patch with data `points` at a point
    /// prepared by [`SampledForm::prepare`].
    fn eval(&self, points: &[Point3<f64>], prepared: &[f64]) -> Derivatives;

    /// True when stored point `k` is a direction (a normal), not a position: it follows only
    /// the linear part of a change of frame.
    fn is_direction(&self, _k: usize) -> bool {
        false
    }
}

impl std::fmt::Debug for dyn SampledForm {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A local point prepared for evaluation (see [`prepare`]).
#[derive(Clone, Debug)]
pub enum Prepared {
    /// Bernstein weights of a Bézier net.
    Bezier(SampleWeights),
    /// A sampled form's numbers.
    Sampled(Vec<f64>),
}

/// Prepares local point `local` of a patch of `layout` (module docs).
pub fn prepare(layout: &Layout, local: Bary) -> Prepared {
    match layout.form {
        Form::Bezier => Prepared::Bezier(SampleWeights::new(layout.degree, local[0], local[1])),
        Form::Sampled(s) => Prepared::Sampled(s.prepare(local)),
    }
}

/// Position and partials of the patch with stored points `points` (one patch of `layout`) at
/// a prepared point (prepared for the same layout; otherwise every component is NaN).
pub fn eval(layout: &Layout, points: &[Point3<f64>], at: &Prepared) -> Derivatives {
    match (layout.form, at) {
        (_, Prepared::Bezier(w)) => net_derivatives(points, w),
        (Form::Sampled(s), Prepared::Sampled(p)) => s.eval(points, p),
        // A point prepared for a sampled form, used with a Bézier layout: a caller's mix-up,
        // made visible.
        (Form::Bezier, Prepared::Sampled(_)) => Derivatives::nan(),
    }
}

/// The first partials `(r_u, r_v)` of the patch with stored points `points` at a prepared
/// point: [`eval`]'s `du` and `dv`, bit for bit, without the position and second partials for
/// a Bézier net ([`crate::beztri::net_partials`]; a sampled form evaluates in full).
pub fn partials(
    layout: &Layout,
    points: &[Point3<f64>],
    at: &Prepared,
) -> (Vector3<f64>, Vector3<f64>) {
    match (layout.form, at) {
        (_, Prepared::Bezier(w)) => net_partials(points, w),
        _ => {
            let d = eval(layout, points, at);
            (d.du, d.dv)
        }
    }
}

/// Position and partials at local point `local` (prepares and evaluates; for single points).
pub fn eval_at(layout: &Layout, points: &[Point3<f64>], local: Bary) -> Derivatives {
    match layout.form {
        Form::Bezier => BezierTriangle::new(layout.degree, points.to_vec())
            .map(|b| b.derivatives(local[0], local[1]))
            .unwrap_or_else(|_| eval(layout, points, &prepare(layout, local))),
        Form::Sampled(s) => s.eval(points, &s.prepare(local)),
    }
}

/// Fraction of the way to the patch centre that a singular sample is moved
/// ([`crate::tessellate`]'s rule, for every form).
const SINGULAR_NUDGE: f64 = 1e-6;

/// The differential geometry at `local`, or where the patch is singular there, a small step
/// towards its centre ([`crate::tessellate`]'s rule); `None` only where it is singular at the
/// nudged point too. The flag is true when the sample was nudged.
pub fn curvature_near(
    layout: &Layout,
    points: &[Point3<f64>],
    local: Bary,
) -> Option<(Curvature, bool)> {
    match curvature_of(&eval_at(layout, points, local)) {
        Some(c) => Some((c, false)),
        None => nudged_curvature(layout, points, local).map(|c| (c, true)),
    }
}

/// The differential geometry [`SINGULAR_NUDGE`] of the way from `local` towards the patch's
/// centre: for a sample already found singular there.
pub fn nudged_curvature(layout: &Layout, points: &[Point3<f64>], local: Bary) -> Option<Curvature> {
    let third = 1.0 / 3.0;
    let nudged = local.map(|x| x + SINGULAR_NUDGE * (third - x));
    curvature_of(&eval_at(layout, points, nudged))
}

/// Local barycentric coordinates of the face point `x` in sub-triangle `sub`.
pub fn local_in(sub: &[Bary; 3], x: Bary) -> Option<Bary> {
    let m = nalgebra::Matrix3::from_fn(|r, c| sub[c][r]);
    let l = m.try_inverse()? * nalgebra::Vector3::from(x);
    Some([l[0], l[1], l[2]])
}

/// Tolerance on a local barycentric coordinate for "inside the sub-triangle" (rounding of the
/// inverse of a sub-triangle matrix with entries in sixths).
const INSIDE: f64 = 1e-12;

impl Fit {
    /// The patch of face `face` containing the face's barycentric point `x`, with `x`'s local
    /// coordinates in it.
    pub fn locate(&self, face: usize, x: Bary) -> Option<(usize, Bary)> {
        let ppf = self.layout.patches_per_face();
        self.layout.subs.iter().enumerate().find_map(|(s, sub)| {
            let l = local_in(sub, x)?;
            l.iter()
                .all(|c| *c >= -INSIDE)
                .then_some((face * ppf + s, l))
        })
    }

    /// Position and partials of the fitted surface at the barycentric point `x` of face
    /// `face`, with respect to the local `(u, v)` of the patch that contains it (returned
    /// too). `None` when `face` is out of range.
    pub fn eval(&self, face: usize, x: Bary) -> Option<(usize, Derivatives)> {
        let (patch, local) = self.locate(face, x)?;
        let net = self.net(patch)?;
        Some((patch, eval_at(&self.layout, net, local)))
    }

    /// The unit normal of the fitted surface at the barycentric point `x` of face `face`.
    pub fn normal(&self, face: usize, x: Bary) -> Option<Vector3<f64>> {
        let (_, d) = self.eval(face, x)?;
        d.du.cross(&d.dv).try_normalize(0.0)
    }

    /// The point of the fitted surface at the barycentric point `x` of face `face`.
    pub fn point(&self, face: usize, x: Bary) -> Option<Point3<f64>> {
        self.eval(face, x).map(|(_, d)| d.p)
    }
}

//! `nielson`: Nielson's transfinite, visually continuous triangular interpolant (Nielson 1987,
//! in Farin (ed.), *Geometric Modeling: Algorithms and New Trends*, SIAM, pp. 235–246), over
//! the cubic edge curves of any curve method, with the cross-boundary tangent planes from the
//! vertex normals. Not a polynomial: the patch is evaluated by its own rule
//! ([`crate::side_vertex`], which derives it), so the layout's form is
//! [`Form::Sampled`](super::Form::Sampled).
//!
//! G1 across every edge (the tangent plane along an edge is fixed by the edge's own data, the
//! same for both faces); the measured normal jump is rounding. The vertices are the
//! parametrization's singular points (the three blending weights are `0/0` there); the surface
//! takes the vertex tangent plane in the limit.

use nalgebra::Point3;

use super::{Continuity, FaceInput, Form, Layout, Scheme, WHOLE};
use crate::fit::FaceFallbackReason;
use crate::side_vertex::{build_face, write_face, NIELSON};

/// The Nielson side-vertex scheme.
#[derive(Clone, Copy, Debug, Default)]
pub struct Nielson;

impl Scheme for Nielson {
    fn name(&self) -> &'static str {
        "nielson"
    }

    fn layout(&self) -> Layout {
        Layout {
            degree: 3,
            subs: &WHOLE,
            form: Form::Sampled(&NIELSON),
        }
    }

    fn continuity(&self) -> Continuity {
        Continuity::G1
    }

    fn uses_curves(&self) -> bool {
        true
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        build_face(&NIELSON, input, out)
    }

    /// The same boundary curves with the discrete cross-boundary data (zero normals): C0 with
    /// the neighbours, which reproduce the same curves.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        write_face(input.edges, [nalgebra::Vector3::zeros(); 3], out);
    }
}

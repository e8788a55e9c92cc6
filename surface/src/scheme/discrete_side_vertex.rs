//! `discrete-side-vertex`: the side-vertex interpolant with discrete cross-boundary data — the
//! linear interpolant of the vertex derivatives along each edge — over the cubic edge curves of
//! any curve method ([`crate::side_vertex`] derives it). It uses the data at the vertices only,
//! as a finite-dimensional ("discrete") triangular interpolant does.
//!
//! This is the scheme to set beside [`super::nielson`]: the two differ only in the
//! cross-boundary derivative, so the pair shows what Nielson's transfinite normal field buys.
//! Both faces on an edge agree in position and, at its ends, in tangent plane; in between the
//! normal jumps (C0, measured).
//!
//! Herron's scheme (*Smooth closed surfaces with discrete triangular interpolants*, CAGD 2,
//! 1985), which the testbed names among its fitters, is of this family, but its construction
//! (how it makes the discrete data meet with G1 on a closed surface) could not be recovered
//! from any source available to this project; it is not registered under Herron's name.

use nalgebra::Point3;

use super::{Continuity, FaceInput, Form, Layout, Scheme, WHOLE};
use crate::fit::FaceFallbackReason;
use crate::side_vertex::{build_face, write_face, DISCRETE};

/// The discrete side-vertex scheme.
#[derive(Clone, Copy, Debug, Default)]
pub struct DiscreteSideVertex;

impl Scheme for DiscreteSideVertex {
    fn name(&self) -> &'static str {
        "discrete-side-vertex"
    }

    fn layout(&self) -> Layout {
        Layout {
            degree: 3,
            subs: &WHOLE,
            form: Form::Sampled(&DISCRETE),
        }
    }

    fn continuity(&self) -> Continuity {
        Continuity::C0
    }

    fn uses_curves(&self) -> bool {
        true
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        build_face(&DISCRETE, input, out)
    }

    /// The same data: the discrete form never needs the normals.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        write_face(input.edges, input.vertices.map(|v| v.n), out);
    }
}

//! `shirman-sequin-testbed`: the modified Shirman–Séquin fitter of the original testbed's
//! fitters (UW 1990), the scheme Mann's report modifies further: three quartics per face over
//! the centroid split on the face's cubic edge curves, the interior taken from one cubic macro
//! patch with the quadratic-precision centre (degree-raised and split at the centroid), the
//! twists replaced by Chiyokura–Kimura (G1 across mesh edges), and C1 inside restored by
//! averaging. No free parameter. Derivation, and how it differs from Mann's β/c form (the
//! interior edges are quartics here, cubics there; no β, c makes the two coincide):
//! [`crate::ss_variants`].
//!
//! The sources' default boundary for this fitter is the projection tangent rule; the
//! workbench's curve layer gives the boundaries (`--curves`, default `chord`), as for every
//! scheme on curves.

use nalgebra::Point3;

use super::shirman_sequin_1987::write_nets;
use super::{Continuity, FaceInput, Layout, Scheme, CENTROID_SPLIT};
use crate::fallback::fallback_patch;
use crate::fit::FaceFallbackReason;
use crate::ss_variants::testbed_modified;

/// The testbed's modified Shirman–Séquin scheme.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShirmanSequinTestbed;

impl Scheme for ShirmanSequinTestbed {
    fn name(&self) -> &'static str {
        "shirman-sequin-testbed"
    }

    fn layout(&self) -> Layout {
        Layout::bezier(4, &CENTROID_SPLIT)
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
        let nets =
            testbed_modified(input.vertices, input.edges).map_err(FaceFallbackReason::Scheme)?;
        write_nets(&nets, out)
    }

    /// [`crate::fallback::fallback_patch`]: C0 on the shared edge curves.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        for (chunk, net) in out.chunks_exact_mut(15).zip(&fallback_patch(input.edges)) {
            chunk.copy_from_slice(net);
        }
    }
}

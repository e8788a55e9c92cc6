//! `shirman-sequin-1987`: the original Shirman–Séquin construction (Shirman and Séquin 1987,
//! as the original testbed's fitters, UW 1990, coded it) with its one free parameter `α₂`:
//! three quartics per face over the centroid split on the face's cubic edge curves
//! (`--curves`, default `chord`), Chiyokura–Kimura across mesh edges (G1), the interior closed
//! by the G1 conditions with a multiplier running linearly from `4α₂/3` at the corners to 3 at
//! the split point. Derivation, the check of the sources' coefficients, and why it is Mann's
//! construction at `β = 3/(4α₂)`, `c = 1`: [`crate::ss_variants`]. C1 inside each face at the
//! default `α₂ = 9/4` only; G1 inside for every other `α₂`.
//!
//! Named for the year of the paper rather than `shirman-sequin-original`: the registry's
//! `shirman-sequin` is Mann's modification, and this is the construction it modifies.

use nalgebra::Point3;

use super::{Continuity, FaceInput, Layout, ParameterSpec, Scheme, CENTROID_SPLIT};
use crate::fallback::fallback_patch;
use crate::fit::FaceFallbackReason;
use crate::ss_variants::{shirman_sequin_1987, ALPHA2_RANGE, DEFAULT_ALPHA2};

/// `α₂` of the 1987 construction.
pub const ALPHA2: ParameterSpec = ParameterSpec {
    name: "alpha2",
    symbol: "α₂",
    default: DEFAULT_ALPHA2,
    range: ALPHA2_RANGE,
    range_reason: "it degenerates as α₂ → 0 (interior points ~1/α₂) and α₂ → ∞ (interior edges' end derivatives ~1/α₂); β = 3/(4α₂) within Mann's β range",
    summary: "the 1987 Shirman–Séquin parameter α₂ (9/4: C1 inside each triangle; else G1 there)",
};

/// The scheme's parameters.
pub const PARAMETERS: &[ParameterSpec] = &[ALPHA2];

/// The 1987 Shirman–Séquin scheme with its `α₂`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShirmanSequin1987 {
    /// The free parameter `α₂ > 0`.
    pub alpha2: f64,
}

impl Scheme for ShirmanSequin1987 {
    fn name(&self) -> &'static str {
        "shirman-sequin-1987"
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
        let nets = shirman_sequin_1987(input.vertices, input.edges, self.alpha2)
            .map_err(FaceFallbackReason::Scheme)?;
        write_nets(&nets, out)
    }

    /// [`crate::fallback::fallback_patch`]: C0 on the shared edge curves.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        for (chunk, net) in out.chunks_exact_mut(15).zip(&fallback_patch(input.edges)) {
            chunk.copy_from_slice(net);
        }
    }
}

/// Copies three quartic nets into a face's slots, refusing non-finite points.
pub(crate) fn write_nets(
    nets: &[crate::shirman_sequin::QuarticNet; 3],
    out: &mut [Point3<f64>],
) -> Result<(), FaceFallbackReason> {
    if !super::shirman_sequin::finite(nets) {
        return Err(FaceFallbackReason::NonFinite);
    }
    for (chunk, net) in out.chunks_exact_mut(15).zip(nets) {
        chunk.copy_from_slice(net);
    }
    Ok(())
}

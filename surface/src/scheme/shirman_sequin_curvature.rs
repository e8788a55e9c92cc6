//! `shirman-sequin-curvature`: the modified Shirman–Séquin macro-patch with a cross-boundary
//! field that carries the vertices' shape tensors ([`crate::curvature_cross`]): the surface's
//! normal turns across each edge at its ends as the data's does (geodesic torsion), where
//! Chiyokura–Kimura's linear field averages it over the edge. Same layout, curves, interior
//! construction (β at every corner), straight crease corners and fallback as
//! `shirman-sequin`; no Jensen `c` (the field's quadratic freedom is spent on the data).

use nalgebra::Point3;

use super::shirman_sequin::BETA;
use super::shirman_sequin_1987::write_nets;
use super::{Continuity, FaceInput, Layout, ParameterSpec, Scheme, SchemeOptions, CENTROID_SPLIT};
use crate::curvature_cross::macro_patch_curvature;
use crate::fallback::fallback_patch;
use crate::fit::FaceFallbackReason;
use crate::shirman_sequin::{InteriorParameters, DEFAULT_C};

/// The scheme's parameters: `shirman-sequin`'s β.
pub const PARAMETERS: &[ParameterSpec] = &[BETA];

/// The curvature-matched variant with β at every corner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShirmanSequinCurvature {
    /// β at every corner.
    pub beta: f64,
}

impl ShirmanSequinCurvature {
    /// The variant with the options' β.
    pub fn from_options(options: &SchemeOptions) -> Self {
        ShirmanSequinCurvature {
            beta: options.value(&BETA),
        }
    }
}

impl Scheme for ShirmanSequinCurvature {
    fn name(&self) -> &'static str {
        "shirman-sequin-curvature"
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
        let params = InteriorParameters {
            beta: [self.beta; 3],
            c: [DEFAULT_C; 3],
        };
        let nets = macro_patch_curvature(
            input.vertices,
            input.edges,
            &params,
            input.creased_corners(),
        )
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

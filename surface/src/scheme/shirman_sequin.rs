//! `shirman-sequin`: Mann's modified Shirman–Séquin split-domain scheme, three quartic patches
//! per face over the centroid split on the face's cubic edge curves (derivation in
//! [`crate::shirman_sequin`]), with its C0 fallback ([`crate::fallback`]) for faces it cannot
//! fit. This file only adapts that module to the [`Scheme`] trait: the nets are the same, byte
//! for byte (Appendix A and B tests).

use nalgebra::Point3;

use super::{Continuity, FaceInput, Layout, ParameterSpec, Scheme, CENTROID_SPLIT};
use crate::fallback::fallback_patch;
use crate::fit::FaceFallbackReason;
use crate::shirman_sequin::{macro_patch, InteriorParameters, DEFAULT_BETA, DEFAULT_C};

/// Where the interior parameters come from.
#[derive(Clone, Copy)]
enum Interior<'a> {
    Uniform(InteriorParameters),
    PerFace(&'a (dyn Fn(usize) -> InteriorParameters + Sync)),
}

/// The modified Shirman–Séquin scheme with its interior parameters.
#[derive(Clone, Copy)]
pub struct ShirmanSequin<'a> {
    interior: Interior<'a>,
}

impl std::fmt::Debug for ShirmanSequin<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.interior {
            Interior::Uniform(p) => write!(f, "ShirmanSequin({p:?})"),
            Interior::PerFace(_) => write!(f, "ShirmanSequin(per face)"),
        }
    }
}

impl ShirmanSequin<'static> {
    /// The same β and c on every face.
    pub fn uniform(params: InteriorParameters) -> Self {
        ShirmanSequin {
            interior: Interior::Uniform(params),
        }
    }
}

impl<'a> ShirmanSequin<'a> {
    /// β and c of face `f` from `params(f)`.
    pub fn per_face(params: &'a (dyn Fn(usize) -> InteriorParameters + Sync)) -> Self {
        ShirmanSequin {
            interior: Interior::PerFace(params),
        }
    }

    fn params(&self, f: usize) -> InteriorParameters {
        match self.interior {
            Interior::Uniform(p) => p,
            Interior::PerFace(g) => g(f),
        }
    }
}

const PARAMETERS: &[ParameterSpec] = &[
    ParameterSpec {
        name: "beta",
        default: DEFAULT_BETA,
        summary: "interior-boundary parameter β of every face (Shirman–Séquin: 1/3)",
    },
    ParameterSpec {
        name: "c",
        default: DEFAULT_C,
        summary: "cross-boundary parameter c of every face (Shirman–Séquin: 1)",
    },
];

impl Scheme for ShirmanSequin<'_> {
    fn name(&self) -> &'static str {
        "shirman-sequin"
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

    fn parameters(&self) -> &'static [ParameterSpec] {
        PARAMETERS
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        let nets = macro_patch(input.vertices, input.edges, &self.params(input.face))
            .map_err(FaceFallbackReason::Scheme)?;
        if !nets
            .iter()
            .flatten()
            .all(|p| p.iter().all(|c| c.is_finite()))
        {
            return Err(FaceFallbackReason::NonFinite);
        }
        for (chunk, net) in out.chunks_exact_mut(15).zip(&nets) {
            chunk.copy_from_slice(net);
        }
        Ok(())
    }

    /// [`crate::fallback::fallback_patch`]: C0 on the shared edge curves.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        for (chunk, net) in out.chunks_exact_mut(15).zip(&fallback_patch(input.edges)) {
            chunk.copy_from_slice(net);
        }
    }
}

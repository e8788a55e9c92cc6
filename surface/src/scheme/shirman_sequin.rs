//! `shirman-sequin`: Mann's modified Shirman–Séquin split-domain scheme, three quartic patches
//! per face over the centroid split on the face's cubic edge curves (derivation in
//! [`crate::shirman_sequin`]), with its C0 fallback ([`crate::fallback`]) for faces it cannot
//! fit. This file adapts that module to the [`Scheme`] trait: the nets are the same, byte
//! for byte (Appendix A and B tests), a corner between two crease edges is built as a straight
//! crease corner where its tangents are opposite ([`crate::shirman_sequin::macro_patch_creased`],
//! from the crease lines the fit gives [`FaceInput::creases`]), and one choice of its own: a face whose macro-patch
//! turns over it (a patch normal at 90° or more from the face normal at a sample of the fold
//! measure, `surface::folds`) while the fallback patch on the same curves does not gets the
//! fallback ([`SchemeError::FoldsOverFace`]): a C0 crease instead of a fold
//! ([`ShirmanSequin::with_unfold`]; off by default, [`DEFAULT_UNFOLD`] says why). The test costs a
//! face the Bernstein coefficients of its projected Jacobian (a hundred dot products per
//! sub-patch, [`crate::fallback::worst_cosine`]); only faces they do not certify are sampled.

use nalgebra::Point3;

use super::{Continuity, FaceInput, Layout, ParameterSpec, Scheme, SchemeOptions, CENTROID_SPLIT};
use crate::fallback::{face_normal, fallback_patch, folds_over};
use crate::fit::FaceFallbackReason;
use crate::shirman_sequin::{
    macro_patch_creased, InteriorParameters, SchemeError, DEFAULT_BETA, DEFAULT_C,
};

/// Where the interior parameters come from.
#[derive(Clone, Copy)]
enum Interior<'a> {
    Uniform(InteriorParameters),
    PerFace(&'a (dyn Fn(usize) -> InteriorParameters + Sync)),
}

/// Whether a face whose macro-patch turns over it gets the fallback when that does not
/// (module docs): off by default, so the scheme's nets are exactly [`macro_patch`]'s wherever it
/// succeeds (the dBHS lumps of the 16 × 8 ring, 64 folded faces, stay as the seeds draw them).
/// On, whether a face is fitted regularly would depend on its interior parameters: the
/// `interior` study's corner measures, independent of β and c by construction, then jump by up
/// to 0.94 over its sweeps where a β folds a face. [`ShirmanSequin::with_unfold`] turns it on
/// (bunny on dBHS curves: 190 folded faces → 1).
pub const DEFAULT_UNFOLD: bool = false;

/// The modified Shirman–Séquin scheme with its interior parameters.
#[derive(Clone, Copy)]
pub struct ShirmanSequin<'a> {
    interior: Interior<'a>,
    unfold: bool,
}

impl std::fmt::Debug for ShirmanSequin<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.interior {
            Interior::Uniform(p) => write!(f, "ShirmanSequin({p:?}, unfold {})", self.unfold),
            Interior::PerFace(_) => write!(f, "ShirmanSequin(per face, unfold {})", self.unfold),
        }
    }
}

impl ShirmanSequin<'static> {
    /// The same β and c on every face.
    pub fn uniform(params: InteriorParameters) -> Self {
        ShirmanSequin {
            interior: Interior::Uniform(params),
            unfold: DEFAULT_UNFOLD,
        }
    }
}

impl<'a> ShirmanSequin<'a> {
    /// β and c of face `f` from `params(f)`.
    pub fn per_face(params: &'a (dyn Fn(usize) -> InteriorParameters + Sync)) -> Self {
        ShirmanSequin {
            interior: Interior::PerFace(params),
            unfold: DEFAULT_UNFOLD,
        }
    }

    /// The same scheme with the fallback for faces whose patch turns over them on (`true`,
    /// [`DEFAULT_UNFOLD`]) or off.
    pub fn with_unfold(self, unfold: bool) -> Self {
        ShirmanSequin { unfold, ..self }
    }

    fn params(&self, f: usize) -> InteriorParameters {
        match self.interior {
            Interior::Uniform(p) => p,
            Interior::PerFace(g) => g(f),
        }
    }
}

/// β at every corner. Any β > 0 gives a G1 surface, but the interior points move by `~1/β`
/// (the `m = 2` step divides by β): below 0.01 the nets reach 100× the triangle's size and the
/// surface folds; above 10 the first interior points overshoot the triangle tenfold. Appendix A
/// uses 1/3.
pub const BETA: ParameterSpec = ParameterSpec {
    name: "beta",
    symbol: "β",
    default: DEFAULT_BETA,
    range: (0.01, 10.0),
    range_reason: "the interior points move by ~1/β",
    summary: "interior-boundary parameter β at every corner (1/3: the Shirman–Séquin default, C1 inside each triangle)",
};

/// Jensen's c on every edge. `K(t)` is a quadratic in c; at 0.01 or 100 the cross-boundary
/// field already changes by 100× along an edge, beyond which the patch folds over itself. 1 is
/// Chiyokura–Kimura.
pub const C: ParameterSpec = ParameterSpec {
    name: "c",
    symbol: "c",
    default: DEFAULT_C,
    range: (0.01, 100.0),
    range_reason: "the cross-boundary field changes by c along an edge",
    summary: "Jensen's cross-boundary parameter c on every edge (1: Chiyokura–Kimura)",
};

/// The scheme's parameters.
pub const PARAMETERS: &[ParameterSpec] = &[BETA, C];

/// The uniform interior parameters `options` set (β at every corner, c on every edge).
pub fn uniform_parameters(options: &SchemeOptions) -> InteriorParameters {
    InteriorParameters {
        beta: [options.value(&BETA); 3],
        c: [options.value(&C); 3],
    }
}

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

    fn has_interior_parameters(&self) -> bool {
        true
    }

    fn build(
        &self,
        input: &FaceInput<'_>,
        out: &mut [Point3<f64>],
    ) -> Result<(), FaceFallbackReason> {
        // A corner between two crease edges may be a straight crease corner
        // (`crate::shirman_sequin`, "Straight crease corners").
        let creased = std::array::from_fn(|i| {
            input.crease_line(i, i).is_some() && input.crease_line(i, (i + 2) % 3).is_some()
        });
        let nets = macro_patch_creased(
            input.vertices,
            input.edges,
            &self.params(input.face),
            creased,
        )
        .map_err(FaceFallbackReason::Scheme)?;
        if !nets
            .iter()
            .flatten()
            .all(|p| p.iter().all(|c| c.is_finite()))
        {
            return Err(FaceFallbackReason::NonFinite);
        }
        if let Some(n) = face_normal(&input.vertices.map(|v| v.p)).filter(|_| self.unfold) {
            if folds_over(&nets, &n) && !folds_over(&fallback_patch(input.edges), &n) {
                return Err(FaceFallbackReason::Scheme(SchemeError::FoldsOverFace));
            }
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

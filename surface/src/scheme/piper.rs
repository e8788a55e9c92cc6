//! `piper`: after Piper, *Visually smooth interpolation with triangular Bézier patches* (in
//! G. Farin (ed.), *Geometric Modeling: Algorithms and New Trends*, SIAM 1987), the testbed
//! seed's Example 1 scheme (`Piper < octa.m | Tess …`): three quartic Bézier triangles per face
//! over the centroid split, on the shared cubic edge curves, G1 everywhere.
//!
//! # What is and is not Piper's
//!
//! Piper's paper could not be recovered: no text, summary or implementation of its
//! construction was found in the available sources (public pages, code and documentation
//! searched for the paper, its title and the testbed's fitters). What is known from the seeds
//! and the surveys that cite it is the frame: a split-domain scheme on the Clough–Tocher
//! (centroid) split, quartic patches, cubic boundary curves, visual (G1) smoothness across the
//! mesh edges. The one trace of Piper in the testbed's own sources is an option of its
//! modified Shirman–Séquin fitter (`piperBoundary`) that lengthens the projected
//! one-third-of-the-chord end tangent of a boundary curve by 10/9; as written it computes the
//! same length twice (which suggests a slip), and it breaks linear precision (a straight edge
//! of planar data would not be parametrized at thirds), so it is not adopted: this scheme uses
//! the curves of the chosen curve method like the other schemes on curves.
//!
//! The construction implemented is the closest well-defined one in that frame, and it is
//! derived rather than guessed:
//!
//! * Across a mesh edge, the quartic patch's cross-boundary derivative is a cubic in the edge
//!   parameter, and G1 with a neighbour that knows only the shared data needs a transversal
//!   field built from that data: the Chiyokura–Kimura field `K(t)Ĉ(t) + h(t)B'(t)` with `Ĉ`
//!   the linear blend of the unit perpendiculars `n × B'` at the ends
//!   ([`crate::shirman_sequin::chiyokura_kimura`], with `K` linear: Jensen's `c = 1`).
//! * Inside the face, C1 across the interior boundaries (the classical Clough–Tocher rules at
//!   quartic degree, `β = ⅓` in [`crate::shirman_sequin`]'s parametrization). Given the
//!   boundary curves and the corner cross vectors, the C1 conditions at the split determine
//!   every remaining interior point, and the m = 0 condition fixes the corner cross vectors as
//!   `I¹_i = V_i + ¼(E_a + E_b − 2V_i)` (quartic points; `E_a`, `E_b` the cubic points next to
//!   `V_i`): no free choice is left.
//!
//! Both choices together are exactly the modified Shirman–Séquin macro-patch at its default
//! parameters (`β = ⅓`, `c = 1`): the nets are built by [`crate::shirman_sequin::macro_patch`]
//! and are identical to `shirman-sequin`'s defaults (tested). So this entry is a named, fixed-
//! parameter member of that family, standing in for Piper's scheme, and any difference
//! between Piper's published construction and this one (his boundary curves, his transversal
//! field, his interior) is unknown here. It ignores `--beta` and `--c`.

use nalgebra::Point3;

use super::{Continuity, FaceInput, Layout, Scheme, CENTROID_SPLIT};
use crate::fallback::fallback_patch;
use crate::fit::FaceFallbackReason;
use crate::shirman_sequin::{macro_patch, InteriorParameters};

/// The quartic G1 split-domain scheme standing in for Piper's (module docs).
#[derive(Clone, Copy, Debug, Default)]
pub struct Piper;

/// Control points per quartic net.
const NP: usize = 15;

impl Scheme for Piper {
    fn name(&self) -> &'static str {
        "piper"
    }

    fn layout(&self) -> Layout {
        Layout {
            degree: 4,
            subs: &CENTROID_SPLIT,
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
        let nets = macro_patch(input.vertices, input.edges, &InteriorParameters::default())
            .map_err(FaceFallbackReason::Scheme)?;
        if !nets
            .iter()
            .flatten()
            .all(|p| p.iter().all(|c| c.is_finite()))
        {
            return Err(FaceFallbackReason::NonFinite);
        }
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&nets) {
            chunk.copy_from_slice(net);
        }
        Ok(())
    }

    /// [`crate::fallback::fallback_patch`]: C0 on the shared edge curves.
    fn fallback(&self, input: &FaceInput<'_>, out: &mut [Point3<f64>]) {
        for (chunk, net) in out.chunks_exact_mut(NP).zip(&fallback_patch(input.edges)) {
            chunk.copy_from_slice(net);
        }
    }
}

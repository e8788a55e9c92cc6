//! The local quadric fit of libigl's `igl::principal_curvature` (Panozzo, Puppo & Rocca,
//! *Efficient multi-scale curvature and crease estimation*, 2010).
//!
//! At each vertex `v`, with the vertex normal `n0` (given, else angle-weighted,
//! [`crate::normals`]) as the `z` axis of an orthonormal frame at `v`:
//!
//! 1. the neighbourhood is the `k`-ring of `v` ([`DEFAULT_RINGS`] = 2; libigl's `radius`
//!    argument), without `v` itself;
//! 2. the quadric `z = a x² + b xy + c y² + d x + e y` — through the vertex, no constant term —
//!    is fitted by least squares on coordinates scaled by the neighbourhood radius (libigl
//!    solves the same 5-unknown system by SVD; here pivoted QR, [`crate::fit`]);
//! 3. the curvature is that of the quadric at the origin: first fundamental form
//!    `E = 1 + d²`, `F = de`, `G = 1 + e²`, second `L = 2a/W`, `M = b/W`, `N = 2c/W`,
//!    `W = √(1 + d² + e²)`, Weingarten map `I⁻¹ II` (libigl's `CurvatureCalculator::
//!    getCurvature`; derivation in the [`crate::fit`] module docs), written as a world tensor.
//!
//! As in libigl the **normal is the vertex normal** `n0`, not the quadric's, and the tensor is
//! projected onto its tangent plane (`S ← P S P`, `P = I − n0 n0ᵀ`). This is what separates
//! `quadric` from `jet2`: no constant term (interpolating the vertex), a fixed ring, and the
//! first-estimate normal.
//!
//! **Fallbacks.** Fewer than 5 neighbours, rank deficiency or a condition number above
//! [`crate::fit::MAX_CONDITION`]: `S = 0` ([`crate::FallbackKind::Planar`]).

use mesh::Mesh;
use nalgebra::Vector3;

use crate::fit::{FitSpec, RingRule};
use crate::jet::estimate_by_fitting;
use crate::{Estimate, Estimator};

/// Default ring count `k` of the neighbourhood.
pub const DEFAULT_RINGS: usize = 2;

/// At most this many points: bounds the work at high-valence vertices.
pub const MAX_POINTS: usize = 200;

/// The libigl-style quadric estimator over the `rings`-ring.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Quadric {
    /// The neighbourhood's ring count `k`.
    pub rings: usize,
}

/// The registered `quadric` (2-ring).
pub static QUADRIC: Quadric = Quadric {
    rings: DEFAULT_RINGS,
};

impl Estimator for Quadric {
    fn name(&self) -> &'static str {
        "quadric"
    }

    fn description(&self) -> &'static str {
        "local quadric through the vertex over the 2-ring (libigl principal_curvature, Panozzo et al. 2010)"
    }

    fn estimate(&self, mesh: &Mesh, given: Option<&[Vector3<f64>]>) -> Estimate {
        let spec = FitSpec {
            degree: 2,
            constant: false,
            rule: RingRule {
                min_points: usize::MAX,
                max_rings: self.rings.max(1),
                max_points: MAX_POINTS,
            },
        };
        estimate_by_fitting(mesh, given, spec, false)
    }
}

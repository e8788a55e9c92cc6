//! The constructions the schemes are made of: the modified Shirman–Séquin macro-patch, its
//! 1987 and testbed variants, its curvature-matched cross-boundary field, and the C0 fallback patch of a face a scheme cannot fit.

pub mod curvature_cross;
pub mod fallback;
pub mod shirman_sequin;
pub mod ss_variants;

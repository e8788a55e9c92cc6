//! The constructions the schemes are made of: the modified Shirman–Séquin macro-patch, its
//! 1987 and testbed variants, and the C0 fallback patch of a face a scheme cannot fit.

pub mod fallback;
pub mod shirman_sequin;
pub mod ss_variants;

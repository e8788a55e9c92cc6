//! Measures of a fit: G1 across patch boundaries (of a fitted mesh, or of bare patches),
//! errors against the true surface, Section 4's corner measures, boundary-curve statistics,
//! folds, and sharp features (kinks on smooth data, creases kept, flat regions kept flat).

pub mod curve_stats;
pub mod ends;
pub mod folds;
pub mod g1;
pub mod interior;
pub mod metrics;
pub mod patch_g1;
pub mod sharp;

//! What several of the workspace's integration tests share.

#![allow(clippy::expect_used)] // a test helper fails loudly by design

use estimate::{estimator_by_name, Estimator, DEFAULT_ESTIMATOR};

/// The estimator `fit` and `convert` use unless told otherwise (`DEFAULT_ESTIMATOR`).
pub fn default_estimator() -> &'static dyn Estimator {
    estimator_by_name(DEFAULT_ESTIMATOR).expect("the default estimator is registered")
}

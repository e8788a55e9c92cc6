//! Shared test fixtures: numbers in [−1, 1) and vectors of them, drawn from the workbench's one
//! generator (`rng::SplitMix64`).

use nalgebra::Vector3;
use rng::SplitMix64;

/// Numbers in [−1, 1) from a seeded [`SplitMix64`].
pub struct Rng(SplitMix64);

impl Rng {
    /// The stream of `seed`.
    pub fn new(seed: u64) -> Self {
        Rng(SplitMix64::new(seed))
    }

    /// The next number in [−1, 1).
    pub fn next(&mut self) -> f64 {
        self.0.uniform(-1.0, 1.0)
    }

    /// A vector with coordinates in [−1, 1).
    pub fn vec(&mut self) -> Vector3<f64> {
        Vector3::new(self.next(), self.next(), self.next())
    }
}

//! Shared test fixtures: a seeded SplitMix64 generator of numbers in [−1, 1) and vectors.

use nalgebra::Vector3;

/// SplitMix64, seeded.
pub struct Rng(pub u64);

impl Rng {
    /// The next number in [−1, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// A vector with coordinates in [−1, 1).
    pub fn vec(&mut self) -> Vector3<f64> {
        Vector3::new(self.next(), self.next(), self.next())
    }
}

//! [`SplitMix64`]: the one seeded pseudo-random generator of the workbench.
//!
//! Every random choice of the workbench comes from it: the fixtures' irregular meshes
//! (`fixtures`, which re-exports it), the irregular shapes of `subdiv`, the fuzzer's mutations
//! (`fuzz`), and the random inputs of unit and integration tests. Streams are fixed by their
//! seed and by this file alone, so a committed result or golden number that depends on one
//! reproduces exactly, with no dependency whose stream could change between versions.
//!
//! Why a crate of its own: its users sit at the bottom of both sides of the dependency graph.
//! `solver` (and `cost` above it) depend on nothing of the workbench's, `meshio` is the lowest
//! crate of the mesh side, and both have tests that draw numbers; `fixtures` (which generates
//! meshes) sits above `meshio`. A module of `meshio` would make `solver` and `cost` depend on a
//! mesh-file crate to draw a number, and a module of `fixtures` cannot serve `meshio`'s own
//! tests without a dev-dependency cycle. This crate has no dependencies, so anything can depend
//! on it.

/// Steele, Lea and Flood's SplitMix64 (the generator of Java's `SplittableRandom`, and Vigna's
/// seeding generator for xoshiro): 64 bits of state advanced by the golden-ratio increment,
/// each output a bijective mix of the state. It passes BigCrush, and two seeds give unrelated
/// streams. Not for cryptography.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator whose stream is fixed by `seed` (any value, 0 included).
    pub const fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`: the top 53 bits of [`SplitMix64::next_u64`] times 2⁻⁵³ (exact,
    /// every multiple of 2⁻⁵³ equally likely).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[lo, hi)`: `lo + (hi − lo) · next_f64()`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// Uniform integer in `0..n` (`0` when `n` is 0), `next_u64() % n`; the modulo bias is
    /// below `n / 2⁶⁴`.
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next_u64() % n as u64) as usize
        }
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.next_f64() < p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The published reference outputs: Vigna's `splitmix64.c` seeded with 0, and the seed
    /// 1234567 test vector of the SplitMix64 literature (Java's `SplittableRandom`).
    #[test]
    fn reference_outputs() {
        let mut r = SplitMix64::new(0);
        let first: Vec<u64> = (0..5).map(|_| r.next_u64()).collect();
        assert_eq!(
            first,
            [
                0xE220_A839_7B1D_CDAF,
                0x6E78_9E6A_A1B9_65F4,
                0x06C4_5D18_8009_454F,
                0xF88B_B8A8_724C_81EC,
                0x1B39_896A_51A8_749B,
            ]
        );
        let mut r = SplitMix64::new(1_234_567);
        assert_eq!(r.next_u64(), 6_457_827_717_110_365_317);
        assert_eq!(r.next_u64(), 3_203_168_211_198_807_973);
        assert_eq!(r.next_u64(), 9_817_491_932_198_370_423);
    }

    #[test]
    fn floats_are_the_top_53_bits() {
        let mut r = SplitMix64::new(0);
        let x = r.next_f64();
        assert_eq!(
            x,
            (0xE220_A839_7B1D_CDAFu64 >> 11) as f64 / 9_007_199_254_740_992.0
        );
        assert_eq!(x, 0.883_310_808_213_642_6);
        // `uniform` and `chance` read the next float the same way.
        let mut a = SplitMix64::new(3);
        let mut b = SplitMix64::new(3);
        let u = b.next_f64();
        assert_eq!(a.uniform(-1.0, 1.0), -1.0 + 2.0 * u);
        let v = b.next_f64();
        assert_eq!(a.chance(0.5), v < 0.5);
    }

    #[test]
    fn ranges_are_respected() {
        let mut r = SplitMix64::new(42);
        let mut seen = [0usize; 7];
        for _ in 0..7000 {
            let x = r.uniform(-2.0, 3.0);
            assert!((-2.0..3.0).contains(&x));
            seen[r.below(7)] += 1;
        }
        // Every value of `below(7)` about a seventh of the time (1000 ± 5 σ, σ ≈ 29).
        assert!(seen.iter().all(|&n| (850..1150).contains(&n)), "{seen:?}");
        assert_eq!(r.below(0), 0);
        assert!(!r.chance(0.0) && r.chance(1.0));
    }

    /// Cloning forks the stream: both copies continue identically.
    #[test]
    fn clones_continue_the_same_stream() {
        let mut a = SplitMix64::new(9);
        a.next_u64();
        let mut b = a.clone();
        assert_eq!(a.next_u64(), b.next_u64());
    }
}

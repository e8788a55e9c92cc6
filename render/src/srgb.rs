//! Linear → 8-bit sRGB by table, equal to the formula for every `f32`.
//!
//! The exact conversion ([`to_srgb8_exact`]) clamps to `[0, 1]`, applies the sRGB transfer
//! function (`12.92 c` below 0.0031308, `1.055 c^(1/2.4) − 0.055` above, in `f32` with
//! `powf`) and rounds `255 s` to the nearest byte. It is a non-decreasing step function of `c`,
//! so it is described completely by its 255 **thresholds**: the smallest `f32` at which each
//! level 1…255 is reached. [`Srgb8Table`] finds them once per process (a binary search over the
//! bit patterns of `[0, 1]`, 255 × 31 evaluations of the formula) and converts by
//!
//! 1. a start level from a 4096-entry table indexed by `⌊4096 c⌋` (the formula's level at the
//!    bucket's lower end, `i / 4096`; the scaling by a power of two is exact, so the index never
//!    rounds into the next bucket), then
//! 2. stepping up while `c` has reached the next threshold (at most two steps: the steepest part
//!    of the curve, `12.92 · 255 ≈ 3295` levels per unit, puts at most 0.81 level change in a
//!    bucket).
//!
//! The result is the number of thresholds at or below `c`, which equals the formula wherever
//! the formula is non-decreasing. It is: the unit tests compare both on every `f32` within 4096
//! ulps of every threshold (the only places where a non-monotone `powf` could change a rounded
//! byte) and on a stride of all of `[0, 1]`; `table_matches_the_formula_for_every_f32`
//! (ignored by default, run with `cargo test --release -p render -- --ignored`) compares all
//! 1 065 353 218 values of `[0, 1]` and measured **no difference** (maximum difference 0 levels).
//! NaN and values at or below zero give 0, values at or above one give 255, as the formula does.

use std::sync::OnceLock;

/// Buckets of the start-level table (a power of two, so `c · BUCKETS` is exact).
const BUCKETS: usize = 4096;

/// Linear → sRGB byte by the formula (one `powf`): the reference [`to_srgb8`] reproduces. The
/// formula is the one the mesh writers store colours by (`meshio::srgb::encode_byte`).
pub fn to_srgb8_exact(c: f32) -> u8 {
    meshio::srgb::encode_byte(c)
}

/// Linear → sRGB byte by table; equal to [`to_srgb8_exact`] for every `f32` (module docs).
#[inline]
pub fn to_srgb8(c: f32) -> u8 {
    Srgb8Table::get().encode(c)
}

/// The thresholds of the 8-bit sRGB encoding and a start-level table (module docs).
#[derive(Clone, Debug)]
pub struct Srgb8Table {
    /// `threshold[k]`: the smallest `f32` whose exact encoding is at least `k` (`k ≥ 1`);
    /// `threshold[0]` is unused (0).
    threshold: [f32; 256],
    /// `start[i]`: the exact encoding of `i / BUCKETS`.
    start: [u8; BUCKETS],
}

static TABLE: OnceLock<Srgb8Table> = OnceLock::new();

impl Srgb8Table {
    /// The process's table, built on first use (about 8 000 evaluations of the formula).
    pub fn get() -> &'static Srgb8Table {
        TABLE.get_or_init(Srgb8Table::build)
    }

    fn build() -> Srgb8Table {
        let one = 1.0f32.to_bits();
        let mut threshold = [0.0f32; 256];
        for (k, t) in threshold.iter_mut().enumerate().skip(1) {
            // Smallest bit pattern in [0, 1] whose encoding reaches k; the encoding of 1 is 255.
            let (mut lo, mut hi) = (0u32, one);
            while lo < hi {
                let mid = lo + (hi - lo) / 2;
                if usize::from(to_srgb8_exact(f32::from_bits(mid))) >= k {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            *t = f32::from_bits(lo);
        }
        let mut start = [0u8; BUCKETS];
        for (i, s) in start.iter_mut().enumerate() {
            let c = i as f32 / BUCKETS as f32;
            *s = threshold[1..].iter().filter(|t| **t <= c).count() as u8;
        }
        Srgb8Table { threshold, start }
    }

    /// The smallest `f32` whose encoding is at least `level` (0 for level 0).
    pub fn threshold(&self, level: u8) -> f32 {
        self.threshold[usize::from(level)]
    }

    /// Linear → sRGB byte (equal to [`to_srgb8_exact`]).
    #[inline]
    pub fn encode(&self, c: f32) -> u8 {
        // NaN, zero and below.
        if c.is_nan() || c <= 0.0 {
            return 0;
        }
        if c >= 1.0 {
            return 255;
        }
        // c in (0, 1): the index is below BUCKETS; `get` keeps a panic out regardless.
        let mut level = self
            .start
            .get((c * BUCKETS as f32) as usize)
            .copied()
            .unwrap_or(255);
        while level < 255 && c >= self.threshold[usize::from(level) + 1] {
            level += 1;
        }
        level
    }

    /// [`encode`](Self::encode) of three channels.
    #[inline]
    pub fn encode3(&self, c: [f32; 3]) -> [u8; 3] {
        c.map(|x| self.encode(x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ulps either side of each threshold compared one by one: far more than the error of
    /// `powf` (an ulp or two), which is what could make the formula non-monotone there.
    const NEIGHBOURHOOD: u32 = 4096;

    /// Stride through the bit patterns of `[0, 1]` for the coarse comparison (prime, so every
    /// low-bit pattern is visited; about 4 million values).
    const STRIDE: usize = 251;

    #[test]
    fn table_matches_the_formula_near_every_level_change() {
        let t = Srgb8Table::get();
        for k in 1..=255u8 {
            let b = t.threshold(k).to_bits();
            assert_eq!(to_srgb8_exact(t.threshold(k)), k);
            assert_eq!(to_srgb8_exact(f32::from_bits(b - 1)), k - 1);
            for bits in b.saturating_sub(NEIGHBOURHOOD)..=b + NEIGHBOURHOOD {
                let c = f32::from_bits(bits);
                assert_eq!(t.encode(c), to_srgb8_exact(c), "{c:e} ({bits:#x})");
            }
        }
    }

    #[test]
    fn table_matches_the_formula_on_a_stride_and_at_special_values() {
        let t = Srgb8Table::get();
        for bits in (0..=1.0f32.to_bits()).step_by(STRIDE) {
            let c = f32::from_bits(bits);
            assert_eq!(t.encode(c), to_srgb8_exact(c), "{c:e}");
        }
        for c in [
            f32::NAN,
            -f32::NAN,
            f32::NEG_INFINITY,
            -1.0,
            -0.0,
            0.0,
            f32::MIN_POSITIVE,
            1e-45,
            0.003_130_8,
            0.5,
            1.0 - f32::EPSILON / 2.0,
            1.0,
            1.5,
            f32::INFINITY,
        ] {
            assert_eq!(t.encode(c), to_srgb8_exact(c), "{c:e}");
            assert_eq!(to_srgb8(c), to_srgb8_exact(c), "{c:e}");
        }
    }

    #[test]
    #[ignore = "every f32 of [0, 1]: about 10 s in release, minutes unoptimized"]
    fn table_matches_the_formula_for_every_f32() {
        use rayon::prelude::*;
        let t = Srgb8Table::get();
        let one = 1.0f32.to_bits();
        let chunks: Vec<u32> = (0..=one).step_by(1 << 20).collect();
        let bad: usize = chunks
            .into_par_iter()
            .map(|lo| {
                (lo..=(lo + (1 << 20) - 1).min(one))
                    .filter(|&b| {
                        let c = f32::from_bits(b);
                        t.encode(c) != to_srgb8_exact(c)
                    })
                    .count()
            })
            .sum();
        assert_eq!(bad, 0);
    }
}

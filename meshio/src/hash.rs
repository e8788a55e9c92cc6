//! [`FxHasher`]: the one fast, non-cryptographic hasher of the workbench, for hash maps whose
//! keys are small (names of a `.m` file, grid cells of a weld) and where SipHash's cost shows.
//!
//! It is the multiply–rotate step of FxHash (the hash of Firefox and of rustc before
//! `rustc-hash` 2): `state = (state.rotate_left(5) ^ word) · 0x517c_c1b7_2722_0a95`, a word
//! being 8 bytes read little-endian, so a 24-byte key is three steps, not twenty-four. Its
//! [`finish`](std::hash::Hasher::finish) folds the high bits down, because the multiply leaves
//! the low bits (those a table's bucket index is taken from) depending on the low input bits
//! only: keys that differ only in their last bytes would otherwise share buckets.
//!
//! Not for untrusted keys unless seeded per table: [`FxBuildHasher::with_seed`] with a random
//! seed (as the `.m` reader does) keeps collisions from being planted in a file.
//!
//! It lives here, in the lowest crate of the mesh side that both of its users depend on (the
//! `.m` reader in this crate, the weld of `surface`), so that there is one definition and no
//! crate-to-crate copy.

use std::collections::HashMap;
use std::hash::{BuildHasher, Hasher};

/// FxHash's multiply constant (odd, so each step is a bijection of the state).
const MULTIPLY: u64 = 0x517c_c1b7_2722_0a95;
/// The golden-ratio constant of the final fold.
const FOLD: u64 = 0x9e37_79b9_7f4a_7c15;

/// The multiply–rotate hasher (module docs). [`Default`] starts from state 0.
#[derive(Clone, Copy, Debug, Default)]
pub struct FxHasher(u64);

impl FxHasher {
    /// A hasher starting from `seed`.
    pub const fn with_seed(seed: u64) -> Self {
        FxHasher(seed)
    }

    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(MULTIPLY);
    }
}

impl Hasher for FxHasher {
    /// The bytes as little-endian 8-byte words; a last partial word is zero-padded and
    /// marked (`^ 0xff`). (Keys of different lengths are told apart by the length a slice
    /// hashes first, not by the mark.)
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            let mut w = [0u8; 8];
            w.copy_from_slice(c);
            self.add(u64::from_le_bytes(w));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut w = [0u8; 8];
            w[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(w) ^ 0xff);
        }
    }

    fn write_u64(&mut self, n: u64) {
        self.add(n);
    }

    fn write_i64(&mut self, n: i64) {
        self.add(n as u64);
    }

    fn write_usize(&mut self, n: usize) {
        self.add(n as u64);
    }

    fn finish(&self) -> u64 {
        let x = self.0 ^ (self.0 >> 32);
        x.wrapping_mul(FOLD) ^ (x >> 29)
    }
}

/// Builds [`FxHasher`]s from one seed ([`Default`]: seed 0, for keys that are not
/// adversarial).
#[derive(Clone, Copy, Debug, Default)]
pub struct FxBuildHasher {
    seed: u64,
}

impl FxBuildHasher {
    /// Hashers starting from `seed`.
    pub const fn with_seed(seed: u64) -> Self {
        FxBuildHasher { seed }
    }
}

impl BuildHasher for FxBuildHasher {
    type Hasher = FxHasher;

    fn build_hasher(&self) -> FxHasher {
        FxHasher::with_seed(self.seed)
    }
}

/// A [`HashMap`] hashed with [`FxHasher`].
pub type FxHashMap<K, V> = HashMap<K, V, FxBuildHasher>;

#[cfg(test)]
mod tests {
    use super::*;

    // Expected values computed independently (Python) from the definition in the module docs.

    #[test]
    fn one_word_is_one_multiply_then_the_fold() {
        let mut h = FxHasher::default();
        h.write_u64(1);
        // State (0·rotl 5 ^ 1)·K = K; then the fold.
        assert_eq!(h.0, MULTIPLY);
        assert_eq!(h.finish(), 0x18a3_dd23_be19_2c71);
        // The same word as bytes, and as the other integer widths that map to it.
        let mut b = FxHasher::default();
        b.write(&1u64.to_le_bytes());
        assert_eq!(b.finish(), h.finish());
        let (mut i, mut u) = (FxHasher::default(), FxHasher::default());
        i.write_i64(1);
        u.write_usize(1);
        assert_eq!((i.finish(), u.finish()), (h.finish(), h.finish()));
    }

    #[test]
    fn names_hash_as_length_then_padded_words() {
        // A map key `&[u8]` hashes its length, then its bytes.
        let key: &[u8] = b"v17";
        assert_eq!(
            FxBuildHasher::default().hash_one(key),
            0xb3ad_274e_07c2_6c06
        );
        assert_eq!(
            FxBuildHasher::with_seed(12345).hash_one(key),
            0x2ab3_d6c0_9a3c_5a24
        );
        // Eleven bytes: one full word and a marked partial one.
        let key: &[u8] = b"corner_name";
        assert_eq!(
            FxBuildHasher::default().hash_one(key),
            0x3c54_26cf_bec6_983e
        );
        // The partial word is marked: `"a"` is the word 0x61 ^ 0xff, not 0x61.
        let mut partial = FxHasher::default();
        partial.write(b"a");
        let mut marked = FxHasher::default();
        marked.write_u64(0x61 ^ 0xff);
        let mut unmarked = FxHasher::default();
        unmarked.write_u64(0x61);
        assert_eq!(partial.finish(), marked.finish());
        assert_ne!(partial.finish(), unmarked.finish());
    }

    #[test]
    fn grid_cells_hash_as_three_words() {
        // `[i64; 3]` hashes its length, then its 24 bytes: three words.
        assert_eq!(
            FxBuildHasher::default().hash_one([1i64, -2, 3]),
            0x721e_6cba_c502_483d
        );
        let mut m: FxHashMap<[i64; 3], usize> = FxHashMap::default();
        m.insert([1, -2, 3], 7);
        m.insert([1, -2, 4], 8);
        assert_eq!(
            (m.get(&[1, -2, 3]), m.get(&[1, -2, 4])),
            (Some(&7), Some(&8))
        );
    }

    /// The fold spreads keys that differ in their last bits over the low (bucket) bits.
    #[test]
    fn low_bits_depend_on_every_word() {
        let low = |k: [i64; 3]| FxBuildHasher::default().hash_one(k) & 0xff;
        let distinct: std::collections::HashSet<u64> =
            (0..64).map(|z| low([1 << 40, 0, z << 32])).collect();
        assert!(distinct.len() > 32, "{}", distinct.len());
    }
}

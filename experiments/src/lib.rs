//! The parts of the experiment runner that other tools read the same way: the shard files of
//! `sweep` (for `merge` and the fuzz harness). The runner itself is the `experiments` binary.

pub mod shard;

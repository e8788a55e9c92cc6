//! The parts of the experiment runner that other tools read or run the same way: the shard files
//! of `sweep` (for `merge` and the fuzz harness), and the sweep's grid and task function
//! ([`sweep_tasks`], for front ends that schedule the tasks themselves) with what they need
//! (the data sets, the fit job's fit kept, the limits, the errors). The runner itself is the
//! `experiments` binary, whose experiments use these modules under the same names.

pub mod curve_args;
pub mod datasets;
pub mod error;
pub mod input;
pub mod limits;
pub mod shard;
pub mod study;
pub mod subdivision;
pub mod sweep_tasks;

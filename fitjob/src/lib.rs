//! The end-to-end fit as one library job: a data set, a mesh file, a raw mesh in memory or a
//! prepared mesh is
//! read, repaired, completed by an estimator, fitted with a surface scheme on boundary curves,
//! measured (G1 and interpolation), optionally tessellated, and written, with the memory
//! estimates checked before the large allocations and every output path checked before any
//! work; the result is a typed, serializable [`FitReport`].
//!
//! Every front end calls [`run`] with one [`FitOptions`]: `experiments fit`, the pipeline's
//! `testbed fit`, the studies, the Python package. So the limits, the streaming, the fallbacks
//! and the measures are the same wherever a user comes in.
//!
//! ```text
//! FitOptions ─► input::load ─► scheme + curve method ─► fit (streamed, or whole when kept or
//!   the interior is optimized) ─► G1 ─► patches out ─► tessellation out ─► FitReport (+ Kept)
//! ```
//!
//! * [`options`] — [`FitOptions`]: input, scheme and parameters, curves and solver, interior,
//!   tessellation, outputs;
//! * [`input`] — the input and its completion ([`input::load`]);
//! * [`limits`] — valid ranges and memory estimates, shared by every front end;
//! * [`output`] — safe writing of the outputs and the checks made on their paths;
//! * [`report`] — [`FitReport`] and the terminal summary;
//! * [`error`] — [`JobError`];
//! * `cli` (feature `cli`) — the command lines' `--scheme` and scheme-parameter options,
//!   generated from the registry.
//!
//! This crate sits above `surface` (patches, schemes, G1, tessellation), `estimate`, `subdiv`
//! and `render` (the colour maps of written meshes): the job needs all of them, and none of
//! them needs the job.

#[cfg(feature = "cli")]
pub mod cli;
pub mod colour;
pub mod error;
pub mod input;
pub mod limits;
pub mod options;
pub mod output;
pub mod report;
mod run;
mod subdivision;

pub use error::{chain, JobError};
pub use input::{InputOptions, Source};
pub use options::FitOptions;
pub use output::destination;
pub use report::FitReport;
pub use run::{run, FitOutcome, Kept};

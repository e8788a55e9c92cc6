//! The testbed pipeline of Lounsbery et al. (1990), *A testbed for the comparison of
//! parametric surface methods* (§§2–3.5; docs/references.md): standalone
//! filters connected by pipes, passing a stream of self-describing records.
//!
//! * [`stream`] — records in and out: JSON Lines (default), the seed's dstruct external
//!   format ([`dstruct`]), a self-describing binary form ([`binary`]); the input format is
//!   detected, the output follows it unless chosen;
//! * [`tape`] — a record in memory: tokens over one text buffer, reused from record to
//!   record (no `serde_json::Value` per record), read and written by every format ([`json`],
//!   [`dstruct`], [`binary`]);
//! * [`record`] — the record schemas (`BezierTriangle`, `Triangle`) read from a tape straight
//!   into typed structs;
//! * [`triangle_mesh`] — the shared-vertex record `TriangleMesh` (a patch's vertices once,
//!   its triangles as indices): `tess --mesh` writes it, every filter reads it;
//! * [`fit`](mod@fit) — the head: a mesh file to patches (Fitter0, Piper, … by the
//!   workbench's schemes), or sampled straight to triangles (Example 5);
//! * [`filters`] — Tess, Mat0, KColor, Radial, and the pass-through rules;
//! * [`g1`](mod@g1) — G1 as a filter: records through, normal angles along shared boundaries
//!   on standard error;
//! * [`draw`] — the tail: Render (shaded PNG), XRender (wire-frame PNG), a mesh file.
//!
//! Every filter keeps the fields and records it does not use (see [`filters`] for the fields
//! a transforming filter carries over), so a field added at the head arrives at the end.

pub mod binary;
pub mod draw;
pub mod dstruct;
pub mod error;
pub mod filters;
pub mod fit;
pub mod g1;
pub mod json;
pub mod record;
pub mod stream;
pub mod tape;
pub mod triangle_mesh;

pub use error::{FieldError, FilterError, Position, StreamError};
pub use stream::{Format, Record, RecordReader, RecordWriter};

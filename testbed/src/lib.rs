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
//! * [`filters`] — the filters, one module each, and their registry (`testbed`'s
//!   subcommands): [`fit`](mod@filters::fit) (the head: a mesh file to patches, or sampled
//!   straight to triangles), `tess`, [`g1`](mod@filters::g1), `mat0`, `kcolor`, `radial`,
//!   `render`, `wire`, `to-mesh`;
//! * the filters' shared machinery: [`pipe`] (the stream options every filter takes and the
//!   [`Pipe`](pipe::Pipe) it reads and writes through), [`sample`] (tessellated vertices and
//!   the `Triangle` records built from them), [`tessellator`] (the patch tessellator),
//!   [`binders`] (the colour binders of `mat0`, `kcolor`, `radial`), [`hold`] (records held
//!   back in order in bounded memory, the rest in a temporary file), [`triangle_store`] (the
//!   pictures' triangles kept for replaying, likewise), [`scratch_file`] (those temporary
//!   files), [`draw`] (reading the
//!   triangles at the end of the pipeline, the pictures), [`options`] (option values parsed
//!   alike).
//!
//! Every filter keeps the fields and records it does not use (see [`filters`] for the fields
//! a transforming filter carries over), so a field added at the head arrives at the end.

pub mod binary;
pub mod binders;
pub mod bzp;
pub mod draw;
pub mod dstruct;
pub mod error;
pub mod filters;
pub mod hold;
pub mod json;
pub mod options;
pub mod pipe;
pub mod record;
pub mod sample;
pub mod scratch_file;
pub mod stream;
pub mod tape;
pub mod tessellator;
pub mod triangle_mesh;
pub mod triangle_store;

/// The `g1` filter at its former path (`testbed::g1`).
pub use filters::g1;

pub use error::{FieldError, FilterError, Position, StreamError};
pub use stream::{Format, Record, RecordReader, RecordWriter};

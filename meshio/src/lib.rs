//! Mesh file formats of the workbench.
//!
//! Every reader parses a file into a [`RawMesh`] (positions, optional per-vertex normals,
//! shape tensors, colours and other properties, polygons, notes), and every writer writes one.
//! Validation and repair (non-manifold edges, orientation, degenerate faces) happen in the
//! `mesh` crate, so a reader's only job is to read exactly what the file says, or to say
//! exactly where it cannot.
//!
//! Formats ([`FORMATS`]):
//!
//! | name | extensions | read | write | module |
//! | --- | --- | --- | --- | --- |
//! | `ply` | `.ply` | ascii, binary little and big endian | binary little endian (ascii option) | [`ply`] |
//! | `obj` | `.obj` | yes | yes | [`obj`] |
//! | `stl` | `.stl` | ascii and binary | binary (ascii option) | [`stl`] |
//! | `off` | `.off` | `OFF`, `COFF`, `NOFF`, `CNOFF` | `OFF`/`NOFF`/`COFF` | [`off`] |
//! | `testbed` | `.m` | yes | yes | [`testbed`] |
//! | `glb` | `.glb` | glTF 2.0 binary (triangles, node transforms) | glTF 2.0 binary | [`glb`] |
//!
//! Readers never panic, whatever the bytes: they return a [`ReadError`] naming the format, the
//! place ([`Location`]: line, element record, byte, header) and the problem. They refuse NaN and
//! infinite numbers and out-of-range face indices, keep polygons as polygons (no
//! triangulation), and do not check topology. Memory stays within a small multiple of the input
//! size: no reader reserves room from a header count before checking it against the bytes
//! left.
//!
//! Written files follow the conventions other tools' users expect ([`convention`]): the
//! exported curvature sign (`H > 0` on a sphere with outward normals, as libigl, trimesh and
//! MeshLab), sRGB colours in PLY, OBJ and OFF ([`srgb`]), one all-float PLY layout, glTF's up
//! axis, and the generator and convention named in every file.
//!
//! Every file the workbench writes, mesh or not, goes through [`outfile`]: atomically, only
//! over a regular file or nothing, with temporaries removed on failure and on interruption.

pub mod bounds;
pub mod convention;
pub mod direct;
pub mod error;
pub mod format;
pub mod glb;
pub mod hash;
pub mod obj;
pub mod off;
pub mod outfile;
pub mod ply;
pub mod raw;
pub mod srgb;
pub mod stl;
pub mod testbed;
mod util;

pub use bounds::{bounding_size, BoundingBox};
pub use convention::{ColorMap, Curvature, UpAxis, GENERATOR};
pub use error::{Location, MeshIoError, ReadError, WriteError};
pub use format::{
    format_by_name, format_for_path, read_bytes, read_file, readable_extensions, sniff_format,
    writable_extensions, write_bytes, MeshFormat, WriteOptions, FORMATS,
};
pub use raw::{Polygons, RawMesh, VertexProperties};

//! The [`MeshFormat`] trait, the registry [`FORMATS`], and reading a file by extension and
//! content.
//!
//! [`read_file`] picks a format by the file's extension (case-insensitive), but trusts the
//! content: when the bytes are recognisably another format (a PLY saved as `.obj`), that
//! format reads them and the mesh gets a note saying so. A file with an unknown extension is
//! read by whichever format recognises its content. Memory stays within a small multiple of
//! the file size: the file is read into memory once, and no reader allocates from a count in a
//! header before checking it against the bytes left.

use std::path::Path;

use crate::convention::UpAxis;
use crate::error::{MeshIoError, ReadError, WriteError};
use crate::raw::RawMesh;

/// How to write: the choices some formats offer. Formats ignore the options they have no use
/// for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WriteOptions {
    /// Write text instead of binary (PLY, STL). Default: binary.
    pub ascii: bool,
    /// Write positions as 64-bit floats (PLY `double`). Default: 32-bit floats.
    pub double_precision: bool,
    /// The data's up axis, for formats that fix one (glTF is `y` up). Default: `z`, turned into
    /// glTF's `y` ([`UpAxis::to_gltf`]).
    pub up: UpAxis,
}

impl WriteOptions {
    /// The defaults: binary, 32-bit floats, `z` up.
    pub fn new() -> Self {
        Self::default()
    }

    /// Text instead of binary.
    pub fn ascii(mut self) -> Self {
        self.ascii = true;
        self
    }

    /// 64-bit positions.
    pub fn double_precision(mut self) -> Self {
        self.double_precision = true;
        self
    }

    /// The data's up axis.
    pub fn up(mut self, up: UpAxis) -> Self {
        self.up = up;
        self
    }
}

/// One mesh file format: its name and extensions, how to recognise it, how to read and write
/// it.
pub trait MeshFormat: Sync {
    /// Short lower-case name (`"ply"`, `"obj"`, …), unique in [`FORMATS`].
    fn name(&self) -> &'static str;

    /// File extensions, lower case, without the dot.
    fn extensions(&self) -> &'static [&'static str];

    /// True when `bytes` (the start of a file, or the whole file) look like this format. May be
    /// called with any bytes; never panics. Formats whose signature depends on the file size
    /// (binary STL) recognise it only when given the whole file.
    fn sniff(&self, bytes: &[u8]) -> bool;

    /// True when [`MeshFormat::read`] is implemented.
    fn can_read(&self) -> bool {
        true
    }

    /// True when [`MeshFormat::write`] is implemented.
    fn can_write(&self) -> bool {
        true
    }

    /// True if its writer keeps [`RawMesh::properties`] (named per-vertex scalars such as
    /// `gaussian` and `mean`), so that a caller adds them only where they are written.
    fn writes_properties(&self) -> bool {
        false
    }

    /// True if its writer stores [`RawMesh::curvature`], so that a caller computes it (and its
    /// values are checked) only where it is written.
    fn writes_curvature(&self) -> bool {
        false
    }

    /// True if its writer stores [`RawMesh::shapes`] (the shape tensors), so that a caller fills
    /// them (36 bytes a vertex… 72 at f64) only where they are written.
    fn writes_shapes(&self) -> bool {
        false
    }

    /// Parses a whole file.
    fn read(&self, bytes: &[u8]) -> Result<RawMesh, ReadError>;

    /// Writes a whole file to `out`: the format's one encoder. Every check that can refuse the
    /// mesh runs before the first byte is written, so a [`WriteError::Invalid`] leaves `out`
    /// untouched; the bytes go out in chunks of a few hundred KiB (never the whole file in
    /// memory), and a failing `out` gives [`WriteError::Io`]. `out` is flushed at the end.
    fn write_to(
        &self,
        mesh: &RawMesh,
        options: &WriteOptions,
        out: &mut dyn std::io::Write,
    ) -> Result<(), WriteError>;

    /// About how many bytes [`MeshFormat::write_to`] writes for `mesh`, so that
    /// [`MeshFormat::write`] reserves its `Vec` once instead of growing it by doubling (a
    /// 10⁶-triangle PLY took 2.3 times as long without it). A guess, never needed for
    /// correctness; 0 when unknown.
    fn size_hint(&self, mesh: &RawMesh, options: &WriteOptions) -> usize {
        let _ = (mesh, options);
        0
    }

    /// Writes a whole file into memory ([`MeshFormat::write_to`] into a `Vec` of
    /// [`MeshFormat::size_hint`] bytes).
    fn write(&self, mesh: &RawMesh, options: &WriteOptions) -> Result<Vec<u8>, WriteError> {
        let mut bytes = Vec::with_capacity(self.size_hint(mesh, options));
        self.write_to(mesh, options, &mut bytes)?;
        Ok(bytes)
    }
}

/// Every format, in the order content sniffing tries them (the most specific signatures
/// first: PLY and glTF have magic bytes, OBJ has none and comes last).
pub static FORMATS: &[&dyn MeshFormat] = &[
    &crate::ply::Ply,
    &crate::glb::Glb,
    &crate::off::Off,
    &crate::stl::Stl,
    &crate::testbed::Testbed,
    &crate::obj::Obj,
];

/// The format called `name` (case-insensitive).
pub fn format_by_name(name: &str) -> Option<&'static dyn MeshFormat> {
    FORMATS
        .iter()
        .copied()
        .find(|f| f.name().eq_ignore_ascii_case(name))
}

/// The format a path's extension names (case-insensitive: `.OBJ` is OBJ).
pub fn format_for_path(path: &Path) -> Option<&'static dyn MeshFormat> {
    let ext = path.extension()?.to_str()?;
    FORMATS
        .iter()
        .copied()
        .find(|f| f.extensions().iter().any(|e| e.eq_ignore_ascii_case(ext)))
}

/// The extensions of every writable format, in registry order (`["obj", "ply", …]`), for
/// messages that say what an output path may end in.
pub fn writable_extensions() -> Vec<&'static str> {
    FORMATS
        .iter()
        .filter(|f| f.can_write())
        .flat_map(|f| f.extensions().iter().copied())
        .collect()
}

/// The first readable format that recognises `bytes`.
pub fn sniff_format(bytes: &[u8]) -> Option<&'static dyn MeshFormat> {
    FORMATS
        .iter()
        .copied()
        .find(|f| f.can_read() && f.sniff(bytes))
}

/// The extensions of the readable formats, comma-separated (`.ply, .obj, …`).
pub fn readable_extensions() -> String {
    FORMATS
        .iter()
        .filter(|f| f.can_read())
        .flat_map(|f| f.extensions().iter())
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Reads bytes named `path` (the path only picks the format and names errors): the
/// extension's format unless the content is recognisably another one (then that one, with a
/// note); an unknown extension goes by content alone.
pub fn read_bytes(path: &Path, bytes: &[u8]) -> Result<RawMesh, MeshIoError> {
    let by_ext = format_for_path(path);
    let chosen = match by_ext {
        Some(f) if f.sniff(bytes) => (f, None),
        Some(f) => match sniff_format(bytes) {
            Some(g) if g.name() != f.name() => (
                g,
                Some(format!(
                    "the file is named as {} but its content is {}: read as {}",
                    f.name(),
                    g.name(),
                    g.name()
                )),
            ),
            _ => (f, None),
        },
        None => match sniff_format(bytes) {
            Some(g) => (
                g,
                Some(format!(
                    "the extension names no format; the content is {}",
                    g.name()
                )),
            ),
            None => {
                return Err(MeshIoError::Unsupported {
                    path: path.to_path_buf(),
                    extensions: readable_extensions(),
                })
            }
        },
    };
    let (format, note) = chosen;
    let mut mesh = format.read(bytes).map_err(|source| MeshIoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    if let Some(note) = note {
        mesh.notes.insert(0, note);
    }
    Ok(mesh)
}

/// Reads a mesh file (the whole file into memory, then [`read_bytes`]).
pub fn read_file(path: impl AsRef<Path>) -> Result<RawMesh, MeshIoError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| MeshIoError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_bytes(path, &bytes)
}

/// Writes `mesh` in `format` to bytes in memory. A file on disk is better written with
/// [`crate::outfile::write_atomic_mesh`], which streams it atomically.
pub fn write_bytes(
    mesh: &RawMesh,
    format: &dyn MeshFormat,
    options: &WriteOptions,
) -> Result<Vec<u8>, WriteError> {
    format.write(mesh, options)
}

//! The testbed's mesh format (Lounsbery et al. 1990, Figure 2) as a validated [`Mesh`], exactly
//! as the file has it: no repair, the vertices in the order the points are defined, the faces in
//! the order of the `mesh` statement, named by their names.
//!
//! Parsing and writing are [`meshio`]'s (`meshio::testbed`: the grammar, the `pos`, `norm`,
//! `shape` fields and the kept extra fields are documented there); this module only turns the
//! raw mesh into a [`Mesh`] strictly — a face that is not a triangle or a mesh that does not
//! validate is an error naming the face — for the built-in data sets and for files a user wants
//! read as they are. `fit` and `convert` read files through [`crate::repair`] instead, which
//! repairs rather than refuses.

use std::path::{Path, PathBuf};

use meshio::{Location, MeshFormat, RawMesh, ReadError, WriteOptions};

use crate::mesh::{Mesh, MeshError};
use crate::repair::mesh_to_raw;

/// What went wrong reading or writing a testbed mesh.
#[derive(Debug, thiserror::Error)]
pub enum TestbedError {
    /// A syntax or reference error at a line.
    #[error("line {line}: {message}")]
    Syntax {
        /// 1-based line number.
        line: usize,
        /// What was expected or wrong.
        message: String,
    },
    /// Any other read error of the format (located as the reader located it).
    #[error(transparent)]
    Read(ReadError),
    /// A face of the `mesh` statement is not a triangle.
    #[error("face `{name}` has {corners} vertices: the testbed format's faces are triangles")]
    NotTriangle {
        /// The face's name.
        name: String,
        /// Its number of vertices.
        corners: usize,
    },
    /// The faces do not form a valid mesh.
    #[error("{}{source}", face_name.as_ref().map(|n| format!("face `{n}`: ")).unwrap_or_default())]
    Mesh {
        /// Name of the face at fault, when the error names a face.
        face_name: Option<String>,
        /// The mesh error.
        source: MeshError,
    },
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// An error in a named file.
    #[error("{}: {source}", path.display())]
    InFile {
        /// The file.
        path: PathBuf,
        /// The error.
        source: Box<TestbedError>,
    },
}

fn format() -> &'static dyn MeshFormat {
    &meshio::testbed::Testbed
}

/// The face a mesh error names, if any.
fn face_of(e: &MeshError) -> Option<usize> {
    match e {
        MeshError::MissingVertex { face, .. }
        | MeshError::RepeatedVertex { face, .. }
        | MeshError::ZeroArea { face, .. } => Some(*face),
        MeshError::InconsistentOrientation { faces, .. } => Some(faces[1]),
        MeshError::NonManifoldEdge { faces, .. } => faces.last().copied(),
        _ => None,
    }
}

/// A raw testbed mesh as a [`Mesh`], strictly (module docs).
fn strict(raw: RawMesh) -> Result<Mesh, TestbedError> {
    let name = |f: usize| {
        raw.face_name(f)
            .map_or_else(|| format!("#{f}"), |n| n.into_owned())
    };
    let mut faces = Vec::with_capacity(raw.polygons.len());
    for (f, poly) in raw.polygons.iter().enumerate() {
        match poly {
            [a, b, c] => faces.push([*a, *b, *c]),
            _ => {
                return Err(TestbedError::NotTriangle {
                    name: name(f),
                    corners: poly.len(),
                })
            }
        }
    }
    let vertices = (0..raw.positions.len())
        .map(|i| {
            let p = raw.positions[i];
            let n = raw
                .normals
                .as_ref()
                .map_or_else(nalgebra::Vector3::zeros, |ns| ns[i]);
            let mut v = match &raw.shapes {
                Some(s) => crate::Vertex::new(crate::VertexData::new(p, n, s[i])),
                None => crate::Vertex::without_curvature(p, n),
            };
            v.set_name(raw.vertex_name(i).map(|n| n.into_owned()));
            for (k, vals) in &raw.properties {
                if let Some(x) = vals.get(i) {
                    v.extra_mut().insert(k.clone(), vec![*x]);
                }
            }
            v
        })
        .collect();
    let mesh = Mesh::new(vertices, faces).map_err(|source| TestbedError::Mesh {
        face_name: face_of(&source).map(name),
        source,
    })?;
    let mut mesh = if raw.has_face_names() {
        let names = (0..raw.polygons.len())
            .map(|f| raw.face_name(f).map(|n| n.into_owned()).unwrap_or_default())
            .collect();
        mesh.with_face_names(names)
    } else {
        mesh
    };
    mesh.extra = raw.mesh_fields;
    Ok(mesh)
}

/// Reads a mesh in the testbed's format from text.
pub fn read_testbed(text: &str) -> Result<Mesh, TestbedError> {
    let raw = format()
        .read(text.as_bytes())
        .map_err(|e| match e.location {
            Location::Line(line) => TestbedError::Syntax {
                line,
                message: e.message,
            },
            _ => TestbedError::Read(e),
        })?;
    strict(raw)
}

/// Reads a mesh file in the testbed's format; errors name the file.
pub fn read_testbed_file(path: impl AsRef<Path>) -> Result<Mesh, TestbedError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| TestbedError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_testbed(&text).map_err(|e| TestbedError::InFile {
        path: path.to_path_buf(),
        source: Box::new(e),
    })
}

/// Writes a mesh in the testbed's format (`meshio`'s writer): every vertex as a point with its
/// normal, its shape tensor when every vertex's curvature is known, its extra fields, every
/// face and the `mesh` statement; numbers in shortest round-trip form, so reading the output
/// gives the same mesh.
pub fn write_testbed(mesh: &Mesh) -> String {
    let raw = mesh_to_raw(mesh, true);
    match format().write(&raw, &WriteOptions::new()) {
        Ok(bytes) => String::from_utf8_lossy(&bytes).into_owned(),
        Err(e) => format!("% could not write the mesh: {e}\n"),
    }
}

/// Writes [`write_testbed`]'s text to `path` through a temporary file renamed into place, so an
/// existing file is never left half-written.
pub fn write_testbed_file(mesh: &Mesh, path: impl AsRef<Path>) -> Result<(), TestbedError> {
    let path = path.as_ref();
    let io = |source| TestbedError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, write_testbed(mesh)).map_err(io)?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io(e)
    })
}

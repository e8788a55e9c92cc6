//! Wavefront OBJ: a small reader for triangle meshes with per-vertex normals, and a writer.
//!
//! # Reading
//!
//! Statements used: `v x y z [w]` (the optional `w` is ignored), `vn x y z`, and
//! `f c1 c2 c3 …` with corners `a`, `a/b`, `a//c` or `a/b/c` (position / texture / normal
//! index, 1-based; negative indices count back from the latest element read so far, as the OBJ
//! specification says). Everything else (`vt`, `o`, `g`, `s`, `usemtl`, `mtllib`, comments) is
//! ignored. Polygons with more than three corners are split into a fan around their first
//! corner (right for convex polygons, which is what exporters write; a concave polygon should be
//! triangulated before). Faces with fewer than three corners are an error.
//!
//! Normals are per vertex: every position used by a face must get a normal from the `//c` or
//! `/b/c` part of some corner, and all corners using a position must agree on it (within
//! [`NORMAL_AGREEMENT`]); otherwise the error names the line. Positions not used by any face
//! are dropped (the mesh keeps only vertices of faces, in order of first `v` statement). The
//! curvature is unknown: zero shape tensors, [`crate::Vertex::curvature_known`]` = false`.
//!
//! # Writing
//!
//! [`write_obj`] writes positions, normals (one `vn` per `v`, same index) and `f a//a b//b
//! c//c` faces.

use std::io::Write;
use std::path::{Path, PathBuf};

use nalgebra::{Point3, Vector3};

use crate::mesh::{Mesh, MeshError, Vertex};

/// Two corners giving the same position normals whose directions differ by more than this angle
/// (radians, ~0.06°) disagree: exporters that weld vertices print the same normal with the same
/// rounding, while a deliberate crease differs by degrees.
pub const NORMAL_AGREEMENT: f64 = 1e-3;

/// What went wrong reading or writing OBJ.
#[derive(Debug, thiserror::Error)]
pub enum ObjError {
    /// A problem at a line.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The faces do not form a valid mesh.
    #[error("line {line}: {source}")]
    Mesh {
        /// Line of the face named by the error (or of the last face).
        line: usize,
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
        source: Box<ObjError>,
    },
}

fn at(line: usize, message: impl Into<String>) -> ObjError {
    ObjError::Line {
        line,
        message: message.into(),
    }
}

fn floats(line: usize, what: &str, parts: &[&str], min: usize) -> Result<Vec<f64>, ObjError> {
    if parts.len() < min {
        return Err(at(
            line,
            format!("`{what}` needs {min} numbers, found {}", parts.len()),
        ));
    }
    parts
        .iter()
        .map(|s| match s.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(at(
                line,
                format!("`{s}` in `{what}` is not a finite number"),
            )),
        })
        .collect()
}

/// 1-based or negative OBJ index → 0-based, given how many elements exist so far.
fn resolve(line: usize, s: &str, count: usize, what: &str) -> Result<usize, ObjError> {
    let i: i64 = s
        .parse()
        .map_err(|_| at(line, format!("`{s}` is not a {what} index")))?;
    let resolved = if i > 0 {
        i - 1
    } else if i < 0 {
        count as i64 + i
    } else {
        -1
    };
    if resolved < 0 || resolved >= count as i64 {
        return Err(at(
            line,
            format!("{what} index {i} is out of range ({count} defined so far)"),
        ));
    }
    Ok(resolved as usize)
}

/// Reads an OBJ triangle mesh with per-vertex normals (see the module docs).
pub fn read_obj(text: &str) -> Result<Mesh, ObjError> {
    let mut positions: Vec<(Point3<f64>, usize)> = Vec::new();
    let mut normals: Vec<Vector3<f64>> = Vec::new();
    // Per position: normal and the line that set it.
    let mut vnormal: Vec<Option<(Vector3<f64>, usize)>> = Vec::new();
    let mut faces: Vec<([usize; 3], usize)> = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let content = raw.split('#').next().unwrap_or("");
        let parts: Vec<&str> = content.split_whitespace().collect();
        let Some((&kw, rest)) = parts.split_first() else {
            continue;
        };
        match kw {
            "v" => {
                let c = floats(line, "v", rest, 3)?;
                positions.push((Point3::new(c[0], c[1], c[2]), line));
                vnormal.push(None);
            }
            "vn" => {
                let c = floats(line, "vn", rest, 3)?;
                let n = Vector3::new(c[0], c[1], c[2]);
                if n.norm() == 0.0 {
                    return Err(at(line, "zero normal"));
                }
                normals.push(n.normalize());
            }
            "f" => {
                if rest.len() < 3 {
                    return Err(at(
                        line,
                        format!("face with {} corners; a face needs at least 3", rest.len()),
                    ));
                }
                let mut corners = Vec::with_capacity(rest.len());
                for corner in rest {
                    let fields: Vec<&str> = corner.split('/').collect();
                    if fields.len() > 3 || fields[0].is_empty() {
                        return Err(at(line, format!("`{corner}` is not a face corner")));
                    }
                    let v = resolve(line, fields[0], positions.len(), "vertex")?;
                    if let Some(ns) = fields.get(2).filter(|s| !s.is_empty()) {
                        let n = normals[resolve(line, ns, normals.len(), "normal")?];
                        match vnormal[v] {
                            None => vnormal[v] = Some((n, line)),
                            Some((m, first)) => {
                                if m.angle(&n) > NORMAL_AGREEMENT {
                                    return Err(at(
                                        line,
                                        format!(
                                            "vertex {} gets a normal that differs from the one given at line {first}",
                                            v + 1
                                        ),
                                    ));
                                }
                            }
                        }
                    }
                    corners.push(v);
                }
                for i in 1..corners.len() - 1 {
                    faces.push(([corners[0], corners[i], corners[i + 1]], line));
                }
            }
            _ => {}
        }
    }
    // Keep only used positions, in order.
    let mut remap = vec![usize::MAX; positions.len()];
    for (f, _) in &faces {
        for &v in f {
            remap[v] = 0;
        }
    }
    let mut vertices = Vec::new();
    for (v, slot) in remap.iter_mut().enumerate() {
        if *slot == usize::MAX {
            continue;
        }
        let (p, vline) = positions[v];
        let Some((n, _)) = vnormal[v] else {
            let first_face = faces
                .iter()
                .find(|(f, _)| f.contains(&v))
                .map_or(vline, |(_, l)| *l);
            return Err(at(
                first_face,
                format!(
                    "vertex {} (defined at line {vline}) has no normal: give its face corners a `//n` or `/t/n` part",
                    v + 1
                ),
            ));
        };
        *slot = vertices.len();
        vertices.push(Vertex::without_curvature(p, n));
    }
    let tris: Vec<[usize; 3]> = faces.iter().map(|(f, _)| f.map(|v| remap[v])).collect();
    let last_line = faces.last().map_or(0, |(_, l)| *l);
    Mesh::new(vertices, tris).map_err(|source| {
        let face = match &source {
            MeshError::MissingVertex { face, .. }
            | MeshError::RepeatedVertex { face, .. }
            | MeshError::ZeroArea { face, .. } => Some(*face),
            MeshError::InconsistentOrientation { faces, .. } => Some(faces[1]),
            MeshError::NonManifoldEdge { faces, .. } => faces.last().copied(),
            _ => None,
        };
        ObjError::Mesh {
            line: face
                .and_then(|f| faces.get(f))
                .map_or(last_line, |(_, l)| *l),
            source,
        }
    })
}

/// Reads an OBJ file; errors name the file.
pub fn read_obj_file(path: impl AsRef<Path>) -> Result<Mesh, ObjError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| ObjError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_obj(&text).map_err(|e| ObjError::InFile {
        path: path.to_path_buf(),
        source: Box::new(e),
    })
}

/// Writes positions, normals (same indexing) and triangles as OBJ. Numbers are written in
/// Rust's shortest round-trip form.
pub fn write_obj<W: Write>(
    mut out: W,
    positions: &[Point3<f64>],
    normals: &[Vector3<f64>],
    faces: &[[usize; 3]],
) -> std::io::Result<()> {
    writeln!(out, "# written by the surface crate")?;
    for p in positions {
        writeln!(out, "v {} {} {}", p.x, p.y, p.z)?;
    }
    for n in normals {
        writeln!(out, "vn {} {} {}", n.x, n.y, n.z)?;
    }
    let with_normals = normals.len() == positions.len();
    for f in faces {
        let [a, b, c] = f.map(|i| i + 1);
        if with_normals {
            writeln!(out, "f {a}//{a} {b}//{b} {c}//{c}")?;
        } else {
            writeln!(out, "f {a} {b} {c}")?;
        }
    }
    out.flush()
}

/// Writes `bytes` to `path` through a temporary file in the same directory, renamed into place.
pub(crate) fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, bytes)?;
    std::fs::rename(&tmp, path)
}

/// Writes a mesh's positions, normals and faces as an OBJ file (atomically: temporary file,
/// then rename).
pub fn write_obj_file(mesh: &Mesh, path: impl AsRef<Path>) -> Result<(), ObjError> {
    let path = path.as_ref();
    let positions: Vec<Point3<f64>> = mesh.vertices().iter().map(|v| v.data.p).collect();
    let normals: Vec<Vector3<f64>> = mesh.vertices().iter().map(|v| v.data.n).collect();
    let mut buf = Vec::new();
    let io = |source| ObjError::Io {
        path: path.to_path_buf(),
        source,
    };
    write_obj(&mut buf, &positions, &normals, mesh.faces()).map_err(io)?;
    write_atomically(path, &buf).map_err(io)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: &str = "# a square\n\
        v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\n\
        vt 0 0\nvn 0 0 1\n\
        f 1//1 2//1 3//1\n\
        f -5/1/-1 -3/1/1 4//1\n";

    fn err_line(text: &str) -> (usize, String) {
        match read_obj(text) {
            Err(ObjError::Line { line, message }) => (line, message),
            Err(ObjError::Mesh { line, source }) => (line, source.to_string()),
            other => panic!("expected an error, got {other:?}"),
        }
    }

    #[test]
    fn reads_all_corner_forms() {
        let m = read_obj(SQUARE).unwrap();
        // The unused fifth vertex is dropped.
        assert_eq!((m.num_vertices(), m.num_faces(), m.num_edges()), (4, 2, 5));
        assert_eq!(m.faces()[1], [0, 2, 3]);
        assert!(m.vertices().iter().all(|v| v.data.n == Vector3::z()));
        assert!(!m.vertex(0).unwrap().curvature_known);
    }

    #[test]
    fn polygons_are_fanned() {
        let m = read_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n")
            .unwrap();
        assert_eq!(m.faces(), &[[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn errors_name_lines() {
        let (line, msg) = err_line("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        assert_eq!(line, 4);
        assert!(msg.contains("has no normal"), "{msg}");
        let (line, msg) = err_line(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 1 0 0\nf 1//1 2//1 3//1\nf 1//2 3//1 2//1\n",
        );
        assert_eq!(line, 7);
        assert!(
            msg.contains("differs from the one given at line 6"),
            "{msg}"
        );
        let (line, msg) = err_line("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 9//1\n");
        assert_eq!(line, 5);
        assert!(msg.contains("out of range"), "{msg}");
        let (line, msg) = err_line("v 0 0\n");
        assert_eq!(line, 1);
        assert!(msg.contains("needs 3 numbers"), "{msg}");
        let (line, _) = err_line("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1\n");
        assert_eq!(line, 5);
        let (line, msg) = err_line(
            "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 4//1\nf 1//1 2//1 3//1\n",
        );
        assert_eq!(line, 7);
        assert!(msg.contains("zero area"), "{msg}");
    }

    #[test]
    fn write_then_read_round_trips() {
        let m = read_obj(SQUARE).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("square.obj");
        write_obj_file(&m, &path).unwrap();
        let again = read_obj_file(&path).unwrap();
        assert_eq!(again.faces(), m.faces());
        for (a, b) in again.vertices().iter().zip(m.vertices()) {
            assert_eq!(a.data, b.data);
        }
    }
}

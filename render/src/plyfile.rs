//! Binary PLY (little endian) with per-vertex normals, colours and an optional quality value, as
//! MeshLab, Blender and Polyscope read it; written atomically.

use std::path::Path;

use nalgebra::{Point3, Vector3};

use crate::error::RenderError;
use crate::io::write_atomic;

/// The PLY bytes (header and body) for a triangle mesh.
pub fn ply_bytes(
    positions: &[Point3<f64>],
    normals: &[Vector3<f64>],
    colors: &[[u8; 3]],
    quality: Option<&[f32]>,
    faces: &[[usize; 3]],
) -> Vec<u8> {
    let mut out = Vec::with_capacity(64 + positions.len() * 31 + faces.len() * 13);
    let mut header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by the workbench's render crate\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n",
        positions.len()
    );
    if quality.is_some() {
        header.push_str("property float quality\n");
    }
    header.push_str(&format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        faces.len()
    ));
    out.extend_from_slice(header.as_bytes());
    for (i, p) in positions.iter().enumerate() {
        let n = normals.get(i).copied().unwrap_or_else(Vector3::zeros);
        for v in [p.x, p.y, p.z, n.x, n.y, n.z] {
            out.extend_from_slice(&(v as f32).to_le_bytes());
        }
        out.extend_from_slice(&colors.get(i).copied().unwrap_or([200, 200, 200]));
        if let Some(q) = quality {
            out.extend_from_slice(&q.get(i).copied().unwrap_or(0.0).to_le_bytes());
        }
    }
    for f in faces {
        out.push(3);
        for &i in f {
            out.extend_from_slice(&(i as i32).to_le_bytes());
        }
    }
    out
}

/// Writes [`ply_bytes`] to `path` atomically.
pub fn write_ply_binary(
    path: &Path,
    positions: &[Point3<f64>],
    normals: &[Vector3<f64>],
    colors: &[[u8; 3]],
    quality: Option<&[f32]>,
    faces: &[[usize; 3]],
) -> Result<(), RenderError> {
    write_atomic(path, &ply_bytes(positions, normals, colors, quality, faces))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_is_exact() {
        let p = [
            Point3::new(1.0, 2.0, 3.0),
            Point3::origin(),
            Point3::new(0.0, 1.0, 0.0),
        ];
        let n = [Vector3::z(); 3];
        let c = [[255, 0, 0]; 3];
        let b = ply_bytes(&p, &n, &c, Some(&[0.5; 3]), &[[0, 1, 2]]);
        let text = String::from_utf8_lossy(&b);
        let end = text.find("end_header\n").expect("header") + "end_header\n".len();
        assert!(text.starts_with("ply\nformat binary_little_endian 1.0\n"));
        assert!(
            text[..end].contains("element vertex 3\n")
                && text[..end].contains("property float quality\n")
        );
        // 3 vertices × (6 floats + 3 bytes + 1 float) + 1 face × (1 + 3 ints).
        assert_eq!(b.len() - end, 3 * (24 + 3 + 4) + 13);
        assert_eq!(
            f32::from_le_bytes([b[end], b[end + 1], b[end + 2], b[end + 3]]),
            1.0
        );
        assert_eq!(&b[end + 24..end + 27], &[255, 0, 0]);
    }
}

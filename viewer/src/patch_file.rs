//! Patch files read back for viewing: `surface::patch_io`'s JSON Lines (`.jsonl`, one
//! `{"type":"BezierTriangle","degree":n,"points":[[x,y,z],…]}` record a line; other fields
//! ignored, blank lines skipped) and its binary form (`.bzp`, Bézier nets only: a sampled
//! form's file is refused by `read_binary`'s header check).

use std::path::{Path, PathBuf};

use nalgebra::Point3;
use surface::BezierTriangle;

/// Why a patch file could not be read; every variant names the file (and the line).
#[derive(Debug, thiserror::Error)]
pub enum PatchFileError {
    /// The file could not be read.
    #[error("cannot read {path}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The binary form is broken.
    #[error("{path}: {source}")]
    Binary {
        /// The file.
        path: PathBuf,
        /// Why.
        source: surface::patch_io::PatchReadError,
    },
    /// A record (a JSON line, or a binary patch) is not a patch.
    #[error("{path}:{line}: {message}")]
    Record {
        /// The file.
        path: PathBuf,
        /// The line (JSON Lines) or the patch's position from 1 (binary).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file holds no patch.
    #[error("{path}: no patches")]
    Empty {
        /// The file.
        path: PathBuf,
    },
}

/// True when the path's extension names a patch file (`.jsonl`, `.bzp`, any case).
pub fn is_patch_file(path: &Path) -> bool {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .is_some_and(|e| e == "jsonl" || e == "bzp")
}

/// Reads a patch file: the binary form when it starts with `BEZPATCH1`, else JSON Lines.
pub fn read_patch_file(path: &Path) -> Result<Vec<BezierTriangle>, PatchFileError> {
    let bytes = std::fs::read(path).map_err(|source| PatchFileError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let patches = if bytes.starts_with(surface::patch_io::BINARY_MAGIC) {
        binary(path, &bytes)?
    } else {
        json_lines(path, &bytes)?
    };
    if patches.is_empty() {
        return Err(PatchFileError::Empty {
            path: path.to_path_buf(),
        });
    }
    Ok(patches)
}

/// The highest patch degree the viewer reads: the testbed's record bound
/// (`testbed::record::MAX_DEGREE`), far above any scheme's quartics. A hostile degree
/// (`2⁶⁴ − 1` overflowed the net's size and panicked; 60 kept the tessellator busy for minutes)
/// is refused by name.
pub const MAX_DEGREE: usize = 32;

/// `degree` as a patch degree the viewer reads, or why not.
fn check_degree(degree: u64) -> Result<usize, String> {
    usize::try_from(degree)
        .ok()
        .filter(|d| (1..=MAX_DEGREE).contains(d))
        .ok_or_else(|| format!("degree {degree}: outside [1, {MAX_DEGREE}]"))
}

fn record(path: &Path, line: usize, message: String) -> PatchFileError {
    PatchFileError::Record {
        path: path.to_path_buf(),
        line,
        message,
    }
}

fn binary(path: &Path, bytes: &[u8]) -> Result<Vec<BezierTriangle>, PatchFileError> {
    let (degree, _, points) =
        surface::patch_io::read_binary(bytes).map_err(|source| PatchFileError::Binary {
            path: path.to_path_buf(),
            source,
        })?;
    let degree = check_degree(degree as u64).map_err(|m| record(path, 1, m))?;
    let per = surface::beztri::num_points(degree);
    points
        .chunks(per)
        .enumerate()
        .map(|(k, net)| {
            BezierTriangle::new(degree, net.to_vec())
                .map_err(|e| record(path, k + 1, format!("patch {}: {e}", k + 1)))
        })
        .collect()
}

fn json_lines(path: &Path, bytes: &[u8]) -> Result<Vec<BezierTriangle>, PatchFileError> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        record(
            path,
            1,
            format!("neither a binary patch file nor UTF-8 text: {e}"),
        )
    })?;
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let bad = |m: String| record(path, n + 1, m);
        let r: serde_json::Value =
            serde_json::from_str(line).map_err(|e| bad(format!("not JSON: {e}")))?;
        if r["type"] != "BezierTriangle" {
            return Err(bad(format!(
                "a record of type {} (only BezierTriangle patches can be shown)",
                r["type"]
            )));
        }
        let degree = r["degree"]
            .as_u64()
            .ok_or_else(|| bad("no `degree`".into()))
            .and_then(|d| check_degree(d).map_err(bad))?;
        let points = r["points"]
            .as_array()
            .ok_or_else(|| bad("no `points`".into()))?
            .iter()
            .map(|p| {
                let c: Option<Vec<f64>> = p
                    .as_array()
                    .and_then(|c| c.iter().map(serde_json::Value::as_f64).collect());
                match c.as_deref() {
                    Some(&[x, y, z]) => Ok(Point3::new(x, y, z)),
                    _ => Err(bad(format!("a point that is not [x, y, z]: {p}"))),
                }
            })
            .collect::<Result<Vec<_>, _>>()?;
        out.push(BezierTriangle::new(degree, points).map_err(|e| bad(e.to_string()))?);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    }

    #[test]
    fn json_lines_are_read_and_bad_lines_named() {
        let dir = tempfile::tempdir().unwrap();
        let good =
            r#"{"type":"BezierTriangle","degree":1,"points":[[0,0,0],[1,0,0],[0,1,0]],"face":0}"#;
        let p = write(
            dir.path(),
            "a.jsonl",
            format!("{good}\n\n{good}\n").as_bytes(),
        );
        let patches = read_patch_file(&p).unwrap();
        assert_eq!(patches.len(), 2);
        assert_eq!(patches[1].degree(), 1);
        let p = write(
            dir.path(),
            "b.jsonl",
            format!("{good}\n{{\"type\":\"Other\"}}\n").as_bytes(),
        );
        let e = read_patch_file(&p).unwrap_err().to_string();
        assert!(
            e.ends_with(
                "b.jsonl:2: a record of type \"Other\" (only BezierTriangle patches can be shown)"
            ),
            "{e}"
        );
        // A hostile degree is refused by name, before any net is sized or tessellated.
        for degree in ["0", "33", "60", "18446744073709551615"] {
            let line = format!(r#"{{"type":"BezierTriangle","degree":{degree},"points":[]}}"#);
            let p = write(dir.path(), "deg.jsonl", line.as_bytes());
            let e = read_patch_file(&p).unwrap_err().to_string();
            assert!(
                e.contains(&format!("deg.jsonl:1: degree {degree}: outside [1, 32]")),
                "{e}"
            );
        }
        let bad = r#"{"type":"BezierTriangle","degree":1,"points":[[0,0],[1,0,0],[0,1,0]]}"#;
        let p = write(dir.path(), "c.jsonl", bad.as_bytes());
        assert!(read_patch_file(&p)
            .unwrap_err()
            .to_string()
            .contains("c.jsonl:1: a point"));
        let p = write(dir.path(), "d.jsonl", b"\n");
        assert!(matches!(
            read_patch_file(&p),
            Err(PatchFileError::Empty { .. })
        ));
    }

    #[test]
    fn truncated_binary_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let mut bytes = surface::patch_io::BINARY_MAGIC.to_vec();
        bytes.extend_from_slice(
            br#"{"degree":1,"patches_per_face":1,"faces":1,"points_per_patch":3,"form":"bezier","scalar":"f64le"}"#,
        );
        bytes.push(b'\n');
        bytes.extend(std::iter::repeat_n(0u8, 9 * 8 - 1));
        let p = write(dir.path(), "t.bzp", &bytes);
        assert!(matches!(
            read_patch_file(&p),
            Err(PatchFileError::Binary { .. })
        ));
        bytes.push(0);
        let p = write(dir.path(), "u.bzp", &bytes);
        assert_eq!(read_patch_file(&p).map(|v| v.len()).ok(), Some(1));
    }
}

//! A fit's patches written out: JSON Lines (one record per patch) or a compact binary form,
//! both self-describing, both written in parallel chunks without intermediate JSON values.
//!
//! # JSON Lines
//!
//! One record per patch, `{"type":"BezierTriangle","degree":n,"points":[[x,y,z],…],
//! "face":f,"subpatch":s}` (points in net order, docs/conventions.md). Numbers are printed by
//! the shortest round-trip formatting (Ryū, Adams 2018), so reading them back gives the same
//! `f64`s.
//!
//! # Binary
//!
//! `BEZPATCH1\n`, then one line of JSON naming the layout,
//! `{"degree":n,"patches_per_face":p,"faces":F,"points_per_patch":m,"form":"bezier","scalar":"f64le"}\n`
//! (`form` names the [`crate::patch::SampledForm`] of a patch that is not a Bézier net), then
//! `F·p·m·3` little-endian `f64`s (patch after patch, each net in net order, x y z per point).
//! The header is JSON so a reader can check what it gets and a later version can add fields;
//! the body is the in-memory layout, 24 bytes per control point (2.7–3.2× smaller than the JSON
//! Lines form, and written at memory speed).

use std::fmt::Write as _;
use std::io::Write;

use nalgebra::Point3;
use rayon::prelude::*;

use crate::fit::Fit;
use crate::scheme::Form;

/// How stored point `k` of a patch maps to the world: positions by `to_world`, directions (a
/// sampled form's normals) by its linear part, renormalized.
fn mapped(
    form: Form,
    k: usize,
    p: &Point3<f64>,
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
) -> Point3<f64> {
    match form {
        Form::Sampled(f) if f.is_direction(k) => {
            let o = Point3::origin();
            let d = to_world(&(o + p.coords)) - to_world(&o);
            if d == p.coords {
                return *p;
            }
            Point3::from(d.try_normalize(0.0).unwrap_or(d))
        }
        _ => to_world(p),
    }
}

/// The `form` header value of a layout.
fn form_name(form: Form) -> &'static str {
    match form {
        Form::Bezier => "bezier",
        Form::Sampled(f) => f.name(),
    }
}

/// The first bytes of the binary form.
pub const BINARY_MAGIC: &[u8] = b"BEZPATCH1\n";

/// Patches per formatting task: large enough to amortize rayon, small enough to bound the
/// memory held by formatted text at once.
const CHUNK: usize = 4096;

/// Why patches could not be read back.
#[derive(Debug, thiserror::Error)]
pub enum PatchReadError {
    /// The bytes do not start with [`BINARY_MAGIC`].
    #[error("not a binary patch file (no BEZPATCH1 header)")]
    NotBinary,
    /// The header line is not the expected JSON.
    #[error("bad header: {0}")]
    Header(String),
    /// The body is shorter or longer than the header says.
    #[error("the header promises {expected} bytes of points, the file has {found}")]
    Length {
        /// Bytes the header implies.
        expected: usize,
        /// Bytes present.
        found: usize,
    },
}

/// Writes every patch of `fit` as JSON Lines to `out`, each point mapped by `to_world` first
/// (the identity, or a working frame's way back). Chunks of patches are formatted in parallel
/// and written in order.
pub fn write_jsonl<W: Write + ?Sized>(
    fit: &Fit,
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
    out: &mut W,
) -> std::io::Result<()> {
    let per_face = fit.layout.patches_per_face().max(1);
    let degree = fit.layout.degree;
    let np = fit.layout.points_per_patch().max(1);
    let form = fit.layout.form;
    let head = match form {
        Form::Bezier => format!("{{\"type\":\"BezierTriangle\",\"degree\":{degree},\"points\":["),
        Form::Sampled(f) => format!(
            "{{\"type\":\"SampledPatch\",\"form\":\"{}\",\"points\":[",
            f.name()
        ),
    };
    let patches = fit.num_patches();
    let chunks: Vec<usize> = (0..patches).step_by(CHUNK).collect();
    // Formatting in parallel, a window of chunks at a time, so memory stays bounded.
    for window in chunks.chunks(64) {
        let texts: Vec<String> = window
            .par_iter()
            .map(|&first| {
                let last = (first + CHUNK).min(patches);
                let mut s = String::with_capacity((last - first) * (np * 60 + 80));
                let mut num = ryu::Buffer::new();
                for i in first..last {
                    s.push_str(&head);
                    for (k, p) in fit.points[i * np..(i + 1) * np].iter().enumerate() {
                        let q = mapped(form, k, p, to_world);
                        if k > 0 {
                            s.push(',');
                        }
                        s.push('[');
                        s.push_str(num.format(q.x));
                        s.push(',');
                        s.push_str(num.format(q.y));
                        s.push(',');
                        s.push_str(num.format(q.z));
                        s.push(']');
                    }
                    let _ = writeln!(
                        s,
                        "],\"face\":{},\"subpatch\":{}}}",
                        i / per_face,
                        i % per_face
                    );
                }
                s
            })
            .collect();
        for t in texts {
            out.write_all(t.as_bytes())?;
        }
    }
    Ok(())
}

/// Writes every patch of `fit` in the binary form (module docs), points mapped by `to_world`.
pub fn write_binary<W: Write + ?Sized>(
    fit: &Fit,
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
    out: &mut W,
) -> std::io::Result<()> {
    let np = fit.layout.points_per_patch();
    out.write_all(BINARY_MAGIC)?;
    writeln!(
        out,
        "{{\"degree\":{},\"patches_per_face\":{},\"faces\":{},\"points_per_patch\":{np},\"form\":\"{}\",\"scalar\":\"f64le\"}}",
        fit.layout.degree,
        fit.layout.patches_per_face(),
        fit.num_patches() / fit.layout.patches_per_face().max(1),
        form_name(fit.layout.form),
    )?;
    let form = fit.layout.form;
    let per_chunk = CHUNK * np.max(1);
    for window in fit.points.chunks(per_chunk * 64) {
        let bytes: Vec<Vec<u8>> = window
            .par_chunks(per_chunk)
            .map(|pts| {
                let mut b = Vec::with_capacity(pts.len() * 24);
                for (k, p) in pts.iter().enumerate() {
                    let q = mapped(form, k % np.max(1), p, to_world);
                    for c in [q.x, q.y, q.z] {
                        b.extend_from_slice(&c.to_le_bytes());
                    }
                }
                b
            })
            .collect();
        for b in bytes {
            out.write_all(&b)?;
        }
    }
    Ok(())
}

/// The layout and control points of a binary patch file: `(degree, patches_per_face, points)`.
pub fn read_binary(bytes: &[u8]) -> Result<(usize, usize, Vec<Point3<f64>>), PatchReadError> {
    let rest = bytes
        .strip_prefix(BINARY_MAGIC)
        .ok_or(PatchReadError::NotBinary)?;
    let end = rest
        .iter()
        .position(|b| *b == b'\n')
        .ok_or_else(|| PatchReadError::Header("no end of line".into()))?;
    let header: serde_json::Value =
        serde_json::from_slice(&rest[..end]).map_err(|e| PatchReadError::Header(e.to_string()))?;
    let field = |k: &str| {
        header[k]
            .as_u64()
            .map(|v| v as usize)
            .ok_or_else(|| PatchReadError::Header(format!("missing `{k}`")))
    };
    let (degree, ppf, faces, np) = (
        field("degree")?,
        field("patches_per_face")?,
        field("faces")?,
        field("points_per_patch")?,
    );
    let bezier = header.get("form").is_none_or(|f| f == "bezier");
    if header["scalar"] != "f64le" || (bezier && np != crate::beztri::num_points(degree)) {
        return Err(PatchReadError::Header(
            "unsupported scalar type or point count".into(),
        ));
    }
    let body = &rest[end + 1..];
    let expected = faces
        .checked_mul(ppf)
        .and_then(|x| x.checked_mul(np))
        .and_then(|x| x.checked_mul(24))
        .ok_or_else(|| PatchReadError::Header("sizes overflow".into()))?;
    if body.len() != expected {
        return Err(PatchReadError::Length {
            expected,
            found: body.len(),
        });
    }
    let points = body
        .chunks_exact(24)
        .map(|c| {
            let f = |k: usize| {
                let mut a = [0u8; 8];
                a.copy_from_slice(&c[8 * k..8 * k + 8]);
                f64::from_le_bytes(a)
            };
            Point3::new(f(0), f(1), f(2))
        })
        .collect();
    Ok((degree, ppf, points))
}

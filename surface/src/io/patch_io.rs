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

use std::io::Write;

use nalgebra::Point3;
use rayon::prelude::*;

use crate::fit::Fit;
use crate::scheme::{Form, Layout};

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

/// Patches per formatting task at most: large enough to amortize rayon (a task formats in
/// about 30 µs as binary, 600 µs as JSON Lines, one thread), small enough that its buffer (190 KB binary,
/// about 0.5 MB of JSON for quartics) stays in the allocator's reach. With 4096, buffers of
/// 1.5–4 MB were mapped fresh and returned on many calls (glibc's thresholds), which cost a
/// 10⁵-face fit's binary output up to 2.3× and left small fits one task for two threads.
const CHUNK: usize = 512;

/// Fewest patches per formatting task (below this the task costs more than it saves).
const MIN_CHUNK: usize = 256;

/// Chunks a fit is cut into at least, when it has patches enough: two threads, a few
/// tasks each to even out their speeds.
const MIN_CHUNKS: usize = 16;

/// Chunks formatted side by side before they are written in order: a window of at most
/// 32 768 patches (about 12 MB of binary, 33 MB of JSON Lines for quartics).
const CHUNKS_PER_WINDOW: usize = 64;

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

/// The two forms patches are written in (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PatchFormat {
    /// One JSON record per patch, a line each.
    JsonLines,
    /// [`BINARY_MAGIC`], a JSON header line, then little-endian `f64`s.
    Binary,
}

impl PatchFormat {
    /// The form a file name asks for: binary when it ends in `.bzp`, JSON Lines otherwise.
    pub fn for_path(path: &std::path::Path) -> PatchFormat {
        if path.extension().is_some_and(|e| e == "bzp") {
            PatchFormat::Binary
        } else {
            PatchFormat::JsonLines
        }
    }

    /// What comes before the first patch of a fit with `layout` and `faces` faces.
    pub fn header(self, layout: &Layout, faces: usize) -> Vec<u8> {
        match self {
            PatchFormat::JsonLines => Vec::new(),
            PatchFormat::Binary => {
                let mut h = BINARY_MAGIC.to_vec();
                let _ = writeln!(
                    h,
                    "{{\"degree\":{},\"patches_per_face\":{},\"faces\":{faces},\"points_per_patch\":{},\"form\":\"{}\",\"scalar\":\"f64le\"}}",
                    layout.degree,
                    layout.patches_per_face(),
                    layout.points_per_patch(),
                    form_name(layout.form),
                );
                h
            }
        }
    }

    /// Appends to `out` the patches whose nets are `points` (whole patches of `layout`),
    /// the first of them patch number `first_patch` of the fit, each point mapped by
    /// `to_world`. A fit's output is its header and then its patches formatted in order, in
    /// pieces of any size: the bytes do not depend on where the pieces are cut.
    pub fn format(
        self,
        layout: &Layout,
        first_patch: usize,
        points: &[Point3<f64>],
        to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
        out: &mut Vec<u8>,
    ) {
        match self {
            PatchFormat::JsonLines => format_jsonl(layout, first_patch, points, to_world, out),
            PatchFormat::Binary => format_binary(layout, points, to_world, out),
        }
    }
}

/// What a patch record says it is: a Bézier net of a degree, or the data of an evaluated form.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RecordKind<'a> {
    /// `{"type":"BezierTriangle","degree":n,…}`.
    Bezier {
        /// The degree.
        degree: usize,
    },
    /// `{"type":"SampledPatch","form":"name",…}`.
    Sampled {
        /// The form's name.
        form: &'a str,
    },
}

/// Patch number `patch` of a fit with `layout` (its net `net`, each point mapped by
/// `to_world`) as the record every patch writer of the workbench emits ([`record_of`]).
pub fn patch_record(
    layout: &Layout,
    patch: usize,
    net: &[Point3<f64>],
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
) -> serde_json::Map<String, serde_json::Value> {
    let points: Vec<Point3<f64>> = net
        .iter()
        .enumerate()
        .map(|(k, p)| mapped(layout.form, k, p, to_world))
        .collect();
    let kind = match layout.form {
        Form::Bezier => RecordKind::Bezier {
            degree: layout.degree,
        },
        Form::Sampled(f) => RecordKind::Sampled { form: f.name() },
    };
    record_of(kind, layout.patches_per_face(), patch, &points)
}

/// The patch record, defined once: `type` (with `degree`, or `form`), `points` (as given:
/// world coordinates), `face` and `subpatch` (patch `patch` of faces of `per_face` patches),
/// in that order. The JSON Lines writer ([`PatchFormat::JsonLines`]) formats the same fields
/// without building it (for speed; a test checks the bytes are those of this record
/// serialized); the pipeline's `fit` writes it in any of its stream formats, and its readers
/// of `.bzp` files make it from each patch read.
pub fn record_of(
    kind: RecordKind<'_>,
    per_face: usize,
    patch: usize,
    points: &[Point3<f64>],
) -> serde_json::Map<String, serde_json::Value> {
    use serde_json::Value;
    let per_face = per_face.max(1);
    let mut m = serde_json::Map::new();
    match kind {
        RecordKind::Bezier { degree } => {
            m.insert("type".into(), Value::from("BezierTriangle"));
            m.insert("degree".into(), Value::from(degree));
        }
        RecordKind::Sampled { form } => {
            m.insert("type".into(), Value::from("SampledPatch"));
            m.insert("form".into(), Value::from(form));
        }
    }
    let points = points
        .iter()
        .map(|q| Value::Array(vec![q.x.into(), q.y.into(), q.z.into()]))
        .collect();
    m.insert("points".into(), Value::Array(points));
    m.insert("face".into(), Value::from(patch / per_face));
    m.insert("subpatch".into(), Value::from(patch % per_face));
    m
}

/// [`PatchFormat::format`] for JSON Lines: [`patch_record`]'s fields, formatted directly.
fn format_jsonl(
    layout: &Layout,
    first_patch: usize,
    points: &[Point3<f64>],
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
    s: &mut Vec<u8>,
) {
    let per_face = layout.patches_per_face().max(1);
    let degree = layout.degree;
    let np = layout.points_per_patch().max(1);
    let form = layout.form;
    let head = match form {
        Form::Bezier => format!("{{\"type\":\"BezierTriangle\",\"degree\":{degree},\"points\":["),
        Form::Sampled(f) => format!(
            "{{\"type\":\"SampledPatch\",\"form\":\"{}\",\"points\":[",
            f.name()
        ),
    };
    s.reserve(points.len() / np * (np * 60 + 80));
    let mut num = ryu::Buffer::new();
    let mut int = itoa_buffer();
    for (j, net) in points.chunks_exact(np).enumerate() {
        let i = first_patch + j;
        s.extend_from_slice(head.as_bytes());
        for (k, p) in net.iter().enumerate() {
            let q = mapped(form, k, p, to_world);
            if k > 0 {
                s.push(b',');
            }
            s.push(b'[');
            s.extend_from_slice(num.format(q.x).as_bytes());
            s.push(b',');
            s.extend_from_slice(num.format(q.y).as_bytes());
            s.push(b',');
            s.extend_from_slice(num.format(q.z).as_bytes());
            s.push(b']');
        }
        s.extend_from_slice(b"],\"face\":");
        s.extend_from_slice(format_usize(&mut int, i / per_face));
        s.extend_from_slice(b",\"subpatch\":");
        s.extend_from_slice(format_usize(&mut int, i % per_face));
        s.extend_from_slice(b"}\n");
    }
}

/// Room for the decimal digits of any `usize`.
fn itoa_buffer() -> [u8; 20] {
    [0; 20]
}

/// `n` in decimal, in the tail of `buf`.
fn format_usize(buf: &mut [u8; 20], mut n: usize) -> &[u8] {
    let mut at = buf.len();
    loop {
        at -= 1;
        buf[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    &buf[at..]
}

/// [`PatchFormat::format`] for the binary form.
fn format_binary(
    layout: &Layout,
    points: &[Point3<f64>],
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
    b: &mut Vec<u8>,
) {
    let np = layout.points_per_patch().max(1);
    let form = layout.form;
    b.reserve(points.len() * 24);
    for (k, p) in points.iter().enumerate() {
        let q = mapped(form, k % np, p, to_world);
        for c in [q.x, q.y, q.z] {
            b.extend_from_slice(&c.to_le_bytes());
        }
    }
}

/// Writes every patch of `fit` in `format` to `out`, each point mapped by `to_world` first
/// (the identity, or a working frame's way back). Chunks of patches are formatted in parallel,
/// a window at a time (so memory stays bounded), and written in order.
pub fn write_patches<W: Write + ?Sized>(
    fit: &Fit,
    format: PatchFormat,
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
    out: &mut W,
) -> std::io::Result<()> {
    let np = fit.layout.points_per_patch().max(1);
    let faces = fit.num_patches() / fit.layout.patches_per_face().max(1);
    out.write_all(&format.header(&fit.layout, faces))?;
    // Small fits in smaller chunks, so both threads have work (at 10³ faces one chunk of
    // CHUNK patches held them all); the bytes do not depend on the cut.
    let patches = fit.points.len() / np;
    let chunk = patches.div_ceil(MIN_CHUNKS).clamp(MIN_CHUNK, CHUNK);
    let per_chunk = chunk * np;
    // One buffer per chunk of a window, reused by every window: their pages are faulted in
    // once, not once per window (from 10⁵ faces on that was a third of the binary form's time).
    let mut buffers: Vec<Vec<u8>> = vec![Vec::new(); CHUNKS_PER_WINDOW];
    for (w, window) in fit.points.chunks(per_chunk * CHUNKS_PER_WINDOW).enumerate() {
        window
            .par_chunks(per_chunk)
            .zip(buffers.par_iter_mut())
            .enumerate()
            .for_each(|(c, (pts, b))| {
                b.clear();
                let first = (w * CHUNKS_PER_WINDOW + c) * chunk;
                format.format(&fit.layout, first, pts, to_world, b);
            });
        let used = window.len().div_ceil(per_chunk);
        for b in &buffers[..used] {
            out.write_all(b)?;
        }
    }
    Ok(())
}

/// Writes every patch of `fit` as JSON Lines to `out` ([`write_patches`]).
pub fn write_jsonl<W: Write + ?Sized>(
    fit: &Fit,
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
    out: &mut W,
) -> std::io::Result<()> {
    write_patches(fit, PatchFormat::JsonLines, to_world, out)
}

/// Writes every patch of `fit` in the binary form (module docs, [`write_patches`]).
pub fn write_binary<W: Write + ?Sized>(
    fit: &Fit,
    to_world: &(dyn Fn(&Point3<f64>) -> Point3<f64> + Sync),
    out: &mut W,
) -> std::io::Result<()> {
    write_patches(fit, PatchFormat::Binary, to_world, out)
}

/// The header line of the binary form: what its patches are, and how many.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BinaryHeader {
    /// Degree of the patches.
    pub degree: usize,
    /// Patches per mesh face.
    pub patches_per_face: usize,
    /// Mesh faces.
    pub faces: usize,
    /// Points stored per patch.
    pub points_per_patch: usize,
    /// The evaluated form's name for a non-Bézier layout (`None`: Bézier nets).
    pub form: Option<String>,
}

impl BinaryHeader {
    /// Parses the header line (the JSON between [`BINARY_MAGIC`] and the first newline).
    pub fn parse(line: &[u8]) -> Result<BinaryHeader, PatchReadError> {
        let header: serde_json::Value =
            serde_json::from_slice(line).map_err(|e| PatchReadError::Header(e.to_string()))?;
        let field = |k: &str| {
            header[k]
                .as_u64()
                .and_then(|v| usize::try_from(v).ok())
                .ok_or_else(|| PatchReadError::Header(format!("missing `{k}`")))
        };
        let (degree, patches_per_face, faces, points_per_patch) = (
            field("degree")?,
            field("patches_per_face")?,
            field("faces")?,
            field("points_per_patch")?,
        );
        let form = match header.get("form") {
            None => None,
            Some(f) if f == "bezier" => None,
            Some(f) => Some(f.as_str().unwrap_or_default().to_string()),
        };
        if header["scalar"] != "f64le"
            || (form.is_none() && points_per_patch != crate::beztri::num_points(degree))
        {
            return Err(PatchReadError::Header(
                "unsupported scalar type or point count".into(),
            ));
        }
        Ok(BinaryHeader {
            degree,
            patches_per_face,
            faces,
            points_per_patch,
            form,
        })
    }

    /// Patches in the file (`faces × patches_per_face`; `None` on overflow).
    pub fn patches(&self) -> Option<usize> {
        self.faces.checked_mul(self.patches_per_face)
    }
}

/// Reads a binary patch file back: `(degree, patches_per_face, points)` (points in world
/// coordinates, patch after patch in net order).
pub fn read_binary(bytes: &[u8]) -> Result<(usize, usize, Vec<Point3<f64>>), PatchReadError> {
    let rest = bytes
        .strip_prefix(BINARY_MAGIC)
        .ok_or(PatchReadError::NotBinary)?;
    let end = rest
        .iter()
        .position(|b| *b == b'\n')
        .ok_or_else(|| PatchReadError::Header("no end of line".into()))?;
    let h = BinaryHeader::parse(&rest[..end])?;
    let (degree, ppf, faces, np) = (h.degree, h.patches_per_face, h.faces, h.points_per_patch);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The JSON Lines writer's bytes are [`patch_record`] serialized, record by record, for a
    /// Bézier layout (the ring, Shirman–Séquin) and an evaluated one (Nielson's, whose
    /// normals are directions), through a scaling map to world coordinates.
    #[test]
    fn the_json_lines_writer_writes_the_one_patch_record() {
        let data = mesh::dataset_by_name("ring", None).expect("ring");
        let method =
            curves::method_by_name("chord", &curves::MethodOptions::default()).expect("chord");
        let to_world = |p: &Point3<f64>| Point3::from(p.coords * 2.5) + nalgebra::Vector3::x();
        for name in ["shirman-sequin", "nielson"] {
            let scheme = crate::scheme::scheme_by_name(name, &Default::default()).expect(name);
            let fit =
                crate::fit::fit_scheme(&data.mesh, scheme.as_ref(), method.as_ref()).expect("fit");
            let mut fast = Vec::new();
            write_jsonl(&fit, &to_world, &mut fast).expect("written");
            let mut generic = Vec::new();
            for (i, net) in fit.nets().enumerate() {
                let record = patch_record(&fit.layout, i, net, &to_world);
                generic.extend_from_slice(
                    serde_json::to_string(&record)
                        .expect("serializes")
                        .as_bytes(),
                );
                generic.push(b'\n');
            }
            assert_eq!(
                String::from_utf8_lossy(&fast),
                String::from_utf8_lossy(&generic),
                "{name}"
            );
        }
    }
}

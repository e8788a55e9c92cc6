//! OFF (Object File Format, Geomview): reads `OFF`, `COFF`, `NOFF`, `CNOFF`; writes `OFF`,
//! `COFF` or `NOFF`.
//!
//! # Reading
//!
//! The header keyword (`OFF`, `COFF`, `NOFF` or `CNOFF`; other variants such as `STOFF` or
//! `4OFF` are refused) may be followed on the same line by the counts `nv nf ne`, or the counts
//! come on the next line (`ne` is read and ignored). `#` starts a comment; blank lines are
//! skipped. Then one line per vertex: `x y z`, then `nx ny nz` for `N` variants (→ normals),
//! then 3 or 4 colour values for `C` variants (→ colours, read as sRGB-encoded, as every OFF
//! viewer does, and decoded to linear: [`crate::srgb`]; integers are 0–255 and divided by 255,
//! numbers with a decimal point or exponent are 0–1; the fourth value, alpha, is dropped with a
//! note). Then one line per face: `n i1 … in`, optionally followed by a face colour (ignored,
//! with a note). Polygons are kept as they are.
//!
//! Refused, naming the line: a wrong number of values on a vertex line, numbers that do not
//! parse or are not finite, faces with fewer than 3 corners, indices out of range, fewer
//! vertex or face lines than the counts say.
//!
//! # Writing
//!
//! A header other tools read: `COFF` with colours (sRGB bytes 0–255, what libigl and MeshLab
//! read), `NOFF` with normals and no colours, else `OFF`. `CNOFF`, colours and normals, is
//! refused by libigl and by Python's meshio, so with colours the normals are left out (a
//! comment says so). Python's meshio 5.3 reads only plain `OFF`. Then `#` comment lines (the
//! generator, the curvature convention where the colours show curvature, the colour encoding
//! and map: [`crate::convention`]), which every reader skips after the header line; the counts
//! on their own line, polygons as they are, numbers in Rust's shortest round-trip form.
//! Curvature is not written (OFF has no place for it).

use std::fmt::Write as _;

use nalgebra::{Point3, Vector3};

use crate::error::{ReadError, WriteError};
use crate::format::{MeshFormat, WriteOptions};
use crate::raw::{Polygons, RawMesh};
use crate::util::{
    lines, parse_f64, parse_usize, show, skip_space_and_comments, tokens, validate_for_write,
};

const NAME: &str = "off";

/// How the colours are stored, for the header comment.
const COLOUR_NOTE: &str = "bytes 0-255 after the position";

/// The OFF format (`.off`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Off;

const HEADERS: &[&[u8]] = &[b"OFF", b"COFF", b"NOFF", b"CNOFF"];

impl MeshFormat for Off {
    fn name(&self) -> &'static str {
        NAME
    }

    fn extensions(&self) -> &'static [&'static str] {
        &["off"]
    }

    fn sniff(&self, bytes: &[u8]) -> bool {
        let rest = skip_space_and_comments(bytes, b'#');
        let first = rest
            .split(|b| b.is_ascii_whitespace() || *b == b'#')
            .next()
            .unwrap_or(&[]);
        HEADERS.contains(&first)
    }

    fn read(&self, bytes: &[u8]) -> Result<RawMesh, ReadError> {
        read_off(bytes)
    }

    fn size_hint(&self, mesh: &RawMesh, _: &WriteOptions) -> usize {
        // About 40 characters a vertex line and 30 a face line.
        40 * mesh.positions.len() + 30 * mesh.polygons.len()
    }

    fn write_to(
        &self,
        mesh: &RawMesh,
        _: &WriteOptions,
        out: &mut dyn std::io::Write,
    ) -> Result<(), WriteError> {
        write_off(mesh, out)
    }
}

fn read_off(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    let err = |ln: usize, m: String| ReadError::line(NAME, ln, m);
    // Non-empty lines without comments.
    let mut content = lines(bytes).filter_map(|(ln, l)| {
        let l = match l.iter().position(|&b| b == b'#') {
            Some(c) => l.get(..c).unwrap_or(l),
            None => l,
        };
        tokens(l).next().is_some().then_some((ln, l))
    });
    let Some((hl, header)) = content.next() else {
        return Err(err(1, "empty file: expected `OFF`".into()));
    };
    let mut htoks = tokens(header);
    let kw = htoks.next().unwrap_or(&[]);
    let (normals_flag, colors_flag) = match kw {
        b"OFF" => (false, false),
        b"COFF" => (false, true),
        b"NOFF" => (true, false),
        b"CNOFF" => (true, true),
        other => {
            return Err(err(
                hl,
                format!(
                    "expected `OFF`, `COFF`, `NOFF` or `CNOFF`, found `{}`",
                    show(other)
                ),
            ))
        }
    };
    let mut counts: Vec<(usize, &[u8])> = htoks.map(|t| (hl, t)).collect();
    let mut last = hl;
    if counts.is_empty() {
        let Some((cl, cline)) = content.next() else {
            return Err(err(
                hl,
                "unexpected end of file: expected the counts `nv nf ne`".into(),
            ));
        };
        counts = tokens(cline).map(|t| (cl, t)).collect();
        last = cl;
    }
    let (nv, nf) = match counts.as_slice() {
        [(l1, v), (l2, f), rest @ ..] if rest.len() <= 1 => (
            parse_usize(v).map_err(|m| err(*l1, m))?,
            parse_usize(f).map_err(|m| err(*l2, m))?,
        ),
        _ => {
            return Err(err(
                last,
                format!(
                    "expected the counts `nv nf ne`, found {} values",
                    counts.len()
                ),
            ))
        }
    };
    let left = bytes.len();
    // A vertex line takes at least 6 bytes (`0 0 0\n`), a face line at least 8.
    let vcap = nv.min(left / 6);
    let fcap = nf.min(left / 8);
    let mut positions = Vec::with_capacity(vcap);
    let mut normals = Vec::with_capacity(if normals_flag { vcap } else { 0 });
    let mut colors = Vec::with_capacity(if colors_flag { vcap } else { 0 });
    let mut alpha = 0usize;
    let ncols = 3 + if normals_flag { 3 } else { 0 };
    let mut vals = [0.0f64; 10];
    for v in 0..nv {
        let Some((ln, line)) = content.next() else {
            return Err(err(
                last,
                format!("unexpected end of file: {v} of {nv} vertices read"),
            ));
        };
        last = ln;
        let mut n = 0;
        let mut float_color = false;
        for t in tokens(line) {
            let slot = vals
                .get_mut(n)
                .ok_or_else(|| err(ln, "too many values on a vertex line".into()))?;
            *slot = parse_f64(t).map_err(|m| err(ln, m))?;
            if n >= ncols && t.iter().any(|b| matches!(b, b'.' | b'e' | b'E')) {
                float_color = true;
            }
            n += 1;
        }
        let ok = if colors_flag {
            n == ncols + 3 || n == ncols + 4
        } else {
            n == ncols
        };
        if !ok {
            return Err(err(
                ln,
                format!(
                    "vertex {v} has {n} values, expected {}",
                    if colors_flag {
                        format!("{} or {}", ncols + 3, ncols + 4)
                    } else {
                        ncols.to_string()
                    }
                ),
            ));
        }
        let [x, y, z, a, b, c, ..] = vals;
        positions.push(Point3::new(x, y, z));
        if normals_flag {
            normals.push(Vector3::new(a, b, c));
        }
        if colors_flag {
            let scale = if float_color { 1.0 } else { 255.0 };
            let col = [0, 1, 2].map(|k| {
                crate::srgb::decode((vals.get(ncols + k).copied().unwrap_or(0.0) / scale) as f32)
            });
            colors.push(col);
            if n == ncols + 4 {
                alpha += 1;
            }
        }
    }
    let mut polys = Polygons::with_capacity(fcap, 3 * fcap);
    let mut corners = Vec::new();
    let mut face_colors = 0usize;
    for f in 0..nf {
        let Some((ln, line)) = content.next() else {
            return Err(err(
                last,
                format!("unexpected end of file: {f} of {nf} faces read"),
            ));
        };
        last = ln;
        let mut toks = tokens(line);
        let k = parse_usize(toks.next().unwrap_or(&[])).map_err(|m| err(ln, m))?;
        if k < 3 {
            return Err(err(
                ln,
                format!("face {f} has {k} corners, at least 3 needed"),
            ));
        }
        corners.clear();
        for c in 0..k {
            let t = toks
                .next()
                .ok_or_else(|| err(ln, format!("face {f} says {k} corners but has {c}")))?;
            let i = parse_usize(t).map_err(|m| err(ln, format!("face {f}: {m}")))?;
            if i >= nv {
                return Err(err(
                    ln,
                    format!("face {f}: vertex index {i} is out of range ({nv} vertices)"),
                ));
            }
            corners.push(i);
        }
        if toks.next().is_some() {
            face_colors += 1;
        }
        polys.push(&corners);
    }
    let mut notes = Vec::new();
    if alpha > 0 {
        notes.push(format!("alpha of {alpha} vertex colours dropped"));
    }
    if face_colors > 0 {
        notes.push(format!("colours of {face_colors} faces ignored"));
    }
    Ok(RawMesh {
        positions,
        normals: normals_flag.then_some(normals),
        colors: colors_flag.then_some(colors),
        polygons: polys,
        notes,
        ..RawMesh::default()
    })
}

fn write_off(mesh: &RawMesh, out: &mut dyn std::io::Write) -> Result<(), WriteError> {
    validate_for_write(mesh, NAME)?;
    let mut s = crate::util::Sink::new(out);
    // One of the headers libigl, MeshLab and trimesh all read: `COFF` when there are colours
    // (normals then left out: no reader takes both), `NOFF` with normals, else `OFF`.
    let colors = mesh.colors.as_ref();
    let normals = if colors.is_some() {
        None
    } else {
        mesh.normals.as_ref()
    };
    s.push_str(match (colors.is_some(), normals.is_some()) {
        (true, _) => "COFF\n",
        (false, true) => "NOFF\n",
        (false, false) => "OFF\n",
    });
    for line in crate::util::provenance(mesh, Some(COLOUR_NOTE)) {
        let _ = writeln!(s, "# {line}");
    }
    if colors.is_some() && mesh.normals.is_some() {
        s.push_str(
            "# normals not written: OFF readers take colours (COFF) or normals (NOFF), not both\n",
        );
    }
    let _ = writeln!(s, "{} {} 0", mesh.positions.len(), mesh.polygons.len());
    for (i, p) in mesh.positions.iter().enumerate() {
        let _ = write!(s, "{:?} {:?} {:?}", p.x, p.y, p.z);
        if let Some(n) = normals.and_then(|n| n.get(i)) {
            let _ = write!(s, " {:?} {:?} {:?}", n.x, n.y, n.z);
        }
        if let Some(c) = colors.and_then(|c| c.get(i)) {
            let [r, g, b] = c.map(crate::srgb::encode_byte);
            let _ = write!(s, " {r} {g} {b}");
        }
        s.push('\n');
    }
    for poly in mesh.polygons.iter() {
        let _ = write!(s, "{}", poly.len());
        for &i in poly {
            let _ = write!(s, " {i}");
        }
        s.push('\n');
    }
    s.finish(NAME)
}

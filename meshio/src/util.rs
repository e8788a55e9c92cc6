//! Helpers shared by the readers and writers.

use std::io::Write;

use crate::error::WriteError;
use crate::raw::RawMesh;

/// How many bytes [`Sink`] gathers before handing them to its writer: large enough that the
/// dynamic call and the system call behind it are paid once per 256 KiB, small enough to stay
/// in the L2 cache of the machines the workbench runs on.
pub(crate) const SINK_BUFFER: usize = 256 * 1024;

/// The buffered byte sink every encoder writes into: records are appended to a buffer of
/// [`SINK_BUFFER`] bytes, which goes to the writer in one `write_all` when the next record
/// does not fit, so that encoding a record costs a copy and a comparison and not a dynamic
/// call.
///
/// An error of the writer is kept, later bytes are dropped, and [`Sink::finish`] returns it:
/// encoders then need no error path per number. Text goes in through [`std::fmt::Write`]
/// (`write!(sink, …)`), which never fails here.
pub(crate) struct Sink<'a> {
    out: &'a mut dyn Write,
    /// [`SINK_BUFFER`] bytes, of which the first `len` are waiting.
    buf: Box<[u8]>,
    len: usize,
    error: Option<std::io::Error>,
}

impl<'a> Sink<'a> {
    /// A sink writing to `out`.
    pub(crate) fn new(out: &'a mut dyn Write) -> Self {
        Sink {
            out,
            buf: vec![0; SINK_BUFFER].into_boxed_slice(),
            len: 0,
            error: None,
        }
    }

    /// Appends bytes, handing the buffer on first when they do not fit (and bytes longer than
    /// the buffer straight on after it).
    #[inline]
    pub(crate) fn put(&mut self, bytes: &[u8]) {
        let end = self.len + bytes.len();
        match self.buf.get_mut(self.len..end) {
            Some(room) => {
                room.copy_from_slice(bytes);
                self.len = end;
            }
            None => self.put_slow(bytes),
        }
    }

    #[cold]
    fn put_slow(&mut self, bytes: &[u8]) {
        self.drain();
        if bytes.len() >= SINK_BUFFER {
            self.hand_on(bytes);
        } else if let Some(room) = self.buf.get_mut(..bytes.len()) {
            room.copy_from_slice(bytes);
            self.len = bytes.len();
        }
    }

    fn hand_on(&mut self, bytes: &[u8]) {
        if self.error.is_none() {
            if let Err(e) = self.out.write_all(bytes) {
                self.error = Some(e);
            }
        }
    }

    /// One byte.
    #[inline]
    pub(crate) fn u8(&mut self, x: u8) {
        self.put(&[x]);
    }

    /// A 32-bit float, little-endian.
    #[inline]
    pub(crate) fn f32(&mut self, x: f32) {
        self.put(&x.to_le_bytes());
    }

    /// Three 32-bit floats, little-endian, as one 12-byte record.
    #[inline]
    pub(crate) fn f32x3(&mut self, v: [f32; 3]) {
        self.put(&record12(v.map(f32::to_le_bytes)));
    }

    /// Three 32-bit unsigned integers, little-endian, as one 12-byte record.
    #[inline]
    pub(crate) fn u32x3(&mut self, v: [u32; 3]) {
        self.put(&record12(v.map(u32::to_le_bytes)));
    }

    /// A 32-bit signed integer, little-endian.
    #[inline]
    pub(crate) fn i32(&mut self, x: i32) {
        self.put(&x.to_le_bytes());
    }

    /// A 32-bit unsigned integer, little-endian.
    #[inline]
    pub(crate) fn u32(&mut self, x: u32) {
        self.put(&x.to_le_bytes());
    }

    /// Text.
    #[inline]
    pub(crate) fn push_str(&mut self, s: &str) {
        self.put(s.as_bytes());
    }

    /// One character.
    #[inline]
    pub(crate) fn push(&mut self, c: char) {
        self.put(c.encode_utf8(&mut [0; 4]).as_bytes());
    }

    fn drain(&mut self) {
        let len = std::mem::take(&mut self.len);
        if len > 0 && self.error.is_none() {
            if let Err(e) = self.out.write_all(self.buf.get(..len).unwrap_or(&[])) {
                self.error = Some(e);
            }
        }
    }

    /// Hands on what is left and flushes the writer; the first error of the writer, if any,
    /// as [`WriteError::Io`] of `format`.
    pub(crate) fn finish(mut self, format: &'static str) -> Result<(), WriteError> {
        self.drain();
        if self.error.is_none() {
            if let Err(e) = self.out.flush() {
                self.error = Some(e);
            }
        }
        match self.error {
            Some(source) => Err(WriteError::Io { format, source }),
            None => Ok(()),
        }
    }
}

impl std::fmt::Write for Sink<'_> {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.push_str(s);
        Ok(())
    }
}

/// Three 4-byte words as one 12-byte record.
#[inline]
fn record12(words: [[u8; 4]; 3]) -> [u8; 12] {
    let mut record = [0u8; 12];
    for (slot, w) in record.chunks_exact_mut(4).zip(words) {
        slot.copy_from_slice(&w);
    }
    record
}

/// Lines of a text file, 1-based, without the line break (`\n` or `\r\n`).
pub(crate) fn lines(bytes: &[u8]) -> impl Iterator<Item = (usize, &[u8])> {
    bytes.split(|&b| b == b'\n').enumerate().map(|(i, l)| {
        let l = l.strip_suffix(b"\r").unwrap_or(l);
        (i + 1, l)
    })
}

/// The whitespace-separated tokens of a line.
pub(crate) fn tokens(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|t| !t.is_empty())
}

/// A token for an error message (lossy, at most 40 characters).
pub(crate) fn show(tok: &[u8]) -> String {
    let s = String::from_utf8_lossy(tok);
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s.into_owned()
    }
}

/// A finite number, or what is wrong with the token.
pub(crate) fn parse_f64(tok: &[u8]) -> Result<f64, String> {
    let x: f64 = std::str::from_utf8(tok)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("`{}` is not a number", show(tok)))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("`{}` is not a finite number", show(tok)))
    }
}

/// The integer `i64::from_str` reads from the token (an optional sign, then decimal digits),
/// without going through `str`: the same value, and `None` where it fails (empty, a stray
/// character, overflow). Face corners are most of an OBJ file, so this is its hot path.
pub(crate) fn parse_i64(tok: &[u8]) -> Option<i64> {
    let (negative, digits) = match tok {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, tok),
    };
    if digits.is_empty() {
        return None;
    }
    let mut x: i64 = 0;
    for &d in digits {
        let d = i64::from(d.checked_sub(b'0').filter(|d| *d < 10)?);
        // Negative numbers are accumulated negatively, so that i64::MIN reads too.
        x = x.checked_mul(10)?;
        x = if negative {
            x.checked_sub(d)?
        } else {
            x.checked_add(d)?
        };
    }
    Some(x)
}

/// A non-negative integer, or what is wrong with the token.
pub(crate) fn parse_usize(tok: &[u8]) -> Result<usize, String> {
    std::str::from_utf8(tok)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("`{}` is not a non-negative integer", show(tok)))
}

/// The start of `bytes` after whitespace and whole-line comments starting with `comment`.
pub(crate) fn skip_space_and_comments(mut bytes: &[u8], comment: u8) -> &[u8] {
    loop {
        let start = bytes
            .iter()
            .position(|b| !b.is_ascii_whitespace())
            .unwrap_or(bytes.len());
        bytes = bytes.get(start..).unwrap_or(&[]);
        if bytes.first() == Some(&comment) {
            let end = bytes
                .iter()
                .position(|&b| b == b'\n')
                .unwrap_or(bytes.len());
            bytes = bytes.get(end..).unwrap_or(&[]);
        } else {
            return bytes;
        }
    }
}

/// Checks what every writer relies on: per-vertex arrays of the right length, finite positions,
/// normals, shapes and colours, face indices in range, no face with fewer than 3 corners.
/// Properties and curvature are checked by the writers that store them
/// ([`check_f32_values`]): a format is asked only for what it stores.
pub(crate) fn validate_for_write(mesh: &RawMesh, format: &'static str) -> Result<(), WriteError> {
    let n = mesh.positions.len();
    let check_len = |what: &str, len: Option<usize>| match len {
        Some(l) if l != n => Err(WriteError::invalid(
            format,
            format!("{what} has {l} entries for {n} vertices"),
        )),
        _ => Ok(()),
    };
    check_len("normals", mesh.normals.as_ref().map(Vec::len))?;
    check_len("shapes", mesh.shapes.as_ref().map(Vec::len))?;
    check_len("colors", mesh.colors.as_ref().map(Vec::len))?;
    check_len("vertex_names", mesh.vertex_names.as_ref().map(Vec::len))?;
    for (k, v) in &mesh.properties {
        check_len(&format!("property `{k}`"), Some(v.len()))?;
    }
    if let Some(names) = &mesh.face_names {
        if names.len() != mesh.polygons.len() {
            return Err(WriteError::invalid(
                format,
                format!(
                    "face_names has {} entries for {} faces",
                    names.len(),
                    mesh.polygons.len()
                ),
            ));
        }
    }
    let nonfinite = |what: &str, i: usize| {
        Err(WriteError::invalid(
            format,
            format!("{what} of vertex {i} is not finite"),
        ))
    };
    for (i, p) in mesh.positions.iter().enumerate() {
        if !p.coords.iter().all(|x| x.is_finite()) {
            return nonfinite("position", i);
        }
    }
    if let Some(ns) = &mesh.normals {
        for (i, v) in ns.iter().enumerate() {
            if !v.iter().all(|x| x.is_finite()) {
                return nonfinite("normal", i);
            }
        }
    }
    if let Some(ss) = &mesh.shapes {
        for (i, s) in ss.iter().enumerate() {
            if !s.iter().all(|x| x.is_finite()) {
                return nonfinite("shape", i);
            }
        }
    }
    if let Some(cs) = &mesh.colors {
        for (i, c) in cs.iter().enumerate() {
            if !c.iter().all(|x| x.is_finite()) {
                return nonfinite("colour", i);
            }
        }
    }
    if let Some(c) = &mesh.curvature {
        check_len("curvature (gaussian)", Some(c.gaussian.len()))?;
        check_len("curvature (mean)", Some(c.mean.len()))?;
    }
    for (f, poly) in mesh.polygons.iter().enumerate() {
        if poly.len() < 3 {
            return Err(WriteError::invalid(
                format,
                format!("face {f} has {} corners (at least 3 needed)", poly.len()),
            ));
        }
        if let Some(&i) = poly.iter().find(|&&i| i >= n) {
            return Err(WriteError::invalid(
                format,
                format!("face {f} refers to vertex {i}, but there are {n} vertices"),
            ));
        }
    }
    Ok(())
}

/// The triangles of a fan around the polygon's first corner.
pub(crate) fn fan(poly: &[usize]) -> impl Iterator<Item = [usize; 3]> + '_ {
    let first = poly.first().copied().unwrap_or(0);
    poly.windows(2).skip(1).map(move |w| [first, w[0], w[1]])
}

/// Number of triangles of all fans.
pub(crate) fn fan_count(mesh: &RawMesh) -> usize {
    mesh.polygons
        .iter()
        .map(|p| p.len().saturating_sub(2))
        .sum()
}

/// Checks that every value of a per-vertex quantity stored as a 32-bit float (PLY `float`, glTF
/// `FLOAT`) is one: finite and at most `f32::MAX` in magnitude. The error names the quantity,
/// the vertex, the value and the range, so that a curvature overflowing at an extreme scale is
/// refused rather than written as an infinity or a plausible-looking number. The values are
/// taken one by one (derived quantities are checked without being stored).
pub(crate) fn check_f32_values(
    format: &'static str,
    what: &str,
    values: impl IntoIterator<Item = f64>,
) -> Result<(), WriteError> {
    match values
        .into_iter()
        .enumerate()
        .find(|(_, x)| !x.is_finite() || x.abs() > f64::from(f32::MAX))
    {
        Some((i, x)) => Err(WriteError::invalid(
            format,
            format!(
                "{what} of vertex {i} is {x:e}, which a 32-bit float does not hold (finite, at most {:e} in magnitude)",
                f32::MAX
            ),
        )),
        None => Ok(()),
    }
}

/// Principal curvature `j` (0: `k1`, 1: `k2`, `k1 ≥ k2`) of vertex `i`
/// ([`crate::convention::Curvature::principal`]), 0 out of range.
pub(crate) fn principal(c: &crate::convention::Curvature, i: usize, j: usize) -> f64 {
    c.principal(i)
        .and_then(|k| k.get(j).copied())
        .unwrap_or(0.0)
}

/// Checks the curvature quantities a writer stores, in the exported convention, with
/// [`check_f32_values`]: the Gaussian and the mean curvature and the principal curvatures
/// `k1 ≥ k2`, in that order.
pub(crate) fn check_curvature(
    format: &'static str,
    c: &crate::convention::Curvature,
) -> Result<(), WriteError> {
    check_f32_values(format, "gaussian curvature", c.gaussian.iter().copied())?;
    check_f32_values(format, "mean curvature", c.mean.iter().copied())?;
    check_f32_values(
        format,
        "principal curvature k1",
        (0..c.len()).map(|i| principal(c, i, 0)),
    )?;
    check_f32_values(
        format,
        "principal curvature k2",
        (0..c.len()).map(|i| principal(c, i, 1)),
    )
}

/// The lines every written file opens with, each for the format's own comment syntax: the
/// generator, the curvature convention when the mesh holds curvature or colours by it, the
/// colour map, and how the colours are stored (`colours`) when there are colours.
pub(crate) fn provenance(mesh: &RawMesh, colours: Option<&str>) -> Vec<String> {
    let mut lines = vec![format!("generator {}", crate::convention::GENERATOR)];
    let by_curvature = mesh
        .color_map
        .as_ref()
        .is_some_and(|m| m.quantity.contains("curvature"));
    if mesh.curvature.is_some() || by_curvature {
        lines.push(crate::convention::CURVATURE_CONVENTION.to_string());
    }
    if mesh.colors.is_some() {
        if let Some(c) = colours {
            lines.push(format!("{}, {c}", crate::convention::SRGB_COLOURS));
        }
        if let Some(m) = &mesh.color_map {
            lines.push(m.describe());
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_i64_reads_what_from_str_reads() {
        let mut cases: Vec<String> = [
            "",
            "-",
            "+",
            "0",
            "-0",
            "+0",
            "7",
            "-7",
            "+7",
            "0012",
            "-0012",
            "1a",
            "a1",
            "1 ",
            " 1",
            "--1",
            "+-1",
            "1.0",
            "1e3",
            "9223372036854775807",
            "9223372036854775808",
            "-9223372036854775808",
            "-9223372036854775809",
            "99999999999999999999",
            "١",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        // Random strings of 0 to 15 characters, one 4-bit draw each, from one 64-bit draw.
        let mut rng = rng::SplitMix64::new(1);
        for _ in 0..2000 {
            let state = rng.next_u64();
            let len = (state >> 60) as usize;
            let s: String = (0..len)
                .map(|k| b"0123456789-+/x9"[((state >> (4 * k)) % 15) as usize] as char)
                .collect();
            cases.push(s);
        }
        for s in cases {
            assert_eq!(parse_i64(s.as_bytes()), s.parse::<i64>().ok(), "{s:?}");
        }
    }
}

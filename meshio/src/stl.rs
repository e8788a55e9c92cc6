//! STL (stereolithography): ASCII and binary.
//!
//! # Reading
//!
//! A file is binary when its size is exactly `84 + 50 · count` for the triangle count at byte
//! 80, even if it starts with `solid` (many binary writers put `solid` in the header); it is
//! ASCII when it starts with `solid` otherwise, and binary again otherwise (then a size that
//! does not fit the count is an error naming the first incomplete facet, and bytes after the
//! last facet are ignored with a note).
//!
//! STL stores every triangle's corners separately; the reader welds corners with exactly the
//! same position (bit pattern, with `-0.0` taken as `0.0`) into one vertex, in order of first
//! appearance, and notes how many corners were welded. Facet normals are not vertex normals:
//! they are ignored (with a note). ASCII `outer loop`s with more than three vertices are kept as
//! polygons; several `solid`s in one file are read one after the other. The binary attribute
//! bytes are ignored.
//!
//! Refused: non-finite coordinates (naming the facet for binary, the line for ASCII), loops
//! with fewer than 3 vertices, malformed ASCII keywords.
//!
//! # Writing
//!
//! Binary by default ([`WriteOptions::ascii`] for ASCII): polygons fan-triangulated around their
//! first corner, facet normal = the normalized cross product of two edges (zero for degenerate
//! triangles), coordinates as 32-bit floats. Only positions and faces are written.

use std::collections::HashMap;
use std::fmt::Write as _;

use nalgebra::{Point3, Vector3};

use crate::error::{ReadError, WriteError};
use crate::format::{MeshFormat, WriteOptions};
use crate::raw::{Polygons, RawMesh};
use crate::util::{fan, fan_count, lines, parse_f64, show, tokens, validate_for_write};

const NAME: &str = "stl";

/// The STL format (`.stl`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Stl;

/// The triangle count of a binary STL of exactly this size, if it is one.
fn binary_count(bytes: &[u8]) -> Option<usize> {
    let c = bytes.get(80..84)?;
    let count = u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as usize;
    (count.checked_mul(50)?.checked_add(84)? == bytes.len()).then_some(count)
}

fn starts_with_solid(bytes: &[u8]) -> bool {
    let start = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .unwrap_or(bytes.len());
    bytes.get(start..).is_some_and(|b| b.starts_with(b"solid"))
}

impl MeshFormat for Stl {
    fn name(&self) -> &'static str {
        NAME
    }

    fn extensions(&self) -> &'static [&'static str] {
        &["stl"]
    }

    fn sniff(&self, bytes: &[u8]) -> bool {
        binary_count(bytes).is_some() || starts_with_solid(bytes)
    }

    fn read(&self, bytes: &[u8]) -> Result<RawMesh, ReadError> {
        if binary_count(bytes).is_some() || !starts_with_solid(bytes) {
            read_binary(bytes)
        } else {
            read_ascii(bytes)
        }
    }

    fn size_hint(&self, mesh: &RawMesh, options: &WriteOptions) -> usize {
        // Binary: an 84-byte header and 50 bytes a triangle; text about 250 bytes a triangle.
        let per = if options.ascii { 250 } else { 50 };
        84 + per * crate::util::fan_count(mesh)
    }

    fn write_to(
        &self,
        mesh: &RawMesh,
        options: &WriteOptions,
        out: &mut dyn std::io::Write,
    ) -> Result<(), WriteError> {
        write_stl(mesh, options, out)
    }
}

/// Welds corners by exact position.
struct Welder {
    index: HashMap<[u64; 3], usize>,
    positions: Vec<Point3<f64>>,
    corners: usize,
}

impl Welder {
    fn new(cap: usize) -> Self {
        Welder {
            index: HashMap::with_capacity(cap),
            positions: Vec::with_capacity(cap),
            corners: 0,
        }
    }

    fn add(&mut self, p: [f64; 3]) -> usize {
        self.corners += 1;
        // -0.0 + 0.0 is +0.0: one key for both zeros.
        let key = p.map(|x| (x + 0.0).to_bits());
        let next = self.positions.len();
        *self.index.entry(key).or_insert_with(|| {
            self.positions.push(Point3::from(p.map(|x| x + 0.0)));
            next
        })
    }

    fn finish(self, polygons: Polygons, extra: Vec<String>) -> RawMesh {
        let mut notes = vec![
            format!(
                "welded {} corners into {} vertices ({} corners merged with an earlier one)",
                self.corners,
                self.positions.len(),
                self.corners - self.positions.len()
            ),
            "facet normals ignored (STL has no vertex normals)".to_string(),
        ];
        notes.extend(extra);
        RawMesh {
            positions: self.positions,
            polygons,
            notes,
            ..RawMesh::default()
        }
    }
}

fn read_binary(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    let Some(c) = bytes.get(80..84) else {
        return Err(ReadError::header(
            NAME,
            format!(
                "a binary STL has an 84-byte header; the file has {} bytes",
                bytes.len()
            ),
        ));
    };
    let count = u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as usize;
    let body = bytes.get(84..).unwrap_or(&[]);
    let cap = count.min(body.len() / 50);
    let mut welder = Welder::new(cap.saturating_mul(3) / 2);
    let mut polys = Polygons::with_capacity(cap, 3 * cap);
    let mut records = body.chunks(50);
    for i in 0..count {
        let rec = records.next().unwrap_or(&[]);
        if rec.len() < 50 {
            return Err(ReadError::element(
                NAME,
                "facet",
                i,
                format!(
                    "unexpected end of file (the header says {count} facets, the file has room for {i})"
                ),
            ));
        }
        let mut tri = [0usize; 3];
        for (k, slot) in tri.iter_mut().enumerate() {
            let mut p = [0.0f64; 3];
            for (j, x) in p.iter_mut().enumerate() {
                let o = 12 + 12 * k + 4 * j;
                let b = rec.get(o..o + 4).unwrap_or(&[0; 4]);
                let v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                if !v.is_finite() {
                    return Err(ReadError::element(
                        NAME,
                        "facet",
                        i,
                        format!("vertex {}: coordinate {v} is not finite", k + 1),
                    ));
                }
                *x = v as f64;
            }
            *slot = welder.add(p);
        }
        polys.push(&tri);
    }
    let trailing = body.len().saturating_sub(50 * count);
    let extra = if trailing > 0 {
        vec![format!("{trailing} bytes after the last facet ignored")]
    } else {
        Vec::new()
    };
    Ok(welder.finish(polys, extra))
}

fn read_ascii(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    let err = |ln: usize, m: String| ReadError::line(NAME, ln, m);
    let mut welder = Welder::new(0);
    let mut polys = Polygons::new();
    let mut loop_corners: Option<Vec<usize>> = None;
    let mut in_solid = false;
    let mut last_line = 0;
    for (ln, line) in lines(bytes) {
        last_line = ln;
        let mut toks = tokens(line);
        let Some(kw) = toks.next() else { continue };
        match kw {
            b"solid" => {
                if in_solid {
                    return Err(err(ln, "`solid` inside a solid".into()));
                }
                in_solid = true;
            }
            b"endsolid" => {
                if loop_corners.is_some() {
                    return Err(err(ln, "`endsolid` inside a loop".into()));
                }
                in_solid = false;
            }
            b"facet" | b"endfacet" if in_solid => {}
            b"outer" if in_solid => {
                if toks.next() != Some(b"loop") {
                    return Err(err(ln, "expected `outer loop`".into()));
                }
                if loop_corners.is_some() {
                    return Err(err(ln, "`outer loop` inside a loop".into()));
                }
                loop_corners = Some(Vec::with_capacity(3));
            }
            b"vertex" => {
                let Some(corners) = loop_corners.as_mut() else {
                    return Err(err(ln, "`vertex` outside `outer loop`".into()));
                };
                let mut p = [0.0; 3];
                for x in p.iter_mut() {
                    let t = toks
                        .next()
                        .ok_or_else(|| err(ln, "`vertex` needs 3 coordinates".into()))?;
                    *x = parse_f64(t).map_err(|m| err(ln, m))?;
                }
                corners.push(welder.add(p));
            }
            b"endloop" => {
                let Some(corners) = loop_corners.take() else {
                    return Err(err(ln, "`endloop` without `outer loop`".into()));
                };
                if corners.len() < 3 {
                    return Err(err(
                        ln,
                        format!("facet has {} vertices, at least 3 needed", corners.len()),
                    ));
                }
                polys.push(&corners);
            }
            other => {
                return Err(err(ln, format!("unexpected `{}`", show(other))));
            }
        }
    }
    if loop_corners.is_some() || in_solid {
        return Err(err(
            last_line,
            "unexpected end of file (missing `endloop`/`endsolid`)".into(),
        ));
    }
    Ok(welder.finish(polys, Vec::new()))
}

fn facet_normal(a: &Point3<f64>, b: &Point3<f64>, c: &Point3<f64>) -> Vector3<f64> {
    let n = (b - a).cross(&(c - a));
    n.try_normalize(0.0).unwrap_or_else(Vector3::zeros)
}

fn write_stl(
    mesh: &RawMesh,
    options: &WriteOptions,
    out: &mut dyn std::io::Write,
) -> Result<(), WriteError> {
    validate_for_write(mesh, NAME)?;
    let p = &mesh.positions;
    let tris = mesh.polygons.iter().flat_map(fan);
    let corner = |i: usize| p.get(i).copied().unwrap_or_else(Point3::origin);
    if options.ascii {
        let mut s = crate::util::Sink::new(out);
        s.push_str("solid meshio\n");
        for [a, b, c] in tris {
            let (a, b, c) = (corner(a), corner(b), corner(c));
            let n = facet_normal(&a, &b, &c);
            let _ = writeln!(
                s,
                "  facet normal {:?} {:?} {:?}",
                n.x as f32, n.y as f32, n.z as f32
            );
            s.push_str("    outer loop\n");
            for v in [a, b, c] {
                let _ = writeln!(
                    s,
                    "      vertex {:?} {:?} {:?}",
                    v.x as f32, v.y as f32, v.z as f32
                );
            }
            s.push_str("    endloop\n  endfacet\n");
        }
        s.push_str("endsolid meshio\n");
        return s.finish(NAME);
    }
    let count = fan_count(mesh);
    let count32 = u32::try_from(count).map_err(|_| {
        WriteError::invalid(NAME, format!("{count} triangles do not fit a binary STL"))
    })?;
    let mut s = crate::util::Sink::new(out);
    let mut header = [b' '; 80];
    let text = b"binary STL written by meshio";
    for (h, t) in header.iter_mut().zip(text) {
        *h = *t;
    }
    s.put(&header);
    s.u32(count32);
    // One facet is one 50-byte record: normal and corners as 12 f32, then 2 attribute bytes.
    let mut record = [0u8; 50];
    for [a, b, c] in tris {
        let (a, b, c) = (corner(a), corner(b), corner(c));
        let n = facet_normal(&a, &b, &c);
        let values = [n, a.coords, b.coords, c.coords];
        let floats = values.iter().flat_map(|v| v.iter());
        for (slot, x) in record.chunks_exact_mut(4).zip(floats) {
            slot.copy_from_slice(&(*x as f32).to_le_bytes());
        }
        s.put(&record);
    }
    s.finish(NAME)
}

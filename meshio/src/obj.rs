//! Wavefront OBJ.
//!
//! # Reading
//!
//! * `v x y z [w]` positions (`w` is ignored); `v x y z r g b` also gives a vertex colour (0–1,
//!   sRGB-encoded as every OBJ viewer reads it, decoded to linear: [`crate::srgb`]), kept in
//!   [`RawMesh::colors`] when every vertex has one (otherwise dropped with a note).
//! * `vn x y z` normals, used through the faces' corners (see below).
//! * `f c1 c2 c3 …` polygons, kept as they are, with corners `a`, `a/b`, `a//c` or `a/b/c`
//!   (position / texture / normal index, 1-based; negative indices count back from the last
//!   element read so far). A corner must refer to an element already read.
//! * Everything else (`vt`, `o`, `g`, `s`, `usemtl`, `mtllib`, `l`, `p`, curves, unknown
//!   keywords) is ignored and counted in one note; `#` starts a comment.
//!
//! OBJ normals belong to face corners, [`RawMesh::normals`] to vertices. When every position
//! used by a face has a normal at all of its corners, each position gets its corners' normal as
//! written if they all agree within [`NORMAL_AGREEMENT`]; where they disagree (a crease), it
//! gets the normalized sum of the corners' unit normals, and a note counts these. When some
//! used positions have no normal, no normals are kept and a note says for how many of the
//! used vertices they were given. Unused positions get a zero normal (and a note).
//!
//! Refused, with the line: numbers that do not parse or are not finite, a wrong number of
//! values in `v`/`vn`, faces with fewer than 3 corners, index 0 and indices out of range.
//!
//! # Writing
//!
//! `#` comment lines first: the generator, the curvature convention where the colours show
//! curvature, the colour encoding and map ([`crate::convention`]). `v x y z` (`v x y z r g b`
//! with colours, sRGB-encoded 0–1), `vn` per vertex when there are normals, `f` with `a//a`
//! corners when there are normals; polygons as they are. Numbers are written in Rust's
//! shortest round-trip form, so reading back gives identical positions (colours within the
//! `f32` rounding of the sRGB round trip). Shapes, names, curvature and other properties are
//! not written (OBJ has no place for them).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use nalgebra::{Point3, Vector3};

use crate::error::{ReadError, WriteError};
use crate::format::{MeshFormat, WriteOptions};
use crate::raw::{Polygons, RawMesh};
use crate::util::{
    lines, parse_f64, parse_i64, show, skip_space_and_comments, tokens, validate_for_write,
};

const NAME: &str = "obj";

/// How the colours are stored, for the header comment.
const COLOUR_NOTE: &str = "0-1 after the position (v x y z r g b)";

/// Two corners of one position whose normals' directions differ by more than this angle
/// (radians, about 0.06°) disagree: exporters that weld vertices print the same normal with the
/// same rounding (differences of ~1e-6), while a deliberate crease differs by degrees.
pub const NORMAL_AGREEMENT: f64 = 1e-3;

/// The Wavefront OBJ format (`.obj`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Obj;

const KEYWORDS: &[&[u8]] = &[
    b"v", b"vn", b"vt", b"vp", b"f", b"o", b"g", b"s", b"l", b"p", b"usemtl", b"mtllib",
];

impl MeshFormat for Obj {
    fn name(&self) -> &'static str {
        NAME
    }

    fn extensions(&self) -> &'static [&'static str] {
        &["obj"]
    }

    fn sniff(&self, bytes: &[u8]) -> bool {
        let rest = skip_space_and_comments(bytes, b'#');
        let first = rest
            .split(|b| b.is_ascii_whitespace())
            .next()
            .unwrap_or(&[]);
        let follows = rest.get(first.len()).copied();
        KEYWORDS.contains(&first) && follows.is_some_and(|b| b == b' ' || b == b'\t')
    }

    fn read(&self, bytes: &[u8]) -> Result<RawMesh, ReadError> {
        read_obj(bytes)
    }

    fn write(&self, mesh: &RawMesh, _: &WriteOptions) -> Result<Vec<u8>, WriteError> {
        write_obj(mesh)
    }
}

fn err(line: usize, message: impl Into<String>) -> ReadError {
    ReadError::line(NAME, line, message)
}

/// What a face corner's index refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Indexed {
    /// A `v` line.
    Vertex,
    /// A `vn` line.
    Normal,
}

impl Indexed {
    fn name(self) -> &'static str {
        match self {
            Indexed::Vertex => "vertex",
            Indexed::Normal => "normal",
        }
    }

    fn plural(self) -> &'static str {
        match self {
            Indexed::Vertex => "vertices",
            Indexed::Normal => "normals",
        }
    }
}

/// Resolves a 1-based or negative OBJ index against `count` elements read so far.
fn resolve(
    tok: &[u8],
    count: usize,
    indexed: Indexed,
    line: usize,
    corner: usize,
) -> Result<usize, ReadError> {
    let (what, plural) = (indexed.name(), indexed.plural());
    let i: i64 = parse_i64(tok).ok_or_else(|| {
        err(
            line,
            format!(
                "face corner {}: `{}` is not a {what} index",
                corner + 1,
                show(tok)
            ),
        )
    })?;
    let resolved = if i > 0 {
        usize::try_from(i - 1).ok()
    } else if i < 0 {
        usize::try_from(i.unsigned_abs())
            .ok()
            .and_then(|k| count.checked_sub(k))
    } else {
        None
    };
    match resolved {
        Some(r) if r < count => Ok(r),
        _ => Err(err(
            line,
            format!(
                "face corner {}: {what} index {i} is out of range ({count} {plural} read so far)",
                corner + 1
            ),
        )),
    }
}

fn read_obj(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    let mut positions: Vec<Point3<f64>> = Vec::new();
    let mut colors: Vec<[f32; 3]> = Vec::new();
    let mut vnormals: Vec<Vector3<f64>> = Vec::new();
    let mut polygons = Polygons::new();
    // Normal index of every corner (usize::MAX: none).
    let mut corner_normals: Vec<usize> = Vec::new();
    let mut ignored: BTreeMap<String, usize> = BTreeMap::new();
    let mut corners: Vec<usize> = Vec::new();
    let mut cnormals: Vec<usize> = Vec::new();
    let mut values = [0.0f64; 7];
    for (ln, line) in lines(bytes) {
        let line = match line.iter().position(|&b| b == b'#') {
            Some(c) => line.get(..c).unwrap_or(line),
            None => line,
        };
        let mut toks = tokens(line);
        let Some(kw) = toks.next() else { continue };
        match kw {
            b"v" | b"vn" => {
                let mut n = 0;
                for t in toks {
                    let slot = values
                        .get_mut(n)
                        .ok_or_else(|| err(ln, format!("`{}` has more than 7 values", show(kw))))?;
                    *slot = parse_f64(t).map_err(|m| err(ln, m))?;
                    n += 1;
                }
                let [x, y, z, r, g, b, _] = values;
                if kw == b"vn" {
                    if n != 3 {
                        return Err(err(ln, format!("`vn` has {n} values, expected 3")));
                    }
                    vnormals.push(Vector3::new(x, y, z));
                } else {
                    match n {
                        3 | 4 => {}
                        6 => colors.push([r, g, b].map(|c| crate::srgb::decode(c as f32))),
                        _ => {
                            return Err(err(
                                ln,
                                format!(
                                "`v` has {n} values, expected 3, 4 (x y z w) or 6 (x y z r g b)"
                            ),
                            ))
                        }
                    }
                    positions.push(Point3::new(x, y, z));
                }
            }
            b"f" => {
                corners.clear();
                cnormals.clear();
                for (c, t) in toks.enumerate() {
                    let mut parts = t.split(|&b| b == b'/');
                    let p = parts.next().unwrap_or(&[]);
                    let _tex = parts.next();
                    let nrm = parts.next();
                    if parts.next().is_some() {
                        return Err(err(
                            ln,
                            format!("face corner {}: `{}` has more than 3 parts", c + 1, show(t)),
                        ));
                    }
                    corners.push(resolve(p, positions.len(), Indexed::Vertex, ln, c)?);
                    cnormals.push(match nrm {
                        Some(nt) if !nt.is_empty() => {
                            resolve(nt, vnormals.len(), Indexed::Normal, ln, c)?
                        }
                        _ => usize::MAX,
                    });
                }
                if corners.len() < 3 {
                    return Err(err(
                        ln,
                        format!("face has {} corners, at least 3 needed", corners.len()),
                    ));
                }
                polygons.push(&corners);
                corner_normals.extend_from_slice(&cnormals);
            }
            other => {
                *ignored.entry(show(other)).or_default() += 1;
            }
        }
    }
    let mut notes = Vec::new();
    if !ignored.is_empty() {
        let total: usize = ignored.values().sum();
        let list: Vec<String> = ignored.iter().map(|(k, n)| format!("{k} ×{n}")).collect();
        notes.push(format!("ignored {total} statements: {}", list.join(", ")));
    }
    let colors = if colors.is_empty() {
        None
    } else if colors.len() == positions.len() {
        Some(colors)
    } else {
        notes.push(format!(
            "colours given for {} of {} vertices: ignored",
            colors.len(),
            positions.len()
        ));
        None
    };
    let normals = vertex_normals(
        &positions,
        &polygons,
        &corner_normals,
        &vnormals,
        &mut notes,
    );
    Ok(RawMesh {
        positions,
        normals,
        colors,
        polygons,
        notes,
        ..RawMesh::default()
    })
}

/// Per-vertex normals from per-corner normal indices (see the module docs).
fn vertex_normals(
    positions: &[Point3<f64>],
    polygons: &Polygons,
    corner_normals: &[usize],
    vnormals: &[Vector3<f64>],
    notes: &mut Vec<String>,
) -> Option<Vec<Vector3<f64>>> {
    if !corner_normals.iter().any(|&c| c != usize::MAX) {
        return None;
    }
    let n = positions.len();
    // Per position: 0 unused, 1 all corners so far with normals, 2 some corner without.
    let mut state = vec![0u8; n];
    let mut first: Vec<usize> = vec![usize::MAX; n];
    let mut sum = vec![Vector3::zeros(); n];
    let mut crease = vec![false; n];
    let corners = polygons.iter().flat_map(|p| p.iter().copied());
    for (v, &c) in corners.zip(corner_normals) {
        let (Some(s), Some(f), Some(acc), Some(cr)) = (
            state.get_mut(v),
            first.get_mut(v),
            sum.get_mut(v),
            crease.get_mut(v),
        ) else {
            continue;
        };
        let Some(normal) = vnormals.get(c) else {
            *s = 2;
            continue;
        };
        if *s == 0 {
            *s = 1;
        }
        let unit = normal.try_normalize(0.0).unwrap_or(*normal);
        *acc += unit;
        match vnormals.get(*f) {
            None => *f = c,
            Some(f0) => {
                if f0.angle(normal) > NORMAL_AGREEMENT {
                    *cr = true;
                }
            }
        }
    }
    let used = state.iter().filter(|&&s| s != 0).count();
    let with = state.iter().filter(|&&s| s == 1).count();
    if with < used {
        notes.push(format!(
            "normals given for {with} of {used} vertices: ignored"
        ));
        return None;
    }
    let mut creases = 0;
    let out = (0..n)
        .map(|v| {
            let f = first.get(v).copied().unwrap_or(usize::MAX);
            match (vnormals.get(f), crease.get(v), sum.get(v)) {
                (Some(_), Some(true), Some(s)) => {
                    creases += 1;
                    s.try_normalize(0.0).unwrap_or(*s)
                }
                (Some(n0), _, _) => *n0,
                _ => Vector3::zeros(),
            }
        })
        .collect();
    if creases > 0 {
        notes.push(format!(
            "{creases} vertices have corners with different normals (creases): each gets the normalized sum"
        ));
    }
    if used < n {
        notes.push(format!(
            "{} vertices are used by no face: their normal is zero",
            n - used
        ));
    }
    Some(out)
}

fn write_obj(mesh: &RawMesh) -> Result<Vec<u8>, WriteError> {
    validate_for_write(mesh, NAME)?;
    let mut s = String::with_capacity(40 * mesh.positions.len() + 30 * mesh.polygons.len());
    for line in crate::util::provenance(mesh, Some(COLOUR_NOTE)) {
        let _ = writeln!(s, "# {line}");
    }
    for (i, p) in mesh.positions.iter().enumerate() {
        let _ = write!(s, "v {:?} {:?} {:?}", p.x, p.y, p.z);
        if let Some(c) = mesh.colors.as_ref().and_then(|c| c.get(i)) {
            let [r, g, b] = c.map(crate::srgb::encode);
            let _ = write!(s, " {r:?} {g:?} {b:?}");
        }
        s.push('\n');
    }
    if let Some(ns) = &mesh.normals {
        for n in ns {
            let _ = writeln!(s, "vn {:?} {:?} {:?}", n.x, n.y, n.z);
        }
    }
    let with_normals = mesh.normals.is_some();
    for poly in mesh.polygons.iter() {
        s.push('f');
        for &i in poly {
            if with_normals {
                let _ = write!(s, " {}//{}", i + 1, i + 1);
            } else {
                let _ = write!(s, " {}", i + 1);
            }
        }
        s.push('\n');
    }
    Ok(s.into_bytes())
}

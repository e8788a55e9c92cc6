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
//! * `s N` / `s off` smoothing groups: the polygons after the line are in group `N` (a 32-bit
//!   unsigned number, as exporters write them), or in none after `s off` or `s 0`; polygons
//!   before the first `s` line are in none. Used for sharp edges only (below).
//! * Everything else (`vt`, `o`, `g`, `usemtl`, `mtllib`, `l`, `p`, curves, unknown keywords)
//!   is ignored and counted in one note; `#` starts a comment.
//!
//! OBJ normals belong to face corners, [`RawMesh::normals`] to vertices. When every position
//! used by a face has a normal at all of its corners, each position gets its corners' normal as
//! written if they all agree within [`NORMAL_AGREEMENT`]; where they disagree (a crease), it
//! gets the normalized sum of the corners' unit normals, and a note counts these. When some
//! used positions have no normal, no normals are kept and a note says for how many of the
//! used vertices they were given. Unused positions get a zero normal (and a note).
//!
//! ## Sharp edges
//!
//! [`RawMesh::crease_edges`] holds the polygon sides the file marks as sharp, from two sources:
//!
//! * **per-corner normals** (`f v//vn`, `f v/vt/vn`): a side shared by two polygons is sharp
//!   when, at either of its two end positions, the two polygons' corner normals there make an
//!   angle larger than [`NORMAL_AGREEMENT`] (the angle of the directions, so lengths do not
//!   matter; the same `vn` index agrees exactly). Where one of the two corners has no normal,
//!   that end says nothing;
//! * **smoothing groups**, only when the file has an `s` line at all (a file without one says
//!   nothing): a side shared by two polygons is sharp when they are in different groups or
//!   either is in none.
//!
//! The two combine by union: a side is sharp when either source says so (the reader's note
//! counts each source, `N edges marked sharp by per-corner normals, M by smoothing groups`, and
//! the union). A side of one polygon only (a boundary) is never sharp. On an edge with more than
//! two polygon sides (non-manifold) each side is compared with the first one that has a normal
//! (or a group) at that end. Crease pairs are always sides of the file's polygons: the fans a
//! polygon of more than three corners is later split into (`mesh::repair`) add diagonals,
//! which are never creases (unless the same vertex pair is also a marked side of another
//! polygon).
//!
//! The sides are grouped by edge with a counting sort on the edge's lower vertex (16 bytes a
//! side, no allocation per face), and only where the answer is not known from the vertices
//! alone: a side can be sharp by normals only if one of its end positions has corners with
//! different `vn` indices, and by groups only if neither end position has all its polygons in
//! one group (both exact: two polygons that differ at an end give that end two `vn` indices;
//! two polygons in different groups, or one in none, are at both ends). A smooth file with one
//! normal per position, or large smoothing groups, sorts (next to) nothing.
//!
//! Refused, with the line: numbers that do not parse or are not finite, a wrong number of
//! values in `v`/`vn`, faces with fewer than 3 corners, index 0 and indices out of range, an
//! `s` line without exactly one group number (or `off`).
//!
//! # Writing
//!
//! `#` comment lines first: the generator, the curvature convention where the colours show
//! curvature, the colour encoding and map ([`crate::convention`]). `v x y z` (`v x y z r g b`
//! with colours, sRGB-encoded 0–1), `vn` per vertex when there are normals, `f` with `a//a`
//! corners when there are normals; polygons as they are. Numbers are written in Rust's
//! shortest round-trip form, so reading back gives identical positions (colours within the
//! `f32` rounding of the sRGB round trip). Shapes, names, curvature, other properties and crease
//! edges are not written (OBJ has no place for the first four, and smoothing groups or split
//! normals cannot carry every set of creases: a crease that ends inside a smooth region).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use nalgebra::{Point3, Vector3};

use crate::error::{ReadError, WriteError};
use crate::format::{MeshFormat, WriteOptions};
use crate::raw::{Polygons, RawMesh};
use crate::util::{
    lines, parse_f64, parse_i64, parse_usize, show, skip_space_and_comments, tokens,
    validate_for_write,
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
        write_obj(mesh, out)
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
    // Smoothing group of every polygon (0: none), kept from the first `s` line on.
    let mut groups: Option<Vec<u32>> = None;
    let mut group: u32 = 0;
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
                if let Some(g) = &mut groups {
                    g.push(group);
                }
            }
            b"s" => {
                group = smoothing_group(toks).map_err(|m| err(ln, m))?;
                if groups.is_none() {
                    // The polygons so far are in no group.
                    groups = Some(vec![0; polygons.len()]);
                }
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
    let creases = crease_edges(
        positions.len(),
        &polygons,
        &corner_normals,
        &vnormals,
        groups.as_deref(),
        &mut notes,
    );
    if !creases.edges.is_empty() {
        notes.push(format!(
            "{} edges marked sharp by per-corner normals, {} by smoothing groups ({} in all)",
            creases.by_normals,
            creases.by_groups,
            creases.edges.len()
        ));
    }
    Ok(RawMesh {
        positions,
        normals,
        colors,
        polygons,
        crease_edges: creases.edges,
        notes,
        ..RawMesh::default()
    })
}

/// The group of an `s` line's arguments: `off` (any case) and `0` are none (0).
fn smoothing_group<'a>(mut args: impl Iterator<Item = &'a [u8]>) -> Result<u32, String> {
    let (Some(arg), None) = (args.next(), args.next()) else {
        return Err("`s` takes one argument: a smoothing group number or `off`".into());
    };
    if arg.eq_ignore_ascii_case(b"off") {
        return Ok(0);
    }
    let n = parse_usize(arg)
        .map_err(|_| format!("`s {}`: not a smoothing group number or `off`", show(arg)))?;
    u32::try_from(n).map_err(|_| format!("`s {n}`: a smoothing group number has 32 bits"))
}

/// Sharp polygon sides (module docs), with how many each source marked.
struct Creases {
    /// The union, sorted pairs `a < b`, sorted.
    edges: Vec<[usize; 2]>,
    /// Marked by per-corner normals.
    by_normals: usize,
    /// Marked by smoothing groups.
    by_groups: usize,
}

/// No normal index at a corner (as stored by the reader), and no per-vertex state yet.
const NONE: usize = usize::MAX;
/// A vertex whose corners have several normal indices, or whose polygons are not all in one
/// group: its sides must be compared. (Normal indices are below `usize::MAX - 1` because a
/// vector cannot hold that many normals; groups have 32 bits.)
const MIXED: usize = usize::MAX - 1;
/// [`NONE`] in a [`Side`].
const NONE32: u32 = u32::MAX;

/// A polygon side that must be compared with the other sides of its edge, filed under the
/// edge's lower vertex: 16 bytes, so that a million faces of per-face normals (three million
/// sides, every one compared) take 48 MB.
#[derive(Clone, Copy, Default)]
struct Side {
    /// The edge's higher vertex.
    hi: u32,
    /// The normal index at the lower vertex ([`NONE32`]: none).
    n_lo: u32,
    /// The normal index at the higher vertex.
    n_hi: u32,
    /// The group of the side's polygon (0: none, or groups unused).
    group: u32,
}

/// The polygon sides marked sharp by the corners' normal indices `corner_normals` (into
/// `vnormals`, [`NONE`] where a corner has none) and by the polygons' smoothing `groups` (when
/// the file has any `s` line; 0: none), on `nv` positions (module docs), with a note when the
/// mesh is too large for them.
///
/// The sides to compare are bucketed by their edge's lower vertex (a counting sort: one pass
/// counts, one files them, in polygon order), then each bucket is sorted by the higher vertex
/// (stably, so the first side of an edge is its first in the file); the edges come out sorted.
/// File order keeps the buckets that consecutive polygons fill close together, where a hash
/// map scatters them: on a million triangles with a normal each (every side compared), a hash
/// map made the whole read three times slower, the buckets add 0.1–0.2 s to its 0.6–0.8 s.
fn crease_edges(
    nv: usize,
    polygons: &Polygons,
    corner_normals: &[usize],
    vnormals: &[Vector3<f64>],
    groups: Option<&[u32]>,
    notes: &mut Vec<String>,
) -> Creases {
    let mut out = Creases {
        edges: Vec::new(),
        by_normals: 0,
        by_groups: 0,
    };
    let with_normals = !vnormals.is_empty() && corner_normals.iter().any(|&c| c != NONE);
    if !with_normals && groups.is_none() {
        return out;
    }
    // Vertices, normal indices and side counts are stored in 32 bits (NONE32 aside).
    let fits = |n: usize| n < NONE32 as usize;
    if !(fits(nv) && fits(vnormals.len()) && fits(polygons.corner_count())) {
        notes.push(format!(
            "sharp edges not read: more than {} vertices, normals or corners",
            NONE32 - 1
        ));
        return out;
    }
    // Per position: its one normal index so far, or MIXED (only with normals); its one group,
    // or MIXED (a polygon in no group, or two groups; only with groups).
    let mut normal_at = if with_normals {
        vec![NONE; nv]
    } else {
        Vec::new()
    };
    let mut group_at = if groups.is_some() {
        vec![NONE; nv]
    } else {
        Vec::new()
    };
    let merge = |state: &mut usize, value: usize| {
        if *state == NONE {
            *state = value;
        } else if *state != value {
            *state = MIXED;
        }
    };
    if with_normals {
        for (&v, &c) in polygons.all_corners().iter().zip(corner_normals) {
            if let (Some(s), true) = (normal_at.get_mut(v), c != NONE) {
                merge(s, c);
            }
        }
    }
    if let Some(gs) = groups {
        for (poly, &g) in polygons.iter().zip(gs) {
            for &v in poly {
                if let Some(s) = group_at.get_mut(v) {
                    merge(s, if g == 0 { MIXED } else { g as usize });
                }
            }
        }
    }
    if !normal_at.contains(&MIXED) && !group_at.contains(&MIXED) {
        // Every position has one normal index and one group (a smooth file): nothing is sharp.
        return out;
    }
    let mixed = |state: &[usize], v: usize| state.get(v) == Some(&MIXED);
    // Which of the two comparisons the sides of edge lo–hi need: by normals when an end has
    // several normal indices, by groups when neither end has all its polygons in one group.
    let checks = |lo: usize, hi: usize| {
        (
            with_normals && (mixed(&normal_at, lo) || mixed(&normal_at, hi)),
            groups.is_some() && mixed(&group_at, lo) && mixed(&group_at, hi),
        )
    };
    // Every side to compare, in polygon order: its edge's lower vertex and its record.
    let for_each_side = |f: &mut dyn FnMut(usize, Side)| {
        let mut base = 0;
        for (p, poly) in polygons.iter().enumerate() {
            let group = groups.and_then(|g| g.get(p)).copied().unwrap_or(0);
            let normals = corner_normals.get(base..base + poly.len()).unwrap_or(&[]);
            base += poly.len();
            let mut prev = (poly.last().copied(), normals.last().copied());
            for (&w, &nw) in poly.iter().zip(normals) {
                let (Some(u), Some(nu)) = prev else { break };
                prev = (Some(w), Some(nw));
                let (lo, hi) = (u.min(w), u.max(w));
                let (check_normals, check_groups) = checks(lo, hi);
                if u == w || !(check_normals || check_groups) {
                    continue;
                }
                let short = |n: usize| if n == NONE { NONE32 } else { n as u32 };
                let (n_lo, n_hi) = if u < w { (nu, nw) } else { (nw, nu) };
                f(
                    lo,
                    Side {
                        hi: hi as u32,
                        n_lo: short(n_lo),
                        n_hi: short(n_hi),
                        group,
                    },
                );
            }
        }
    };
    // Bucket starts by lower vertex (exclusive prefix sums of the counts).
    let mut start = vec![0u32; nv + 1];
    for_each_side(&mut |lo, _| {
        if let Some(c) = start.get_mut(lo + 1) {
            *c += 1;
        }
    });
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let total = start[nv] as usize;
    if total == 0 {
        return out;
    }
    let mut filed = vec![Side::default(); total];
    let mut next: Vec<u32> = start[..nv].to_vec();
    for_each_side(&mut |lo, side| {
        if let Some(slot) = next.get_mut(lo) {
            if let Some(f) = filed.get_mut(*slot as usize) {
                *f = side;
            }
            *slot += 1;
        }
    });
    drop(next);
    // The angle θ of x and y exceeds the agreement angle A exactly when cos θ < cos A, as the
    // cosine decreases on [0, π]: x · y < cos A |x| |y| (a zero normal agrees with any, as in
    // `Vector3::angle`, which gives it 0), one comparison instead of an arccosine.
    let cos_agreement = NORMAL_AGREEMENT.cos();
    let disagree = |a: u32, b: u32| {
        a != b
            && match (vnormals.get(a as usize), vnormals.get(b as usize)) {
                (Some(x), Some(y)) => x.dot(y) < cos_agreement * x.norm() * y.norm(),
                _ => false,
            }
    };
    for lo in 0..nv {
        let bucket = &mut filed[start[lo] as usize..start[lo + 1] as usize];
        if bucket.len() < 2 {
            continue;
        }
        bucket.sort_by_key(|s| s.hi);
        for run in bucket.chunk_by(|a, b| a.hi == b.hi) {
            let Some((first, rest)) = run.split_first() else {
                continue;
            };
            let hi = first.hi as usize;
            let (check_normals, check_groups) = checks(lo, hi);
            // Each side is compared with the first side that has a normal at that end.
            let (mut n_lo, mut n_hi) = (first.n_lo, first.n_hi);
            let (mut by_normals, mut by_groups) = (false, false);
            for s in rest {
                if check_normals {
                    for (mine, theirs) in [(&mut n_lo, s.n_lo), (&mut n_hi, s.n_hi)] {
                        if *mine == NONE32 {
                            *mine = theirs;
                        } else if theirs != NONE32 && disagree(*mine, theirs) {
                            by_normals = true;
                        }
                    }
                }
                if check_groups && (s.group == 0 || first.group == 0 || s.group != first.group) {
                    by_groups = true;
                }
            }
            out.by_normals += usize::from(by_normals);
            out.by_groups += usize::from(by_groups);
            if by_normals || by_groups {
                out.edges.push([lo, hi]);
            }
        }
    }
    out
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

fn write_obj(mesh: &RawMesh, out: &mut dyn std::io::Write) -> Result<(), WriteError> {
    validate_for_write(mesh, NAME)?;
    let mut s = crate::util::Sink::new(out);
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
    s.finish(NAME)
}

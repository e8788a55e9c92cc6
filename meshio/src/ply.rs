//! PLY (Stanford polygon format): ascii, binary little endian and binary big endian.
//!
//! # Reading
//!
//! The header may hold `comment` and `obj_info` lines (skipped) and any elements. Scalar types:
//! `char uchar short ushort int uint float double` and `int8 uint8 int16 uint16 int32 uint32
//! float32 float64`.
//!
//! * Element `vertex` (required): `x y z` (required) → positions; `nx ny nz` (all three) →
//!   normals; `red green blue` (all three) → colours, read as sRGB-encoded (what every PLY
//!   viewer assumes) and decoded to linear ([`crate::srgb`]): integer types divided by the
//!   type's maximum (`uchar`: 255), float types taken as 0–1; `gaussian_curvature` and
//!   `mean_curvature` (both) → [`RawMesh::curvature`] (the exported convention, as written),
//!   with `k1`, `k2` and a `quality` equal to `K` dropped as derived from them; every other
//!   scalar property (also `alpha`, texture coordinates, `quality`, …) →
//!   [`RawMesh::properties`] as `f64`. List properties of vertices are skipped (with a note).
//! * Element `face`: the list property `vertex_indices` (or `vertex_index`), any integer count
//!   and index types → polygons as they are; other face properties are skipped.
//! * Element `edge` with its two vertices (the scalar properties `vertex1` and `vertex2`, the
//!   convention of the PLY documentation and libigl, or a list property `ends` or
//!   `vertex_indices` of two) and a scalar property `crease` (or `sharp`): the edges whose
//!   `crease` is not zero → [`RawMesh::crease_edges`] (each pair smaller index first, sorted,
//!   without repeats), as listed: they need not be sides of a face. A note counts them.
//!   Without such properties the element is skipped like any other.
//! * Other elements (`material`, …) are parsed and skipped (with a note), lists included.
//!
//! Refused, naming the element and record (`element vertex 17, property y: …`): a truncated
//! body, a number that does not parse or is not finite, a list count that is negative, faces
//! with fewer than 3 corners, edges without two distinct ends, and indices out of range;
//! header errors name the header line.
//! Binary bodies are read without allocating per record, and nothing is reserved from a header
//! count before checking it against the bytes left.
//!
//! # Writing
//!
//! One layout for every file the workbench writes, read by libigl (Python `igl` 2.6.3),
//! trimesh, MeshLab (pymeshlab) and Python's meshio (`scripts/readback/readback.py` checks
//! each). Binary little endian by default ([`WriteOptions::ascii`] for text). The header's
//! comments name the generator, the curvature convention where there is curvature or colours
//! by it, the colour encoding and the colour map ([`crate::convention`]). Vertex properties:
//!
//! * `x y z` as `float` (`double` with [`WriteOptions::double_precision`]);
//! * `nx ny nz` as `float` when there are normals;
//! * `red green blue` as `float` 0–1, **sRGB-encoded**, when there are colours;
//! * with [`RawMesh::curvature`]: `quality` (MeshLab's per-vertex scalar, which it colours and
//!   filters by) holding the Gaussian curvature `K`, then `gaussian_curvature`,
//!   `mean_curvature`, `k1`, `k2` (`k1 ≥ k2`), all in the exported convention (`H > 0` on a
//!   sphere with outward normals), each checked to fit a `float`;
//! * [`RawMesh::properties`] as `float`.
//!
//! Every property after `x y z` is a `float`, colours included: libigl's reader requests every
//! property it does not know (`red`, `quality`, …) as one matrix of one type and aborts the
//! process (a "double free") when their types differ, so byte colours beside any float
//! property kill it; Python's meshio 5.3 also reads binary `uchar` as signed bytes (180 → −76).
//! MeshLab reads colours from `uchar` only, so it shows these files by `quality` (Colorize by
//! vertex quality), which it reads. Faces as `list uchar int vertex_indices` (`list int int`
//! when a polygon has more than 255 corners). With [`RawMesh::crease_edges`] (and only then:
//! a mesh without creases gives the same bytes as before there were any), an element `edge`
//! follows the faces, one record a crease: `int vertex1`, `int vertex2`, `uchar crease` (1).
//! libigl 2.6.3 (`read_triangle_mesh`; its `readPLY` takes the pairs as its edge list `E` and
//! `crease` as edge data) and MeshLab (pymeshlab 2025.7: 12 edges on a cube) read such a file;
//! trimesh 5.2.0 reads the ascii one but refuses the binary one (it turns every column of a
//! binary `edge` element into path indices: "edges are not (n, 2)"), and Python's meshio 5.3.5
//! refuses any element but `vertex` and `face`. No file the workbench writes today has creases
//! (its tessellations and repaired meshes carry none), so those are unchanged for every reader.
//! Shapes and names are not written (PLY has no standard place for them).

use std::fmt::Write as _;

use nalgebra::{Point3, Vector3};

use crate::error::{ReadError, WriteError};
use crate::format::{MeshFormat, WriteOptions};
use crate::raw::{Polygons, RawMesh};
use crate::util::{show, validate_for_write};

const NAME: &str = "ply";

/// The PLY format (`.ply`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Ply;

impl MeshFormat for Ply {
    fn name(&self) -> &'static str {
        NAME
    }

    fn extensions(&self) -> &'static [&'static str] {
        &["ply"]
    }

    fn sniff(&self, bytes: &[u8]) -> bool {
        bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n")
    }

    fn writes_properties(&self) -> bool {
        true
    }

    fn writes_curvature(&self) -> bool {
        true
    }

    fn read(&self, bytes: &[u8]) -> Result<RawMesh, ReadError> {
        read_ply(bytes)
    }

    fn size_hint(&self, mesh: &RawMesh, options: &WriteOptions) -> usize {
        // Binary: x y z (4 or 8 bytes each), then a count byte and 4-byte indices a face; text
        // takes about twice as much.
        let coords = if options.double_precision { 24 } else { 12 };
        let binary = 1024
            + coords * mesh.positions.len()
            + mesh.polygons.len()
            + 4 * mesh.polygons.corner_count()
            + 9 * mesh.crease_edges.len();
        if options.ascii {
            2 * binary
        } else {
            binary
        }
    }

    fn write_to(
        &self,
        mesh: &RawMesh,
        options: &WriteOptions,
        out: &mut dyn std::io::Write,
    ) -> Result<(), WriteError> {
        write_ply(mesh, options, out)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_float(self) -> bool {
        matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// Range of an integer type.
    fn range(self) -> (f64, f64) {
        match self {
            Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
            Scalar::U8 => (0.0, u8::MAX.into()),
            Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
            Scalar::U16 => (0.0, u16::MAX.into()),
            Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
            Scalar::U32 => (0.0, u32::MAX.into()),
            Scalar::F32 | Scalar::F64 => (f64::MIN, f64::MAX),
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Clone, Debug)]
struct Property {
    name: String,
    kind: Kind,
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: usize,
    props: Vec<Property>,
}

impl Element {
    /// Fewest bytes one record can take in `enc`.
    fn min_record_bytes(&self, enc: Encoding) -> usize {
        let binary: usize = self
            .props
            .iter()
            .map(|p| match p.kind {
                Kind::Scalar(s) => s.size(),
                Kind::List { count, .. } => count.size(),
            })
            .sum();
        match enc {
            Encoding::Ascii => 2 * self.props.len(),
            _ => binary,
        }
        .max(1)
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

fn header_err(line: usize, message: impl std::fmt::Display) -> ReadError {
    ReadError::header(NAME, format!("line {line}: {message}"))
}

/// Parses the header; returns the encoding, the elements and the offset of the body.
fn parse_header(bytes: &[u8]) -> Result<(Encoding, Vec<Element>, usize), ReadError> {
    let mut pos = 0;
    let mut ln = 0;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        ln += 1;
        let rest = bytes.get(pos..).unwrap_or(&[]);
        let Some(end) = rest.iter().position(|&b| b == b'\n') else {
            return Err(header_err(ln, "the header has no `end_header` line"));
        };
        let raw_line = rest.get(..end).unwrap_or(&[]);
        pos += end + 1;
        let line = raw_line.strip_suffix(b"\r").unwrap_or(raw_line);
        let mut toks = line
            .split(|b| *b == b' ' || *b == b'\t')
            .filter(|t| !t.is_empty());
        let first = toks.next().unwrap_or(&[]);
        if ln == 1 {
            if first != b"ply" {
                return Err(header_err(1, "a PLY file starts with `ply`"));
            }
            continue;
        }
        match first {
            b"end_header" => break,
            b"comment" | b"obj_info" | b"" => {}
            b"format" => {
                let enc = match toks.next() {
                    Some(b"ascii") => Encoding::Ascii,
                    Some(b"binary_little_endian") => Encoding::Little,
                    Some(b"binary_big_endian") => Encoding::Big,
                    other => {
                        return Err(header_err(
                            ln,
                            format!("unknown format `{}`", show(other.unwrap_or(&[]))),
                        ))
                    }
                };
                match toks.next() {
                    Some(b"1.0") | Some(b"1") => {}
                    other => {
                        return Err(header_err(
                            ln,
                            format!("unsupported version `{}`", show(other.unwrap_or(&[]))),
                        ))
                    }
                }
                encoding = Some(enc);
            }
            b"element" => {
                let (Some(name), Some(count)) = (toks.next(), toks.next()) else {
                    return Err(header_err(ln, "expected `element NAME COUNT`"));
                };
                let count = crate::util::parse_usize(count).map_err(|m| header_err(ln, m))?;
                elements.push(Element {
                    name: String::from_utf8_lossy(name).into_owned(),
                    count,
                    props: Vec::new(),
                });
            }
            b"property" => {
                let Some(el) = elements.last_mut() else {
                    return Err(header_err(ln, "`property` before any `element`"));
                };
                let ty = toks.next().unwrap_or(&[]);
                let kind =
                    if ty == b"list" {
                        let c = toks.next().unwrap_or(&[]);
                        let i = toks.next().unwrap_or(&[]);
                        let (Some(count), Some(item)) = (Scalar::parse(c), Scalar::parse(i)) else {
                            return Err(header_err(
                                ln,
                                format!("unknown list types `{}` `{}`", show(c), show(i)),
                            ));
                        };
                        if count.is_float() {
                            return Err(header_err(ln, "a list count must have an integer type"));
                        }
                        Kind::List { count, item }
                    } else {
                        Kind::Scalar(Scalar::parse(ty).ok_or_else(|| {
                            header_err(ln, format!("unknown type `{}`", show(ty)))
                        })?)
                    };
                let Some(name) = toks.next() else {
                    return Err(header_err(ln, "property without a name"));
                };
                el.props.push(Property {
                    name: String::from_utf8_lossy(name).into_owned(),
                    kind,
                });
            }
            other => {
                return Err(header_err(
                    ln,
                    format!("unknown header keyword `{}`", show(other)),
                ))
            }
        }
    }
    let encoding = encoding.ok_or_else(|| ReadError::header(NAME, "no `format` line"))?;
    Ok((encoding, elements, pos))
}

/// The body, read value by value.
struct Body<'a> {
    data: &'a [u8],
    pos: usize,
    enc: Encoding,
}

const EOF: &str = "unexpected end of file";

impl Body<'_> {
    fn left(&self) -> usize {
        self.data.len().saturating_sub(self.pos)
    }

    #[inline]
    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let b = self
            .data
            .get(self.pos..self.pos.saturating_add(N))
            .and_then(|s| <[u8; N]>::try_from(s).ok())
            .ok_or_else(|| EOF.to_string())?;
        self.pos += N;
        Ok(b)
    }

    /// One value of type `s` (integers exactly, as `f64`). Floats may be non-finite here.
    #[inline]
    fn value(&mut self, s: Scalar) -> Result<f64, String> {
        macro_rules! bin {
            ($t:ty, $n:literal) => {{
                let b = self.take::<$n>()?;
                if self.enc == Encoding::Little {
                    <$t>::from_le_bytes(b) as f64
                } else {
                    <$t>::from_be_bytes(b) as f64
                }
            }};
        }
        Ok(match (self.enc, s) {
            (Encoding::Ascii, _) => return self.ascii_value(s),
            (_, Scalar::I8) => bin!(i8, 1),
            (_, Scalar::U8) => bin!(u8, 1),
            (_, Scalar::I16) => bin!(i16, 2),
            (_, Scalar::U16) => bin!(u16, 2),
            (_, Scalar::I32) => bin!(i32, 4),
            (_, Scalar::U32) => bin!(u32, 4),
            (_, Scalar::F32) => bin!(f32, 4),
            (_, Scalar::F64) => bin!(f64, 8),
        })
    }

    fn ascii_value(&mut self, s: Scalar) -> Result<f64, String> {
        let rest = self.data.get(self.pos..).unwrap_or(&[]);
        let start = rest
            .iter()
            .position(|b| !b.is_ascii_whitespace())
            .ok_or_else(|| EOF.to_string())?;
        let tok = rest.get(start..).unwrap_or(&[]);
        let len = tok
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(tok.len());
        let tok = tok.get(..len).unwrap_or(&[]);
        self.pos += start + len;
        let text = std::str::from_utf8(tok).ok();
        if s.is_float() {
            text.and_then(|t| t.parse::<f64>().ok())
                .ok_or_else(|| format!("`{}` is not a number", show(tok)))
        } else {
            let v = text
                .and_then(|t| t.parse::<i64>().ok())
                .ok_or_else(|| format!("`{}` is not an integer", show(tok)))?;
            let (lo, hi) = s.range();
            let v = v as f64;
            if v < lo || v > hi {
                return Err(format!("{v} is out of range for its type"));
            }
            Ok(v)
        }
    }

    /// Skips a property.
    fn skip(&mut self, kind: Kind) -> Result<(), String> {
        match kind {
            Kind::Scalar(s) => self.skip_values(s, 1),
            Kind::List { count, item } => {
                let n = self.count(count)?;
                self.skip_values(item, n)
            }
        }
    }

    fn skip_values(&mut self, s: Scalar, n: usize) -> Result<(), String> {
        if self.enc == Encoding::Ascii {
            for _ in 0..n {
                self.ascii_value(s)?;
            }
            Ok(())
        } else {
            let bytes = n.checked_mul(s.size()).ok_or_else(|| EOF.to_string())?;
            if bytes > self.left() {
                return Err(EOF.to_string());
            }
            self.pos += bytes;
            Ok(())
        }
    }

    fn count(&mut self, s: Scalar) -> Result<usize, String> {
        let c = self.value(s)?;
        if c < 0.0 {
            return Err(format!("negative list count {c}"));
        }
        Ok(c as usize)
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Slot {
    Coord(usize),
    Normal(usize),
    Color(usize),
    Prop(usize),
    Skip,
}

fn read_ply(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    let (enc, elements, body_start) = parse_header(bytes)?;
    let Some(vertex_el) = elements.iter().find(|e| e.name == "vertex") else {
        return Err(ReadError::header(NAME, "no `vertex` element"));
    };
    let nv = vertex_el.count;
    let mut body = Body {
        data: bytes,
        pos: body_start,
        enc,
    };
    let mut mesh = RawMesh::default();
    let mut seen_vertex = false;
    let mut seen_face = false;
    let mut seen_edge = false;
    let mut skipped: Vec<String> = Vec::new();
    for el in &elements {
        let cap = el.count.min(body.left() / el.min_record_bytes(enc));
        let at = |i: usize, prop: Option<&str>, m: String| match prop {
            Some(p) => ReadError::property(NAME, &el.name, i, p, m),
            None => ReadError::element(NAME, &el.name, i, m),
        };
        if el.name == "vertex" && !seen_vertex {
            seen_vertex = true;
            read_vertices(&mut body, el, cap, &mut mesh, &at)?;
        } else if el.name == "face" && !seen_face {
            seen_face = true;
            read_faces(&mut body, el, cap, nv, &mut mesh, &at)?;
        } else if let (false, Some(layout)) = (seen_edge, EdgeLayout::of(el)?) {
            seen_edge = true;
            read_edges(&mut body, el, &layout, cap, nv, &mut mesh, &at)?;
        } else {
            let all_scalar_size: Option<usize> = el
                .props
                .iter()
                .map(|p| match p.kind {
                    Kind::Scalar(s) => Some(s.size()),
                    Kind::List { .. } => None,
                })
                .sum();
            match (enc, all_scalar_size) {
                (Encoding::Little | Encoding::Big, Some(size)) => {
                    let need = el.count.checked_mul(size);
                    match need {
                        Some(need) if need <= body.left() => body.pos += need,
                        _ => {
                            let i = body.left().checked_div(size).unwrap_or(0);
                            return Err(at(i, None, EOF.to_string()));
                        }
                    }
                }
                // An element without properties takes no bytes, whatever its count.
                _ if el.props.is_empty() => {}
                _ => {
                    for i in 0..el.count {
                        for p in &el.props {
                            body.skip(p.kind).map_err(|m| at(i, Some(&p.name), m))?;
                        }
                    }
                }
            }
            skipped.push(format!("{} ({})", el.name, el.count));
        }
    }
    if !skipped.is_empty() {
        mesh.notes
            .push(format!("skipped elements: {}", skipped.join(", ")));
    }
    Ok(mesh)
}

fn read_vertices(
    body: &mut Body<'_>,
    el: &Element,
    cap: usize,
    mesh: &mut RawMesh,
    at: &dyn Fn(usize, Option<&str>, String) -> ReadError,
) -> Result<(), ReadError> {
    let find = |n: &str| {
        el.props
            .iter()
            .position(|p| p.name == n && matches!(p.kind, Kind::Scalar(_)))
    };
    let (Some(_), Some(_), Some(_)) = (find("x"), find("y"), find("z")) else {
        return Err(ReadError::header(
            NAME,
            "element vertex needs scalar properties x, y and z",
        ));
    };
    let has_normals = find("nx").is_some() && find("ny").is_some() && find("nz").is_some();
    let has_colors = find("red").is_some() && find("green").is_some() && find("blue").is_some();
    let mut prop_names: Vec<String> = Vec::new();
    let mut skipped_lists = Vec::new();
    let slots: Vec<(Slot, Kind, f64)> = el
        .props
        .iter()
        .map(|p| {
            let Kind::Scalar(s) = p.kind else {
                skipped_lists.push(p.name.clone());
                return (Slot::Skip, p.kind, 1.0);
            };
            let scale = if s.is_float() { 1.0 } else { s.range().1 };
            let slot = match p.name.as_str() {
                "x" => Slot::Coord(0),
                "y" => Slot::Coord(1),
                "z" => Slot::Coord(2),
                "nx" if has_normals => Slot::Normal(0),
                "ny" if has_normals => Slot::Normal(1),
                "nz" if has_normals => Slot::Normal(2),
                "red" if has_colors => Slot::Color(0),
                "green" if has_colors => Slot::Color(1),
                "blue" if has_colors => Slot::Color(2),
                _ => {
                    prop_names.push(p.name.clone());
                    Slot::Prop(prop_names.len() - 1)
                }
            };
            (slot, p.kind, scale)
        })
        .collect();
    let mut positions = Vec::with_capacity(cap);
    let mut normals = Vec::with_capacity(if has_normals { cap } else { 0 });
    let mut colors = Vec::with_capacity(if has_colors { cap } else { 0 });
    let mut props: Vec<Vec<f64>> = prop_names.iter().map(|_| Vec::with_capacity(cap)).collect();
    for i in 0..el.count {
        let mut c = [0.0f64; 3];
        let mut n = [0.0f64; 3];
        let mut col = [0.0f32; 3];
        for ((slot, kind, scale), p) in slots.iter().zip(&el.props) {
            let Kind::Scalar(s) = *kind else {
                body.skip(*kind).map_err(|m| at(i, Some(&p.name), m))?;
                continue;
            };
            let v = body.value(s).map_err(|m| at(i, Some(&p.name), m))?;
            if !v.is_finite() {
                return Err(at(i, Some(&p.name), format!("{v} is not finite")));
            }
            match *slot {
                Slot::Coord(k) => {
                    if let Some(x) = c.get_mut(k) {
                        *x = v;
                    }
                }
                Slot::Normal(k) => {
                    if let Some(x) = n.get_mut(k) {
                        *x = v;
                    }
                }
                Slot::Color(k) => {
                    if let Some(x) = col.get_mut(k) {
                        *x = crate::srgb::decode((v / scale) as f32);
                    }
                }
                Slot::Prop(k) => {
                    if let Some(x) = props.get_mut(k) {
                        x.push(v);
                    }
                }
                Slot::Skip => {}
            }
        }
        positions.push(Point3::from(c));
        if has_normals {
            normals.push(Vector3::from(n));
        }
        if has_colors {
            colors.push(col);
        }
    }
    mesh.positions = positions;
    mesh.normals = has_normals.then_some(normals);
    mesh.colors = has_colors.then_some(colors);
    mesh.properties = prop_names.into_iter().zip(props).collect();
    take_curvature(mesh);
    if !skipped_lists.is_empty() {
        mesh.notes.push(format!(
            "skipped vertex list properties: {}",
            skipped_lists.join(", ")
        ));
    }
    Ok(())
}

/// Moves `gaussian_curvature` and `mean_curvature` (both present) from the properties into
/// [`RawMesh::curvature`], with what the writer derives from them (`k1` and `k2`, and `quality`
/// when it holds `K` exactly, as the writer writes it).
fn take_curvature(mesh: &mut RawMesh) {
    let props = &mut mesh.properties;
    if !(props.contains_key("gaussian_curvature") && props.contains_key("mean_curvature")) {
        return;
    }
    let gaussian = props.remove("gaussian_curvature").unwrap_or_default();
    let mean = props.remove("mean_curvature").unwrap_or_default();
    if props.contains_key("k1") && props.contains_key("k2") {
        props.remove("k1");
        props.remove("k2");
    }
    if props.get("quality") == Some(&gaussian) {
        props.remove("quality");
    }
    let directions = if DIRECTION_NAMES.iter().all(|n| props.contains_key(*n)) {
        let cols: Vec<Vec<f64>> = DIRECTION_NAMES
            .iter()
            .map(|n| props.remove(*n).unwrap_or_default())
            .collect();
        Some(
            (0..gaussian.len())
                .map(|i| {
                    let at = |k: usize| cols[k].get(i).copied().unwrap_or(f64::NAN);
                    [
                        nalgebra::Vector3::new(at(0), at(1), at(2)),
                        nalgebra::Vector3::new(at(3), at(4), at(5)),
                    ]
                })
                .collect(),
        )
    } else {
        None
    };
    mesh.curvature = Some(crate::convention::Curvature {
        gaussian,
        mean,
        directions,
    });
}

fn read_faces(
    body: &mut Body<'_>,
    el: &Element,
    cap: usize,
    nv: usize,
    mesh: &mut RawMesh,
    at: &dyn Fn(usize, Option<&str>, String) -> ReadError,
) -> Result<(), ReadError> {
    let Some(list) = el.props.iter().position(|p| {
        (p.name == "vertex_indices" || p.name == "vertex_index")
            && matches!(p.kind, Kind::List { .. })
    }) else {
        return Err(ReadError::header(
            NAME,
            "element face needs a list property vertex_indices (or vertex_index)",
        ));
    };
    let mut polys = Polygons::with_capacity(cap, cap.saturating_mul(3));
    let mut corners: Vec<usize> = Vec::new();
    let mut other = 0;
    for i in 0..el.count {
        for (k, p) in el.props.iter().enumerate() {
            let ctx = |m: String| at(i, Some(&p.name), m);
            match p.kind {
                Kind::List { count, item } if k == list => {
                    if item.is_float() {
                        return Err(ReadError::header(
                            NAME,
                            format!("face property {} has a float index type", p.name),
                        ));
                    }
                    let n = body.count(count).map_err(ctx)?;
                    if n < 3 {
                        return Err(ctx(format!("face has {n} corners, at least 3 needed")));
                    }
                    if body.enc != Encoding::Ascii && n.saturating_mul(item.size()) > body.left() {
                        return Err(ctx(EOF.to_string()));
                    }
                    corners.clear();
                    for _ in 0..n {
                        let v = body.value(item).map_err(ctx)?;
                        if v < 0.0 || v >= nv as f64 {
                            return Err(ctx(format!(
                                "vertex index {v} is out of range ({nv} vertices)"
                            )));
                        }
                        corners.push(v as usize);
                    }
                    polys.push(&corners);
                }
                kind => {
                    if i == 0 {
                        other += 1;
                    }
                    body.skip(kind).map_err(ctx)?;
                }
            }
        }
    }
    mesh.polygons = polys;
    if other > 0 {
        mesh.notes
            .push(format!("skipped {other} other face properties"));
    }
    Ok(())
}

/// Where an `edge` element keeps what [`read_edges`] reads (property positions).
struct EdgeLayout {
    /// The two ends: `vertex1` and `vertex2`, or one list of two.
    ends: Ends,
    /// The `crease` (or `sharp`) property.
    crease: usize,
}

/// The ends of an edge record.
enum Ends {
    /// Scalar properties `vertex1`, `vertex2`.
    Pair(usize, usize),
    /// A list property (`ends`, `vertex_indices`).
    List(usize),
}

impl EdgeLayout {
    /// The layout of an element `edge` with ends and a crease property; `None` for another
    /// element or an edge element without them. Float index types are refused (a header error).
    fn of(el: &Element) -> Result<Option<EdgeLayout>, ReadError> {
        if el.name != "edge" {
            return Ok(None);
        }
        let scalar = |names: &[&str]| {
            el.props
                .iter()
                .position(|p| names.contains(&p.name.as_str()) && matches!(p.kind, Kind::Scalar(_)))
        };
        let list = el.props.iter().position(|p| {
            (p.name == "ends" || p.name == "vertex_indices") && matches!(p.kind, Kind::List { .. })
        });
        let ends = match (scalar(&["vertex1"]), scalar(&["vertex2"]), list) {
            (Some(a), Some(b), _) => Ends::Pair(a, b),
            (_, _, Some(l)) => Ends::List(l),
            _ => return Ok(None),
        };
        let Some(crease) = scalar(&["crease", "sharp"]) else {
            return Ok(None);
        };
        let index_props = match ends {
            Ends::Pair(a, b) => vec![a, b],
            Ends::List(l) => vec![l],
        };
        for k in index_props {
            let float = match el.props.get(k).map(|p| p.kind) {
                Some(Kind::Scalar(s)) | Some(Kind::List { item: s, .. }) => s.is_float(),
                None => false,
            };
            if float {
                let name = el.props.get(k).map_or("", |p| p.name.as_str());
                return Err(ReadError::header(
                    NAME,
                    format!("edge property {name} has a float index type"),
                ));
            }
        }
        Ok(Some(EdgeLayout { ends, crease }))
    }
}

/// Reads an `edge` element laid out as `layout`: the pairs whose crease value is not zero into
/// [`RawMesh::crease_edges`] (sorted pairs, sorted, without repeats), with a note.
fn read_edges(
    body: &mut Body<'_>,
    el: &Element,
    layout: &EdgeLayout,
    cap: usize,
    nv: usize,
    mesh: &mut RawMesh,
    at: &dyn Fn(usize, Option<&str>, String) -> ReadError,
) -> Result<(), ReadError> {
    let mut creases: Vec<[usize; 2]> = Vec::with_capacity(cap);
    for i in 0..el.count {
        let mut ends = [usize::MAX; 2];
        let mut sharp = false;
        for (k, p) in el.props.iter().enumerate() {
            let ctx = |m: String| at(i, Some(&p.name), m);
            let index = |v: f64| {
                if v < 0.0 || v >= nv as f64 {
                    Err(ctx(format!(
                        "vertex index {v} is out of range ({nv} vertices)"
                    )))
                } else {
                    Ok(v as usize)
                }
            };
            match (&layout.ends, p.kind) {
                (Ends::Pair(a, b), Kind::Scalar(s)) if k == *a || k == *b => {
                    let v = body.value(s).map_err(ctx)?;
                    ends[usize::from(k == *b)] = index(v)?;
                }
                (Ends::List(l), Kind::List { count, item }) if k == *l => {
                    let n = body.count(count).map_err(ctx)?;
                    if n != 2 {
                        return Err(ctx(format!("edge has {n} ends, 2 needed")));
                    }
                    for end in &mut ends {
                        *end = index(body.value(item).map_err(ctx)?)?;
                    }
                }
                (_, Kind::Scalar(s)) if k == layout.crease => {
                    let v = body.value(s).map_err(ctx)?;
                    if !v.is_finite() {
                        return Err(ctx(format!("{v} is not finite")));
                    }
                    sharp = v != 0.0;
                }
                (_, kind) => body.skip(kind).map_err(ctx)?,
            }
        }
        let [a, b] = ends;
        if a == b {
            return Err(at(i, None, format!("edge joins vertex {a} to itself")));
        }
        if sharp {
            creases.push([a.min(b), a.max(b)]);
        }
    }
    creases.sort_unstable();
    creases.dedup();
    let crease_name = el.props.get(layout.crease).map_or("", |p| p.name.as_str());
    mesh.notes.push(format!(
        "{} of {} edges marked sharp (element edge, property {crease_name})",
        creases.len(),
        el.count
    ));
    mesh.crease_edges = creases;
    Ok(())
}

/// Vertex property names the writer sets itself.
const RESERVED: &[&str] = &["x", "y", "z", "nx", "ny", "nz", "red", "green", "blue"];

/// The names the curvature is written under (with `quality`, MeshLab's scalar, holding `K`).
const CURVATURE_NAMES: &[&str] = &[
    "quality",
    "gaussian_curvature",
    "mean_curvature",
    "k1",
    "k2",
    "pd1x",
    "pd1y",
    "pd1z",
    "pd2x",
    "pd2y",
    "pd2z",
];

/// The principal directions' properties, `d1` then `d2` (libigl's `PD1`, `PD2`).
const DIRECTION_NAMES: [&str; 6] = ["pd1x", "pd1y", "pd1z", "pd2x", "pd2y", "pd2z"];

/// How the colours are stored, for the header comment.
const COLOUR_NOTE: &str = "float 0-1 (float, not uchar: libigl 2.6's reader aborts on byte colours beside float properties)";

/// Where the values of one vertex property come from: read from the mesh vertex by vertex as
/// the records are written, never gathered into a column of their own.
enum Column<'a> {
    /// Component `k` of the normals.
    Normal(&'a [Vector3<f64>], usize),
    /// Component `k` of the colours, sRGB-encoded ([`crate::srgb::encode`]).
    Colour(&'a [[f32; 3]], usize),
    /// One value per vertex, as stored (curvature, properties).
    Values(&'a [f64]),
    /// Principal curvature `j` (0: `k1`, 1: `k2`) of the curvature.
    Principal(&'a crate::convention::Curvature, usize),
    /// Component `k % 3` of principal direction `k / 3`.
    Direction(&'a [[Vector3<f64>; 2]], usize),
}

impl Column<'_> {
    /// The value of vertex `i` (0 out of range; the lengths are checked before writing).
    fn value(&self, i: usize) -> f64 {
        match *self {
            Column::Normal(ns, k) => ns.get(i).map_or(0.0, |n| n[k]),
            Column::Colour(cs, k) => cs
                .get(i)
                .map_or(0.0, |c| f64::from(crate::srgb::encode(c[k]))),
            Column::Values(vs) => vs.get(i).copied().unwrap_or(0.0),
            Column::Principal(c, j) => crate::util::principal(c, i, j),
            Column::Direction(ds, k) => ds.get(i).map_or(0.0, |d| d[k / 3][k % 3]),
        }
    }
}

/// Every vertex property after `x y z` in file order, each as `(name, where its values come
/// from)`, with every check of their names and values done; all are `float`, so that libigl's
/// reader, which reads every property it does not know into one matrix of one type, survives
/// (module docs).
fn float_columns(mesh: &RawMesh) -> Result<Vec<(&str, Column<'_>)>, WriteError> {
    let mut cols: Vec<(&str, Column<'_>)> = Vec::new();
    if let Some(ns) = &mesh.normals {
        for (k, name) in ["nx", "ny", "nz"].into_iter().enumerate() {
            cols.push((name, Column::Normal(ns, k)));
        }
    }
    if let Some(cs) = &mesh.colors {
        for (k, name) in ["red", "green", "blue"].into_iter().enumerate() {
            cols.push((name, Column::Colour(cs, k)));
        }
    }
    if let Some(c) = &mesh.curvature {
        crate::util::check_curvature(NAME, c)?;
        cols.push(("quality", Column::Values(&c.gaussian)));
        cols.push(("gaussian_curvature", Column::Values(&c.gaussian)));
        cols.push(("mean_curvature", Column::Values(&c.mean)));
        cols.push(("k1", Column::Principal(c, 0)));
        cols.push(("k2", Column::Principal(c, 1)));
        if let Some(ds) = &c.directions {
            for (k, name) in DIRECTION_NAMES.into_iter().enumerate() {
                let column = Column::Direction(ds, k);
                let values = (0..ds.len()).map(|i| column.value(i));
                crate::util::check_f32_values(NAME, "principal direction", values)?;
                cols.push((name, column));
            }
        }
    }
    for (k, vs) in &mesh.properties {
        if k.is_empty()
            || k.bytes()
                .any(|b| b.is_ascii_whitespace() || !b.is_ascii_graphic())
        {
            return Err(WriteError::invalid(
                NAME,
                format!("property name `{k}` is not a PLY name (printable ASCII without spaces)"),
            ));
        }
        if RESERVED.contains(&k.as_str()) {
            return Err(WriteError::invalid(
                NAME,
                format!("property `{k}` would clash with a standard vertex property"),
            ));
        }
        if mesh.curvature.is_some() && CURVATURE_NAMES.contains(&k.as_str()) {
            return Err(WriteError::invalid(
                NAME,
                format!("property `{k}` would clash with the curvature written under that name"),
            ));
        }
        crate::util::check_f32_values(NAME, &format!("property `{k}`"), vs.iter().copied())?;
        cols.push((k.as_str(), Column::Values(vs)));
    }
    Ok(cols)
}

fn write_ply(
    mesh: &RawMesh,
    options: &WriteOptions,
    out: &mut dyn std::io::Write,
) -> Result<(), WriteError> {
    validate_for_write(mesh, NAME)?;
    let cols = float_columns(mesh)?;
    if !options.double_precision
        && mesh
            .positions
            .iter()
            .any(|p| p.coords.amax() > f32::MAX as f64)
    {
        return Err(WriteError::invalid(
            NAME,
            "a position does not fit a float (write with double precision)",
        ));
    }
    if let Some(ns) = &mesh.normals {
        if let Some(i) = ns.iter().position(|n| n.amax() > f32::MAX as f64) {
            return Err(WriteError::invalid(
                NAME,
                format!("the normal of vertex {i} does not fit a float"),
            ));
        }
    }
    if mesh.positions.len() > i32::MAX as usize {
        return Err(WriteError::invalid(
            NAME,
            "more vertices than int indices hold",
        ));
    }
    for (k, &[a, b]) in mesh.crease_edges.iter().enumerate() {
        let n = mesh.positions.len();
        if a == b || a >= n || b >= n {
            return Err(WriteError::invalid(
                NAME,
                format!("crease edge {k} ({a}, {b}) is not two distinct vertices of {n}"),
            ));
        }
    }
    let big_faces = mesh.polygons.iter().any(|p| p.len() > 255);
    let ascii = options.ascii;
    let pos_ty = if options.double_precision {
        "double"
    } else {
        "float"
    };
    let mut h = String::new();
    h.push_str("ply\n");
    h.push_str(if ascii {
        "format ascii 1.0\n"
    } else {
        "format binary_little_endian 1.0\n"
    });
    for line in crate::util::provenance(mesh, Some(COLOUR_NOTE)) {
        let _ = writeln!(h, "comment {line}");
    }
    let _ = writeln!(h, "element vertex {}", mesh.positions.len());
    for c in ["x", "y", "z"] {
        let _ = writeln!(h, "property {pos_ty} {c}");
    }
    for (k, _) in &cols {
        let _ = writeln!(h, "property float {k}");
    }
    let _ = writeln!(h, "element face {}", mesh.polygons.len());
    h.push_str(if big_faces {
        "property list int int vertex_indices\n"
    } else {
        "property list uchar int vertex_indices\n"
    });
    let creases = &mesh.crease_edges;
    if !creases.is_empty() {
        let _ = writeln!(h, "element edge {}", creases.len());
        h.push_str("property int vertex1\nproperty int vertex2\nproperty uchar crease\n");
    }
    h.push_str("end_header\n");
    // Every check is done: from here on, bytes go out.
    let mut s = crate::util::Sink::new(out);
    s.push_str(&h);
    if ascii {
        for (i, p) in mesh.positions.iter().enumerate() {
            if options.double_precision {
                let _ = write!(s, "{:?} {:?} {:?}", p.x, p.y, p.z);
            } else {
                let _ = write!(s, "{:?} {:?} {:?}", p.x as f32, p.y as f32, p.z as f32);
            }
            for (_, column) in &cols {
                let _ = write!(s, " {:?}", column.value(i) as f32);
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
        for [a, b] in creases {
            let _ = writeln!(s, "{a} {b} 1");
        }
    } else {
        // Each record is gathered in a small buffer and handed to the sink whole.
        let mut record: Vec<u8> = Vec::with_capacity(24 + 4 * cols.len());
        for (i, p) in mesh.positions.iter().enumerate() {
            if cols.is_empty() && !options.double_precision {
                // Fixed-size records are copied without a call.
                s.f32x3([p.x as f32, p.y as f32, p.z as f32]);
                continue;
            }
            record.clear();
            for x in [p.x, p.y, p.z] {
                if options.double_precision {
                    record.extend_from_slice(&x.to_le_bytes());
                } else {
                    record.extend_from_slice(&(x as f32).to_le_bytes());
                }
            }
            for (_, column) in &cols {
                record.extend_from_slice(&(column.value(i) as f32).to_le_bytes());
            }
            s.put(&record);
        }
        for poly in mesh.polygons.iter() {
            if let (false, &[a, b, c]) = (big_faces, poly) {
                let mut triangle = [3u8; 13];
                for (slot, i) in triangle[1..].chunks_exact_mut(4).zip([a, b, c]) {
                    slot.copy_from_slice(&(i as i32).to_le_bytes());
                }
                s.put(&triangle);
                continue;
            }
            record.clear();
            if big_faces {
                record.extend_from_slice(&(poly.len() as i32).to_le_bytes());
            } else {
                record.push(poly.len() as u8);
            }
            for &i in poly {
                record.extend_from_slice(&(i as i32).to_le_bytes());
            }
            s.put(&record);
        }
        for &[a, b] in creases {
            s.i32(a as i32);
            s.i32(b as i32);
            s.u8(1);
        }
    }
    s.finish(NAME)
}

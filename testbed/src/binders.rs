//! The colour binders of `mat0`, `kcolor` and `radial`: a [`Colouring`] picks each vertex's
//! colour, [`colour`] binds it to every vertex of every `Triangle` and `TriangleMesh` of the
//! stream (the range fixed from the first block of triangles unless given, [`DEFAULT_BLOCK`]),
//! in place when present, appended otherwise; records of other types pass through in place.
//! The records held until the range is fixed stay within [`HELD_BYTES`] of memory (the rest
//! in a temporary file, [`crate::hold`]); a stream with nothing to colour is an error.

use crate::error::{FieldError, FilterError, StreamError};
use crate::hold::{Held, HELD_BYTES};
use crate::pipe::Pipe;
use crate::record::{self, Vertex};
use crate::stream::Record;
use crate::tape::Tok;
use crate::triangle_mesh::{self, TriangleMesh};

/// How a colouring filter picks each vertex's colour.
pub trait Colouring {
    /// The filter's name.
    fn name(&self) -> &'static str;
    /// True when the colour depends on the data (then the default range needs every value).
    fn data_dependent(&self) -> bool {
        true
    }
    /// The value the colour depends on (`None` for a uniform colour).
    fn value(&self, v: &Vertex, field: &str) -> Result<Option<f64>, FieldError>;
    /// The colour of `value` given the range chosen.
    fn color(&self, value: f64, range: (f64, f64)) -> [f32; 3];
    /// Extra vertex field written with the colour (its name), if any.
    fn extra_field(&self) -> Option<&'static str> {
        None
    }
    /// The default range from the values (all finite).
    fn default_range(&self, values: &mut [f64]) -> (f64, f64);
}

pub use render::colors::{robust_max, ROBUST_QUANTILE};

/// Triangles held by a data-dependent colouring without `--range` before the colour range
/// is fixed from their values and everything streams. 8 192 triangles (24 576 values) hold
/// about 8 MB and let the next filter start after 8% of a 10⁵-triangle stream instead of at
/// its end. The block is the *first* part of the surface, not a random sample, so its range
/// can differ from the whole stream's where curvature varies along the stream: on
/// `ring(16, 16)` at `-s 8` it gives ±4.12 against ±4.18 (1.6%, no visible difference).
/// Streams shorter than this are coloured exactly as with the whole stream.
pub const DEFAULT_BLOCK: usize = 8192;

/// The records a colouring filter colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Coloured {
    /// A `Triangle`: three vertex objects.
    Triangle,
    /// A `TriangleMesh`: vertex columns.
    Mesh,
}

impl Coloured {
    fn of(rec: &Record) -> Option<Self> {
        match rec.kind() {
            "Triangle" => Some(Coloured::Triangle),
            triangle_mesh::KIND => Some(Coloured::Mesh),
            _ => None,
        }
    }
}

/// Most triangles a block may hold (4 Mi): their corner values, from which the range is taken,
/// stay in memory (3 a triangle at 8 bytes: 96 MiB), where the records themselves are held
/// within [`HELD_BYTES`] (the rest in a temporary file, [`crate::hold`]). `--block 0` holds
/// the whole stream up to this many triangles; above it, `--block` is refused with the range.
/// 512 times the default block: the range of 4 M triangles of a surface is its range.
pub const MAX_BLOCK: usize = 1 << 22;

/// The kinds of records a colouring filter passed without colouring, for the message that says
/// nothing was coloured: the first [`NAMED_KINDS`] kinds by name, the rest counted.
#[derive(Default)]
struct Passed {
    kinds: Vec<(String, usize)>,
    others: usize,
    total: usize,
}

/// Kinds named in the message of a filter that coloured nothing (the rest are counted).
const NAMED_KINDS: usize = 4;

/// Longest kind name quoted in that message (a record's `type` can be a megabyte long).
const KIND_NAME_CHARS: usize = 40;

impl Passed {
    fn count(&mut self, kind: &str) {
        self.total += 1;
        if let Some(k) = self.kinds.iter_mut().find(|(n, _)| n == kind) {
            k.1 += 1;
        } else if self.kinds.len() < NAMED_KINDS && kind.chars().count() <= KIND_NAME_CHARS {
            self.kinds.push((kind.to_string(), 1));
        } else {
            self.others += 1;
        }
    }

    /// What the stream held, for the message.
    fn describe(&self, skipped: usize) -> String {
        let mut parts: Vec<String> = self
            .kinds
            .iter()
            .map(|(n, c)| {
                let n = if n.is_empty() { "(no type)" } else { n };
                format!("{c} {n}")
            })
            .collect();
        if self.others > 0 {
            parts.push(format!("{} of other types", self.others));
        }
        if skipped > 0 {
            parts.push(format!("{skipped} bad record(s) skipped"));
        }
        if parts.is_empty() {
            "the stream is empty".to_string()
        } else {
            format!("the stream held {}", parts.join(", "))
        }
    }
}

/// Binds a colour to every vertex of every `Triangle` and `TriangleMesh`. Without `range`
/// and for a data-dependent colouring the first `block` triangles are held (`0`: the whole
/// stream, up to [`MAX_BLOCK`]; a `TriangleMesh` is held whole, so the block may run on to
/// the end of its patch), the range is taken from their values at every triangle corner (so
/// a `TriangleMesh` stream is coloured exactly as the `Triangle` stream of the same triangles
/// when the block ends at the end of a patch), and the rest stream through with it. Records
/// of other types keep their place in the stream: written at once while nothing is held (a
/// stream without triangles is never held), held with the triangles otherwise. What is held
/// stays within [`HELD_BYTES`] of memory, the rest in a temporary file ([`crate::hold`]).
/// A stream without a single `Triangle` or `TriangleMesh` to colour is an error (after its
/// records have passed through), naming what it held: a colouring filter before `tess`.
pub fn colour(
    pipe: &mut Pipe,
    colouring: &dyn Colouring,
    field: &str,
    range: Option<(f64, f64)>,
    block: usize,
) -> Result<(), FilterError> {
    let block = if block == 0 {
        MAX_BLOCK
    } else {
        block.min(MAX_BLOCK)
    };
    let mut range = match range {
        Some(r) => Some(r),
        None if !colouring.data_dependent() => Some((0.0, 1.0)),
        None => None,
    };
    // Held records with their vertex values, and the values at the held triangles' corners.
    let mut held = Held::new(HELD_BYTES);
    let mut corners: Vec<f64> = Vec::new();
    let mut binder = Binder::default();
    let mut mesh = TriangleMesh::default();
    let mut values: Vec<f64> = Vec::new();
    let mut rec = Record::default();
    let mut coloured = 0usize;
    let mut passed = Passed::default();
    while pipe.next_good(&mut rec)? {
        let Some(kind) = Coloured::of(&rec) else {
            passed.count(rec.kind());
            if held.is_empty() {
                pipe.write(&rec)?;
            } else {
                held.push(std::mem::take(&mut rec), Vec::new(), colouring.name())?;
            }
            continue;
        };
        values.clear();
        let read = match kind {
            Coloured::Triangle => record::triangle(&rec.tape).and_then(|t| {
                for v in &t {
                    values.push(colouring.value(v, field)?.unwrap_or(0.0));
                }
                Ok(())
            }),
            Coloured::Mesh => mesh.read(&rec.tape).and_then(|()| {
                for i in 0..mesh.pos.len() {
                    let x = colouring.value(&mesh.vertex(i), field).map_err(|e| {
                        // A vertex field of a Triangle is a column of a TriangleMesh.
                        let column = e.field.trim_start_matches("vertex.").to_string();
                        FieldError::new(column, e.message)
                    })?;
                    values.push(x.unwrap_or(0.0));
                }
                Ok(())
            }),
        };
        if let Err(e) = read {
            pipe.bad_field(&rec, e)?;
            continue;
        }
        coloured += 1;
        match range {
            Some(r) => {
                binder.bind(colouring, &mut rec, kind, &values, r);
                pipe.write(&rec)?;
            }
            None => {
                match kind {
                    Coloured::Triangle => corners.extend_from_slice(&values),
                    Coloured::Mesh => {
                        corners.extend(mesh.triangles.iter().flatten().map(|&i| values[i as usize]))
                    }
                }
                held.push(std::mem::take(&mut rec), values.clone(), colouring.name())?;
                if corners.len() / 3 >= block {
                    range = Some(release(
                        pipe,
                        colouring,
                        &mut held,
                        &mut corners,
                        &mut binder,
                        block,
                    )?);
                }
            }
        }
    }
    if !held.is_empty() {
        release(pipe, colouring, &mut held, &mut corners, &mut binder, block)?;
    }
    pipe.finish()?;
    if coloured == 0 {
        return Err(FilterError::NothingToColour {
            filter: colouring.name(),
            held: passed.describe(pipe.skipped),
        });
    }
    Ok(())
}

/// Fixes the range from the held triangles' corner values, then colours and writes the held
/// records in order.
fn release(
    pipe: &mut Pipe,
    colouring: &dyn Colouring,
    held: &mut Held,
    corners: &mut Vec<f64>,
    binder: &mut Binder,
    block: usize,
) -> Result<(f64, f64), StreamError> {
    let n = corners.len() / 3;
    let r = colouring.default_range(corners);
    *corners = Vec::new();
    let whole = if n < block {
        "the whole stream".to_string()
    } else if block == MAX_BLOCK {
        format!("the first {n} triangles, the most a block holds")
    } else {
        format!("the first {n} triangles")
    };
    eprintln!(
        "{}: colour range [{:.4e}, {:.4e}] ({} of |value| over {whole}; --range A:B to fix it)",
        colouring.name(),
        r.0,
        r.1,
        ROBUST_QUANTILE
    );
    held.drain(&mut |mut rec, values| {
        if let Some(kind) = Coloured::of(&rec) {
            binder.bind(colouring, &mut rec, kind, &values, r);
        }
        pipe.write(&rec)
    })?;
    Ok(r)
}

/// Sets colours in a record's tape (reused scratch storage).
#[derive(Default)]
struct Binder {
    scratch: Vec<Tok>,
    colors: Vec<[f32; 3]>,
}

impl Binder {
    /// Sets `color` (and the colouring's extra field) of every vertex: the vertex objects of
    /// a Triangle, the columns of a TriangleMesh (both checked when `values` were read).
    fn bind(
        &mut self,
        colouring: &dyn Colouring,
        rec: &mut Record,
        kind: Coloured,
        values: &[f64],
        range: (f64, f64),
    ) {
        self.colors.clear();
        self.colors
            .extend(values.iter().map(|&v| colouring.color(v, range)));
        let colors = &self.colors;
        let extra = colouring.extra_field();
        let names: &[&str] = match extra {
            Some(e) => &["color", e][..],
            None => &["color"][..],
        };
        let color_toks = |c: &[f32; 3], out: &mut Vec<Tok>| {
            out.push(Tok::Arr { items: 3, len: 3 });
            out.extend(c.iter().map(|&c| Tok::Float(record::color_component(c))));
        };
        match kind {
            Coloured::Triangle => {
                rec.tape
                    .set_vertex_fields(names, &mut self.scratch, &mut |vi, ni, out| {
                        if ni == 0 {
                            color_toks(&colors[vi], out);
                        } else {
                            out.push(Tok::Float(values[vi]));
                        }
                    });
            }
            Coloured::Mesh => {
                let n = values.len() as u32;
                rec.tape
                    .set_fields(names, &mut self.scratch, &mut |ni, out| {
                        if ni == 0 {
                            out.push(Tok::Arr {
                                items: n,
                                len: 4 * n,
                            });
                            for c in colors {
                                color_toks(c, out);
                            }
                        } else {
                            out.push(Tok::Arr { items: n, len: n });
                            out.extend(values.iter().map(|&v| Tok::Float(v)));
                        }
                    });
            }
        }
    }
}

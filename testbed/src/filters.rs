//! The pipeline's filters over record streams (the seed's Tess, G1, Mat0, KColor, Radial) and
//! its ends (Render, XRender, a mesh file).
//!
//! **Pass-through.** Every filter writes the records it does not use unchanged and in order,
//! and keeps the fields it does not use in the records it changes, in order:
//!
//! * `tess` turns each `BezierTriangle` into `s²` `Triangle`s; each triangle gets the three
//!   vertex fields first, then **every field of its patch except `type`, `degree` and
//!   `points`** (the fields tess consumes), in the patch's order: `face`, `subpatch`,
//!   `scheme` and anything added upstream (a `provenance`) reach the triangles;
//! * `tess --mesh` writes one `TriangleMesh` per patch instead (`crate::triangle_mesh`): its
//!   vertex columns and `triangles` first, then the same carried fields;
//! * `mat0`, `kcolor`, `radial` set `color` (and `radial` also `dist`) in each vertex object
//!   of a `Triangle`, and the `color` (and `dist`) column of a `TriangleMesh`, in place when
//!   present, appended otherwise;
//! * `g1` writes every record unchanged.
//!
//! Records of other types pass through all of them. Malformed records are errors naming the
//! record number, its line and the field; with `keep_going` they are skipped (not written),
//! counted and reported on standard error.

use std::collections::HashMap;
use std::io::{BufRead, Write};

use nalgebra::{Point3, Vector3};
use serde_json::{Map, Value};
use surface::beztri::SampleWeights;
use surface::BezierTriangle;

use crate::error::{FieldError, FilterError, StreamError};
use crate::record::{self, Vertex, VERTEX_FIELDS};
use crate::stream::{Format, Record, RecordReader, RecordWriter};
use crate::tape::{Span, Tape, Tok};
use crate::triangle_mesh::{self, MeshTapes, TriangleMesh};

/// How many skipped records are described one by one on standard error (the rest are only
/// counted).
pub const REPORTED_SKIPS: usize = 5;

/// A filter's input and output streams and how to treat bad records.
pub struct Pipe<'a> {
    /// The input.
    pub reader: RecordReader<&'a mut dyn BufRead>,
    /// The output.
    pub writer: RecordWriter<&'a mut dyn Write>,
    /// Skip bad records instead of stopping.
    pub keep_going: bool,
    /// Records skipped.
    pub skipped: usize,
    /// The filter's name, for messages.
    pub name: &'static str,
}

impl<'a> Pipe<'a> {
    /// A pipe from `input` to `output`; `format`: the output format (default: the input's).
    pub fn new(
        name: &'static str,
        input: &'a mut dyn BufRead,
        output: &'a mut dyn Write,
        format: Option<Format>,
        keep_going: bool,
    ) -> Self {
        Pipe {
            reader: RecordReader::new(input),
            writer: RecordWriter::new(output, format),
            keep_going,
            skipped: 0,
            name,
        }
    }

    /// Reads the next good record into `rec` (its storage reused); false at the end. Bad
    /// records are skipped (with `keep_going`) or returned as errors.
    pub fn next_good(&mut self, rec: &mut Record) -> Result<bool, StreamError> {
        loop {
            match self.reader.read_into(rec) {
                None => return Ok(false),
                Some(Ok(())) => {
                    self.writer.default_format(self.reader.format());
                    return Ok(true);
                }
                Some(Err(e)) => self.bad(e)?,
            }
        }
    }

    /// A bad record: skipped and reported with `keep_going` (if confined to the record),
    /// otherwise the error.
    pub fn bad(&mut self, e: StreamError) -> Result<(), StreamError> {
        if self.keep_going && e.is_record_error() {
            self.skipped += 1;
            if self.skipped <= REPORTED_SKIPS {
                eprintln!("{}: skipped {e}", self.name);
            }
            Ok(())
        } else {
            Err(e)
        }
    }

    /// A field error of `record`, through [`Pipe::bad`].
    pub fn bad_field(&mut self, record: &Record, e: FieldError) -> Result<(), StreamError> {
        let kind = record.kind().to_string();
        self.bad(StreamError::Field {
            at: record.at,
            kind,
            source: e,
        })
    }

    /// Writes a record.
    pub fn write(&mut self, record: &Record) -> Result<(), StreamError> {
        self.write_tape(&record.tape, record)
    }

    /// Writes `tape`, named in errors as `record`.
    pub fn write_tape(&mut self, tape: &Tape, record: &Record) -> Result<(), StreamError> {
        match self.writer.write_tape(tape, record.at) {
            Err(e) if e.is_record_error() => self.bad(e),
            other => other,
        }
    }

    /// Flushes the output and reports the skipped records.
    pub fn finish(&mut self) -> Result<(), StreamError> {
        self.writer.finish()?;
        self.report_skipped();
        Ok(())
    }

    /// Says on standard error how many records were skipped, if any (the end of a sink's
    /// reading; [`Pipe::finish`] for a filter).
    pub fn report_skipped(&self) {
        if self.skipped > 0 {
            eprintln!(
                "{}: {} bad record(s) skipped (--keep-going)",
                self.name, self.skipped
            );
        }
    }
}

/// Which curvatures a tessellation writes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CurvatureFields {
    /// Gaussian curvature `kg`.
    pub kg: bool,
    /// Mean curvature `km`.
    pub km: bool,
}

/// One tessellated vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Position.
    pub pos: Point3<f64>,
    /// Unit normal.
    pub norm: Vector3<f64>,
    /// Gaussian curvature.
    pub kg: f64,
    /// Mean curvature.
    pub km: f64,
}

/// One patch's tessellation with shared vertices: its samples, and its triangles as indices
/// into them (counter-clockwise, in the order of `surface::tessellate`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IndexedPatch {
    /// The samples (vertices), each once.
    pub samples: Vec<Sample>,
    /// The triangles: indices into `samples`.
    pub triangles: Vec<[u32; 3]>,
}

impl IndexedPatch {
    /// The triangles with their vertices, appended to `out` after clearing it.
    pub fn expand(&self, out: &mut Vec<[Sample; 3]>) {
        out.clear();
        out.extend(
            self.triangles
                .iter()
                .map(|t| t.map(|i| self.samples[i as usize])),
        );
    }
}

/// Tessellates patches one at a time at `s` segments per edge, exactly as
/// `surface::tessellate` does for the patch alone, with the Bernstein weights of the samples
/// computed once per degree and shared by every patch (`surface::tessellate` computes them
/// per call, which is 90% of its time for one patch). A patch with a singular sample or two
/// boundary samples close enough to be welded goes through `surface::tessellate` itself.
#[derive(Debug)]
pub struct PatchTessellator {
    s: usize,
    tables: HashMap<usize, Vec<SampleWeights>>,
    indexed: IndexedPatch,
}

/// Boundary samples closer than this many weld tolerances (`surface::tessellate`'s
/// `WELD_RELATIVE` times the net's size) send a patch to the general path: a margin of 4
/// keeps the fast path away from the welder's own comparisons.
const WELD_MARGIN: f64 = 4.0;

impl PatchTessellator {
    /// A tessellator at `s ≥ 1` segments per edge.
    pub fn new(s: usize) -> Result<Self, surface::TessError> {
        if s == 0 {
            return Err(surface::TessError::ZeroDensity);
        }
        Ok(PatchTessellator {
            s,
            tables: HashMap::new(),
            indexed: IndexedPatch::default(),
        })
    }

    /// The `s²` triangles of `patch` (fewer where the general path collapses some), appended
    /// to `out` after clearing it: [`PatchTessellator::tessellate_indexed`] with each
    /// triangle's vertices copied out.
    pub fn tessellate(
        &mut self,
        patch: &BezierTriangle,
        out: &mut Vec<[Sample; 3]>,
    ) -> Result<(), surface::TessError> {
        let mut indexed = std::mem::take(&mut self.indexed);
        let result = self.tessellate_indexed(patch, &mut indexed);
        indexed.expand(out);
        self.indexed = indexed;
        result
    }

    /// The tessellation of `patch` with shared vertices: `(s + 1)(s + 2)/2` samples and `s²`
    /// triangles on the fast path; on the general path the welded vertices and triangles of
    /// `surface::tessellate` for the patch alone. `out` is cleared first.
    pub fn tessellate_indexed(
        &mut self,
        patch: &BezierTriangle,
        out: &mut IndexedPatch,
    ) -> Result<(), surface::TessError> {
        out.samples.clear();
        out.triangles.clear();
        let s = self.s;
        let table = self
            .tables
            .entry(patch.degree())
            .or_insert_with(|| SampleWeights::grid(patch.degree(), s));
        for w in table.iter() {
            let Some((d, c)) = patch
                .derivatives_with(w)
                .and_then(|d| surface::beztri::curvature_of(&d).map(|c| (d, c)))
            else {
                return general(patch, s, out);
            };
            out.samples.push(Sample {
                pos: d.p,
                norm: c.normal,
                kg: c.gaussian,
                km: c.mean,
            });
        }
        let local = |i: usize, j: usize| j * (s + 1) - j * j.saturating_sub(1) / 2 + i;
        // Would the welder join two boundary samples?
        let tol = surface::tessellate::WELD_RELATIVE
            * surface::mesh::bounding_size(patch.points()).max(f64::MIN_POSITIVE)
            * WELD_MARGIN;
        let mut boundary = Vec::with_capacity(3 * s);
        for j in 0..=s {
            for i in 0..=s - j {
                if i == 0 || j == 0 || i + j == s {
                    boundary.push(out.samples[local(i, j)].pos);
                }
            }
        }
        for (a, p) in boundary.iter().enumerate() {
            if boundary[a + 1..].iter().any(|q| (p - q).norm() <= tol) {
                return general(patch, s, out);
            }
        }
        // Sample indices fit u32 for any s whose samples fit in memory (and `tess` allows at
        // most MAX_SEGMENTS).
        let at = |i: usize, j: usize| local(i, j) as u32;
        for j in 0..s {
            for i in 0..s - j {
                // Upward triangle: corners towards u, v, w; then the downward one (the order
                // of `surface::tessellate`).
                out.triangles.push([at(i + 1, j), at(i, j + 1), at(i, j)]);
                if i + j + 2 <= s {
                    out.triangles
                        .push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
        Ok(())
    }
}

/// `surface::tessellate` on the patch alone.
fn general(
    patch: &BezierTriangle,
    s: usize,
    out: &mut IndexedPatch,
) -> Result<(), surface::TessError> {
    out.samples.clear();
    out.triangles.clear();
    let t = surface::tessellate(std::slice::from_ref(patch), s)?;
    out.samples.extend((0..t.positions.len()).map(|i| Sample {
        pos: t.positions[i],
        norm: t.normals[i],
        kg: t.gaussian[i],
        km: t.mean[i],
    }));
    out.triangles
        .extend(t.faces.iter().map(|f| f.map(|i| i as u32)));
    Ok(())
}

/// The `s²` triangles of one patch at `s` segments per patch edge (`surface::tessellate` on
/// the patch alone, so every vertex carries its own patch's normal and curvature). For many
/// patches use a [`PatchTessellator`], which shares the sample weights.
pub fn tessellate_patch(
    patch: &BezierTriangle,
    s: usize,
) -> Result<Vec<[Sample; 3]>, surface::TessError> {
    let mut indexed = IndexedPatch::default();
    general(patch, s, &mut indexed)?;
    let mut out = Vec::new();
    indexed.expand(&mut out);
    Ok(out)
}

/// The vertex object of a sample (fit's slow path).
pub fn sample_value(s: &Sample, fields: CurvatureFields) -> Value {
    let mut v = Map::with_capacity(4);
    v.insert("pos".into(), record::arr3([s.pos.x, s.pos.y, s.pos.z]));
    v.insert("norm".into(), record::arr3([s.norm.x, s.norm.y, s.norm.z]));
    if fields.kg {
        v.insert("kg".into(), record::num(s.kg));
    }
    if fields.km {
        v.insert("km".into(), record::num(s.km));
    }
    Value::Object(v)
}

/// A Triangle record: the three vertices, then `carried` fields in order (fit's slow path).
pub fn triangle_value<'v>(
    tri: &[Sample; 3],
    fields: CurvatureFields,
    carried: impl Iterator<Item = (&'v String, &'v Value)>,
) -> Value {
    let mut m = Map::new();
    m.insert("type".into(), Value::from("Triangle"));
    for (name, s) in VERTEX_FIELDS.iter().zip(tri) {
        m.insert((*name).into(), sample_value(s, fields));
    }
    for (k, v) in carried {
        m.insert(k.clone(), v.clone());
    }
    Value::Object(m)
}

/// Fields of a patch record that tess consumes (the rest are carried to its triangles).
pub const TESS_CONSUMES: [&str; 3] = ["type", "degree", "points"];

/// The token ranges (key and value) of the fields of a patch record that tess carries to its
/// triangles: every field but [`TESS_CONSUMES`], in order. `out` is cleared first.
pub fn carried_fields(patch: &Tape, out: &mut Vec<std::ops::Range<usize>>) {
    out.clear();
    for (key, v) in patch.fields(0) {
        if !TESS_CONSUMES.iter().any(|c| c.as_bytes() == key) {
            let w = patch.toks.get(v).map_or(1, Tok::width);
            out.push(v - 1..v + w);
        }
    }
}

/// Builds Triangle tapes over one patch record's text (so carried fields are copied as
/// tokens, their strings not at all).
struct TriangleTapes {
    tape: Tape,
    /// Spans of `type`, `Triangle`, `vertex1..3`, `pos`, `norm`, `kg`, `km`.
    names: [Span; 9],
    /// Token ranges (key and value) of the carried fields.
    carried: Vec<std::ops::Range<usize>>,
}

impl TriangleTapes {
    fn new() -> Self {
        TriangleTapes {
            tape: Tape::default(),
            names: [Span { start: 0, len: 0 }; 9],
            carried: Vec::new(),
        }
    }

    /// Starts the triangles of `patch`.
    fn start(&mut self, patch: &Tape) {
        self.tape.clear();
        self.tape.text.extend_from_slice(&patch.text);
        for (k, n) in [
            "type", "Triangle", "vertex1", "vertex2", "vertex3", "pos", "norm", "kg", "km",
        ]
        .iter()
        .enumerate()
        {
            self.names[k] = self.tape.push_text(n.as_bytes());
        }
        carried_fields(patch, &mut self.carried);
    }

    /// The tape of one triangle.
    fn build(&mut self, patch: &Tape, tri: &[Sample; 3], fields: CurvatureFields) -> &Tape {
        let n = self.names;
        let toks = &mut self.tape.toks;
        toks.clear();
        toks.push(Tok::Obj { fields: 0, len: 0 });
        toks.push(Tok::Key(n[0]));
        toks.push(Tok::Str(n[1]));
        for (vi, smp) in tri.iter().enumerate() {
            toks.push(Tok::Key(n[2 + vi]));
            let obj = toks.len();
            toks.push(Tok::Obj { fields: 0, len: 0 });
            toks.push(Tok::Key(n[5]));
            toks.push(Tok::Arr { items: 3, len: 3 });
            toks.extend(smp.pos.iter().map(|&x| Tok::Float(x)));
            toks.push(Tok::Key(n[6]));
            toks.push(Tok::Arr { items: 3, len: 3 });
            toks.extend(smp.norm.iter().map(|&x| Tok::Float(x)));
            let mut count = 2;
            if fields.kg {
                toks.push(Tok::Key(n[7]));
                toks.push(Tok::Float(smp.kg));
                count += 1;
            }
            if fields.km {
                toks.push(Tok::Key(n[8]));
                toks.push(Tok::Float(smp.km));
                count += 1;
            }
            toks[obj] = Tok::Obj {
                fields: count,
                len: (toks.len() - obj - 1) as u32,
            };
        }
        for r in &self.carried {
            toks.extend_from_slice(&patch.toks[r.clone()]);
        }
        toks[0] = Tok::Obj {
            fields: 4 + self.carried.len() as u32,
            len: (toks.len() - 1) as u32,
        };
        &self.tape
    }
}

/// Largest `tess -s`: a patch at s = 4096 is 8.4 M samples (about half a GB with their weights),
/// far beyond any picture's need, while a larger `-s` would only exhaust memory (or overflow
/// the sample table's size) instead of failing with a message; it also keeps every vertex
/// index of a `TriangleMesh` within `u32`.
pub const MAX_SEGMENTS: usize = 4096;

/// What `tess` writes for each patch.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TessRecords {
    /// `s²` `Triangle` records (the seed's record, the default).
    #[default]
    Triangles,
    /// One `TriangleMesh` record: the patch's vertices once, its triangles as indices
    /// (`crate::triangle_mesh`).
    Mesh,
}

/// `tess -s N [--kg] [--km] [--mesh]`: BezierTriangles to Triangles, or to one TriangleMesh
/// each (module docs for what is carried).
pub fn tess(
    pipe: &mut Pipe,
    s: usize,
    fields: CurvatureFields,
    records: TessRecords,
) -> Result<(), FilterError> {
    if s == 0 || s > MAX_SEGMENTS {
        return Err(FilterError::Usage(format!(
            "tess: -s {s}: from 1 to {MAX_SEGMENTS} segments per edge"
        )));
    }
    let mut tessellator = PatchTessellator::new(s)?;
    let mut degrees_checked = Vec::new();
    let mut rec = Record::default();
    let mut indexed = IndexedPatch::default();
    let mut tris = Vec::new();
    let mut tapes = TriangleTapes::new();
    let mut meshes = MeshTapes::default();
    let mut carried = Vec::new();
    while pipe.next_good(&mut rec)? {
        if rec.kind() != "BezierTriangle" {
            pipe.write(&rec)?;
            continue;
        }
        let patch = match record::bezier_triangle(&rec.tape) {
            Ok(p) => p,
            Err(e) => {
                pipe.bad_field(&rec, e)?;
                continue;
            }
        };
        if !degrees_checked.contains(&patch.degree()) {
            check_tess_memory(s, patch.degree())?;
            degrees_checked.push(patch.degree());
        }
        match records {
            TessRecords::Mesh => {
                tessellator.tessellate_indexed(&patch, &mut indexed)?;
                carried_fields(&rec.tape, &mut carried);
                let t = meshes.build(&rec.tape, &indexed, fields, &carried);
                match pipe.writer.write_tape(t, rec.at) {
                    Err(e) if e.is_record_error() => pipe.bad(e)?,
                    other => other?,
                }
            }
            TessRecords::Triangles => {
                tessellator.tessellate(&patch, &mut tris)?;
                tapes.start(&rec.tape);
                for tri in &tris {
                    let t = tapes.build(&rec.tape, tri, fields);
                    match pipe.writer.write_tape(t, rec.at) {
                        Err(e) if e.is_record_error() => pipe.bad(e)?,
                        other => other?,
                    }
                }
            }
        }
    }
    pipe.finish()?;
    Ok(())
}

/// Bytes per sample of the record `tess` builds for one patch before writing it: a
/// `TriangleMesh` tape holds each sample's coordinates, normal and its two triangles' indices
/// as tokens with their text (measured: binary `--mesh` at `-s 1024` peaks at 1.7 GB, of which
/// 0.86 GB the weight table and 0.12 GB the tessellation, 1.4 KB a sample for the rest); a
/// `Triangle` stream holds the patch's triangles with their vertices (2 × 168 bytes a sample).
const TESS_RECORD_BYTES_PER_SAMPLE: u128 = 1500;

/// Refuses `tess -s s` for patches of `degree` when one patch's tessellation, the weight table
/// kept for the degree and the record built from it would exceed the library's limit
/// ([`surface::limits::check_memory`], the estimates of `experiments`:
/// [`surface::limits::tessellation_bytes`], [`surface::limits::sample_weights_bytes`]). One
/// patch is held at a time, so the stream's length does not count; the check is made when a
/// degree is first met, before its table is built.
pub fn check_tess_memory(s: usize, degree: usize) -> Result<(), FilterError> {
    let samples = (s as u128 + 1) * (s as u128 + 2) / 2;
    let points = (degree + 1) * (degree + 2) / 2;
    let bytes = surface::limits::tessellation_bytes(1, s)
        .saturating_add(surface::limits::sample_weights_bytes(points, s))
        .saturating_add(samples.saturating_mul(TESS_RECORD_BYTES_PER_SAMPLE));
    Ok(surface::limits::check_memory(
        &format!("tess -s {s} (patches of degree {degree})"),
        bytes,
    )?)
}

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

/// Mat0: the uniform material colour.
pub struct Mat0;

impl Colouring for Mat0 {
    fn name(&self) -> &'static str {
        "mat0"
    }
    fn data_dependent(&self) -> bool {
        false
    }
    fn value(&self, _: &Vertex, _: &str) -> Result<Option<f64>, FieldError> {
        Ok(None)
    }
    fn color(&self, _: f64, _: (f64, f64)) -> [f32; 3] {
        render::colors::MATERIAL
    }
    fn default_range(&self, _: &mut [f64]) -> (f64, f64) {
        (0.0, 1.0)
    }
}

/// KColor: a diverging colour of a curvature (`kg` by default), white-grey at zero.
pub struct KColor;

impl Colouring for KColor {
    fn name(&self) -> &'static str {
        "kcolor"
    }
    fn value(&self, v: &Vertex, field: &str) -> Result<Option<f64>, FieldError> {
        let x = match field {
            "km" => v.km,
            _ => v.kg,
        };
        x.map(Some).ok_or_else(|| {
            FieldError::new(
                format!("vertex.{field}"),
                format!("missing: run tess with --{field}"),
            )
        })
    }
    fn color(&self, value: f64, (lo, hi): (f64, f64)) -> [f32; 3] {
        // [lo, hi] onto [−1, 1] of the diverging map (for a symmetric range: value / hi).
        let t = -1.0 + 2.0 * (value - lo) / (hi - lo).max(f64::MIN_POSITIVE);
        render::colors::diverging(t, 1.0)
    }
    fn default_range(&self, values: &mut [f64]) -> (f64, f64) {
        let m = robust_max(values);
        (-m, m)
    }
}

/// Radial: a sequential colour of the distance to a true surface.
pub struct Radial {
    /// The true surface.
    pub surface: std::sync::Arc<dyn surface::AnalyticSurface>,
}

impl Colouring for Radial {
    fn name(&self) -> &'static str {
        "radial"
    }
    fn value(&self, v: &Vertex, _: &str) -> Result<Option<f64>, FieldError> {
        Ok(Some(self.surface.signed_distance(&v.pos)))
    }
    fn color(&self, value: f64, (lo, hi): (f64, f64)) -> [f32; 3] {
        render::colors::sequential(value.abs(), lo, hi)
    }
    fn extra_field(&self) -> Option<&'static str> {
        Some("dist")
    }
    fn default_range(&self, values: &mut [f64]) -> (f64, f64) {
        (0.0, robust_max(values))
    }
}

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

/// Binds a colour to every vertex of every `Triangle` and `TriangleMesh`. Without `range`
/// and for a data-dependent colouring the first `block` triangles are held (`0`: the whole
/// stream; a `TriangleMesh` is held whole, so the block may run on to the end of its
/// patch), the range is taken from their values at every triangle corner (so a
/// `TriangleMesh` stream is coloured exactly as the `Triangle` stream of the same triangles
/// when the block ends at the end of a patch), and the rest stream through with it. Records
/// of other types keep their place in the stream (held with the triangles until the range is
/// fixed).
pub fn colour(
    pipe: &mut Pipe,
    colouring: &dyn Colouring,
    field: &str,
    range: Option<(f64, f64)>,
    block: usize,
) -> Result<(), FilterError> {
    let block = if block == 0 { usize::MAX } else { block };
    let mut range = match range {
        Some(r) => Some(r),
        None if !colouring.data_dependent() => Some((0.0, 1.0)),
        None => None,
    };
    // Held records with their vertex values, and the values at the held triangles' corners.
    let mut held: Vec<(Record, Vec<f64>)> = Vec::new();
    let mut corners: Vec<f64> = Vec::new();
    let mut binder = Binder::default();
    let mut mesh = TriangleMesh::default();
    let mut values: Vec<f64> = Vec::new();
    let mut rec = Record::default();
    while pipe.next_good(&mut rec)? {
        let Some(kind) = Coloured::of(&rec) else {
            if range.is_none() {
                held.push((std::mem::take(&mut rec), Vec::new()));
            } else {
                pipe.write(&rec)?;
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
                held.push((std::mem::take(&mut rec), values.clone()));
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
    Ok(())
}

/// Fixes the range from the held triangles' corner values, then colours and writes the held
/// records in order.
fn release(
    pipe: &mut Pipe,
    colouring: &dyn Colouring,
    held: &mut Vec<(Record, Vec<f64>)>,
    corners: &mut Vec<f64>,
    binder: &mut Binder,
    block: usize,
) -> Result<(f64, f64), StreamError> {
    let n = corners.len() / 3;
    let r = colouring.default_range(corners);
    corners.clear();
    let whole = if n < block {
        "the whole stream".to_string()
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
    for (mut rec, values) in held.drain(..) {
        if let Some(kind) = Coloured::of(&rec) {
            binder.bind(colouring, &mut rec, kind, &values, r);
        }
        pipe.write(&rec)?;
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The shared-weights path gives exactly (bit for bit) what `surface::tessellate` gives
    /// for the patch alone, on regular patches and on a degenerate one (a collapsed edge: its
    /// samples are welded and some triangles dropped there, so it takes the general path).
    #[test]
    fn patch_tessellator_equals_surface_tessellate() {
        let quad = BezierTriangle::from_fn(4, |i, j, k| {
            let (u, v) = (i as f64 / 4.0, j as f64 / 4.0);
            Point3::new(
                u,
                v,
                0.3 * u * u - 0.2 * u * v + 0.1 * v * v + 0.05 * k as f64,
            )
        });
        let collapsed = BezierTriangle::from_fn(2, |i, j, _| {
            // Corners (2,0,0) and (0,2,0) coincide: edge w = 0 is a point.
            Point3::new(
                (i * j) as f64 * 0.5,
                (i + j) as f64 * 0.25,
                (i as f64 - 1.0).abs(),
            )
        });
        for s in [1, 3, 8] {
            let mut t = PatchTessellator::new(s).expect("s ≥ 1");
            let mut out = Vec::new();
            for patch in [&quad, &collapsed, &quad] {
                t.tessellate(patch, &mut out).expect("tessellates");
                let expected = tessellate_patch(patch, s).expect("tessellates");
                assert_eq!(out, expected, "s = {s}");
            }
            // Shared vertices: each sample once, s² triangles on the fast path (the quartic),
            // fewer vertices where the general path welds (the collapsed edge).
            let mut indexed = IndexedPatch::default();
            t.tessellate_indexed(&quad, &mut indexed)
                .expect("tessellates");
            assert_eq!(indexed.samples.len(), (s + 1) * (s + 2) / 2);
            assert_eq!(indexed.triangles.len(), s * s);
            t.tessellate_indexed(&collapsed, &mut indexed)
                .expect("tessellates");
            assert!(indexed.samples.len() < (s + 1) * (s + 2) / 2, "s = {s}");
            indexed.expand(&mut out);
            assert_eq!(out, tessellate_patch(&collapsed, s).expect("tessellates"));
        }
        assert!(PatchTessellator::new(0).is_err());
    }
}

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
//! * `mat0`, `kcolor`, `radial` set `color` (and `radial` also `dist`) in each vertex object
//!   of a `Triangle`, in place when present, appended otherwise;
//! * `g1` writes every record unchanged.
//!
//! Records of other types pass through all of them. Malformed records are errors naming the
//! record number, its line and the field; with `keep_going` they are skipped (not written),
//! counted and reported on standard error.

use std::io::{BufRead, Write};

use nalgebra::{Point3, Vector3};
use serde_json::{Map, Value};
use surface::BezierTriangle;

use crate::error::{FieldError, FilterError, StreamError};
use crate::record::{self, Vertex, VERTEX_FIELDS};
use crate::stream::{Format, Record, RecordReader, RecordWriter};

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

    /// The next good record; bad ones are skipped (with `keep_going`) or returned as errors.
    pub fn next_good(&mut self) -> Result<Option<Record>, StreamError> {
        loop {
            match self.reader.next_record() {
                None => return Ok(None),
                Some(Ok(r)) => {
                    self.writer.default_format(self.reader.format());
                    return Ok(Some(r));
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
    pub fn write(&mut self, value: &Value, record: &Record) -> Result<(), StreamError> {
        match self.writer.write(value, record.at) {
            Err(e) if e.is_record_error() => self.bad(e),
            other => other,
        }
    }

    /// Flushes the output and reports the skipped records.
    pub fn finish(&mut self) -> Result<(), StreamError> {
        self.writer.finish()?;
        if self.skipped > 0 {
            eprintln!(
                "{}: {} bad record(s) skipped (--keep-going)",
                self.name, self.skipped
            );
        }
        Ok(())
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

/// The `s²` triangles of one patch at `s` segments per edge (`surface::tessellate` on the
/// patch alone, so every vertex carries its own patch's normal and curvature).
pub fn tessellate_patch(
    patch: &BezierTriangle,
    s: usize,
) -> Result<Vec<[Sample; 3]>, surface::TessError> {
    let t = surface::tessellate(std::slice::from_ref(patch), s)?;
    let sample = |i: usize| Sample {
        pos: t.positions[i],
        norm: t.normals[i],
        kg: t.gaussian[i],
        km: t.mean[i],
    };
    Ok(t.faces
        .iter()
        .map(|f| [sample(f[0]), sample(f[1]), sample(f[2])])
        .collect())
}

/// The vertex object of a sample.
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

/// A Triangle record: the three vertices, then `carried` fields in order.
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

/// `tess -s N [--kg] [--km]`: BezierTriangles to Triangles (module docs for what is carried).
pub fn tess(pipe: &mut Pipe, s: usize, fields: CurvatureFields) -> Result<(), FilterError> {
    if s == 0 {
        return Err(FilterError::Usage(
            "tess: -s must be at least 1 segment per edge".into(),
        ));
    }
    while let Some(rec) = pipe.next_good()? {
        let Some(obj) = rec
            .value
            .as_object()
            .filter(|_| rec.kind() == "BezierTriangle")
        else {
            pipe.write(&rec.value, &rec)?;
            continue;
        };
        let patch = match record::bezier_triangle(obj) {
            Ok(p) => p,
            Err(e) => {
                pipe.bad_field(&rec, e)?;
                continue;
            }
        };
        let tris = tessellate_patch(&patch, s)?;
        for tri in &tris {
            let carried = obj
                .iter()
                .filter(|(k, _)| !TESS_CONSUMES.contains(&k.as_str()));
            let v = triangle_value(tri, fields, carried);
            pipe.write(&v, &rec)?;
        }
    }
    pipe.finish()?;
    Ok(())
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

/// Quantile of `|value|` taken as the data's robust maximum for colour ranges: curvature
/// spikes at a few singular samples (collapsed edges, seams of fallback faces) would
/// otherwise wash the picture out; 95% keeps the bulk of the surface in the scale (the same
/// choice as `experiments fit --mesh-out`).
pub const ROBUST_QUANTILE: f64 = 0.95;

/// The [`ROBUST_QUANTILE`] of `|values|` (1 when all are zero or there are none).
pub fn robust_max(values: &mut [f64]) -> f64 {
    for v in values.iter_mut() {
        *v = v.abs();
    }
    values.sort_by(f64::total_cmp);
    let k = ((values.len().saturating_sub(1)) as f64 * ROBUST_QUANTILE).round() as usize;
    values
        .get(k)
        .copied()
        .filter(|m| *m > 0.0 && m.is_finite())
        .unwrap_or(1.0)
}

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

/// Binds a colour to every vertex of every Triangle. Without `range` and for a data-dependent
/// colouring the triangles are held until the end (the range needs all values); other records
/// pass through at once.
pub fn colour(
    pipe: &mut Pipe,
    colouring: &dyn Colouring,
    field: &str,
    range: Option<(f64, f64)>,
) -> Result<(), FilterError> {
    let data_dependent = colouring.data_dependent();
    let mut held: Vec<(Record, [f64; 3])> = Vec::new();
    while let Some(mut rec) = pipe.next_good()? {
        if rec.kind() != "Triangle" {
            pipe.write(&rec.value, &rec)?;
            continue;
        }
        let values = rec
            .value
            .as_object()
            .ok_or_else(|| FieldError::new("", "not an object"))
            .and_then(record::triangle)
            .and_then(|t| {
                let mut out = [0.0; 3];
                for (o, v) in out.iter_mut().zip(&t) {
                    *o = colouring.value(v, field)?.unwrap_or(0.0);
                }
                Ok(out)
            });
        let values = match values {
            Ok(v) => v,
            Err(e) => {
                pipe.bad_field(&rec, e)?;
                continue;
            }
        };
        match range {
            Some(r) => {
                bind(colouring, &mut rec, values, r);
                pipe.write(&rec.value, &rec)?;
            }
            None if !data_dependent => {
                bind(colouring, &mut rec, values, (0.0, 1.0));
                pipe.write(&rec.value, &rec)?;
            }
            None => held.push((rec, values)),
        }
    }
    if !held.is_empty() {
        let mut all: Vec<f64> = held.iter().flat_map(|(_, v)| v.iter().copied()).collect();
        let r = colouring.default_range(&mut all);
        eprintln!(
            "{}: colour range [{:.4e}, {:.4e}] ({} of |value|)",
            colouring.name(),
            r.0,
            r.1,
            ROBUST_QUANTILE
        );
        for (mut rec, values) in held {
            bind(colouring, &mut rec, values, r);
            pipe.write(&rec.value, &rec)?;
        }
    }
    pipe.finish()?;
    Ok(())
}

fn bind(colouring: &dyn Colouring, rec: &mut Record, values: [f64; 3], range: (f64, f64)) {
    if let Some(obj) = rec.value.as_object_mut() {
        let colors = values.map(|v| record::color_value(colouring.color(v, range)));
        // The vertex objects were checked when the values were read.
        let _ = record::set_vertex_field(obj, "color", colors);
        if let Some(extra) = colouring.extra_field() {
            let _ = record::set_vertex_field(obj, extra, values.map(record::num));
        }
    }
}

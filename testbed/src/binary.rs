//! The self-describing binary stream (`--format binary`).
//!
//! ```text
//! stream  := MAGIC block*
//! block   := 'S' u32:len JSON-schema(len bytes)     a new schema, numbered 0, 1, … in order
//!          | 'R' u32:schema slot*                   one record
//! slot    := f64 | i64 | u64                         8 bytes each (kinds 'f', 'i', 'u')
//!          | u32:len UTF-8(len bytes)                a string (kind 's')
//! ```
//!
//! All integers little-endian. A schema is the JSON object `{"template": T, "slots": K}`: `T`
//! is a record with every number replaced by `0` and every string by `""` — the field names,
//! their order, array lengths, `true`/`false`/`null` are the template's own — and `K` a
//! string of one kind letter per number or string of `T` in depth-first order (object fields
//! in order, array items in order). A record is its schema's template with the slots filled
//! in. Records without string slots are fixed-size.
//!
//! The record's `type` string is kept in the template (a constant of the schema) rather than a
//! slot, so records of one type and shape are exactly `5 + 8 × numbers` bytes plus their other
//! strings. Any other field passes through as long as it is in a schema: unknown fields cost
//! nothing but their slots.
//!
//! Hostile input: a schema's text is at most [`MAX_SCHEMA_BYTES`], a record's in-memory size at
//! most [`MAX_EXPANSION`] times its size in the stream plus [`EXPANSION_ALLOWANCE`] (checked
//! when the schema is declared, before any record of it is decoded), the schemas together at
//! most [`MAX_SCHEMA_MEMORY`], a record at most [`MAX_RECORD_TOKENS`] tokens and
//! [`MAX_RECORD_BYTES`] of text, strings at most [`MAX_STRING_BYTES`], schemas at most
//! [`MAX_SCHEMAS`]; non-finite floats, unknown tags, a schema number not declared and
//! truncation are errors naming the record. The encoder refuses what the decoder would, so
//! every binary stream a filter writes reads back.

use std::io::{BufRead, Read};

use crate::json;
use crate::tape::{Tape, Tok, MAX_RECORD_BYTES, MAX_RECORD_TOKENS, TOK_BYTES};

/// The first bytes of a binary stream.
pub const MAGIC: &[u8] = b"TBIN1\n";

/// Largest schema text accepted: a template is its record with every value a `0` or `""`,
/// never longer than a record may be ([`MAX_RECORD_BYTES`]); `tess --mesh -s 512` writes a
/// 6.2 MB template (the former limit, 1 MiB, refused every `TriangleMesh` from `-s 256`).
pub const MAX_SCHEMA_BYTES: u32 = MAX_RECORD_BYTES as u32;

/// A record decoded holds at most this many times the bytes it takes in the stream (its slots,
/// 8 bytes a number and 4 plus the text a string, and its 5-byte header), plus
/// [`EXPANSION_ALLOWANCE`]: the template's tokens ([`TOK_BYTES`] each) and keys are copied
/// into every record, so a template of constants (`null`s, keys, empty arrays) with few slots
/// would turn a 5-byte record into a megabyte (a 1 MiB template of `null`s: 18 000× from
/// binary to JSON). The pipeline's records expand 4–7× (a `Triangle` 6.3×, a `TriangleMesh`
/// 4.0×, a `BezierTriangle` 4.6×: `binary::tests`), well inside.
pub const MAX_EXPANSION: usize = 32;

/// Bytes of constants a record may expand to beyond [`MAX_EXPANSION`] times its size: room
/// for a small record's keys, `type` and a few `null`s or `true`s (`{"type":"Note"}` is 80
/// bytes decoded from 5); a zero-slot record then decodes to at most 1 184 bytes.
pub const EXPANSION_ALLOWANCE: usize = 1024;

/// Most memory the schemas of one stream may hold together (their templates, slots and
/// slot positions; 256 MiB): one schema per record shape, and a stream of one shape (every
/// filter's) needs one, of a few hundred bytes (`Triangle`) to a few MB (`TriangleMesh`
/// at large `-s`); without a total, [`MAX_SCHEMAS`] templates of [`MAX_SCHEMA_BYTES`] each
/// could ask for terabytes.
pub const MAX_SCHEMA_MEMORY: usize = 256 << 20;

/// Largest string slot accepted (16 MiB): a string longer than any field of the pipeline's,
/// short enough that a damaged length cannot allocate much.
pub const MAX_STRING_BYTES: u32 = 1 << 24;

/// Most schemas in one stream: a stream of one record type needs one; a writer that would
/// need more (every record shaped differently) is better served by JSON.
pub const MAX_SCHEMAS: usize = 1 << 16;

/// The in-memory size of a record of `template` before its strings: its tokens and the text of
/// its keys and constant strings (what [`Decoder`] copies into every record).
fn decoded_bytes(template: &Tape) -> usize {
    let text: usize = template
        .toks
        .iter()
        .map(|t| match t {
            Tok::Key(s) | Tok::Str(s) => s.len as usize,
            _ => 0,
        })
        .sum();
    template.toks.len() * TOK_BYTES + text
}

/// The fewest bytes a record of `slots` takes in the stream: its tag and schema number, 8
/// bytes a number, 4 a string's length (its text comes on top, on both sides).
fn encoded_bytes(slots: &[u8]) -> usize {
    5 + slots
        .iter()
        .map(|&k| if k == b's' { 4 } else { 8 })
        .sum::<usize>()
}

/// Memory a schema holds (template tokens and text, slot kinds, positions and runs).
fn schema_memory(template: &Tape, slots: &[u8]) -> usize {
    template.toks.len() * TOK_BYTES + template.text.len() + slots.len() * (1 + 4 + 8)
}

/// Checks what a record of `template` with `slots` may take in memory: at most
/// [`MAX_RECORD_TOKENS`] tokens and [`MAX_EXPANSION`] × its stream size +
/// [`EXPANSION_ALLOWANCE`]; `id` names the schema.
fn check_expansion(template: &Tape, slots: &[u8], id: usize) -> Result<(), String> {
    if template.toks.len() > MAX_RECORD_TOKENS {
        return Err(format!("schema {id}: {}", crate::tape::too_many_tokens()));
    }
    let (decoded, encoded) = (decoded_bytes(template), encoded_bytes(slots));
    let allowed = MAX_EXPANSION * encoded + EXPANSION_ALLOWANCE;
    if decoded > allowed {
        return Err(format!(
            "schema {id}: a record of {encoded} bytes ({} slots) would expand to {decoded} bytes \
             in memory ({} tokens of its template copied into each); at most {MAX_EXPANSION} × \
             its size + {EXPANSION_ALLOWANCE} bytes = {allowed} bytes (write such records as \
             JSON)",
            slots.len(),
            template.toks.len()
        ));
    }
    Ok(())
}

/// The schemas' memory after adding `more` bytes, refused past [`MAX_SCHEMA_MEMORY`].
fn add_schema_memory(held: usize, more: usize) -> Result<usize, String> {
    let total = held.saturating_add(more);
    if total > MAX_SCHEMA_MEMORY {
        return Err(format!(
            "the schemas would hold {total} bytes, more than the {MAX_SCHEMA_MEMORY} bytes ({} \
             MiB) a stream's schemas may hold together (write such a stream as JSON)",
            MAX_SCHEMA_MEMORY >> 20
        ));
    }
    Ok(total)
}

/// One schema: the template (a record tape), slot kinds, and the template token each slot
/// fills.
#[derive(Clone, Debug, PartialEq)]
struct Schema {
    template: Tape,
    slots: Vec<u8>,
    at: Vec<u32>,
}

impl Schema {
    /// The schema of `template` with `slots` (already checked to match it).
    fn new(template: Tape, slots: Vec<u8>) -> Self {
        let keep = type_range(&template);
        let at = template
            .toks
            .iter()
            .enumerate()
            .filter(|(i, t)| {
                !keep.contains(i)
                    && matches!(
                        t,
                        Tok::Str(_) | Tok::Float(_) | Tok::Text(..) | Tok::Int(_) | Tok::UInt(_)
                    )
            })
            .map(|(i, _)| i as u32)
            .collect();
        Schema {
            template,
            slots,
            at,
        }
    }
}

/// Encodes records, declaring schemas as new shapes appear.
#[derive(Debug, Default)]
pub struct Encoder {
    schemas: Vec<Schema>,
    last: usize,
    started: bool,
    scratch: Vec<u8>,
    /// Memory the schemas hold ([`MAX_SCHEMA_MEMORY`]).
    memory: usize,
}

/// The token range of the top-level `type` value (kept in the template, not a slot).
fn type_range(t: &Tape) -> std::ops::Range<usize> {
    match t.get(0, "type") {
        Some(i) => i..i + t.toks.get(i).map_or(1, Tok::width),
        None => 0..0,
    }
}

/// Builds the template and slot kinds of `v`.
fn shape(v: &Tape) -> Schema {
    let keep = type_range(v);
    // The template's text is the record's: its keys keep their spans, so later records laid
    // out alike compare by span ([`encode`]).
    let mut template = Tape {
        toks: Vec::with_capacity(v.toks.len()),
        text: v.text.clone(),
    };
    let mut slots = Vec::new();
    for (i, t) in v.toks.iter().enumerate() {
        let out = match *t {
            Tok::Key(_) => *t,
            _ if keep.contains(&i) => *t,
            Tok::Str(_) => {
                slots.push(b's');
                Tok::Str(template.push_text(b""))
            }
            Tok::Float(_) | Tok::Text(..) => {
                slots.push(b'f');
                Tok::Int(0)
            }
            Tok::Int(_) => {
                slots.push(b'i');
                Tok::Int(0)
            }
            Tok::UInt(_) => {
                slots.push(b'u');
                Tok::Int(0)
            }
            other => other,
        };
        template.toks.push(out);
    }
    Schema::new(template, slots)
}

/// Writes the slots of `v` against `schema`; false when `v` does not have its shape (then
/// `out` may hold part of it: the caller takes it back).
fn encode(v: &Tape, schema: &Schema, out: &mut Vec<u8>) -> bool {
    let t = &schema.template;
    if v.toks.len() != t.toks.len() {
        return false;
    }
    // A record whose text begins with the template's has its keys where the template has
    // them: equal spans are equal names (one comparison instead of one per key).
    let same_text = v.text.get(..t.text.len()) == Some(&t.text[..]);
    let mut k = 0;
    // The template token the next slot fills (past the end when none is left).
    let mut slot_at = schema.at.first().map_or(usize::MAX, |&a| a as usize);
    for (i, (a, b)) in v.toks.iter().zip(&t.toks).enumerate() {
        let ok = if i == slot_at {
            let ok = match (schema.slots.get(k), a) {
                (Some(b'f'), Tok::Float(x) | Tok::Text(x, _)) => {
                    out.extend_from_slice(&x.to_le_bytes());
                    true
                }
                (Some(b'i'), Tok::Int(x)) => {
                    out.extend_from_slice(&x.to_le_bytes());
                    true
                }
                (Some(b'u'), Tok::UInt(x)) => {
                    out.extend_from_slice(&x.to_le_bytes());
                    true
                }
                (Some(b's'), Tok::Str(x)) => {
                    let bytes = v.bytes(*x);
                    match u32::try_from(bytes.len()) {
                        Ok(len) => {
                            out.extend_from_slice(&len.to_le_bytes());
                            out.extend_from_slice(bytes);
                            true
                        }
                        Err(_) => false,
                    }
                }
                _ => false,
            };
            k += 1;
            slot_at = schema.at.get(k).map_or(usize::MAX, |&a| a as usize);
            ok
        } else {
            // Structure, keys and the `type` value: the template's own.
            match (a, b) {
                (Tok::Key(x), Tok::Key(y)) => (same_text && x == y) || v.bytes(*x) == t.bytes(*y),
                (Tok::Str(x), Tok::Str(y)) => v.bytes(*x) == t.bytes(*y),
                _ => a == b,
            }
        };
        if !ok {
            return false;
        }
    }
    k == schema.slots.len()
}

impl Encoder {
    /// Appends `record` (and, before it, its schema if new) to `out`. Records with
    /// non-finite numbers cannot occur (the readers refuse them).
    pub fn write(&mut self, record: &Tape, out: &mut Vec<u8>) -> Result<(), String> {
        if !self.started {
            out.extend_from_slice(MAGIC);
            self.started = true;
        }
        let order = std::iter::once(self.last).chain(0..self.schemas.len());
        for id in order {
            let Some(schema) = self.schemas.get(id) else {
                continue;
            };
            // Written in place; taken back if the record does not have the schema's shape.
            let mark = out.len();
            out.reserve(5 + 8 * schema.slots.len());
            out.push(b'R');
            out.extend_from_slice(&(id as u32).to_le_bytes());
            if encode(record, schema, out) {
                if let Err(e) = check_strings(record, schema) {
                    out.truncate(mark);
                    return Err(e);
                }
                self.last = id;
                return Ok(());
            }
            out.truncate(mark);
        }
        if self.schemas.len() >= MAX_SCHEMAS {
            return Err(format!(
                "more than {MAX_SCHEMAS} record shapes: use JSON for such a stream"
            ));
        }
        let schema = shape(record);
        check_expansion(&schema.template, &schema.slots, self.schemas.len())?;
        check_strings(record, &schema)?;
        let memory =
            add_schema_memory(self.memory, schema_memory(&schema.template, &schema.slots))?;
        let mut doc = Tape::default();
        let at = doc.open(true);
        doc.key("template");
        doc.copy_value(&schema.template, 0);
        doc.key("slots");
        doc.string(&String::from_utf8_lossy(&schema.slots));
        doc.close(at, 2);
        let mut text = Vec::new();
        json::write_json(&mut text, &doc, 0);
        let len = u32::try_from(text.len())
            .ok()
            .filter(|&l| l <= MAX_SCHEMA_BYTES)
            .ok_or_else(|| {
                format!(
                    "the record's schema would be {} bytes, more than {MAX_SCHEMA_BYTES} bytes \
                     (a record may hold no more: a TriangleMesh wants a smaller tess -s)",
                    text.len()
                )
            })?;
        self.memory = memory;
        out.push(b'S');
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&text);
        self.schemas.push(schema);
        self.last = self.schemas.len() - 1;
        self.scratch.clear();
        if !encode(record, &self.schemas[self.last], &mut self.scratch) {
            return Err("a record does not match its own schema".into());
        }
        out.push(b'R');
        out.extend_from_slice(&(self.last as u32).to_le_bytes());
        out.extend_from_slice(&self.scratch);
        Ok(())
    }
}

/// Checks that a record of `schema` decodes to at most [`MAX_RECORD_BYTES`] of text (its
/// template's and its strings'), as the decoder requires. Only a record whose text is that
/// long can fail, so the count is made for those alone.
fn check_strings(record: &Tape, schema: &Schema) -> Result<(), String> {
    if record.text.len() <= MAX_RECORD_BYTES {
        return Ok(());
    }
    let strings: usize = record
        .toks
        .iter()
        .map(|t| match t {
            Tok::Str(s) => s.len as usize,
            _ => 0,
        })
        .sum();
    let keys = decoded_bytes(&schema.template) - schema.template.toks.len() * TOK_BYTES;
    if strings + keys > MAX_RECORD_BYTES {
        return Err(format!(
            "the record's strings and keys are {} bytes, more than the {MAX_RECORD_BYTES} \
             bytes a record may hold",
            strings + keys
        ));
    }
    Ok(())
}

/// Decodes records; the magic has been consumed by the caller.
#[derive(Debug, Default)]
pub struct Decoder {
    schemas: Vec<Schema>,
    /// Per schema, per slot: how many numeric slots run from it (0 at a string slot), so a
    /// run is read in one call.
    runs: Vec<Vec<usize>>,
    scratch: Vec<u8>,
    /// Memory the schemas hold ([`MAX_SCHEMA_MEMORY`]).
    memory: usize,
}

/// The numeric runs of `slots` (see [`Decoder`]).
fn numeric_runs(slots: &[u8]) -> Vec<usize> {
    let mut runs = vec![0; slots.len()];
    let mut n = 0;
    for (k, s) in slots.iter().enumerate().rev() {
        n = if *s == b's' { 0 } else { n + 1 };
        runs[k] = n;
    }
    runs
}

fn read_exact<R: Read>(r: &mut R, buf: &mut [u8]) -> Result<(), String> {
    r.read_exact(buf).map_err(|e| {
        if e.kind() == std::io::ErrorKind::UnexpectedEof {
            "truncated stream".to_string()
        } else {
            e.to_string()
        }
    })
}

fn read_u32<R: Read>(r: &mut R) -> Result<u32, String> {
    let mut b = [0u8; 4];
    read_exact(r, &mut b)?;
    Ok(u32::from_le_bytes(b))
}

/// Checks the slot kinds against the template: one per number or string outside the `type`
/// value, of a matching kind.
fn check_template(t: &Tape, slots: &[u8]) -> bool {
    let keep = type_range(t);
    let mut k = 0;
    for (i, tok) in t.toks.iter().enumerate() {
        if keep.contains(&i) {
            continue;
        }
        let ok = match tok {
            Tok::Float(_) | Tok::Text(..) | Tok::Int(_) | Tok::UInt(_) => {
                matches!(slots.get(k), Some(b'f' | b'i' | b'u'))
            }
            Tok::Str(_) => slots.get(k) == Some(&b's'),
            _ => continue,
        };
        k += 1;
        if !ok {
            return false;
        }
    }
    k == slots.len()
}

impl Decoder {
    /// Reads the slots of one record of `schema` into `out`: the template copied whole (keys,
    /// structure and the `type` value are its own), then each slot's token set in place.
    fn fill<R: Read>(
        schema: &Schema,
        runs: &[usize],
        scratch: &mut Vec<u8>,
        r: &mut R,
        out: &mut Tape,
    ) -> Result<(), String> {
        let t = &schema.template;
        // The record's text begins with the template's, so keys and the `type` value keep
        // their spans; strings read from slots follow.
        out.text.extend_from_slice(&t.text);
        out.toks.extend_from_slice(&t.toks);
        let n = schema.slots.len();
        let mut k = 0;
        while k < n {
            let (Some(&kind), Some(&at)) = (schema.slots.get(k), schema.at.get(k)) else {
                return Err("schema without a slot's token".into());
            };
            let Some(slot) = out.toks.get_mut(at as usize) else {
                return Err("schema without a slot's token".into());
            };
            if kind == b's' {
                let len = read_u32(r)?;
                if len > MAX_STRING_BYTES {
                    return Err(format!(
                        "string of {len} bytes (at most {MAX_STRING_BYTES})"
                    ));
                }
                if out.text.len() + len as usize > MAX_RECORD_BYTES {
                    return Err(format!(
                        "the record's strings and keys exceed {MAX_RECORD_BYTES} bytes (the \
                         most a record may hold)"
                    ));
                }
                let start = out.text.len();
                out.text.resize(start + len as usize, 0);
                read_exact(r, &mut out.text[start..])?;
                if std::str::from_utf8(&out.text[start..]).is_err() {
                    return Err("string is not UTF-8".into());
                }
                *slot = Tok::Str(crate::tape::Span {
                    start: start as u32,
                    len,
                });
                k += 1;
                continue;
            }
            // A run of numeric slots, read in one call.
            let run = runs.get(k).copied().unwrap_or(1).clamp(1, n - k);
            scratch.resize(8 * run, 0);
            read_exact(r, scratch)?;
            for (j, b) in scratch.chunks_exact(8).enumerate() {
                let mut bytes = [0u8; 8];
                bytes.copy_from_slice(b);
                let tok = match schema.slots.get(k + j) {
                    Some(b'f') => {
                        let f = f64::from_le_bytes(bytes);
                        if !f.is_finite() {
                            return Err(format!("non-finite number {f}"));
                        }
                        Tok::Float(f)
                    }
                    Some(b'i') => Tok::Int(i64::from_le_bytes(bytes)),
                    _ => {
                        let u = u64::from_le_bytes(bytes);
                        // A `u` slot holds what `i64` cannot; keep the tape canonical.
                        i64::try_from(u).map_or(Tok::UInt(u), Tok::Int)
                    }
                };
                let at = schema.at.get(k + j).copied().unwrap_or(u32::MAX) as usize;
                if let Some(slot) = out.toks.get_mut(at) {
                    *slot = tok;
                }
            }
            k += run;
        }
        Ok(())
    }

    /// Reads the next record into `out` (declaring schemas on the way); `Ok(false)` at a
    /// clean end of the stream (between blocks).
    pub fn next_into<R: BufRead>(&mut self, r: &mut R, out: &mut Tape) -> Result<bool, String> {
        loop {
            let mut tag = [0u8; 1];
            match r.read(&mut tag) {
                Ok(0) => return Ok(false),
                Ok(_) => {}
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e.to_string()),
            }
            match tag[0] {
                b'S' => {
                    let len = read_u32(r)?;
                    if len > MAX_SCHEMA_BYTES {
                        return Err(format!(
                            "schema of {len} bytes (at most {MAX_SCHEMA_BYTES})"
                        ));
                    }
                    if self.schemas.len() >= MAX_SCHEMAS {
                        return Err(format!("more than {MAX_SCHEMAS} schemas"));
                    }
                    // Read as it comes (a damaged length allocates no more than is there).
                    let mut b = Vec::new();
                    r.by_ref()
                        .take(u64::from(len))
                        .read_to_end(&mut b)
                        .map_err(|e| e.to_string())?;
                    if b.len() != len as usize {
                        return Err("truncated stream".into());
                    }
                    let mut doc = Tape::default();
                    json::parse_record(&b, &mut doc)
                        .map_err(|e| format!("bad schema: {}", e.message))?;
                    let mut template = Tape::default();
                    match doc.get(0, "template") {
                        Some(i) if matches!(doc.toks.get(i), Some(Tok::Obj { .. })) => {
                            template.copy_value(&doc, i)
                        }
                        _ => {}
                    }
                    let slots = match doc.get(0, "slots").and_then(|i| doc.toks.get(i)) {
                        Some(Tok::Str(s)) => doc.bytes(*s).to_vec(),
                        _ => return Err("schema without a `slots` string".into()),
                    };
                    if template.toks.is_empty() || !check_template(&template, &slots) {
                        return Err(format!(
                            "schema {} does not match its slots",
                            self.schemas.len()
                        ));
                    }
                    check_expansion(&template, &slots, self.schemas.len())?;
                    self.memory = add_schema_memory(self.memory, schema_memory(&template, &slots))?;
                    self.runs.push(numeric_runs(&slots));
                    self.schemas.push(Schema::new(template, slots));
                }
                b'R' => {
                    let id = read_u32(r)? as usize;
                    let schema = self
                        .schemas
                        .get(id)
                        .ok_or_else(|| format!("record of undeclared schema {id}"))?;
                    out.clear();
                    let runs = self.runs.get(id).map_or(&[][..], Vec::as_slice);
                    Self::fill(schema, runs, &mut self.scratch, r, out)?;
                    return Ok(true);
                }
                other => return Err(format!("unknown block tag byte {other:#04x}")),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::Value;

    /// The expansion ([`MAX_EXPANSION`]) of a record: bytes decoded per byte in the stream.
    fn expansion(v: &Value) -> f64 {
        let schema = shape(&Tape::from_value(v));
        decoded_bytes(&schema.template) as f64 / encoded_bytes(&schema.slots) as f64
    }

    /// The pipeline's records (coloured, with their carried fields) expand far less than
    /// [`MAX_EXPANSION`]: a `Triangle` 6.3×, a `TriangleMesh` of `-s 8` 4.0×, a quartic
    /// `BezierTriangle` 4.6× (the figures of [`MAX_EXPANSION`]'s doc); a template of `null`s is
    /// refused by both sides, naming the limit.
    #[test]
    fn pipeline_records_expand_within_the_limit_and_a_template_of_constants_is_refused() {
        /// Margin kept below the limit by every record the pipeline writes.
        const MARGIN: f64 = 4.0;
        let vertex = serde_json::json!({"pos":[0.5,1.0,-2.0],"norm":[0.0,0.6,0.8],"kg":1.5,"color":[0.1,0.2,0.3]});
        let triangle = serde_json::json!({"type":"Triangle","vertex1":vertex,"vertex2":vertex,
            "vertex3":vertex,"face":3,"subpatch":1,"scheme":"shirman-sequin"});
        let n = 45;
        let col3: Vec<Value> = (0..n)
            .map(|_| serde_json::json!([0.5, 1.0, -2.0]))
            .collect();
        let col1: Vec<Value> = (0..n).map(|_| serde_json::json!(1.5)).collect();
        let tris: Vec<Value> = (0..64).map(|_| serde_json::json!([0, 1, 2])).collect();
        let mesh = serde_json::json!({"type":"TriangleMesh","pos":col3,"norm":col3,"kg":col1,
            "triangles":tris,"face":3,"subpatch":1,"scheme":"shirman-sequin","color":col3});
        let points: Vec<Value> = (0..15)
            .map(|_| serde_json::json!([0.5, 1.0, -2.0]))
            .collect();
        let patch = serde_json::json!({"type":"BezierTriangle","degree":4,"points":points,
            "face":3,"subpatch":1,"scheme":"shirman-sequin"});
        let mut seen = Vec::new();
        for r in [&triangle, &mesh, &patch] {
            let x = expansion(r);
            seen.push(format!("{x:.2}"));
            assert!(x * MARGIN < MAX_EXPANSION as f64, "{r}: {x}");
        }
        eprintln!("expansions: {seen:?}");
        let nulls = vec![Value::Null; 1000];
        let hostile = serde_json::json!({"type":"X","a":nulls});
        let mut out = Vec::new();
        let e = Encoder::default()
            .write(&Tape::from_value(&hostile), &mut out)
            .expect_err("refused");
        assert!(e.contains("at most 32 × its size + 1024 bytes"), "{e}");
    }

    #[test]
    fn round_trip_of_mixed_records() {
        let records: Vec<Value> = [
            r#"{"type":"Triangle","vertex1":{"pos":[0.5,1.0,-2.0]},"face":3,"big":18446744073709551615}"#,
            r#"{"type":"Triangle","vertex1":{"pos":[0.25,1.5,-2.5]},"face":-4,"big":18446744073709551614}"#,
            r#"{"type":"BezierTriangle","degree":1,"points":[[0.0,0.0,0.0],[1.0,0.0,0.0],[0.0,1.0,0.0]],"scheme":"flat","ok":true,"n":null}"#,
            r#"{"type":"Triangle","vertex1":{"pos":[1.0,1.0,1.0]},"face":5,"big":7}"#,
        ]
        .iter()
        .map(|s| serde_json::from_str(s).expect("json"))
        .collect();
        let mut enc = Encoder::default();
        let mut bytes = Vec::new();
        for r in &records {
            enc.write(&Tape::from_value(r), &mut bytes)
                .expect("encodes");
        }
        let mut cursor = std::io::Cursor::new(&bytes[MAGIC.len()..]);
        let mut dec = Decoder::default();
        let mut back = Vec::new();
        let mut t = Tape::default();
        while dec.next_into(&mut cursor, &mut t).expect("decodes") {
            back.push(t.to_value());
        }
        assert_eq!(back, records);
        // Every prefix is either a clean end (between blocks) or an error, never a panic.
        for cut in 0..bytes.len() - MAGIC.len() {
            let mut c = std::io::Cursor::new(&bytes[MAGIC.len()..MAGIC.len() + cut]);
            let mut d = Decoder::default();
            while let Ok(true) = d.next_into(&mut c, &mut t) {}
        }
    }
}

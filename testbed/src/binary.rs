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
//! Hostile input: schema texts are at most [`MAX_SCHEMA_BYTES`], strings at most
//! [`MAX_STRING_BYTES`], schemas at most [`MAX_SCHEMAS`]; non-finite floats, unknown tags, a
//! schema number not declared and truncation are errors naming the record.

use std::io::{BufRead, Read};

use serde_json::{Map, Number, Value};

/// The first bytes of a binary stream.
pub const MAGIC: &[u8] = b"TBIN1\n";

/// Largest schema text accepted: a record template is a few hundred bytes; 1 MiB leaves
/// room for any record a filter writes while bounding what a damaged length can allocate.
pub const MAX_SCHEMA_BYTES: u32 = 1 << 20;

/// Largest string slot accepted (16 MiB), for the same reason.
pub const MAX_STRING_BYTES: u32 = 1 << 24;

/// Most schemas in one stream: a stream of one record type needs one; a writer that would
/// need more (every record shaped differently) is better served by JSON.
pub const MAX_SCHEMAS: usize = 1 << 16;

/// One schema: the template and slot kinds.
#[derive(Clone, Debug, PartialEq)]
struct Schema {
    template: Value,
    slots: Vec<u8>,
}

/// Encodes records, declaring schemas as new shapes appear.
#[derive(Debug, Default)]
pub struct Encoder {
    schemas: Vec<Schema>,
    last: usize,
    started: bool,
    scratch: Vec<u8>,
}

/// Builds the template and slot kinds of `v`.
fn shape(v: &Value, top: bool, slots: &mut Vec<u8>) -> Value {
    match v {
        Value::Number(n) => {
            slots.push(if n.is_f64() {
                b'f'
            } else if n.as_i64().is_some() {
                b'i'
            } else {
                b'u'
            });
            Value::from(0)
        }
        Value::String(_) => {
            slots.push(b's');
            Value::String(String::new())
        }
        Value::Array(items) => Value::Array(items.iter().map(|i| shape(i, false, slots)).collect()),
        Value::Object(map) => Value::Object(
            map.iter()
                .map(|(k, v)| {
                    let t = if top && k == "type" {
                        v.clone()
                    } else {
                        shape(v, false, slots)
                    };
                    (k.clone(), t)
                })
                .collect(),
        ),
        other => other.clone(),
    }
}

/// Writes the slots of `v` against `template`; false when `v` does not have its shape.
fn encode(
    v: &Value,
    template: &Value,
    top: bool,
    slots: &[u8],
    k: &mut usize,
    out: &mut Vec<u8>,
) -> bool {
    match (v, template) {
        (Value::Number(n), Value::Number(_)) => {
            let kind = slots.get(*k).copied();
            *k += 1;
            match kind {
                Some(b'f') if n.is_f64() => {
                    out.extend_from_slice(&n.as_f64().unwrap_or_default().to_le_bytes())
                }
                Some(b'i') if !n.is_f64() && n.as_i64().is_some() => {
                    out.extend_from_slice(&n.as_i64().unwrap_or_default().to_le_bytes())
                }
                Some(b'u') if !n.is_f64() && n.as_i64().is_none() => {
                    out.extend_from_slice(&n.as_u64().unwrap_or_default().to_le_bytes())
                }
                _ => return false,
            }
            true
        }
        (Value::String(s), Value::String(_)) => {
            if slots.get(*k) != Some(&b's') {
                return false;
            }
            *k += 1;
            let Ok(len) = u32::try_from(s.len()) else {
                return false;
            };
            out.extend_from_slice(&len.to_le_bytes());
            out.extend_from_slice(s.as_bytes());
            true
        }
        (Value::Array(a), Value::Array(t)) => {
            a.len() == t.len()
                && a.iter()
                    .zip(t)
                    .all(|(x, y)| encode(x, y, false, slots, k, out))
        }
        (Value::Object(a), Value::Object(t)) => {
            a.len() == t.len()
                && a.iter().zip(t).all(|((ka, va), (kt, vt))| {
                    ka == kt
                        && if top && ka == "type" {
                            va == vt
                        } else {
                            encode(va, vt, false, slots, k, out)
                        }
                })
        }
        (a, t) => matches!(a, Value::Null | Value::Bool(_)) && a == t,
    }
}

impl Encoder {
    /// Appends `record` (and, before it, its schema if new) to `out`. Records with
    /// non-finite numbers cannot occur (JSON values hold none).
    pub fn write(&mut self, record: &Value, out: &mut Vec<u8>) -> Result<(), String> {
        if !self.started {
            out.extend_from_slice(MAGIC);
            self.started = true;
        }
        let order = std::iter::once(self.last).chain(0..self.schemas.len());
        for id in order {
            let Some(schema) = self.schemas.get(id) else {
                continue;
            };
            self.scratch.clear();
            let mut k = 0;
            if encode(
                record,
                &schema.template,
                true,
                &schema.slots,
                &mut k,
                &mut self.scratch,
            ) && k == schema.slots.len()
            {
                self.last = id;
                out.push(b'R');
                out.extend_from_slice(&(id as u32).to_le_bytes());
                out.extend_from_slice(&self.scratch);
                return Ok(());
            }
        }
        if self.schemas.len() >= MAX_SCHEMAS {
            return Err(format!(
                "more than {MAX_SCHEMAS} record shapes: use JSON for such a stream"
            ));
        }
        let mut slots = Vec::new();
        let template = shape(record, true, &mut slots);
        let text = serde_json::to_vec(&serde_json::json!({
            "template": template,
            "slots": String::from_utf8_lossy(&slots),
        }))
        .map_err(|e| e.to_string())?;
        out.push(b'S');
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(&text);
        self.schemas.push(Schema { template, slots });
        self.last = self.schemas.len() - 1;
        self.write(record, out)
    }
}

/// Decodes records; the magic has been consumed by the caller.
#[derive(Debug, Default)]
pub struct Decoder {
    schemas: Vec<Schema>,
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

/// Counts the slots a template needs, checking kinds (`None`: inconsistent).
fn check_template(t: &Value, top: bool, slots: &[u8], k: &mut usize) -> bool {
    match t {
        Value::Number(_) => {
            let ok = matches!(slots.get(*k), Some(b'f' | b'i' | b'u'));
            *k += 1;
            ok
        }
        Value::String(_) => {
            let ok = slots.get(*k) == Some(&b's');
            *k += 1;
            ok
        }
        Value::Array(a) => a.iter().all(|x| check_template(x, false, slots, k)),
        Value::Object(m) => m
            .iter()
            .all(|(key, v)| (top && key == "type") || check_template(v, false, slots, k)),
        _ => true,
    }
}

impl Decoder {
    fn fill<R: Read>(
        &self,
        t: &Value,
        top: bool,
        slots: &[u8],
        k: &mut usize,
        r: &mut R,
    ) -> Result<Value, String> {
        Ok(match t {
            Value::Number(_) | Value::String(_) => {
                let kind = slots.get(*k).copied();
                *k += 1;
                if kind == Some(b's') {
                    let len = read_u32(r)?;
                    if len > MAX_STRING_BYTES {
                        return Err(format!(
                            "string of {len} bytes (at most {MAX_STRING_BYTES})"
                        ));
                    }
                    let mut b = vec![0u8; len as usize];
                    read_exact(r, &mut b)?;
                    Value::String(String::from_utf8(b).map_err(|_| "string is not UTF-8")?)
                } else {
                    let mut b = [0u8; 8];
                    read_exact(r, &mut b)?;
                    match kind {
                        Some(b'f') => {
                            let f = f64::from_le_bytes(b);
                            Value::Number(
                                Number::from_f64(f)
                                    .ok_or_else(|| format!("non-finite number {f}"))?,
                            )
                        }
                        Some(b'i') => Value::from(i64::from_le_bytes(b)),
                        _ => Value::from(u64::from_le_bytes(b)),
                    }
                }
            }
            Value::Array(a) => Value::Array(
                a.iter()
                    .map(|x| self.fill(x, false, slots, k, r))
                    .collect::<Result<_, _>>()?,
            ),
            Value::Object(m) => {
                let mut out = Map::with_capacity(m.len());
                for (key, v) in m {
                    let value = if top && key == "type" {
                        v.clone()
                    } else {
                        self.fill(v, false, slots, k, r)?
                    };
                    out.insert(key.clone(), value);
                }
                Value::Object(out)
            }
            other => other.clone(),
        })
    }

    /// Reads the next record (declaring schemas on the way); `Ok(None)` at a clean end of the
    /// stream (between blocks).
    pub fn next<R: BufRead>(&mut self, r: &mut R) -> Result<Option<Value>, String> {
        loop {
            let mut tag = [0u8; 1];
            match r.read(&mut tag) {
                Ok(0) => return Ok(None),
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
                    let mut b = vec![0u8; len as usize];
                    read_exact(r, &mut b)?;
                    let v: Value =
                        serde_json::from_slice(&b).map_err(|e| format!("bad schema: {e}"))?;
                    let template = v.get("template").cloned().unwrap_or(Value::Null);
                    let slots = v
                        .get("slots")
                        .and_then(Value::as_str)
                        .ok_or("schema without a `slots` string")?
                        .as_bytes()
                        .to_vec();
                    let mut k = 0;
                    if !template.is_object()
                        || !check_template(&template, true, &slots, &mut k)
                        || k != slots.len()
                    {
                        return Err(format!(
                            "schema {} does not match its slots",
                            self.schemas.len()
                        ));
                    }
                    self.schemas.push(Schema { template, slots });
                }
                b'R' => {
                    let id = read_u32(r)? as usize;
                    let schema = self
                        .schemas
                        .get(id)
                        .ok_or_else(|| format!("record of undeclared schema {id}"))?;
                    let mut k = 0;
                    return self
                        .fill(&schema.template, true, &schema.slots, &mut k, r)
                        .map(Some);
                }
                other => return Err(format!("unknown block tag byte {other:#04x}")),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
            enc.write(r, &mut bytes).expect("encodes");
        }
        let mut cursor = std::io::Cursor::new(&bytes[MAGIC.len()..]);
        let mut dec = Decoder::default();
        let mut back = Vec::new();
        while let Some(v) = dec.next(&mut cursor).expect("decodes") {
            back.push(v);
        }
        assert_eq!(back, records);
        // Every prefix is either a clean end (between blocks) or an error, never a panic.
        for cut in 0..bytes.len() - MAGIC.len() {
            let mut c = std::io::Cursor::new(&bytes[MAGIC.len()..MAGIC.len() + cut]);
            let mut d = Decoder::default();
            while let Ok(Some(_)) = d.next(&mut c) {}
        }
    }
}

//! The in-memory form of a record: a flat **tape** of tokens over one text buffer.
//!
//! Every reader ([`crate::stream`]) parses a record straight into a [`Tape`] and every writer
//! writes one, so a record costs no allocation per field (the tape's two vectors are reused
//! from record to record) and every field a filter does not use passes through in order,
//! untouched, whatever the formats. Filters read the fields they need into typed structs
//! ([`crate::record`]) and set fields by rewriting the tape ([`Tape::set_vertex_fields`],
//! [`Tape::set_fields`]).
//!
//! Layout: a value is one token (`Float`, `Int`, `UInt`, `Str`, `Bool`, `Null`) or a
//! container token followed by its contents: an object is `Obj { fields, len }` followed by
//! `fields` pairs of a `Key` and a value, an array `Arr { items, len }` followed by `items`
//! values; `len` counts the tokens inside, so a container is skipped in one step. Strings and
//! keys are spans of [`Tape::text`] (decoded, UTF-8). A record's tape holds one object.

use serde_json::{Map, Number, Value};

/// A span of the tape's text: start and length in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Span {
    /// Start.
    pub start: u32,
    /// Length.
    pub len: u32,
}

/// Why a number's text made no token ([`Tape::push_number`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NumberError {
    /// A number too large for an `f64`.
    OutOfRange,
    /// Not a number.
    Malformed,
}

/// One token of a tape (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tok {
    /// An object of `fields` key–value pairs spanning the next `len` tokens.
    Obj {
        /// Number of fields.
        fields: u32,
        /// Tokens inside.
        len: u32,
    },
    /// An array of `items` values spanning the next `len` tokens.
    Arr {
        /// Number of items.
        items: u32,
        /// Tokens inside.
        len: u32,
    },
    /// A field name.
    Key(Span),
    /// A string.
    Str(Span),
    /// A floating-point number (finite).
    Float(f64),
    /// A floating-point number (finite) read from text, with that text (JSON number syntax):
    /// the text writers write it back as it came, so numbers passing through a filter are
    /// neither reformatted nor changed.
    Text(f64, Span),
    /// An integer that fits `i64`.
    Int(i64),
    /// A non-negative integer above `i64::MAX`.
    UInt(u64),
    /// `true` / `false`.
    Bool(bool),
    /// `null` (dstruct `nil`).
    Null,
}

impl Tok {
    /// Tokens this one spans, itself included.
    pub fn width(&self) -> usize {
        match self {
            Tok::Obj { len, .. } | Tok::Arr { len, .. } => *len as usize + 1,
            _ => 1,
        }
    }
}

/// A record as tokens over a text buffer (module docs).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tape {
    /// The tokens.
    pub toks: Vec<Tok>,
    /// Decoded strings and keys.
    pub text: Vec<u8>,
}

/// Most fields [`Tape::set_vertex_fields`] sets at once (the colour filters set two).
const MAX_SET: usize = 4;

/// Largest text a tape may hold (spans are 32-bit): 4 GiB, far beyond any record.
const MAX_TEXT: usize = u32::MAX as usize;

/// Longest record a stream may hold, in bytes as read: a JSON line, a dstruct record from its
/// `(` to its `;`, a binary schema's text, a binary record's strings together (64 MiB). The
/// pipeline's largest honest records are `TriangleMesh`es: at `tess --mesh -s 512` one patch
/// is 24 MB of JSON, so the limit leaves room for them while a line no filter could use (a
/// 300 MB line held 4.3 GB) is refused as it is read, before it is held whole. The writers
/// refuse a record beyond it too, so every stream a filter writes reads back.
pub const MAX_RECORD_BYTES: usize = 64 << 20;

/// Most tokens one record may hold (8 Mi: 192 MiB at [`TOK_BYTES`] each). A token per value,
/// key and container: a `TriangleMesh` of `tess --mesh --kg -s s` coloured by `radial` holds
/// about 11 s² (2.9 M at `-s 512`), so meshes reach [`MAX_RECORD_BYTES`] of JSON (near `-s
/// 780`) before this; the cap bounds what a line of [`MAX_RECORD_BYTES`] can hold in memory
/// where its values are one or two bytes each (`[0,0,0,…]` would otherwise be 32 M tokens,
/// 768 MiB).
pub const MAX_RECORD_TOKENS: usize = 1 << 23;

/// Bytes of one token in memory (the estimate [`Tape::heap_bytes`] and the binary form's
/// expansion check use).
pub const TOK_BYTES: usize = std::mem::size_of::<Tok>();

/// The message of a record over [`MAX_RECORD_TOKENS`].
pub fn too_many_tokens() -> String {
    format!(
        "more than {MAX_RECORD_TOKENS} values, keys and containers in one record (the most a \
         record may hold: {} MiB in memory)",
        (MAX_RECORD_TOKENS * TOK_BYTES) >> 20
    )
}

/// Objects with more keys than this are checked for duplicate names with a hash set instead
/// of a linear scan (records have about ten).
const LINEAR_DUPLICATE_SCAN: usize = 16;

impl Tape {
    /// True when `name` equals one of the `n` keys already read into the object whose first key
    /// token is at `first` (every value before is complete, so the scan can skip them). Up to
    /// `LINEAR_DUPLICATE_SCAN` keys a linear scan; past it a set, built once into `many` from
    /// the keys so far and kept for the object's later keys (`name` is added to it). The one
    /// check of both text readers.
    pub fn duplicate_key(
        &self,
        first: usize,
        n: usize,
        name: &[u8],
        many: &mut Option<std::collections::HashSet<Vec<u8>>>,
    ) -> bool {
        let keys = || {
            let mut j = first;
            (0..n).filter_map(move |_| {
                let key = match self.toks.get(j) {
                    Some(Tok::Key(s)) => Some(self.bytes(*s)),
                    _ => None,
                };
                j += 1 + self.toks.get(j + 1).map_or(1, Tok::width);
                key
            })
        };
        if n < LINEAR_DUPLICATE_SCAN {
            return keys().any(|k| k == name);
        }
        let set = many.get_or_insert_with(|| keys().map(<[u8]>::to_vec).collect());
        !set.insert(name.to_vec())
    }

    /// The memory the tape holds (its tokens' and text's storage, as allocated): the estimate
    /// a filter holding records counts against its budget.
    pub fn heap_bytes(&self) -> usize {
        self.toks.capacity() * TOK_BYTES + self.text.capacity()
    }

    /// Empties the tape, keeping its storage.
    pub fn clear(&mut self) {
        self.toks.clear();
        self.text.clear();
    }

    /// Pushes the number written `text` (a reader's token, sign and digits checked by its
    /// grammar): an `Int` or `UInt` when `integral` and it fits, else a finite float — a
    /// `Text` token keeping `text` to be written back as it came when `keep_text`, a `Float`
    /// otherwise. Nothing is pushed on an error.
    pub fn push_number(
        &mut self,
        text: &str,
        integral: bool,
        keep_text: bool,
    ) -> Result<(), NumberError> {
        if integral {
            if let Ok(v) = text.parse::<i64>() {
                self.toks.push(Tok::Int(v));
                return Ok(());
            }
            if let Ok(v) = text.parse::<u64>() {
                self.toks.push(Tok::UInt(v));
                return Ok(());
            }
        }
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => {
                if keep_text {
                    let span = self.push_text(text.as_bytes());
                    self.toks.push(Tok::Text(v, span));
                } else {
                    self.toks.push(Tok::Float(v));
                }
                Ok(())
            }
            Ok(_) => Err(NumberError::OutOfRange),
            Err(_) => Err(NumberError::Malformed),
        }
    }

    /// Appends `s` to the text; its span.
    pub fn push_text(&mut self, s: &[u8]) -> Span {
        let start = self.text.len().min(MAX_TEXT) as u32;
        self.text.extend_from_slice(s);
        Span {
            start,
            len: s.len().min(MAX_TEXT) as u32,
        }
    }

    /// The bytes of a span (empty if it lies outside the text).
    pub fn bytes(&self, s: Span) -> &[u8] {
        let a = s.start as usize;
        self.text.get(a..a + s.len as usize).unwrap_or_default()
    }

    /// The string of a span (empty if not UTF-8, which readers never store).
    pub fn str(&self, s: Span) -> &str {
        std::str::from_utf8(self.bytes(s)).unwrap_or_default()
    }

    /// Appends a key token.
    pub fn key(&mut self, k: &str) {
        let s = self.push_text(k.as_bytes());
        self.toks.push(Tok::Key(s));
    }

    /// Appends a string token.
    pub fn string(&mut self, v: &str) {
        let s = self.push_text(v.as_bytes());
        self.toks.push(Tok::Str(s));
    }

    /// Opens a container: pushes a placeholder; close it with [`Tape::close`].
    pub fn open(&mut self, object: bool) -> usize {
        self.toks.push(if object {
            Tok::Obj { fields: 0, len: 0 }
        } else {
            Tok::Arr { items: 0, len: 0 }
        });
        self.toks.len() - 1
    }

    /// Closes the container opened at `at` with `count` fields or items.
    pub fn close(&mut self, at: usize, count: usize) {
        let len = (self.toks.len() - at - 1) as u32;
        if let Some(t) = self.toks.get_mut(at) {
            *t = match t {
                Tok::Obj { .. } => Tok::Obj {
                    fields: count as u32,
                    len,
                },
                _ => Tok::Arr {
                    items: count as u32,
                    len,
                },
            };
        }
    }

    /// Appends `[x, y, z]` of floats.
    pub fn floats(&mut self, xs: &[f64]) {
        self.toks.push(Tok::Arr {
            items: xs.len() as u32,
            len: xs.len() as u32,
        });
        self.toks.extend(xs.iter().map(|&x| Tok::Float(x)));
    }

    /// The fields of the object at token `at`: `(key, index of the value token)`.
    pub fn fields(&self, at: usize) -> Fields<'_> {
        let (n, start) = match self.toks.get(at) {
            Some(Tok::Obj { fields, .. }) => (*fields as usize, at + 1),
            _ => (0, at + 1),
        };
        Fields {
            tape: self,
            left: n,
            i: start,
        }
    }

    /// The value token of field `name` of the object at `at`.
    pub fn get(&self, at: usize, name: &str) -> Option<usize> {
        let name = name.as_bytes();
        self.fields(at).find(|(k, _)| *k == name).map(|(_, v)| v)
    }

    /// The items of the array at `at` (token indices), `None` if not an array.
    pub fn items(&self, at: usize) -> Option<Items<'_>> {
        match self.toks.get(at) {
            Some(Tok::Arr { items, .. }) => Some(Items {
                tape: self,
                left: *items as usize,
                i: at + 1,
            }),
            _ => None,
        }
    }

    /// The record's `type` (empty when absent or not a string).
    pub fn kind(&self) -> &str {
        match self.get(0, "type").and_then(|i| self.toks.get(i)) {
            Some(Tok::Str(s)) => self.str(*s),
            _ => "",
        }
    }

    /// The number at token `at`, as `f64`.
    pub fn number(&self, at: usize) -> Option<f64> {
        match self.toks.get(at)? {
            Tok::Float(x) | Tok::Text(x, _) => Some(*x),
            Tok::Int(x) => Some(*x as f64),
            Tok::UInt(x) => Some(*x as f64),
            _ => None,
        }
    }

    /// Copies the value at `at` of `src` (tokens and text) to the end of this tape.
    pub fn copy_value(&mut self, src: &Tape, at: usize) {
        let w = src.toks.get(at).map_or(0, Tok::width);
        for t in src.toks.get(at..at + w).unwrap_or_default() {
            let t = self.remap(t, src);
            self.toks.push(t);
        }
    }

    /// Token `t` of `src` with its text (if any) copied into this tape.
    pub fn remap(&mut self, t: &Tok, src: &Tape) -> Tok {
        match *t {
            Tok::Key(s) => Tok::Key(self.push_text(src.bytes(s))),
            Tok::Str(s) => Tok::Str(self.push_text(src.bytes(s))),
            Tok::Text(x, s) => Tok::Text(x, self.push_text(src.bytes(s))),
            other => other,
        }
    }

    /// Appends the object at token `at` to `out` with its fields `names` set to the values
    /// built by `value(i, out)` (`i` the name's index): in place when present, appended after
    /// the last field (with key `spans[i]`) otherwise; every other field copied whole, in order.
    fn rebuild_object(
        &self,
        at: usize,
        names: &[&str],
        spans: &[Span],
        out: &mut Vec<Tok>,
        value: &mut dyn FnMut(usize, &mut Vec<Tok>),
    ) {
        let obj = out.len();
        out.push(Tok::Obj { fields: 0, len: 0 });
        let mut set = [false; MAX_SET];
        let mut count = 0u32;
        for (key, v) in self.fields(at) {
            let Some(Tok::Key(span)) = v.checked_sub(1).and_then(|k| self.toks.get(k)) else {
                continue;
            };
            count += 1;
            out.push(Tok::Key(*span));
            match names.iter().position(|n| n.as_bytes() == key) {
                Some(ni) if !set[ni] => {
                    set[ni] = true;
                    value(ni, out);
                }
                _ => {
                    let w = self.toks[v].width();
                    out.extend_from_slice(&self.toks[v..v + w]);
                }
            }
        }
        for (ni, span) in spans.iter().enumerate() {
            if !set[ni] {
                count += 1;
                out.push(Tok::Key(*span));
                value(ni, out);
            }
        }
        let len = (out.len() - obj - 1) as u32;
        out[obj] = Tok::Obj { fields: count, len };
    }

    /// Sets field `name` of every vertex object (`vertex1` … `vertex3`) to the value built
    /// by `value(i, tape)` (`i` the vertex): in place when present, appended otherwise; every
    /// other token is kept in order. `scratch` is reused storage. False when a vertex field is
    /// not an object or more than four names are given (the tape is then unchanged).
    pub fn set_vertex_fields(
        &mut self,
        names: &[&str],
        scratch: &mut Vec<Tok>,
        value: &mut dyn FnMut(usize, usize, &mut Vec<Tok>),
    ) -> bool {
        if names.len() > MAX_SET {
            return false;
        }
        let vertex_at = crate::record::VERTEX_FIELDS.map(|v| self.get(0, v));
        if vertex_at
            .iter()
            .any(|v| !matches!(v.and_then(|i| self.toks.get(i)), Some(Tok::Obj { .. })))
        {
            return false;
        }
        // Keys to append are written to the text once.
        let mut name_spans = Vec::with_capacity(names.len());
        for n in names {
            name_spans.push(self.push_text(n.as_bytes()));
        }
        scratch.clear();
        let mut i = 0;
        let end = self.toks.len();
        while i < end {
            let vi = vertex_at.iter().position(|v| *v == Some(i));
            let Some(vi) = vi else {
                scratch.push(self.toks[i]);
                i += 1;
                continue;
            };
            self.rebuild_object(i, names, &name_spans, scratch, &mut |ni, out| {
                value(vi, ni, out)
            });
            i += self.toks[i].width();
        }
        // Only the record's own length changed: the vertex objects were rebuilt with theirs,
        // everything else copied whole.
        let total = scratch.len().saturating_sub(1) as u32;
        if let Some(Tok::Obj { len, .. }) = scratch.first_mut() {
            *len = total;
        }
        std::mem::swap(&mut self.toks, scratch);
        true
    }

    /// Sets the record's top-level fields `names` to the values built by `value(i, out)` (`i`
    /// the name's index): in place when present, appended after the last field otherwise;
    /// every other token is kept in order. `scratch` is reused storage. False when the tape
    /// is not an object or more than four names are given (the tape is then unchanged). The
    /// colour filters' way to set a `TriangleMesh`'s `color` and `dist` columns.
    pub fn set_fields(
        &mut self,
        names: &[&str],
        scratch: &mut Vec<Tok>,
        value: &mut dyn FnMut(usize, &mut Vec<Tok>),
    ) -> bool {
        if names.len() > MAX_SET || !matches!(self.toks.first(), Some(Tok::Obj { .. })) {
            return false;
        }
        // Keys to append are written to the text once (no allocation per record).
        let mut spans = [Span { start: 0, len: 0 }; MAX_SET];
        for (span, n) in spans.iter_mut().zip(names) {
            *span = self.push_text(n.as_bytes());
        }
        scratch.clear();
        self.rebuild_object(0, names, &spans[..names.len()], scratch, value);
        std::mem::swap(&mut self.toks, scratch);
        true
    }

    /// The tape as a JSON value (for tests and the slow paths).
    pub fn to_value(&self) -> Value {
        self.value_at(0).0
    }

    /// The value at token `at` as a JSON value (messages, slow paths).
    pub fn value(&self, at: usize) -> Value {
        self.value_at(at).0
    }

    fn value_at(&self, at: usize) -> (Value, usize) {
        let Some(t) = self.toks.get(at) else {
            return (Value::Null, at + 1);
        };
        match *t {
            Tok::Obj { fields, .. } => {
                let mut m = Map::new();
                let mut i = at + 1;
                for _ in 0..fields {
                    let k = match self.toks.get(i) {
                        Some(Tok::Key(s)) => self.str(*s).to_string(),
                        _ => String::new(),
                    };
                    let (v, next) = self.value_at(i + 1);
                    m.insert(k, v);
                    i = next;
                }
                (Value::Object(m), i)
            }
            Tok::Arr { items, .. } => {
                let mut a = Vec::with_capacity(items as usize);
                let mut i = at + 1;
                for _ in 0..items {
                    let (v, next) = self.value_at(i);
                    a.push(v);
                    i = next;
                }
                (Value::Array(a), i)
            }
            Tok::Key(s) | Tok::Str(s) => (Value::String(self.str(s).to_string()), at + 1),
            Tok::Float(x) | Tok::Text(x, _) => (
                Number::from_f64(x).map_or(Value::Null, Value::Number),
                at + 1,
            ),
            Tok::Int(x) => (Value::from(x), at + 1),
            Tok::UInt(x) => (Value::from(x), at + 1),
            Tok::Bool(b) => (Value::Bool(b), at + 1),
            Tok::Null => (Value::Null, at + 1),
        }
    }

    /// A tape from a JSON value (the writers of values use it).
    pub fn from_value(v: &Value) -> Tape {
        let mut t = Tape::default();
        t.push_value(v);
        t
    }

    /// Appends a JSON value.
    pub fn push_value(&mut self, v: &Value) {
        match v {
            Value::Null => self.toks.push(Tok::Null),
            Value::Bool(b) => self.toks.push(Tok::Bool(*b)),
            Value::Number(n) => self.toks.push(number_tok(n)),
            Value::String(s) => self.string(s),
            Value::Array(a) => {
                let at = self.open(false);
                for x in a {
                    self.push_value(x);
                }
                self.close(at, a.len());
            }
            Value::Object(m) => {
                let at = self.open(true);
                for (k, x) in m {
                    self.key(k);
                    self.push_value(x);
                }
                self.close(at, m.len());
            }
        }
    }
}

/// The token of a JSON number: integers that fit `i64` as `Int`, larger ones `UInt`, the rest
/// `Float` (the binary format's slot kinds follow this).
pub fn number_tok(n: &Number) -> Tok {
    if let Some(i) = n.as_i64() {
        Tok::Int(i)
    } else if let Some(u) = n.as_u64() {
        Tok::UInt(u)
    } else {
        Tok::Float(n.as_f64().unwrap_or_default())
    }
}

/// Iterator over an object's fields: `(key bytes, value token index)`.
pub struct Fields<'a> {
    tape: &'a Tape,
    left: usize,
    i: usize,
}

impl<'a> Iterator for Fields<'a> {
    type Item = (&'a [u8], usize);
    fn next(&mut self) -> Option<Self::Item> {
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        let key = match self.tape.toks.get(self.i)? {
            Tok::Key(s) => self.tape.bytes(*s),
            _ => b"",
        };
        let v = self.i + 1;
        self.i = v + self.tape.toks.get(v)?.width();
        Some((key, v))
    }
}

/// Iterator over an array's items (token indices).
pub struct Items<'a> {
    tape: &'a Tape,
    left: usize,
    i: usize,
}

impl Iterator for Items<'_> {
    type Item = usize;
    fn next(&mut self) -> Option<usize> {
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        let v = self.i;
        self.i = v + self.tape.toks.get(v)?.width();
        Some(v)
    }
}

impl Items<'_> {
    /// Items left.
    pub fn len(&self) -> usize {
        self.left
    }

    /// True when no items are left.
    pub fn is_empty(&self) -> bool {
        self.left == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_round_trip_and_vertex_fields_are_set_in_place_or_appended() {
        let v: Value = serde_json::from_str(
            r#"{"type":"Triangle","vertex1":{"pos":[1,2,3],"color":[0,0,0]},"vertex2":{"pos":[1.5,2,3]},"vertex3":{"pos":[0,0,0],"x":{"y":[1,[2]]}},"provenance":"p"}"#,
        )
        .expect("json");
        let mut t = Tape::from_value(&v);
        assert_eq!(t.to_value(), v);
        assert_eq!(t.kind(), "Triangle");
        let mut scratch = Vec::new();
        assert!(
            t.set_vertex_fields(&["color"], &mut scratch, &mut |vi, _, out| {
                out.push(Tok::Arr { items: 1, len: 1 });
                out.push(Tok::Int(vi as i64));
            })
        );
        let back = t.to_value();
        assert_eq!(back["vertex1"]["color"], serde_json::json!([0]));
        assert_eq!(back["vertex2"]["color"], serde_json::json!([1]));
        assert_eq!(back["vertex3"]["x"], v["vertex3"]["x"]);
        let keys: Vec<&String> = back["vertex3"].as_object().expect("obj").keys().collect();
        assert_eq!(keys, ["pos", "x", "color"]);
        assert_eq!(back["provenance"], "p");
        // Lengths stay consistent: the last field is found by skipping.
        assert!(t.get(0, "provenance").is_some());
    }

    #[test]
    fn record_fields_are_set_in_place_or_appended() {
        let v: Value = serde_json::from_str(
            r#"{"type":"TriangleMesh","color":[[0,0,0]],"pos":[[1,2,3]],"x":{"y":[1,[2]]}}"#,
        )
        .expect("json");
        let mut t = Tape::from_value(&v);
        let mut scratch = Vec::new();
        assert!(
            t.set_fields(&["color", "dist"], &mut scratch, &mut |ni, out| {
                out.push(Tok::Arr { items: 2, len: 2 });
                out.push(Tok::Int(ni as i64));
                out.push(Tok::Float(0.5));
            })
        );
        let back = t.to_value();
        let keys: Vec<&String> = back.as_object().expect("obj").keys().collect();
        assert_eq!(keys, ["type", "color", "pos", "x", "dist"]);
        assert_eq!(back["color"], serde_json::json!([0, 0.5]));
        assert_eq!(back["dist"], serde_json::json!([1, 0.5]));
        assert_eq!(back["x"], v["x"]);
        assert_eq!(back["pos"], v["pos"]);
        // The tokens are consistent: a round trip through a value gives the same tape.
        assert_eq!(Tape::from_value(&back).to_value(), back);
        assert!(t.get(0, "dist").is_some());
        let five = ["a", "b", "c", "d", "e"];
        assert!(!t.set_fields(&five, &mut scratch, &mut |_, out| out.push(Tok::Null)));
        assert_eq!(t.to_value(), back);
    }
}

//! The testbed's dstruct external format (Lounsbery et al. 1990, §2.2 and Figure 1), read and
//! written.
//!
//! # Grammar
//!
//! ```text
//! record := pair ';'
//! pair   := '(' name '.' value ')'
//! name   := identifier | string                 identifier: [A-Za-z_][A-Za-z0-9_-]*
//! value  := number | string | array | pair pair* | '(' ')' | true | false | nil
//! array  := '[' ']' | '[' value (',' value)* ']'
//! ```
//!
//! Strings are in double quotes with JSON's escapes; numbers are decimal (`-1`, `0.5`,
//! `1e-3`); `%` starts a comment to the end of the line (as in the `.m` mesh files); white
//! space is free. `()` (the empty list), `true`, `false` and `nil` are this implementation's
//! additions, so that every JSON record has a dstruct form.
//!
//! # Mapping to JSON records
//!
//! The in-memory record is a [`Tape`] holding one object (order preserved). A record
//! `(Name . (a . 1) (b . "x"));` is the object `{"type": "Name", "a": 1, "b": "x"}`: the
//! outer pair's name is the `type`, its list of pairs the remaining fields in order. A list of
//! pairs is an object, an array an array, a number a number (integers stay integers), `nil`
//! is `null`. A field name that is not an identifier is written as a string. Duplicate names in
//! one list are an error (an object cannot hold them).
//!
//! Nesting is limited to [`MAX_DEPTH`] levels, so hostile input cannot overflow the stack; a
//! record's tokens to [`MAX_RECORD_TOKENS`] (its length, [`crate::tape::MAX_RECORD_BYTES`], is
//! the stream reader's to check: [`crate::stream`]).

use crate::json;
use crate::tape::{NumberError, Span, Tape, Tok, MAX_RECORD_TOKENS};

/// Deepest nesting of lists and arrays accepted: far above any record of the pipeline (a
/// Triangle nests 3 levels), low enough that recursion cannot exhaust the stack (JSON's reader
/// stops at 128).
pub const MAX_DEPTH: usize = 100;

/// A syntax error inside one record: byte offset into the record text and message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SyntaxError {
    /// Byte offset into the record's text.
    pub offset: usize,
    /// What was expected or found.
    pub message: String,
}

/// The parser; `COUNT`: whether the record's tokens are counted ([`MAX_RECORD_TOKENS`]; only a
/// record that could exceed it is, [`parse_record`]).
struct Parser<'a, 't, const COUNT: bool> {
    /// The record when it is UTF-8 throughout (checked once; any ASCII position is then a
    /// character boundary); `None` when some byte is not (in a comment, say): then strings
    /// are checked one by one.
    src: Option<&'a str>,
    s: &'a [u8],
    i: usize,
    depth: usize,
    tape: &'t mut Tape,
}

fn is_ident_start(c: u8) -> bool {
    c.is_ascii_alphabetic() || c == b'_'
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_' || c == b'-'
}

impl<const COUNT: bool> Parser<'_, '_, COUNT> {
    fn err<T>(&self, message: impl Into<String>) -> Result<T, SyntaxError> {
        Err(SyntaxError {
            offset: self.i,
            message: message.into(),
        })
    }

    fn skip_ws(&mut self) {
        while let Some(&c) = self.s.get(self.i) {
            if c == b'%' {
                while let Some(&d) = self.s.get(self.i) {
                    if d == b'\n' {
                        break;
                    }
                    self.i += 1;
                }
            } else if c.is_ascii_whitespace() {
                self.i += 1;
            } else {
                break;
            }
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.s.get(self.i).copied()
    }

    fn expect(&mut self, c: u8) -> Result<(), SyntaxError> {
        match self.peek() {
            Some(d) if d == c => {
                self.i += 1;
                Ok(())
            }
            Some(d) => self.err(format!("expected `{}`, found `{}`", c as char, d as char)),
            None => self.err(format!("expected `{}`, found the end", c as char)),
        }
    }

    /// Refuses a record past [`MAX_RECORD_TOKENS`] (checked after each pair and item: only
    /// lists and arrays grow a record by more than a token, and their own items are checked).
    #[inline(always)]
    fn count(&self) -> Result<(), SyntaxError> {
        if COUNT && self.tape.toks.len() > MAX_RECORD_TOKENS {
            return self.too_many();
        }
        Ok(())
    }

    /// The error of [`Self::count`], out of the parser's way.
    #[cold]
    #[inline(never)]
    fn too_many(&self) -> Result<(), SyntaxError> {
        self.err(crate::tape::too_many_tokens())
    }

    fn enter(&mut self) -> Result<(), SyntaxError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return self.err(format!("nested deeper than {MAX_DEPTH} levels"));
        }
        Ok(())
    }

    /// A string (the opening quote next), decoded into the tape's text.
    fn string(&mut self) -> Result<Span, SyntaxError> {
        let start = self.i;
        self.i += 1; // the opening quote
        let mut escaped = false;
        loop {
            match self.s.get(self.i) {
                None => {
                    self.i = start;
                    return self.err("unterminated string");
                }
                Some(b'\\') => {
                    escaped = true;
                    self.i += 2;
                }
                Some(b'"') => {
                    self.i += 1;
                    break;
                }
                Some(_) => self.i += 1,
            }
        }
        let text = self.s.get(start..self.i).unwrap_or_default();
        let inner = text
            .get(1..text.len().saturating_sub(1))
            .unwrap_or_default();
        if !escaped
            && inner.iter().all(|&c| c >= 0x20)
            && (self.src.is_some() || std::str::from_utf8(inner).is_ok())
        {
            return Ok(self.tape.push_text(inner));
        }
        match serde_json::from_slice::<String>(text) {
            Ok(s) => Ok(self.tape.push_text(s.as_bytes())),
            Err(e) => {
                self.i = start;
                self.err(format!("bad string: {e}"))
            }
        }
    }

    fn identifier(&mut self) -> Span {
        let start = self.i;
        while self.s.get(self.i).copied().is_some_and(is_ident) {
            self.i += 1;
        }
        // Identifiers are ASCII by construction.
        let bytes = self.s.get(start..self.i).unwrap_or_default();
        self.tape.push_text(bytes)
    }

    fn name(&mut self) -> Result<Span, SyntaxError> {
        match self.peek() {
            Some(b'"') => self.string(),
            Some(c) if is_ident_start(c) => Ok(self.identifier()),
            Some(c) => self.err(format!("expected a field name, found `{}`", c as char)),
            None => self.err("expected a field name, found the end"),
        }
    }

    fn number(&mut self) -> Result<(), SyntaxError> {
        let start = self.i;
        let mut float = false;
        while let Some(&c) = self.s.get(self.i) {
            match c {
                b'0'..=b'9' | b'+' | b'-' => {}
                b'.' | b'e' | b'E' => float = true,
                _ => break,
            }
            self.i += 1;
        }
        let bytes = self.s.get(start..self.i).unwrap_or_default();
        // Digits, signs, `.`, `e`: ASCII.
        let text = match self.src {
            Some(src) => src.get(start..self.i).unwrap_or_default(),
            None => std::str::from_utf8(bytes).unwrap_or_default(),
        };
        let text = text.strip_prefix('+').unwrap_or(text);
        // Text in JSON's grammar is kept to be written back as it came.
        let keep = json::is_json_number(text.as_bytes());
        self.tape.push_number(text, !float, keep).or_else(|e| {
            self.i = start;
            self.err(match e {
                NumberError::OutOfRange => format!("number `{text}` is out of range"),
                NumberError::Malformed => format!("bad number `{text}`"),
            })
        })
    }

    /// One or more pairs, the first `(` next: an object (its token at `obj`, `first` fields
    /// already in it).
    fn pairs(&mut self, obj: usize, first: usize) -> Result<usize, SyntaxError> {
        let mut n = first;
        let mut many: Option<std::collections::HashSet<Vec<u8>>> = None;
        while self.peek() == Some(b'(') {
            let at = self.i;
            self.i += 1;
            let k = self.name()?;
            let name = self.tape.bytes(k);
            let dup = self.tape.duplicate_key(obj + 1, n, name, &mut many);
            if dup {
                let name = String::from_utf8_lossy(name).into_owned();
                self.i = at;
                return self.err(format!("duplicate field `{name}`"));
            }
            self.tape.toks.push(Tok::Key(k));
            self.expect(b'.')?;
            self.value()?;
            self.count()?;
            self.expect(b')')?;
            n += 1;
        }
        Ok(n)
    }

    fn value(&mut self) -> Result<(), SyntaxError> {
        match self.peek() {
            Some(b'"') => {
                let s = self.string()?;
                self.tape.toks.push(Tok::Str(s));
                Ok(())
            }
            Some(b'[') => self.array(),
            Some(b'(') => {
                // `()` is the empty list; otherwise a list of pairs.
                let save = self.i;
                self.i += 1;
                if self.peek() == Some(b')') {
                    self.i += 1;
                    self.tape.toks.push(Tok::Obj { fields: 0, len: 0 });
                    return Ok(());
                }
                self.i = save;
                self.enter()?;
                let obj = self.tape.open(true);
                let n = self.pairs(obj, 0)?;
                self.tape.close(obj, n);
                self.depth -= 1;
                Ok(())
            }
            Some(c) if c.is_ascii_digit() || c == b'-' || c == b'+' || c == b'.' => self.number(),
            Some(c) if is_ident_start(c) => {
                let at = self.i;
                let start = self.i;
                while self.s.get(self.i).copied().is_some_and(is_ident) {
                    self.i += 1;
                }
                match self.s.get(start..self.i).unwrap_or_default() {
                    b"true" => self.tape.toks.push(Tok::Bool(true)),
                    b"false" => self.tape.toks.push(Tok::Bool(false)),
                    b"nil" => self.tape.toks.push(Tok::Null),
                    other => {
                        let other = String::from_utf8_lossy(other).into_owned();
                        self.i = at;
                        return self.err(format!(
                            "unexpected word `{other}` (strings need double quotes)"
                        ));
                    }
                }
                Ok(())
            }
            Some(c) => self.err(format!("expected a value, found `{}`", c as char)),
            None => self.err("expected a value, found the end"),
        }
    }

    fn array(&mut self) -> Result<(), SyntaxError> {
        self.enter()?;
        self.i += 1; // '['
        let at = self.tape.open(false);
        let mut n = 0;
        if self.peek() == Some(b']') {
            self.i += 1;
        } else {
            loop {
                self.value()?;
                self.count()?;
                n += 1;
                match self.peek() {
                    Some(b',') => self.i += 1,
                    Some(b']') => {
                        self.i += 1;
                        break;
                    }
                    Some(c) => {
                        return self.err(format!("expected `,` or `]`, found `{}`", c as char))
                    }
                    None => return self.err("unterminated array"),
                }
            }
        }
        self.tape.close(at, n);
        self.depth -= 1;
        Ok(())
    }
}

/// Parses one record's text (`(Name . …);`, the semicolon optional at the very end) into
/// `tape` (cleared first): an object whose first field is `type`. Every token but the `type`
/// key takes at least one byte of the text, so a record shorter than [`MAX_RECORD_TOKENS`]
/// bytes cannot exceed it and is parsed without counting.
pub fn parse_record(text: &[u8], tape: &mut Tape) -> Result<(), SyntaxError> {
    if text.len() < MAX_RECORD_TOKENS {
        parse::<false>(text, tape)
    } else {
        parse::<true>(text, tape)
    }
}

fn parse<const COUNT: bool>(text: &[u8], tape: &mut Tape) -> Result<(), SyntaxError> {
    tape.clear();
    let src = std::str::from_utf8(text).ok();
    let mut p = Parser::<COUNT> {
        src,
        s: text,
        i: 0,
        depth: 0,
        tape,
    };
    if p.peek() != Some(b'(') {
        return match p.peek() {
            Some(c) => p.err(format!("a record starts with `(`, found `{}`", c as char)),
            None => p.err("empty record"),
        };
    }
    p.enter()?;
    p.i += 1;
    let obj = p.tape.open(true);
    p.tape.key("type");
    let name = p.name()?;
    p.tape.toks.push(Tok::Str(name));
    p.expect(b'.')?;
    // The value: a list of pairs (or `()`).
    match p.peek() {
        Some(b'(') => {
            let save = p.i;
            p.i += 1;
            let n = if p.peek() == Some(b')') {
                p.i += 1;
                1
            } else {
                p.i = save;
                p.pairs(obj, 1).map_err(|e| {
                    if e.message == "duplicate field `type`" {
                        SyntaxError {
                            offset: e.offset,
                            message: "a record's fields cannot be named `type` (it holds the name)"
                                .into(),
                        }
                    } else {
                        e
                    }
                })?
            };
            p.tape.close(obj, n);
        }
        _ => return p.err("a record's value must be a list of `(name . value)` pairs"),
    }
    p.expect(b')')?;
    match p.peek() {
        Some(b';') => p.i += 1,
        None => {}
        Some(c) => {
            return p.err(format!(
                "expected `;` after the record, found `{}`",
                c as char
            ))
        }
    }
    if let Some(c) = p.peek() {
        return p.err(format!("text after the record's `;`: `{}`", c as char));
    }
    Ok(())
}

fn write_name(out: &mut Vec<u8>, name: &[u8]) {
    let plain = name.first().copied().is_some_and(is_ident_start)
        && name.iter().copied().all(is_ident)
        && !matches!(name, b"true" | b"false" | b"nil");
    if plain {
        out.extend_from_slice(name);
    } else {
        // JSON's escaping is the dstruct reader's.
        json::write_string(out, name);
    }
}

/// Appends the value at `at`; the index after it.
fn write_value(out: &mut Vec<u8>, tape: &Tape, at: usize, ryu: &mut ryu::Buffer) -> usize {
    let Some(t) = tape.toks.get(at) else {
        return at + 1;
    };
    match *t {
        Tok::Null => {
            out.extend_from_slice(b"nil");
            at + 1
        }
        Tok::Str(s) | Tok::Key(s) => {
            json::write_string(out, tape.bytes(s));
            at + 1
        }
        Tok::Arr { items, .. } => {
            out.push(b'[');
            let mut i = at + 1;
            for k in 0..items {
                if k > 0 {
                    out.extend_from_slice(b", ");
                }
                i = write_value(out, tape, i, ryu);
            }
            out.push(b']');
            i
        }
        Tok::Obj { fields: 0, .. } => {
            out.extend_from_slice(b"()");
            at + 1
        }
        Tok::Obj { fields, .. } => {
            let mut i = at + 1;
            for k in 0..fields {
                if k > 0 {
                    out.push(b' ');
                }
                out.push(b'(');
                if let Some(Tok::Key(s)) = tape.toks.get(i) {
                    write_name(out, tape.bytes(*s));
                }
                out.extend_from_slice(b" . ");
                i = write_value(out, tape, i + 1, ryu);
                out.push(b')');
            }
            i
        }
        other => {
            json::write_scalar(out, &other, tape, ryu);
            at + 1
        }
    }
}

/// Appends `record` (an object with a string `type`) as one dstruct line ending in `;\n`.
/// Errors name what cannot be written (no `type`, not an object).
pub fn write_record(out: &mut Vec<u8>, record: &Tape) -> Result<(), String> {
    if !matches!(record.toks.first(), Some(Tok::Obj { .. })) {
        return Err("a record must be an object".to_string());
    }
    let name = match record.get(0, "type").and_then(|i| record.toks.get(i)) {
        Some(Tok::Str(s)) => record.bytes(*s),
        _ => return Err("a dstruct record needs a string field `type` (its name)".to_string()),
    };
    let mut ryu = ryu::Buffer::new();
    out.push(b'(');
    write_name(out, name);
    out.extend_from_slice(b" .");
    let mut any = false;
    for (k, v) in record.fields(0) {
        if k == b"type" {
            continue;
        }
        any = true;
        out.extend_from_slice(b" (");
        write_name(out, k);
        out.extend_from_slice(b" . ");
        write_value(out, record, v, &mut ryu);
        out.push(b')');
    }
    if !any {
        out.extend_from_slice(b" ()");
    }
    out.extend_from_slice(b");\n");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &[u8]) -> Result<serde_json::Value, SyntaxError> {
        let mut t = Tape::default();
        parse_record(text, &mut t)?;
        Ok(t.to_value())
    }

    /// Figure 1 of the seed, laid out as printed there.
    const FIGURE_1: &str = r#"(Triangle . (name . "tri-0")
           (vertex1 . (pos . [-1, 0, 0])
                      (norm . [-1, 0, 0]))
           (vertex2 . (pos . [0, 0, -1])
                      (norm . [0, 0, -1]))
           (vertex3 . (pos . [0, -1, 0])
                      (norm . [0, -1, 0])));"#;

    #[test]
    fn figure_1_parses_to_the_documented_object() {
        let v = parse(FIGURE_1.as_bytes()).expect("figure 1 parses");
        assert_eq!(v["type"], "Triangle");
        assert_eq!(v["name"], "tri-0");
        assert_eq!(v["vertex1"]["pos"], serde_json::json!([-1, 0, 0]));
        assert_eq!(v["vertex3"]["norm"][1], -1);
        let keys: Vec<&String> = v.as_object().expect("object").keys().collect();
        assert_eq!(keys, ["type", "name", "vertex1", "vertex2", "vertex3"]);
    }

    #[test]
    fn round_trip_keeps_order_and_values() {
        let v: serde_json::Value = serde_json::from_str(
            r#"{"type":"X","z":1,"a":[0.1,-2.5e-300,3],"s":"q\"uote","e":{},"n":null,"b":true,"weird key":[[1,2],[]],"o":{"k":{"j":1.5}}}"#,
        )
        .expect("json");
        let mut out = Vec::new();
        write_record(&mut out, &Tape::from_value(&v)).expect("writable");
        let back = parse(&out).expect("parses");
        assert_eq!(back, v);
        let keys: Vec<&String> = back.as_object().expect("object").keys().collect();
        assert_eq!(
            keys,
            ["type", "z", "a", "s", "e", "n", "b", "weird key", "o"]
        );
    }

    #[test]
    fn errors_are_errors() {
        for bad in [
            "",
            "(",
            "(T . )",
            "(T . 1);",
            "(T . (a . [1, 2);",
            "(T . (a . 1) (a . 2));",
            "(T . (a . word));",
            "(T . (a . 1)) junk",
            "(T . (a . \"open));",
            "(T . (a . 1e999));",
        ] {
            assert!(parse(bad.as_bytes()).is_err(), "{bad:?} should fail");
        }
        let deep = "(T . (a . ".to_string() + &"[".repeat(10_000);
        assert!(parse(deep.as_bytes()).is_err());
    }
}

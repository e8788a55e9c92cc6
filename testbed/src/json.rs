//! JSON Lines records read straight into a [`Tape`] and written from one (no
//! `serde_json::Value` on the way).
//!
//! The reader accepts RFC 8259 JSON (one object per line); numbers without a fraction or an
//! exponent are integers (`i64`, else `u64`), the rest `f64` (correctly rounded by the
//! standard library; out-of-range numbers are errors, as in `serde_json`). Duplicate field
//! names in one object are an error. Nesting is limited to [`MAX_DEPTH`], a record's tokens to
//! [`MAX_RECORD_TOKENS`] (its length, [`crate::tape::MAX_RECORD_BYTES`], is the stream
//! reader's to check: [`crate::stream`]).
//! The writer prints floats by Ryū (shortest text that reads back to the same `f64`).

use std::io::Write;

use crate::tape::{Tape, Tok, MAX_RECORD_TOKENS};

/// Deepest nesting accepted (`serde_json`'s limit): hostile input cannot exhaust the stack.
pub const MAX_DEPTH: usize = 128;

/// A syntax error: byte offset into the line and message.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JsonError {
    /// Byte offset.
    pub offset: usize,
    /// What is wrong.
    pub message: String,
}

/// The parser; `COUNT`: whether the record's tokens are counted ([`MAX_RECORD_TOKENS`]; only a
/// line that could exceed it is, [`parse_record`]).
struct Parser<'a, 't, const COUNT: bool> {
    /// The line, checked to be UTF-8 once (so any ASCII position is a character boundary).
    src: &'a str,
    s: &'a [u8],
    i: usize,
    depth: usize,
    tape: &'t mut Tape,
}

impl<const COUNT: bool> Parser<'_, '_, COUNT> {
    fn err<T>(&self, message: impl Into<String>) -> Result<T, JsonError> {
        Err(JsonError {
            offset: self.i,
            message: message.into(),
        })
    }

    fn ws(&mut self) {
        while let Some(c) = self.s.get(self.i) {
            if matches!(c, b' ' | b'\t' | b'\n' | b'\r') {
                self.i += 1;
            } else {
                break;
            }
        }
    }

    fn peek(&mut self) -> Option<u8> {
        self.ws();
        self.s.get(self.i).copied()
    }

    fn found(&self) -> String {
        match self.s.get(self.i) {
            Some(c) => format!("`{}`", *c as char),
            None => "the end".into(),
        }
    }

    fn value(&mut self) -> Result<(), JsonError> {
        match self.peek() {
            Some(b'{') => self.object(),
            Some(b'[') => self.array(),
            Some(b'"') => {
                let s = self.string()?;
                self.tape.toks.push(Tok::Str(s));
                Ok(())
            }
            Some(b't') => self.word(b"true", Tok::Bool(true)),
            Some(b'f') => self.word(b"false", Tok::Bool(false)),
            Some(b'n') => self.word(b"null", Tok::Null),
            Some(c) if c == b'-' || c.is_ascii_digit() => self.number(),
            _ => self.err(format!("expected a value, found {}", self.found())),
        }
    }

    fn word(&mut self, w: &[u8], t: Tok) -> Result<(), JsonError> {
        if self.s.get(self.i..self.i + w.len()) == Some(w) {
            self.i += w.len();
            self.tape.toks.push(t);
            Ok(())
        } else {
            self.err("expected a value")
        }
    }

    fn enter(&mut self) -> Result<(), JsonError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return self.err(format!("nested deeper than {MAX_DEPTH} levels"));
        }
        Ok(())
    }

    /// Refuses a record past [`MAX_RECORD_TOKENS`] (checked after each field and item: only
    /// containers grow a record by more than a token, and their own items are checked).
    #[inline(always)]
    fn count(&self) -> Result<(), JsonError> {
        if COUNT && self.tape.toks.len() > MAX_RECORD_TOKENS {
            return self.too_many();
        }
        Ok(())
    }

    /// The error of [`Self::count`], out of the parser's way.
    #[cold]
    #[inline(never)]
    fn too_many(&self) -> Result<(), JsonError> {
        self.err(crate::tape::too_many_tokens())
    }

    fn object(&mut self) -> Result<(), JsonError> {
        self.enter()?;
        self.i += 1;
        let at = self.tape.open(true);
        let mut n = 0;
        let mut many: Option<std::collections::HashSet<Vec<u8>>> = None;
        if self.peek() == Some(b'}') {
            self.i += 1;
        } else {
            loop {
                if self.peek() != Some(b'"') {
                    return self.err(format!("expected a field name, found {}", self.found()));
                }
                let key_at = self.i;
                let k = self.string()?;
                let name = self.tape.bytes(k);
                // The keys read so far: every value before is complete, so skipping works.
                let dup = self.tape.duplicate_key(at + 1, n, name, &mut many);
                if dup {
                    let name = String::from_utf8_lossy(name).into_owned();
                    self.i = key_at;
                    return self.err(format!("duplicate field `{name}`"));
                }
                self.tape.toks.push(Tok::Key(k));
                if self.peek() != Some(b':') {
                    return self.err(format!("expected `:`, found {}", self.found()));
                }
                self.i += 1;
                self.value()?;
                self.count()?;
                n += 1;
                match self.peek() {
                    Some(b',') => self.i += 1,
                    Some(b'}') => {
                        self.i += 1;
                        break;
                    }
                    _ => return self.err(format!("expected `,` or `}}`, found {}", self.found())),
                }
            }
        }
        self.tape.close(at, n);
        self.depth -= 1;
        Ok(())
    }

    fn array(&mut self) -> Result<(), JsonError> {
        self.enter()?;
        self.i += 1;
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
                    _ => return self.err(format!("expected `,` or `]`, found {}", self.found())),
                }
            }
        }
        self.tape.close(at, n);
        self.depth -= 1;
        Ok(())
    }

    /// A string (the opening quote next), decoded into the tape's text.
    fn string(&mut self) -> Result<crate::tape::Span, JsonError> {
        let start = self.i;
        self.i += 1;
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
                Some(b'"') => break,
                Some(c) if *c < 0x20 => return self.err("control character in a string"),
                Some(_) => self.i += 1,
            }
        }
        self.i += 1;
        let raw = self.s.get(start..self.i).unwrap_or_default();
        if !escaped {
            let inner = raw.get(1..raw.len() - 1).unwrap_or_default();
            return Ok(self.tape.push_text(inner));
        }
        match serde_json::from_slice::<String>(raw) {
            Ok(s) => Ok(self.tape.push_text(s.as_bytes())),
            Err(e) => {
                self.i = start;
                self.err(format!("bad string: {e}"))
            }
        }
    }

    fn digits(&mut self) -> usize {
        let a = self.i;
        while self.s.get(self.i).is_some_and(u8::is_ascii_digit) {
            self.i += 1;
        }
        self.i - a
    }

    fn number(&mut self) -> Result<(), JsonError> {
        let start = self.i;
        if self.s.get(self.i) == Some(&b'-') {
            self.i += 1;
        }
        let int_start = self.i;
        let n = self.digits();
        if n == 0 || (n > 1 && self.s.get(int_start) == Some(&b'0')) {
            self.i = start;
            return self.err("bad number");
        }
        let mut float = false;
        if self.s.get(self.i) == Some(&b'.') {
            self.i += 1;
            float = true;
            if self.digits() == 0 {
                self.i = start;
                return self.err("bad number");
            }
        }
        if matches!(self.s.get(self.i), Some(b'e' | b'E')) {
            self.i += 1;
            float = true;
            if matches!(self.s.get(self.i), Some(b'+' | b'-')) {
                self.i += 1;
            }
            if self.digits() == 0 {
                self.i = start;
                return self.err("bad number");
            }
        }
        // ASCII by construction; in JSON's grammar, so its text is kept to be written back.
        let text = self.src.get(start..self.i).unwrap_or_default();
        self.tape.push_number(text, !float, true).or_else(|_| {
            self.i = start;
            self.err(format!("number `{text}` is out of range"))
        })
    }
}

/// Parses one line (one JSON object, surrounding white space allowed) into `tape` (cleared
/// first). Every token takes at least one byte of the line, so a line shorter than
/// [`MAX_RECORD_TOKENS`] bytes cannot exceed it and is parsed without counting: the records of
/// honest streams pay nothing for the limit.
pub fn parse_record(line: &[u8], tape: &mut Tape) -> Result<(), JsonError> {
    if line.len() < MAX_RECORD_TOKENS {
        parse::<false>(line, tape)
    } else {
        parse::<true>(line, tape)
    }
}

fn parse<const COUNT: bool>(line: &[u8], tape: &mut Tape) -> Result<(), JsonError> {
    tape.clear();
    let src = std::str::from_utf8(line).map_err(|e| JsonError {
        offset: e.valid_up_to(),
        message: "the line is not UTF-8".into(),
    })?;
    let mut p = Parser::<COUNT> {
        src,
        s: line,
        i: 0,
        depth: 0,
        tape,
    };
    if p.peek() != Some(b'{') {
        return p.err("a record must be a JSON object");
    }
    p.value()?;
    if p.peek().is_some() {
        return p.err(format!("text after the record: {}", p.found()));
    }
    Ok(())
}

/// Appends a string with JSON's escapes.
pub fn write_string(out: &mut Vec<u8>, s: &[u8]) {
    let plain = s.iter().all(|&c| c >= 0x20 && c != b'"' && c != b'\\');
    if plain {
        out.push(b'"');
        out.extend_from_slice(s);
        out.push(b'"');
    } else {
        let text = String::from_utf8_lossy(s);
        if serde_json::to_writer(&mut *out, text.as_ref()).is_err() {
            out.extend_from_slice(b"\"\"");
        }
    }
}

/// True when `b` is a number in JSON's grammar
/// (`-?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?`).
pub fn is_json_number(b: &[u8]) -> bool {
    let mut i = usize::from(b.first() == Some(&b'-'));
    let digits = |i: &mut usize| {
        let a = *i;
        while b.get(*i).is_some_and(u8::is_ascii_digit) {
            *i += 1;
        }
        *i - a
    };
    let int_start = i;
    let n = digits(&mut i);
    if n == 0 || (n > 1 && b.get(int_start) == Some(&b'0')) {
        return false;
    }
    if b.get(i) == Some(&b'.') {
        i += 1;
        if digits(&mut i) == 0 {
            return false;
        }
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        if digits(&mut i) == 0 {
            return false;
        }
    }
    i == b.len()
}

/// Appends a scalar token the way every text writer of this crate does: integers as
/// integers, floats read from text as they came, other floats by Ryū. (`tape` holds the
/// text of [`Tok::Text`].) A float that is not finite (a binary stream can carry one; JSON
/// cannot) is written `null`, never a number: Ryū's `format_finite` would print a NaN as a
/// plausible-looking finite value.
pub fn write_scalar(out: &mut Vec<u8>, t: &Tok, tape: &Tape, ryu: &mut ryu::Buffer) {
    let mut float = |out: &mut Vec<u8>, x: f64| {
        if x.is_finite() {
            out.extend_from_slice(ryu.format_finite(x).as_bytes());
        } else {
            out.extend_from_slice(b"null");
        }
    };
    match t {
        Tok::Text(x, s) => {
            let text = tape.bytes(*s);
            if text.is_empty() {
                float(out, *x);
            } else {
                out.extend_from_slice(text);
            }
        }
        Tok::Float(x) => float(out, *x),
        Tok::Int(x) => {
            let _ = write!(out, "{x}");
        }
        Tok::UInt(x) => {
            let _ = write!(out, "{x}");
        }
        Tok::Bool(b) => out.extend_from_slice(if *b { b"true" } else { b"false" }),
        _ => out.extend_from_slice(b"null"),
    }
}

/// Appends the value at `at` as JSON; the index after it.
fn write_value(out: &mut Vec<u8>, tape: &Tape, at: usize, ryu: &mut ryu::Buffer) -> usize {
    let Some(t) = tape.toks.get(at) else {
        return at + 1;
    };
    match *t {
        Tok::Obj { fields, .. } => {
            out.push(b'{');
            let mut i = at + 1;
            for k in 0..fields {
                if k > 0 {
                    out.push(b',');
                }
                if let Some(Tok::Key(s)) = tape.toks.get(i) {
                    write_string(out, tape.bytes(*s));
                }
                out.push(b':');
                i = write_value(out, tape, i + 1, ryu);
            }
            out.push(b'}');
            i
        }
        Tok::Arr { items, .. } => {
            out.push(b'[');
            let mut i = at + 1;
            for k in 0..items {
                if k > 0 {
                    out.push(b',');
                }
                i = write_value(out, tape, i, ryu);
            }
            out.push(b']');
            i
        }
        Tok::Str(s) | Tok::Key(s) => {
            write_string(out, tape.bytes(s));
            at + 1
        }
        other => {
            write_scalar(out, &other, tape, ryu);
            at + 1
        }
    }
}

/// Appends the record as one JSON line.
pub fn write_record(out: &mut Vec<u8>, tape: &Tape) {
    let mut ryu = ryu::Buffer::new();
    write_value(out, tape, 0, &mut ryu);
    out.push(b'\n');
}

/// Appends any tape value as JSON text (no newline).
pub fn write_json(out: &mut Vec<u8>, tape: &Tape, at: usize) {
    let mut ryu = ryu::Buffer::new();
    write_value(out, tape, at, &mut ryu);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A NaN or an infinity (which only a binary stream can hold) is written `null`: Ryū's
    /// `format_finite` printed a NaN as -2.696539702293474e308.
    #[test]
    fn a_float_that_is_not_finite_is_written_null() {
        let tape = Tape::default();
        let mut ryu = ryu::Buffer::new();
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut out = Vec::new();
            write_scalar(&mut out, &Tok::Float(x), &tape, &mut ryu);
            assert_eq!(out, b"null", "{x}");
        }
        let mut out = Vec::new();
        write_scalar(&mut out, &Tok::Float(-0.5), &tape, &mut ryu);
        assert_eq!(out, b"-0.5");
    }

    #[test]
    fn lines_parse_like_serde_json_and_write_back() {
        let line = br#" {"type":"T","a":[1,-2,3.5,-0.0,1e-7,18446744073709551615],"s":"q\"u\u00e9","o":{},"e":[],"n":null,"b":false} "#;
        let mut t = Tape::default();
        parse_record(line, &mut t).expect("parses");
        let expected: serde_json::Value = serde_json::from_slice(line).expect("json");
        assert_eq!(t.to_value(), expected);
        let mut out = Vec::new();
        write_record(&mut out, &t);
        let back: serde_json::Value = serde_json::from_slice(&out).expect("json");
        assert_eq!(back, expected);
        for bad in [
            &b"[1]"[..],
            b"{",
            b"{\"a\":}",
            b"{\"a\":1,}",
            b"{\"a\":01}",
            b"{\"a\":1e999}",
            b"{\"a\":1,\"a\":2}",
            b"{\"a\":1} x",
            b"{\"a\":\"\x01\"}",
            b"{\"a\":tru}",
            b"{\"a\":\"\xff\"}",
        ] {
            assert!(
                parse_record(bad, &mut t).is_err(),
                "{:?}",
                String::from_utf8_lossy(bad)
            );
        }
        // Floats read from text are written back as they came.
        parse_record(br#"{"a":[1.50,2e0,-0.0]}"#, &mut t).expect("parses");
        let mut out = Vec::new();
        write_record(&mut out, &t);
        assert_eq!(out, b"{\"a\":[1.50,2e0,-0.0]}\n");
        let deep = "{\"a\":".to_string() + &"[".repeat(10_000);
        assert!(parse_record(deep.as_bytes(), &mut t).is_err());
    }
}

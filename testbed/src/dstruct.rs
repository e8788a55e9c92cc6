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
//! The in-memory record is a JSON object (`serde_json::Value`, order preserved). A record
//! `(Name . (a . 1) (b . "x"));` is the object `{"type": "Name", "a": 1, "b": "x"}`: the
//! outer pair's name is the `type`, its list of pairs the remaining fields in order. A list of
//! pairs is an object, an array an array, a number a number (integers stay integers), `nil`
//! is `null`. A field name that is not an identifier is written as a string. Duplicate names in
//! one list are an error (an object cannot hold them).
//!
//! Nesting is limited to [`MAX_DEPTH`] levels, so hostile input cannot overflow the stack.

use serde_json::{Map, Number, Value};

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

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
    depth: usize,
}

fn is_ident_start(c: u8) -> bool {
    c.is_ascii_alphabetic() || c == b'_'
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_' || c == b'-'
}

impl<'a> Parser<'a> {
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

    fn enter(&mut self) -> Result<(), SyntaxError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return self.err(format!("nested deeper than {MAX_DEPTH} levels"));
        }
        Ok(())
    }

    fn string(&mut self) -> Result<String, SyntaxError> {
        let start = self.i;
        self.i += 1; // the opening quote
        loop {
            match self.s.get(self.i) {
                None => {
                    self.i = start;
                    return self.err("unterminated string");
                }
                Some(b'\\') => self.i += 2,
                Some(b'"') => {
                    self.i += 1;
                    break;
                }
                Some(_) => self.i += 1,
            }
        }
        let text = self.s.get(start..self.i).unwrap_or_default();
        serde_json::from_slice::<String>(text).or_else(|e| {
            self.i = start;
            self.err(format!("bad string: {e}"))
        })
    }

    fn identifier(&mut self) -> &'a str {
        let start = self.i;
        while self.s.get(self.i).copied().is_some_and(is_ident) {
            self.i += 1;
        }
        // Identifiers are ASCII by construction.
        std::str::from_utf8(self.s.get(start..self.i).unwrap_or_default()).unwrap_or_default()
    }

    fn name(&mut self) -> Result<String, SyntaxError> {
        match self.peek() {
            Some(b'"') => self.string(),
            Some(c) if is_ident_start(c) => Ok(self.identifier().to_string()),
            Some(c) => self.err(format!("expected a field name, found `{}`", c as char)),
            None => self.err("expected a field name, found the end"),
        }
    }

    fn number(&mut self) -> Result<Value, SyntaxError> {
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
        let text =
            std::str::from_utf8(self.s.get(start..self.i).unwrap_or_default()).unwrap_or_default();
        let text = text.strip_prefix('+').unwrap_or(text);
        if !float {
            if let Ok(v) = text.parse::<i64>() {
                return Ok(Value::from(v));
            }
            if let Ok(v) = text.parse::<u64>() {
                return Ok(Value::from(v));
            }
        }
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Number::from_f64(v).map_or(Value::Null, Value::Number)),
            Ok(_) => {
                self.i = start;
                self.err(format!("number `{text}` is out of range"))
            }
            Err(_) => {
                self.i = start;
                self.err(format!("bad number `{text}`"))
            }
        }
    }

    /// `( name . value )`, the opening parenthesis next.
    fn pair(&mut self) -> Result<(String, Value), SyntaxError> {
        self.expect(b'(')?;
        let name = self.name()?;
        self.expect(b'.')?;
        let value = self.value()?;
        self.expect(b')')?;
        Ok((name, value))
    }

    /// One or more pairs, the first `(` next: an object.
    fn pairs(&mut self) -> Result<Value, SyntaxError> {
        self.enter()?;
        let mut map = Map::new();
        while self.peek() == Some(b'(') {
            let at = self.i;
            let (name, value) = self.pair()?;
            if map.contains_key(&name) {
                self.i = at;
                return self.err(format!("duplicate field `{name}`"));
            }
            map.insert(name, value);
        }
        self.depth -= 1;
        Ok(Value::Object(map))
    }

    fn value(&mut self) -> Result<Value, SyntaxError> {
        match self.peek() {
            Some(b'"') => self.string().map(Value::String),
            Some(b'[') => self.array(),
            Some(b'(') => {
                // `()` is the empty list; otherwise a list of pairs.
                let save = self.i;
                self.i += 1;
                if self.peek() == Some(b')') {
                    self.i += 1;
                    return Ok(Value::Object(Map::new()));
                }
                self.i = save;
                self.pairs()
            }
            Some(c) if c.is_ascii_digit() || c == b'-' || c == b'+' || c == b'.' => self.number(),
            Some(c) if is_ident_start(c) => {
                let at = self.i;
                match self.identifier() {
                    "true" => Ok(Value::Bool(true)),
                    "false" => Ok(Value::Bool(false)),
                    "nil" => Ok(Value::Null),
                    other => {
                        let other = other.to_string();
                        self.i = at;
                        self.err(format!(
                            "unexpected word `{other}` (strings need double quotes)"
                        ))
                    }
                }
            }
            Some(c) => self.err(format!("expected a value, found `{}`", c as char)),
            None => self.err("expected a value, found the end"),
        }
    }

    fn array(&mut self) -> Result<Value, SyntaxError> {
        self.enter()?;
        self.i += 1; // '['
        let mut items = Vec::new();
        if self.peek() == Some(b']') {
            self.i += 1;
            self.depth -= 1;
            return Ok(Value::Array(items));
        }
        loop {
            items.push(self.value()?);
            match self.peek() {
                Some(b',') => self.i += 1,
                Some(b']') => {
                    self.i += 1;
                    break;
                }
                Some(c) => return self.err(format!("expected `,` or `]`, found `{}`", c as char)),
                None => return self.err("unterminated array"),
            }
        }
        self.depth -= 1;
        Ok(Value::Array(items))
    }
}

/// Parses one record's text (`(Name . …);`, the semicolon optional at the very end) into a
/// JSON object whose first field is `type`.
pub fn parse_record(text: &[u8]) -> Result<Value, SyntaxError> {
    let mut p = Parser {
        s: text,
        i: 0,
        depth: 0,
    };
    if p.peek() != Some(b'(') {
        return match p.peek() {
            Some(c) => p.err(format!("a record starts with `(`, found `{}`", c as char)),
            None => p.err("empty record"),
        };
    }
    p.enter()?;
    let (name, value) = p.pair()?;
    let mut map = Map::new();
    map.insert("type".to_string(), Value::String(name));
    match value {
        Value::Object(fields) => {
            for (k, v) in fields {
                if k == "type" {
                    return p.err("a record's fields cannot be named `type` (it holds the name)");
                }
                map.insert(k, v);
            }
        }
        _ => return p.err("a record's value must be a list of `(name . value)` pairs"),
    }
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
    Ok(Value::Object(map))
}

fn write_name(out: &mut Vec<u8>, name: &str) {
    let plain = name.bytes().next().is_some_and(is_ident_start)
        && name.bytes().all(is_ident)
        && !matches!(name, "true" | "false" | "nil");
    if plain {
        out.extend_from_slice(name.as_bytes());
    } else {
        write_string(out, name);
    }
}

fn write_string(out: &mut Vec<u8>, s: &str) {
    // JSON's escaping is the dstruct reader's.
    match serde_json::to_string(s) {
        Ok(t) => out.extend_from_slice(t.as_bytes()),
        Err(_) => out.extend_from_slice(b"\"\""),
    }
}

/// Appends a number the way every writer of this crate does: integers as integers, floats by
/// Ryū (shortest text that reads back to the same `f64`).
pub fn write_number(out: &mut Vec<u8>, n: &Number, ryu: &mut ryu::Buffer) {
    if let Some(i) = n.as_i64() {
        out.extend_from_slice(i.to_string().as_bytes());
    } else if let Some(u) = n.as_u64() {
        out.extend_from_slice(u.to_string().as_bytes());
    } else if let Some(f) = n.as_f64() {
        out.extend_from_slice(ryu.format(f).as_bytes());
    }
}

fn write_value(out: &mut Vec<u8>, v: &Value, ryu: &mut ryu::Buffer) {
    match v {
        Value::Null => out.extend_from_slice(b"nil"),
        Value::Bool(b) => out.extend_from_slice(if *b { b"true" } else { b"false" }),
        Value::Number(n) => write_number(out, n, ryu),
        Value::String(s) => write_string(out, s),
        Value::Array(items) => {
            out.push(b'[');
            for (k, item) in items.iter().enumerate() {
                if k > 0 {
                    out.extend_from_slice(b", ");
                }
                write_value(out, item, ryu);
            }
            out.push(b']');
        }
        Value::Object(map) if map.is_empty() => out.extend_from_slice(b"()"),
        Value::Object(map) => {
            for (k, (name, value)) in map.iter().enumerate() {
                if k > 0 {
                    out.push(b' ');
                }
                out.push(b'(');
                write_name(out, name);
                out.extend_from_slice(b" . ");
                write_value(out, value, ryu);
                out.push(b')');
            }
        }
    }
}

/// Appends `record` (an object with a string `type`) as one dstruct line ending in `;\n`.
/// Errors name what cannot be written (no `type`, not an object).
pub fn write_record(out: &mut Vec<u8>, record: &Value) -> Result<(), String> {
    let map = record
        .as_object()
        .ok_or_else(|| "a record must be an object".to_string())?;
    let name = map
        .get("type")
        .and_then(Value::as_str)
        .ok_or_else(|| "a dstruct record needs a string field `type` (its name)".to_string())?;
    let mut ryu = ryu::Buffer::new();
    out.push(b'(');
    write_name(out, name);
    out.extend_from_slice(b" .");
    let mut any = false;
    for (k, v) in map {
        if k == "type" {
            continue;
        }
        any = true;
        out.extend_from_slice(b" (");
        write_name(out, k);
        out.extend_from_slice(b" . ");
        write_value(out, v, &mut ryu);
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
        let v = parse_record(FIGURE_1.as_bytes()).expect("figure 1 parses");
        assert_eq!(v["type"], "Triangle");
        assert_eq!(v["name"], "tri-0");
        assert_eq!(v["vertex1"]["pos"], serde_json::json!([-1, 0, 0]));
        assert_eq!(v["vertex3"]["norm"][1], -1);
        let keys: Vec<&String> = v.as_object().expect("object").keys().collect();
        assert_eq!(keys, ["type", "name", "vertex1", "vertex2", "vertex3"]);
    }

    #[test]
    fn round_trip_keeps_order_and_values() {
        let v: Value = serde_json::from_str(
            r#"{"type":"X","z":1,"a":[0.1,-2.5e-300,3],"s":"q\"uote","e":{},"n":null,"b":true,"weird key":[[1,2],[]],"o":{"k":{"j":1.5}}}"#,
        )
        .expect("json");
        let mut out = Vec::new();
        write_record(&mut out, &v).expect("writable");
        let back = parse_record(&out).expect("parses");
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
            assert!(parse_record(bad.as_bytes()).is_err(), "{bad:?} should fail");
        }
        let deep = "(T . (a . ".to_string() + &"[".repeat(10_000);
        assert!(parse_record(deep.as_bytes()).is_err());
    }
}

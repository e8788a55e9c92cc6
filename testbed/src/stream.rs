//! Record streams: reading with the format detected, writing in a chosen format.
//!
//! A record is an object (order preserved) with a string field `type` naming it, held as a
//! [`Tape`] (no `serde_json::Value` per record: [`crate::tape`]). The formats:
//!
//! * [`Format::Json`] — JSON Lines, one object per line (the default);
//! * [`Format::Dstruct`] — the seed's dstruct external format ([`crate::dstruct`]), one
//!   record per line when written, any layout when read;
//! * [`Format::Binary`] — the self-describing binary form ([`crate::binary`]).
//!
//! The input format is detected from the first non-space byte: `{` JSON Lines, `(` or `%` a
//! dstruct stream, `T` (of the magic `TBIN1`) the binary form. An empty input is an empty
//! stream in any format.

use std::io::{BufRead, Write};

use serde_json::Value;

use crate::binary;
use crate::dstruct;
use crate::error::{Position, StreamError};
use crate::json;
use crate::tape::Tape;
pub use crate::tape::{MAX_RECORD_BYTES, MAX_RECORD_TOKENS};

/// A stream format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// JSON Lines.
    Json,
    /// The dstruct external format of the seed's Figure 1.
    Dstruct,
    /// The self-describing binary form.
    Binary,
    /// The workspace's binary patch file (`.bzp`, `surface::patch_io`): read by every filter
    /// (its patches become `BezierTriangle` records), written by `fit` only (it holds the
    /// patches of one fit; the filters after it write `binary` by default).
    Bzp,
}

impl Format {
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Format::Json => "json",
            Format::Dstruct => "dstruct",
            Format::Binary => "binary",
            Format::Bzp => "bzp",
        }
    }
}

/// One record read, with where it started.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Record {
    /// The record: an object.
    pub tape: Tape,
    /// Where it started.
    pub at: Position,
}

impl Record {
    /// The record's `type` (empty when absent).
    pub fn kind(&self) -> &str {
        self.tape.kind()
    }

    /// The record as a JSON value (tests, slow paths).
    pub fn value(&self) -> Value {
        self.tape.to_value()
    }
}

/// Reads records from a byte stream.
pub struct RecordReader<R: BufRead> {
    inner: R,
    format: Option<Format>,
    /// Records seen (good and bad).
    count: usize,
    /// Lines consumed so far (text formats).
    line: usize,
    buf: Vec<u8>,
    decoder: binary::Decoder,
    bzp: crate::bzp::Decoder,
    fatal: bool,
    /// The rest of a record refused as too long, to pass over (not hold) before the next.
    skip: Option<Skip>,
}

/// What is left of a record refused for its length ([`MAX_RECORD_BYTES`]): passed over
/// without being held, so reading can go on with the next record (`--keep-going`).
#[derive(Clone, Copy, Debug)]
enum Skip {
    /// The rest of a JSON line.
    Line,
    /// The rest of a dstruct record, up to its `;`, from the scanner's state.
    Dstruct(DstructScan),
}

/// Where the dstruct record scanner is: in a string, just after an escaping backslash, in a
/// comment.
#[derive(Clone, Copy, Debug, Default)]
struct DstructScan {
    in_string: bool,
    escape: bool,
    comment: bool,
}

/// How a dstruct record scan stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ScanEnd {
    /// At the record's `;`.
    Ended,
    /// At the end of the input.
    Eof,
    /// Past [`MAX_RECORD_BYTES`] (only when the record is being held).
    TooLong,
}

/// What to do about a record too large to write: the pipeline's largest records are one
/// patch's `TriangleMesh` (`tess --mesh` records pass every filter up to about `-s 750`).
const MESH_HINT: &str = "a TriangleMesh: a smaller tess -s, or Triangle records without --mesh";

/// The message of a record refused for its length.
fn too_long(what: &str) -> String {
    format!(
        "{what} is longer than {MAX_RECORD_BYTES} bytes ({} MiB, the longest record a stream \
         may hold)",
        MAX_RECORD_BYTES >> 20
    )
}

impl<R: BufRead> RecordReader<R> {
    /// A reader over `inner`; the format is detected on the first read.
    pub fn new(inner: R) -> Self {
        RecordReader {
            inner,
            format: None,
            count: 0,
            line: 1,
            buf: Vec::new(),
            decoder: binary::Decoder::default(),
            bzp: crate::bzp::Decoder::default(),
            fatal: false,
            skip: None,
        }
    }

    /// The detected format (`None` before the first record or for an empty stream).
    pub fn format(&self) -> Option<Format> {
        self.format
    }

    /// Skips white space (counting lines); the next byte, if any.
    fn skip_space(&mut self) -> Result<Option<u8>, StreamError> {
        loop {
            let buf = self
                .inner
                .fill_buf()
                .map_err(|e| StreamError::io("reading the input", e))?;
            if buf.is_empty() {
                return Ok(None);
            }
            let mut used = 0;
            let mut found = None;
            for &c in buf {
                if c.is_ascii_whitespace() {
                    if c == b'\n' {
                        self.line += 1;
                    }
                    used += 1;
                } else {
                    found = Some(c);
                    break;
                }
            }
            self.inner.consume(used);
            if found.is_some() {
                return Ok(found);
            }
        }
    }

    fn detect(&mut self) -> Result<Option<Format>, StreamError> {
        if let Some(f) = self.format {
            return Ok(Some(f));
        }
        let Some(c) = self.skip_space()? else {
            return Ok(None);
        };
        let format = match c {
            b'{' => Format::Json,
            b'(' | b'%' => Format::Dstruct,
            b'T' => {
                let mut magic = [0u8; 6];
                let ok = std::io::Read::read_exact(&mut self.inner, &mut magic).is_ok()
                    && magic == binary::MAGIC;
                if !ok {
                    self.fatal = true;
                    return Err(StreamError::UnknownFormat { found: 'T' });
                }
                Format::Binary
            }
            b'B' => {
                if let Err(message) = self.bzp.start(&mut self.inner) {
                    self.fatal = true;
                    return Err(StreamError::Binary {
                        at: Position::default(),
                        message,
                    });
                }
                Format::Bzp
            }
            other => {
                self.fatal = true;
                return Err(StreamError::UnknownFormat {
                    found: other as char,
                });
            }
        };
        self.format = Some(format);
        Ok(Some(format))
    }

    /// The next record: `None` at the end, `Some(Err)` for a bad record (after which reading
    /// may continue when [`StreamError::is_record_error`]) or a fatal error (after which the
    /// reader returns `None`).
    pub fn next_record(&mut self) -> Option<Result<Record, StreamError>> {
        let mut r = Record::default();
        match self.read_into(&mut r)? {
            Ok(()) => Some(Ok(r)),
            Err(e) => Some(Err(e)),
        }
    }

    /// [`RecordReader::next_record`] into `record`, reusing its storage: `None` at the end.
    pub fn read_into(&mut self, record: &mut Record) -> Option<Result<(), StreamError>> {
        if self.fatal {
            return None;
        }
        if let Some(skip) = self.skip.take() {
            if let Err(e) = self.pass_over(skip) {
                self.fatal = true;
                return Some(Err(e));
            }
        }
        let format = match self.detect() {
            Ok(Some(f)) => f,
            Ok(None) => return None,
            Err(e) => return Some(Err(e)),
        };
        let result = match format {
            Format::Json => self.next_json(record),
            Format::Dstruct => self.next_dstruct(record),
            Format::Binary => self.next_binary(record),
            Format::Bzp => self.next_bzp(record),
        };
        match result {
            Ok(false) => None,
            Ok(true) => Some(Ok(())),
            Err(e) => {
                if !e.is_record_error() {
                    self.fatal = true;
                }
                Some(Err(e))
            }
        }
    }

    /// Passes over the rest of a record refused for its length, holding none of it.
    fn pass_over(&mut self, skip: Skip) -> Result<(), StreamError> {
        match skip {
            Skip::Line => self.discard_line(),
            Skip::Dstruct(mut state) => self.scan_dstruct(&mut state, false).map(|_| ()),
        }
    }

    /// Reads past the next newline (counted), holding nothing.
    fn discard_line(&mut self) -> Result<(), StreamError> {
        loop {
            let buf = self
                .inner
                .fill_buf()
                .map_err(|e| StreamError::io("reading the input", e))?;
            if buf.is_empty() {
                return Ok(());
            }
            match buf.iter().position(|&c| c == b'\n') {
                Some(p) => {
                    self.inner.consume(p + 1);
                    self.line += 1;
                    return Ok(());
                }
                None => {
                    let n = buf.len();
                    self.inner.consume(n);
                }
            }
        }
    }

    fn next_json(&mut self, record: &mut Record) -> Result<bool, StreamError> {
        if self.skip_space()?.is_none() {
            return Ok(false);
        }
        self.buf.clear();
        let at_line = self.line;
        // At most one byte past the limit is read: a longer line is refused before it is
        // held whole, and its rest passed over on the next read.
        let limit = MAX_RECORD_BYTES as u64 + 1;
        std::io::Read::take(&mut self.inner, limit)
            .read_until(b'\n', &mut self.buf)
            .map_err(|e| StreamError::io("reading the input", e))?;
        self.count += 1;
        let at = Position {
            record: self.count,
            line: at_line,
        };
        record.at = at;
        if self.buf.len() > MAX_RECORD_BYTES && self.buf.last() != Some(&b'\n') {
            self.buf = Vec::new();
            self.skip = Some(Skip::Line);
            return Err(StreamError::Syntax {
                at,
                message: too_long("the line"),
            });
        }
        self.line += 1;
        // Strings are checked for UTF-8 as they are read; the rest of a line is ASCII syntax.
        json::parse_record(&self.buf, &mut record.tape)
            .map(|()| true)
            .map_err(|e| StreamError::Syntax {
                at,
                message: format!("bad JSON: {} at column {}", e.message, e.offset + 1),
            })
    }

    /// Scans a dstruct record from `state` up to its `;` outside strings and comments,
    /// counting lines: into the buffer when `keep` (stopping past [`MAX_RECORD_BYTES`]),
    /// passed over otherwise.
    fn scan_dstruct(
        &mut self,
        state: &mut DstructScan,
        keep: bool,
    ) -> Result<ScanEnd, StreamError> {
        loop {
            if keep && self.buf.len() > MAX_RECORD_BYTES {
                return Ok(ScanEnd::TooLong);
            }
            let chunk = self
                .inner
                .fill_buf()
                .map_err(|e| StreamError::io("reading the input", e))?;
            if chunk.is_empty() {
                return Ok(ScanEnd::Eof);
            }
            // Held: no more than one byte past the limit.
            let room = if keep {
                MAX_RECORD_BYTES + 1 - self.buf.len()
            } else {
                usize::MAX
            };
            let chunk = &chunk[..chunk.len().min(room)];
            // Jump from one byte that matters to the next (in a string: `"`, `\\`; in a
            // comment: the line's end; elsewhere: `"`, `%`, `;`), counting lines as we go.
            let mut used = 0;
            let mut ended = false;
            while used < chunk.len() {
                let rest = &chunk[used..];
                if state.escape {
                    state.escape = false;
                    self.line += usize::from(rest[0] == b'\n');
                    used += 1;
                    continue;
                }
                let hit = if state.comment {
                    rest.iter().position(|&c| c == b'\n')
                } else if state.in_string {
                    rest.iter()
                        .position(|&c| c == b'"' || c == b'\\' || c == b'\n')
                } else {
                    rest.iter()
                        .position(|&c| matches!(c, b'"' | b'%' | b';' | b'\n'))
                };
                let Some(p) = hit else {
                    used = chunk.len();
                    break;
                };
                used += p + 1;
                match rest[p] {
                    b'\n' => {
                        self.line += 1;
                        state.comment = false;
                    }
                    b'\\' => state.escape = true,
                    b'"' => state.in_string = !state.in_string,
                    b'%' => state.comment = true,
                    _ => {
                        ended = true;
                        break;
                    }
                }
            }
            if keep {
                self.buf.extend_from_slice(&chunk[..used]);
            }
            self.inner.consume(used);
            if ended {
                return Ok(ScanEnd::Ended);
            }
        }
    }

    fn next_dstruct(&mut self, record: &mut Record) -> Result<bool, StreamError> {
        // Skip white space and comments before the record (a comment is passed over, not
        // held: it may be as long as the input).
        loop {
            match self.skip_space()? {
                None => return Ok(false),
                Some(b'%') => self.discard_line()?,
                Some(_) => break,
            }
        }
        let at_line = self.line;
        self.count += 1;
        let at = Position {
            record: self.count,
            line: at_line,
        };
        record.at = at;
        // Collect up to the `;` outside strings and comments.
        self.buf.clear();
        let mut state = DstructScan::default();
        match self.scan_dstruct(&mut state, true)? {
            ScanEnd::Ended => {}
            ScanEnd::Eof => {
                return Err(StreamError::Syntax {
                    at,
                    message: "the stream ends inside a record (no terminating `;`)".into(),
                })
            }
            ScanEnd::TooLong => {
                self.buf = Vec::new();
                self.skip = Some(Skip::Dstruct(state));
                return Err(StreamError::Syntax {
                    at,
                    message: too_long("the record"),
                });
            }
        }
        dstruct::parse_record(&self.buf, &mut record.tape)
            .map(|()| true)
            .map_err(|e| {
                let (line, col) = line_col(&self.buf, e.offset);
                StreamError::Syntax {
                    at,
                    message: format!(
                        "{} (at line {}, column {})",
                        e.message,
                        at_line + line,
                        col + 1
                    ),
                }
            })
    }

    fn next_binary(&mut self, record: &mut Record) -> Result<bool, StreamError> {
        record.at = self.next_position();
        let decoded = self.decoder.next_into(&mut self.inner, &mut record.tape);
        self.counted(record.at, decoded)
    }
}

impl<R: BufRead> RecordReader<R> {
    fn next_bzp(&mut self, record: &mut Record) -> Result<bool, StreamError> {
        record.at = self.next_position();
        let decoded = self.bzp.next_into(&mut self.inner, &mut record.tape);
        self.counted(record.at, decoded)
    }

    /// The position of the next record of a stream without lines (binary, `.bzp`).
    fn next_position(&self) -> Position {
        Position {
            record: self.count + 1,
            line: 0,
        }
    }

    /// A binary decoder's answer for the record at `at`: counted when one was read.
    fn counted(
        &mut self,
        at: Position,
        decoded: Result<bool, String>,
    ) -> Result<bool, StreamError> {
        match decoded {
            Ok(false) => Ok(false),
            Ok(true) => {
                self.count += 1;
                Ok(true)
            }
            Err(message) => Err(StreamError::Binary { at, message }),
        }
    }
}

/// Line (from 0) and column (from 0, bytes) of `offset` in `text`.
fn line_col(text: &[u8], offset: usize) -> (usize, usize) {
    let before = text.get(..offset).unwrap_or(text);
    let line = before.iter().filter(|&&c| c == b'\n').count();
    let col = before.iter().rev().take_while(|&&c| c != b'\n').count();
    (line, col)
}

/// Writes records in one format, buffered.
pub struct RecordWriter<W: Write> {
    out: W,
    format: Option<Format>,
    buf: Vec<u8>,
    encoder: binary::Encoder,
    written: usize,
}

/// Buffered bytes written out when this many have accumulated.
const FLUSH_BYTES: usize = 1 << 16;

impl<W: Write> RecordWriter<W> {
    /// A writer in `format`; `None`: decided by [`RecordWriter::default_format`] before the
    /// first record (JSON if never decided).
    pub fn new(out: W, format: Option<Format>) -> Self {
        RecordWriter {
            out,
            format,
            buf: Vec::with_capacity(FLUSH_BYTES * 2),
            encoder: binary::Encoder::default(),
            written: 0,
        }
    }

    /// Sets the format if none was chosen (a filter's output follows its input's format).
    /// The format to write when none was asked for: the input's (the self-describing binary
    /// form for a `.bzp` input, which only `fit` writes).
    pub fn default_format(&mut self, format: Option<Format>) {
        if self.format.is_none() {
            self.format = format.map(|f| match f {
                Format::Bzp => Format::Binary,
                f => f,
            });
        }
    }

    /// Records written so far.
    pub fn written(&self) -> usize {
        self.written
    }

    /// Writes one record given as a JSON value (the slow path: fit's patches, tests).
    pub fn write(&mut self, record: &Value, at: Position) -> Result<(), StreamError> {
        self.write_tape(&Tape::from_value(record), at)
    }

    /// Writes one record; `at` names it in errors.
    pub fn write_tape(&mut self, record: &Tape, at: Position) -> Result<(), StreamError> {
        let format = *self.format.get_or_insert(Format::Json);
        let unwritable = |message: String| StreamError::Unwritable {
            at,
            format: format.name(),
            message,
        };
        let is_object = matches!(record.toks.first(), Some(crate::tape::Tok::Obj { .. }));
        // What no reader would take back is not written: a stream a filter writes reads back.
        if record.toks.len() > MAX_RECORD_TOKENS {
            return Err(unwritable(format!(
                "{}; no reader would take it back ({MESH_HINT})",
                crate::tape::too_many_tokens()
            )));
        }
        let mark = self.buf.len();
        match format {
            Format::Json => {
                if !is_object {
                    return Err(unwritable("a record must be an object".into()));
                }
                json::write_record(&mut self.buf, record);
            }
            Format::Dstruct => dstruct::write_record(&mut self.buf, record).map_err(unwritable)?,
            Format::Binary => {
                if !is_object {
                    return Err(unwritable("a record must be an object".into()));
                }
                self.encoder
                    .write(record, &mut self.buf)
                    .map_err(unwritable)?
            }
            Format::Bzp => {
                return Err(unwritable(
                    "the binary patch file holds the patches of one fit: only `fit` writes it (choose json, dstruct or binary)".into(),
                ))
            }
        }
        // The text formats: the record without its newline is what a reader measures.
        let text = (self.buf.len() - mark).saturating_sub(1);
        if format != Format::Binary && text > MAX_RECORD_BYTES {
            self.buf.truncate(mark);
            return Err(unwritable(format!(
                "the record would be {text} bytes, longer than the {MAX_RECORD_BYTES} bytes ({} \
                 MiB) a record may hold, so no reader would take it back ({MESH_HINT})",
                MAX_RECORD_BYTES >> 20
            )));
        }
        self.written += 1;
        if self.buf.len() >= FLUSH_BYTES {
            self.flush_buf()?;
        }
        Ok(())
    }

    fn flush_buf(&mut self) -> Result<(), StreamError> {
        self.out
            .write_all(&self.buf)
            .map_err(|e| StreamError::io("writing the output", e))?;
        self.buf.clear();
        Ok(())
    }

    /// The output underneath, everything buffered written first: for a writer of a form that is
    /// no record stream (`fit`'s `.bzp`).
    pub fn raw(&mut self) -> Result<&mut W, StreamError> {
        self.flush_buf()?;
        Ok(&mut self.out)
    }

    /// The format being written (`None` until the first record when none was asked for).
    pub fn format(&self) -> Option<Format> {
        self.format
    }

    /// Writes out everything buffered and flushes.
    pub fn finish(&mut self) -> Result<(), StreamError> {
        self.flush_buf()?;
        self.out
            .flush()
            .map_err(|e| StreamError::io("writing the output", e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_all(bytes: &[u8]) -> Vec<Result<Record, String>> {
        let mut r = RecordReader::new(bytes);
        let mut out = Vec::new();
        while let Some(x) = r.next_record() {
            out.push(x.map_err(|e| e.to_string()));
        }
        out
    }

    #[test]
    fn formats_detected_and_positions_named() {
        let json = b"\n{\"type\":\"A\",\"x\":1}\n\n{\"type\":\"B\"\n{\"type\":\"C\"}\n";
        let got = read_all(json);
        assert_eq!(got.len(), 3);
        assert!(got[0].is_ok());
        let e = got[1].as_ref().expect_err("bad line");
        assert!(e.contains("record 2 (line 4)"), "{e}");
        assert_eq!(got[2].as_ref().map(|r| r.at.record).ok(), Some(3));

        let ds = b"% comment\n(A . (x . 1));\n(B . (x . ));\n(C . (y . \"a;b\"));";
        let got = read_all(ds);
        assert_eq!(got.len(), 3);
        assert_eq!(
            got[0].as_ref().map(|r| r.value()).ok(),
            Some(serde_json::json!({"type":"A","x":1}))
        );
        let e = got[1].as_ref().expect_err("bad record");
        assert!(e.contains("record 2 (line 3)"), "{e}");
        assert_eq!(
            got[2].as_ref().map(|r| r.value()["y"].clone()).ok(),
            Some(Value::from("a;b"))
        );
        let got = read_all(b"(A . (x . 1)");
        assert!(got[0].as_ref().is_err_and(|e| e.contains("terminating")));
        let got = read_all(b"  <html>");
        assert_eq!(got.len(), 1);
        assert!(got[0].is_err());
        assert!(read_all(b"   \n ").is_empty());
    }

    #[test]
    fn every_format_round_trips() {
        let records: Vec<Value> = vec![
            serde_json::json!({"type":"Triangle","vertex1":{"pos":[1.5,0.1,-3.0e-7]},"provenance":"x"}),
            serde_json::json!({"type":"BezierTriangle","degree":1,"points":[[0.0,0.0,0.0]],"face":2}),
        ];
        for format in [Format::Json, Format::Dstruct, Format::Binary] {
            let mut bytes = Vec::new();
            {
                let mut w = RecordWriter::new(&mut bytes, Some(format));
                for r in &records {
                    w.write(r, Position::default()).expect("writes");
                }
                w.finish().expect("flushes");
            }
            let mut reader = RecordReader::new(&bytes[..]);
            let mut back = Vec::new();
            while let Some(r) = reader.next_record() {
                back.push(r.expect("reads").value());
            }
            assert_eq!(reader.format(), Some(format));
            assert_eq!(back, records, "{format:?}");
        }
    }

    /// The hand-written readers on mutated streams of every format: no panic, and every
    /// record read is writable in every format and reads back equal (the seeded
    /// `rng::SplitMix64`, so failures reproduce).
    #[test]
    fn mutated_streams_never_panic_and_good_records_round_trip() {
        /// Mutated copies per format: enough to hit every branch of the small grammars many
        /// times over, fast in a debug build.
        const CASES: usize = 2000;
        let records: Vec<Value> = vec![
            serde_json::json!({"type":"Triangle","vertex1":{"pos":[1.5,0.1,-3.0e-7],"kg":2.5},"vertex2":{"pos":[0,1,2]},"vertex3":{"pos":[1,1,1],"color":[0.5,0.25,1.0]},"face":3,"scheme":"s\"q","provenance":"x"}),
            serde_json::json!({"type":"BezierTriangle","degree":1,"points":[[0.0,0.0,0.0],[1.0,0.0,0.0],[0.0,1.0,0.0]],"face":2,"n":null,"b":[true,false],"o":{}}),
            serde_json::json!({"type":"Note","big":18446744073709551615u64,"neg":-7,"e":[],"deep":[[[1]]]}),
            serde_json::json!({"type":"TriangleMesh","pos":[[0.5,0,0],[1,0,0],[0,1.5,0],[1,1,-2e-3]],"norm":[[0,0,1],[0,0,1],[0,0,1],[0,0.6,0.8]],"kg":[1,-2,3,0.25],"uv":[[0,0],[1,0],[0,1],[1,1]],"triangles":[[0,1,2],[1,3,2]],"face":1}),
        ];
        let mut mesh = crate::triangle_mesh::TriangleMesh::default();
        let mut seed = rng::SplitMix64::new(0x2545_f491_4f6c_dd1d);
        let mut next = move || seed.next_u64();
        for format in [Format::Json, Format::Dstruct, Format::Binary] {
            let mut bytes = Vec::new();
            {
                let mut w = RecordWriter::new(&mut bytes, Some(format));
                for _ in 0..3 {
                    for r in &records {
                        w.write(r, Position::default()).expect("writes");
                    }
                }
                w.finish().expect("flushes");
            }
            for _ in 0..CASES {
                let mut m = bytes.clone();
                for _ in 0..1 + next() % 4 {
                    let at = (next() as usize) % m.len();
                    match next() % 3 {
                        0 => m[at] = next() as u8,
                        1 => {
                            m.remove(at);
                        }
                        _ => m.insert(at, b"{}[]()\",.;%:-0e9\n"[(next() % 17) as usize]),
                    }
                }
                let mut reader = RecordReader::new(&m[..]);
                while let Some(r) = reader.next_record() {
                    let Ok(r) = r else { continue };
                    let value = r.value();
                    // The typed readers on whatever survived: an error or a value, and every
                    // index of a mesh read is in range.
                    if mesh.read(&r.tape).is_ok() {
                        let n = mesh.pos.len() as u32;
                        assert!(mesh.triangles.iter().flatten().all(|&i| i < n));
                        assert!([mesh.norm.len(), mesh.kg.len()]
                            .iter()
                            .all(|&l| l == 0 || l == mesh.pos.len()));
                    }
                    let _ = crate::record::triangle(&r.tape);
                    let _ = crate::record::bezier_triangle(&r.tape);
                    for out in [Format::Json, Format::Dstruct, Format::Binary] {
                        let mut again = Vec::new();
                        let mut w = RecordWriter::new(&mut again, Some(out));
                        if w.write_tape(&r.tape, r.at).is_err() {
                            // A dstruct needs a string `type`: the only refusal allowed.
                            assert_eq!(out, Format::Dstruct);
                            continue;
                        }
                        w.finish().expect("flushes");
                        let back = RecordReader::new(&again[..])
                            .next_record()
                            .expect("a record")
                            .expect("reads back");
                        assert_eq!(back.value(), value, "{format:?} → {out:?}");
                    }
                }
            }
        }
    }
}

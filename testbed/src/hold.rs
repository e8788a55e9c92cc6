//! Records a filter holds back, in order, in bounded memory: up to [`HELD_BYTES`] in memory,
//! the rest in a temporary file ([`Held`]).
//!
//! The colouring filters hold the first block of triangles (and whatever records come between
//! them) until their colour range is fixed ([`crate::binders`]). How much that is depends on
//! the stream, not on the filter: a block of `TriangleMesh`es at a large `tess -s`, `--block`
//! set high, or records of other kinds between the triangles. Past the budget the records go
//! to a temporary file and are read back in order when released, so the memory is bounded
//! whatever the stream holds and the output is the same as with everything in memory.
//!
//! The file is created in the system's temporary directory (`TMPDIR`) and unlinked at once
//! (Unix; [`crate::scratch_file`]): the name is gone before anything is written, and the
//! space is returned when the file is closed — on success, on an error, and on any interrupt
//! or kill, with no handler needed. Where unlinking an open file is not possible, the file is
//! registered with [`meshio::outfile::in_flight`] and removed when the holder is dropped.

use std::collections::VecDeque;
use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Seek, Write};

use crate::error::{Position, StreamError};
use crate::scratch_file::{self, ScratchPath};
use crate::stream::Record;
use crate::tape::{Span, Tape, Tok, MAX_RECORD_TOKENS};

/// Memory a filter may hold in records before the rest go to a temporary file (64 MiB): the
/// colouring filters' default block, 8 192 triangles, holds about 18 MB of `Triangle`s read
/// from JSON Lines (2.2 kB each with their number texts; less from the other formats and as
/// `TriangleMesh`es), so honest streams at the default block never touch the disk.
pub const HELD_BYTES: usize = 64 << 20;

/// Bookkeeping of one held record besides its tape and values (the queue's entry).
const ENTRY_BYTES: usize = std::mem::size_of::<(Record, Vec<f64>)>();

/// Records held in order with a value list each (the colouring filters: a record's vertex
/// values), in memory up to a budget and in a temporary file beyond (module docs).
pub struct Held {
    mem: VecDeque<(Record, Vec<f64>)>,
    mem_bytes: usize,
    budget: usize,
    spill: Option<Spill>,
    spilled: usize,
}

impl Held {
    /// An empty holder keeping up to `budget` bytes in memory.
    pub fn new(budget: usize) -> Self {
        Held {
            mem: VecDeque::new(),
            mem_bytes: 0,
            budget,
            spill: None,
            spilled: 0,
        }
    }

    /// True when nothing is held.
    pub fn is_empty(&self) -> bool {
        self.mem.is_empty() && self.spilled == 0
    }

    /// Records held in memory and in the file.
    pub fn len(&self) -> usize {
        self.mem.len() + self.spilled
    }

    /// Records held in the temporary file.
    pub fn spilled(&self) -> usize {
        self.spilled
    }

    /// Memory held by the records kept in memory (the estimate the budget is checked with).
    pub fn memory(&self) -> usize {
        self.mem_bytes
    }

    /// The memory one record takes when held.
    fn cost(rec: &Record, values: &[f64]) -> usize {
        rec.tape.heap_bytes() + std::mem::size_of_val(values) + ENTRY_BYTES
    }

    /// Holds `rec` with its `values` after every record held before. Past the budget (and
    /// after the first record that went to the file, so the order stays) it is written to
    /// the temporary file; `filter` names the holder in the note printed when the file is
    /// opened.
    pub fn push(
        &mut self,
        rec: Record,
        mut values: Vec<f64>,
        filter: &str,
    ) -> Result<(), StreamError> {
        values.shrink_to_fit();
        let cost = Self::cost(&rec, &values);
        if self.spill.is_none() && self.mem_bytes + cost <= self.budget {
            self.mem_bytes += cost;
            self.mem.push_back((rec, values));
            return Ok(());
        }
        if self.spill.is_none() {
            eprintln!(
                "{filter}: the records held until the colour range is fixed passed {} MiB; the \
                 rest wait in a temporary file (TMPDIR; removed when the filter ends)",
                self.budget >> 20
            );
            self.spill = Some(Spill::create()?);
        }
        if let Some(spill) = self.spill.as_mut() {
            spill.write(&rec, &values)?;
            self.spilled += 1;
        }
        Ok(())
    }

    /// Hands every held record to `f` in the order held (memory first, then the file, read
    /// back one record at a time) and empties the holder (the file is closed and so gone).
    pub fn drain(
        &mut self,
        f: &mut dyn FnMut(Record, Vec<f64>) -> Result<(), StreamError>,
    ) -> Result<(), StreamError> {
        while let Some((rec, values)) = self.mem.pop_front() {
            f(rec, values)?;
        }
        self.mem_bytes = 0;
        if let Some(spill) = self.spill.take() {
            let mut reader = spill.into_reader()?;
            let mut rec = Record::default();
            let mut values = Vec::new();
            for _ in 0..self.spilled {
                read_entry(&mut reader, &mut rec, &mut values)?;
                f(std::mem::take(&mut rec), std::mem::take(&mut values))?;
            }
            self.spilled = 0;
        }
        Ok(())
    }
}

/// The temporary file of a [`Held`].
struct Spill {
    file: BufWriter<File>,
    /// One entry's bytes (reused).
    scratch: Vec<u8>,
    /// The file's path while it still has one (not unlinked): removed on drop.
    _path: ScratchPath,
}

/// An I/O error of the temporary file, named.
fn spill_error(e: std::io::Error) -> StreamError {
    StreamError::io("holding records in a temporary file", e)
}

impl Spill {
    /// A new temporary file, unlinked at once where the system allows (module docs).
    fn create() -> Result<Self, StreamError> {
        let (file, path) = scratch_file::create("held")?;
        Ok(Spill {
            file: BufWriter::with_capacity(1 << 16, file),
            scratch: Vec::new(),
            _path: path,
        })
    }

    fn write(&mut self, rec: &Record, values: &[f64]) -> Result<(), StreamError> {
        self.scratch.clear();
        write_entry(&mut self.scratch, rec, values);
        self.file.write_all(&self.scratch).map_err(spill_error)
    }

    /// The file rewound for reading (this holder's path, if any, still removed on drop).
    fn into_reader(mut self) -> Result<SpillReader, StreamError> {
        self.file.flush().map_err(spill_error)?;
        let mut file = self.file.get_ref().try_clone().map_err(spill_error)?;
        file.rewind().map_err(spill_error)?;
        Ok(SpillReader {
            file: BufReader::with_capacity(1 << 16, file),
            _owner: self,
        })
    }
}

/// A temporary file being read back; the [`Spill`] it came from removes it when dropped.
struct SpillReader {
    file: BufReader<File>,
    _owner: Spill,
}

// The file's layout, one entry a record, all integers little-endian: the position (record,
// line: u64 each), the token count, the text length and the value count (u64 each), then each
// token as a tag byte and its payload, the text, the values (f64). Exact: every token comes
// back as it went (a number's text included), which no stream format guarantees.

const TAG_OBJ: u8 = 0;
const TAG_ARR: u8 = 1;
const TAG_KEY: u8 = 2;
const TAG_STR: u8 = 3;
const TAG_FLOAT: u8 = 4;
const TAG_TEXT: u8 = 5;
const TAG_INT: u8 = 6;
const TAG_UINT: u8 = 7;
const TAG_FALSE: u8 = 8;
const TAG_TRUE: u8 = 9;
const TAG_NULL: u8 = 10;

fn put_u32(out: &mut Vec<u8>, x: u32) {
    out.extend_from_slice(&x.to_le_bytes());
}

fn put_u64(out: &mut Vec<u8>, x: u64) {
    out.extend_from_slice(&x.to_le_bytes());
}

fn put_span(out: &mut Vec<u8>, s: Span) {
    put_u32(out, s.start);
    put_u32(out, s.len);
}

/// Appends one entry (the layout above).
fn write_entry(out: &mut Vec<u8>, rec: &Record, values: &[f64]) {
    put_u64(out, rec.at.record as u64);
    put_u64(out, rec.at.line as u64);
    put_u64(out, rec.tape.toks.len() as u64);
    put_u64(out, rec.tape.text.len() as u64);
    put_u64(out, values.len() as u64);
    for t in &rec.tape.toks {
        match *t {
            Tok::Obj { fields, len } => {
                out.push(TAG_OBJ);
                put_u32(out, fields);
                put_u32(out, len);
            }
            Tok::Arr { items, len } => {
                out.push(TAG_ARR);
                put_u32(out, items);
                put_u32(out, len);
            }
            Tok::Key(s) => {
                out.push(TAG_KEY);
                put_span(out, s);
            }
            Tok::Str(s) => {
                out.push(TAG_STR);
                put_span(out, s);
            }
            Tok::Float(x) => {
                out.push(TAG_FLOAT);
                out.extend_from_slice(&x.to_le_bytes());
            }
            Tok::Text(x, s) => {
                out.push(TAG_TEXT);
                out.extend_from_slice(&x.to_le_bytes());
                put_span(out, s);
            }
            Tok::Int(x) => {
                out.push(TAG_INT);
                out.extend_from_slice(&x.to_le_bytes());
            }
            Tok::UInt(x) => {
                out.push(TAG_UINT);
                put_u64(out, x);
            }
            Tok::Bool(b) => out.push(if b { TAG_TRUE } else { TAG_FALSE }),
            Tok::Null => out.push(TAG_NULL),
        }
    }
    out.extend_from_slice(&rec.tape.text);
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
}

fn damaged() -> StreamError {
    spill_error(std::io::Error::new(
        std::io::ErrorKind::InvalidData,
        "the temporary file does not read back as written",
    ))
}

fn get<const N: usize>(r: &mut impl Read) -> Result<[u8; N], StreamError> {
    let mut b = [0u8; N];
    r.read_exact(&mut b).map_err(spill_error)?;
    Ok(b)
}

fn get_u32(r: &mut impl Read) -> Result<u32, StreamError> {
    get::<4>(r).map(u32::from_le_bytes)
}

fn get_u64(r: &mut impl Read) -> Result<u64, StreamError> {
    get::<8>(r).map(u64::from_le_bytes)
}

fn get_usize(r: &mut impl Read) -> Result<usize, StreamError> {
    usize::try_from(get_u64(r)?).map_err(|_| damaged())
}

fn get_span(r: &mut impl Read) -> Result<Span, StreamError> {
    Ok(Span {
        start: get_u32(r)?,
        len: get_u32(r)?,
    })
}

/// Reads one entry into `rec` and `values` (their storage reused). The file is this
/// process's own, but its counts are checked against the records' limits all the same.
fn read_entry(
    r: &mut SpillReader,
    rec: &mut Record,
    values: &mut Vec<f64>,
) -> Result<(), StreamError> {
    let r = &mut r.file;
    rec.at = Position {
        record: get_usize(r)?,
        line: get_usize(r)?,
    };
    let (toks, text, nvalues) = (get_usize(r)?, get_usize(r)?, get_usize(r)?);
    if toks > MAX_RECORD_TOKENS || text > u32::MAX as usize || nvalues > MAX_RECORD_TOKENS {
        return Err(damaged());
    }
    let tape: &mut Tape = &mut rec.tape;
    tape.clear();
    tape.toks.reserve(toks);
    for _ in 0..toks {
        let tag = get::<1>(r)?[0];
        let t = match tag {
            TAG_OBJ => Tok::Obj {
                fields: get_u32(r)?,
                len: get_u32(r)?,
            },
            TAG_ARR => Tok::Arr {
                items: get_u32(r)?,
                len: get_u32(r)?,
            },
            TAG_KEY => Tok::Key(get_span(r)?),
            TAG_STR => Tok::Str(get_span(r)?),
            TAG_FLOAT => Tok::Float(f64::from_le_bytes(get::<8>(r)?)),
            TAG_TEXT => Tok::Text(f64::from_le_bytes(get::<8>(r)?), get_span(r)?),
            TAG_INT => Tok::Int(i64::from_le_bytes(get::<8>(r)?)),
            TAG_UINT => Tok::UInt(get_u64(r)?),
            TAG_FALSE => Tok::Bool(false),
            TAG_TRUE => Tok::Bool(true),
            TAG_NULL => Tok::Null,
            _ => return Err(damaged()),
        };
        tape.toks.push(t);
    }
    tape.text.resize(text, 0);
    r.read_exact(&mut tape.text).map_err(spill_error)?;
    values.clear();
    values.reserve(nvalues);
    for _ in 0..nvalues {
        values.push(f64::from_le_bytes(get::<8>(r)?));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(i: usize, note: &str) -> Record {
        let line = format!(
            r#"{{"type":"Note","i":{i},"x":[1.50,-2e0,18446744073709551615],"s":"{note}","n":null,"b":[true,false],"o":{{}}}}"#
        );
        let mut tape = Tape::default();
        crate::json::parse_record(line.as_bytes(), &mut tape).expect("parses");
        Record {
            tape,
            at: Position {
                record: i + 1,
                line: i + 1,
            },
        }
    }

    /// Past a small budget the records go to the file and come back exact and in order; the
    /// file has no name in the temporary directory (unlinked) while it is used.
    #[test]
    fn records_past_the_budget_spill_and_come_back_exact_in_order() {
        /// Enough records that most of them spill with the budget below.
        const RECORDS: usize = 200;
        /// A budget of a few records.
        const BUDGET: usize = 8 << 10;
        let mut held = Held::new(BUDGET);
        let mut expected = Vec::new();
        for i in 0..RECORDS {
            let rec = record(i, &"q".repeat(i));
            let values: Vec<f64> = (0..i % 5).map(|k| k as f64 * 0.5 - 1.0).collect();
            expected.push((rec.clone(), values.clone()));
            held.push(rec, values, "test").expect("held");
            assert!(held.memory() <= BUDGET);
        }
        assert_eq!(held.len(), RECORDS);
        assert!(held.spilled() > RECORDS / 2, "{}", held.spilled());
        let mut back = Vec::new();
        held.drain(&mut |r, v| {
            back.push((r, v));
            Ok(())
        })
        .expect("drains");
        assert!(held.is_empty());
        assert_eq!(back.len(), expected.len());
        for (b, e) in back.iter().zip(&expected) {
            assert_eq!(b.0.tape, e.0.tape);
            assert_eq!(b.0.at, e.0.at);
            assert_eq!(b.1, e.1);
        }
        // The number texts came back too: written back as they came.
        let mut out = Vec::new();
        crate::json::write_record(&mut out, &back[3].0.tape);
        assert!(String::from_utf8_lossy(&out).contains("[1.50,-2e0,18446744073709551615]"));
    }
}

//! A filter's streams: the options every filter takes ([`StreamOptions`]: `--input`,
//! `--output`, `--format`, `--keep-going`), the streams they open, and the [`Pipe`] a filter
//! reads and writes records through.
//!
//! A record filter runs on a pipe from its input to its output ([`StreamOptions::filter`]); a
//! sink reads its whole input through a pipe to nowhere, then writes what it made
//! ([`StreamOptions::read`], [`StreamOptions::with_output`]). The output is standard output, or
//! a file written atomically (nothing is left behind when the filter fails).

use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;

use crate::error::{FieldError, FilterError, StreamError};
use crate::stream::{Format, Record, RecordReader, RecordWriter};
use crate::tape::Tape;

/// How many skipped records are described one by one on standard error (the rest are only
/// counted).
pub const REPORTED_SKIPS: usize = 5;

/// Options of every record filter.
#[derive(clap::Args, Debug, Clone, Default, PartialEq, Eq)]
pub struct StreamOptions {
    /// Read this file instead of standard input (`-`: standard input).
    #[arg(long, global = true)]
    pub input: Option<PathBuf>,
    /// Write this file (atomically) instead of standard output (`-`: standard output;
    /// `to-mesh`: the mesh file).
    #[arg(short = 'o', long, global = true)]
    pub output: Option<PathBuf>,
    /// Output format (default: the input's; for fit the binary form, or JSON Lines on a
    /// terminal or for an output named .jsonl).
    #[arg(long, global = true, value_enum)]
    pub format: Option<Format>,
    /// Skip malformed records (counted on standard error) instead of stopping.
    #[arg(long, global = true)]
    pub keep_going: bool,
}

impl StreamOptions {
    /// Opens the input: the `--input` file, or standard input.
    pub fn open_input(&self) -> Result<Box<dyn BufRead>, FilterError> {
        Ok(match self.input.as_deref().and_then(fitjob::destination) {
            Some(p) => Box::new(BufReader::with_capacity(
                1 << 16,
                std::fs::File::open(p)
                    .map_err(|e| StreamError::io(format!("opening {}", p.display()), e))?,
            )),
            None => Box::new(BufReader::with_capacity(1 << 16, std::io::stdin().lock())),
        })
    }

    /// Runs `f` on the output: standard output, or the `--output` file written atomically.
    pub fn with_output(
        &self,
        f: &mut dyn FnMut(&mut dyn Write) -> Result<(), FilterError>,
    ) -> Result<(), FilterError> {
        match self.output.as_deref().and_then(fitjob::destination) {
            None => {
                let stdout = std::io::stdout();
                let mut lock = stdout.lock();
                f(&mut lock)?;
                lock.flush()
                    .map_err(|e| StreamError::io("writing the output", e).into())
            }
            Some(p) => {
                let mut failure = None;
                let result = meshio::outfile::write_atomic_with(p, &mut |w| {
                    f(w).map_err(|e| {
                        failure = Some(e);
                        std::io::Error::other("the filter failed")
                    })
                });
                match failure {
                    Some(e) => Err(e),
                    None => result.map_err(|e| FilterError::from(render::RenderError::from(e))),
                }
            }
        }
    }

    /// Runs a record filter named `name`: `f` on a pipe from the input to the output, in the
    /// chosen format (default: the input's).
    pub fn filter<T>(
        &self,
        name: &'static str,
        f: &mut dyn FnMut(&mut Pipe) -> Result<T, FilterError>,
    ) -> Result<(), FilterError> {
        let mut input = self.open_input()?;
        self.with_output(&mut |out| {
            let mut pipe = Pipe::new(name, &mut *input, out, self.format, self.keep_going);
            f(&mut pipe).map(|_| ())
        })
    }

    /// Reads the input for a sink named `name`: `f` on a pipe from the input to nowhere (what
    /// the sink makes is written afterwards, [`StreamOptions::with_output`]).
    pub fn read<T>(
        &self,
        name: &'static str,
        f: &mut dyn FnMut(&mut Pipe) -> Result<T, FilterError>,
    ) -> Result<T, FilterError> {
        let mut input = self.open_input()?;
        let mut nothing = std::io::sink();
        let mut pipe = Pipe::new(name, &mut *input, &mut nothing, None, self.keep_going);
        f(&mut pipe)
    }
}

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
    /// Records read so far.
    pub records: u64,
    /// The records read, on a terminal once the filter has run a moment (`progress`: only the
    /// pipeline's last stage shows it).
    progress: progress::Progress,
}

/// How often the progress line's count is renewed, in records (a message built per record
/// would cost more than some filters' work).
const PROGRESS_EVERY: u64 = 65_536;

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
            records: 0,
            progress: progress::Progress::spinner(name),
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
                    self.records += 1;
                    if self.records % PROGRESS_EVERY == 1 {
                        let n = self.records;
                        self.progress.stage_with(|| format!("{n} records read"));
                    }
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
                self.progress.say(&format!("{}: skipped {e}", self.name));
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

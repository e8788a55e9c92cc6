//! Unnamed temporary files for data a filter keeps past its memory budget ([`crate::hold`]'s
//! records, [`crate::triangle_store`]'s triangles).
//!
//! A file is created in a directory (the system's temporary directory, `TMPDIR`, unless a
//! caller chooses) and unlinked at once (Unix): the name is gone before anything is written,
//! and the space is returned when the file is closed — on success, on an error, and on any
//! interrupt or kill, with no handler needed. Where unlinking an open file is not possible,
//! the file is registered with [`meshio::outfile::in_flight`] and removed when its
//! [`ScratchPath`] is dropped.

use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::StreamError;

/// Distinguishes the temporary files of one process.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// The path of a temporary file while it still has one (not unlinked): removed on drop.
pub struct ScratchPath(Option<PathBuf>);

impl Drop for ScratchPath {
    fn drop(&mut self) {
        if let Some(path) = self.0.take() {
            let _ = std::fs::remove_file(&path);
            meshio::outfile::landed(&path);
        }
    }
}

/// A new temporary file `dir/.testbed-{kind}-{pid}-{n}`, open for reading and writing and
/// unlinked at once where the system allows (module docs), with the guard that removes it
/// otherwise. An error names the directory.
pub fn create_in(dir: &Path, kind: &str) -> Result<(File, ScratchPath), StreamError> {
    let mut tries = 0;
    let (file, path) = loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = dir.join(format!(".testbed-{kind}-{}-{n}", std::process::id()));
        match File::options()
            .read(true)
            .write(true)
            .create_new(true)
            .open(&path)
        {
            Ok(f) => break (f, path),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && tries < 100 => {
                tries += 1;
            }
            Err(e) => {
                return Err(StreamError::io(
                    format!("creating a temporary file in {}", dir.display()),
                    e,
                ))
            }
        }
    };
    meshio::outfile::in_flight(&path);
    let path = if std::fs::remove_file(&path).is_ok() {
        meshio::outfile::landed(&path);
        None
    } else {
        Some(path)
    };
    Ok((file, ScratchPath(path)))
}

/// [`create_in`] the system's temporary directory (`TMPDIR`).
pub fn create(kind: &str) -> Result<(File, ScratchPath), StreamError> {
    create_in(&std::env::temp_dir(), kind)
}

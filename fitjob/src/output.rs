//! Writing the job's outputs: atomically (`meshio::outfile`), to a file or to standard
//! output, and the checks made on every output path before any work is done.

use std::io::Write;
use std::path::Path;

use crate::error::JobError;

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename),
/// creating the parent directory if needed; `None` writes to standard output.
pub fn write_result(path: Option<&Path>, bytes: &[u8]) -> Result<(), JobError> {
    match path {
        Some(p) => {
            if let Some(parent) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                ensure_dir(parent)?;
            }
            meshio::outfile::write_atomic(p, bytes).map_err(JobError::from)
        }
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(bytes)
                .and_then(|_| out.flush())
                .map_err(|source| JobError::Write {
                    path: "<stdout>".into(),
                    source,
                })
        }
    }
}

/// Writes to `path` atomically what `produce` writes, piece by piece (no full copy in memory);
/// `None` streams to standard output.
pub fn write_result_with(
    path: Option<&Path>,
    produce: &mut dyn FnMut(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), JobError> {
    match path {
        Some(p) => {
            if let Some(parent) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                ensure_dir(parent)?;
            }
            meshio::outfile::write_atomic_with(p, produce).map_err(JobError::from)
        }
        None => {
            let mut out = std::io::BufWriter::new(std::io::stdout().lock());
            produce(&mut out)
                .and_then(|_| out.flush())
                .map_err(|source| JobError::Write {
                    path: "<stdout>".into(),
                    source,
                })
        }
    }
}

/// Creates a results directory (and its parents).
pub fn ensure_dir(dir: &Path) -> Result<(), JobError> {
    std::fs::create_dir_all(dir).map_err(|source| JobError::Write {
        path: dir.to_path_buf(),
        source,
    })
}

/// Refuses, before any work is done, an output `out` (given by `option`) that could not be
/// written at the end: a path that exists and is not a regular file or a link to one (a
/// directory, a device …: [`meshio::outfile::writable_target`]), or the input file itself
/// ([`refuse_overwriting_input`]). A run over a large mesh then fails in milliseconds instead
/// of after its whole computation.
pub fn refuse_unwritable(option: &'static str, out: &Path, input: &str) -> Result<(), JobError> {
    meshio::outfile::writable_target(out)?;
    refuse_overwriting_input(option, out, input)
}

/// Refuses to write `out` (given by `option`, such as `--out`) when it is the input file `input`
/// (the same file, by any path): a conversion or fit would otherwise destroy its own input.
pub fn refuse_overwriting_input(
    option: &'static str,
    out: &Path,
    input: &str,
) -> Result<(), JobError> {
    let (Ok(a), Ok(b)) = (std::fs::canonicalize(out), std::fs::canonicalize(input)) else {
        return Ok(());
    };
    if a == b {
        return Err(JobError::OutputIsInput {
            option,
            path: out.to_path_buf(),
        });
    }
    Ok(())
}

/// The writable mesh format `path`'s extension names, or the error naming `option` and the
/// extensions that would do.
pub fn mesh_format_for(
    option: &'static str,
    path: &Path,
) -> Result<&'static dyn meshio::MeshFormat, JobError> {
    meshio::format_for_path(path)
        .filter(|f| f.can_write())
        .ok_or_else(|| JobError::UnsupportedOutputFormat {
            option,
            path: path.to_path_buf(),
            writable: writable_extensions(),
        })
}

/// The extensions of the writable mesh formats as a message lists them (`.obj, .ply, …`;
/// `meshio::writable_extensions`).
pub fn writable_extensions() -> String {
    meshio::writable_extensions()
        .iter()
        .map(|e| format!(".{e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

//! Writing results: atomically, to a file or to standard output.

use std::io::Write;
use std::path::Path;

use crate::error::ExperimentError;

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename),
/// creating the parent directory if needed; `None` writes to standard output.
pub fn write_result(path: Option<&Path>, bytes: &[u8]) -> Result<(), ExperimentError> {
    match path {
        Some(p) => {
            if let Some(parent) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                ensure_dir(parent)?;
            }
            render::write_atomic(p, bytes).map_err(ExperimentError::from)
        }
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(bytes)
                .and_then(|_| out.flush())
                .map_err(|source| ExperimentError::Write {
                    path: "<stdout>".into(),
                    source,
                })
        }
    }
}

/// Creates a results directory (and its parents).
pub fn ensure_dir(dir: &Path) -> Result<(), ExperimentError> {
    std::fs::create_dir_all(dir).map_err(|source| ExperimentError::Write {
        path: dir.to_path_buf(),
        source,
    })
}

/// Refuses to write `out` when it is the input file `input` (the same file, by any path): a
/// conversion or fit would otherwise destroy its own input.
pub fn refuse_overwriting_input(out: &Path, input: &str) -> Result<(), ExperimentError> {
    let (Ok(a), Ok(b)) = (std::fs::canonicalize(out), std::fs::canonicalize(input)) else {
        return Ok(());
    };
    if a == b {
        return Err(ExperimentError::Usage(format!(
            "{}: the output is the input file; choose another output path",
            out.display()
        )));
    }
    Ok(())
}

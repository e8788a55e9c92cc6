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
            meshio::outfile::write_atomic(p, bytes).map_err(ExperimentError::from)
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

/// Writes to `path` atomically what `produce` writes, piece by piece (no full copy in memory);
/// `None` streams to standard output.
pub fn write_result_with(
    path: Option<&Path>,
    produce: &mut dyn FnMut(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), ExperimentError> {
    match path {
        Some(p) => {
            if let Some(parent) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                ensure_dir(parent)?;
            }
            meshio::outfile::write_atomic_with(p, produce).map_err(ExperimentError::from)
        }
        None => {
            let mut out = std::io::BufWriter::new(std::io::stdout().lock());
            produce(&mut out)
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

/// Refuses, before any work is done, an output `out` (given by `option`) that could not be
/// written at the end: a path that exists and is not a regular file or a link to one (a
/// directory, a device …: [`meshio::outfile::writable_target`]), or the input file itself
/// ([`refuse_overwriting_input`]). A run over a large mesh then fails in milliseconds instead
/// of after its whole computation.
pub fn refuse_unwritable(
    option: &'static str,
    out: &Path,
    input: &str,
) -> Result<(), ExperimentError> {
    meshio::outfile::writable_target(out)?;
    refuse_overwriting_input(option, out, input)
}

/// Refuses to write `out` (given by `option`, such as `--out`) when it is the input file `input`
/// (the same file, by any path): a conversion or fit would otherwise destroy its own input.
pub fn refuse_overwriting_input(
    option: &'static str,
    out: &Path,
    input: &str,
) -> Result<(), ExperimentError> {
    let (Ok(a), Ok(b)) = (std::fs::canonicalize(out), std::fs::canonicalize(input)) else {
        return Ok(());
    };
    if a == b {
        return Err(ExperimentError::OutputIsInput {
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
) -> Result<&'static dyn meshio::MeshFormat, ExperimentError> {
    meshio::format_for_path(path)
        .filter(|f| f.can_write())
        .ok_or_else(|| ExperimentError::UnsupportedOutputFormat {
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

/// A report as pretty-printed JSON with a final newline, the form of every `report.json` and
/// shard file; `what` names the report in the error.
pub fn pretty_json(
    value: &serde_json::Value,
    what: &'static str,
) -> Result<String, ExperimentError> {
    let mut text = serde_json::to_string_pretty(value)
        .map_err(|source| ExperimentError::Json { what, source })?;
    text.push('\n');
    Ok(text)
}

/// A result directory written whole: every file goes into a fresh staging directory beside the
/// final one, and [`Staged::commit`] swaps it in (the old directory renamed aside, the new one
/// renamed into place, the old one removed), so a reader never sees files of two runs mixed.
/// Dropped without a commit (an error), the staging directory is removed; on an interrupt the
/// handler of `main` removes it ([`meshio::outfile::remove_in_flight`]).
pub struct Staged {
    final_dir: std::path::PathBuf,
    staging: std::path::PathBuf,
    committed: bool,
}

impl Staged {
    /// Starts a result directory at `out` (which may exist: it is replaced on commit, but must be
    /// a directory, not a file, a device or a link to one).
    pub fn begin(out: &Path) -> Result<Self, ExperimentError> {
        Self::begin_keeping(out, |_| false)
    }

    /// [`Staged::begin`], carrying over (copying into the staging directory) the files of the
    /// existing directory whose names `keep` accepts — the shard files of a sweep, which other
    /// runs wrote and the swap must not lose.
    pub fn begin_keeping(out: &Path, keep: impl Fn(&str) -> bool) -> Result<Self, ExperimentError> {
        if let Ok(meta) = std::fs::symlink_metadata(out) {
            if !meta.is_dir() {
                return Err(ExperimentError::NotADirectory {
                    path: out.to_path_buf(),
                });
            }
        }
        let name = out
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "results".into());
        let staging = out.with_file_name(format!(".{name}.staging-{}", std::process::id()));
        if staging.exists() {
            let _ = std::fs::remove_dir_all(&staging);
        }
        ensure_dir(&staging)?;
        meshio::outfile::in_flight(&staging);
        let staged = Staged {
            final_dir: out.to_path_buf(),
            staging,
            committed: false,
        };
        if let Ok(entries) = std::fs::read_dir(out) {
            for e in entries.flatten() {
                let name = e.file_name().to_string_lossy().into_owned();
                if keep(&name) && e.path().is_file() {
                    std::fs::copy(e.path(), staged.staging.join(&name)).map_err(|source| {
                        ExperimentError::Write {
                            path: staged.staging.join(&name),
                            source,
                        }
                    })?;
                }
            }
        }
        Ok(staged)
    }

    /// Where to write the files now.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// Swaps the staging directory in.
    pub fn commit(mut self) -> Result<(), ExperimentError> {
        let write_err = |path: &Path, source| ExperimentError::Write {
            path: path.to_path_buf(),
            source,
        };
        let old = self.final_dir.with_file_name(format!(
            ".{}.old-{}",
            self.final_dir
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            std::process::id()
        ));
        let had_old = self.final_dir.exists();
        if had_old {
            std::fs::rename(&self.final_dir, &old).map_err(|e| write_err(&self.final_dir, e))?;
        }
        if let Err(e) = std::fs::rename(&self.staging, &self.final_dir) {
            if had_old {
                let _ = std::fs::rename(&old, &self.final_dir);
            }
            return Err(write_err(&self.final_dir, e));
        }
        meshio::outfile::landed(&self.staging);
        self.committed = true;
        if had_old {
            let _ = std::fs::remove_dir_all(&old);
        }
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
            meshio::outfile::landed(&self.staging);
        }
    }
}

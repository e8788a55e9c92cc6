//! Writing results: atomically, to a file or to standard output (the fit job's writers,
//! `fitjob::output`), as pretty JSON, and as result directories swapped in whole.

use std::path::Path;

use crate::error::ExperimentError;

/// Writes `bytes` to `path` atomically, or to standard output ([`fitjob::output::write_result`]).
pub fn write_result(path: Option<&Path>, bytes: &[u8]) -> Result<(), ExperimentError> {
    Ok(fitjob::output::write_result(path, bytes)?)
}

/// Creates a results directory and its parents ([`fitjob::output::ensure_dir`]).
pub fn ensure_dir(dir: &Path) -> Result<(), ExperimentError> {
    Ok(fitjob::output::ensure_dir(dir)?)
}

/// Refuses an output that could not be written at the end, before any work
/// ([`fitjob::output::refuse_unwritable`]).
pub fn refuse_unwritable(
    option: &'static str,
    out: &Path,
    input: &str,
) -> Result<(), ExperimentError> {
    Ok(fitjob::output::refuse_unwritable(option, out, input)?)
}

/// Refuses an output that is the input file ([`fitjob::output::refuse_overwriting_input`]).
pub fn refuse_overwriting_input(
    option: &'static str,
    out: &Path,
    input: &str,
) -> Result<(), ExperimentError> {
    Ok(fitjob::output::refuse_overwriting_input(
        option, out, input,
    )?)
}

/// The writable mesh format `path`'s extension names ([`fitjob::output::mesh_format_for`]).
pub fn mesh_format_for(
    option: &'static str,
    path: &Path,
) -> Result<&'static dyn meshio::MeshFormat, ExperimentError> {
    Ok(fitjob::output::mesh_format_for(option, path)?)
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

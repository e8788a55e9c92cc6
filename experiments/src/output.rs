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

/// The directory a study writes its results into for `-o, --output DIR`: `out` itself when it
/// is a directory or does not exist yet, the target of a symbolic link to a directory (so that
/// the staged swap replaces the target and keeps the link); anything else (a regular file, a
/// device, a link to one, a dangling link) is refused: results never go over a file that is
/// not a results directory.
pub fn results_dir(out: &Path) -> Result<std::path::PathBuf, ExperimentError> {
    let refused = || ExperimentError::NotADirectory {
        path: out.to_path_buf(),
    };
    match std::fs::symlink_metadata(out) {
        Err(_) => Ok(out.to_path_buf()),
        Ok(meta) if meta.is_dir() => Ok(out.to_path_buf()),
        Ok(meta) if meta.file_type().is_symlink() => match std::fs::metadata(out) {
            Ok(target) if target.is_dir() => std::fs::canonicalize(out).map_err(|_| refused()),
            _ => Err(refused()),
        },
        Ok(_) => Err(refused()),
    }
}

/// The manifest every results directory carries: the names of the entries the study that
/// wrote it put there, one a line. A directory is a study's to replace only when it is empty or
/// its manifest lists every entry in it ([`Staged::begin`]).
pub const MANIFEST: &str = ".triwb-results";

/// How many entries a refusal names ([`ExperimentError::ForeignFiles`]).
const NAMED: usize = 5;

/// Refuses `dir` (an existing results directory) when it holds an entry its manifest does not
/// list (every entry, without a manifest) and `own` does not claim (a sweep's shard files,
/// which other runs write straight into it): a file of the user's, which the swap would delete.
fn refuse_foreign(dir: &Path, own: &dyn Fn(&str) -> bool) -> Result<(), ExperimentError> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    let listed: std::collections::HashSet<String> = std::fs::read_to_string(dir.join(MANIFEST))
        .map(|t| t.lines().map(str::to_owned).collect())
        .unwrap_or_default();
    let mut foreign: Vec<String> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != MANIFEST && !listed.contains(n) && !own(n))
        .collect();
    if foreign.is_empty() {
        return Ok(());
    }
    foreign.sort();
    let more = foreign.len().saturating_sub(NAMED);
    foreign.truncate(NAMED);
    Err(ExperimentError::ForeignFiles {
        path: dir.to_path_buf(),
        names: foreign,
        more,
    })
}

/// A result directory written whole: every file goes into a fresh staging directory beside the
/// final one, and [`Staged::commit`] swaps it in (the old directory renamed aside, the new one
/// renamed into place, the old one removed), so a reader never sees files of two runs mixed.
/// Only a directory that is empty, new, or holds nothing but what its manifest ([`MANIFEST`])
/// lists is replaced: anything else is refused before any work, so no file of the user's is
/// ever deleted. Dropped without a commit (an error), the staging directory is removed; on an
/// interrupt the handler of `main` removes it ([`meshio::outfile::remove_in_flight`]).
pub struct Staged {
    final_dir: std::path::PathBuf,
    staging: std::path::PathBuf,
    committed: bool,
    /// The entries of the final directory the study claims without a manifest
    /// ([`Staged::begin_keeping`]).
    own: Box<dyn Fn(&str) -> bool>,
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
    ///
    /// A symbolic link to a directory is that directory: the swap happens at the link's target
    /// (the link is kept and still points to the results). A link to anything else, or a
    /// dangling one, is refused like a file.
    pub fn begin_keeping(
        out: &Path,
        keep: impl Fn(&str) -> bool + 'static,
    ) -> Result<Self, ExperimentError> {
        let out = &results_dir(out)?;
        refuse_foreign(out, &keep)?;
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
        let mut staged = Staged {
            final_dir: out.to_path_buf(),
            staging,
            committed: false,
            own: Box::new(|_| false),
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
        staged.own = Box::new(keep);
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
        // The manifest: every entry this run put in the staging directory.
        let mut written: Vec<String> = std::fs::read_dir(&self.staging)
            .map_err(|e| write_err(&self.staging, e))?
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n != MANIFEST)
            .collect();
        written.sort();
        let mut manifest = written.join("\n");
        manifest.push('\n');
        std::fs::write(self.staging.join(MANIFEST), manifest)
            .map_err(|e| write_err(&self.staging.join(MANIFEST), e))?;
        // Nothing foreign may have appeared since the run began (entries the run carried over
        // are in the staging directory, hence in the manifest).
        refuse_foreign(&self.final_dir, &|n| {
            (self.own)(n) || self.staging.join(n).exists()
        })?;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A symbolic link to a directory is a directory to write into: the results land in the
    /// target, the link stays a link; a link to a file and a file are refused, untouched.
    #[cfg(unix)]
    #[test]
    fn a_link_to_a_directory_is_written_through_and_a_file_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("target");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("old.txt"), "old run\n").unwrap();
        // A previous run's directory: its manifest lists what it wrote.
        std::fs::write(target.join(MANIFEST), "old.txt\n").unwrap();
        let link = dir.path().join("link");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let staged = Staged::begin(&link).unwrap();
        std::fs::write(staged.path().join("report.md"), "new run\n").unwrap();
        staged.commit().unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(
            std::fs::read_to_string(link.join("report.md")).unwrap(),
            "new run\n"
        );
        assert_eq!(
            std::fs::read_to_string(target.join("report.md")).unwrap(),
            "new run\n"
        );
        assert!(!target.join("old.txt").exists(), "swapped in whole");
        // A regular file, and a link to one, are refused and left as they were.
        let file = dir.path().join("file.txt");
        std::fs::write(&file, "mine\n").unwrap();
        let file_link = dir.path().join("file-link");
        std::os::unix::fs::symlink(&file, &file_link).unwrap();
        for p in [&file, &file_link, &dir.path().join("dangling")] {
            if p.ends_with("dangling") {
                std::os::unix::fs::symlink(dir.path().join("nowhere"), p).unwrap();
            }
            let e = Staged::begin(p).err().expect("refused");
            assert!(
                e.to_string().contains("exists and is not a directory"),
                "{e}"
            );
        }
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "mine\n");
        // Nothing left beside them.
        let mut names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            ["dangling", "file-link", "file.txt", "link", "target"]
        );
    }

    /// `-o DIR` on a directory of the user's (`thesis/thesis.tex`) is refused before any work,
    /// the file untouched and named; a directory a run wrote is replaced whole by the next run
    /// (its manifest lists the run's files); a file the user put into it afterwards makes it
    /// the user's again; the files a sweep claims (`begin_keeping`) are not the user's.
    #[test]
    fn a_directory_with_files_no_run_wrote_is_refused_and_kept() {
        let dir = tempfile::tempdir().unwrap();
        let thesis = dir.path().join("thesis");
        std::fs::create_dir(&thesis).unwrap();
        std::fs::write(thesis.join("thesis.tex"), "x\n").unwrap();
        let e = Staged::begin(&thesis).err().expect("refused");
        assert!(matches!(e, ExperimentError::ForeignFiles { .. }), "{e}");
        assert!(e.to_string().contains("thesis.tex"), "{e}");
        assert_eq!(
            std::fs::read_to_string(thesis.join("thesis.tex")).unwrap(),
            "x\n"
        );
        // No staging directory left beside it.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        // A new directory, then the next run over it.
        let out = dir.path().join("out");
        for run in ["first", "second"] {
            let staged = Staged::begin(&out).unwrap();
            std::fs::write(staged.path().join("report.md"), run).unwrap();
            if run == "first" {
                std::fs::write(staged.path().join("only-first.txt"), run).unwrap();
            }
            staged.commit().unwrap();
        }
        assert_eq!(
            std::fs::read_to_string(out.join("report.md")).unwrap(),
            "second"
        );
        assert!(
            !out.join("only-first.txt").exists(),
            "the run's own files are replaced"
        );
        assert_eq!(
            std::fs::read_to_string(out.join(MANIFEST)).unwrap(),
            "report.md\n"
        );
        // A file of the user's put in afterwards: refused, kept.
        std::fs::write(out.join("notes.txt"), "mine\n").unwrap();
        assert!(Staged::begin(&out).is_err());
        assert!(out.join("notes.txt").exists());
        // Files the study claims are carried over, not refused.
        std::fs::remove_file(out.join("notes.txt")).unwrap();
        std::fs::write(out.join("part-1.jsonl"), "{}\n").unwrap();
        let staged = Staged::begin_keeping(&out, |n| n.starts_with("part-")).unwrap();
        staged.commit().unwrap();
        assert!(out.join("part-1.jsonl").exists());
    }
}

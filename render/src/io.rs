//! Atomic file output shared by all renderers.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::RenderError;

/// Distinguishes temporary files of concurrent writes from one process.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Write `bytes` to `path` atomically: the bytes go to a temporary file in the same directory
/// (so the rename cannot cross file systems), are flushed to disk, and the temporary file is then
/// renamed over `path`. Readers see either the old file or the complete new one, and a failure
/// leaves an existing `path` untouched and removes the temporary file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), RenderError> {
    let io_err = |source| RenderError::Io {
        path: path.to_path_buf(),
        source,
    };
    let tmp = temp_sibling(path)?;
    let result = (|| {
        let mut file = fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        drop(file);
        fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        // Best effort: the temporary file may not exist if creating it was what failed.
        let _ = fs::remove_file(&tmp);
        return Err(io_err(e));
    }
    Ok(())
}

/// `dir/.name.tmp-<pid>-<n>` beside `path`.
fn temp_sibling(path: &Path) -> Result<PathBuf, RenderError> {
    let name = path.file_name().ok_or_else(|| RenderError::NoFileName {
        path: path.to_path_buf(),
    })?;
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".tmp-{}-{n}", std::process::id()));
    Ok(path.with_file_name(tmp_name))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn writes_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        write_atomic(&path, b"hello").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"hello");
        assert_eq!(entries(dir.path()), vec!["out.txt".to_string()]);
    }

    #[test]
    fn replaces_an_existing_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        fs::write(&path, b"a much longer old content").unwrap();
        write_atomic(&path, b"new").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        assert_eq!(entries(dir.path()), vec!["out.txt".to_string()]);
    }

    #[test]
    fn relative_bare_file_name_has_a_sibling_in_the_same_directory() {
        let tmp = temp_sibling(Path::new("fig.png")).unwrap();
        assert_eq!(tmp.parent(), Some(Path::new("")));
        assert!(tmp.to_string_lossy().starts_with(".fig.png.tmp-"));
    }

    #[test]
    fn failures_name_the_file_and_keep_nothing() {
        let dir = tempfile::tempdir().unwrap();
        // A directory that does not exist: creating the temporary file fails.
        let path = dir.path().join("missing").join("out.txt");
        let err = write_atomic(&path, b"x").unwrap_err();
        assert!(matches!(err, RenderError::Io { .. }));
        assert!(err.to_string().contains("out.txt"));
        assert!(entries(dir.path()).is_empty());
        // No file name at all.
        let err = write_atomic(Path::new("/"), b"x").unwrap_err();
        assert!(matches!(err, RenderError::NoFileName { .. }));
    }

    #[test]
    fn rename_failure_removes_the_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        // Renaming a file over a non-empty directory fails on every platform.
        let path = dir.path().join("occupied");
        fs::create_dir(&path).unwrap();
        fs::write(path.join("keep"), b"k").unwrap();
        assert!(write_atomic(&path, b"x").is_err());
        assert_eq!(entries(dir.path()), vec!["occupied".to_string()]);
        assert_eq!(fs::read(path.join("keep")).unwrap(), b"k");
    }
}

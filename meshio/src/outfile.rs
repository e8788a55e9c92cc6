//! File output that cannot destroy anything, shared by every writer of the workbench (mesh
//! files, patches, pictures, reports): the one place results reach the disk.
//!
//! * **Atomic**: bytes go to a temporary sibling, are flushed, and the sibling is renamed over
//!   the path; a reader sees the old file or the whole new one.
//! * **Only over regular files**: a path that exists and is a directory, device, FIFO or socket
//!   is refused ([`OutputError::NotRegularFile`]); a symbolic link is followed to its target,
//!   which must itself be a regular file or not exist (the link stays a link, the target is
//!   replaced atomically).
//! * **No leftovers**: a temporary file is removed when the write fails, and every temporary
//!   path in flight is registered ([`in_flight`]) so that an interrupt handler can remove them
//!   ([`remove_in_flight`]) before the process exits.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// Why an output file could not be written; every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// Writing the file (or its temporary sibling), or renaming it into place, failed.
    #[error("cannot write {path}: {source}", path = .path.display())]
    Io {
        /// The file being written.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The output path has no file name (for example `/` or `..`), so there is nothing to
    /// create a temporary sibling of.
    #[error("cannot write {path}: the path has no file name", path = .path.display())]
    NoFileName {
        /// The offending path.
        path: PathBuf,
    },
    /// The output path exists and is not a regular file (a directory, a device, a FIFO, a
    /// socket, or a symbolic link to one): writing would replace or feed something that is not
    /// a result file.
    #[error("cannot write {path}: it is {kind}, not a regular file (choose a file path; to write to standard output, leave the option out)", path = .path.display())]
    NotRegularFile {
        /// The offending path.
        path: PathBuf,
        /// What it is (`"a directory"`, `"a FIFO"`, …).
        kind: &'static str,
    },
}

/// Distinguishes temporary files of concurrent writes from one process.
static COUNTER: AtomicU64 = AtomicU64::new(0);

/// A set of temporary paths (files or directories) being written.
#[derive(Debug, Default)]
pub struct Registry(Mutex<Vec<PathBuf>>);

impl Registry {
    /// An empty registry.
    pub const fn new() -> Self {
        Registry(Mutex::new(Vec::new()))
    }

    /// Registers a path as in flight.
    pub fn add(&self, path: &Path) {
        if let Ok(mut v) = self.0.lock() {
            v.push(path.to_path_buf());
        }
    }

    /// Unregisters a path (renamed into place or removed).
    pub fn remove(&self, path: &Path) {
        if let Ok(mut v) = self.0.lock() {
            v.retain(|p| p != path);
        }
    }

    /// Removes every registered file and directory from the disk; returns how many were.
    pub fn remove_all(&self) -> usize {
        let paths: Vec<PathBuf> = match self.0.lock() {
            Ok(mut v) => std::mem::take(&mut *v),
            Err(_) => return 0,
        };
        paths
            .iter()
            .filter(|p| {
                if p.is_dir() {
                    fs::remove_dir_all(p).is_ok()
                } else {
                    fs::remove_file(p).is_ok()
                }
            })
            .count()
    }
}

/// The process's temporary files and directories being written, for [`remove_in_flight`].
static IN_FLIGHT: Registry = Registry::new();

/// Registers a temporary path (file or directory) as in flight.
pub fn in_flight(path: &Path) {
    IN_FLIGHT.add(path);
}

/// Unregisters a temporary path (it was renamed into place or removed).
pub fn landed(path: &Path) {
    IN_FLIGHT.remove(path);
}

/// Removes every temporary file and directory of this process still in flight (for an
/// interrupt handler, just before the process exits); returns how many were removed.
pub fn remove_in_flight() -> usize {
    IN_FLIGHT.remove_all()
}

/// What a non-regular file is, for messages.
fn kind_of(meta: &fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_socket() {
            return "a socket";
        }
        if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
    }
    if meta.is_dir() {
        "a directory"
    } else if meta.file_type().is_symlink() {
        "a symbolic link"
    } else {
        "not a regular file"
    }
}

/// The path to write for `path`: itself when it does not exist or is a regular file, the
/// target of a symbolic link when that is a regular file or does not exist; an error otherwise.
pub fn writable_target(path: &Path) -> Result<PathBuf, OutputError> {
    let refuse = |kind| OutputError::NotRegularFile {
        path: path.to_path_buf(),
        kind,
    };
    match fs::symlink_metadata(path) {
        Err(_) => Ok(path.to_path_buf()),
        Ok(meta) if meta.file_type().is_symlink() => match fs::metadata(path) {
            Ok(target) if target.is_file() => {
                fs::canonicalize(path).map_err(|source| OutputError::Io {
                    path: path.to_path_buf(),
                    source,
                })
            }
            Ok(target) => Err(refuse(kind_of(&target))),
            // A dangling link: its target does not exist yet; write through to it.
            Err(_) => fs::read_link(path)
                .map(|t| {
                    if t.is_absolute() {
                        t
                    } else {
                        path.parent().unwrap_or(Path::new("")).join(t)
                    }
                })
                .map_err(|source| OutputError::Io {
                    path: path.to_path_buf(),
                    source,
                }),
        },
        Ok(meta) if meta.is_file() => Ok(path.to_path_buf()),
        Ok(meta) => Err(refuse(kind_of(&meta))),
    }
}

/// Write `bytes` to `path` atomically: the bytes go to a temporary file in the same directory
/// (so the rename cannot cross file systems), are flushed to disk, and the temporary file is then
/// renamed over `path`. Readers see either the old file or the complete new one, and a failure
/// leaves an existing `path` untouched and removes the temporary file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_atomic_with(path, &mut |w| w.write_all(bytes))
}

/// [`write_atomic`] for output produced piece by piece: `produce` writes into a buffered
/// temporary file, which is flushed, synced and renamed over `path` only if `produce` succeeds
/// (so gigabytes of output never sit in memory, and a failure still leaves `path` untouched).
/// Output larger than one buffer goes to the device past the page cache where the file system
/// allows ([`crate::direct`]).
pub fn write_atomic_with(
    path: &Path,
    produce: &mut dyn FnMut(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), OutputError> {
    let io_err = |source| OutputError::Io {
        path: path.to_path_buf(),
        source,
    };
    let target = writable_target(path)?;
    let path = target.as_path();
    let tmp = temp_sibling(path)?;
    in_flight(&tmp);
    let result = (|| {
        let file = fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        // Buffered, and past the page cache once the output outgrows the buffer
        // (`crate::direct`): the sync below would write the bytes out anyway.
        let mut buffered = crate::direct::DirectWriter::new(file, &tmp);
        produce(&mut buffered)?;
        let (file, _) = buffered.finish()?;
        file.sync_all()?;
        drop(file);
        fs::rename(&tmp, path)
    })();
    landed(&tmp);
    if let Err(e) = result {
        // Best effort: the temporary file may not exist if creating it was what failed.
        let _ = fs::remove_file(&tmp);
        return Err(io_err(e));
    }
    Ok(())
}

/// Why a mesh file could not be written: the format's encoder refused the mesh, or the file
/// could not be written. Both name the file.
#[derive(Debug, thiserror::Error)]
pub enum MeshOutputError {
    /// The encoder refused the mesh (something the format cannot hold); nothing was written
    /// and an existing file is untouched.
    #[error("cannot write {path} as a mesh: {source}", path = .path.display())]
    Encode {
        /// The file.
        path: PathBuf,
        /// The encoder's answer.
        #[source]
        source: crate::error::WriteError,
    },
    /// The file could not be written (or its path is not a writable regular file).
    #[error(transparent)]
    File(#[from] OutputError),
}

/// Writes `mesh` in `format` to `path` atomically ([`write_atomic_with`]), streaming: the
/// encoder ([`crate::MeshFormat::write_to`]) writes into the buffered temporary file, so the
/// file's bytes never sit in memory all at once. An encoder refusal leaves an existing `path`
/// untouched and no temporary file behind.
pub fn write_atomic_mesh(
    path: &Path,
    format: &dyn crate::MeshFormat,
    mesh: &crate::RawMesh,
    options: &crate::WriteOptions,
) -> Result<(), MeshOutputError> {
    // The encoder's refusal is kept here; the atomic writer sees an I/O error and cleans up.
    let mut refused = None;
    let result = write_atomic_with(path, &mut |w| {
        format.write_to(mesh, options, w).map_err(|e| match e {
            crate::error::WriteError::Io { source, .. } => source,
            other => {
                refused = Some(other);
                std::io::Error::other("the encoder refused the mesh")
            }
        })
    });
    match (refused, result) {
        (Some(source), _) => Err(MeshOutputError::Encode {
            path: path.to_path_buf(),
            source,
        }),
        (None, result) => result.map_err(MeshOutputError::File),
    }
}

/// `dir/.name.tmp-<pid>-<n>` beside `path`.
fn temp_sibling(path: &Path) -> Result<PathBuf, OutputError> {
    let name = path.file_name().ok_or_else(|| OutputError::NoFileName {
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
        assert!(matches!(err, OutputError::Io { .. }));
        assert!(err.to_string().contains("out.txt"));
        assert!(entries(dir.path()).is_empty());
        // No file name at all: `/` is a directory, refused before a temporary name is made.
        let err = write_atomic(Path::new("/"), b"x").unwrap_err();
        assert!(matches!(err, OutputError::NotRegularFile { .. }));
        assert!(matches!(
            temp_sibling(Path::new("/")),
            Err(OutputError::NoFileName { .. })
        ));
    }

    #[test]
    fn non_regular_paths_are_refused_and_links_followed() {
        let dir = tempfile::tempdir().unwrap();
        let sub = dir.path().join("sub");
        fs::create_dir(&sub).unwrap();
        let err = write_atomic(&sub, b"x").unwrap_err();
        assert!(err.to_string().contains("a directory"), "{err}");
        #[cfg(unix)]
        {
            // A link to a regular file writes the target and keeps the link.
            let target = dir.path().join("target.txt");
            fs::write(&target, b"old").unwrap();
            let link = dir.path().join("link.txt");
            std::os::unix::fs::symlink(&target, &link).unwrap();
            write_atomic(&link, b"new").unwrap();
            assert_eq!(fs::read(&target).unwrap(), b"new");
            assert!(fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink());
            // A link to a directory, and a device, are refused.
            let dlink = dir.path().join("dlink");
            std::os::unix::fs::symlink(&sub, &dlink).unwrap();
            assert!(write_atomic(&dlink, b"x").is_err());
            let err = write_atomic(Path::new("/dev/null"), b"x").unwrap_err();
            assert!(err.to_string().contains("a device"), "{err}");
        }
    }

    #[test]
    fn in_flight_paths_are_removed_on_request() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join(".x.tmp");
        let sub = dir.path().join(".staging");
        fs::write(&file, b"half").unwrap();
        fs::create_dir(&sub).unwrap();
        fs::write(sub.join("a.png"), b"half").unwrap();
        let registry = Registry::new();
        registry.add(&file);
        registry.add(&sub);
        assert_eq!(registry.remove_all(), 2);
        assert!(entries(dir.path()).is_empty());
    }

    #[test]
    fn mesh_files_stream_and_refusals_keep_the_old_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("tri.obj");
        let obj = crate::format_by_name("obj").unwrap();
        let opts = crate::WriteOptions::new();
        let mut mesh = crate::RawMesh::from_triangles(
            vec![
                nalgebra::Point3::new(0.0, 0.0, 0.0),
                nalgebra::Point3::new(1.0, 0.0, 0.0),
                nalgebra::Point3::new(0.0, 1.0, 0.0),
            ],
            &[[0, 1, 2]],
        );
        write_atomic_mesh(&path, obj, &mesh, &opts).unwrap();
        let written = fs::read(&path).unwrap();
        assert_eq!(written, obj.write(&mesh, &opts).unwrap());
        // A NaN position is refused by the encoder: the old file stays, no temporary is left.
        mesh.positions[1].x = f64::NAN;
        let err = write_atomic_mesh(&path, obj, &mesh, &opts).unwrap_err();
        assert!(matches!(err, MeshOutputError::Encode { .. }), "{err}");
        assert!(err.to_string().contains("tri.obj"), "{err}");
        assert_eq!(fs::read(&path).unwrap(), written);
        assert_eq!(entries(dir.path()), vec!["tri.obj".to_string()]);
        // A file that cannot be made is the file's error, naming it.
        mesh.positions[1].x = 1.0;
        let missing = dir.path().join("missing").join("x.obj");
        let err = write_atomic_mesh(&missing, obj, &mesh, &opts).unwrap_err();
        assert!(matches!(err, MeshOutputError::File(_)), "{err}");
        assert!(err.to_string().contains("x.obj"), "{err}");
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

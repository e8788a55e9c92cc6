//! What the studies share beyond the fit job: list options with every item once, the committed
//! data found wherever the binary runs, and the studies' own refusals ([`StudyError`]).
//!
//! **Lists.** A study option that takes several values (`--data ring,sphere`, `--scheme a,b`,
//! `--beta 0.2,0.33`, …) takes them comma-separated or with the option repeated; an item given
//! twice is refused by name ([`refuse_duplicates`]): a data set solved twice is counted twice in
//! every total of a report, and a grid axis with a repeated value runs the same tasks twice.
//!
//! **Committed data.** The small committed data (the libigl golden numbers, 29 kB) is built into
//! the binary (`include_str!`), so a study gives the same report whatever directory it runs
//! in; the real-mesh corpus (1.2 MB of PLY, with its licences beside it) is not, and is found at
//! the source tree the binary was built from ([`committed_path`]), with an error naming the
//! path tried when it is not there.

use std::path::{Path, PathBuf};

/// A study refused its options or its input.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// A list option names the same item twice.
    #[error("{option}: `{item}` is given twice (each item of a list once: a repeated item would be run and counted twice)")]
    Duplicate {
        /// The option (`--data`, `--scheme`, …) or grid key.
        option: String,
        /// The item repeated, as given.
        item: String,
    },
    /// A value of a list option is not one the option takes.
    #[error("{option}: `{value}`: {why}")]
    BadValue {
        /// The option or grid key.
        option: String,
        /// The value as given.
        value: String,
        /// Why it is refused (the valid names or range).
        why: String,
    },
    /// A grid file cannot be read as a sweep grid.
    #[error("{path}: {message}", path = .path.display())]
    Grid {
        /// The grid file.
        path: PathBuf,
        /// What is wrong and where (line, key).
        message: String,
    },
    /// A grid given as JSON (`experiments::sweep_tasks`) cannot be read as a sweep grid: the
    /// grid file's message, without a file or line.
    #[error("the JSON grid: {message}")]
    JsonGrid {
        /// What is wrong and where (the key).
        message: String,
    },
    /// `sweep --task ID` names no task of the grid.
    #[error("--task {id}: no task of this grid has that id ({total} tasks; `sweep --list-tasks` lists them with the same grid options)")]
    UnknownTask {
        /// The id given.
        id: String,
        /// Tasks of the grid.
        total: usize,
    },
    /// A grid with more tasks than the limit.
    #[error("the grid has {tasks} tasks, more than the {max} a sweep runs (shorten a list; the limit keeps a task manifest and a merge in memory)")]
    TooManyTasks {
        /// Tasks the grid would have (saturating).
        tasks: u128,
        /// The limit.
        max: usize,
    },
    /// Two tasks of a grid have the same id (two data files with the same name).
    #[error("tasks {first} and {second} have the same id `{id}` (two inputs of the same name); rename one")]
    SameId {
        /// The id.
        id: String,
        /// Index of the first task.
        first: usize,
        /// Index of the second.
        second: usize,
    },
    /// A file in a corpus directory is not a regular file (a FIFO would block the read forever,
    /// a device would be read without end).
    #[error("{path}: not a regular file ({kind}); a corpus holds mesh files only", path = .path.display())]
    SpecialFile {
        /// The file.
        path: PathBuf,
        /// What it is (`a FIFO`, `a socket`, `a device`, …).
        kind: &'static str,
    },
    /// Committed data a study reads is not where the binary was built from.
    #[error("{what}: not found at {path} (the source tree the binary was built from); give its location with {option}", path = .path.display())]
    MissingData {
        /// What was looked for.
        what: &'static str,
        /// The path tried.
        path: PathBuf,
        /// The option that names another location.
        option: &'static str,
    },
    /// A sweep's directory holds the tasks of another grid.
    #[error("{path}: the directory holds the tasks of another grid (options {theirs}; this run's are {these}): these shards come from different runs; use another --output or remove the directory", path = .path.display())]
    OtherGrid {
        /// The manifest found.
        path: PathBuf,
        /// This run's grid options (JSON).
        these: String,
        /// The manifest's (JSON).
        theirs: String,
    },
    /// A task's own result has a measure that cannot be reported (not finite, out of range).
    #[error("task {task}: its result cannot be reported")]
    BadResult {
        /// The task's id.
        task: String,
        /// Which measure and why.
        source: crate::shard::ShardError,
    },
}

impl StudyError {
    /// True for a usage error (exit status 2: an option's value refused before any work),
    /// false for a runtime error (exit status 1: input, a grid file, a corpus, missing data). A JSON
    /// grid is the arguments of a library call, so a bad one is a usage error.
    pub fn is_usage(&self) -> bool {
        matches!(
            self,
            StudyError::Duplicate { .. }
                | StudyError::BadValue { .. }
                | StudyError::JsonGrid { .. }
                | StudyError::UnknownTask { .. }
                | StudyError::TooManyTasks { .. }
        )
    }
}

/// Refuses a list in which an item appears twice, naming the first repeated one; `key` gives
/// what makes two items the same (a file's canonical path, a number's value).
pub fn refuse_duplicates<T, K: PartialEq>(
    option: &str,
    items: &[T],
    key: impl Fn(&T) -> K,
    shown: impl Fn(&T) -> String,
) -> Result<(), StudyError> {
    let keys: Vec<K> = items.iter().map(&key).collect();
    for (j, k) in keys.iter().enumerate() {
        if keys[..j].contains(k) {
            return Err(StudyError::Duplicate {
                option: option.to_string(),
                item: shown(&items[j]),
            });
        }
    }
    Ok(())
}

/// Refuses a list of names (`--data`, `--scheme`, `--curves`, …) with a name twice. A name that
/// is an existing file is compared by its canonical path, so `a.ply` and `./a.ply` are one.
pub fn refuse_duplicate_names(option: &str, items: &[String]) -> Result<(), StudyError> {
    refuse_duplicates(
        option,
        items,
        |s| {
            let p = Path::new(s.trim());
            if p.is_file() {
                std::fs::canonicalize(p)
                    .map(|c| c.to_string_lossy().into_owned())
                    .unwrap_or_else(|_| s.trim().to_string())
            } else {
                s.trim().to_string()
            }
        },
        |s| s.trim().to_string(),
    )
}

/// Refuses a list of numbers with a value twice (`--beta 0.2,0.2`; `0.20` and `0.2` are one).
pub fn refuse_duplicate_numbers<T: PartialEq + Copy + std::fmt::Display>(
    option: &str,
    items: &[T],
) -> Result<(), StudyError> {
    refuse_duplicates(option, items, |x| *x, |x| x.to_string())
}

/// The libigl golden numbers of `estimation` (`data/golden/libigl-estimators.json`, written by
/// `scripts/golden_estimators.py`), built into the binary.
pub const LIBIGL_GOLDEN: &str = include_str!("../../data/golden/libigl-estimators.json");

/// Where the committed file or directory `relative` (to the repository root, e.g.
/// `data/meshes`) is: in the source tree the binary was built from, which need not be the
/// working directory. An error naming the path tried (and `option`, which names another
/// location) when it is not there.
pub fn committed_path(
    what: &'static str,
    relative: &str,
    option: &'static str,
) -> Result<PathBuf, StudyError> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(relative);
    let path = std::fs::canonicalize(&path).unwrap_or(path);
    if path.exists() {
        Ok(path)
    } else {
        Err(StudyError::MissingData { what, path, option })
    }
}

/// What a file that is not regular is, for messages; `None` for a regular file or a directory.
#[cfg(unix)]
pub fn special_kind(t: std::fs::FileType) -> Option<&'static str> {
    use std::os::unix::fs::FileTypeExt as _;
    if t.is_file() || t.is_dir() {
        None
    } else if t.is_fifo() {
        Some("a FIFO")
    } else if t.is_socket() {
        Some("a socket")
    } else if t.is_block_device() || t.is_char_device() {
        Some("a device")
    } else {
        Some("not a regular file")
    }
}

/// What a file that is not regular is, for messages; `None` for a regular file or a directory.
#[cfg(not(unix))]
pub fn special_kind(t: std::fs::FileType) -> Option<&'static str> {
    if t.is_file() || t.is_dir() {
        None
    } else {
        Some("not a regular file")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicates_are_named_and_distinct_items_pass() {
        let names = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let e = refuse_duplicate_names("--data", &names(&["ring", "sphere", "ring"])).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--data: `ring` is given twice (each item of a list once: a repeated item would be run and counted twice)"
        );
        assert!(e.is_usage());
        assert!(refuse_duplicate_names("--data", &names(&["ring", "sphere"])).is_ok());
        let e = refuse_duplicate_numbers("--beta", &[0.2, 0.33, 0.20]).unwrap_err();
        assert!(
            e.to_string().starts_with("--beta: `0.2` is given twice"),
            "{e}"
        );
        assert!(refuse_duplicate_numbers("--segments", &[4usize, 8]).is_ok());
    }

    #[test]
    fn the_golden_numbers_are_built_in_and_the_corpus_is_found() {
        let v: serde_json::Value = serde_json::from_str(LIBIGL_GOLDEN).unwrap();
        assert!(v["meshes"].as_object().is_some_and(|m| !m.is_empty()));
        let corpus = committed_path("the corpus", "data/meshes", "--corpus").unwrap();
        assert!(corpus.join("bunny.ply").is_file());
        let e = committed_path("nothing", "data/no-such-dir", "--x").unwrap_err();
        assert!(e.to_string().contains("no-such-dir"), "{e}");
    }
}

//! Shard files of `sweep --shard i/n`, as `merge` reads them: a pure function of the file's
//! text, so that the fuzz harness reads them exactly as `merge` does.
//!
//! A shard file is a JSON object `{"shard": [i, n], "tasks_total": N, "options": {…},
//! "results": [{"index": k, "task": "…", …}, …]}`; every result's `index` must be below the
//! number of tasks of the sweep.

use serde_json::Value;

/// A shard file's content.
#[derive(Clone, Debug, PartialEq)]
pub struct ShardFile {
    /// The options the shard's run used (compared across shards by `merge`).
    pub options: Value,
    /// Each result with its task index.
    pub results: Vec<(usize, Value)>,
}

/// Why a shard file cannot be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    /// Not JSON.
    #[error("not a shard report: {0}")]
    NotJson(String),
    /// A result has no index, or one beyond the sweep's tasks.
    #[error("result {position} has no valid task index (the sweep has {total} tasks)")]
    BadIndex {
        /// Position of the result in the file's list.
        position: usize,
        /// Tasks of the sweep.
        total: usize,
    },
}

/// Reads a shard file's text for a sweep of `total` tasks.
pub fn read_shard(text: &str, total: usize) -> Result<ShardFile, ShardError> {
    let v: Value = serde_json::from_str(text).map_err(|e| ShardError::NotJson(e.to_string()))?;
    let mut results = Vec::new();
    for (position, r) in v["results"].as_array().into_iter().flatten().enumerate() {
        let k = r["index"]
            .as_u64()
            .and_then(|k| usize::try_from(k).ok())
            .filter(|k| *k < total)
            .ok_or(ShardError::BadIndex { position, total })?;
        results.push((k, r.clone()));
    }
    Ok(ShardFile {
        options: v["options"].clone(),
        results,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_are_checked() {
        let ok = read_shard(r#"{"options":{"a":1},"results":[{"index":3}]}"#, 4).unwrap();
        assert_eq!(ok.results.len(), 1);
        assert_eq!(ok.options["a"], 1);
        assert_eq!(
            read_shard(r#"{"results":[{"index":4}]}"#, 4),
            Err(ShardError::BadIndex {
                position: 0,
                total: 4
            })
        );
        assert!(matches!(read_shard("{", 4), Err(ShardError::NotJson(_))));
    }
}

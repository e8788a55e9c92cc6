//! The result lines of `sweep` as `merge` reads them: pure functions of the text, so that the
//! fuzz harness reads them exactly as `merge` does.
//!
//! A sweep writes one JSON object a task, one a line (JSON Lines: `shard-i-of-n.jsonl`,
//! `task-K.jsonl`, `results.jsonl`; pandas reads them with `read_json(path, lines=True)`).
//! Each line holds the task's identity — `index`, `task` (its id), `dataset`, `file`,
//! `resolution`, `scheme`, `subdivision`, `parameters`, `curves`, `solver`, `segments`,
//! `interior`, as the manifest (`tasks.json`) lists them — and its measures. [`check_line`]
//! compares a line's identity with the manifest's task of the same index, key by key, and
//! checks the type and range of every measure, so a forged or stale line (a task renamed, a
//! negative distance, a count that is text) is refused by name, not published.

use serde_json::Value;

/// A shard file's content.
#[derive(Clone, Debug, PartialEq)]
pub struct ShardFile {
    /// Each result with its task index, in file order.
    pub results: Vec<(usize, Value)>,
}

/// Why a result line cannot be merged.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ShardError {
    /// A line is not a JSON object.
    #[error("line {line}: not a JSON object: {message}")]
    NotJson {
        /// 1-based line.
        line: usize,
        /// The parser's answer.
        message: String,
    },
    /// A result has no index, or one beyond the sweep's tasks.
    #[error("line {line}: no valid task index (the sweep has {total} tasks)")]
    BadIndex {
        /// 1-based line.
        line: usize,
        /// Tasks of the sweep.
        total: usize,
    },
    /// A line's identity differs from the manifest's task of its index.
    #[error("line {line}: task {index} `{task}`: `{key}` is {found}, the manifest's task {index} has {expected}", line = .0.line, index = .0.index, task = .0.task, key = .0.key, found = .0.found, expected = .0.expected)]
    NotTheTask(Box<Mismatch>),
    /// A measure has the wrong type or is out of its range.
    #[error("line {line}: task {index} `{task}`: `{key}` is {found}: {expected}", line = .0.line, index = .0.index, task = .0.task, key = .0.key, found = .0.found, expected = .0.expected)]
    BadMeasure(Box<Mismatch>),
    /// A line longer than [`MAX_LINE_BYTES`].
    #[error("line {line}: longer than {MAX_LINE_BYTES} bytes: not a sweep result")]
    LineTooLong {
        /// 1-based line.
        line: usize,
    },
}

/// Where a line differs from what it must be.
#[derive(Clone, Debug, PartialEq)]
pub struct Mismatch {
    /// 1-based line.
    pub line: usize,
    /// The task index the line claims.
    pub index: usize,
    /// The manifest's id of that task.
    pub task: String,
    /// The key (a measure's path such as `errors.position_max`).
    pub key: String,
    /// The line's value (JSON, or `missing`).
    pub found: String,
    /// The manifest's value (JSON), or what the measure must be.
    pub expected: String,
}

/// Longest result line a reader takes: a task's line is about 1 kB.
pub const MAX_LINE_BYTES: usize = 64 * 1024;

/// The keys of a task's identity, as the manifest lists them and each line repeats them.
pub const IDENTITY: [&str; 12] = [
    "index",
    "task",
    "dataset",
    "file",
    "resolution",
    "scheme",
    "subdivision",
    "parameters",
    "curves",
    "solver",
    "segments",
    "interior",
];

/// Reads the result lines of a file for a sweep of `total` tasks (blank lines skipped): each a
/// JSON object with an index below `total`.
pub fn read_shard(text: &str, total: usize) -> Result<ShardFile, ShardError> {
    let mut results = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        if raw.trim().is_empty() {
            continue;
        }
        if raw.len() > MAX_LINE_BYTES {
            return Err(ShardError::LineTooLong { line });
        }
        let v: Value = serde_json::from_str(raw).map_err(|e| ShardError::NotJson {
            line,
            message: e.to_string(),
        })?;
        let k = task_index(line, &v, total)?;
        results.push((k, v));
    }
    Ok(ShardFile { results })
}

/// The task index of result `v` (line `line`, 1-based, for messages) of a sweep of `total`
/// tasks: `v` must be a JSON object whose `index` is below `total`.
pub fn task_index(line: usize, v: &Value, total: usize) -> Result<usize, ShardError> {
    if !v.is_object() {
        return Err(ShardError::NotJson {
            line,
            message: "a JSON value that is not an object".into(),
        });
    }
    v["index"]
        .as_u64()
        .and_then(|k| usize::try_from(k).ok())
        .filter(|k| *k < total)
        .ok_or(ShardError::BadIndex { line, total })
}

/// What a measure must be.
#[derive(Clone, Copy)]
enum Kind {
    /// A non-negative integer.
    Count,
    /// A positive integer.
    Positive,
    /// A finite number ≥ 0.
    NonNegative,
    /// An angle in radians, in [0, π].
    Radians,
    /// An angle in degrees, in [0, 180].
    Degrees,
}

impl Kind {
    fn accepts(self, v: &Value) -> bool {
        match self {
            Kind::Count => v.as_u64().is_some(),
            Kind::Positive => v.as_u64().is_some_and(|n| n > 0),
            Kind::NonNegative => v.as_f64().is_some_and(|x| x.is_finite() && x >= 0.0),
            Kind::Radians => v
                .as_f64()
                .is_some_and(|x| (0.0..=std::f64::consts::PI).contains(&x)),
            Kind::Degrees => v.as_f64().is_some_and(|x| (0.0..=180.0).contains(&x)),
        }
    }

    fn expected(self) -> &'static str {
        match self {
            Kind::Count => "expected a non-negative integer",
            Kind::Positive => "expected a positive integer",
            Kind::NonNegative => "expected a finite number ≥ 0",
            Kind::Radians => "expected an angle in radians in [0, π]",
            Kind::Degrees => "expected an angle in degrees in [0, 180]",
        }
    }
}

/// The measures against the true surface (`errors`).
const ERRORS: [(&str, Kind); 9] = [
    ("samples", Kind::Positive),
    ("position_max", Kind::NonNegative),
    ("position_rms", Kind::NonNegative),
    ("normal_max_degrees", Kind::Degrees),
    ("normal_rms_degrees", Kind::Degrees),
    ("gaussian_rms", Kind::NonNegative),
    ("gaussian_max", Kind::NonNegative),
    ("mean_rms", Kind::NonNegative),
    ("mean_max", Kind::NonNegative),
];

/// The boundary-curve measures (`curve_measures`).
const CURVE_MEASURES: [(&str, Kind); 5] = [
    ("end_curvature_error_max", Kind::NonNegative),
    ("shortest_alpha", Kind::NonNegative),
    ("curvature_variation_max", Kind::NonNegative),
    ("fallbacks_to_chord", Kind::Count),
    ("unconverged_optimizations", Kind::Count),
];

/// Checks result line `line` (1-based, for messages) against `expected`, the manifest's task
/// of the same index: every identity key equal, and every measure of the task's kind present
/// with its type and range. `errors` may be null only for a mesh file (no true surface),
/// `curve_measures` only for a task without curves or a mesh file whose edge problems could
/// not be set up (the line then says why in `curve_measures_note`).
pub fn check_line(line: usize, v: &Value, expected: &Value) -> Result<(), ShardError> {
    let index = expected["index"].as_u64().unwrap_or_default() as usize;
    let task = expected["task"].as_str().unwrap_or_default().to_string();
    for key in IDENTITY {
        let found = v.get(key).unwrap_or(&Value::Null);
        let want = expected.get(key).unwrap_or(&Value::Null);
        if found != want {
            return Err(ShardError::NotTheTask(Box::new(Mismatch {
                line,
                index,
                task,
                key: key.to_string(),
                found: found.to_string(),
                expected: want.to_string(),
            })));
        }
    }
    let bad = |key: String, found: Option<&Value>, expected: &'static str| {
        ShardError::BadMeasure(Box::new(Mismatch {
            line,
            index,
            task: task.clone(),
            key,
            found: found.map_or_else(|| "missing".to_string(), Value::to_string),
            expected: expected.to_string(),
        }))
    };
    let check = |key: String, value: Option<&Value>, kind: Kind| -> Result<(), ShardError> {
        match value {
            Some(x) if kind.accepts(x) => Ok(()),
            other => Err(bad(key, other, kind.expected())),
        }
    };
    let group = |name: &str, fields: &[(&str, Kind)], nullable: bool| -> Result<(), ShardError> {
        match v.get(name) {
            Some(Value::Null) if nullable => Ok(()),
            Some(Value::Object(m)) => fields
                .iter()
                .try_for_each(|(k, kind)| check(format!("{name}.{k}"), m.get(*k), *kind)),
            other => Err(bad(
                name.to_string(),
                other,
                if nullable {
                    "expected an object of measures or null"
                } else {
                    "expected an object of measures"
                },
            )),
        }
    };
    let file = expected["file"].as_bool().unwrap_or(false);
    let subdivision = expected["subdivision"].as_bool().unwrap_or(false);
    let curves = expected["curves"].as_str() != Some("none");
    check("faces".into(), v.get("faces"), Kind::Positive)?;
    group("errors", &ERRORS, file)?;
    check(
        "fit_time_seconds".into(),
        v.get("fit_time_seconds"),
        Kind::NonNegative,
    )?;
    check(
        "task_time_seconds".into(),
        v.get("task_time_seconds"),
        Kind::NonNegative,
    )?;
    if subdivision {
        for key in ["g1_defect_radians", "curve_measures"] {
            if !v.get(key).is_some_and(Value::is_null) {
                return Err(bad(key.into(), v.get(key), "expected null (subdivision)"));
            }
        }
        check("levels".into(), v.get("levels"), Kind::Positive)?;
        check(
            "data_to_limit_max".into(),
            v.get("data_to_limit_max"),
            Kind::NonNegative,
        )?;
    } else {
        check(
            "g1_defect_radians".into(),
            v.get("g1_defect_radians"),
            Kind::Radians,
        )?;
        check(
            "interpolation_position_error".into(),
            v.get("interpolation_position_error"),
            Kind::NonNegative,
        )?;
        check(
            "interpolation_normal_error_radians".into(),
            v.get("interpolation_normal_error_radians"),
            Kind::Radians,
        )?;
        if curves {
            let noted = v.get("curve_measures_note").is_some_and(Value::is_string);
            group("curve_measures", &CURVE_MEASURES, file && noted)?;
        } else if !v.get("curve_measures").is_some_and(Value::is_null) {
            return Err(bad(
                "curve_measures".into(),
                v.get("curve_measures"),
                "expected null (no edge curves)",
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn task() -> Value {
        json!({"index": 3, "task": "ring/optimized/lbfgs", "dataset": "ring", "file": false,
               "resolution": null, "scheme": "shirman-sequin", "subdivision": false,
               "parameters": {"beta": 0.3333333333333333, "c": 1.0}, "curves": "optimized",
               "solver": "lbfgs", "segments": 4, "interior": "default"})
    }

    fn line() -> Value {
        let mut v = task();
        for (k, x) in [
            ("faces", json!(256)),
            ("g1_defect_radians", json!(1e-14)),
            ("interpolation_position_error", json!(0.0)),
            ("interpolation_normal_error_radians", json!(0.0)),
            (
                "errors",
                json!({"samples": 6144, "position_max": 0.001, "position_rms": 0.0005,
                       "normal_max_degrees": 2.7, "normal_rms_degrees": 0.9, "gaussian_rms": 0.9,
                       "gaussian_max": 8.9, "mean_rms": 0.3, "mean_max": 1.6}),
            ),
            (
                "curve_measures",
                json!({"end_curvature_error_max": 0.1, "shortest_alpha": 1.0,
                       "curvature_variation_max": 0.5, "fallbacks_to_chord": 0,
                       "unconverged_optimizations": 0}),
            ),
            ("fit_time_seconds", json!(0.01)),
            ("task_time_seconds", json!(0.02)),
        ] {
            v[k] = x;
        }
        v
    }

    #[test]
    fn indices_are_checked() {
        let ok = read_shard("{\"index\":3}\n\n{\"index\":0}\n", 4).unwrap();
        assert_eq!(ok.results.len(), 2);
        assert_eq!(ok.results[1].0, 0);
        assert_eq!(
            read_shard("{\"index\":0}\n{\"index\":4}\n", 4),
            Err(ShardError::BadIndex { line: 2, total: 4 })
        );
        assert!(matches!(
            read_shard("{", 4),
            Err(ShardError::NotJson { line: 1, .. })
        ));
        assert!(matches!(
            read_shard("[1]", 4),
            Err(ShardError::NotJson { .. })
        ));
    }

    #[test]
    fn a_true_line_passes_and_a_forged_one_is_named() {
        assert_eq!(check_line(1, &line(), &task()), Ok(()));
        // Another task's name in place of the task of that index.
        let mut forged = line();
        forged["task"] = json!("ring/bogus");
        let e = check_line(7, &forged, &task()).unwrap_err().to_string();
        assert_eq!(
            e,
            "line 7: task 3 `ring/optimized/lbfgs`: `task` is \"ring/bogus\", the manifest's task 3 has \"ring/optimized/lbfgs\""
        );
        // Another parameter value.
        let mut forged = line();
        forged["parameters"]["beta"] = json!(0.5);
        assert!(check_line(1, &forged, &task())
            .unwrap_err()
            .to_string()
            .contains("`parameters` is"));
        // A negative distance, a count that is text, a missing measure, an angle past π.
        for (path, value, says) in [
            (
                "position_max",
                json!(-0.001),
                "`errors.position_max` is -0.001: expected a finite number ≥ 0",
            ),
            (
                "samples",
                json!("6144"),
                "`errors.samples` is \"6144\": expected a positive integer",
            ),
        ] {
            let mut forged = line();
            forged["errors"][path] = value;
            let e = check_line(1, &forged, &task()).unwrap_err().to_string();
            assert!(e.ends_with(says), "{e}");
        }
        let mut forged = line();
        forged.as_object_mut().unwrap().remove("fit_time_seconds");
        let e = check_line(1, &forged, &task()).unwrap_err().to_string();
        assert!(e.contains("`fit_time_seconds` is missing"), "{e}");
        let mut forged = line();
        forged["g1_defect_radians"] = json!(4.0);
        assert!(check_line(1, &forged, &task()).is_err());
        let mut forged = line();
        forged["errors"] = json!(null);
        let e = check_line(1, &forged, &task()).unwrap_err().to_string();
        assert!(
            e.contains("`errors` is null: expected an object of measures"),
            "{e}"
        );
    }
}

//! `sweep` and `merge`: shards whose options differ are refused by name, and shards merged
//! write the report an unsharded run writes.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

fn run(args: &[&str]) -> (i32, String) {
    let (code, _, err) = common::run(args, "");
    (code, err)
}

#[test]
fn shards_of_different_runs_are_not_merged() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let (code, err) = run(&["sweep", "--shard", "0/2", "--out", out]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = run(&[
        "sweep",
        "--shard",
        "1/2",
        "--interior",
        "membrane",
        "--out",
        out,
    ]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = run(&["merge", "--out", out]);
    assert_ne!(code, 0);
    assert!(err.contains("come from different runs"), "{err}");
    // The same options merge.
    let (code, err) = run(&["sweep", "--shard", "1/2", "--out", out]);
    assert_eq!(code, 0, "{err}");
    let (code, err) = run(&["merge", "--out", out]);
    assert_eq!(code, 0, "{err}");
    let report = std::fs::read_to_string(dir.path().join("report.json")).unwrap();
    assert!(report.contains("\"options\""));
}

/// Removes every key that holds a timing (its name contains `time` or `seconds`:
/// `fit_time_seconds`, `task_time_seconds`), at any depth; returns how many it removed.
fn drop_timings(v: &mut serde_json::Value) -> usize {
    match v {
        serde_json::Value::Object(map) => {
            let before = map.len();
            map.retain(|k, _| !(k.contains("time") || k.contains("seconds")));
            let mut removed = before - map.len();
            for x in map.values_mut() {
                removed += drop_timings(x);
            }
            removed
        }
        serde_json::Value::Array(xs) => xs.iter_mut().map(drop_timings).sum(),
        _ => 0,
    }
}

/// `report.md` without its timing column (`fit (ms)`, found by its header): every table row
/// keeps its other cells, every other line is kept as it is.
fn drop_timing_column(md: &str) -> String {
    let header = md
        .lines()
        .find(|l| l.starts_with("| task |"))
        .expect("the table's header");
    let cells = |l: &str| -> Vec<String> { l.split('|').map(str::to_string).collect() };
    let column = cells(header)
        .iter()
        .position(|c| c.trim() == "fit (ms)")
        .expect("a fit (ms) column");
    md.lines()
        .map(|l| {
            if l.starts_with('|') {
                let mut c = cells(l);
                assert!(c.len() > column, "a short row: {l}");
                c[column] = " (time) ".into();
                c.join("|")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// What `sweep` and `merge` leave in `dir`: `report.json` (as JSON) and `report.md`.
fn reports(dir: &std::path::Path) -> (serde_json::Value, String) {
    let json = std::fs::read_to_string(dir.join("report.json")).unwrap();
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    (serde_json::from_str(&json).unwrap(), md)
}

/// Runs the sweep with `options` whole into one directory and as `shards` shards merged in
/// another, and compares the two reports: `report.json` equal but for its timings,
/// `report.md` equal but for its timing column. Returns the number of tasks.
fn whole_equals_merged(options: &[&str], shards: usize) -> usize {
    let whole = tempfile::tempdir().unwrap();
    let sharded = tempfile::tempdir().unwrap();
    let with = |more: &[&str]| -> Vec<String> {
        ["sweep"]
            .iter()
            .chain(options)
            .chain(more)
            .map(|s| s.to_string())
            .collect()
    };
    let args = with(&["--out", whole.path().to_str().unwrap()]);
    let (code, err) = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 0, "{err}");
    for i in 0..shards {
        let shard = format!("{i}/{shards}");
        let args = with(&["--shard", &shard, "--out", sharded.path().to_str().unwrap()]);
        let (code, err) = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert_eq!(code, 0, "{err}");
    }
    let (code, err) = run(&["merge", "--out", sharded.path().to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let (mut a, md_a) = reports(whole.path());
    let (mut b, md_b) = reports(sharded.path());
    // The report is what the comparison assumes: two timings a task (the fit's and the
    // task's), nothing else timed, results in task order.
    let tasks = a["results"].as_array().expect("results").len();
    assert_eq!(drop_timings(&mut a), 2 * tasks, "{options:?}");
    assert_eq!(drop_timings(&mut b), 2 * tasks, "{options:?}");
    for (k, r) in a["results"].as_array().unwrap().iter().enumerate() {
        assert_eq!(r["index"], k, "{options:?}: results in task order");
        assert!(r["errors"]["position_max"].as_f64().is_some(), "{r}");
    }
    // Equal as JSON and as text (the same keys in the same order).
    assert_eq!(a, b, "{options:?}");
    assert_eq!(
        serde_json::to_string_pretty(&a).unwrap(),
        serde_json::to_string_pretty(&b).unwrap(),
        "{options:?}"
    );
    let (md_a, md_b) = (drop_timing_column(&md_a), drop_timing_column(&md_b));
    assert_eq!(
        md_a.lines().filter(|l| l.starts_with("| ")).count(),
        tasks + 1,
        "{options:?}: a row a task under the header"
    );
    assert_eq!(md_a, md_b, "{options:?}");
    tasks
}

/// The default sweep (the data sets × curve constructions × solvers, 20 tasks) as three uneven
/// shards (7, 7, 6 tasks), and a subdivision sweep (`--scheme loop`: one task a data set, its G1
/// and curve columns null) as two, each merged: the report an unsharded run writes.
#[test]
fn merged_shards_equal_an_unsharded_run() {
    assert_eq!(whole_equals_merged(&[], 3), 20);
    assert_eq!(whole_equals_merged(&["--scheme", "loop"], 2), 4);
}

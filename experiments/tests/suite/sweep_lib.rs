//! The library's sweep (`experiments::sweep_tasks`) against the binary's: the manifest of a JSON
//! grid is the one `sweep --list-tasks` prints for the same grid as options, a task run by the
//! library is the line `sweep --task ID` writes (timings aside), and a bad grid or id gets the
//! command line's message and kind.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use serde_json::{json, Value};

use experiments::sweep_tasks::{grid_manifest, merge_results, run_task};

use crate::common;

/// The measures that are timings (they differ from run to run, nothing else does).
const TIMINGS: [&str; 2] = ["fit_time_seconds", "task_time_seconds"];

/// `v` without its timings: the keys of [`TIMINGS`], which must all be there.
fn without_timings(mut v: Value) -> Value {
    let map = v.as_object_mut().expect("a result is an object");
    for key in TIMINGS {
        let t = map.shift_remove(key).expect("a result has its timings");
        assert!(t.as_f64().is_some_and(|t| t >= 0.0), "{key}: {t}");
    }
    v
}

/// The manifest `sweep --list-tasks ARGS` prints.
fn cli_manifest(args: &[&str]) -> Value {
    let (code, out, err) = common::run(&[&["sweep", "--list-tasks"][..], args].concat(), "");
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).expect("the manifest is JSON")
}

#[test]
fn the_manifest_of_a_json_grid_is_the_one_list_tasks_prints() {
    let grid = json!({
        "data": ["octa", "sphere"],
        "scheme": ["shirman-sequin", "phong", "loop"],
        "curves": ["chord", "optimized"],
        "solver": "lm",
        "beta": [0.2, 0.5],
        "phong-alpha": [0.25, 0.75],
        "segments": [2, 4],
        "interior": "default",
    });
    let manifest = grid_manifest(&grid).unwrap();
    let cli = cli_manifest(&[
        "--data",
        "octa,sphere",
        "--scheme",
        "shirman-sequin,phong,loop",
        "--curves",
        "chord,optimized",
        "--solver",
        "lm",
        "--beta",
        "0.2,0.5",
        "--phong-alpha",
        "0.25,0.75",
        "-s",
        "2,4",
    ]);
    assert_eq!(manifest, cli);
    // Key for key in the same order, as printed.
    assert_eq!(manifest.to_string(), cli.to_string());
    // Per mesh: shirman-sequin 2 β × (chord, optimized/lm) × 2 segments, phong 2 α × 2
    // segments, loop once: 13; two meshes.
    assert_eq!(manifest["tasks_total"], 26);
    let tasks = manifest["tasks"].as_array().unwrap();
    assert_eq!(tasks.len(), 26);
    assert_eq!(tasks[0]["task"], "octa/beta=0.2/chord/s=2");
    assert_eq!(tasks[8]["task"], "octa/phong/phong-alpha=0.25/none/s=2");
    assert_eq!(tasks[12]["task"], "octa/loop/none");
    assert_eq!(tasks[25]["task"], "sphere/loop/none");
    assert_eq!(manifest["options"]["phong_alpha"], json!([0.25, 0.75]));
}

#[test]
fn a_task_run_by_the_library_is_the_line_the_binary_writes() {
    let grid = json!({
        "data": "octa",
        "scheme": ["shirman-sequin", "loop"],
        "curves": ["chord", "optimized"],
        "solver": ["lm"],
    });
    let flags = [
        "--data",
        "octa",
        "--scheme",
        "shirman-sequin,loop",
        "--curves",
        "chord,optimized",
        "--solver",
        "lm",
    ];
    let manifest = grid_manifest(&grid).unwrap();
    assert_eq!(manifest, cli_manifest(&flags));
    let tasks = manifest["tasks"].as_array().unwrap();
    let ids: Vec<&str> = tasks.iter().map(|t| t["task"].as_str().unwrap()).collect();
    assert_eq!(ids, ["octa/chord", "octa/optimized/lm", "octa/loop/none"]);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let mut mine = Vec::new();
    for (k, id) in ids.iter().enumerate() {
        let (code, _, err) = common::run(
            &[&["sweep", "--task", id, "-o", out][..], &flags].concat(),
            "",
        );
        assert_eq!(code, 0, "{id}: {err}");
        let line = std::fs::read_to_string(dir.path().join(format!("task-{k}.jsonl"))).unwrap();
        let theirs: Value = serde_json::from_str(line.trim_end()).unwrap();
        let ours = run_task(&grid, id).unwrap();
        mine.push(ours.clone());
        // The same keys in the same order and the same numbers, bit for bit, but the timings.
        assert_eq!(
            without_timings(ours).to_string(),
            without_timings(theirs).to_string(),
            "{id}"
        );
    }
    // The numbers are the task's: the octahedron's 8 faces, chord curves G1 to rounding, the
    // subdivision task without G1 measured at the limit of 3 levels.
    assert_eq!(mine[0]["faces"], 8);
    assert!(mine[0]["g1_defect_radians"].as_f64().unwrap() < 1e-12);
    assert_eq!(mine[1]["solver"], "lm");
    assert!(mine[1]["curve_measures"]["end_curvature_error_max"].is_number());
    assert!(mine[2]["g1_defect_radians"].is_null());
    assert_eq!(mine[2]["levels"], 3);
    // The library's merge of the lines, given in any order, is the binary's.
    let (code, _, err) = common::run(&["merge", "-o", out], "");
    assert_eq!(code, 0, "{err}");
    let merged = merge_results(&manifest, mine.into_iter().rev().collect()).unwrap();
    let text = std::fs::read_to_string(dir.path().join("results.jsonl")).unwrap();
    let theirs: Vec<Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(merged.len(), 3);
    for (ours, theirs) in merged.into_iter().zip(theirs) {
        assert_eq!(without_timings(ours), without_timings(theirs));
    }
}

#[test]
fn merged_results_are_checked_against_the_manifest() {
    let grid = json!({"data": "octa", "curves": ["chord", "dbhs"]});
    let manifest = grid_manifest(&grid).unwrap();
    let chord = run_task(&grid, "octa/chord").unwrap();
    // A task missing.
    let e = merge_results(&manifest, vec![chord.clone()]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "merge: 1 of 2 tasks missing from 1 shard file(s): octa/dbhs"
    );
    assert!(!e.is_usage());
    // A task twice.
    let e = merge_results(&manifest, vec![chord.clone(), chord.clone()]).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("<results>: task 0 (\"octa/chord\") appears in more than one shard"),
        "{e}"
    );
    // A line that claims another task's index.
    let mut forged = chord.clone();
    forged["index"] = json!(1);
    let e = merge_results(&manifest, vec![forged]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "<results>: not a shard file of `sweep` that merge can read\n  caused by: line 1: task 1 `octa/dbhs`: `task` is \"octa/chord\", the manifest's task 1 has \"octa/dbhs\""
    );
    // A measure out of its range.
    let mut forged = chord;
    forged["errors"]["position_max"] = json!(-1.0);
    let e = merge_results(&manifest, vec![forged]).unwrap_err();
    assert!(
        e.to_string().contains("`errors.position_max` is -1.0"),
        "{e}"
    );
}

/// The message the binary prints for `sweep --grid FILE --list-tasks` with `toml` in the file,
/// after the file's name and the line: the grid file's own message.
fn grid_file_message(toml: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("grid.toml");
    std::fs::write(&path, toml).unwrap();
    let (code, _, err) = common::run(
        &["sweep", "--list-tasks", "--grid", path.to_str().unwrap()],
        "",
    );
    assert_eq!(code, 1, "{err}");
    let prefix = format!("error: {}: line ", path.display());
    let rest = err.trim_end().strip_prefix(&prefix).expect(&err);
    let (_line, message) = rest.split_once(": ").unwrap();
    message.to_string()
}

#[test]
fn bad_json_grids_get_the_grid_files_messages() {
    for (toml, grid) in [
        ("betta = 0.2\n", json!({"betta": 0.2})),
        ("segments = [\"four\"]\n", json!({"segments": ["four"]})),
        (
            "interior = [\"thin-plate\"]\n",
            json!({"interior": ["thin-plate"]}),
        ),
        ("[beta]\nx = 1\n", json!({"beta": {"x": 1}})),
    ] {
        let expected = grid_file_message(toml);
        let e = grid_manifest(&grid).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("the JSON grid: {expected}"),
            "{toml}"
        );
        assert!(e.is_usage(), "{e}");
        assert_eq!(e.exit_code(), 2);
        // The same for a task of that grid.
        let e = run_task(&grid, "octa/chord").unwrap_err();
        assert_eq!(e.to_string(), format!("the JSON grid: {expected}"));
    }
    assert!(grid_file_message("betta = 0.2\n").starts_with("`betta`: not a grid key; known: data,"));
}

/// The error the binary prints for `sweep ARGS` (after `error: `) and its exit status.
fn cli_error(args: &[&str]) -> (String, i32) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let (code, _, err) = common::run(&[&["sweep", "-o", out][..], args].concat(), "");
    let message = err.trim_end().strip_prefix("error: ").expect(&err);
    (message.to_string(), code)
}

#[test]
fn refused_grids_and_ids_and_failed_tasks_show_the_command_lines_message() {
    let bad_ply = tempfile::Builder::new().suffix(".ply").tempfile().unwrap();
    std::fs::write(bad_ply.path(), "garbage\n").unwrap();
    let bad_ply = bad_ply.path().to_str().unwrap();
    let bad_id = format!("{bad_ply}/chord");
    for (grid, flags, id, usage) in [
        // An item twice, checked when the grid is settled.
        (
            json!({"data": ["octa", "octa"]}),
            vec!["--data", "octa,octa", "--list-tasks"],
            None,
            true,
        ),
        // A parameter outside its range.
        (
            json!({"beta": 1e9}),
            vec!["--beta", "1e9", "--list-tasks"],
            None,
            true,
        ),
        // An axis no task reads.
        (
            json!({"curves": "chord", "solver": "lm"}),
            vec!["--curves", "chord", "--solver", "lm", "--list-tasks"],
            None,
            true,
        ),
        // An id that is no task of the grid.
        (
            json!({"data": "octa", "curves": "chord"}),
            vec![
                "--data",
                "octa",
                "--curves",
                "chord",
                "--task",
                "octa/bogus",
            ],
            Some("octa/bogus"),
            true,
        ),
        // A mesh file that is not one: the task fails as it runs.
        (
            json!({"data": bad_ply, "curves": "chord"}),
            vec!["--data", bad_ply, "--curves", "chord", "--task", &bad_id],
            Some(bad_id.as_str()),
            false,
        ),
    ] {
        let (expected, code) = cli_error(&flags);
        let e = match id {
            None => grid_manifest(&grid).unwrap_err(),
            Some(id) => run_task(&grid, id).unwrap_err(),
        };
        assert_eq!(e.to_string(), expected, "{flags:?}");
        assert_eq!(e.is_usage(), usage, "{e}");
        assert_eq!(i32::from(e.exit_code()), code, "{e}");
    }
}

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
    let small = ["--data", "octa", "--curves", "chord,dbhs"];
    let (code, err) = run(&[&["sweep", "--shard", "0/2", "-o", out][..], &small].concat());
    assert_eq!(code, 0, "{err}");
    // Another grid's shard into the same directory is refused before it runs.
    let (code, err) = run(&[
        &[
            "sweep",
            "--shard",
            "1/2",
            "--interior",
            "membrane",
            "-o",
            out,
        ][..],
        &small,
    ]
    .concat());
    assert_ne!(code, 0);
    assert!(err.contains("come from different runs"), "{err}");
    assert!(!dir.path().join("shard-1-of-2.jsonl").exists());
    // The same options merge.
    let (code, err) = run(&[&["sweep", "--shard", "1/2", "-o", out][..], &small].concat());
    assert_eq!(code, 0, "{err}");
    let (code, err) = run(&["merge", "-o", out]);
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
/// `report.md` equal but for its timing column. Returns the whole run's report without its
/// timings.
fn whole_equals_merged(options: &[&str], shards: usize) -> serde_json::Value {
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
    let args = with(&["-o", whole.path().to_str().unwrap()]);
    let (code, err) = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
    assert_eq!(code, 0, "{err}");
    for i in 0..shards {
        let shard = format!("{i}/{shards}");
        let args = with(&["--shard", &shard, "-o", sharded.path().to_str().unwrap()]);
        let (code, err) = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
        assert_eq!(code, 0, "{err}");
    }
    let (code, err) = run(&["merge", "-o", sharded.path().to_str().unwrap()]);
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
    a
}

/// Two measures of the same computation agree to this relative difference: the committed report
/// was written by the same code; only the last digits of a different CPU's libm may differ.
const SAME_NUMBER: f64 = 1e-9;

/// `a` and `b` equal as JSON, numbers to [`SAME_NUMBER`] relative; the path of the first
/// difference.
fn same_numbers(a: &serde_json::Value, b: &serde_json::Value, at: &str) -> Result<(), String> {
    use serde_json::Value;
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            if (x - y).abs() <= SAME_NUMBER * x.abs().max(y.abs()) {
                Ok(())
            } else {
                Err(format!("{at}: {x} against {y}"))
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            for (k, v) in x {
                let w = y.get(k).ok_or_else(|| format!("{at}.{k}: missing"))?;
                same_numbers(v, w, &format!("{at}.{k}"))?;
            }
            Ok(())
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .try_for_each(|(i, (v, w))| same_numbers(v, w, &format!("{at}[{i}]"))),
        _ if a == b => Ok(()),
        _ => Err(format!("{at}: {a} against {b}")),
    }
}

/// The default sweep (the data sets × curve constructions, those that take a solver once per
/// solver: 4 × (7 + 2 × 3) = 52 tasks)
/// as three uneven shards, and a subdivision sweep (`--scheme loop`: one task a data set, its G1
/// and curve columns null) as two, each merged: the report an unsharded run writes. Every task
/// of the committed `results/sweep/report.json` is in the default run, in the same order, with
/// the same numbers (a report written before constructions joined the registry has fewer).
#[test]
fn merged_shards_equal_an_unsharded_run() {
    let whole = whole_equals_merged(&[], 3);
    let results = whole["results"].as_array().unwrap();
    assert_eq!(
        results.len(),
        4 * curves::REGISTRY
            .iter()
            .map(|e| if curves::takes_solver(e.name) { 3 } else { 1 })
            .sum::<usize>()
    );
    let committed = std::fs::read_to_string(common::root().join("results/sweep/report.json"))
        .expect("the committed sweep report");
    let mut committed: serde_json::Value = serde_json::from_str(&committed).unwrap();
    drop_timings(&mut committed);
    let old = committed["results"].as_array().unwrap();
    assert!(old.len() >= 20, "{}", old.len());
    let mut from = 0;
    for old in old {
        let at = results[from..]
            .iter()
            .position(|new| new["task"] == old["task"])
            .unwrap_or_else(|| panic!("{} not run, or out of order", old["task"]));
        from += at + 1;
        // Every key of the committed task, with the same value (new keys may be added), but its
        // index in the grid, which the constructions added to the registry moved.
        let mut old = old.clone();
        if let Some(o) = old.as_object_mut() {
            o.remove("index");
        }
        if let Err(e) = same_numbers(&old, &results[from - 1], &format!("{}", old["task"])) {
            panic!("{e}");
        }
    }
    let loop_run = whole_equals_merged(&["--scheme", "loop"], 2);
    assert_eq!(loop_run["results"].as_array().unwrap().len(), 4);
}

/// `sweep --list-tasks` writes the manifest of a grid given by lists (and the same one by a
/// TOML file); `sweep --task ID` runs each task alone, as a scheduler would, and `merge` joins
/// them into the report of the whole grid, whose options record exactly the axes run.
#[test]
fn a_grid_runs_task_by_task_and_merges() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("grid");
    let out = out.to_str().unwrap();
    let grid = [
        "--data",
        "octa",
        "--curves",
        "chord,optimized",
        "--solver",
        "lm,lbfgs",
        "--beta",
        "0.2,0.5",
        "-s",
        "2,4",
    ];
    let (code, manifest, err) = common::run(&[&["sweep", "--list-tasks"][..], &grid].concat(), "");
    assert_eq!(code, 0, "{err}");
    let manifest: serde_json::Value = serde_json::from_str(&manifest).expect("JSON manifest");
    let tasks = manifest["tasks"].as_array().unwrap();
    // 2 β × (chord + optimized with 2 solvers) × 2 segments.
    assert_eq!(tasks.len(), 12);
    assert_eq!(manifest["tasks_total"], 12);
    assert_eq!(tasks[0]["task"], "octa/beta=0.2/chord/s=2");
    assert_eq!(tasks[3]["task"], "octa/beta=0.2/optimized/lm");
    assert_eq!(tasks[0]["parameters"]["beta"], 0.2);
    assert_eq!(tasks[0]["parameters"]["c"], 1.0);
    assert_eq!(manifest["options"]["beta"], serde_json::json!([0.2, 0.5]));
    assert_eq!(manifest["options"]["segments"], serde_json::json!([2, 4]));
    assert!(manifest["options"].get("phong_alpha").is_none());
    // The same grid from a TOML file.
    let toml = dir.path().join("grid.toml");
    std::fs::write(
        &toml,
        "data = [\"octa\"]\ncurves = [\"chord\", \"optimized\"]\nsolver = [\"lm\", \"lbfgs\"]\nbeta = [0.2, 0.5]\nsegments = [2, 4]\n",
    )
    .unwrap();
    let (code, from_file, err) = common::run(
        &["sweep", "--list-tasks", "--grid", toml.to_str().unwrap()],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        serde_json::from_str::<serde_json::Value>(&from_file).unwrap(),
        manifest
    );
    // Each task alone, in reverse order; then the merge.
    for t in tasks.iter().rev() {
        let id = t["task"].as_str().unwrap();
        let (code, err) = run(&[&["sweep", "--task", id, "-o", out][..], &grid].concat());
        assert_eq!(code, 0, "{id}: {err}");
    }
    let (code, err) = run(&["merge", "-o", out]);
    assert_eq!(code, 0, "{err}");
    let lines = std::fs::read_to_string(dir.path().join("grid/results.jsonl")).unwrap();
    let lines: Vec<serde_json::Value> = lines
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect();
    assert_eq!(lines.len(), 12);
    for (k, (line, task)) in lines.iter().zip(tasks).enumerate() {
        assert_eq!(line["index"], k);
        assert_eq!(line["task"], task["task"]);
        assert_eq!(line["segments"], task["segments"]);
        assert!(line["g1_defect_radians"].as_f64().unwrap() < 1e-9, "{line}");
        assert!(line["errors"]["position_max"].as_f64().unwrap() >= 0.0);
    }
    // β changes the surface: the two β of the same construction differ.
    assert_ne!(lines[0]["errors"], lines[6]["errors"]);
    // More segments, more samples.
    assert!(lines[1]["errors"]["samples"].as_u64() > lines[0]["errors"]["samples"].as_u64());
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("grid/report.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(report["options"], manifest["options"]);
    // An id not in the grid.
    let (code, err) = run(&[&["sweep", "--task", "octa/bogus", "-o", out][..], &grid].concat());
    assert_ne!(code, 0);
    assert!(
        err.contains("--task octa/bogus: no task of this grid"),
        "{err}"
    );
}

/// A forged or damaged shard is refused with the file and the task named: another task's name
/// in place of a missing task, a negative or non-numeric measure, a parameter changed.
#[test]
fn merge_checks_every_line_against_the_manifest() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let small = ["--data", "octa", "--curves", "chord,dbhs"];
    for shard in ["0/2", "1/2"] {
        let (code, err) = run(&[&["sweep", "--shard", shard, "-o", out][..], &small].concat());
        assert_eq!(code, 0, "{err}");
    }
    let shard = dir.path().join("shard-1-of-2.jsonl");
    let good = std::fs::read_to_string(&shard).unwrap();
    let line: serde_json::Value = serde_json::from_str(good.lines().next().unwrap()).unwrap();
    assert_eq!(line["task"], "octa/dbhs");
    let forge = |edit: &dyn Fn(&mut serde_json::Value)| -> String {
        let mut v = line.clone();
        edit(&mut v);
        std::fs::write(&shard, format!("{v}\n")).unwrap();
        let (code, err) = run(&["merge", "-o", out]);
        assert_ne!(code, 0, "a forged line was merged");
        assert!(err.contains("shard-1-of-2.jsonl"), "{err}");
        err
    };
    let err = forge(&|v| v["task"] = serde_json::json!("octa/bogus"));
    assert!(
        err.contains("task 1 `octa/dbhs`: `task` is \"octa/bogus\""),
        "{err}"
    );
    let err = forge(&|v| v["errors"]["position_max"] = serde_json::json!(-1.0));
    assert!(
        err.contains("`errors.position_max` is -1.0: expected a finite number ≥ 0"),
        "{err}"
    );
    let err = forge(&|v| v["faces"] = serde_json::json!("eight"));
    assert!(
        err.contains("`faces` is \"eight\": expected a positive integer"),
        "{err}"
    );
    let err = forge(&|v| v["parameters"]["beta"] = serde_json::json!(0.5));
    assert!(err.contains("`parameters` is"), "{err}");
    let err = forge(&|v| v["index"] = serde_json::json!(7));
    assert!(
        err.contains("no valid task index (the sweep has 2 tasks)"),
        "{err}"
    );
    // The true line merges.
    std::fs::write(&shard, good).unwrap();
    let (code, err) = run(&["merge", "-o", out]);
    assert_eq!(code, 0, "{err}");
}

/// Lists with an item twice are refused naming it, before any work: data sets, schemes,
/// parameter values, segments (and `solvers --data`, which used to solve and count a data set
/// twice).
#[test]
fn repeated_items_of_a_list_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x");
    let out = out.to_str().unwrap();
    for (args, item) in [
        (
            vec!["sweep", "--data", "octa,octa"],
            "--data: `octa` is given twice",
        ),
        (
            vec!["sweep", "--data", "octa", "--data", "octa"],
            "--data: `octa` is given twice",
        ),
        (
            vec!["sweep", "--scheme", "phong,phong"],
            "--scheme: `phong` is given twice",
        ),
        (
            vec!["sweep", "--beta", "0.2,0.20"],
            "--beta: `0.2` is given twice",
        ),
        (vec!["sweep", "-s", "4,4"], "--segments: `4` is given twice"),
        (
            vec!["solvers", "--data", "ring,ring"],
            "--data: `ring` is given twice",
        ),
        (
            vec!["schemes", "--data", "octa,octa"],
            "--data: `octa` is given twice",
        ),
        (
            vec!["curve", "--curves", "chord,chord"],
            "--curves: `chord` is given twice",
        ),
    ] {
        let (code, err) = run(&[&args[..], &["-o", out]].concat());
        assert_ne!(code, 0, "{args:?}");
        assert!(err.contains(item), "{args:?}: {err}");
    }
    assert!(!dir.path().join("x").exists(), "nothing written");
}

/// `-o` given a symbolic link to a directory writes into the directory (the link stays).
#[cfg(unix)]
#[test]
fn a_link_to_a_directory_is_an_output_directory() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("target");
    std::fs::create_dir(&target).unwrap();
    let link = dir.path().join("link");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let (code, err) = run(&[
        "sweep",
        "--data",
        "octa",
        "--curves",
        "chord",
        "-o",
        link.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(target.join("report.json").is_file());
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
}

/// A whole run plots K and H along the data sets' paths, every task against the truth; a mesh
/// file and the octahedron have no paths, and a sharded run draws nothing (its lines hold no
/// surfaces).
#[test]
fn a_whole_run_plots_the_curvature_along_paths() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let grid = ["--data", "ring,octa", "--curves", "chord,dbhs"];
    let (code, err) = run(&[&["sweep", "-o", out][..], &grid].concat());
    assert_eq!(code, 0, "{err}");
    let md = std::fs::read_to_string(dir.path().join("curvature.md")).unwrap();
    assert!(md.contains("![ring](curvature-ring.png)"), "{md}");
    assert!(!md.contains("curvature-octa"), "{md}");
    for ext in ["png", "svg"] {
        let f = dir.path().join(format!("curvature-ring.{ext}"));
        assert!(
            std::fs::metadata(&f).unwrap().len() > 10_000,
            "{}",
            f.display()
        );
    }
    let svg = std::fs::read_to_string(dir.path().join("curvature-ring.svg")).unwrap();
    for label in [
        "true surface",
        "chord",
        "dbhs",
        "K along the outer equator",
        "H along the meridian",
    ] {
        assert!(svg.contains(label), "{label}");
    }
    let shards = tempfile::tempdir().unwrap();
    let s = shards.path().to_str().unwrap();
    let (code, err) = run(&[&["sweep", "--shard", "0/1", "-o", s][..], &grid].concat());
    assert_eq!(code, 0, "{err}");
    assert!(!shards.path().join("curvature.md").exists());
    assert!(!shards.path().join("tasks-ring.png").exists());
}

/// The PNG's (width, height), from its IHDR chunk.
fn png_size(path: &std::path::Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap();
    assert_eq!(&b[1..4], b"PNG", "{}", path.display());
    let be = |i: usize| u32::from_be_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
    (be(16), be(20))
}

/// A whole run draws one composite per data set, a column per task (shaded, K, reflection
/// lines), octahedron included, names them in `curvature.md`, and names the tasks beyond the
/// composite's columns.
#[test]
fn a_whole_run_draws_a_composite_per_data_set_with_a_column_per_task() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    let grid = ["--data", "ring,octa", "--curves", "chord,dbhs"];
    let (code, err) = run(&[&["sweep", "-o", out][..], &grid].concat());
    assert_eq!(code, 0, "{err}");
    let md = std::fs::read_to_string(dir.path().join("curvature.md")).unwrap();
    let (ring, octa) = (
        dir.path().join("tasks-ring.png"),
        dir.path().join("tasks-octa.png"),
    );
    assert!(md.contains("![ring: every task](tasks-ring.png)"), "{md}");
    assert!(md.contains("![octa: every task](tasks-octa.png)"), "{md}");
    assert!(!md.contains("Left out of the composite"), "{md}");
    // Two tasks a data set: two tile columns, three tile rows (taller than wide per tile).
    let (w, h) = png_size(&ring);
    assert_eq!(png_size(&octa), (w, h));
    assert_eq!(w % 2, 0);
    assert!(h > (w / 2) * 2, "{w}×{h}: fewer than three rows of tiles");
    // Twelve tasks on the ring: ten columns, two named as left out.
    let many = tempfile::tempdir().unwrap();
    let m = many.path().to_str().unwrap();
    let grid = [
        "--data",
        "ring",
        "--curves",
        "chord",
        "--beta",
        "0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0,1.1,1.2",
    ];
    let (code, err) = run(&[&["sweep", "-o", m][..], &grid].concat());
    assert_eq!(code, 0, "{err}");
    let (w10, _) = png_size(&many.path().join("tasks-ring.png"));
    assert_eq!(w10, w / 2 * 10);
    let md = std::fs::read_to_string(many.path().join("curvature.md")).unwrap();
    assert!(
        md.contains("Left out of the composite (more than 10 tasks)"),
        "{md}"
    );
}

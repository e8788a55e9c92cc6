//! The `curve` experiment as a user runs it: standard input to standard output, bad lines named,
//! exit status.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use common::run;

#[test]
fn answers_every_line_in_order_and_names_bad_ones() {
    let input = concat!(
        r#"{"t0":[0.995,0.0998],"t1":[0.995,-0.0998],"k0":-0.2,"k1":-0.2,"tag":"a"}"#,
        "\n",
        r#"{"t0":[1,0],"t1":[1,0],"k0":0}"#,
        "\n\n",
        "not json\n",
        r#"{"t0":[0.6,0.8],"t1":[0.6,-0.8],"k0":-1.0,"k1":-1.0}"#,
        "\n"
    );
    let (code, out, err) = run(&["curve"], input);
    assert_eq!(code, 1, "bad lines make the exit status non-zero");
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).expect("JSON line"))
        .collect();
    assert_eq!(lines.len(), 4);
    assert_eq!(lines[0]["line"], 1);
    assert_eq!(lines[0]["input"]["tag"], "a");
    assert_eq!(
        lines[0]["methods"]["chord"]["alpha"],
        serde_json::json!([1.0, 1.0])
    );
    assert!(lines[0]["methods"]["dbhs"]["solutions"].is_array());
    assert_eq!(lines[1]["line"], 2);
    assert_eq!(lines[1]["error"], "missing field `k1`");
    assert!(lines[1].get("methods").is_none());
    assert_eq!(lines[2]["line"], 4);
    assert!(lines[2]["error"]
        .as_str()
        .expect("message")
        .starts_with("bad JSON"));
    assert_eq!(lines[3]["line"], 5);
    assert!(lines[3]["methods"]["dbhs"]["alpha"].is_array());
    assert!(err.contains("2 problems answered, 2 with errors"), "{err}");
    assert!(err.contains("line 2: missing field `k1`"), "{err}");
}

#[test]
fn an_unknown_method_is_a_usage_error_and_a_missing_file_a_runtime_error() {
    let (code, out, err) = run(&["curve", "--curves", "chord,splines"], "");
    assert_eq!(code, 2);
    assert!(out.is_empty());
    assert!(
        err.contains("unknown boundary-curve method `splines`"),
        "{err}"
    );
    let (code, _, err) = run(&["curve", "--input", "/nonexistent/problems.jsonl"], "");
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("/nonexistent/problems.jsonl"), "{err}");
    // The cause is kept and printed on its own line.
    assert!(
        err.lines()
            .any(|l| l.trim_start().starts_with("caused by: ")),
        "{err}"
    );
}

#[test]
fn ring_study_runs_small_and_reports_g1() {
    let dir = std::env::temp_dir().join(format!("ring-test-{}", std::process::id()));
    let out = dir.to_str().expect("utf-8 path");
    let (code, stdout, err) = run(
        &[
            "ring",
            "--resolution",
            "6",
            "--segments",
            "2",
            "--output",
            out,
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("optimized"), "{stdout}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).expect("report"))
            .expect("JSON");
    // By default the seeds' three constructions.
    let seeds = ["chord", "dbhs", "optimized"];
    for m in seeds {
        let g1 = report["methods"][m]["g1_defect_exterior_radians"]
            .as_f64()
            .expect("number");
        assert!(g1 < 1e-9, "{m}: {g1}");
    }
    // The true ring, the flat triangles, and one surface per construction.
    assert_eq!(
        report["surfaces"].as_array().map(Vec::len),
        Some(2 + seeds.len())
    );
    for f in [
        "shaded.png",
        "kcolor.png",
        "radial.png",
        "figure2.png",
        "optimized.ply",
        "report.md",
    ] {
        assert!(dir.join(f).exists(), "{f} missing");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `ring --curves` takes any registered constructions (one surface each, G1 on every one) and
/// refuses one listed twice.
#[test]
fn ring_study_takes_a_list_of_constructions() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().expect("utf-8 path");
    let small = ["ring", "--resolution", "6", "--segments", "2", "-o", out];
    let (code, _, err) = run(&[&small[..], &["--curves", "piper,tweak"]].concat(), "");
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("report.json")).expect("report"),
    )
    .expect("JSON");
    for m in ["piper", "tweak"] {
        let g1 = report["methods"][m]["g1_defect_exterior_radians"]
            .as_f64()
            .expect("number");
        assert!(g1 < 1e-9, "{m}: {g1}");
    }
    assert_eq!(report["surfaces"].as_array().map(Vec::len), Some(4));
    let (code, _, err) = run(&[&small[..], &["--curves", "chord,chord"]].concat(), "");
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("`chord` is listed twice"), "{err}");
}

#[test]
fn merge_refuses_an_incomplete_set_of_shards() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().expect("utf-8 path");
    let (code, _, err) = run(&["sweep", "--shard", "0/20", "-o", out], "");
    assert_eq!(code, 0, "{err}");
    assert!(dir.path().join("shard-0-of-20.jsonl").exists());
    let (code, _, err) = run(&["merge", "-o", out], "");
    assert_eq!(
        code, 1,
        "an incomplete set of shards is an input error: {err}"
    );
    // The default grid: four data sets × every construction, those that take a solver once per
    // solver (3).
    let tasks = 4 * curves::REGISTRY
        .iter()
        .map(|e| if curves::takes_solver(e.name) { 3 } else { 1 })
        .sum::<usize>();
    let held = tasks.div_ceil(20);
    assert!(
        err.contains(&format!("{} of {tasks} tasks missing", tasks - held)),
        "{err}"
    );
    let (code, _, err) = run(&["sweep", "--shard", "3/2", "-o", out], "");
    assert_eq!(code, 2, "{err}");
}

/// A problem line with a key twice is refused naming the line and the key (serde_json alone
/// would keep the last value silently; the testbed's readers refuse them too), nested keys
/// with their path; the other lines are answered.
#[test]
fn duplicate_keys_are_refused_with_the_line_and_the_key() {
    let input = concat!(
        r#"{"t0":[0.6,0.8],"t1":[0.6,-0.8],"k0":-1.0,"k1":-1.0}"#,
        "\n",
        r#"{"t0":[0.6,0.8],"t1":[0.6,-0.8],"k0":-1.0,"k1":-1.0,"k0":5.0}"#,
        "\n",
        r#"{"t0":[0.6,0.8],"t1":[0.6,-0.8],"k0":-1.0,"k1":-1.0,"meta":{"a":1,"a":2}}"#,
        "\n",
        r#"{"t0":[0.6,0.8],"t1":[0.6,-0.8],"k0":-1.0,"k\u0031":-1.0,"k1":2}"#,
        "\n",
        r#"{"t0":[0.6,0.8],"t1":[0.6,-0.8],"k0":-1.0,"k1":-1.0,"list":[{"a":1},{"a":2}]}"#,
        "\n",
    );
    let (code, out, err) = run(&["curve", "--curves", "chord"], input);
    assert_eq!(code, 1, "{err}");
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).expect("JSON line"))
        .collect();
    assert_eq!(lines.len(), 5);
    assert!(lines[0]["methods"]["chord"].is_object());
    assert_eq!(
        lines[1]["error"],
        "duplicate key `k0` (which of its values was meant is not known)"
    );
    assert!(lines[1].get("methods").is_none());
    assert!(
        lines[2]["error"].as_str().unwrap().contains("`meta.a`"),
        "{}",
        lines[2]
    );
    assert!(
        lines[3]["error"].as_str().unwrap().contains("`k1`"),
        "{}",
        lines[3]
    );
    // The same key in two objects of an array is no duplicate.
    assert!(lines[4]["methods"]["chord"].is_object(), "{}", lines[4]);
    assert!(err.contains("line 2: duplicate key `k0`"), "{err}");
    assert!(err.contains("2 problems answered, 3 with errors"), "{err}");
}

/// `--plot` draws the figures of at most `--plot-limit` problems (each about 550 kB) and says
/// how many it left out; every problem is still answered and tabled.
#[test]
fn plots_are_bounded_by_a_stated_limit() {
    let dir = tempfile::tempdir().unwrap();
    let plot = dir.path().join("plot");
    let line = r#"{"t0":[0.6,0.8],"t1":[0.6,-0.8],"k0":-1.0,"k1":-1.0}"#;
    let input = format!("{line}\n{line}\n{line}\n");
    let (code, out, err) = run(
        &[
            "curve",
            "--curves",
            "chord",
            "--plot",
            plot.to_str().unwrap(),
            "--plot-limit",
            "2",
        ],
        input,
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 3);
    let pngs = std::fs::read_dir(&plot)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "png")
        })
        .count();
    assert_eq!(pngs, 2);
    assert!(
        err.contains("figures of the first 2 of 3 answered problems"),
        "{err}"
    );
    let md = std::fs::read_to_string(plot.join("report.md")).unwrap();
    assert!(md.contains("Figures of the first 2 of 3 problems"), "{md}");
    assert_eq!(md.matches("| chord |").count(), 3, "every problem tabled");
    // The limit has a stated range.
    let (code, _, err) = run(&["curve", "--plot-limit", "100000"], "");
    assert_ne!(code, 0);
    assert!(
        err.contains("--plot-limit 100000: outside its valid range [1, 1000]"),
        "{err}"
    );
}

/// A line longer than the limit gets an error record without being held; the others are
/// answered.
#[test]
fn a_line_longer_than_the_limit_is_refused_and_skipped() {
    let line = r#"{"t0":[0.6,0.8],"t1":[0.6,-0.8],"k0":-1.0,"k1":-1.0}"#;
    let long = format!("{{\"pad\":\"{}\"}}", "x".repeat(200_000));
    let (code, out, err) = run(
        &["curve", "--curves", "chord"],
        format!("{line}\n{long}\n{line}\n"),
    );
    assert_eq!(code, 1, "{err}");
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).expect("JSON line"))
        .collect();
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[1]["line"], 2);
    assert!(
        lines[1]["error"]
            .as_str()
            .unwrap()
            .contains("longer than the 65536"),
        "{}",
        lines[1]
    );
    assert_eq!(lines[2]["line"], 3);
    assert!(lines[2]["methods"]["chord"].is_object());
}

#[test]
fn a_line_that_is_not_utf8_gets_its_own_error_and_the_others_answers() {
    let (code, out, _) = run(
        &["curve", "--curves", "chord"],
        b"{\"t0\":[1,0],\"t1\":[1,0],\"k0\":0,\"k1\":0}\n\xff\xfe bad\n{\"t0\":[0.6,0.8],\"t1\":[0.6,-0.8],\"k0\":-1.0,\"k1\":-1.0}\n",
    );
    assert_eq!(code, 1);
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).expect("json"))
        .collect();
    assert_eq!(lines.len(), 3);
    assert!(lines[0]["methods"]["chord"].is_object());
    assert!(lines[1]["error"]
        .as_str()
        .expect("error")
        .contains("not UTF-8"));
    assert!(lines[2]["methods"]["chord"].is_object());
}

/// `alpha` of construction `m` in a `curve` answer line.
fn alpha_of(line: &serde_json::Value, m: &str) -> [f64; 2] {
    let a = &line["methods"][m]["alpha"];
    [a[0].as_f64().expect("α0"), a[1].as_f64().expect("α1")]
}

/// The original testbed's tangent rules through the command line: `--curves` takes their
/// registered names, `--tweak-t` and `--four-ninths` reach them, bad values are usage errors.
#[test]
fn the_testbed_tangent_rules_and_their_options_reach_the_curve_command() {
    /// The answers are written with shortest-round-trip digits: closed forms to rounding.
    const ROUNDING: f64 = 1e-12;
    // An arc with tangents at 60° to its chord: cos θ = ½.
    let s = 0.75f64.sqrt();
    let input = format!(r#"{{"t0":[0.5,{s}],"t1":[0.5,-{s}],"k0":0,"k1":0}}"#) + "\n";
    let args = [
        "curve",
        "--curves",
        "projection,piper,tweak,quadric,projection-scaled",
    ];
    let (code, out, err) = run(&args, &input);
    assert_eq!(code, 0, "{err}");
    let line: serde_json::Value = serde_json::from_str(out.trim()).expect("JSON line");
    let want = [
        ("projection", 0.5),
        ("piper", 5.0 / 9.0),
        ("projection-scaled", 1.0),
        // 3t/(2 cos θ) at the default t = 0.5858, and 1/cos θ for the quadric.
        ("tweak", 3.0 * 0.5858),
        ("quadric", 2.0),
    ];
    for (m, a) in want {
        for got in alpha_of(&line, m) {
            assert!((got - a).abs() < ROUNDING, "{m}: {got} vs {a}");
        }
    }
    let (code, out, err) = run(
        &[&args[..], &["--tweak-t", "0.5", "--four-ninths"]].concat(),
        &input,
    );
    assert_eq!(code, 0, "{err}");
    let line: serde_json::Value = serde_json::from_str(out.trim()).expect("JSON line");
    for (m, a) in [
        ("projection", 5.0 / 6.0),
        ("piper", 25.0 / 27.0),
        ("projection-scaled", 5.0 / 3.0),
        ("tweak", 1.5),
        ("quadric", 2.0),
    ] {
        for got in alpha_of(&line, m) {
            assert!((got - a).abs() < ROUNDING, "{m}: {got} vs {a}");
        }
    }
    for bad in ["0", "-0.5", "1.5", "nan"] {
        let (code, out, err) = run(&["curve", "--tweak-t", bad], &input);
        assert_eq!(code, 2, "{bad}: {err}");
        assert!(out.is_empty());
        assert!(
            err.contains("outside (0, 1]") || err.contains("not a number"),
            "{err}"
        );
    }
}

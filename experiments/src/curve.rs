//! `experiments -- curve`: boundary curves for planar unit-chord problems.
//!
//! Input: JSON Lines, one problem a line, `{"t0":[x,y],"t1":[x,y],"k0":k,"k1":k}` on the unit
//! chord from (0,0) to (1,0); other fields are kept and echoed. Output: one JSON line per input
//! line, in input order:
//!
//! ```text
//! {"line": n, "input": {…}, "methods": {"chord": {"alpha": [a0, a1], "points": [[x, y], …],
//!   "kappa": [k0, k1], "curvature_variation": v},
//!   "dbhs": {"solutions": [{"alpha", "points", "kappa", "curvature_variation"}, …],
//!            "chosen": i | null, "fallback": bool, "alpha": …, "points": …, "kappa": …, …},
//!   "optimized": {"alpha", "points", "kappa", "curvature_variation", "report": {solver report}}}}
//! ```
//!
//! `kappa` holds the end curvatures the curve achieves (compare with the input's `k0, k1`);
//! `curvature_variation` is `∫ (dκ/ds)² ds`. A line that cannot be read gets
//! `{"line": n, "input": …, "error": "…"}` instead of `"methods"`; the other lines are still
//! answered, stderr sums up, and the exit status is 1. This schema is a contract: extend it, do
//! not rename it.

use std::io::{BufRead, Read as _};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use curves::jsonl::{self, LineAnswer};
use curves::{method_by_name, CurveMethod, MethodOptions};
use render::{CurveFigure, CurvePanel};
use serde_json::{json, Value};
use solver::SolveOptions;

use crate::curve_args::CurveOptions;
use crate::error::ExperimentError;
use crate::output::{ensure_dir, write_result, Staged};

/// Figures written by `--plot` unless `--plot-limit` says otherwise: a figure is about 550 kB
/// (PNG and SVG), so the default keeps a plot directory near 55 MB.
const DEFAULT_PLOT_LIMIT: usize = 100;

/// The most figures `--plot-limit` allows: about 550 MB of pictures, more than anyone looks at.
const PLOT_LIMIT_RANGE: std::ops::RangeInclusive<usize> = 1..=1000;

/// Longest input line read, in bytes: a problem is about 100 bytes; a longer line gets an error
/// record (the rest of it is skipped, never held), so one huge line cannot exhaust the memory.
const MAX_LINE_BYTES: usize = 64 * 1024;

/// Options of the `curve` experiment.
#[derive(clap::Args, Debug)]
pub struct CurveArgs {
    /// JSON Lines file of problems (standard input when absent or `-`).
    #[arg(long)]
    input: Option<PathBuf>,
    /// Where to write the JSON Lines answers (standard output when absent or `-`).
    #[arg(short = 'o', long)]
    output: Option<PathBuf>,
    /// Comma-separated constructions to run (by default every registered one), each once.
    #[arg(long, value_delimiter = ',', default_value = crate::curve_args::all_methods())]
    curves: Vec<String>,
    /// The curve constructions' options.
    #[command(flatten)]
    curve: CurveOptions,
    /// Directory for Figure-2-style plots (PNG and SVG per problem) with report.md and
    /// report.json.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// With `--plot`: the figures of the first N answered problems are drawn (each about
    /// 550 kB), the others only tabled; report.md and stderr say how many were left out.
    #[arg(long, default_value_t = DEFAULT_PLOT_LIMIT, value_name = "N")]
    plot_limit: usize,
}

/// `-` as a path: standard input or output.
fn stdio_dash(p: &Option<PathBuf>) -> Option<&Path> {
    p.as_deref().filter(|p| *p != Path::new("-"))
}

/// The first key of an object in `text` (valid JSON) that the same object already has, with
/// the keys of the objects it sits in (`meta.k0`); `None` when every key is unique. JSON
/// readers disagree on which of two values to keep (serde_json keeps the last, others the
/// first), so a line with one is refused, as every reader of the testbed refuses it. Keys are
/// compared decoded (`"k0"` and `"k\u0030"` are one key).
fn first_duplicate_key(text: &str) -> Option<String> {
    // Per open container: its keys so far (`None` for an array) and its key being read.
    let mut stack: Vec<(Option<Vec<String>>, Option<String>)> = Vec::new();
    let mut expect_key = false;
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'{' => {
                stack.push((Some(Vec::new()), None));
                expect_key = true;
            }
            b'[' => {
                stack.push((None, None));
                expect_key = false;
            }
            b'}' | b']' => {
                stack.pop();
                expect_key = false;
            }
            b',' => expect_key = matches!(stack.last(), Some((Some(_), _))),
            b'"' => {
                let start = i;
                i += 1;
                while i < bytes.len() && bytes[i] != b'"' {
                    i += if bytes[i] == b'\\' { 2 } else { 1 };
                }
                if expect_key {
                    let raw = text.get(start..=i).unwrap_or_default();
                    let key = serde_json::from_str::<String>(raw).unwrap_or_else(|_| raw.into());
                    let outer = stack.len().saturating_sub(1);
                    let path = || {
                        stack[..outer]
                            .iter()
                            .filter_map(|(_, k)| k.clone())
                            .chain(std::iter::once(key.clone()))
                            .collect::<Vec<_>>()
                            .join(".")
                    };
                    if let Some((Some(keys), _)) = stack.last() {
                        if keys.contains(&key) {
                            return Some(path());
                        }
                    }
                    if let Some((Some(keys), current)) = stack.last_mut() {
                        keys.push(key.clone());
                        *current = Some(key);
                    }
                    expect_key = false;
                }
            }
            _ => {}
        }
        i += 1;
    }
    None
}

/// Runs the experiment; `Ok` carries the exit code (1 if some lines were bad).
pub fn run(args: &CurveArgs) -> Result<ExitCode, ExperimentError> {
    let defaults = MethodOptions::default();
    let options = MethodOptions {
        solve_options: SolveOptions {
            record_history: true,
            ..defaults.solve_options
        },
        ..args.curve.method_options()
    };
    crate::study::refuse_duplicate_names("--curves", &args.curves)?;
    crate::limits::check_usize("plot-limit", args.plot_limit, &PLOT_LIMIT_RANGE)?;
    let methods: Vec<Box<dyn CurveMethod>> = args
        .curves
        .iter()
        .map(|m| method_by_name(m.trim(), &options))
        .collect::<Result<_, _>>()
        .map_err(ExperimentError::from)?;
    let (input, output) = (stdio_dash(&args.input), stdio_dash(&args.output));
    if let (Some(i), Some(o)) = (input, output) {
        crate::output::refuse_overwriting_input("--output", o, &i.to_string_lossy())?;
    }
    let lines = read_lines(input)?;

    let mut out = String::new();
    let mut answered = Vec::new();
    let mut bad = Vec::new();
    // Lines are split on bytes: a line that is not UTF-8 gets its own error, the others are
    // answered (`curves::jsonl`).
    for (i, line_read) in lines.into_iter().enumerate() {
        let line = i + 1;
        let refused = match &line_read {
            Line::TooLong(n) => Some((
                format!("a line of {n} bytes: longer than the {MAX_LINE_BYTES} a problem may take"),
                Value::Null,
            )),
            Line::Text(bytes) => std::str::from_utf8(bytes)
                .ok()
                .filter(|t| serde_json::from_str::<Value>(t).is_ok())
                .and_then(|t| first_duplicate_key(t).map(|k| (t, k)))
                .map(|(t, k)| {
                    (
                        format!("duplicate key `{k}` (which of its values was meant is not known)"),
                        Value::String(t.to_string()),
                    )
                }),
        };
        let record = match (refused, &line_read) {
            (Some((error, input)), _) => {
                let record = json!({"line": line, "input": input, "error": error});
                bad.push((line, error));
                record
            }
            (None, Line::TooLong(_)) => continue,
            (None, Line::Text(bytes)) => match jsonl::answer_line(line, bytes, &methods) {
                None => continue,
                Some(Ok(a)) => {
                    let v = jsonl::answer_json(&a);
                    answered.push(a);
                    v
                }
                Some(Err((error, record))) => {
                    bad.push((line, error));
                    record
                }
            },
        };
        out.push_str(&record.to_string());
        out.push('\n');
    }
    // The plot directory is written whole (staged, then swapped in); an `--output` inside it
    // goes into the staging directory too, so it is not lost in the swap.
    let staged = args.plot.as_deref().map(Staged::begin).transpose()?;
    let output = match (output, &args.plot, &staged) {
        (Some(o), Some(dir), Some(st)) => match o.strip_prefix(dir) {
            Ok(rel) => Some(st.path().join(rel)),
            Err(_) => Some(o.to_path_buf()),
        },
        (o, _, _) => o.map(Path::to_path_buf),
    };
    write_result(output.as_deref(), out.as_bytes())?;
    if let Some(st) = staged {
        write_plots(st.path(), &answered, args)?;
        st.commit()?;
        if answered.len() > args.plot_limit {
            say!(
                "curve: figures of the first {} of {} answered problems drawn (--plot-limit {}); every problem is in the tables",
                args.plot_limit,
                answered.len(),
                args.plot_limit
            );
        }
    }
    let fallbacks = answered
        .iter()
        .flat_map(|a| a.choices.iter())
        .filter(|c| c.2.fallback)
        .count();
    let overshooting = answered
        .iter()
        .flat_map(|a| a.choices.iter().map(move |c| (a, c)))
        .filter(|(a, c)| jsonl::curve_json(&a.problem, c.2.alpha).contains_key("overshoots_chord"))
        .count();
    let unconverged = answered
        .iter()
        .flat_map(|a| a.choices.iter())
        .filter(|c| c.2.report.as_ref().is_some_and(|r| !r.converged()))
        .count();
    say!(
        "curve: {} problems answered, {} with errors, {} fallbacks to chord, {} unconverged optimizations, {} curves overshooting their chord",
        answered.len(),
        bad.len(),
        fallbacks,
        unconverged,
        overshooting
    );
    for (line, e) in &bad {
        say!("  line {line}: {e}");
    }
    Ok(if bad.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// One input line: its bytes (without the newline), or how long it was when it was longer
/// than [`MAX_LINE_BYTES`] (its bytes are not kept).
enum Line {
    Text(Vec<u8>),
    TooLong(usize),
}

/// Reads the lines of `path` (standard input when `None`), each at most [`MAX_LINE_BYTES`]
/// held: a longer one is skipped to its end and kept as [`Line::TooLong`].
fn read_lines(path: Option<&Path>) -> Result<Vec<Line>, ExperimentError> {
    let shown = path.map_or_else(|| PathBuf::from("<stdin>"), Path::to_path_buf);
    let err = |source| ExperimentError::Read {
        path: shown.clone(),
        source,
    };
    let mut reader: Box<dyn BufRead> = match path {
        Some(p) => Box::new(std::io::BufReader::new(
            std::fs::File::open(p).map_err(err)?,
        )),
        None => Box::new(std::io::BufReader::new(std::io::stdin())),
    };
    let mut lines = Vec::new();
    loop {
        let mut buf = Vec::new();
        let n = (&mut reader)
            .take(MAX_LINE_BYTES as u64 + 1)
            .read_until(b'\n', &mut buf)
            .map_err(err)?;
        if n == 0 {
            break;
        }
        if buf.last() == Some(&b'\n') {
            buf.pop();
            lines.push(Line::Text(buf));
        } else if buf.len() <= MAX_LINE_BYTES {
            // The last line, without a newline.
            lines.push(Line::Text(buf));
        } else {
            // Too long: skip to the end of the line without holding it.
            let mut length = buf.len();
            loop {
                let chunk = reader.fill_buf().map_err(err)?;
                if chunk.is_empty() {
                    break;
                }
                match chunk.iter().position(|b| *b == b'\n') {
                    Some(k) => {
                        length += k;
                        reader.consume(k + 1);
                        break;
                    }
                    None => {
                        let k = chunk.len();
                        length += k;
                        reader.consume(k);
                    }
                }
            }
            lines.push(Line::TooLong(length));
        }
    }
    Ok(lines)
}

fn problem_label(a: &LineAnswer) -> String {
    a.input
        .get("name")
        .and_then(Value::as_str)
        .map(str::to_string)
        .unwrap_or_else(|| format!("line {}", a.line))
}

fn file_stem(a: &LineAnswer) -> String {
    let name: String = problem_label(a)
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("problem-{:03}-{}", a.line, name)
}

fn fmt_pair(x: [f64; 2]) -> String {
    format!("({:.4}, {:.4})", x[0], x[1])
}

fn panels(a: &LineAnswer) -> Vec<CurvePanel> {
    let p = &a.problem;
    let targets = [p.k0, p.k1];
    let panel = |title: String, alpha: [f64; 2]| CurvePanel {
        title,
        curve: p.curve(alpha),
        targets,
        notes: vec![format!("α = {}", fmt_pair(alpha))],
    };
    let mut out = Vec::new();
    for (name, enumerates, choice) in &a.choices {
        let title = if choice.fallback {
            format!("{name}: none, chord fallback")
        } else if *enumerates {
            match choice.chosen {
                Some(i) => format!(
                    "{name} (solution {} of {}, chosen)",
                    i + 1,
                    choice.candidates.len()
                ),
                None => (*name).to_string(),
            }
        } else {
            (*name).to_string()
        };
        out.push(panel(title, choice.alpha));
        if *enumerates {
            for (i, alpha) in choice.candidates.as_slice().iter().enumerate() {
                if Some(i) != choice.chosen {
                    out.push(panel(
                        format!("{name} (solution {} of {})", i + 1, choice.candidates.len()),
                        *alpha,
                    ));
                }
            }
        }
    }
    out
}

fn write_plots(
    dir: &Path,
    answered: &[LineAnswer],
    args: &CurveArgs,
) -> Result<(), ExperimentError> {
    ensure_dir(dir)?;
    let mut md = String::new();
    md.push_str("# Boundary curves for unit-chord problems\n\n");
    md.push_str(&format!(
        "Written by `cargo run --release -p experiments -- curve{}{} --curves {} --dbhs-pick {} --solver {} --tweak-t {}{} --plot {} --plot-limit {}`.\n\n",
        args.input
            .as_ref()
            .map(|p| format!(" --input {}", p.display()))
            .unwrap_or_default(),
        args.output
            .as_ref()
            .map(|p| format!(" --output {}", p.display()))
            .unwrap_or_default(),
        args.curves.join(","),
        args.curve.dbhs_pick,
        args.curve.solver,
        args.curve.tweak_t,
        if args.curve.four_ninths { " --four-ninths" } else { "" },
        args.plot.as_deref().unwrap_or(dir).display(),
        args.plot_limit
    ));
    md.push_str(
        "Each figure shows, per construction, the cubic on the unit chord with its control \
         points (×) and below it the signed curvature against normalized arc length, with the \
         straight line joining the target end curvatures (as in Figure 2 of Mann 1994). \
         `α` are the end-derivative lengths (α = 1 is one third of the chord).\n\n",
    );
    md.push_str("| line | problem | construction | α0 | α1 | κ(0) | κ(1) | target κ(0) | target κ(1) | ∫(dκ/ds)² ds |\n");
    md.push_str("|---:|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    let mut records = Vec::new();
    for a in answered {
        let label = problem_label(a);
        for (name, _, choice) in &a.choices {
            let k = a.problem.end_curvatures(choice.alpha);
            let var = a.problem.curve(choice.alpha).curvature_variation();
            md.push_str(&format!(
                "| {} | {} | {}{} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.4} | {:.3e} |\n",
                a.line,
                label,
                name,
                if choice.fallback { " (fallback)" } else { "" },
                choice.alpha[0],
                choice.alpha[1],
                k[0],
                k[1],
                a.problem.k0,
                a.problem.k1,
                var
            ));
        }
        records.push(jsonl::answer_json(a));
    }
    md.push('\n');
    let plotted = answered.len().min(args.plot_limit);
    if plotted < answered.len() {
        md.push_str(&format!(
            "Figures of the first {plotted} of {} problems (`--plot-limit {}`; each figure is about 550 kB); every problem is in the table above.\n\n",
            answered.len(),
            args.plot_limit
        ));
    }
    for a in &answered[..plotted] {
        let stem = file_stem(a);
        let fig = CurveFigure {
            title: format!(
                "{} — t0 = {}, t1 = {}, targets κ = {}",
                problem_label(a),
                fmt_pair([a.problem.t0.x, a.problem.t0.y]),
                fmt_pair([a.problem.t1.x, a.problem.t1.y]),
                fmt_pair([a.problem.k0, a.problem.k1])
            ),
            rows: vec![panels(a)],
        };
        render::write_curve_figure(
            &fig,
            &dir.join(format!("{stem}.png")),
            &dir.join(format!("{stem}.svg")),
        )?;
        let source = a
            .input
            .get("source")
            .and_then(Value::as_str)
            .map(|s| format!(": {s}"))
            .unwrap_or_default();
        md.push_str(&format!(
            "## {}{}\n\n![{}]({}.png)\n\n",
            problem_label(a),
            source,
            problem_label(a),
            stem
        ));
    }
    let report = json!({"experiment": "curve", "problems": records,
                        "plotted": plotted, "plot_limit": args.plot_limit});
    let json_text = crate::output::pretty_json(&report, "the curve report")?;
    write_result(Some(&dir.join("report.json")), json_text.as_bytes())?;
    write_result(Some(&dir.join("report.md")), md.as_bytes())?;
    Ok(())
}

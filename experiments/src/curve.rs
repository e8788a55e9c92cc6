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

use std::io::Read;
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

/// Options of the `curve` experiment.
#[derive(clap::Args, Debug)]
pub struct CurveArgs {
    /// JSON Lines file of problems (standard input when absent).
    #[arg(long)]
    input: Option<PathBuf>,
    /// Where to write the JSON Lines answers (standard output when absent).
    #[arg(long)]
    output: Option<PathBuf>,
    /// Comma-separated constructions to run (by default every registered one).
    #[arg(long, value_delimiter = ',', default_value = crate::curve_args::all_methods())]
    methods: Vec<String>,
    /// The curve constructions' options.
    #[command(flatten)]
    curve: CurveOptions,
    /// Directory for Figure-2-style plots (PNG and SVG per problem) with report.md and
    /// report.json.
    #[arg(long)]
    plot: Option<PathBuf>,
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
    let methods: Vec<Box<dyn CurveMethod>> = args
        .methods
        .iter()
        .map(|m| method_by_name(m.trim(), &options))
        .collect::<Result<_, _>>()
        .map_err(ExperimentError::from)?;
    if let (Some(i), Some(o)) = (&args.input, &args.output) {
        crate::output::refuse_overwriting_input("--output", o, &i.to_string_lossy())?;
    }
    let text = read_input(args.input.as_deref())?;

    let mut out = String::new();
    let mut answered = Vec::new();
    let mut bad = Vec::new();
    // Lines are split on bytes: a line that is not UTF-8 gets its own error, the others are
    // answered (`curves::jsonl`).
    for (i, bytes) in text.split(|b| *b == b'\n').enumerate() {
        let line = i + 1;
        let record = match jsonl::answer_line(line, bytes, &methods) {
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
        };
        out.push_str(&record.to_string());
        out.push('\n');
    }
    // The plot directory is written whole (staged, then swapped in); an `--output` inside it
    // goes into the staging directory too, so it is not lost in the swap.
    let staged = args.plot.as_deref().map(Staged::begin).transpose()?;
    let output = match (&args.output, &args.plot, &staged) {
        (Some(o), Some(dir), Some(st)) => match o.strip_prefix(dir) {
            Ok(rel) => Some(st.path().join(rel)),
            Err(_) => Some(o.clone()),
        },
        (o, _, _) => o.clone(),
    };
    write_result(output.as_deref(), out.as_bytes())?;
    if let Some(st) = staged {
        write_plots(st.path(), &answered, args)?;
        st.commit()?;
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

fn read_input(path: Option<&Path>) -> Result<Vec<u8>, ExperimentError> {
    let mut text = Vec::new();
    match path {
        Some(p) => {
            text = std::fs::read(p).map_err(|source| ExperimentError::Read {
                path: p.to_path_buf(),
                source,
            })?
        }
        None => {
            std::io::stdin()
                .read_to_end(&mut text)
                .map_err(|source| ExperimentError::Read {
                    path: "<stdin>".into(),
                    source,
                })?;
        }
    }
    Ok(text)
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
        "Written by `cargo run --release -p experiments -- curve{}{} --methods {} --dbhs-pick {} --solver {} --plot {}`.\n\n",
        args.input
            .as_ref()
            .map(|p| format!(" --input {}", p.display()))
            .unwrap_or_default(),
        args.output
            .as_ref()
            .map(|p| format!(" --output {}", p.display()))
            .unwrap_or_default(),
        args.methods.join(","),
        args.curve.dbhs_pick,
        args.curve.solver,
        args.plot.as_deref().unwrap_or(dir).display()
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
    for a in answered {
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
    let report = json!({"experiment": "curve", "problems": records});
    let json_text = crate::output::pretty_json(&report, "the curve report")?;
    write_result(Some(&dir.join("report.json")), json_text.as_bytes())?;
    write_result(Some(&dir.join("report.md")), md.as_bytes())?;
    Ok(())
}

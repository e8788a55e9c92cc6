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

use curves::{method_by_name, CurveChoice, CurveMethod, DbhsPick, MethodOptions, UnitProblem};
use nalgebra::Vector2;
use render::{CurveFigure, CurvePanel};
use serde_json::{json, Map, Value};
use solver::{SolveOptions, SolverKind};

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
    /// Comma-separated constructions to run (known: chord, dbhs, optimized).
    #[arg(long, value_delimiter = ',', default_value = "chord,dbhs,optimized")]
    methods: Vec<String>,
    /// Solver of the optimized construction: exact-penalty, lbfgs or lm.
    #[arg(long, default_value_t = SolverKind::ExactPenalty)]
    solver: SolverKind,
    /// Which dBHS solution to take: closest (to α = (1, 1)), longest-short (largest shorter
    /// tangent), or a solution index in order of increasing α0.
    #[arg(long, default_value_t = DbhsPick::Closest)]
    dbhs_pick: DbhsPick,
    /// Directory for Figure-2-style plots (PNG and SVG per problem) with report.md and
    /// report.json.
    #[arg(long)]
    plot: Option<PathBuf>,
}

/// One input line that was read successfully.
struct Answered {
    line: usize,
    input: Value,
    problem: UnitProblem,
    choices: Vec<(&'static str, bool, CurveChoice)>,
}

/// Runs the experiment; `Ok` carries the exit code (1 if some lines were bad).
pub fn run(args: &CurveArgs) -> Result<ExitCode, ExperimentError> {
    let defaults = MethodOptions::default();
    let options = MethodOptions {
        dbhs_pick: args.dbhs_pick,
        solver: args.solver,
        solve_options: SolveOptions {
            record_history: true,
            ..defaults.solve_options
        },
        ..defaults
    };
    let methods: Vec<Box<dyn CurveMethod>> = args
        .methods
        .iter()
        .map(|m| method_by_name(m.trim(), &options))
        .collect::<Result<_, _>>()
        .map_err(|e| ExperimentError::Usage(e.to_string()))?;
    if let (Some(i), Some(o)) = (&args.input, &args.output) {
        crate::output::refuse_overwriting_input(o, &i.to_string_lossy())?;
    }
    let text = read_input(args.input.as_deref())?;

    let mut out = String::new();
    let mut answered = Vec::new();
    let mut bad = Vec::new();
    // Lines are split on bytes: a line that is not UTF-8 gets its own error, the others are
    // answered.
    for (i, bytes) in text.split(|b| *b == b'\n').enumerate() {
        let line = i + 1;
        let bytes = bytes.strip_suffix(b"\r").unwrap_or(bytes);
        let parsed = match std::str::from_utf8(bytes) {
            Ok(raw) if raw.trim().is_empty() => continue,
            Ok(raw) => parse_line(raw),
            Err(e) => Err((
                Value::String(String::from_utf8_lossy(bytes).into_owned()),
                format!("not UTF-8: {e}"),
            )),
        };
        let record = match parsed {
            Ok((input, problem)) => {
                let choices = methods
                    .iter()
                    .map(|m| (m.name(), m.enumerates_solutions(), m.construct(&problem)))
                    .collect();
                let a = Answered {
                    line,
                    input,
                    problem,
                    choices,
                };
                let v = answer_json(&a);
                answered.push(a);
                v
            }
            Err((input, error)) => {
                bad.push((line, error.clone()));
                let mut m = Map::new();
                m.insert("line".into(), json!(line));
                m.insert("input".into(), input);
                m.insert("error".into(), json!(error));
                Value::Object(m)
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
        .filter(|(a, c)| curve_json(&a.problem, c.2.alpha).contains_key("overshoots_chord"))
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

/// Parses one line; on failure returns what can be echoed as the input and the message.
fn parse_line(raw: &str) -> Result<(Value, UnitProblem), (Value, String)> {
    let value: Value = serde_json::from_str(raw)
        .map_err(|e| (Value::String(raw.to_string()), format!("bad JSON: {e}")))?;
    let problem = problem_from(&value).map_err(|e| (value.clone(), e))?;
    Ok((value, problem))
}

fn problem_from(v: &Value) -> Result<UnitProblem, String> {
    let obj = v
        .as_object()
        .ok_or_else(|| "expected a JSON object with t0, t1, k0, k1".to_string())?;
    let field = |name: &str| {
        obj.get(name)
            .ok_or_else(|| format!("missing field `{name}`"))
    };
    let vec2 = |name: &str| -> Result<Vector2<f64>, String> {
        let arr = field(name)?
            .as_array()
            .filter(|a| a.len() == 2)
            .ok_or_else(|| format!("`{name}` must be an array of two numbers"))?;
        let c = |i: usize| {
            arr[i]
                .as_f64()
                .ok_or_else(|| format!("`{name}` must be an array of two numbers"))
        };
        Ok(Vector2::new(c(0)?, c(1)?))
    };
    let num = |name: &str| -> Result<f64, String> {
        field(name)?
            .as_f64()
            .ok_or_else(|| format!("`{name}` must be a number"))
    };
    UnitProblem::new(vec2("t0")?, vec2("t1")?, num("k0")?, num("k1")?).map_err(|e| e.to_string())
}

/// `{"alpha", "points", "kappa", "curvature_variation"}` of the unit curve for `alpha`.
fn curve_json(problem: &UnitProblem, alpha: [f64; 2]) -> Map<String, Value> {
    let c = problem.curve(alpha);
    let mut m = Map::new();
    m.insert("alpha".into(), json!(alpha));
    m.insert(
        "points".into(),
        json!(c.points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>()),
    );
    m.insert("kappa".into(), json!(problem.end_curvatures(alpha)));
    m.insert(
        "curvature_variation".into(),
        json_number(c.curvature_variation()),
    );
    // A curve that runs past an end of its chord (antiparallel or backward tangents) is
    // flagged: `x(t)` of the unit-chord cubic leaves [0, 1] at one of OVERSHOOT_SAMPLES points.
    let overshoot = (0..=OVERSHOOT_SAMPLES).any(|i| {
        let x = c.eval(i as f64 / OVERSHOOT_SAMPLES as f64).x;
        !(-OVERSHOOT_TOL..=1.0 + OVERSHOOT_TOL).contains(&x)
    });
    if overshoot {
        m.insert("overshoots_chord".into(), json!(true));
    }
    m
}

/// Samples of `x(t)` checked for leaving the chord's slab (a cubic's `x(t)` has at most two
/// extrema, which 64 samples place to within 1/64 of the parameter).
const OVERSHOOT_SAMPLES: usize = 64;
/// Rounding allowance at the chord's ends, in chord lengths.
const OVERSHOOT_TOL: f64 = 1e-12;

/// A finite number, or null (JSON has no infinity: a cusp's curvature variation is unbounded).
fn json_number(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

fn answer_json(a: &Answered) -> Value {
    let mut methods = Map::new();
    for (name, enumerates, choice) in &a.choices {
        let mut m = Map::new();
        if *enumerates {
            let sols: Vec<Value> = choice
                .candidates
                .as_slice()
                .iter()
                .map(|alpha| Value::Object(curve_json(&a.problem, *alpha)))
                .collect();
            m.insert("solutions".into(), Value::Array(sols));
            m.insert("chosen".into(), json!(choice.chosen));
            m.insert("fallback".into(), json!(choice.fallback));
        } else if choice.fallback {
            m.insert("fallback".into(), json!(true));
        }
        m.extend(curve_json(&a.problem, choice.alpha));
        if let Some(report) = &choice.report {
            m.insert(
                "report".into(),
                serde_json::to_value(report).unwrap_or(Value::Null),
            );
        }
        methods.insert((*name).to_string(), Value::Object(m));
    }
    json!({"line": a.line, "input": a.input, "methods": methods})
}

fn problem_label(a: &Answered) -> String {
    a.input
        .get("name")
        .and_then(Value::as_str)
        .map(str::to_string)
        .unwrap_or_else(|| format!("line {}", a.line))
}

fn file_stem(a: &Answered) -> String {
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

fn panels(a: &Answered) -> Vec<CurvePanel> {
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

fn write_plots(dir: &Path, answered: &[Answered], args: &CurveArgs) -> Result<(), ExperimentError> {
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
        args.dbhs_pick,
        args.solver,
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
        records.push(answer_json(a));
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
    let mut json_text = serde_json::to_string_pretty(&report)
        .map_err(|e| ExperimentError::Usage(format!("cannot serialize the report: {e}")))?;
    json_text.push('\n');
    write_result(Some(&dir.join("report.json")), json_text.as_bytes())?;
    write_result(Some(&dir.join("report.md")), md.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_lines_are_named() {
        let err = |s: &str| parse_line(s).expect_err("bad line").1;
        assert!(err("{").starts_with("bad JSON"));
        assert_eq!(
            err(r#"{"t0":[1,0],"t1":[1,0],"k0":0}"#),
            "missing field `k1`"
        );
        assert_eq!(
            err(r#"{"t0":[1,0,0],"t1":[1,0],"k0":0,"k1":0}"#),
            "`t0` must be an array of two numbers"
        );
        assert!(err(r#"{"t0":[2,0],"t1":[1,0],"k0":0,"k1":0}"#).contains("expected a unit vector"));
        assert_eq!(
            err(r#"{"t0":[1,0],"t1":[1,0],"k0":"x","k1":0}"#),
            "`k0` must be a number"
        );
        assert!(err("[1, 2]").starts_with("expected a JSON object"));
        // JSON has no NaN; such a line is bad JSON.
        assert!(err(r#"{"t0":[NaN,0],"t1":[1,0],"k0":0,"k1":0}"#).starts_with("bad JSON"));
    }

    #[test]
    fn answers_keep_extra_fields_and_list_dbhs_solutions() {
        let (input, problem) = parse_line(
            r#"{"name":"arc","t0":[0.9950041652780258,0.09983341664682815],"t1":[0.9950041652780258,-0.09983341664682815],"k0":-0.2,"k1":-0.2}"#,
        )
        .expect("valid");
        let opts = MethodOptions::default();
        let methods: Vec<_> = ["chord", "dbhs"]
            .iter()
            .map(|m| method_by_name(m, &opts).expect("known"))
            .collect();
        let a = Answered {
            line: 1,
            input,
            problem,
            choices: methods
                .iter()
                .map(|m| (m.name(), m.enumerates_solutions(), m.construct(&problem)))
                .collect(),
        };
        let v = answer_json(&a);
        assert_eq!(v["input"]["name"], "arc");
        assert_eq!(v["methods"]["chord"]["alpha"], json!([1.0, 1.0]));
        let d = &v["methods"]["dbhs"];
        assert_eq!(d["solutions"].as_array().map(Vec::len), Some(3));
        assert_eq!(d["chosen"], json!(1));
        assert_eq!(d["fallback"], json!(false));
        let k = d["kappa"].as_array().expect("kappa");
        assert!((k[0].as_f64().expect("number") + 0.2).abs() < 1e-9);
        assert_eq!(d["points"].as_array().map(Vec::len), Some(4));
    }
}

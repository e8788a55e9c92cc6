//! The `curve` experiment's line protocol: one unit-chord problem a JSON line in, one answer a
//! line out, every construction's curve with its measures. A library module (not the runner's)
//! so that the fuzz harness and other tools answer lines exactly as the command does.
//!
//! Input: `{"t0":[x,y],"t1":[x,y],"k0":k,"k1":k}` on the unit chord from (0,0) to (1,0); other
//! fields are kept and echoed. Output (a contract: extend it, do not rename it):
//!
//! ```text
//! {"line": n, "input": {…}, "methods": {"chord": {"alpha": [a0, a1], "points": [[x, y], …],
//!   "kappa": [k0, k1], "curvature_variation": v[, "overshoots_chord": true]},
//!   "dbhs": {"solutions": [{…}, …], "chosen": i | null, "fallback": bool, "alpha": …, …},
//!   "optimized": {…, "report": {solver report}}}}
//! ```
//!
//! A line that cannot be read gets `{"line": n, "input": …, "error": "…"}`.

use serde_json::{json, Map, Value};

use crate::{CurveChoice, CurveMethod, UnitProblem};
use nalgebra::Vector2;

/// One input line that was read successfully.
pub struct LineAnswer {
    /// 1-based line number.
    pub line: usize,
    /// The line as read (all its fields).
    pub input: Value,
    /// The problem it states.
    pub problem: UnitProblem,
    /// Each construction's name, whether it enumerates solutions, and its choice.
    pub choices: Vec<(&'static str, bool, CurveChoice)>,
}

/// Parses one line; on failure returns what can be echoed as the input and the message.
pub fn parse_line(raw: &str) -> Result<(Value, UnitProblem), (Value, String)> {
    let value: Value = serde_json::from_str(raw)
        .map_err(|e| (Value::String(raw.to_string()), format!("bad JSON: {e}")))?;
    let problem = problem_from(&value).map_err(|e| (value.clone(), e))?;
    Ok((value, problem))
}

/// The problem a parsed line states, or the message naming what is wrong.
pub fn problem_from(v: &Value) -> Result<UnitProblem, String> {
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

/// Answers line `line` (its bytes, without the newline): `None` for a blank line, the answer,
/// or the error message with the error record to write in its place.
pub fn answer_line(
    line: usize,
    bytes: &[u8],
    methods: &[Box<dyn CurveMethod>],
) -> Option<Result<LineAnswer, (String, Value)>> {
    let bytes = bytes.strip_suffix(b"\r").unwrap_or(bytes);
    let parsed = match std::str::from_utf8(bytes) {
        Ok(raw) if raw.trim().is_empty() => return None,
        Ok(raw) => parse_line(raw),
        Err(e) => Err((
            Value::String(String::from_utf8_lossy(bytes).into_owned()),
            format!("not UTF-8: {e}"),
        )),
    };
    Some(match parsed {
        Ok((input, problem)) => Ok(LineAnswer {
            line,
            input,
            choices: methods
                .iter()
                .map(|m| (m.name(), m.enumerates_solutions(), m.construct(&problem)))
                .collect(),
            problem,
        }),
        Err((input, error)) => {
            let mut m = Map::new();
            m.insert("line".into(), json!(line));
            m.insert("input".into(), input);
            m.insert("error".into(), json!(error));
            Err((error, Value::Object(m)))
        }
    })
}

/// `{"alpha", "points", "kappa", "curvature_variation"}` of the unit curve for `alpha`.
pub fn curve_json(problem: &UnitProblem, alpha: [f64; 2]) -> Map<String, Value> {
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
pub fn json_number(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

/// The answer record of a line.
pub fn answer_json(a: &LineAnswer) -> Value {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{method_by_name, MethodOptions};

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
        let a = LineAnswer {
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

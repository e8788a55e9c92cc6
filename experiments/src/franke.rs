//! `experiments -- franke`: the functional schemes (`clough-tocher` with the classical and the
//! least-squares cubic cross-boundary rule, `--ct-cubic 0` and `1`, and `powell-sabin`, on
//! height fields: `surface::scheme::functional`) on Franke's six test functions, at Franke's two
//! samplings (the 33 × 33 grid and 100 scattered points with their Delaunay triangulation,
//! `mesh::datasets`), with exact gradients and with gradients from the normals an estimator
//! finds from the positions alone (`--estimate`, default the workbench's default estimator):
//! the largest and RMS error `|s(x, y) − F(x, y)|` over the `G × G` evaluation grid of
//! `[0, 1]²` (`--grid`, default 101, Franke's error grid), and the largest gradient error.
//! Writes `report.json` and `report.md` to `--output` (default `results/franke`).
//!
//! On the default 101 × 101 grid the table has scipy's `CloughTocher2DInterpolator` beside
//! them (golden numbers of `scripts/golden_franke.py`, scipy 1.17.1, on the same points, checked
//! by their coordinate sums; its own gradient estimate and Qhull's triangulation, which on the
//! grid may choose other diagonals).
//!
//! The scattered sampling's Delaunay triangulation has slivers along the square's sides (a
//! boundary triangle whose third point lies close to the side): there the cross-boundary
//! derivative comes from tangent planes extrapolated over the sliver's small width, and the
//! gradient error is large (measured: `powell-sabin` `|∇ error|` up to 4e2 on F1 at the side
//! `x = 0`, whose incentre-based split puts the inner net points at the inradius from the side;
//! `clough-tocher` 1.8), while the value errors of the two schemes stay alike.
//!
//! The scattered points are the workbench's seeded set (`mesh::datasets::FRANKE_SEED`), not
//! Franke's own 100 points (not available here): the scattered figures are comparable in
//! kind, not digit for digit, with the literature's.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use nalgebra::Vector2;
use serde_json::json;
use surface::scheme::functional::{self, graph::Graph, HeightFieldMode};

use crate::error::ExperimentError;
use crate::output::{write_result, Staged};

/// Options of the `franke` study.
#[derive(clap::Args, Debug)]
pub struct FrankeArgs {
    /// Output directory.
    #[arg(short = 'o', long, default_value = "results/franke")]
    output: PathBuf,
    /// Points a side of the evaluation grid on [0, 1]².
    #[arg(long, default_value_t = 101, value_parser = clap::value_parser!(u64).range(2..=2001))]
    grid: u64,
    /// The estimator of the "estimated" gradients (normals from the positions alone).
    #[arg(long, default_value = estimate::DEFAULT_ESTIMATOR, value_parser = fitjob::cli::estimator_names())]
    estimate: String,
}

/// scipy's Clough–Tocher interpolant on the same points, from `scripts/golden_franke.py`
/// (scipy 1.17.1 pinned in `scripts/requirements-franke.txt`): its own gradients (a global
/// curvature-minimizing estimate) and its own (Qhull) Delaunay triangulation.
const SCIPY_GOLDEN: &str = include_str!("../../data/golden/franke-scipy.json");

/// The scattered points' coordinate sums must match the golden file's to rounding: it was
/// made on the same points (the script regenerates them from the same SplitMix64).
const SAME_POINTS: f64 = 1e-9;

/// scipy's rows, checked to be of this study's scattered points.
fn scipy_rows() -> Result<Vec<Row>, ExperimentError> {
    let bad = |m: String| ExperimentError::Measure {
        subject: "data/golden/franke-scipy.json".into(),
        message: m,
    };
    let v: serde_json::Value =
        serde_json::from_str(SCIPY_GOLDEN).map_err(|e| bad(e.to_string()))?;
    let points = surface::dataset_by_name("franke1@scattered", None)?.mesh;
    let sum = points
        .vertices()
        .iter()
        .fold([0.0, 0.0], |s, v| [s[0] + v.data.p.x, s[1] + v.data.p.y]);
    let golden = [0, 1].map(|i| v["scattered_sum"][i].as_f64().unwrap_or(f64::NAN));
    if (0..2).any(|i| (golden[i] - sum[i]).abs() > SAME_POINTS) {
        return Err(bad(format!(
            "made on other scattered points (coordinate sums {golden:?}, these {sum:?}): run scripts/golden_franke.py again"
        )));
    }
    let version = v["scipy"].as_str().unwrap_or("?").to_string();
    let rows = v["rows"].as_array().cloned().unwrap_or_default();
    rows.iter()
        .map(|r| {
            let num = |k: &str| r[k].as_f64().ok_or_else(|| bad(format!("row without {k}")));
            Ok(Row {
                function: num("function")? as usize,
                sampling: if r["sampling"].as_str() == Some("grid 33 × 33") {
                    "grid 33 × 33"
                } else {
                    "scattered 100"
                },
                gradients: format!("estimated (scipy {version}, global)"),
                scheme: "scipy CloughTocher2DInterpolator",
                max: num("max_error")?,
                rms: num("rms_error")?,
                gradient_max: f64::NAN,
                outside: num("points_outside")? as usize,
            })
        })
        .collect()
}

/// The schemes compared: name, label, `clough-tocher`'s cubic weight (`--ct-cubic`).
const SCHEMES: [(&str, &str, f64); 3] = [
    ("clough-tocher", "clough-tocher", 0.0),
    ("clough-tocher", "clough-tocher --ct-cubic 1", 1.0),
    ("powell-sabin", "powell-sabin", 0.0),
];

/// One measured fit.
#[derive(Clone)]
struct Row {
    function: usize,
    sampling: &'static str,
    gradients: String,
    scheme: &'static str,
    max: f64,
    rms: f64,
    gradient_max: f64,
    outside: usize,
}

/// Runs the study.
pub fn run(args: &FrankeArgs) -> Result<ExitCode, ExperimentError> {
    let est = estimate::estimator_by_name(&args.estimate)
        .map_err(|e| ExperimentError::Usage(format!("--estimate {}: {e}", args.estimate)))?;
    let method = curves::method_by_name("chord", &curves::MethodOptions::default())?;
    let g = args.grid as usize;
    let mut rows = Vec::new();
    for k in 1..=6 {
        let f = mesh::analytic_franke::Franke::by_number(k)
            .ok_or_else(|| ExperimentError::Usage(format!("no Franke function {k}")))?;
        for (sampling, suffix) in [("grid 33 × 33", ""), ("scattered 100", "@scattered")] {
            let name = format!("franke{k}{suffix}");
            let exact = surface::dataset_by_name(&name, None)?.mesh;
            let mut estimated = exact.clone();
            estimate::apply(&mut estimated, est, false);
            for (gradients, mesh) in [
                ("exact".to_string(), &exact),
                (format!("estimated ({})", est.name()), &estimated),
            ] {
                for (scheme_name, scheme, w) in SCHEMES {
                    let options = surface::SchemeOptions::default()
                        .with(&surface::scheme::clough_tocher::CUBIC_WEIGHT, w);
                    let s = surface::scheme_by_name(scheme_name, &options)?;
                    let subject = format!("{name} {scheme} {gradients}");
                    let (s, _) = functional::choose(s, mesh, HeightFieldMode::On).map_err(|e| {
                        ExperimentError::Measure {
                            subject: subject.clone(),
                            message: e.to_string(),
                        }
                    })?;
                    let fit = surface::fit_scheme(mesh, s.as_ref(), method.as_ref()).map_err(
                        |source| ExperimentError::Fit {
                            subject: subject.clone(),
                            source,
                        },
                    )?;
                    let graph = Graph::new(mesh, &fit);
                    let (mut max, mut sum, mut count, mut gmax, mut outside) =
                        (0.0f64, 0.0, 0usize, 0.0f64, 0usize);
                    for j in 0..g {
                        for i in 0..g {
                            let q = Vector2::new(i as f64, j as f64) / (g - 1) as f64;
                            let Some((z, grad)) = graph.at(&q) else {
                                outside += 1;
                                continue;
                            };
                            let jet = f.jet(q.x, q.y);
                            let e = (z - jet.f).abs();
                            max = max.max(e);
                            sum += e * e;
                            count += 1;
                            gmax = gmax.max((grad - jet.grad).norm());
                        }
                    }
                    rows.push(Row {
                        function: k,
                        sampling,
                        gradients: gradients.clone(),
                        scheme,
                        max,
                        rms: (sum / count.max(1) as f64).sqrt(),
                        gradient_max: gmax,
                        outside,
                    });
                }
            }
        }
    }
    if g == 101 {
        // The golden numbers are on the 101 × 101 grid.
        let scipy = scipy_rows()?;
        let at = |r: &Row| (r.function, r.sampling);
        let mut merged = Vec::with_capacity(rows.len() + scipy.len());
        for r in rows {
            let next = merged.last().map(at);
            if next.is_some_and(|n| n != at(&r)) {
                let done = next.unwrap_or_default();
                merged.extend(scipy.iter().filter(|s| at(s) == done).map(Row::clone));
            }
            merged.push(r);
        }
        let last = merged.last().map(at).unwrap_or_default();
        merged.extend(scipy.iter().filter(|s| at(s) == last).map(Row::clone));
        rows = merged;
    }
    let staged = Staged::begin(&args.output)?;
    let out = staged.path().to_path_buf();
    let report = json!({
        "study": "franke",
        "evaluation_grid": g,
        "estimator": est.name(),
        "scattered_seed": mesh::datasets::FRANKE_SEED,
        "rows": rows.iter().map(|r| json!({
            "function": r.function,
            "sampling": r.sampling,
            "gradients": r.gradients,
            "scheme": r.scheme,
            "max_error": r.max,
            "rms_error": r.rms,
            "max_gradient_error": r.gradient_max.is_finite().then_some(r.gradient_max),
            "points_outside": r.outside,
        })).collect::<Vec<_>>(),
    });
    let text = crate::output::pretty_json(&report, "the franke report")?;
    write_result(Some(&out.join("report.json")), text.as_bytes())?;
    let mut md = String::new();
    let _ = writeln!(md, "# Franke's test functions: the functional C1 schemes\n");
    let _ = writeln!(
        md,
        "Error |s − F| over the {g} × {g} grid of [0, 1]²; gradients exact or estimated by `{}` from the positions. Scattered: the workbench's 100 seeded points (seed {:#x}), not Franke's own set.\n",
        est.name(),
        mesh::datasets::FRANKE_SEED
    );
    let _ = writeln!(
        md,
        "| F | sampling | gradients | scheme | max | RMS | max ‖∇ error‖ |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|");
    for r in &rows {
        let _ = writeln!(
            md,
            "| F{} | {} | {} | {} | {:.3e} | {:.3e} | {} |",
            r.function,
            r.sampling,
            r.gradients,
            r.scheme,
            r.max,
            r.rms,
            if r.gradient_max.is_finite() {
                format!("{:.3e}", r.gradient_max)
            } else {
                "—".into()
            }
        );
    }
    write_result(Some(&out.join("report.md")), md.as_bytes())?;
    say!("franke: written to {}", args.output.display());
    staged.commit()?;
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    /// The committed golden numbers are of this workbench's scattered points, all twelve rows.
    #[test]
    fn the_scipy_golden_numbers_are_of_these_points() {
        let rows = super::scipy_rows().expect("golden");
        assert_eq!(rows.len(), 12);
        assert!(rows
            .iter()
            .all(|r| r.max > 0.0 && r.rms > 0.0 && r.rms <= r.max));
    }
}

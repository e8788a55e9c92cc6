//! The sweep's curvature plots (the design card's "plots the resulting curvature"): for every
//! data set of a whole run, K and H along its paths (`experiments::sweep_tasks::paths`: the
//! ring's outer equator and a meridian, the sphere's and the capsule's meridian), every task's
//! fitted surface against the true one, written as `curvature-<data>.png`/`.svg` with
//! `curvature.md` listing them. Mesh files have no true surface and no paths; `merge` draws
//! none (its lines hold no surfaces: run the whole grid for the plots).

use std::fmt::Write as _;
use std::path::Path;

use experiments::sweep_tasks::grid::Task;
use experiments::sweep_tasks::paths::{paths_of, sample, PathSamples, BINS, MAX_OFFSET};
use experiments::sweep_tasks::TaskSurface;
use render::{LineChart, Series};

use crate::error::ExperimentError;
use crate::output::write_result;

/// Most tasks drawn in one figure: beyond a dozen series a legend is not read (the rest are
/// named in `curvature.md` as left out).
pub const MAX_SERIES: usize = 12;

/// Which column of a task's samples a chart draws.
type Column = fn(&PathSamples) -> &Vec<f64>;

/// One task's samples along its data set's paths.
pub struct TaskPaths {
    /// The task's id.
    id: String,
    /// Its data set and resolution, the figure it goes in (`ring`, `sphere@3`).
    group: String,
    /// Per path: its name, abscissa label and samples.
    paths: Vec<(&'static str, &'static str, PathSamples)>,
}

/// The samples of task `t` on its surface; `None` for a task without paths (a mesh file, the
/// octahedron).
pub fn task_paths(t: &Task, surface: &TaskSurface) -> Option<TaskPaths> {
    let paths = paths_of(&t.data);
    if t.file || paths.is_empty() {
        return None;
    }
    let truth = surface.truth.as_deref();
    Some(TaskPaths {
        id: t.id.clone(),
        group: match t.resolution {
            Some(r) => format!("{}@{r}", t.data),
            None => t.data.clone(),
        },
        paths: paths
            .iter()
            .map(|p| (p.name, p.x_label, sample(&surface.tessellation, truth, p)))
            .collect(),
    })
}

/// The points of `(x, y)` columns, non-finite ones dropped, `y` clamped to `window`.
fn points(x: &[f64], y: &[f64], window: (f64, f64)) -> Vec<(f64, f64)> {
    x.iter()
        .zip(y)
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(a, b)| (*a, b.clamp(window.0, window.1)))
        .collect()
}

/// The y window of a chart: the true values' range widened by [`WINDOW_MARGIN`] of its span
/// (at least 1) on each side. A lump of a few thousand (dBHS on the ring) would otherwise
/// flatten every other series; values beyond are drawn at the edge and the title says so.
fn window(truth: &[f64]) -> (f64, f64) {
    let (lo, hi) = truth
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    if !lo.is_finite() {
        return (f64::NEG_INFINITY, f64::INFINITY);
    }
    let span = (hi - lo).max(1.0);
    (lo - WINDOW_MARGIN * span, hi + WINDOW_MARGIN * span)
}

/// How far beyond the true range a chart's y axis reaches, in spans of that range.
const WINDOW_MARGIN: f64 = 1.0;

/// Writes the figures and `curvature.md` into `out`; nothing when no task has paths.
pub fn write(out: &Path, tasks: &[TaskPaths]) -> Result<(), ExperimentError> {
    if tasks.is_empty() {
        return Ok(());
    }
    let mut groups: Vec<&str> = tasks.iter().map(|t| t.group.as_str()).collect();
    groups.dedup();
    let mut md = String::from("# Sweep: curvature along paths\n\n");
    let _ = writeln!(
        md,
        "Written with `report.md` by a whole `sweep` run. K and H (H > 0 on a sphere with outward normals) of each task's tessellation along curves of its data set's surface (the ring's outer equator and its meridian u = 0, the sphere's and the capsule's meridian y = 0) against the true surface at the same points (the first series). Each chart's y axis spans the true range widened by its span on either side; samples beyond are drawn at the edge and counted in the chart's title. A sample is the tessellation vertex nearest the curve's plane in each of {BINS} bins of the abscissa, within {MAX_OFFSET} of the plane.\n"
    );
    for group in groups {
        let mine: Vec<&TaskPaths> = tasks.iter().filter(|t| t.group == group).collect();
        let shown = &mine[..mine.len().min(MAX_SERIES)];
        let mut charts = Vec::new();
        for (k, (name, x_label, first)) in mine[0].paths.iter().enumerate() {
            let columns: [(&str, &Vec<f64>, Column); 2] = [
                ("K", &first.k_true, |s| &s.k),
                ("H", &first.h_true, |s| &s.h),
            ];
            for (quantity, truth, of) in columns {
                let w = window(truth);
                let mut clipped = 0usize;
                let mut series = vec![Series {
                    label: "true surface".into(),
                    points: points(&first.x, truth, w),
                }];
                let prefix = format!("{}/", group.split('@').next().unwrap_or(group));
                for t in shown {
                    let s = &t.paths[k].2;
                    clipped += of(s).iter().filter(|v| **v < w.0 || **v > w.1).count();
                    series.push(Series {
                        label: t.id.strip_prefix(&prefix).unwrap_or(&t.id).to_string(),
                        points: points(&s.x, of(s), w),
                    });
                }
                let note = if clipped > 0 {
                    format!(
                        " ({clipped} samples beyond [{:.2}, {:.2}] drawn at its edge)",
                        w.0, w.1
                    )
                } else {
                    String::new()
                };
                charts.push(LineChart {
                    title: format!("{quantity} along the {name}{note}"),
                    x_label: (*x_label).into(),
                    y_label: quantity.into(),
                    series,
                    log_y: false,
                });
            }
        }
        let stem = format!("curvature-{}", group.replace('@', "-"));
        render::write_line_charts(
            &charts,
            2,
            &format!("{group}: curvature along paths, every task against the true surface"),
            &out.join(format!("{stem}.png")),
            &out.join(format!("{stem}.svg")),
        )?;
        let _ = writeln!(md, "## {group}\n\n![{group}]({stem}.png)\n");
        if mine.len() > shown.len() {
            let left: Vec<&str> = mine[shown.len()..].iter().map(|t| t.id.as_str()).collect();
            let _ = writeln!(
                md,
                "Left out of the figure (more than {MAX_SERIES} tasks): {}.\n",
                left.join(", ")
            );
        }
    }
    write_result(Some(&out.join("curvature.md")), md.as_bytes())?;
    Ok(())
}

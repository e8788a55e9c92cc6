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

/// Series per figure besides the truth: the chart palette's six colours (Okabe–Ito) less the
/// truth's, so no two series of a figure share a colour; more rows go to further figures.
pub const SERIES_PER_FIGURE: usize = 5;

/// Most figures per data set: 40 tasks drawn; the rest are named in the report as left out.
pub const MAX_FIGURES: usize = 8;

/// Most rows drawn for one data set.
pub const MAX_SERIES: usize = SERIES_PER_FIGURE * MAX_FIGURES;

/// Which column of a task's samples a chart draws.
type Column = fn(&PathSamples) -> &Vec<f64>;

/// One task's samples along its data set's paths.
pub struct TaskPaths {
    /// The task's id.
    id: String,
    /// Its data set and resolution, the figure it goes in (`ring`, `sphere@3`).
    group: String,
    /// Per path: its name, abscissa label and samples.
    paths: Vec<Sampled>,
}

/// The samples of task `t` on its surface; `None` for a task without paths (a mesh file, the
/// octahedron).
pub fn task_paths(t: &Task, surface: &TaskSurface) -> Option<TaskPaths> {
    if t.file || paths_of(&t.data).is_empty() {
        return None;
    }
    Some(TaskPaths {
        id: t.id.clone(),
        group: match t.resolution {
            Some(r) => format!("{}@{r}", t.data),
            None => t.data.clone(),
        },
        paths: sample_paths(&t.data, &surface.tessellation, surface.truth.as_deref()),
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

/// Writes the figures and `curvature.md` into `out`, with the run's interactive `page` and its
/// `(data set, file)` picture composites named; nothing when there is nothing to show.
pub fn write(
    out: &Path,
    tasks: &[TaskPaths],
    page: Option<&str>,
    composites: &[super::pictures::Composite],
) -> Result<(), ExperimentError> {
    if tasks.is_empty() && composites.is_empty() {
        return Ok(());
    }
    let mut groups: Vec<&str> = tasks.iter().map(|t| t.group.as_str()).collect();
    groups.dedup();
    let mut md = String::from("# Sweep: the surfaces and their curvature\n\n");
    md.push_str("Written with `report.md` by a whole `sweep` run.\n\n");
    if !composites.is_empty() {
        let _ = writeln!(
            md,
            "## The surfaces\n\n{}\n",
            super::pictures::description()
        );
        for c in composites {
            let _ = writeln!(
                md,
                "### {}\n\n![{}: every task]({})\n",
                c.group, c.group, c.file
            );
            if !c.left_out.is_empty() {
                let _ = writeln!(
                    md,
                    "Left out of the composite (more than {} tasks): {}.\n",
                    super::pictures::MAX_COLUMNS,
                    c.left_out.join(", ")
                );
            }
        }
    }
    if let Some(p) = page {
        let _ = writeln!(
            md,
            "Interactive: [{p}]({p}) (works offline): the tasks on that data set side by side with linked cameras; shaded, K, H, κ1, κ2, reflection lines, isophotes, distance to the true surface.\n"
        );
    }
    if !tasks.is_empty() {
        let _ = writeln!(md, "## Curvature along paths\n\n{}\n", description());
    }
    for group in groups {
        let mine: Vec<&TaskPaths> = tasks.iter().filter(|t| t.group == group).collect();
        let prefix = format!("{}/", group.split('@').next().unwrap_or(group));
        let rows: Vec<(String, &[Sampled])> = mine
            .iter()
            .map(|t| {
                let label = t.id.strip_prefix(&prefix).unwrap_or(&t.id).to_string();
                (label, t.paths.as_slice())
            })
            .collect();
        let stem = format!("curvature-{}", group.replace('@', "-"));
        let stems = figure(
            out,
            &stem,
            &format!("{group}: curvature along paths, every task against the true surface"),
            &rows,
        )?;
        let _ = writeln!(md, "### {group}\n");
        for s in stems {
            let _ = writeln!(md, "![{group}]({s}.png)\n");
        }
        if mine.len() > MAX_SERIES {
            let left: Vec<&str> = mine[MAX_SERIES..].iter().map(|t| t.id.as_str()).collect();
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

/// What the figures show, for the reports that include them.
pub fn description() -> String {
    format!("K and H (H > 0 on a sphere with outward normals) of each tessellation along curves of its data set's surface (the ring's outer equator and its meridian u = 0, the sphere's and the capsule's meridian y = 0) against the true surface at the same points (the first series). A sample is the tessellation vertex nearest the curve's plane in each of {BINS} bins of the abscissa, within {MAX_OFFSET} of the plane. Each chart's y axis spans the true range widened by its span on either side; samples beyond are drawn at the edge and counted in the chart's title (\"clipped\"). A figure draws at most five series besides the truth, so that no two share a colour.")
}

/// One path's name, abscissa label and samples.
pub type Sampled = (&'static str, &'static str, PathSamples);

/// The samples of `tess` along the paths of data set `data` (empty for one without paths).
pub fn sample_paths(
    data: &str,
    tess: &surface::Tessellation,
    truth: Option<&dyn surface::AnalyticSurface>,
) -> Vec<Sampled> {
    paths_of(data)
        .iter()
        .map(|p| (p.name, p.x_label, sample(tess, truth, p)))
        .collect()
}

/// The figures of `rows` in `out`: per path a K and an H chart, the truth (from the first row)
/// then each row as a series, [`SERIES_PER_FIGURE`] rows a figure (`stem.png`, or `stem-1.png`,
/// `stem-2.png`, … when there are more), at most [`MAX_FIGURES`]. Returns the stems written.
pub fn figure(
    out: &Path,
    stem: &str,
    title: &str,
    rows: &[(String, &[Sampled])],
) -> Result<Vec<String>, ExperimentError> {
    let Some((_, first_paths)) = rows.first() else {
        return Ok(Vec::new());
    };
    let chunks: Vec<&[(String, &[Sampled])]> =
        rows.chunks(SERIES_PER_FIGURE).take(MAX_FIGURES).collect();
    let mut stems = Vec::new();
    for (c, shown) in chunks.iter().enumerate() {
        let name_of = if chunks.len() == 1 {
            stem.to_string()
        } else {
            format!("{stem}-{}", c + 1)
        };
        let mut charts = Vec::new();
        for (k, (name, x_label, first)) in first_paths.iter().enumerate() {
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
                for (label, paths) in shown.iter() {
                    let Some((_, _, s)) = paths.get(k) else {
                        continue;
                    };
                    clipped += of(s).iter().filter(|v| **v < w.0 || **v > w.1).count();
                    series.push(Series {
                        label: label.clone(),
                        points: points(&s.x, of(s), w),
                    });
                }
                let note = if clipped > 0 {
                    format!(" ({clipped} clipped)")
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
        let part = if chunks.len() > 1 {
            format!(" ({} of {})", c + 1, chunks.len())
        } else {
            String::new()
        };
        render::write_line_charts(
            &charts,
            2,
            &format!("{title}{part}"),
            &out.join(format!("{name_of}.png")),
            &out.join(format!("{name_of}.svg")),
        )?;
        stems.push(name_of);
    }
    Ok(stems)
}

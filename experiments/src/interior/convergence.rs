//! The seed's open question answered with numbers: curvature data in the cross-boundary field
//! (`shirman-sequin-curvature`, `surface::curvature_cross`) against the Shirman–Séquin
//! defaults, Nielson and Loop, at doubling resolutions of the ring (the torus), the sphere and
//! the capsule: errors against the true surface and their convergence orders; and Section 4's
//! corner objectives, which β and c cannot move (the first part of the study), with the
//! curvature data in the construction.

use std::fmt::Write as _;

use curves::CurveMethod;
use experiments::error::ExperimentError;
use experiments::study::StudyError;
use experiments::sweep_tasks::grid::{axes_from_json, Grid};
use render::{LineChart, Series};
use serde_json::{json, Value};
use surface::interior::corner_measures;
use surface::{InteriorParameters, SurfaceErrors as Errors};

/// The data sets and their resolutions, each step halving the edge length: the ring's steps
/// around the axis (tube `nu/2`), the sphere's subdivision levels, the capsule's meridians.
pub const SERIES: [(&str, [usize; 4]); 3] = [
    ("ring", [16, 32, 64, 128]),
    ("sphere", [1, 2, 3, 4]),
    ("capsule", [16, 32, 64, 128]),
];

/// The schemes and curve constructions compared (`None`: a subdivision scheme, at the limit of
/// the sweep's three levels).
pub const CONTENDERS: [(&str, Option<&str>); 8] = [
    ("shirman-sequin", Some("optimized")),
    ("shirman-sequin", Some("dbhs")),
    ("shirman-sequin-curvature", Some("optimized")),
    ("shirman-sequin-curvature", Some("dbhs")),
    ("shirman-sequin-curvature", Some("dbhs-guarded")),
    ("nielson", Some("optimized")),
    ("nielson", Some("dbhs")),
    ("loop", None),
];

/// The contenders drawn in the K RMS charts: five, so that no two share a colour (the tables
/// have all of them).
const CHARTED: [(&str, Option<&str>); 5] = [
    ("shirman-sequin", Some("optimized")),
    ("shirman-sequin-curvature", Some("dbhs")),
    ("shirman-sequin-curvature", Some("dbhs-guarded")),
    ("nielson", Some("optimized")),
    ("loop", None),
];

/// One measured fit.
pub struct Row {
    /// Data set.
    pub data: &'static str,
    /// Its resolution.
    pub resolution: usize,
    /// Faces of the data mesh.
    pub faces: usize,
    /// Scheme name.
    pub scheme: &'static str,
    /// Curve construction (`None` for subdivision).
    pub curves: Option<&'static str>,
    /// Errors against the true surface.
    pub errors: Errors,
    /// G1 defect (radians; `None` for subdivision).
    pub g1: Option<f64>,
}

impl Row {
    fn label(&self) -> String {
        match self.curves {
            Some(c) => format!("{}/{c}", self.scheme),
            None => self.scheme.to_string(),
        }
    }
}

/// Every task of the sweep grid `axes` (a JSON object of a grid file's keys), in task order:
/// its record (identity, `faces`, `g1_defect_radians`: the line a `sweep` over the same grid
/// writes) and its errors against the true surface, read back from the record.
fn run_grid(axes: &Value) -> Result<Vec<(Value, Errors)>, ExperimentError> {
    let parsed = axes_from_json(axes).map_err(|message| StudyError::JsonGrid { message })?;
    let grid = Grid::new(parsed)?;
    let tasks = grid.tasks()?;
    let mut out = Vec::with_capacity(tasks.len());
    for task in &tasks {
        let v = experiments::sweep_tasks::run_grid_task(task, &grid)?;
        let errors = serde_json::from_value::<Errors>(v["errors"].clone()).map_err(|e| {
            ExperimentError::Measure {
                subject: task.id.clone(),
                message: format!("no errors against the true surface: {e}"),
            }
        })?;
        out.push((v, errors));
    }
    Ok(out)
}

/// The grid axes of one contender on `data` at `resolutions` (none: the default), one solver
/// (exact penalty) where the construction takes one, so that a task is one resolution.
fn contender_axes(data: &str, resolutions: &[usize], scheme: &str, curves: Option<&str>) -> Value {
    let mut axes = json!({"data": [data], "scheme": [scheme]});
    if !resolutions.is_empty() {
        axes["resolution"] = json!(resolutions);
    }
    if let Some(c) = curves {
        axes["curves"] = json!([c]);
        if curves::takes_solver(c) {
            axes["solver"] = json!(["exact-penalty"]);
        }
    }
    axes
}

/// Every data set × resolution × contender, through the sweep's task runner.
pub fn measure() -> Result<Vec<Row>, ExperimentError> {
    let mut rows = Vec::new();
    for (data, resolutions) in SERIES {
        for (scheme, curves) in CONTENDERS {
            let axes = contender_axes(data, &resolutions, scheme, curves);
            for (v, errors) in run_grid(&axes)? {
                rows.push(Row {
                    data,
                    resolution: v["resolution"].as_u64().unwrap_or(0) as usize,
                    faces: v["faces"].as_u64().unwrap_or(0) as usize,
                    scheme,
                    curves,
                    errors,
                    g1: v["g1_defect_radians"].as_f64(),
                });
            }
        }
    }
    Ok(rows)
}

/// The one setting the verdict measures: the curvature variant on `dbhs-guarded` curves.
pub const SETTING: (&str, &str) = ("shirman-sequin-curvature", "dbhs-guarded");

/// The Shirman–Séquin defaults it is held against: the fit's default curves and the seeds'
/// best.
pub const DEFAULTS: [(&str, &str); 2] =
    [("shirman-sequin", "chord"), ("shirman-sequin", "optimized")];

/// The verdict at each data set's default resolution: [`SETTING`] against [`DEFAULTS`] on
/// position, normal, K and H RMS at once, and its K RMS against every registered scheme's on
/// optimized curves (the `schemes` study's setting). Markdown and JSON records.
pub fn verdict() -> Result<(String, Vec<Value>), ExperimentError> {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "| data set | setting | position RMS | normal RMS (°) | K RMS | H RMS |"
    );
    let _ = writeln!(md, "|---|---|---:|---:|---:|---:|");
    let mut notes = String::new();
    let mut records = Vec::new();
    for data in ["ring", "sphere", "capsule", "octa"] {
        let one = |scheme: &str, curves: &str| -> Result<Errors, ExperimentError> {
            let rows = run_grid(&contender_axes(data, &[], scheme, Some(curves)))?;
            rows.into_iter()
                .next()
                .map(|r| r.1)
                .ok_or_else(|| ExperimentError::Measure {
                    subject: format!("{data}/{scheme}/{curves}"),
                    message: "no task".into(),
                })
        };
        let ours = one(SETTING.0, SETTING.1)?;
        let mut beats_all = true;
        let mut lines = vec![(format!("{}/{}", SETTING.0, SETTING.1), ours)];
        for (scheme, curves) in DEFAULTS {
            let e = one(scheme, curves)?;
            beats_all &= ours.position_rms < e.position_rms
                && ours.normal_rms_degrees < e.normal_rms_degrees
                && ours.gaussian_rms < e.gaussian_rms
                && ours.mean_rms < e.mean_rms;
            lines.push((format!("{scheme}/{curves}"), e));
        }
        for (label, e) in &lines {
            let _ = writeln!(
                md,
                "| {data} | {label} | {:.3e} | {:.3e} | {:.3e} | {:.3e} |",
                e.position_rms, e.normal_rms_degrees, e.gaussian_rms, e.mean_rms
            );
        }
        // Every registered scheme on optimized curves (those that make their own boundaries
        // ignore the curves).
        let all = run_grid(&json!({"data": [data], "scheme": surface::scheme_names(),
            "curves": ["optimized"], "solver": ["exact-penalty"]}))?;
        let best = all
            .iter()
            .min_by(|a, b| a.1.gaussian_rms.total_cmp(&b.1.gaussian_rms))
            .map(|(v, e)| {
                (
                    v["scheme"].as_str().unwrap_or("?").to_string(),
                    e.gaussian_rms,
                )
            });
        let best_k = best.as_ref().map_or(f64::NAN, |b| b.1);
        let is_best = ours.gaussian_rms <= best_k;
        let _ = writeln!(
            notes,
            "- {data}: beats both defaults on all four measures: **{}**; K RMS {:.3e} against the best registered scheme on optimized curves, {} ({best_k:.3e}): **{}**",
            if beats_all { "yes" } else { "no" },
            ours.gaussian_rms,
            best.as_ref().map_or("—", |b| b.0.as_str()),
            if is_best { "best" } else { "not best" }
        );
        records.push(json!({"dataset": data, "beats_defaults_on_every_measure": beats_all,
            "k_rms": ours.gaussian_rms, "best_registered_on_optimized": best.as_ref().map(|b| b.0.clone()),
            "best_registered_k_rms": best_k, "best_k_rms": is_best,
            "rows": lines.iter().map(|(l, e)| json!({"setting": l, "position_rms": e.position_rms,
                "normal_rms_degrees": e.normal_rms_degrees, "gaussian_rms": e.gaussian_rms, "mean_rms": e.mean_rms})).collect::<Vec<_>>()}));
    }
    md.push('\n');
    md.push_str(&notes);
    Ok((md, records))
}

/// `log₂(previous / this)`: the convergence order of an error when the edge length halves;
/// `None` for the first resolution or an error that is not positive.
fn order(previous: Option<f64>, this: f64) -> Option<f64> {
    let p = previous?;
    (p > 0.0 && this > 0.0).then(|| (p / this).log2())
}

fn cell(x: f64, o: Option<f64>) -> String {
    match o {
        Some(o) => format!("{x:.3e} ({o:.2})"),
        None => format!("{x:.3e}"),
    }
}

/// The convergence tables (markdown), the JSON records and a K RMS chart per data set.
pub fn report(rows: &[Row]) -> (String, Vec<Value>, Vec<LineChart>) {
    let mut md = String::new();
    let mut records = Vec::new();
    let mut charts = Vec::new();
    for (data, _) in SERIES {
        let _ = writeln!(md, "\n### {data}\n");
        let _ = writeln!(md, "| scheme / curves | resolution | faces | position RMS | normal RMS (°) | K RMS | H RMS | G1 (rad) |");
        let _ = writeln!(md, "|---|---:|---:|---:|---:|---:|---:|---:|");
        let mut series = Vec::new();
        for (scheme, curves) in CONTENDERS {
            let mut prev: Option<&Row> = None;
            let mut points = Vec::new();
            for r in rows
                .iter()
                .filter(|r| r.data == data && r.scheme == scheme && r.curves == curves)
            {
                let e = &r.errors;
                let o = |f: &dyn Fn(&Errors) -> f64| order(prev.map(|p| f(&p.errors)), f(e));
                let (op, on, ok, oh) = (
                    o(&|e| e.position_rms),
                    o(&|e| e.normal_rms_degrees),
                    o(&|e| e.gaussian_rms),
                    o(&|e| e.mean_rms),
                );
                let g1 = r.g1.map_or("—".to_string(), |g| format!("{g:.1e}"));
                let _ = writeln!(
                    md,
                    "| {} | {} | {} | {} | {} | {} | {} | {g1} |",
                    r.label(),
                    r.resolution,
                    r.faces,
                    cell(e.position_rms, op),
                    cell(e.normal_rms_degrees, on),
                    cell(e.gaussian_rms, ok),
                    cell(e.mean_rms, oh),
                );
                records.push(json!({
                    "dataset": data, "resolution": r.resolution, "faces": r.faces,
                    "scheme": scheme, "curves": curves,
                    "errors": {"position_rms": e.position_rms, "normal_rms_degrees": e.normal_rms_degrees, "gaussian_rms": e.gaussian_rms, "mean_rms": e.mean_rms},
                    "g1_defect_radians": r.g1,
                    "orders": {"position_rms": op, "normal_rms": on, "gaussian_rms": ok, "mean_rms": oh},
                }));
                points.push(((r.faces as f64).log2() / 2.0, e.gaussian_rms));
                prev = Some(r);
            }
            if !CHARTED.contains(&(scheme, curves)) {
                continue;
            }
            series.push(Series {
                label: match curves {
                    Some(c) => format!("{scheme}/{c}"),
                    None => scheme.to_string(),
                },
                points,
            });
        }
        charts.push(LineChart {
            title: format!("{data}: K RMS against the true surface"),
            x_label: "log₂ √faces (one step: edges halved)".into(),
            y_label: "K RMS".into(),
            series,
            log_y: true,
        });
    }
    (md, records, charts)
}

/// Section 4's objectives (Σ of squared corner-measure errors over every corner, as the first
/// part of the study sums them) of the defaults' nets and of the curvature variant's, on the
/// claim's data sets at their default resolutions with `method`'s curves: `(curvature,
/// twist)` for each.
pub fn corner_objectives(
    mesh: &surface::Mesh,
    method: &dyn CurveMethod,
    subject: &str,
) -> Result<[(f64, f64); 2], ExperimentError> {
    let f = surface::fit(mesh, method, &|_| InteriorParameters::default()).map_err(|source| {
        ExperimentError::Fit {
            subject: subject.to_string(),
            source,
        }
    })?;
    let mut out = [(0.0, 0.0); 2];
    for (fi, face) in mesh.faces().iter().enumerate() {
        let v = face.map(|i| &mesh.vertices()[i].data);
        let curves = f
            .face_curves(mesh, fi)
            .map_err(|e| ExperimentError::Measure {
                subject: subject.to_string(),
                message: format!("face {fi}: {e}"),
            })?;
        let p = InteriorParameters::default();
        let built = [
            surface::macro_patch(v, &curves, &p),
            surface::curvature_cross::macro_patch_curvature(v, &curves, &p, [false; 3]),
        ];
        for (slot, nets) in out.iter_mut().zip(built) {
            // A face the construction refuses is a fallback face of the fit: not measured.
            let Ok(nets) = nets else { continue };
            for m in corner_measures(&nets, v) {
                slot.0 += (m.boundary_curvature - m.boundary_target).powi(2);
                slot.1 += (m.twist_start - m.twist_targets[0]).powi(2)
                    + (m.twist_end - m.twist_targets[1]).powi(2);
            }
        }
    }
    Ok(out)
}

/// Size of one picture of the K figure.
const TILE: (u32, u32) = (300, 230);

/// The view of the K figure (azimuth°, elevation°): the `schemes` study's.
const VIEW: (f64, f64) = (35.0, 35.0);

/// The ring resolutions of the K figure: the seeds' 16 × 8 and one step finer.
const PICTURED: [usize; 2] = [16, 32];

/// The K figure: on the ring at [`PICTURED`], the true surface's K at the samples, the default
/// (optimized curves), [`SETTING`] and Loop, one colour scale (the true surface's largest
/// |K|), written as `file` in `out`. Returns the figure's title.
pub fn kcolor_figure(out: &std::path::Path, file: &str) -> Result<String, ExperimentError> {
    use render::colors as colormap;
    use render::{
        render, write_composite, Camera, Legend, LegendKind, RenderMesh, RenderOptions, Tile,
    };
    let settings: [(&str, Option<&str>); 3] = [
        ("shirman-sequin", Some("optimized")),
        (SETTING.0, Some(SETTING.1)),
        ("loop", None),
    ];
    let mut tiles = Vec::new();
    let mut k_limit = 0.0f64;
    let mut rows = Vec::new();
    for nu in PICTURED {
        let mut row = Vec::new();
        for (scheme, curves) in settings {
            let axes = contender_axes("ring", &[nu], scheme, curves);
            let parsed =
                axes_from_json(&axes).map_err(|message| StudyError::JsonGrid { message })?;
            let grid = Grid::new(parsed)?;
            let tasks = grid.tasks()?;
            let Some(task) = tasks.first() else {
                return Err(ExperimentError::Measure {
                    subject: format!("ring@{nu}/{scheme}"),
                    message: "no task".into(),
                });
            };
            let (_, surface) = experiments::sweep_tasks::run_grid_task_keeping(task, &grid)?;
            let label = match curves {
                Some(c) => format!("{scheme}/{c}"),
                None => scheme.to_string(),
            };
            row.push((label, surface));
        }
        rows.push((nu, row));
    }
    // One scale: the true surface's largest |K| at every sample.
    for (_, row) in &rows {
        for (_, s) in row {
            if let Some(truth) = &s.truth {
                for p in &s.tessellation.positions {
                    k_limit = k_limit.max(truth.closest(p).gaussian().abs());
                }
            }
        }
    }
    let k_limit = k_limit.max(1e-12);
    let options = RenderOptions {
        width: TILE.0,
        height: TILE.1,
        ..RenderOptions::default()
    };
    for (nu, row) in &rows {
        let all: Vec<nalgebra::Point3<f64>> = row
            .iter()
            .flat_map(|(_, s)| s.tessellation.positions.iter().copied())
            .collect();
        let cam = Camera::framing_points(&all, VIEW.0, VIEW.1, TILE.0 as f64 / TILE.1 as f64);
        let mesh = |t: &surface::Tessellation, colour: &dyn Fn(usize) -> [f32; 3]| RenderMesh {
            positions: t.positions.clone(),
            normals: t.normals.clone(),
            colors: (0..t.positions.len()).map(colour).collect(),
            faces: t.faces.clone(),
        };
        // The truth at the first surface's samples.
        if let Some((_, first)) = row.first() {
            if let Some(truth) = &first.truth {
                let t = &first.tessellation;
                let k: Vec<f64> = t
                    .positions
                    .iter()
                    .map(|p| truth.closest(p).gaussian())
                    .collect();
                tiles.push(Tile {
                    image: render(
                        &mesh(t, &|i| colormap::diverging(k[i], k_limit)),
                        &cam,
                        &options,
                    )?,
                    label: format!("ring {nu} × {}: true K", nu / 2),
                });
            }
        }
        for (label, s) in row {
            let t = &s.tessellation;
            tiles.push(Tile {
                image: render(
                    &mesh(t, &|i| colormap::diverging(t.gaussian[i], k_limit)),
                    &cam,
                    &options,
                )?,
                label: format!("{label}: K"),
            });
        }
    }
    let title = "The ring's Gaussian curvature: the true torus, the default (optimized curves), the curvature variant on dbhs-guarded curves, and Loop (three levels, at the limit)".to_string();
    write_composite(
        &tiles,
        1 + settings.len(),
        "Gaussian curvature on the ring: truth, default, curvature variant, Loop",
        Some(&Legend {
            title: "Gaussian curvature K".into(),
            kind: LegendKind::Diverging { limit: k_limit },
        }),
        &out.join(file),
    )?;
    Ok(title)
}

/// The face of the 16 × 8 ring whose interior boundary the boundary chart follows: one on the
/// tube's inner side, where K is most negative and the default's star pattern strongest.
pub const CHARTED_FACE: usize = 37;

/// Samples along the charted interior boundary.
const BOUNDARY_SAMPLES: usize = 41;

/// K and H along the interior boundary from corner 0 of [`CHARTED_FACE`] to its split point,
/// on both sub-patches that share it (the boundary is G1, not C2: the curvature may jump across
/// it), for the default on optimized curves and for [`SETTING`], with the true torus's at the
/// same points: two charts.
pub fn boundary_charts() -> Result<[LineChart; 2], ExperimentError> {
    let data = surface::dataset_by_name("ring", Some(16))?;
    let mut series: [Vec<Series>; 2] = [Vec::new(), Vec::new()];
    let mut truth: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
    for (scheme, curves) in [("shirman-sequin", "optimized"), SETTING] {
        let s = surface::scheme_by_name(scheme, &surface::SchemeOptions::default())?;
        let m = curves::method_by_name(curves, &curves::MethodOptions::default())?;
        let f = surface::fit_scheme(&data.mesh, s.as_ref(), m.as_ref()).map_err(|source| {
            ExperimentError::Fit {
                subject: format!("ring/{scheme}/{curves}"),
                source,
            }
        })?;
        let net = |e: usize| {
            f.quartic_net(3 * CHARTED_FACE + e)
                .and_then(|n| surface::BezierTriangle::new(4, n.to_vec()).ok())
                .ok_or_else(|| ExperimentError::Measure {
                    subject: format!("ring/{scheme}/{curves}"),
                    message: format!("face {CHARTED_FACE} has no quartic net"),
                })
        };
        // Sub-patch 0 starts at corner 0 (b400), sub-patch 2 ends there (b040).
        let (left, right) = (net(0)?, net(2)?);
        let mut sides: [[Vec<(f64, f64)>; 2]; 2] = Default::default();
        for k in 0..BOUNDARY_SAMPLES {
            let t = k as f64 / (BOUNDARY_SAMPLES - 1) as f64;
            for (side, c) in [left.curvature(1.0 - t, 0.0), right.curvature(0.0, 1.0 - t)]
                .into_iter()
                .enumerate()
            {
                if let Some(c) = c {
                    sides[0][side].push((t, c.gaussian));
                    sides[1][side].push((t, c.mean));
                }
            }
            if scheme == "shirman-sequin" {
                let q = data.surface.closest(&left.eval(1.0 - t, 0.0, t));
                truth[0].push((t, q.gaussian()));
                truth[1].push((t, q.mean()));
            }
        }
        for (measure, [l, r]) in sides.into_iter().enumerate() {
            series[measure].push(Series {
                label: format!("{scheme}/{curves} (sub-patch 0)"),
                points: l,
            });
            series[measure].push(Series {
                label: format!("{scheme}/{curves} (sub-patch 2)"),
                points: r,
            });
        }
    }
    let [ks, hs] = series;
    let [kt, ht] = truth;
    let chart = |name: &str, truth: Vec<(f64, f64)>, mut s: Vec<Series>| {
        s.insert(
            0,
            Series {
                label: "true surface".into(),
                points: truth,
            },
        );
        LineChart {
            title: format!("{name} along face {CHARTED_FACE}'s interior boundary, ring 16 × 8"),
            x_label: "t (0: the data vertex, 1: the split point)".into(),
            y_label: name.into(),
            series: s,
            log_y: false,
        }
    };
    Ok([chart("K", kt, ks), chart("H", ht, hs)])
}

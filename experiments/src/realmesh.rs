//! `experiments -- realmesh`: the committed real-world meshes (`data/meshes/`: Stanford bunny,
//! Utah teapot, Stanford dragon at two resolutions), each read as it is, repaired, completed by
//! the default estimator and fitted with every curve construction; pictures of the
//! optimized-curve surfaces, shaded and coloured by Gaussian curvature.
//!
//! The curvature colours are scale-free: `K · L²` with `L` the object's bounding-box diagonal,
//! one colour limit for every object ([`KCOLOR_MEDIANS`] times the median of `|K| L²` over all
//! of them), so the objects compare although their sizes differ by orders of magnitude.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use meshio::BoundingBox;
use nalgebra::{Point3, Vector3};
use render::colors as colormap;
use render::{
    render, write_composite, Camera, Legend, LegendKind, RenderMesh, RenderOptions, Tile,
};
use serde_json::{json, Map, Value};

use crate::error::ExperimentError;
use crate::input::{load, InputArgs};
use crate::output::{write_result, Staged};

/// The KColor limit in medians of `|K| L²`: the tails of scanned meshes are spikes of 10⁴ and
/// more (a percentile limit washes everything else out), while a sphere has `K L² = 12`; four
/// medians keep the smooth parts' variation visible and saturate the spikes.
const KCOLOR_MEDIANS: f64 = 4.0;
/// Size of one picture in a composite.
const TILE: (u32, u32) = (360, 300);
/// Tessellation density of the pictures (segments per sub-patch edge).
const SAMPLING: usize = 3;
/// The construction whose surfaces are pictured.
const PICTURED_METHOD: &str = "optimized";
/// The two views (azimuth°, elevation°, name).
const VIEWS: [(f64, f64, &str); 2] = [(-60.0, 15.0, "front"), (120.0, 30.0, "back")];

/// The committed corpus, relative to the repository root.
const CORPUS: &str = "data/meshes";

/// Options of the `realmesh` experiment.
#[derive(clap::Args, Debug)]
pub struct RealMeshArgs {
    /// Directory of the corpus (default: the committed `data/meshes` of the source tree the
    /// binary was built from, wherever it runs).
    #[arg(long, value_name = "DIR")]
    corpus: Option<PathBuf>,
    /// Output directory.
    #[arg(short = 'o', long, default_value = "results/realmesh")]
    output: PathBuf,
    /// Estimator for the normals and shape tensors the files lack.
    #[arg(long, default_value = estimate::DEFAULT_ESTIMATOR)]
    estimate: String,
}

/// The mesh files of `dir` (by extension, sorted). Each one's type is checked before anything
/// opens it: a FIFO would block the read forever and a device would be read without end, so a
/// corpus entry with a mesh extension that is not a regular file (or a link to one) is refused
/// by name.
fn corpus_files(dir: &Path) -> Result<Vec<PathBuf>, ExperimentError> {
    let read_err = |source| ExperimentError::Read {
        path: dir.to_path_buf(),
        source,
    };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(read_err)? {
        let entry = entry.map_err(read_err)?;
        let path = entry.path();
        if !meshio::format_for_path(&path).is_some_and(|f| f.can_read()) {
            continue;
        }
        // The type of what the entry names (a link followed), without opening it.
        let kind = std::fs::metadata(&path)
            .map(|m| m.file_type())
            .map_err(|source| ExperimentError::Read {
                path: path.clone(),
                source,
            })?;
        let refused = if kind.is_dir() {
            Some("a directory")
        } else {
            crate::study::special_kind(kind)
        };
        if let Some(kind) = refused {
            return Err(crate::study::StudyError::SpecialFile { path, kind }.into());
        }
        files.push(path);
    }
    files.sort();
    Ok(files)
}

/// Runs the experiment.
pub fn run(args: &RealMeshArgs) -> Result<ExitCode, ExperimentError> {
    let t_all = Instant::now();
    let corpus = match &args.corpus {
        Some(dir) => dir.clone(),
        None => crate::study::committed_path("the committed corpus", CORPUS, "--corpus DIR")?,
    };
    let files = corpus_files(&corpus)?;
    if files.is_empty() {
        return Err(ExperimentError::EmptyCorpus { path: corpus });
    }
    let staged = Staged::begin(&args.output)?;
    let out = staged.path().to_path_buf();
    let mut md = String::from(
        "# Real meshes\n\nThe committed corpus (`data/meshes/`, licences there), each file read as it is, repaired by the stated rules, its normals and shape tensors estimated, and fitted with the modified Shirman–Séquin scheme and every curve construction. G1 defects are split into edges between regular faces (the scheme's guarantee) and edges touching a fallback face (C0 only). A face is folded where a patch normal turns to or past 90° from the data face's normal (`surface::folds`).\n\n| mesh | vertices | faces | repairs | curves | fallback faces | folded faces | degenerate edges | G1 regular (rad) | G1 at fallbacks (rad) | unconverged | fit time (s) |\n|---|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut report = Map::new();
    let mut shots: Vec<(String, surface::Tessellation, f64)> = Vec::new();
    // The bar counts the files begun; its message names the one being fitted.
    let bar = progress::Progress::bar("realmesh", files.len() as u64);
    for path in &files {
        bar.inc(1);
        bar.stage(&path.display().to_string());
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let input = InputArgs {
            data: path.to_string_lossy().into_owned(),
            resolution: None,
            estimate: args.estimate.clone(),
            replace_normals: false,
            creases: fitjob::cli::CreaseArgs::default(),
        };
        let t = Instant::now();
        let loaded = load(&input)?;
        let t_load = t.elapsed().as_secs_f64();
        let mesh = &loaded.mesh;
        let repairs = loaded
            .repairs
            .as_ref()
            .map(|r| r.summary_lines())
            .unwrap_or_default();
        let mut per_method = Map::new();
        for method in curves::REGISTRY.iter().map(|e| e.name) {
            let crate::input::KeptFit {
                fit: f,
                g1,
                seconds: t_fit,
                folded_faces,
                worst_fold_cosine,
            } = crate::input::fit_prepared(
                &format!("{} ({method} curves)", path.display()),
                mesh,
                loaded.frame,
                surface::DEFAULT_SCHEME,
                method,
                curves::MethodOptions::default(),
            )?;
            let finite = f.points.iter().all(|q| q.iter().all(|c| c.is_finite()));
            let _ = writeln!(
                md,
                "| {name} | {} | {} | {} | {method} | {} | {} | {} | {:.1e} | {:.2} | {} | {:.3} |",
                mesh.num_vertices(),
                mesh.num_faces(),
                if repairs.is_empty() {
                    "none".to_string()
                } else {
                    repairs.join("; ")
                },
                f.face_fallbacks.len(),
                folded_faces,
                f.degenerate_edges.len(),
                g1.max_angle(),
                g1.fallback_interior_max.max(g1.fallback_exterior_max),
                f.unconverged,
                t_fit
            );
            per_method.insert(
                method.into(),
                json!({"fallback_faces": f.face_fallbacks.len(),
                       "folded_faces": folded_faces,
                       "worst_fold_cosine": worst_fold_cosine,
                       "degenerate_edges": f.degenerate_edges.len(),
                       "g1_regular_radians": g1.max_angle(),
                       "g1_fallback_radians": g1.fallback_interior_max.max(g1.fallback_exterior_max),
                       "unconverged": f.unconverged, "finite": finite,
                       "fit_time_seconds": t_fit}),
            );
            if method == PICTURED_METHOD {
                let tess = surface::tessellate_fit(mesh, &f, SAMPLING).map_err(|source| {
                    ExperimentError::Tessellate {
                        subject: format!("{} ({method} curves)", path.display()),
                        source,
                    }
                })?;
                let size = BoundingBox::of(&tess.positions).diagonal();
                shots.push((name.clone(), tess, size));
            }
        }
        report.insert(
            name.clone(),
            json!({"vertices": mesh.num_vertices(), "faces": mesh.num_faces(),
                   "notes": loaded.notes.iter().filter(|n| !n.starts_with("time:")).collect::<Vec<_>>(), "load_time_seconds": t_load,
                   "methods": per_method}),
        );
        bar.say(&format!(
            "  {name}: {} faces, {} notes",
            mesh.num_faces(),
            loaded.notes.len()
        ));
    }

    // Pictures: columns are the objects, rows the views.
    let mut scaled: Vec<f64> = shots
        .iter()
        .flat_map(|(_, t, l)| t.gaussian.iter().map(move |k| (k * l * l).abs()))
        .filter(|x| x.is_finite())
        .collect();
    scaled.sort_by(f64::total_cmp);
    let limit = scaled
        .get(scaled.len() / 2)
        .map(|m| KCOLOR_MEDIANS * m)
        .filter(|x| *x > 0.0)
        .unwrap_or(1.0);
    let options = RenderOptions {
        width: TILE.0,
        height: TILE.1,
        ..RenderOptions::default()
    };
    for (file, title, kcolor) in [
        (
            "shaded",
            "Fitted with optimized curves from estimated data: shaded",
            false,
        ),
        (
            "kcolor",
            "Fitted with optimized curves from estimated data: Gaussian curvature × L²",
            true,
        ),
    ] {
        let mut tiles = Vec::new();
        for (az, el, vname) in VIEWS {
            for (name, t, l) in &shots {
                let colors = if kcolor {
                    t.gaussian
                        .iter()
                        .map(|k| colormap::diverging(k * l * l, limit))
                        .collect()
                } else {
                    vec![colormap::MATERIAL; t.positions.len()]
                };
                // The corpus models are y-up (as their sources); the camera is z-up.
                let up = |p: &Point3<f64>| Point3::new(p.x, -p.z, p.y);
                let mesh = RenderMesh {
                    positions: t.positions.iter().map(up).collect(),
                    normals: t
                        .normals
                        .iter()
                        .map(|n| Vector3::new(n.x, -n.z, n.y))
                        .collect(),
                    colors,
                    faces: t.faces.clone(),
                };
                let b = BoundingBox::of(&mesh.positions);
                let cam = Camera::framing(b.min, b.max, az, el);
                tiles.push(Tile {
                    image: render(&mesh, &cam, &options)?,
                    label: format!("{name} — {vname}"),
                });
            }
        }
        let legend = kcolor.then(|| Legend {
            title: "K × (bounding-box diagonal)²".into(),
            kind: LegendKind::Diverging { limit },
        });
        write_composite(
            &tiles,
            shots.len(),
            title,
            legend.as_ref(),
            &out.join(format!("{file}.png")),
        )?;
        let _ = writeln!(md, "\n![{title}]({file}.png)");
    }
    let mut root = Map::new();
    root.insert("estimator".into(), json!(args.estimate));
    root.insert("sampling".into(), json!(SAMPLING));
    root.insert("gaussian_colour_limit_scaled".into(), json!(limit));
    root.insert("meshes".into(), Value::Object(report));
    root.insert("time_seconds".into(), json!(t_all.elapsed().as_secs_f64()));
    write_result(
        Some(&out.join("report.json")),
        serde_json::to_string_pretty(&Value::Object(root))
            .unwrap_or_default()
            .as_bytes(),
    )?;
    write_result(Some(&out.join("report.md")), md.as_bytes())?;
    say!(
        "realmesh: {} meshes in {:.1} s → {}",
        files.len(),
        t_all.elapsed().as_secs_f64(),
        args.output.display()
    );
    staged.commit()?;
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default corpus is the committed one wherever the study runs (the unit tests run in
    /// `experiments/`, where a relative `data/meshes` is not).
    #[test]
    fn the_default_corpus_is_found_from_any_directory() {
        assert!(!Path::new(CORPUS).exists());
        let dir =
            crate::study::committed_path("the committed corpus", CORPUS, "--corpus DIR").unwrap();
        let names: Vec<String> = corpus_files(&dir)
            .unwrap()
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            names,
            [
                "bunny.ply",
                "dragon_res3.ply",
                "dragon_res4.ply",
                "teapot.ply"
            ]
        );
    }
}

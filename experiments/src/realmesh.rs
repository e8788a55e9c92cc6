//! `experiments -- realmesh`: the committed real-world meshes (`data/meshes/`: Stanford bunny,
//! Utah teapot, Stanford dragon at two resolutions; `data/cad/`: CAD parts with creases, badly
//! remeshed), each read as it is, repaired, its creases found, completed by the default
//! estimator per sector and fitted with every curve construction, measured for folds, kinks on
//! smooth edges, creases kept and flat planar faces (`surface::sharp`); pictures of the
//! optimized-curve surfaces, shaded and coloured by Gaussian curvature, front and back.
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
/// The committed CAD corpus (`data/cad/generate.py`), relative to the repository root.
const CAD_CORPUS: &str = "data/cad";

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

/// One corpus directory and the up axis of its models (the renderer's camera is z-up).
struct Corpus {
    /// Where it is.
    dir: PathBuf,
    /// Its name in the report (`meshes`, `cad`, or the directory given).
    name: String,
    /// Whether its models are y-up (the scans and the teapot, as their sources) or z-up (the
    /// CAD corpus, as manifold3d builds it).
    y_up: bool,
}

/// A fitted mesh's pictures and their curvature colours.
struct Shot {
    name: String,
    tess: surface::Tessellation,
    /// The coarser tessellation of the interactive page ([`PAGE_SAMPLING`]).
    page_tess: surface::Tessellation,
    size: f64,
    y_up: bool,
}

/// The corpora to run: `--corpus DIR` (y-up, as most scan repositories), or both committed
/// ones.
fn corpora(args: &RealMeshArgs) -> Result<Vec<Corpus>, ExperimentError> {
    if let Some(dir) = &args.corpus {
        return Ok(vec![Corpus {
            dir: dir.clone(),
            name: dir.display().to_string(),
            y_up: true,
        }]);
    }
    Ok(vec![
        Corpus {
            dir: crate::study::committed_path("the committed corpus", CORPUS, "--corpus DIR")?,
            name: "meshes".into(),
            y_up: true,
        },
        Corpus {
            dir: crate::study::committed_path("the CAD corpus", CAD_CORPUS, "--corpus DIR")?,
            name: "cad".into(),
            y_up: false,
        },
    ])
}

/// Runs the experiment.
pub fn run(args: &RealMeshArgs) -> Result<ExitCode, ExperimentError> {
    let t_all = Instant::now();
    let mut jobs: Vec<(usize, PathBuf)> = Vec::new();
    let corpora = corpora(args)?;
    for (c, corpus) in corpora.iter().enumerate() {
        let files = corpus_files(&corpus.dir)?;
        if files.is_empty() {
            return Err(ExperimentError::EmptyCorpus {
                path: corpus.dir.clone(),
            });
        }
        jobs.extend(files.into_iter().map(|f| (c, f)));
    }
    let staged = Staged::begin(&args.output)?;
    let out = staged.path().to_path_buf();
    let mut md = String::from(
        "# Real meshes\n\nThe committed corpora — scans and a tessellated teapot (`data/meshes/`, licences there) and CAD parts made by CSG and remeshed badly on purpose (`data/cad/`, generator there) — each file read as it is, repaired by the stated rules, its creases found by the default rule (docs/conventions.md: the file's, and edges over 40° on tessellated models), its normals and shape tensors estimated per sector, and fitted with the modified Shirman–Séquin scheme and every curve construction.\n\nColumns: *fallback* — faces fitted with the C0 fallback patch; *folded* — faces where a patch normal turns to or past 90° from the data face's normal (`surface::folds`); *kinked* — smooth edges (data dihedral below 10°) where the patches meet at more than 1e-7 rad, of all smooth edges, and the worst; *creases kept* — edges over 40° where the patches meet at least at half the data's angle (`surface::sharp`); *flat* — the largest distance of the surface from a planar face of the data (bounded by creases), relative to the bounding-box diagonal; *G1* — the largest normal angle along smooth boundaries between regular faces (crease edges are C0 by construction).\n\n| mesh | faces | creases | curves | fallback | folded | kinked (of smooth) | worst kink (rad) | creases kept | flat | G1 regular (rad) | fit time (s) |\n|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut notes_md = String::new();
    let mut closeups: Vec<Closeup> = Vec::new();
    let mut causes_md = String::from(
        "\n## Corners and fallback causes\n\nThe corner test (`surface::fit::fan`): a face corner passes when its two boundary tangents lie in the vertex's tangent plane and turn counter-clockwise about its normal by an angle strictly between 0 and π. *before* — corners failing it with each edge's own end tangents; *after* — failing once every sector with a failing corner has its tangents chosen together from its star (the projection rules keep the tangents their source defines, and are only counted); *fanned* — sectors given a fan; *straight* — straight crease corners (a single face between two crease edges whose tangents are opposite: no fan exists, the two crease curves get one direction and length there, the crease C1, and the scheme builds the face with its straight-corner form, `surface::shirman_sequin`; their corners stay in *after*); *no fan* — sectors that have neither; *facing away* — sectors left to the per-edge tangents because their normal is at 90° or more from one of their faces (those faces fall back whatever the tangents); *folds forced by the curves* — folded faces whose three edge curves, projected onto the face, leave no patch on them unfolded (`surface::fallback::forced_fold`), of all folded faces; *fallback by cause* — `FaceFallbackReason::kind`.\n\n| mesh | curves | corners failing before | after | sectors fanned | straight | no fan | facing away | folds forced by the curves | fallback | fallback by cause |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
    );
    let mut report = Map::new();
    let mut shots: Vec<Vec<Shot>> = corpora.iter().map(|_| Vec::new()).collect();
    // The bar counts the files begun; its message names the one being fitted.
    let bar = progress::Progress::bar("realmesh", jobs.len() as u64);
    for (c, path) in &jobs {
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
            radius: None,
            replace_normals: false,
            creases: fitjob::cli::CreaseArgs::default(),
        };
        let t = Instant::now();
        let loaded = load(&input)?;
        let t_load = t.elapsed().as_secs_f64();
        let mesh = &loaded.mesh;
        let creases = mesh.sectors().map_or(0, |s| s.num_creases());
        let notes: Vec<&String> = loaded
            .notes
            .iter()
            .filter(|n| !n.starts_with("time:"))
            .collect();
        let _ = writeln!(
            notes_md,
            "- **{name}** ({} vertices): {}",
            mesh.num_vertices(),
            notes
                .iter()
                .map(|n| n.trim().to_string())
                .collect::<Vec<_>>()
                .join("; ")
        );
        let mut per_method = Map::new();
        for method in curves::REGISTRY.iter().map(|e| e.name) {
            let subject = format!("{} ({method} curves)", path.display());
            let crate::input::KeptFit {
                fit: f,
                g1,
                seconds: t_fit,
                folded,
                worst_fold_cosine,
            } = crate::input::fit_prepared(
                &subject,
                mesh,
                loaded.frame,
                surface::DEFAULT_SCHEME,
                method,
                curves::MethodOptions::default(),
            )?;
            let sharp =
                surface::sharp::measure(mesh, &f).map_err(|e| ExperimentError::Measure {
                    subject: subject.clone(),
                    message: e.to_string(),
                })?;
            let finite = f.points.iter().all(|q| q.iter().all(|c| c.is_finite()));
            let worst_kink = sharp.smooth.worst.map_or(0.0, |w| w.fitted);
            let _ = writeln!(
                md,
                "| {name} | {} | {creases} | {method} | {} | {} | {} of {} | {:.1e} | {} of {} | {} | {:.1e} | {:.3} |",
                mesh.num_faces(),
                f.face_fallbacks.len(),
                folded.len(),
                sharp.smooth.kinked,
                sharp.smooth.edges,
                worst_kink,
                sharp.creases.kept,
                sharp.creases.candidates,
                if sharp.flat.regions > 0 {
                    format!("{:.1e}", sharp.flat.deviation)
                } else {
                    "–".into()
                },
                g1.max_angle(),
                t_fit
            );
            // Folded faces whose curves already force the fold (no patch on them avoids it:
            // `surface::fallback::forced_fold`).
            let forced_folds = folded
                .iter()
                .filter(|&&face| {
                    f.face_curves(mesh, face)
                        .is_ok_and(|c| surface::fallback::forced_fold(&c).is_some())
                })
                .count();
            let mut by_kind: std::collections::BTreeMap<&str, usize> = Default::default();
            for fb in &f.face_fallbacks {
                *by_kind.entry(fb.reason.kind()).or_default() += 1;
            }
            let _ = writeln!(
                causes_md,
                "| {name} | {method} | {} | {} | {} | {} | {} | {} | {} of {} | {} | {} |",
                f.fan.corners_failing_before,
                f.fan.corners_failing_after,
                f.fan.sectors_fanned,
                f.fan.sectors_straight,
                f.fan.sectors_unfannable,
                f.fan.sectors_facing_away,
                forced_folds,
                folded.len(),
                f.face_fallbacks.len(),
                if by_kind.is_empty() {
                    "–".to_string()
                } else {
                    by_kind
                        .iter()
                        .map(|(k, n)| format!("{k} {n}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            );
            per_method.insert(
                method.into(),
                json!({"fallback_faces": f.face_fallbacks.len(),
                       "fallback_by_reason": by_kind,
                       "folds_forced_by_curves": forced_folds,
                       "fan": f.fan,
                       "folded_faces": folded.len(),
                       "worst_fold_cosine": worst_fold_cosine,
                       "degenerate_edges": f.degenerate_edges.len(),
                       "g1_regular_radians": g1.max_angle(),
                       "g1_fallback_radians": g1.fallback_interior_max.max(g1.fallback_exterior_max),
                       "crease_edges": f.crease_edges,
                       "crease_ends_off_line": f.crease_ends_off_line,
                       "sharp": sharp,
                       "unconverged": f.unconverged, "finite": finite,
                       "fit_time_seconds": t_fit}),
            );
            if method == PICTURED_METHOD {
                if let Some(c) = closeup(&name, &subject, mesh, loaded.frame, &f)? {
                    closeups.push(c);
                }
                let tess = surface::tessellate_fit(mesh, &f, SAMPLING).map_err(|source| {
                    ExperimentError::Tessellate {
                        subject: subject.clone(),
                        source,
                    }
                })?;
                let size = BoundingBox::of(&tess.positions).diagonal();
                let page_tess =
                    surface::tessellate_fit(mesh, &f, PAGE_SAMPLING).map_err(|source| {
                        ExperimentError::Tessellate {
                            subject: format!("{subject} (page)"),
                            source,
                        }
                    })?;
                shots[*c].push(Shot {
                    name: name.clone(),
                    tess,
                    page_tess,
                    size,
                    y_up: corpora[*c].y_up,
                });
            }
        }
        report.insert(
            name.clone(),
            json!({"corpus": corpora[*c].name,
                   "vertices": mesh.num_vertices(), "faces": mesh.num_faces(),
                   "creases": loaded.creases,
                   "notes": notes, "load_time_seconds": t_load,
                   "methods": per_method}),
        );
        bar.say(&format!(
            "  {name}: {} faces, {} notes",
            mesh.num_faces(),
            loaded.notes.len()
        ));
    }
    md.push_str(&causes_md);
    closeup_pictures(&mut closeups, &out, &mut md)?;
    let _ = writeln!(md, "\nWhat was done to each file:\n\n{notes_md}");

    let mut limits = Map::new();
    for (corpus, shots) in corpora.iter().zip(&shots) {
        let limit = pictures(shots, &corpus.name, &out, &mut md)?;
        limits.insert(corpus.name.clone(), json!(limit));
        page(shots, corpus, &out, &mut md)?;
    }
    let mut root = Map::new();
    root.insert("estimator".into(), json!(args.estimate));
    root.insert("sampling".into(), json!(SAMPLING));
    root.insert("gaussian_colour_limit_scaled".into(), Value::Object(limits));
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
        jobs.len(),
        t_all.elapsed().as_secs_f64(),
        args.output.display()
    );
    staged.commit()?;
    Ok(ExitCode::SUCCESS)
}

/// Close-ups of the worst kinks: at most this many meshes, worst first.
const CLOSEUPS: usize = 8;
/// The close-up's neighbourhood: the faces within this many vertex rings of the kinked edge's
/// ends.
const CLOSEUP_RINGS: usize = 2;
/// The colour of the two faces on the kinked edge in a close-up (a warm grey, so the shading
/// still reads).
const KINKED_FACES: [f32; 3] = [0.75, 0.55, 0.35];
/// Segments per patch edge of the close-ups (finer than the overviews: a kink is a line).
const CLOSEUP_SAMPLING: usize = 8;

/// The worst smooth-edge kink of one mesh with each edge's own tangents, and the same
/// neighbourhood fitted with the tangent fans (the default).
struct Closeup {
    name: String,
    /// The kink with each edge's own tangents, and at the same edge with the fans (radians).
    before: f64,
    after: f64,
    /// The neighbourhood's surfaces, before and after, and the view direction.
    surfaces: [RenderMesh; 2],
    view: Vector3<f64>,
}

/// The triangles of `tess` over the faces `keep` marks (1: shown, 2: shown highlighted), as a
/// render mesh.
fn region_mesh(tess: &surface::Tessellation, per_face: usize, keep: &[u8]) -> RenderMesh {
    let mut map = vec![usize::MAX; tess.positions.len()];
    let mut out = RenderMesh {
        positions: Vec::new(),
        normals: Vec::new(),
        colors: Vec::new(),
        faces: Vec::new(),
    };
    for (t, &patch) in tess.faces.iter().zip(&tess.patch_of_face) {
        let mark = keep.get(patch / per_face.max(1)).copied().unwrap_or(0);
        if mark == 0 {
            continue;
        }
        let color = if mark == 2 {
            KINKED_FACES
        } else {
            colormap::MATERIAL
        };
        // Vertices are shared within one colour only (a highlighted face keeps its colour).
        let tri = t.map(|v| {
            if map[v] == usize::MAX || out.colors[map[v]] != color {
                map[v] = out.positions.len();
                out.positions.push(tess.positions[v]);
                out.normals.push(tess.normals[v]);
                out.colors.push(color);
            }
            map[v]
        });
        out.faces.push(tri);
    }
    out
}

/// The close-up of `fitted`'s mesh at the worst kink of the fit with each edge's own tangents
/// (when it has one over 1e-7 rad); `None` when there is none.
fn closeup(
    name: &str,
    subject: &str,
    mesh: &surface::Mesh,
    frame: surface::Frame,
    fitted: &surface::Fit,
) -> Result<Option<Closeup>, ExperimentError> {
    let per_edge = curves::MethodOptions {
        tangents: curves::TangentRule::PerEdge,
        ..curves::MethodOptions::default()
    };
    let before_fit = crate::input::fit_prepared(
        &format!("{subject}, per-edge tangents"),
        mesh,
        frame,
        surface::DEFAULT_SCHEME,
        PICTURED_METHOD,
        per_edge,
    )?
    .fit;
    let measure = |f: &surface::Fit| {
        surface::sharp::measure(mesh, f).map_err(|e| ExperimentError::Measure {
            subject: subject.to_string(),
            message: e.to_string(),
        })
    };
    let before = measure(&before_fit)?;
    let Some(worst) = before.smooth.worst.filter(|w| w.fitted > 1e-7) else {
        return Ok(None);
    };
    // A kink that cannot be measured (no sample with both normals) is shown as NaN, not 0.
    let after_angle = surface::sharp::edge_kink(mesh, fitted, worst.edge).unwrap_or(f64::NAN);
    // The faces within CLOSEUP_RINGS vertex rings of the edge's ends; the edge's own faces
    // highlighted.
    let mut keep = vec![0u8; mesh.num_faces()];
    let mut ring: Vec<usize> = worst.vertices.to_vec();
    for _ in 0..CLOSEUP_RINGS {
        let mut next = Vec::new();
        for &v in &ring {
            for f in mesh.faces_around_vertex(v) {
                if keep[f] == 0 {
                    keep[f] = 1;
                    next.extend(mesh.faces()[f]);
                }
            }
        }
        next.sort_unstable();
        next.dedup();
        ring = next;
    }
    let edge = mesh.edge(worst.edge);
    let mut view = Vector3::zeros();
    for (f, _) in [Some(edge.first), edge.second].into_iter().flatten() {
        keep[f] = 2;
        view += mesh.face_unit_normal(f).unwrap_or_default();
    }
    let view = view.try_normalize(0.0).unwrap_or_else(Vector3::z);
    let tess = |f: &surface::Fit, which: &str| {
        surface::tessellate_fit(mesh, f, CLOSEUP_SAMPLING).map_err(|source| {
            ExperimentError::Tessellate {
                subject: format!("{subject} ({which} close-up)"),
                source,
            }
        })
    };
    let per_face = fitted.layout.patches_per_face();
    let surfaces = [
        region_mesh(&tess(&before_fit, "per-edge")?, per_face, &keep),
        region_mesh(&tess(fitted, "fanned")?, per_face, &keep),
    ];
    Ok(Some(Closeup {
        name: name.to_string(),
        before: worst.fitted,
        after: after_angle,
        surfaces,
        view,
    }))
}

/// `worst.png`: each close-up before and after, worst first.
fn closeup_pictures(
    closeups: &mut [Closeup],
    out: &Path,
    md: &mut String,
) -> Result<(), ExperimentError> {
    if closeups.is_empty() {
        return Ok(());
    }
    closeups.sort_by(|a, b| b.before.total_cmp(&a.before));
    let options = RenderOptions {
        width: TILE.0,
        height: TILE.1,
        ..RenderOptions::default()
    };
    let mut tiles = Vec::new();
    for c in closeups.iter().take(CLOSEUPS) {
        let az = c.view.y.atan2(c.view.x).to_degrees();
        let el = c.view.z.clamp(-1.0, 1.0).asin().to_degrees();
        for (surface, label) in c.surfaces.iter().zip([
            format!("{}: {:.2} rad", c.name, c.before),
            format!("{}: {:.1e} rad", c.name, c.after),
        ]) {
            let aspect = f64::from(options.width) / f64::from(options.height);
            let cam = Camera::framing_points(&surface.positions, az, el, aspect);
            tiles.push(Tile {
                image: render(surface, &cam, &options)?,
                label,
            });
        }
    }
    let title = "worst kinks: own tangents | tangent fans";
    write_composite(&tiles, 2, title, None, &out.join("worst.png"))?;
    let _ = writeln!(
        md,
        "\n## The worst kinks\n\nEach mesh's worst smooth-edge kink with each edge's own tangents (`--tangents per-edge`, optimized curves), left, and the same neighbourhood (two vertex rings round the edge, its two faces in brown) with the tangent fans, right; the angle across that edge in each.\n\n![{title}](worst.png)"
    );
    Ok(())
}

/// Most objects a picture row holds: more are wrapped onto further rows (each object keeps
/// its front and back views one above the other).
const PICTURE_COLUMNS: usize = 5;

/// The shaded and the KColor composites of one corpus (`shaded.png`, `kcolor.png` for the
/// scans; `<corpus>-shaded.png`, … for the others), front and back views of every object framed
/// whole; returns the KColor limit used.
/// Segments per patch edge of the interactive page's surfaces (the pictures use [`SAMPLING`]).
const PAGE_SAMPLING: usize = 2;

/// Triangles of one mesh's surface on a corpus page, and of the page's surfaces together: a
/// page stays near 3 MB (a larger mesh is left off the page and named).
const PAGE_TRIANGLES: (usize, usize) = (45_000, 60_000);

/// The corpus's interactive page (`<corpus>.html`): its meshes' surfaces side by side, with
/// their curvature and reflection lines; the meshes over [`PAGE_TRIANGLES`] are left off and
/// named in the report.
fn page(
    shots: &[Shot],
    corpus: &Corpus,
    out: &Path,
    md: &mut String,
) -> Result<(), ExperimentError> {
    let mut total = 0;
    let mut views = Vec::new();
    let mut left = Vec::new();
    for s in shots {
        let n = s.page_tess.faces.len();
        if n > PAGE_TRIANGLES.0 || total + n > PAGE_TRIANGLES.1 {
            left.push(s.name.as_str());
            continue;
        }
        total += n;
        let mut view = crate::pages::fit_view(&s.name, &s.page_tess, None, None, None);
        // Patch boundaries would be half the page (six segments a patch at s = 2): left off.
        view.boundaries = None;
        views.push(view);
    }
    if views.is_empty() {
        return Ok(());
    }
    let file = format!("{}.html", corpus.name);
    let up = if corpus.y_up {
        meshio::UpAxis::Y
    } else {
        meshio::UpAxis::Z
    };
    let bytes = crate::pages::write_up(
        &out.join(&file),
        &format!("{}: every mesh, {PICTURED_METHOD} curves", corpus.name),
        views,
        up,
    )?;
    let _ = writeln!(
        md,
        "\nInteractive: [{file}]({file}) ({:.1} MB, works offline): the meshes side by side with linked cameras, tessellated at {PAGE_SAMPLING} segments a patch edge; shaded, K, H, κ1, κ2, reflection lines, isophotes (patch boundaries left off for size).{}",
        bytes as f64 / 1e6,
        if left.is_empty() { String::new() } else { format!(" Left off (over {} triangles, or the page full): {}.", PAGE_TRIANGLES.0, left.join(", ")) }
    );
    Ok(())
}

fn pictures(
    shots: &[Shot],
    corpus: &str,
    out: &Path,
    md: &mut String,
) -> Result<f64, ExperimentError> {
    if shots.is_empty() {
        return Ok(0.0);
    }
    let mut scaled: Vec<f64> = shots
        .iter()
        .flat_map(|s| {
            s.tess
                .gaussian
                .iter()
                .map(move |k| (k * s.size * s.size).abs())
        })
        .filter(|x| x.is_finite() && *x > 0.0)
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
    let prefix = if corpus == "meshes" {
        String::new()
    } else {
        format!("{corpus}-")
    };
    let columns = shots.len().min(PICTURE_COLUMNS);
    for (file, what, kcolor) in [
        ("shaded", "shaded", false),
        ("kcolor", "Gaussian curvature × L²", true),
    ] {
        let title = format!("{corpus}: fitted with optimized curves from estimated data: {what}");
        let mut tiles = Vec::new();
        for block in shots.chunks(columns) {
            for (az, el, vname) in VIEWS {
                for s in block {
                    let t = &s.tess;
                    let colors = if kcolor {
                        t.gaussian
                            .iter()
                            .map(|k| colormap::diverging(k * s.size * s.size, limit))
                            .collect()
                    } else {
                        vec![colormap::MATERIAL; t.positions.len()]
                    };
                    // y-up models are turned z-up for the camera.
                    let (pos, nor): (Vec<Point3<f64>>, Vec<Vector3<f64>>) = if s.y_up {
                        (
                            t.positions
                                .iter()
                                .map(|p| Point3::new(p.x, -p.z, p.y))
                                .collect(),
                            t.normals
                                .iter()
                                .map(|n| Vector3::new(n.x, -n.z, n.y))
                                .collect(),
                        )
                    } else {
                        (t.positions.clone(), t.normals.clone())
                    };
                    let mesh = RenderMesh {
                        positions: pos,
                        normals: nor,
                        colors,
                        faces: t.faces.clone(),
                    };
                    let cam = Camera::framing_points(
                        &mesh.positions,
                        az,
                        el,
                        f64::from(options.width) / f64::from(options.height),
                    );
                    tiles.push(Tile {
                        image: render(&mesh, &cam, &options)?,
                        label: format!("{} — {vname}", s.name),
                    });
                }
                // A short last row is filled with blank tiles so the columns line up.
                for _ in block.len()..columns {
                    tiles.push(Tile {
                        image: render::Image {
                            width: options.width,
                            height: options.height,
                            rgb: vec![255; 3 * options.width as usize * options.height as usize],
                        },
                        label: String::new(),
                    });
                }
            }
        }
        let legend = kcolor.then(|| Legend {
            title: "K × (bounding-box diagonal)²".into(),
            kind: LegendKind::Diverging { limit },
        });
        let name = format!("{prefix}{file}.png");
        write_composite(&tiles, columns, &title, legend.as_ref(), &out.join(&name))?;
        let _ = writeln!(md, "\n![{title}]({name})");
    }
    Ok(limit)
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

//! The ring study's surfaces, built and measured: the true torus on a fine grid, the sampled
//! triangulation as flat triangles, and the Shirman–Séquin surface fitted with each of the
//! study's curve constructions (with its G1 defect and boundary-curve measures), each
//! tessellated and compared with the torus; and the view of them the renderer takes.

use curves::{BoundaryProblem, MethodOptions};
use surface::analytic::torus_point;
use surface::curve_stats::CurveStats;
use surface::fairing::InteriorChoice;
use surface::{
    compare_with_truth, tessellate, AnalyticSurface, BezierTriangle, Fit, G1Report, Mesh,
    SurfaceErrors, Tessellation,
};

use crate::error::ExperimentError;

/// Grid of the "true ring" picture: fine enough that smooth shading shows no facets.
const TRUE_GRID: (usize, usize) = (96, 48);

/// One of the five surfaces.
pub(super) struct Surface {
    pub(super) name: &'static str,
    pub(super) label: String,
    pub(super) tess: Tessellation,
    /// Draw with per-face normals (the flat triangulation).
    pub(super) flat: bool,
    pub(super) errors: SurfaceErrors,
}

/// The surface fitted with one curve construction, and its measures.
pub(super) struct FittedMethod {
    /// The construction's name (`curves::REGISTRY`).
    pub(super) name: &'static str,
    /// The fit (nets, per-edge α).
    pub(super) fit: Fit,
    /// G1 defect and interpolation error.
    pub(super) g1: G1Report,
    /// Boundary-curve measures.
    pub(super) curves: CurveStats,
    /// Time of the fit (curves, nets, interior choice), seconds.
    pub(super) fit_time_seconds: f64,
}

/// The true torus, tessellated on a fine grid with exact normals and curvatures.
pub(super) fn true_ring(big: f64, small: f64) -> Tessellation {
    let (nu, nv) = TRUE_GRID;
    let mut positions = Vec::with_capacity(nu * nv);
    let mut normals = Vec::with_capacity(nu * nv);
    let mut gaussian = Vec::with_capacity(nu * nv);
    let mut mean = Vec::with_capacity(nu * nv);
    let mut shapes = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let (u, v) = (
                std::f64::consts::TAU * i as f64 / nu as f64,
                std::f64::consts::TAU * j as f64 / nv as f64,
            );
            let d = torus_point(u, v, big, small);
            let (ku, kv) = (-v.cos() / (big + small * v.cos()), -1.0 / small);
            positions.push(d.p);
            normals.push(d.n);
            gaussian.push(ku * kv);
            mean.push(0.5 * (ku + kv));
            shapes.push(d.shape);
        }
    }
    let id = |i: usize, j: usize| (i % nu) * nv + (j % nv);
    let mut faces = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let n = faces.len();
    Tessellation {
        positions,
        normals,
        gaussian,
        mean,
        shapes,
        faces,
        directions: Vec::new(),
        patch_of_face: vec![0; n],
        welds: 0,
        max_weld_normal_angle: 0.0,
        singular_samples: 0,
        collapsed_faces: 0,
    }
}

/// The sampled triangulation as flat linear patches, tessellated like the fitted surfaces.
fn flat_triangles(mesh: &Mesh, s: usize) -> Result<Tessellation, ExperimentError> {
    let patches: Vec<BezierTriangle> = mesh
        .faces()
        .iter()
        .filter_map(|f| {
            let v = mesh.vertices();
            BezierTriangle::new(1, vec![v[f[0]].data.p, v[f[1]].data.p, v[f[2]].data.p]).ok()
        })
        .collect();
    tessellate(&patches, s).map_err(|source| ExperimentError::Tessellate {
        subject: "ring/flat".into(),
        source,
    })
}

/// The ring at `resolution` fitted with each curve construction of `methods` (registered names)
/// by the fit job (`fitjob::run`, the fit and G1 every front end gets),
/// interior parameters as `interior` chooses them (`--interior`, the solver of `options`).
pub(super) fn fit_methods(
    methods: &[String],
    resolution: usize,
    scheme: &fitjob::cli::SchemeArgs<fitjob::cli::PatchesOnly>,
    problems: &[BoundaryProblem],
    options: &MethodOptions,
    interior: InteriorChoice,
) -> Result<Vec<FittedMethod>, ExperimentError> {
    let mut fits = Vec::new();
    for asked in methods {
        // The registry's own `&'static str` (the parser admits registered names only).
        let Some(name) = curves::REGISTRY.iter().map(|e| e.name).find(|n| n == asked) else {
            return Err(ExperimentError::Usage(format!(
                "--curves: unknown construction `{asked}`"
            )));
        };
        let crate::input::KeptFit {
            fit: f,
            g1,
            seconds: fit_time_seconds,
            ..
        } = crate::input::fit_kept(fitjob::FitOptions {
            input: fitjob::InputOptions {
                source: fitjob::Source::DataSet {
                    name: "ring".into(),
                    resolution: Some(resolution),
                },
                ..fitjob::InputOptions::default()
            },
            scheme: scheme.scheme.clone(),
            scheme_options: scheme.options.clone(),
            curves: name.into(),
            method_options: *options,
            interior,
            ..fitjob::FitOptions::default()
        })?;
        let cs = surface::curve_stats::curve_stats(problems, &f);
        fits.push(FittedMethod {
            name,
            fit: f,
            g1,
            curves: cs,
            fit_time_seconds,
        });
    }
    Ok(fits)
}

/// The five surfaces (true ring, flat triangles, one per fit), tessellated at `sampling` and
/// measured against `truth`; `resolution` names the triangulation in its label.
pub(super) fn measure_surfaces(
    mesh: &Mesh,
    truth: &dyn AnalyticSurface,
    fits: &[FittedMethod],
    resolution: usize,
    sampling: usize,
) -> Result<Vec<Surface>, ExperimentError> {
    let (big, small) = (
        surface::datasets::RING_MAJOR_RADIUS,
        surface::datasets::RING_TUBE_RADIUS,
    );
    let mut surfaces = Vec::new();
    let tt = true_ring(big, small);
    let te = compare_with_truth(&tt, truth);
    surfaces.push(Surface {
        name: "true",
        label: "true ring".into(),
        tess: tt,
        flat: false,
        errors: te,
    });
    let ft = flat_triangles(mesh, sampling)?;
    let fe = compare_with_truth(&ft, truth);
    surfaces.push(Surface {
        name: "flat",
        label: format!(
            "sampled {}×{} triangulation",
            resolution,
            (resolution / 2).max(3)
        ),
        tess: ft,
        flat: true,
        errors: fe,
    });
    for FittedMethod { name, fit: f, .. } in fits {
        let tess = surface::tessellate_fit(mesh, f, sampling).map_err(|source| {
            ExperimentError::Tessellate {
                subject: format!("ring/{name}"),
                source,
            }
        })?;
        let errors = compare_with_truth(&tess, truth);
        surfaces.push(Surface {
            name,
            label: fit_label(f.scheme, name),
            tess,
            flat: false,
            errors,
        });
    }
    Ok(surfaces)
}

/// The label of a surface fitted by `scheme` on `curves` curves: Mann's scheme by its authors'
/// names (the seeds' pictures), any other (`ring --scheme`) by its registered name.
pub(super) fn fit_label(scheme: &str, curves: &str) -> String {
    match scheme {
        "shirman-sequin" => format!("Shirman–Séquin, {curves} curves"),
        other => format!("{other}, {curves} curves"),
    }
}

/// What the renderer needs of a surface.
pub struct SurfaceView<'a> {
    /// File-name stem.
    pub name: &'a str,
    /// Label on pictures.
    pub label: &'a str,
    /// The tessellation.
    pub tess: &'a Tessellation,
    /// Per-face normals (flat shading).
    pub flat: bool,
    /// Distance of each sample to the true surface.
    pub distance: Vec<f64>,
}

/// The renderer's view of the surfaces, with each sample's distance to the torus.
pub(super) fn surfaces_view(surfaces: &[Surface]) -> Vec<SurfaceView<'_>> {
    let torus = surface::Torus {
        big: surface::datasets::RING_MAJOR_RADIUS,
        small: surface::datasets::RING_TUBE_RADIUS,
    };
    surfaces
        .iter()
        .map(|s| SurfaceView {
            name: s.name,
            label: &s.label,
            tess: &s.tess,
            flat: s.flat,
            distance: s
                .tess
                .positions
                .iter()
                .map(|p| torus.signed_distance(p).abs())
                .collect(),
        })
        .collect()
}

//! Pictures and mesh files of the ring study: every surface from three views, shaded, coloured
//! by Gaussian curvature (KColor) and by distance to the true surface (Radial); every surface as
//! PLY, the optimized one as OBJ and as patch nets (JSON Lines).

use std::path::Path;

use nalgebra::Vector3;
use render::colors as colormap;
use render::{write_composite, Camera, Image, Legend, LegendKind, RenderMesh, RenderOptions, Tile};
use serde_json::{json, Value};

use super::surfaces::{FittedMethod, SurfaceView};
use crate::error::ExperimentError;
use crate::output::write_result;

/// The three views (azimuth°, elevation°, name) of the seeds' Pictures 1–3: an overview, a view
/// from above onto the top of the ring (where Mann's Picture 2 shows the worst artifact), and a
/// grazing side view under which bumps and flat spots stand out.
pub const VIEWS: [(f64, f64, &str); 3] = [
    (35.0, 35.0, "overview"),
    (100.0, 65.0, "from above"),
    (200.0, 6.0, "grazing"),
];

/// Size of one picture in a composite.
const TILE: (u32, u32) = (380, 285);

enum Colouring {
    Uniform,
    Gaussian(f64),
    Distance(f64),
}

fn render_mesh(s: &SurfaceView<'_>, colouring: &Colouring) -> RenderMesh {
    let t = s.tess;
    let colour = |i: usize| match colouring {
        Colouring::Uniform => colormap::MATERIAL,
        Colouring::Gaussian(limit) => colormap::diverging(t.gaussian[i], *limit),
        Colouring::Distance(hi) => colormap::sequential(s.distance[i], 0.0, *hi),
    };
    if s.flat {
        // One vertex per face corner with the face normal: flat shading.
        let mut m = RenderMesh {
            positions: Vec::with_capacity(3 * t.faces.len()),
            normals: Vec::with_capacity(3 * t.faces.len()),
            colors: Vec::with_capacity(3 * t.faces.len()),
            faces: Vec::with_capacity(t.faces.len()),
        };
        for f in &t.faces {
            let [a, b, c] = f.map(|i| t.positions[i]);
            let n = (b - a).cross(&(c - a));
            let n = if n.norm() > 0.0 {
                n.normalize()
            } else {
                Vector3::z()
            };
            let base = m.positions.len();
            for &i in f {
                m.positions.push(t.positions[i]);
                m.normals.push(n);
                m.colors.push(colour(i));
            }
            m.faces.push([base, base + 1, base + 2]);
        }
        m
    } else {
        RenderMesh {
            positions: t.positions.clone(),
            normals: t.normals.clone(),
            colors: (0..t.positions.len()).map(colour).collect(),
            faces: t.faces.clone(),
        }
    }
}

/// The Gaussian-curvature colour limit shared by pictures and PLY colours: the true ring's
/// largest |K|.
fn gaussian_limit(views: &[SurfaceView<'_>]) -> f64 {
    views
        .iter()
        .find(|v| v.name == "true")
        .map(|v| v.tess.gaussian.iter().fold(0.0f64, |m, k| m.max(k.abs())))
        .unwrap_or(1.0)
        .max(1e-12)
}

/// Renders the three composites; returns their description for the report.
pub fn render_all(out: &Path, views: &[SurfaceView<'_>]) -> Result<Value, ExperimentError> {
    // Every surface from the same camera, framed on all of their vertices.
    let all: Vec<nalgebra::Point3<f64>> = views
        .iter()
        .flat_map(|v| v.tess.positions.iter().copied())
        .collect();
    // Colour limits shared by every surface so the pictures compare: the true ring's largest
    // |K|, and twice the median over the fitted surfaces of their largest distance (so the
    // typical fitted surface uses the lower half of the scale; lumps and flat triangles
    // saturate).
    let k_limit = gaussian_limit(views);
    let mut maxima: Vec<f64> = views
        .iter()
        .filter(|v| !matches!(v.name, "true" | "flat"))
        .map(|v| v.distance.iter().copied().fold(0.0f64, f64::max))
        .collect();
    maxima.sort_by(f64::total_cmp);
    let d_limit = (2.0 * maxima.get(maxima.len() / 2).copied().unwrap_or(1.0)).max(1e-12);
    let options = RenderOptions {
        width: TILE.0,
        height: TILE.1,
        ..RenderOptions::default()
    };
    let modes = [
        ("shaded", "Shaded", Colouring::Uniform, None),
        (
            "kcolor",
            "Gaussian curvature (KColor)",
            Colouring::Gaussian(k_limit),
            Some(Legend {
                title: "Gaussian curvature K".into(),
                kind: LegendKind::Diverging { limit: k_limit },
            }),
        ),
        (
            "radial",
            "Distance to the true ring (Radial)",
            Colouring::Distance(d_limit),
            Some(Legend {
                title: "distance to the torus".into(),
                kind: LegendKind::Sequential {
                    lo: 0.0,
                    hi: d_limit,
                },
            }),
        ),
    ];
    let mut files = Vec::new();
    for (file, title, colouring, legend) in &modes {
        let meshes: Vec<RenderMesh> = views.iter().map(|v| render_mesh(v, colouring)).collect();
        // Every (view, surface) picture in parallel, in the composite's order.
        let cams: Vec<Camera> = VIEWS
            .iter()
            .map(|(az, el, _)| {
                Camera::framing_points(&all, *az, *el, f64::from(TILE.0) / f64::from(TILE.1))
            })
            .collect();
        let jobs: Vec<(&RenderMesh, &Camera)> = cams
            .iter()
            .flat_map(|cam| meshes.iter().map(move |m| (m, cam)))
            .collect();
        let images: Vec<Image> = render::render_many(&jobs, &options)?;
        let labels = VIEWS
            .iter()
            .flat_map(|(_, _, vname)| views.iter().map(move |v| format!("{} — {vname}", v.label)));
        let tiles: Vec<Tile> = images
            .into_iter()
            .zip(labels)
            .map(|(image, label)| Tile { image, label })
            .collect();
        let path = out.join(format!("{file}.png"));
        write_composite(&tiles, views.len(), title, legend.as_ref(), &path)?;
        files.push(json!({"file": format!("{file}.png"), "title": title}));
    }
    Ok(
        json!({"views": VIEWS.iter().map(|v| json!({"azimuth_degrees": v.0, "elevation_degrees": v.1, "name": v.2})).collect::<Vec<_>>(),
              "gaussian_colour_limit": k_limit, "distance_colour_limit": d_limit, "files": files}),
    )
}

/// PLY (binary, KColor colours, the curvature in the exported convention: `meshio::ply`) of
/// every surface, and OBJ of the optimized one (committed results stay a few MB).
pub fn write_meshes(out: &Path, views: &[SurfaceView<'_>]) -> Result<(), ExperimentError> {
    let k_limit = gaussian_limit(views);
    for v in views {
        let t = v.tess;
        // The workspace's one PLY writer (meshio's) and its one layout: positions, normals,
        // KColor colours (sRGB-encoded, the range recorded), and the curvature (K as MeshLab's
        // `quality` too), in libigl's, trimesh's and MeshLab's sign (H > 0 on a sphere).
        let mut raw = meshio::RawMesh::from_triangles(t.positions.clone(), &t.faces);
        raw.normals = Some(t.normals.clone());
        raw.colors = Some(
            t.gaussian
                .iter()
                .map(|k| colormap::diverging(*k, k_limit))
                .collect(),
        );
        raw.color_map = Some(meshio::ColorMap {
            quantity: "gaussian_curvature".into(),
            map: "diverging".into(),
            min: -k_limit,
            max: k_limit,
        });
        raw.curvature = Some(meshio::Curvature::from_internal(
            t.gaussian.clone(),
            t.mean.clone(),
        ));
        let path = out.join(format!("{}.ply", v.name));
        let bytes =
            meshio::MeshFormat::write(&meshio::ply::Ply, &raw, &meshio::WriteOptions::new())
                .map_err(|source| ExperimentError::MeshWrite {
                    path: path.clone(),
                    source,
                })?;
        write_result(Some(&path), &bytes)?;
        if v.name != "optimized" {
            continue;
        }
        // Positions, normals, triangles and the generator's comment (OBJ holds no curvature).
        let mut plain = meshio::RawMesh::from_triangles(t.positions.clone(), &t.faces);
        plain.normals = Some(t.normals.clone());
        let obj =
            meshio::MeshFormat::write(&meshio::obj::Obj, &plain, &meshio::WriteOptions::new())
                .map_err(|source| ExperimentError::MeshWrite {
                    path: out.join(format!("{}.obj", v.name)),
                    source,
                })?;
        write_result(Some(&out.join(format!("{}.obj", v.name))), &obj)?;
    }
    Ok(())
}

/// Patches of the optimized surface (the others: `experiments -- fit --out`), to keep the
/// committed results small; written by `surface::patch_io` for any scheme's layout.
pub fn write_patches(out: &Path, fits: &[FittedMethod]) -> Result<(), ExperimentError> {
    for FittedMethod { name, fit: f, .. } in fits.iter().filter(|f| f.name == "optimized") {
        let mut text = Vec::new();
        surface::patch_io::write_jsonl(f, &|p| *p, &mut text).map_err(|source| {
            ExperimentError::Write {
                path: out.join(format!("patches-{name}.jsonl")),
                source,
            }
        })?;
        write_result(Some(&out.join(format!("patches-{name}.jsonl"))), &text)?;
    }
    Ok(())
}

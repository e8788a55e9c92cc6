//! The sweep's pictures: for every data set of a whole run, one composite with a column per
//! task and three rows, shaded, Gaussian curvature K (one diverging scale for the data set:
//! the true surface's largest |K| at the first task's samples, or the first task's own
//! colour limit for a mesh file) and reflection lines
//! (continuous across patch boundaries where the surface is G1), every task seen from the
//! same camera, framed on all of their vertices.

use std::path::Path;

use render::colors as colormap;
use render::{
    render, write_composite, Camera, Legend, LegendKind, RenderMesh, RenderOptions, Tile,
};
use surface::Tessellation;

use crate::error::ExperimentError;

/// Size of one picture.
const TILE: (u32, u32) = (260, 200);
/// The view (azimuth°, elevation°).
const VIEW: (f64, f64) = (35.0, 35.0);
/// Most tasks (columns) a composite draws; the rest are named as left out.
pub const MAX_COLUMNS: usize = 10;

/// One task's tessellation, kept for its data set's composite.
pub struct Shot {
    /// The task's id.
    pub id: String,
    /// Its surface, in world coordinates.
    pub tess: Tessellation,
    /// The true surface's largest |K| at its samples (`None` for a mesh file).
    pub k_true_max: Option<f64>,
}

/// A data set's shots: the first [`MAX_COLUMNS`] tasks kept, the ids of the rest.
pub struct Group {
    /// The data set (with `@resolution` where the grid has resolutions).
    pub name: String,
    shots: Vec<Shot>,
    left_out: Vec<String>,
}

impl Group {
    /// A group holding its first shot.
    pub fn new(name: String, first: Shot) -> Self {
        Group {
            name,
            shots: vec![first],
            left_out: Vec::new(),
        }
    }

    /// Keeps `shot`, or only its id once the composite is full.
    pub fn add(&mut self, shot: Shot) {
        if self.shots.len() < MAX_COLUMNS {
            self.shots.push(shot);
        } else {
            self.left_out.push(shot.id);
        }
    }
}

/// A written composite, for `curvature.md`.
pub struct Composite {
    /// The group's name.
    pub group: String,
    /// The PNG's file name in the output directory.
    pub file: String,
    /// Tasks not drawn (beyond [`MAX_COLUMNS`]).
    pub left_out: Vec<String>,
}

fn mesh(t: &Tessellation, colour: impl Fn(usize) -> [f32; 3]) -> RenderMesh {
    RenderMesh {
        positions: t.positions.clone(),
        normals: t.normals.clone(),
        colors: (0..t.positions.len()).map(colour).collect(),
        faces: t.faces.clone(),
    }
}

/// Writes `tasks-<group>.png` into `out`.
pub fn write(out: &Path, g: &Group) -> Result<Composite, ExperimentError> {
    let (group, shown) = (g.name.as_str(), g.shots.as_slice());
    let first = &shown[0];
    let all: Vec<nalgebra::Point3<f64>> = shown
        .iter()
        .flat_map(|s| s.tess.positions.iter().copied())
        .collect();
    let cam = Camera::framing_points(&all, VIEW.0, VIEW.1, TILE.0 as f64 / TILE.1 as f64);
    let limit = first
        .k_true_max
        .unwrap_or_else(|| fitjob::output::gaussian_colour_limit(&first.tess.gaussian))
        .max(1e-12);
    let lit = RenderOptions {
        width: TILE.0,
        height: TILE.1,
        ..RenderOptions::default()
    };
    let zebra = RenderOptions {
        shading: render::interrogation::Shading::REFLECTION,
        ..lit.clone()
    };
    let mut rows: [Vec<Tile>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    let prefix = format!("{}/", group.split('@').next().unwrap_or(group));
    for s in shown {
        let label = s.id.strip_prefix(&prefix).unwrap_or(&s.id).to_string();
        let t = &s.tess;
        rows[0].push(Tile {
            image: render(&mesh(t, |_| colormap::MATERIAL), &cam, &lit)?,
            label: format!("{label} — shaded"),
        });
        rows[1].push(Tile {
            image: render(
                &mesh(t, |i| colormap::diverging(t.gaussian[i], limit)),
                &cam,
                &lit,
            )?,
            label: format!("{label} — K"),
        });
        rows[2].push(Tile {
            image: render(&mesh(t, |_| colormap::MATERIAL), &cam, &zebra)?,
            label: format!("{label} — reflection lines"),
        });
    }
    let columns = shown.len();
    let tiles: Vec<Tile> = rows.into_iter().flatten().collect();
    let file = format!("tasks-{}.png", group.replace('@', "-"));
    write_composite(
        &tiles,
        columns,
        &format!("{group}: every task, shaded, K and reflection lines (a column a task)"),
        Some(&Legend {
            title: "Gaussian curvature K (the middle row)".into(),
            kind: LegendKind::Diverging { limit },
        }),
        &out.join(&file),
    )?;
    Ok(Composite {
        group: group.to_string(),
        file,
        left_out: g.left_out.clone(),
    })
}

/// What the composites show, for `curvature.md`.
pub fn description() -> String {
    format!(
        "One composite per data set, a column per task (at most {MAX_COLUMNS}) and three rows: shaded, Gaussian curvature K on one diverging scale for the data set (the true surface's largest |K| at the first task's vertices; for a mesh file, the first task's own colour limit) and reflection lines (continuous across patch boundaries where the surface is G1, broken where it is only C0). Every task is seen from the same camera (azimuth {}°, elevation {}°), framed on all of the composite's vertices.",
        VIEW.0, VIEW.1
    )
}

//! The interactive pages of `fit --html` and the studies (the `viewer` crate): a fitted
//! surface as a view with its curvature, patch boundaries, control nets, the data mesh and,
//! where there is a true surface, each vertex's distance to it.

use std::path::Path;

use surface::{AnalyticSurface, Fit, Frame, Mesh, Tessellation};

use crate::error::ExperimentError;
use crate::output::write_result;

/// `t` (in world coordinates) as a view titled `title`, with the data mesh `mesh` (in its
/// working frame, moved by `frame`) drawn over it, the control nets of `fit` when its patches
/// are Bézier nets, and the distance to `truth` when there is one.
pub fn fit_view(
    title: &str,
    t: &Tessellation,
    mesh: Option<(&Mesh, &Frame)>,
    fit: Option<&Fit>,
    truth: Option<&dyn AnalyticSurface>,
) -> viewer::View {
    let mut view = viewer::view_from_tessellation(title, t);
    if let Some((mesh, frame)) = mesh {
        let positions: Vec<[f32; 3]> = mesh
            .vertices()
            .iter()
            .map(|v| {
                let p = frame.to_world(&v.data.p);
                [p.x as f32, p.y as f32, p.z as f32]
            })
            .collect();
        let faces: Vec<[u32; 3]> = mesh.faces().iter().map(|f| f.map(|i| i as u32)).collect();
        view.data_mesh = Some(viewer::wireframe(&positions, &faces));
        if let Some(fit) = fit.filter(|f| f.layout.is_bezier()) {
            let patches: Vec<surface::BezierTriangle> = (0..fit.num_patches())
                .filter_map(|i| {
                    let p = fit.patch(i)?;
                    let world = p.points().iter().map(|q| frame.to_world(q)).collect();
                    surface::BezierTriangle::new(p.degree(), world).ok()
                })
                .collect();
            view.nets = Some(viewer::control_nets(&patches));
        }
    }
    if let Some(truth) = truth {
        view.distance = Some(
            t.positions
                .iter()
                .map(|p| truth.signed_distance(p).abs() as f32)
                .collect(),
        );
    }
    view
}

/// Writes a page of `views` (side by side, cameras linked) titled `title` to `path`.
pub fn write(path: &Path, title: &str, views: Vec<viewer::View>) -> Result<u64, ExperimentError> {
    write_up(path, title, views, meshio::UpAxis::Z)
}

/// [`write`] for data whose up axis is `up` (scans are mostly y up).
pub fn write_up(
    path: &Path,
    title: &str,
    views: Vec<viewer::View>,
    up: meshio::UpAxis,
) -> Result<u64, ExperimentError> {
    let mut page = viewer::Page::new(title);
    page.set_up(up);
    for v in views {
        page.add_view(v).map_err(|source| ExperimentError::Page {
            path: path.to_path_buf(),
            source,
        })?;
    }
    let html = page.to_html();
    write_result(Some(path), html.as_bytes())?;
    Ok(html.len() as u64)
}

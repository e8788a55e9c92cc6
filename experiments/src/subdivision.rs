//! The surface of a subdivision scheme on a data mesh, measured like the Bézier schemes'
//! tessellations (`schemes` and `sweep` put them in one table).

use nalgebra::Point3;
use surface::Tessellation;

/// Subdivision steps of the approximating schemes in the study: 3 gives Loop 64 triangles per
/// data face (the Bézier schemes get 64–75), Catmull–Clark 96 (48 quads).
pub const SUBDIVISION_LEVELS: u32 = 3;

/// The surface of a subdivision scheme on the data mesh, as a tessellation: `levels` steps,
/// every vertex pushed to its limit position with its limit normal (the schemes' exact limit
/// stencils), quads split along their first diagonal, and the curvature estimated on that mesh
/// by the default estimator (`estimate`, hybrid jet/Rusinkiewicz) — subdivision surfaces have
/// no closed-form curvature at the vertices here. Also returns the largest distance from a data
/// point to the limit surface (the schemes approximate).
pub fn subdivision_surface(
    mesh: &surface::Mesh,
    scheme: &str,
    levels: u32,
) -> Result<(Tessellation, f64), subdiv::SubdivError> {
    let s = subdiv::scheme_by_name(scheme)?;
    let positions: Vec<Point3<f64>> = mesh.vertices().iter().map(|v| v.data.p).collect();
    let base = subdiv::PolyMesh::from_triangles(positions, mesh.faces())?;
    let data_limit = s.limit_positions(&base)?;
    let to_limit = base
        .positions()
        .iter()
        .zip(&data_limit)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0f64, f64::max);
    let refined = subdiv::subdivide(s.as_ref(), &base, levels, subdiv::DEFAULT_MAX_FACES)?;
    let p = s.limit_positions(&refined)?;
    let n = s.limit_normals(&refined)?;
    let mut faces = Vec::with_capacity(2 * refined.num_faces());
    for f in refined.faces() {
        let f: Vec<usize> = f.iter().map(|&v| v as usize).collect();
        for k in 1..f.len().saturating_sub(1) {
            faces.push([f[0], f[k], f[k + 1]]);
        }
    }
    let per_face = faces.len() / mesh.num_faces().max(1);
    let vertices = p
        .iter()
        .zip(&n)
        .map(|(p, n)| surface::mesh::Vertex::without_curvature(*p, *n))
        .collect();
    let mut tess = Tessellation {
        positions: p.clone(),
        normals: n.clone(),
        gaussian: vec![0.0; p.len()],
        mean: vec![0.0; p.len()],
        shapes: vec![nalgebra::Matrix3::zeros(); p.len()],
        directions: Vec::new(),
        patch_of_face: (0..faces.len()).map(|t| t / per_face.max(1)).collect(),
        faces: faces.clone(),
        ..Tessellation::default()
    };
    if let (Ok(mut m), Ok(est)) = (
        surface::Mesh::new(vertices, faces),
        estimate::estimator_by_name(estimate::DEFAULT_ESTIMATOR),
    ) {
        estimate::apply(&mut m, est, true);
        for (i, v) in m.vertices().iter().enumerate() {
            let [a, b] = estimate::principal_curvatures(&v.data.shape, &v.data.n);
            tess.gaussian[i] = a * b;
            tess.mean[i] = 0.5 * (a + b);
            tess.shapes[i] = v.data.shape;
        }
    }
    Ok((tess, to_limit))
}

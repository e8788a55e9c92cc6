//! The colours a written tessellation carries: Gaussian curvature by the testbed's KColor map.

/// A tessellation as a raw mesh for a PLY writer: positions, normals, colours by Gaussian
/// curvature and the curvature in the exported convention ([`crate::output::tessellation_mesh`],
/// which the job uses with the output's own format).
pub fn tessellation_to_raw(tess: &surface::Tessellation) -> meshio::RawMesh {
    crate::output::tessellation_mesh(tess, &meshio::ply::Ply)
}

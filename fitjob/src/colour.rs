//! The colours a written tessellation carries: Gaussian curvature by the testbed's KColor map.

/// A tessellation as a raw mesh for the writers: positions, normals, colours by Gaussian
/// curvature (diverging map, limit the 95th percentile of |K| so a few spikes do not wash the
/// picture out) and the curvatures as properties `gaussian`, `mean`.
pub fn tessellation_to_raw(tess: &surface::Tessellation) -> meshio::RawMesh {
    let mut raw = tess.to_raw();
    let mut abs: Vec<f64> = tess
        .gaussian
        .iter()
        .map(|k| k.abs())
        .filter(|k| k.is_finite())
        .collect();
    abs.sort_by(f64::total_cmp);
    let limit = abs
        .get(abs.len().saturating_sub(1) * 95 / 100)
        .copied()
        .filter(|l| *l > 0.0)
        .unwrap_or(1.0);
    raw.colors = Some(
        tess.gaussian
            .iter()
            .map(|k| render::colors::diverging(*k, limit))
            .collect(),
    );
    raw
}

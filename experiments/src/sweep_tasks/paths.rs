//! Curvature along paths: the sweep's plots of K and H along named curves of a data set's
//! surface, every task's tessellation against the true surface.
//!
//! A path is a plane curve on the surface, given by a signed offset of a point from the path's
//! plane (zero on it) and an abscissa along it:
//!
//! | data set | path | offset | abscissa |
//! |---|---|---|---|
//! | `ring` (torus about z, `R = 1`) | outer equator | `z` (on the outer half, `ρ > R`) | `u = atan2(y, x)` |
//! | `ring` | meridian `u = 0` | `y` (where `x > 0`) | `v = atan2(z, x − R)` around the tube |
//! | `sphere`, `capsule` (axis z) | meridian `y = 0` | `y` (where `x > 0`) | `z` |
//!
//! The tessellation's vertices are binned by abscissa ([`BINS`] bins over the path's range);
//! in each bin the vertex nearest the plane is kept when it lies within [`MAX_OFFSET`] of it
//! (a few tessellation spacings on the unit-sized data sets; a bin with none stays empty). The
//! fitted surface's K and H at those vertices are plotted with the true surface's at the
//! vertex's closest point, in the exported convention (H > 0 on a sphere with outward
//! normals).

use nalgebra::Point3;

/// Abscissa bins per path: 180, two degrees of a turn of the ring.
pub const BINS: usize = 180;

/// Largest distance of a kept vertex from the path's plane, in the data sets' units (the ring's
/// tube radius is 0.4, the sphere's radius 1): a vertex farther away samples another curve.
pub const MAX_OFFSET: f64 = 0.05;

/// Major radius of the ring data set (`mesh::datasets`).
const RING_R: f64 = 1.0;

/// A named curve on a data set's surface.
#[derive(Clone, Copy)]
pub struct Path {
    /// Its name in titles and files (`outer equator`, `meridian`).
    pub name: &'static str,
    /// The abscissa's label.
    pub x_label: &'static str,
    /// The abscissa's range.
    pub range: (f64, f64),
    /// The signed offset of a point from the path's plane, `None` where the point is on the
    /// wrong side (the inner half of the ring, the far half of a meridian plane).
    offset: fn(&Point3<f64>) -> Option<f64>,
    /// The abscissa of a point.
    abscissa: fn(&Point3<f64>) -> f64,
}

/// The paths of data set `name` (none for a mesh file or a data set without one).
pub fn paths_of(name: &str) -> Vec<Path> {
    use std::f64::consts::PI;
    match name {
        "ring" => vec![
            Path {
                name: "outer equator",
                x_label: "u = atan2(y, x) (rad)",
                range: (-PI, PI),
                offset: |p| (p.x.hypot(p.y) > RING_R).then_some(p.z),
                abscissa: |p| p.y.atan2(p.x),
            },
            Path {
                name: "meridian",
                x_label: "v around the tube (rad; 0 outside)",
                range: (-PI, PI),
                offset: |p| (p.x > 0.0).then_some(p.y),
                abscissa: |p| p.z.atan2(p.x - RING_R),
            },
        ],
        "sphere" | "capsule" => vec![Path {
            name: "meridian",
            x_label: "z",
            range: (-f64::INFINITY, f64::INFINITY),
            offset: |p| (p.x > 0.0).then_some(p.y),
            abscissa: |p| p.z,
        }],
        _ => Vec::new(),
    }
}

/// K and H along a path: the fitted surface's and the true surface's, bin by bin.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PathSamples {
    /// Abscissa of each kept vertex, increasing.
    pub x: Vec<f64>,
    /// The fitted surface's Gaussian curvature there.
    pub k: Vec<f64>,
    /// Its mean curvature (exported convention).
    pub h: Vec<f64>,
    /// The true surface's Gaussian curvature at the closest point.
    pub k_true: Vec<f64>,
    /// The true surface's mean curvature there (exported convention).
    pub h_true: Vec<f64>,
}

/// Samples `path` on `tess` (module docs); the truth columns are NaN without a true surface.
pub fn sample(
    tess: &surface::Tessellation,
    truth: Option<&dyn surface::AnalyticSurface>,
    path: &Path,
) -> PathSamples {
    let (mut lo, mut hi) = path.range;
    if !lo.is_finite() || !hi.is_finite() {
        // An open range: the abscissa's extent over the vertices near the plane.
        (lo, hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in &tess.positions {
            if (path.offset)(p).is_some_and(|o| o.abs() <= MAX_OFFSET) {
                let x = (path.abscissa)(p);
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
    }
    let mut best: Vec<Option<(f64, usize)>> = vec![None; BINS];
    let width = (hi - lo) / BINS as f64;
    if width.is_finite() && width > 0.0 {
        for (i, p) in tess.positions.iter().enumerate() {
            let Some(o) = (path.offset)(p).map(f64::abs).filter(|o| *o <= MAX_OFFSET) else {
                continue;
            };
            let b = (((path.abscissa)(p) - lo) / width).floor();
            if !(0.0..BINS as f64).contains(&b) {
                continue;
            }
            let slot = &mut best[b as usize];
            if slot.is_none_or(|(d, _)| o < d) {
                *slot = Some((o, i));
            }
        }
    }
    let mut out = PathSamples::default();
    for (_, i) in best.into_iter().flatten() {
        let p = &tess.positions[i];
        out.x.push((path.abscissa)(p));
        out.k.push(tess.gaussian[i]);
        out.h.push(-tess.mean[i]);
        match truth {
            Some(t) => {
                out.k_true.push(t.gaussian_curvature(p));
                out.h_true.push(-t.mean_curvature(p));
            }
            None => {
                out.k_true.push(f64::NAN);
                out.h_true.push(f64::NAN);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where the truth along the ring's paths is a closed form: `K = cos v / (r (R + r cos v))`
    /// with `r = 0.4` (constant `1/(r (R + r))` on the outer equator). The samples are the
    /// tessellation's vertices, off the torus by the fit's error, so the truth at their closest
    /// points matches the formula at their abscissa to that error (measured 2e-3 here).
    const TRUTH_ON_PATH: f64 = 1e-2;
    /// The RMS of K along the paths of the 32 × 16 ring's Shirman–Séquin fit on chord curves at
    /// s = 8 against the torus (measured 0.41 on the meridian, 0.12 on the outer equator):
    /// chord curves are the workbench's coarsest; the bound says the samples are the fitted
    /// surface's, not another curve's (K there ranges over −4.2 … 1.8).
    const CHORD_FIT_K_RMS: f64 = 0.6;

    #[test]
    fn the_ring_paths_sample_the_torus_curvature() {
        let set = mesh::dataset_by_name("ring", Some(32)).expect("ring");
        let params = surface::InteriorParameters::default();
        let fit = surface::fit::fit(&set.mesh, &curves::Chord, &|_| params).expect("fit");
        let tess = surface::tessellate_fit(&set.mesh, &fit, 8).expect("tessellate");
        let truth: Option<&dyn surface::AnalyticSurface> = Some(set.surface.as_ref());
        let r = 0.4;
        for (k, path) in paths_of("ring").iter().enumerate() {
            let s = sample(&tess, truth, path);
            assert!(
                s.x.len() > BINS / 2,
                "{}: {} bins filled",
                path.name,
                s.x.len()
            );
            assert!(s.x.windows(2).all(|w| w[0] <= w[1]));
            for (x, kt) in s.x.iter().zip(&s.k_true) {
                let v = if k == 0 { 0.0 } else { *x };
                let formula = v.cos() / (r * (RING_R + r * v.cos()));
                assert!(
                    (kt - formula).abs() < TRUTH_ON_PATH,
                    "{}: at {x}: {kt} vs {formula}",
                    path.name
                );
            }
            let rms =
                (s.k.iter()
                    .zip(&s.k_true)
                    .map(|(a, b)| (a - b).powi(2))
                    .sum::<f64>()
                    / s.k.len() as f64)
                    .sqrt();
            assert!(rms < CHORD_FIT_K_RMS, "{}: K RMS {rms}", path.name);
            // H = (1/r + cos v/(R + r cos v))/2 > 0 all round the tube (exported convention).
            assert!(s.h_true.iter().all(|h| *h > 0.0), "{}", path.name);
        }
    }

    #[test]
    fn a_mesh_file_has_no_paths() {
        assert!(paths_of("bunny.ply").is_empty());
    }
}

//! Quality measures of a tessellated surface against the true surface (docs/conventions.md, "Quality
//! measures"): position error (distance of samples to the true surface), normal error (angle to
//! the true normal at the closest point), and Gaussian and mean curvature errors. Every sample
//! (tessellation vertex) counts once.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::datasets::AnalyticSurface;
use crate::tessellate::Tessellation;

/// The median of the finite values (the mean of the two middle ones for an even count), NaN if
/// there are none.
pub fn median(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Errors of a tessellation against an analytic surface (read back from a sweep's records too).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SurfaceErrors {
    /// Number of samples.
    pub samples: usize,
    /// Largest distance from a sample to the true surface.
    pub position_max: f64,
    /// Root-mean-square distance.
    pub position_rms: f64,
    /// Largest angle (degrees) between a sample's normal and the true normal there.
    pub normal_max_degrees: f64,
    /// Root-mean-square normal angle (degrees).
    pub normal_rms_degrees: f64,
    /// Root-mean-square error of the Gaussian curvature.
    pub gaussian_rms: f64,
    /// Largest Gaussian-curvature error.
    pub gaussian_max: f64,
    /// Root-mean-square error of the mean curvature.
    pub mean_rms: f64,
    /// Largest mean-curvature error.
    pub mean_max: f64,
}

fn angle_degrees(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b)).to_degrees()
}

/// Compares every sample of `tess` with the closest point of `truth`.
pub fn compare(tess: &Tessellation, truth: &dyn AnalyticSurface) -> SurfaceErrors {
    let mut e = SurfaceErrors::default();
    let (mut p2, mut n2, mut k2, mut h2) = (0.0, 0.0, 0.0, 0.0);
    for (i, p) in tess.positions.iter().enumerate() {
        let c = truth.closest(p);
        let d = c.signed_distance.abs();
        let a = angle_degrees(&tess.normals[i], &c.data.n);
        let dk = (tess.gaussian[i] - c.gaussian()).abs();
        let dh = (tess.mean[i] - c.mean()).abs();
        e.position_max = e.position_max.max(d);
        e.normal_max_degrees = e.normal_max_degrees.max(a);
        e.gaussian_max = e.gaussian_max.max(dk);
        e.mean_max = e.mean_max.max(dh);
        p2 += d * d;
        n2 += a * a;
        k2 += dk * dk;
        h2 += dh * dh;
        e.samples += 1;
    }
    let n = e.samples.max(1) as f64;
    e.position_rms = (p2 / n).sqrt();
    e.normal_rms_degrees = (n2 / n).sqrt();
    e.gaussian_rms = (k2 / n).sqrt();
    e.mean_rms = (h2 / n).sqrt();
    e
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 2.0, 3.0]), 2.5);
        assert_eq!(median(vec![f64::NAN, 5.0]), 5.0);
        assert!(median(vec![]).is_nan());
    }
    use crate::datasets::Sphere;
    use nalgebra::{Matrix3, Point3};

    /// Closed-form errors agree to rounding.
    const EXACT: f64 = 1e-12;

    fn tess(points: &[Point3<f64>], normals: &[Vector3<f64>], k: f64, h: f64) -> Tessellation {
        Tessellation {
            positions: points.to_vec(),
            normals: normals.to_vec(),
            gaussian: vec![k; points.len()],
            mean: vec![h; points.len()],
            shapes: vec![Matrix3::zeros(); points.len()],
            faces: vec![],
            directions: Vec::new(),
            patch_of_face: vec![],
            welds: 0,
            max_weld_normal_angle: 0.0,
            singular_samples: 0,
            collapsed_faces: 0,
        }
    }

    #[test]
    fn exact_samples_have_zero_error_and_offsets_are_measured() {
        let s = Sphere {
            center: Point3::origin(),
            radius: 1.0,
        };
        let dirs = [Vector3::x(), Vector3::new(0.0, 0.6, 0.8), -Vector3::z()];
        let pts: Vec<_> = dirs.iter().map(|d| Point3::from(*d)).collect();
        let e = compare(&tess(&pts, &dirs, 1.0, -1.0), &s);
        assert_eq!(e.samples, 3);
        assert!(e.position_max < EXACT && e.normal_max_degrees < 1e-10);
        assert!(e.gaussian_rms < EXACT && e.mean_rms < EXACT);
        // Pushed out by 0.1 with the normal tilted by 10°, curvature of a flat patch.
        let tilt = nalgebra::Rotation3::new(Vector3::y() * 10f64.to_radians());
        let pts: Vec<_> = dirs.iter().map(|d| Point3::from(*d * 1.1)).collect();
        let nrm: Vec<_> = dirs.iter().map(|d| tilt * d).collect();
        let e = compare(&tess(&pts, &nrm, 0.0, 0.0), &s);
        assert!((e.position_max - 0.1).abs() < EXACT && (e.position_rms - 0.1).abs() < EXACT);
        assert!(e.normal_max_degrees <= 10.0 + 1e-9 && e.normal_max_degrees > 5.0);
        assert!((e.gaussian_rms - 1.0).abs() < EXACT && (e.mean_rms - 1.0).abs() < EXACT);
    }
}

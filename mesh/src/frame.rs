//! The working frame of a user's mesh: translated and scaled so that its bounding box is
//! centred at the origin with largest side 1, so that coordinates anywhere from 1e-100 to 1e100
//! neither overflow nor underflow in products of lengths (areas, volumes, normal equations);
//! results are mapped back to the file's coordinates for output.
//!
//! A similarity `x_world = center + scale · x_work`: positions map affinely, unit normals and
//! angles not at all, lengths by `scale`, shape tensors (curvatures, 1/length) by `1/scale`,
//! Gaussian curvature by `1/scale²`. Every quantity the scheme builds is similarity-invariant
//! (tested in `surface/tests/suite/shirman_sequin.rs`), so fitting in the working frame and mapping back is
//! the same surface.

use meshio::{BoundingBox, RawMesh};
use nalgebra::{Matrix3, Point3, Vector3};

/// A similarity between the working frame and the file's (world) coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The world point at the working origin (the bounding box's centre).
    pub center: Vector3<f64>,
    /// World length of a working unit (the bounding box's largest side).
    pub scale: f64,
}

/// Why no working frame exists for a mesh.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum FrameError {
    /// The coordinates span more than a double can hold (an extent overflowed).
    #[error(
        "the coordinates span more than a double can represent (extent {0:e}): rescale the file"
    )]
    Overflow(f64),
}

impl Default for Frame {
    fn default() -> Self {
        Frame::identity()
    }
}

impl Frame {
    /// The identity (analytic data sets, already in a working frame).
    pub fn identity() -> Self {
        Frame {
            center: Vector3::zeros(),
            scale: 1.0,
        }
    }

    /// The frame of a set of (finite) points: bounding-box centre and largest side (1 when
    /// the points coincide or there are none).
    pub fn of_points<'a>(
        points: impl IntoIterator<Item = &'a Point3<f64>>,
    ) -> Result<Self, FrameError> {
        let b = BoundingBox::of(points);
        if !b.min.x.is_finite() {
            return Ok(Frame::identity());
        }
        // The centre as min/2 + max/2, which cannot overflow; the extent as max − min, which
        // can.
        let center = b.center().coords;
        let extent = b.extent().max();
        if !extent.is_finite() {
            return Err(FrameError::Overflow(extent));
        }
        Ok(Frame {
            center,
            scale: if extent > 0.0 { extent } else { 1.0 },
        })
    }

    /// World point → working point.
    pub fn to_work(&self, p: &Point3<f64>) -> Point3<f64> {
        Point3::from((p.coords - self.center) / self.scale)
    }

    /// Working point → world point.
    pub fn to_world(&self, p: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.center + p.coords * self.scale)
    }

    /// A raw mesh moved into the working frame (positions; shape tensors times `scale`).
    pub fn raw_to_work(&self, raw: &RawMesh) -> RawMesh {
        let mut out = raw.clone();
        for p in &mut out.positions {
            *p = self.to_work(p);
        }
        if let Some(shapes) = &mut out.shapes {
            for s in shapes {
                *s *= self.scale;
            }
        }
        out
    }

    /// World shape tensor of a working one.
    pub fn shape_to_world(&self, s: &Matrix3<f64>) -> Matrix3<f64> {
        s / self.scale
    }

    /// A mesh's vertex data mapped back to world coordinates in place (positions, shape
    /// tensors; normals are unchanged).
    pub fn mesh_to_world(&self, mesh: &mut crate::mesh::Mesh) {
        for v in mesh.vertices_mut() {
            v.data.p = self.to_world(&v.data.p);
            v.data.shape = self.shape_to_world(&v.data.shape);
        }
    }

    /// Control points mapped back to world coordinates in place.
    pub fn points_to_world(&self, points: &mut [Point3<f64>]) {
        for p in points {
            *p = self.to_world(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extreme_coordinates_get_a_unit_frame() {
        for scale in [1e-100, 1e-3, 1.0, 1e100, 1e300] {
            let pts = [
                Point3::new(1.0, 2.0, 3.0) * scale,
                Point3::new(-1.0, 0.5, 3.5) * scale,
            ];
            let f = Frame::of_points(&pts).unwrap();
            for p in &pts {
                let w = f.to_work(p);
                assert!(w.coords.amax() <= 0.5 + 1e-15, "{scale}: {w}");
                assert!(((f.to_world(&w) - p).norm() / scale) < 1e-15);
            }
        }
        let huge = [Point3::new(-1e308, 0.0, 0.0), Point3::new(1e308, 0.0, 0.0)];
        assert!(matches!(
            Frame::of_points(&huge),
            Err(FrameError::Overflow(_))
        ));
        assert_eq!(Frame::of_points(&[]).unwrap(), Frame::identity());
    }
}

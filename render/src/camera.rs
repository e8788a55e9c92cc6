//! The perspective camera of the shaded pictures, and its framing: the camera that looks at a
//! set of points from given angles as near as keeps every point in the middle
//! [`FRAME_FILL`] of the picture ([`Camera::framing_points`]), also in two passes over points
//! that are not all in memory at once ([`Camera::framing_passes`], [`FrameBox`],
//! [`Camera::framing_box`]).

use nalgebra::{Point3, Vector3};

/// A perspective camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: Point3<f64>,
    /// Point looked at (image centre).
    pub target: Point3<f64>,
    /// Up direction (need not be perpendicular to the view direction).
    pub up: Vector3<f64>,
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
}

/// How much of the picture's width and height [`Camera::framing`] lets the object fill: 90%,
/// a margin of 5% of each side all round (an object drawn to the very edge looks cut off, and a
/// silhouette pixel on the border cannot be told from one outside it).
pub const FRAME_FILL: f64 = 0.9;

/// Vertical field of view of [`Camera::framing`], degrees (a mild perspective: the pictures
/// compare shapes, not depth cues).
pub const FRAME_FOV_DEGREES: f64 = 30.0;

/// Least distance from [`Camera::framing`]'s eye to the box centre, in box half-diagonals:
/// every point of the box is then at least a quarter half-diagonal in front of the eye, even
/// for a box that the field of view alone would let the eye come nearer to (a segment seen end
/// on, a point). Not more: in a wide picture the field of view puts an edge-on disk at 1.3
/// half-diagonals.
pub const MIN_FRAME_DISTANCE: f64 = 1.25;

impl Camera {
    /// A camera looking at the box `[lo, hi]` from azimuth and elevation (degrees, about the z
    /// axis and above the xy plane), for a picture at least as wide as it is tall: the box
    /// (and so everything in it) fills at most [`FRAME_FILL`] of the picture's height and of
    /// its width. [`Camera::framing_aspect`] with aspect 1, which fits the box in the square
    /// `height × height` at the picture's centre: a wider picture only adds room at the sides.
    pub fn framing(lo: Point3<f64>, hi: Point3<f64>, azimuth: f64, elevation: f64) -> Camera {
        Camera::framing_aspect(lo, hi, azimuth, elevation, 1.0)
    }

    /// [`Camera::framing`] for a picture of `aspect = width / height` (a portrait picture,
    /// `aspect < 1`, needs it; a non-finite or non-positive aspect is taken as 1).
    ///
    /// The view direction is fixed by the angles, so only the distance `D` from the box centre
    /// is chosen. A corner with camera-frame offsets `(x, y, z)` from the centre (`z` along the
    /// view) is seen at `x / (D + z)` across and `y / (D + z)` up, and the picture shows up to
    /// `aspect · tan(fov/2)` and `tan(fov/2)`; the corner lies in the filled part iff
    /// `D ≥ |x| / (FRAME_FILL · aspect · tan(fov/2)) − z` and `D ≥ |y| / (FRAME_FILL ·
    /// tan(fov/2)) − z`. `D` is the largest of these over the eight corners (and at least
    /// [`MIN_FRAME_DISTANCE`] half-diagonals, so the whole box is in front of the eye). A
    /// perspective projection maps segments in front of the eye to segments, so the box, the
    /// convex hull of its corners, projects inside the convex hull of their images: inside the
    /// filled rectangle. This fits the box itself, not its bounding sphere (whose silhouette
    /// overstates a flat or elongated box by up to √3, and which the 0.8 shortcut this replaced
    /// let the corners of a square plate, and the ends of a tall cylinder seen from the side,
    /// stick out of: 17.9° off axis in a 15° half-field).
    pub fn framing_aspect(
        lo: Point3<f64>,
        hi: Point3<f64>,
        azimuth: f64,
        elevation: f64,
        aspect: f64,
    ) -> Camera {
        let corners = (0..8).map(|k| {
            Point3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        });
        Camera::fit(lo, hi, corners, azimuth, elevation, aspect)
    }

    /// [`Camera::framing_aspect`] fitted to `points` themselves rather than to the corners of
    /// their bounding box (same centre, the box's; same bounds on the distance, over the
    /// points): the tightest distance at which every point lies in the middle [`FRAME_FILL`]
    /// of the width and the height, so the object fills that much of one of them. A mesh is
    /// inside the convex hull of its vertices, so its vertices suffice. Points that are not
    /// finite are left out; none left frames the unit box at the origin.
    pub fn framing_points(
        points: &[Point3<f64>],
        azimuth: f64,
        elevation: f64,
        aspect: f64,
    ) -> Camera {
        let once = Camera::framing_passes(
            |visit| {
                visit(points);
                Ok::<(), std::convert::Infallible>(())
            },
            azimuth,
            elevation,
            aspect,
        );
        match once {
            Ok(camera) => camera,
            Err(never) => match never {},
        }
    }

    /// [`Camera::framing_points`] for points that are not all in memory at once: `visit` is
    /// called twice and must hand the same points, in the same order, to the function it is
    /// given, in slices of any lengths (a stream's triangles replayed chunk by chunk). The
    /// first pass finds the finite points' bounding box ([`FrameBox`]), the second the
    /// distance ([`Camera::framing_box`]); the arithmetic is that of `framing_points` point by
    /// point, so the camera is the same bit for bit. An error of `visit` ends the framing and
    /// is returned.
    pub fn framing_passes<E>(
        mut visit: impl FnMut(&mut dyn FnMut(&[Point3<f64>])) -> Result<(), E>,
        azimuth: f64,
        elevation: f64,
        aspect: f64,
    ) -> Result<Camera, E> {
        let mut bounds = FrameBox::default();
        visit(&mut |points| bounds.add(points))?;
        Camera::framing_box(&bounds, visit, azimuth, elevation, aspect)
    }

    /// The second pass of [`Camera::framing_passes`], for a caller that gathered the first
    /// pass's box as the points came (a stream read once, then replayed once): `visit` hands
    /// every point once more (only when the box holds a point), `bounds` is the box of all of
    /// them. The camera is [`Camera::framing_points`]' of the points.
    pub fn framing_box<E>(
        bounds: &FrameBox,
        visit: impl FnOnce(&mut dyn FnMut(&[Point3<f64>])) -> Result<(), E>,
        azimuth: f64,
        elevation: f64,
        aspect: f64,
    ) -> Result<Camera, E> {
        let (lo, hi) = (bounds.lo, bounds.hi);
        if lo.x > hi.x {
            return Ok(Camera::framing_aspect(
                Point3::origin(),
                Point3::new(1.0, 1.0, 1.0),
                azimuth,
                elevation,
                aspect,
            ));
        }
        let mut framer = Framer::new(lo, hi, azimuth, elevation, aspect);
        visit(&mut |points| {
            for p in points.iter().filter(|p| finite(p)) {
                framer.add(*p);
            }
        })?;
        Ok(framer.camera())
    }

    /// The camera looking at the centre of `[lo, hi]` from the angles, at the least distance
    /// that keeps every point of `points` in the middle [`FRAME_FILL`] of the picture
    /// ([`Camera::framing_aspect`] derives it).
    fn fit(
        lo: Point3<f64>,
        hi: Point3<f64>,
        points: impl Iterator<Item = Point3<f64>>,
        azimuth: f64,
        elevation: f64,
        aspect: f64,
    ) -> Camera {
        let mut framer = Framer::new(lo, hi, azimuth, elevation, aspect);
        for p in points {
            framer.add(p);
        }
        framer.camera()
    }
}

/// Whether every coordinate of `p` is finite (the points framing takes).
#[inline]
fn finite(p: &Point3<f64>) -> bool {
    p.iter().all(|x| x.is_finite())
}

/// The bounding box of the finite points added so far: the first pass of
/// [`Camera::framing_passes`] (a minimum and a maximum, so neither the order of the points nor
/// their split into slices changes it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameBox {
    lo: Point3<f64>,
    hi: Point3<f64>,
}

impl Default for FrameBox {
    fn default() -> Self {
        FrameBox {
            lo: Point3::from(Vector3::repeat(f64::INFINITY)),
            hi: Point3::from(Vector3::repeat(f64::NEG_INFINITY)),
        }
    }
}

impl FrameBox {
    /// Adds `points` (those not finite are left out).
    pub fn add(&mut self, points: &[Point3<f64>]) {
        for p in points.iter().filter(|p| finite(p)) {
            self.lo = self.lo.inf(p);
            self.hi = self.hi.sup(p);
        }
    }

    /// The box's corners, `None` while no finite point was added.
    pub fn corners(&self) -> Option<(Point3<f64>, Point3<f64>)> {
        (self.lo.x <= self.hi.x).then_some((self.lo, self.hi))
    }
}

/// [`Camera::fit`] point by point: the view frame of the angles, and the least distance so far
/// that keeps every point added in the middle [`FRAME_FILL`] of the picture.
struct Framer {
    centre: Point3<f64>,
    dir: Vector3<f64>,
    up: Vector3<f64>,
    r: Vector3<f64>,
    u: Vector3<f64>,
    f: Vector3<f64>,
    tx: f64,
    ty: f64,
    distance: f64,
}

impl Framer {
    fn new(lo: Point3<f64>, hi: Point3<f64>, azimuth: f64, elevation: f64, aspect: f64) -> Framer {
        let centre = nalgebra::center(&lo, &hi);
        let radius = (hi - lo).norm() * 0.5;
        let (az, el) = (azimuth.to_radians(), elevation.to_radians());
        let dir = Vector3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let up = if el.cos() < 1e-3 {
            Vector3::y()
        } else {
            Vector3::z()
        };
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        // The frame the rasterizer (`crate::shade`'s `View::new`) builds for this camera.
        let f = -dir;
        let r = f.cross(&up).normalize();
        let u = r.cross(&f);
        let ty = FRAME_FILL * (FRAME_FOV_DEGREES.to_radians() * 0.5).tan();
        let tx = ty * aspect;
        Framer {
            centre,
            dir,
            up,
            r,
            u,
            f,
            tx,
            ty,
            distance: MIN_FRAME_DISTANCE * radius,
        }
    }

    #[inline]
    fn add(&mut self, p: Point3<f64>) {
        let q = p - self.centre;
        let (x, y, z) = (q.dot(&self.r), q.dot(&self.u), q.dot(&self.f));
        self.distance = self
            .distance
            .max(x.abs() / self.tx - z)
            .max(y.abs() / self.ty - z);
    }

    fn camera(self) -> Camera {
        let mut distance = self.distance;
        if !(distance > 0.0 && distance.is_finite()) {
            // A point (or a box that is not finite): any distance frames it.
            distance = 1.0;
        }
        Camera {
            eye: self.centre + self.dir * distance,
            target: self.centre,
            up: self.up,
            fov_y_degrees: FRAME_FOV_DEGREES,
        }
    }
}

//! [`BoundingBox`]: the one axis-aligned bounding box of the workbench (corners, sides,
//! centre), with its diagonal [`bounding_size`], the model size relative tolerances are
//! measured against.
//!
//! It lives here, in the lowest crate of the mesh side, because everything that holds
//! positions depends on this crate: `mesh` for its sizes and working frame (and re-exporting
//! [`bounding_size`] as `mesh::mesh::bounding_size`), `surface` for the weld and the
//! tessellation, `experiments` (and the testbed) for framing pictures. One definition, so that
//! every box is computed the same way.
//!
//! The corners are exact (comparisons only, no arithmetic), compared with `<` and `>`: a NaN
//! coordinate is ignored (it compares false), as `f64::min` and `f64::max` ignore it, where a
//! fold of nalgebra's `inf`/`sup` would take the NaN and then forget every point before it;
//! among equal coordinates the first point's is kept, so even the sign of a zero corner is
//! fixed by the order of the points (`f64::min` leaves it unspecified). For points without NaN
//! the corners are bit for bit those of the `inf`/`sup` fold, and those of
//! `f64::min`/`f64::max` up to the sign of a zero.

use nalgebra::{Point3, Vector3};

/// The smallest axis-aligned box holding some points: the componentwise minimum and maximum.
/// [`BoundingBox::EMPTY`] (no point) has `min = +∞` and `max = −∞`, the identity of
/// [`BoundingBox::union`] and of [`BoundingBox::include`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingBox {
    /// The smallest coordinates.
    pub min: Point3<f64>,
    /// The largest coordinates.
    pub max: Point3<f64>,
}

impl Default for BoundingBox {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl BoundingBox {
    /// The box of no point.
    pub const EMPTY: BoundingBox = BoundingBox {
        min: Point3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY),
        max: Point3::new(f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
    };

    /// The box of `points` ([`BoundingBox::EMPTY`] for none).
    pub fn of<'a>(points: impl IntoIterator<Item = &'a Point3<f64>>) -> Self {
        let mut b = Self::EMPTY;
        for p in points {
            b.include(p);
        }
        b
    }

    /// The box of the points whose coordinates are all finite (one infinite or NaN coordinate
    /// leaves its whole point out).
    pub fn of_finite<'a>(points: impl IntoIterator<Item = &'a Point3<f64>>) -> Self {
        Self::of(
            points
                .into_iter()
                .filter(|p| p.iter().all(|c| c.is_finite())),
        )
    }

    /// Grows the box to hold `p` (a NaN coordinate is ignored).
    pub fn include(&mut self, p: &Point3<f64>) {
        for k in 0..3 {
            if p[k] < self.min[k] {
                self.min[k] = p[k];
            }
            if p[k] > self.max[k] {
                self.max[k] = p[k];
            }
        }
    }

    /// The box of both boxes' points (the componentwise extremes of their corners, compared
    /// as in [`BoundingBox::include`]).
    pub fn union(&self, other: &BoundingBox) -> BoundingBox {
        let mut b = *self;
        for k in 0..3 {
            if other.min[k] < b.min[k] {
                b.min[k] = other.min[k];
            }
            if other.max[k] > b.max[k] {
                b.max[k] = other.max[k];
            }
        }
        b
    }

    /// Whether the box holds no point (on some axis, `min > max`).
    pub fn is_empty(&self) -> bool {
        (0..3).any(|k| self.min[k] > self.max[k])
    }

    /// `max − min`, the sides' lengths (zero for the empty box).
    pub fn extent(&self) -> Vector3<f64> {
        if self.is_empty() {
            Vector3::zeros()
        } else {
            self.max - self.min
        }
    }

    /// The length of the diagonal, `|max − min|` (0 for the empty box): the model size.
    pub fn diagonal(&self) -> f64 {
        self.extent().norm()
    }

    /// The centre, `min/2 + max/2` (which cannot overflow, unlike `(min + max)/2`).
    pub fn center(&self) -> Point3<f64> {
        Point3::from(self.min.coords * 0.5 + self.max.coords * 0.5)
    }
}

/// The diagonal of the bounding box of `points` (0 for none): the model size relative
/// tolerances are measured against. [`BoundingBox::of`] then [`BoundingBox::diagonal`].
pub fn bounding_size<'a>(points: impl IntoIterator<Item = &'a Point3<f64>>) -> f64 {
    BoundingBox::of(points).diagonal()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64, z: f64) -> Point3<f64> {
        Point3::new(x, y, z)
    }

    #[test]
    fn corners_are_the_componentwise_extremes() {
        let pts = [p(1.0, -2.0, 0.5), p(-3.0, 4.0, 0.25), p(2.0, 0.0, -1.0)];
        let b = BoundingBox::of(&pts);
        assert_eq!(b.min, p(-3.0, -2.0, -1.0));
        assert_eq!(b.max, p(2.0, 4.0, 0.5));
        assert_eq!(b.extent(), Vector3::new(5.0, 6.0, 1.5));
        // √(25 + 36 + 2.25) = √63.25.
        assert_eq!(b.diagonal(), 63.25f64.sqrt());
        assert_eq!(bounding_size(&pts), 63.25f64.sqrt());
        assert_eq!(b.center(), p(-0.5, 1.0, -0.25));
        // A 3-4-0 box: diagonal exactly 5.
        assert_eq!(bounding_size(&[p(0.0, 0.0, 7.0), p(3.0, 4.0, 7.0)]), 5.0);
    }

    #[test]
    fn empty_box_and_unions() {
        let e = BoundingBox::of(&[]);
        assert_eq!(e, BoundingBox::EMPTY);
        assert!(e.is_empty());
        assert_eq!((e.diagonal(), bounding_size(&[])), (0.0, 0.0));
        let one = BoundingBox::of(&[p(1.0, 2.0, 3.0)]);
        assert!(!one.is_empty());
        assert_eq!((one.min, one.max), (p(1.0, 2.0, 3.0), p(1.0, 2.0, 3.0)));
        assert_eq!(one.diagonal(), 0.0);
        let two = BoundingBox::of(&[p(-1.0, 5.0, 3.0)]);
        let u = one.union(&two);
        assert_eq!((u.min, u.max), (p(-1.0, 2.0, 3.0), p(1.0, 5.0, 3.0)));
        assert_eq!(e.union(&one), one);
        assert_eq!(one.union(&e), one);
        // The union is the box of all the points.
        assert_eq!(u, BoundingBox::of(&[p(1.0, 2.0, 3.0), p(-1.0, 5.0, 3.0)]));
    }

    #[test]
    fn nan_is_ignored_infinities_kept_or_left_out() {
        let pts = [p(0.0, 0.0, 0.0), p(f64::NAN, 1.0, 0.0), p(1.0, 1.0, 1.0)];
        let b = BoundingBox::of(&pts);
        assert_eq!((b.min, b.max), (p(0.0, 0.0, 0.0), p(1.0, 1.0, 1.0)));
        // Whatever the order of the points.
        let b = BoundingBox::of(&[pts[1], pts[2], pts[0]]);
        assert_eq!((b.min, b.max), (p(0.0, 0.0, 0.0), p(1.0, 1.0, 1.0)));
        let far = [p(0.0, 0.0, 0.0), p(f64::INFINITY, 0.0, 0.0)];
        assert_eq!(bounding_size(&far), f64::INFINITY);
        let f = BoundingBox::of_finite(&far);
        assert_eq!((f.min, f.max, f.diagonal()), (far[0], far[0], 0.0));
        assert!(BoundingBox::of_finite(&[p(f64::NAN, 0.0, 0.0)]).is_empty());
    }

    /// Among equal coordinates the first point's is kept: the sign of a zero corner is fixed.
    #[test]
    fn ties_keep_the_first_point() {
        let b = BoundingBox::of(&[p(-0.0, 0.0, 1.0), p(0.0, -0.0, 1.0)]);
        assert!(b.min.x.is_sign_negative() && b.max.x.is_sign_negative());
        assert!(b.min.y.is_sign_positive() && b.max.y.is_sign_positive());
    }

    /// The corners are nalgebra's `inf`/`sup` fold's, bit for bit, on points without NaN.
    #[test]
    fn same_corners_as_nalgebra_inf_sup() {
        let mut r = rng::SplitMix64::new(5);
        let mut next = || r.uniform(-0.5, 0.5);
        let pts: Vec<Point3<f64>> = (0..500).map(|_| p(next(), next(), next())).collect();
        let (mut lo, mut hi) = (BoundingBox::EMPTY.min, BoundingBox::EMPTY.max);
        for q in &pts {
            lo = lo.inf(q);
            hi = hi.sup(q);
        }
        let b = BoundingBox::of(&pts);
        assert_eq!((b.min, b.max), (lo, hi));
        assert_eq!(b.diagonal().to_bits(), (hi - lo).norm().to_bits());
    }
}

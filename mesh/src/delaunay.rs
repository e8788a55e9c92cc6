//! The Delaunay triangulation of points in the plane, by Bowyer–Watson insertion (Bowyer, and
//! Watson, The Computer Journal 24 (1981)): a super-triangle holding every point; each point in
//! turn removes the triangles whose circumcircle holds it (the cavity, a star-shaped polygon
//! around it) and is joined to the cavity's boundary edges; the triangles touching the
//! super-triangle are dropped at the end. `O(n²)` with the linear search for the cavity, for
//! the few thousand points of the test data sets ([`MAX_POINTS`]).
//!
//! The in-circle test is the sign of the lifted 3 × 3 determinant on coordinates relative to
//! the query point, in `f64`; points in general position (the seeded scattered samplings) never
//! meet its rounding. Triangles are counter-clockwise.

use nalgebra::Vector2;

/// The most points [`delaunay`] takes (its cost is quadratic).
pub const MAX_POINTS: usize = 20_000;

/// Why no triangulation was made.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum DelaunayError {
    /// Fewer than three points, or all on one line.
    #[error("{0} points do not span a triangle")]
    Degenerate(usize),
    /// More than [`MAX_POINTS`].
    #[error("{0} points: more than the {MAX_POINTS} the quadratic insertion takes")]
    TooMany(usize),
    /// A coordinate is not finite.
    #[error("point {0} has a non-finite coordinate")]
    NonFinite(usize),
}

fn orient(a: &Vector2<f64>, b: &Vector2<f64>, c: &Vector2<f64>) -> f64 {
    (b - a).perp(&(c - a))
}

/// Whether `d` lies strictly inside the circumcircle of the counter-clockwise `(a, b, c)`.
fn in_circle(a: &Vector2<f64>, b: &Vector2<f64>, c: &Vector2<f64>, d: &Vector2<f64>) -> bool {
    let (a, b, c) = (a - d, b - d, c - d);
    let det = a.norm_squared() * b.perp(&c) - b.norm_squared() * a.perp(&c)
        + c.norm_squared() * a.perp(&b);
    det > 0.0
}

/// The Delaunay triangles of `points`, counter-clockwise, as indices into `points`.
pub fn delaunay(points: &[Vector2<f64>]) -> Result<Vec<[usize; 3]>, DelaunayError> {
    let n = points.len();
    if n > MAX_POINTS {
        return Err(DelaunayError::TooMany(n));
    }
    if let Some(i) = points.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(DelaunayError::NonFinite(i));
    }
    if n < 3 {
        return Err(DelaunayError::Degenerate(n));
    }
    let (mut lo, mut hi) = (points[0], points[0]);
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let size = (hi - lo).max().max(f64::MIN_POSITIVE);
    let mid = (lo + hi) / 2.0;
    // A super-triangle far outside: its circumcircles must not reach back into the hull's
    // triangles' decisions more than rounding does.
    let big = 1e3 * size;
    let mut pts: Vec<Vector2<f64>> = points.to_vec();
    pts.push(mid + Vector2::new(-big, -big));
    pts.push(mid + Vector2::new(big, -big));
    pts.push(mid + Vector2::new(0.0, big));
    let mut tris: Vec<[usize; 3]> = vec![[n, n + 1, n + 2]];
    for i in 0..n {
        let p = pts[i];
        let (bad, keep): (Vec<[usize; 3]>, Vec<[usize; 3]>) = tris
            .iter()
            .partition(|t| in_circle(&pts[t[0]], &pts[t[1]], &pts[t[2]], &p));
        // The cavity's boundary: edges of bad triangles not shared with another bad one.
        let mut boundary: Vec<[usize; 2]> = Vec::new();
        for t in &bad {
            for k in 0..3 {
                let e = [t[k], t[(k + 1) % 3]];
                let shared = bad
                    .iter()
                    .any(|u| u != t && (0..3).any(|m| u[m] == e[1] && u[(m + 1) % 3] == e[0]));
                if !shared {
                    boundary.push(e);
                }
            }
        }
        tris = keep;
        tris.extend(boundary.into_iter().map(|[a, b]| [a, b, i]));
    }
    tris.retain(|t| t.iter().all(|&v| v < n) && orient(&pts[t[0]], &pts[t[1]], &pts[t[2]]) > 0.0);
    if tris.is_empty() {
        return Err(DelaunayError::Degenerate(n));
    }
    Ok(tris)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_empty_circle_property_holds_and_the_hull_is_covered() {
        let mut rng = rng::SplitMix64::new(7);
        let mut pts = vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(1.0, 1.0),
            Vector2::new(0.0, 1.0),
        ];
        for _ in 0..200 {
            pts.push(Vector2::new(rng.next_f64(), rng.next_f64()));
        }
        let t = delaunay(&pts).unwrap();
        let area: f64 = t
            .iter()
            .map(|f| 0.5 * orient(&pts[f[0]], &pts[f[1]], &pts[f[2]]))
            .sum();
        assert!((area - 1.0).abs() < 1e-12, "the unit square's hull: {area}");
        for f in &t {
            for (i, p) in pts.iter().enumerate() {
                if !f.contains(&i) {
                    assert!(!in_circle(&pts[f[0]], &pts[f[1]], &pts[f[2]], p));
                }
            }
        }
        // Euler: a triangulated disc with V points, h of them on the hull, has 2V − h − 2 faces.
        assert_eq!(t.len(), 2 * pts.len() - 4 - 2);
    }

    #[test]
    fn degenerate_input_is_an_error() {
        assert!(delaunay(&[Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)]).is_err());
        let line: Vec<_> = (0..5).map(|i| Vector2::new(i as f64, 0.0)).collect();
        assert!(delaunay(&line).is_err());
    }
}

//! Welding points by position within a tolerance: the one weld of the workbench.
//!
//! [`PositionWeld`] is a spatial hash of the points kept so far, cells twice the tolerance, so
//! a query looks at eight cells and compares exact distances there: a point joins the nearest
//! kept point within the tolerance, or is kept itself. It is O(1) per point for points that
//! are not piled into one cell (the tolerance is a tiny fraction of the model size: see
//! [`crate::tessellate::WELD_RELATIVE`]).
//!
//! [`crate::tessellate::tessellate`] welds patch boundary samples with it; [`weld_triangles`]
//! welds a triangle soup (the testbed's `to-mesh`, whose triangles come one by one from a
//! record stream), and [`crate::patch_g1`] matches patch corners with it.

use meshio::hash::FxHashMap;
use meshio::BoundingBox;
use nalgebra::Point3;

use crate::tessellate::WELD_RELATIVE;

/// Kept points by grid cell, hashed with the workbench's one fast hasher (`meshio::hash`,
/// unseeded): the cells are small integer triples from our own samples, not adversarial keys,
/// and SipHash cost a quarter of a tessellation. Only looked up, never iterated, so the weld
/// does not depend on the hash values.
type CellMap = FxHashMap<[i64; 3], Vec<usize>>;

/// A spatial hash of kept points for welding within an absolute tolerance (module docs). It
/// stores indices; the positions live in the caller's list, passed to [`PositionWeld::find`].
pub struct PositionWeld {
    cell: f64,
    tol: f64,
    grid: CellMap,
}

impl PositionWeld {
    /// A weld joining points at most `tolerance` apart (at least the smallest positive
    /// number: a zero or NaN tolerance welds coincident points only).
    pub fn new(tolerance: f64) -> Self {
        let tol = tolerance.max(f64::MIN_POSITIVE);
        PositionWeld {
            cell: 2.0 * tol,
            tol,
            grid: CellMap::default(),
        }
    }

    /// The tolerance for points spread over a model of diagonal `size`:
    /// [`WELD_RELATIVE`] times it.
    pub fn relative(size: f64) -> Self {
        Self::new(WELD_RELATIVE * size)
    }

    /// The absolute tolerance.
    pub fn tolerance(&self) -> f64 {
        self.tol
    }

    fn key(&self, p: &Point3<f64>) -> [i64; 3] {
        [p.x, p.y, p.z].map(|c| (c / self.cell).floor() as i64)
    }

    /// The kept point nearest to `p` within the tolerance (`positions` holds the kept points'
    /// coordinates by index), if any.
    pub fn find(&self, p: &Point3<f64>, positions: &[Point3<f64>]) -> Option<usize> {
        let k = self.key(p);
        // The cell is twice the tolerance, so the ball of radius `tol` around `p` meets, along
        // each axis, only `p`'s cell and the neighbour on the side of the nearer face: eight
        // cells, not twenty-seven.
        let side = |c: f64| {
            let f = c / self.cell;
            if f - f.floor() < 0.5 {
                -1
            } else {
                1
            }
        };
        let (sx, sy, sz) = (side(p.x), side(p.y), side(p.z));
        let mut best: Option<(f64, usize)> = None;
        for dx in [0, sx] {
            for dy in [0, sy] {
                for dz in [0, sz] {
                    let Some(list) = self.grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) else {
                        continue;
                    };
                    for &i in list {
                        let Some(q) = positions.get(i) else {
                            continue;
                        };
                        let d = (q - p).norm();
                        if d <= self.tol && best.is_none_or(|(bd, _)| d < bd) {
                            best = Some((d, i));
                        }
                    }
                }
            }
        }
        best.map(|(_, i)| i)
    }

    /// Keeps point `i` at `p`.
    pub fn insert(&mut self, p: &Point3<f64>, i: usize) {
        let k = self.key(p);
        self.grid.entry(k).or_default().push(i);
    }

    /// The index of the kept point `p` welds to, or `p` kept (appended to `positions`):
    /// `(index, welded)`.
    pub fn weld(&mut self, p: Point3<f64>, positions: &mut Vec<Point3<f64>>) -> (usize, bool) {
        if let Some(i) = self.find(&p, positions) {
            return (i, true);
        }
        let i = positions.len();
        positions.push(p);
        self.insert(&p, i);
        (i, false)
    }
}

/// The diagonal of the bounding box of the finite points (0 when there are none): the model
/// size tolerances are relative to, not made infinite or NaN by one bad coordinate.
pub fn finite_size<'a>(points: impl IntoIterator<Item = &'a Point3<f64>>) -> f64 {
    BoundingBox::of_finite(points).diagonal()
}

/// A triangle soup welded by position ([`weld_triangles`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WeldedTriangles {
    /// The welded vertices' positions (each the first corner welded there).
    pub positions: Vec<Point3<f64>>,
    /// For each welded vertex, the corner it came from (`3 × triangle + corner`).
    pub source: Vec<usize>,
    /// The triangles kept, as welded vertex indices.
    pub faces: Vec<[usize; 3]>,
    /// For each triangle kept, its index in the input.
    pub face_source: Vec<usize>,
    /// Corners merged into an existing vertex.
    pub welds: usize,
    /// Triangles dropped because welding made two of their corners one vertex.
    pub collapsed: usize,
    /// The tolerance used (absolute).
    pub tolerance: f64,
}

/// Welds the corners of `triangles` (three positions each) with [`PositionWeld::relative`]
/// over the finite corners' bounding box, in order: the first corner at a place becomes the
/// vertex. Triangles whose corners weld together are dropped and counted, as
/// [`crate::tessellate::tessellate`] drops them.
pub fn weld_triangles(triangles: &[[Point3<f64>; 3]]) -> WeldedTriangles {
    let size = finite_size(triangles.iter().flatten());
    let mut weld = PositionWeld::relative(size);
    let mut out = WeldedTriangles {
        tolerance: weld.tolerance(),
        ..WeldedTriangles::default()
    };
    out.faces.reserve(triangles.len());
    for (ti, t) in triangles.iter().enumerate() {
        let mut f = [0usize; 3];
        for (c, (slot, p)) in f.iter_mut().zip(t).enumerate() {
            let (i, welded) = weld.weld(*p, &mut out.positions);
            if welded {
                out.welds += 1;
            } else {
                out.source.push(3 * ti + c);
            }
            *slot = i;
        }
        let [a, b, c] = f;
        if a == b || b == c || c == a {
            out.collapsed += 1;
        } else {
            out.faces.push(f);
            out.face_source.push(ti);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Corners off by rounding (1e-16 relative) weld; corners a sampling step apart do not.
    #[test]
    fn near_corners_weld_distinct_ones_do_not() {
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let e = 1e-16;
        let tris = [
            [p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)],
            [p(1.0 + e, 0.0), p(1.0, 1.0), p(0.0, 1.0 - e)],
            // Collapsed by the weld: two corners within the tolerance.
            [p(0.0, 0.0), p(1e-12, 0.0), p(0.5, 0.5)],
        ];
        let w = weld_triangles(&tris);
        assert_eq!(w.positions.len(), 5);
        assert_eq!(w.faces, vec![[0, 1, 2], [1, 3, 2]]);
        assert_eq!(w.face_source, vec![0, 1]);
        assert_eq!(w.welds, 4);
        assert_eq!(w.collapsed, 1);
        assert_eq!(w.source, vec![0, 1, 2, 4, 8]);
        // A NaN corner welds to nothing and does not poison the tolerance.
        let bad = [[p(f64::NAN, 0.0), p(1.0, 0.0), p(0.0, 1.0)]];
        let w = weld_triangles(&bad);
        assert_eq!(w.positions.len(), 3);
        assert!(w.tolerance > 0.0 && w.tolerance < 1e-8);
    }
}

//! Welding coincident vertices: the first rule of [`crate::repair`].
//!
//! Files often store one surface as pieces that share positions but not vertices: the Utah
//! teapot's 32 Bézier patches tessellated one by one, an STL or a per-face export, parts glued
//! by a modeller. Their faces are then disconnected at every seam, which a fit treats as
//! boundary: the patches on either side do not join with G1, and every seam shows as a crease.
//!
//! The rule: vertices at **exactly** the same position (the same `f64` coordinates, `−0.0` and
//! `0.0` taken as one) are the same vertex: each face corner is renumbered to the first vertex
//! of its group. Exactness, not a distance, so two vertices a file keeps apart on purpose a
//! rounding away stay apart, and nothing depends on a tolerance or on the order of the file.
//! A group whose members carry data of their own that disagree (file normals more than
//! [`meshio::obj::NORMAL_AGREEMENT`] apart: a sharp edge written as split normals; or
//! different shape tensors) is left apart and counted: the file's data says those are
//! different sides. Faces that then repeat a vertex (a sliver whose two corners coincide) are
//! skipped by the next rule, and the orientation, non-manifold and component rules that follow
//! see the joined mesh.
//!
//! The groups are found by sorting the vertex indices by position (`O(n log n)`, in parallel,
//! four bytes a vertex beside the positions).

use meshio::RawMesh;
use rayon::prelude::*;

/// What to do with vertices at the same position.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WeldRule {
    /// Weld vertices at exactly the same position whose data agree (module docs).
    #[default]
    Coincident,
    /// Keep every vertex of the file.
    Never,
}

/// What [`weld_map`] found.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Welded {
    /// For each file vertex, the vertex it is welded into (itself when it is the first of its
    /// group or not welded). Empty when nothing was welded.
    pub map: Vec<usize>,
    /// Vertices welded into another.
    pub welded: usize,
    /// Groups of coincident vertices left apart because their data disagree.
    pub kept_apart: usize,
}

/// The bits of a coordinate with `−0.0` as `0.0` (other values, NaN included, by their bits).
fn key(x: f64) -> u64 {
    if x == 0.0 {
        0
    } else {
        x.to_bits()
    }
}

/// Whether two file vertices' own data agree (module docs).
fn data_agree(raw: &RawMesh, a: usize, b: usize) -> bool {
    if let Some(n) = &raw.normals {
        if let (Some(na), Some(nb)) = (n.get(a), n.get(b)) {
            let angle = na.cross(nb).norm().atan2(na.dot(nb));
            if angle.is_nan() || angle > meshio::obj::NORMAL_AGREEMENT {
                return false;
            }
        }
    }
    if let Some(s) = &raw.shapes {
        if s.get(a) != s.get(b) {
            return false;
        }
    }
    true
}

/// The weld of `raw`'s vertices by `rule` (module docs).
pub fn weld_map(raw: &RawMesh, rule: WeldRule) -> Welded {
    let n = raw.positions.len();
    if rule == WeldRule::Never || n < 2 || n > u32::MAX as usize {
        return Welded::default();
    }
    let k = |i: u32| {
        let p = raw.positions[i as usize];
        [key(p.x), key(p.y), key(p.z)]
    };
    let mut order: Vec<u32> = (0..n as u32).collect();
    // Ties by index: each group's first member comes first.
    order.par_sort_unstable_by(|&a, &b| k(a).cmp(&k(b)).then(a.cmp(&b)));
    let mut out = Welded::default();
    let mut i = 0;
    while i < n {
        let mut j = i + 1;
        while j < n && k(order[j]) == k(order[i]) {
            j += 1;
        }
        if j - i > 1 {
            let first = order[i] as usize;
            let group = &order[i..j];
            if group.iter().all(|&v| data_agree(raw, first, v as usize)) {
                if out.map.is_empty() {
                    out.map = (0..n).collect();
                }
                for &v in &group[1..] {
                    out.map[v as usize] = first;
                }
                out.welded += j - i - 1;
            } else {
                out.kept_apart += 1;
            }
        }
        i = j;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Point3, Vector3};

    #[test]
    fn coincident_vertices_are_welded_into_the_first() {
        let p = |x: f64| Point3::new(x, 0.0, 0.0);
        let raw = RawMesh::from_triangles(vec![p(1.0), p(0.0), p(1.0), p(-0.0), p(2.0)], &[]);
        let w = weld_map(&raw, WeldRule::Coincident);
        assert_eq!(w.map, vec![0, 1, 0, 1, 4]);
        assert_eq!((w.welded, w.kept_apart), (2, 0));
        assert_eq!(weld_map(&raw, WeldRule::Never), Welded::default());
    }

    #[test]
    fn split_normals_keep_vertices_apart() {
        let mut raw = RawMesh::from_triangles(vec![Point3::origin(); 2], &[]);
        raw.normals = Some(vec![Vector3::z(), Vector3::x()]);
        let w = weld_map(&raw, WeldRule::Coincident);
        assert!(w.map.is_empty());
        assert_eq!((w.welded, w.kept_apart), (0, 1));
    }
}

//! The fallback macro-patch of a face the split-domain construction cannot fit: C0, meeting
//! every neighbour exactly along the shared boundary curves, G1 not promised.
//!
//! Used where [`crate::shirman_sequin::macro_patch`] fails (a corner cross vector that does not
//! point into the patch, a zero end derivative, non-finite points) and for faces of zero area.
//! Same layout as the regular macro-patch: three quartics over the centroid split, in docs/conventions.md
//! row order, sub-patch `e` over `(V_e, V_{e+1}, S)`.
//!
//! # Construction
//!
//! * Row 0 of sub-patch `e` is the face's exterior cubic `e`, degree-raised: the same curve the
//!   neighbour uses, so the surface stays C0 (watertight) across every edge.
//! * The split point is the mean of the six inner control points of the three cubics,
//!   `S = Σ_e (E¹_e + E²_e) / 6` (the centroid for straight edges at thirds).
//! * The interior boundaries `V_i → S` are straight: quartic points `V_i + (m/4)(S − V_i)`,
//!   `m = 1, 2, 3`, shared by the two sub-patches on them (C0 inside).
//! * The remaining three points of each quartic, `C¹ = b₂₁₁`, `C² = b₁₂₁`, `N = b₁₁₂`, make the
//!   net discretely harmonic: each is the mean of its six neighbours in the net. Writing `A`,
//!   `B`, `C'` for the sums of their known neighbours,
//!   `A = I¹_a + q₁ + q₂ + I²_a`, `B = I¹_b + q₂ + q₃ + I²_b`, `C' = I²_a + I²_b + I³_a + I³_b`,
//!   the equations `6C¹ − C² − N = A`, `−C¹ + 6C² − N = B`, `−C¹ − C² + 6N = C'` have the
//!   solution `N = (A + B + 5C')/28`, `C¹ + C² = 6N − C'`, `C¹ − C² = (A − B)/7`.
//!
//! A linear function has the six-neighbour mean property on the triangular grid, so the
//! construction has linear precision: a flat face with straight edges gets the flat patch
//! (tested).

use curves::CubicBez3;
use nalgebra::Point3;

use crate::shirman_sequin::QuarticNet;

fn lerp(a: &Point3<f64>, b: &Point3<f64>, t: f64) -> Point3<f64> {
    a + (b - a) * t
}

/// The fallback macro-patch (module docs) of a face whose exterior cubics are `edges` (`edges[e]`
/// from corner `e` to corner `e + 1`).
pub fn fallback_patch(edges: &[CubicBez3; 3]) -> [QuarticNet; 3] {
    let v: [Point3<f64>; 3] = std::array::from_fn(|i| edges[i].points[0]);
    let inner = edges
        .iter()
        .map(|c| c.points[1].coords + c.points[2].coords)
        .fold(nalgebra::Vector3::zeros(), |a, b| a + b);
    let s = Point3::from(inner / 6.0);
    let i1: [Point3<f64>; 3] = std::array::from_fn(|i| lerp(&v[i], &s, 0.25));
    let i2: [Point3<f64>; 3] = std::array::from_fn(|i| lerp(&v[i], &s, 0.5));
    let i3: [Point3<f64>; 3] = std::array::from_fn(|i| lerp(&v[i], &s, 0.75));
    std::array::from_fn(|e| {
        let (a, b) = (e, (e + 1) % 3);
        let q = edges[e].elevate().points;
        let sum_a = i1[a].coords + q[1].coords + q[2].coords + i2[a].coords;
        let sum_b = i1[b].coords + q[2].coords + q[3].coords + i2[b].coords;
        let sum_c = i2[a].coords + i2[b].coords + i3[a].coords + i3[b].coords;
        let n = (sum_a + sum_b + sum_c * 5.0) / 28.0;
        let plus = n * 6.0 - sum_c;
        let minus = (sum_a - sum_b) / 7.0;
        let c1 = Point3::from((plus + minus) / 2.0);
        let c2 = Point3::from((plus - minus) / 2.0);
        [
            q[0],
            q[1],
            q[2],
            q[3],
            q[4],
            i1[a],
            c1,
            c2,
            i1[b],
            i2[a],
            Point3::from(n),
            i2[b],
            i3[a],
            i3[b],
            s,
        ]
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beztri::index;

    /// Rounding of a few additions and one division per point.
    const EXACT: f64 = 1e-14;

    fn line(a: Point3<f64>, b: Point3<f64>) -> CubicBez3 {
        CubicBez3::new([a, lerp(&a, &b, 1.0 / 3.0), lerp(&a, &b, 2.0 / 3.0), b])
    }

    #[test]
    fn a_flat_face_with_straight_edges_gets_the_flat_patch() {
        let v = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.5),
            Point3::new(0.3, 1.5, 1.0),
        ];
        let edges = [line(v[0], v[1]), line(v[1], v[2]), line(v[2], v[0])];
        let s = Point3::from((v[0].coords + v[1].coords + v[2].coords) / 3.0);
        let nets = fallback_patch(&edges);
        for (e, net) in nets.iter().enumerate() {
            let corners = [v[e], v[(e + 1) % 3], s];
            for k in 0..=4 {
                for i in (0..=4 - k).rev() {
                    let j = 4 - k - i;
                    let want = Point3::from(
                        (corners[0].coords * i as f64
                            + corners[1].coords * j as f64
                            + corners[2].coords * k as f64)
                            / 4.0,
                    );
                    let got = net[index(4, i, j, k)];
                    assert!((got - want).norm() < EXACT, "e {e} ({i},{j},{k})");
                }
            }
        }
    }

    #[test]
    fn the_patch_meets_the_curves_and_itself() {
        let c0 = CubicBez3::new([
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(0.4, -0.1, 0.3),
            Point3::new(0.8, 0.1, 0.2),
            Point3::new(1.0, 0.0, 0.0),
        ]);
        let c1 = CubicBez3::new([
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.9, 0.4, 0.1),
            Point3::new(0.5, 0.9, -0.2),
            Point3::new(0.2, 1.0, 0.0),
        ]);
        let c2 = CubicBez3::new([
            Point3::new(0.2, 1.0, 0.0),
            Point3::new(0.1, 0.6, 0.4),
            Point3::new(-0.1, 0.3, 0.1),
            Point3::new(0.0, 0.0, 0.0),
        ]);
        let edges = [c0, c1, c2];
        let nets = fallback_patch(&edges);
        for e in 0..3 {
            let q = edges[e].elevate().points;
            assert_eq!(&nets[e][..5], &q[..], "row 0 is the exterior curve");
            // Interior boundary V_{e+1} → S: sub-patch e's right side equals sub-patch e+1's
            // left side (the points b_{0,4−k,k} and b_{4−k,0,k}).
            let next = &nets[(e + 1) % 3];
            for k in 0..=4 {
                assert_eq!(nets[e][index(4, 0, 4 - k, k)], next[index(4, 4 - k, 0, k)]);
            }
        }
    }
}

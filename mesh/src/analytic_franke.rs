//! Franke's six test functions (R. Franke, *Scattered data interpolation: tests of some
//! methods*, Math. Comp. 38 (1982) 181–200; first in Naval Postgraduate School report
//! NPS-53-79-003, 1979) with closed-form first and second derivatives, and the graph of one as
//! an [`AnalyticSurface`] for the error measures.
//!
//! # The functions, on `[0, 1]²`
//!
//! ```text
//! F1 (exponential) = ¾ e^{−((9x−2)² + (9y−2)²)/4} + ¾ e^{−(9x+1)²/49 − (9y+1)/10}
//!                  + ½ e^{−((9x−7)² + (9y−3)²)/4} − ⅕ e^{−(9x−4)² − (9y−7)²}
//! F2 (cliff)       = (tanh(9y − 9x) + 1)/9
//! F3 (saddle)      = (1.25 + cos 5.4y) / (6 (1 + (3x − 1)²))
//! F4 (gentle)      = e^{−(81/16) ((x − ½)² + (y − ½)²)} / 3
//! F5 (steep)       = e^{−(81/4) ((x − ½)² + (y − ½)²)} / 3
//! F6 (sphere)      = √(64 − 81 ((x − ½)² + (y − ½)²)) / 9 − ½
//! ```
//!
//! Checked against two independent restatements: the R package `interp`'s `franke.fn` and
//! Renka and Brown's TOMS Algorithm 792 test functions (`tstfn1`/`tstfn2`, which give the
//! first and second partials too); they agree with each other and with the above. Some other
//! restatements are wrong: one drops the minus sign of F1's third exponent, one squares
//! `(9y + 1)` in the second, one turns `−(9y+1)/10` into `+` by a misplaced parenthesis, and
//! one normalizes F2 by `tanh 9 + 1` instead of 9; none of those is used.
//!
//! # Derivatives
//!
//! F1, F4, F5 are sums of `c e^q` with `q` quadratic in `x, y` (F1's second term linear in
//! `y`): `∂(e^q) = q' e^q`, `∂²(e^q) = (q'' + q'q') e^q`. F2 with `t = tanh 9(y − x)`,
//! `s = 1 − t²`: `f_x = −s`, `f_y = s`, `f_xx = f_yy = −18 t s`, `f_xy = 18 t s`. F3 = `A(y)/B(x)`
//! with `A = 1.25 + cos 5.4y`, `B = 6(1 + (3x − 1)²)`: `f_x = −A B'/B²`, `f_y = A'/B`,
//! `f_xx = A (2B'²/B³ − B''/B²)`, `f_xy = −A' B'/B²`, `f_yy = A''/B`. F6 with
//! `s = √(64 − 81 r²)`, `(X, Y) = (x − ½, y − ½)`: `f_x = −9X/s`,
//! `f_xx = −9/s − 729 X²/s³`, `f_xy = −729 X Y/s³` (tested against finite differences).
//!
//! # The graph as a surface
//!
//! `r(x, y) = (x, y, f)`, upward unit normal `n = (−f_x, −f_y, 1)/W`, `W = √(1 + |∇f|²)`, first
//! fundamental form `G = I + ∇f ∇fᵀ`, second `II = Hess f / W` (positive where the graph bends
//! towards `n`, the sign of docs/conventions.md). The world shape tensor is
//! `S = J G⁻¹ II G⁻¹ Jᵀ` with `J = [r_x r_y]`: for a tangent `d = J a`,
//! `dᵀ S d / |d|² = aᵀ II a / aᵀ G a`, the normal curvature, and `S n = 0` (`Jᵀ n = 0`). The
//! principal curvatures are the eigenvalues of `G⁻¹ II`: `H ± √(H² − K)` with
//! `K = det II / det G`, `H = tr(G⁻¹ II)/2`. The closest point of the graph over `[0, 1]²` to a
//! query `q` minimizes `½ |r(x, y) − q|²`: Newton's method on its gradient
//! `(x − q_x + (f − q_z) f_x, y − q_y + (f − q_z) f_y)`, Gauss–Newton where the Hessian is not
//! positive definite, kept in the square.

use nalgebra::{Matrix2, Matrix3, Point3, Vector2, Vector3};

use crate::datasets::{AnalyticSurface, SurfacePoint};
use crate::vertex::VertexData;

/// A function's value with its first and second partial derivatives at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet {
    /// `f`.
    pub f: f64,
    /// `(f_x, f_y)`.
    pub grad: Vector2<f64>,
    /// `[[f_xx, f_xy], [f_xy, f_yy]]`.
    pub hess: Matrix2<f64>,
}

/// One of Franke's six test functions (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Franke {
    /// F1, the exponential: two peaks and a dip on a slope.
    F1,
    /// F2, the cliff: two plateaus joined by a steep rise along `y = x`.
    F2,
    /// F3, the saddle.
    F3,
    /// F4, the gentle Gaussian hill.
    F4,
    /// F5, the steep Gaussian hill.
    F5,
    /// F6, part of a sphere.
    F6,
}

/// `c e^q` with `q`'s value, gradient and Hessian.
fn exp_term(c: f64, q: f64, dq: Vector2<f64>, ddq: Matrix2<f64>) -> Jet {
    let e = c * q.exp();
    Jet {
        f: e,
        grad: dq * e,
        hess: (ddq + dq * dq.transpose()) * e,
    }
}

fn sum(terms: &[Jet]) -> Jet {
    terms.iter().fold(
        Jet {
            f: 0.0,
            grad: Vector2::zeros(),
            hess: Matrix2::zeros(),
        },
        |a, t| Jet {
            f: a.f + t.f,
            grad: a.grad + t.grad,
            hess: a.hess + t.hess,
        },
    )
}

impl Franke {
    /// All six, in order.
    pub const ALL: [Franke; 6] = [
        Franke::F1,
        Franke::F2,
        Franke::F3,
        Franke::F4,
        Franke::F5,
        Franke::F6,
    ];

    /// `F_k` for `k` in `1..=6`.
    pub fn by_number(k: usize) -> Option<Franke> {
        k.checked_sub(1).and_then(|i| Franke::ALL.get(i)).copied()
    }

    /// Its number `k` of `F_k`.
    pub fn number(&self) -> usize {
        Franke::ALL.iter().position(|f| f == self).unwrap_or(0) + 1
    }

    /// Value, gradient and Hessian at `(x, y)`. F6 is defined inside the circle of radius 8/9
    /// about `(½, ½)` (which holds the unit square); outside, its root is taken of at least
    /// `1e-12`, finite.
    pub fn jet(&self, x: f64, y: f64) -> Jet {
        let diag = |a: f64| Matrix2::new(a, 0.0, 0.0, a);
        let (cx, cy) = (x - 0.5, y - 0.5);
        match self {
            Franke::F1 => {
                let (a, b) = (9.0 * x - 2.0, 9.0 * y - 2.0);
                let (c, d) = (9.0 * x - 7.0, 9.0 * y - 3.0);
                let (g, h) = (9.0 * x - 4.0, 9.0 * y - 7.0);
                let e = 9.0 * x + 1.0;
                sum(&[
                    exp_term(
                        0.75,
                        -(a * a + b * b) / 4.0,
                        Vector2::new(-4.5 * a, -4.5 * b),
                        diag(-40.5),
                    ),
                    exp_term(
                        0.75,
                        -e * e / 49.0 - (9.0 * y + 1.0) / 10.0,
                        Vector2::new(-18.0 * e / 49.0, -0.9),
                        Matrix2::new(-162.0 / 49.0, 0.0, 0.0, 0.0),
                    ),
                    exp_term(
                        0.5,
                        -(c * c + d * d) / 4.0,
                        Vector2::new(-4.5 * c, -4.5 * d),
                        diag(-40.5),
                    ),
                    exp_term(
                        -0.2,
                        -g * g - h * h,
                        Vector2::new(-18.0 * g, -18.0 * h),
                        diag(-162.0),
                    ),
                ])
            }
            Franke::F2 => {
                let t = (9.0 * (y - x)).tanh();
                let s = 1.0 - t * t;
                let k = 18.0 * t * s;
                Jet {
                    f: (t + 1.0) / 9.0,
                    grad: Vector2::new(-s, s),
                    hess: Matrix2::new(-k, k, k, -k),
                }
            }
            Franke::F3 => {
                let a = 1.25 + (5.4 * y).cos();
                let (da, dda) = (-5.4 * (5.4 * y).sin(), -29.16 * (5.4 * y).cos());
                let u = 3.0 * x - 1.0;
                let b = 6.0 * (1.0 + u * u);
                let (db, ddb) = (36.0 * u, 108.0);
                let fxx = a * (2.0 * db * db / (b * b * b) - ddb / (b * b));
                let fxy = -da * db / (b * b);
                Jet {
                    f: a / b,
                    grad: Vector2::new(-a * db / (b * b), da / b),
                    hess: Matrix2::new(fxx, fxy, fxy, dda / b),
                }
            }
            Franke::F4 | Franke::F5 => {
                let c = if *self == Franke::F4 {
                    81.0 / 16.0
                } else {
                    81.0 / 4.0
                };
                exp_term(
                    1.0 / 3.0,
                    -c * (cx * cx + cy * cy),
                    Vector2::new(-2.0 * c * cx, -2.0 * c * cy),
                    diag(-2.0 * c),
                )
            }
            Franke::F6 => {
                let s = (64.0 - 81.0 * (cx * cx + cy * cy)).max(1e-24).sqrt();
                let s3 = s * s * s;
                let fxy = -729.0 * cx * cy / s3;
                Jet {
                    f: s / 9.0 - 0.5,
                    grad: Vector2::new(-9.0 * cx / s, -9.0 * cy / s),
                    hess: Matrix2::new(
                        -9.0 / s - 729.0 * cx * cx / s3,
                        fxy,
                        fxy,
                        -9.0 / s - 729.0 * cy * cy / s3,
                    ),
                }
            }
        }
    }
}

/// The graph's data at `(x, y)` from its jet: the point, upward unit normal, shape tensor
/// (module docs) and principal curvatures `κ1 ≤ κ2`.
pub fn graph_data(x: f64, y: f64, jet: &Jet) -> (VertexData, [f64; 2]) {
    let g = jet.grad;
    let w = (1.0 + g.norm_squared()).sqrt();
    let n = Vector3::new(-g.x, -g.y, 1.0) / w;
    let first = Matrix2::identity() + g * g.transpose();
    let second = jet.hess / w;
    let ginv = first.try_inverse().unwrap_or_else(Matrix2::identity);
    let j = nalgebra::Matrix3x2::new(1.0, 0.0, 0.0, 1.0, g.x, g.y);
    let shape: Matrix3<f64> = j * ginv * second * ginv * j.transpose();
    let shape = (shape + shape.transpose()) * 0.5;
    let k = second.determinant() / first.determinant();
    let h = 0.5 * (ginv * second).trace();
    let root = (h * h - k).max(0.0).sqrt();
    (
        VertexData::new(Point3::new(x, y, jet.f), n, shape),
        [h - root, h + root],
    )
}

/// The graph `z = F(x, y)` over `[0, 1]²` (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrankeSurface {
    /// Which function.
    pub function: Franke,
}

/// Newton steps of the closest-point search: quadratic convergence from the query's own
/// `(x, y)` takes a handful for points near the graph; the cap bounds the work for far ones.
const CLOSEST_STEPS: usize = 50;

impl AnalyticSurface for FrankeSurface {
    fn closest(&self, q: &Point3<f64>) -> SurfacePoint {
        let clamp = |v: Vector2<f64>| v.map(|c| c.clamp(0.0, 1.0));
        let mut at = clamp(Vector2::new(q.x, q.y));
        for _ in 0..CLOSEST_STEPS {
            let jet = self.function.jet(at.x, at.y);
            let r = jet.f - q.z;
            let grad = Vector2::new(at.x - q.x, at.y - q.y) + jet.grad * r;
            let gn = Matrix2::identity() + jet.grad * jet.grad.transpose();
            let full = gn + jet.hess * r;
            let hessian = if full.determinant() > 0.0 && full[(0, 0)] > 0.0 {
                full
            } else {
                gn
            };
            let step = hessian
                .try_inverse()
                .map(|h| h * grad)
                .unwrap_or(Vector2::zeros());
            let next = clamp(at - step);
            let moved = (next - at).norm();
            at = next;
            // NaN stops too.
            if moved.partial_cmp(&1e-15) != Some(std::cmp::Ordering::Greater) {
                break;
            }
        }
        let jet = self.function.jet(at.x, at.y);
        let (data, principal) = graph_data(at.x, at.y, &jet);
        SurfacePoint {
            data,
            signed_distance: (q - data.p).dot(&data.n),
            principal,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central differences at step 1e-5 on functions with derivatives up to ~1e3 (F5's
    /// second): truncation ~h² f''' ≈ 1e-7, rounding ~ε/h ≈ 1e-11 relative.
    const FD: f64 = 1e-5;
    const FD_TOL: f64 = 1e-5;

    #[test]
    fn gradients_and_hessians_match_finite_differences() {
        for f in Franke::ALL {
            for (x, y) in [
                (0.1, 0.2),
                (0.5, 0.5),
                (0.73, 0.31),
                (0.9, 0.95),
                (0.33, 0.66),
            ] {
                let j = f.jet(x, y);
                let fd = |dx: f64, dy: f64| f.jet(x + dx, y + dy);
                let gx = (fd(FD, 0.0).f - fd(-FD, 0.0).f) / (2.0 * FD);
                let gy = (fd(0.0, FD).f - fd(0.0, -FD).f) / (2.0 * FD);
                let scale = 1.0 + j.grad.norm();
                assert!(
                    (gx - j.grad.x).abs() < FD_TOL * scale
                        && (gy - j.grad.y).abs() < FD_TOL * scale,
                    "F{} gradient at ({x}, {y})",
                    f.number()
                );
                let hx = (fd(FD, 0.0).grad - fd(-FD, 0.0).grad) / (2.0 * FD);
                let hy = (fd(0.0, FD).grad - fd(0.0, -FD).grad) / (2.0 * FD);
                let hs = 1.0 + j.hess.norm();
                assert!(
                    (hx - j.hess.column(0)).norm() < FD_TOL * hs,
                    "F{} f_x·",
                    f.number()
                );
                assert!(
                    (hy - j.hess.column(1)).norm() < FD_TOL * hs,
                    "F{} f_y·",
                    f.number()
                );
            }
        }
    }

    #[test]
    fn values_match_the_references() {
        // F1(0, 1) = 0.2703372 (SigOptR's example of the same formula, 7 digits); F2 on the
        // diagonal is 1/9; F4, F5 at the centre 1/3; F6 at the centre 8/9 − ½.
        assert!((Franke::F1.jet(0.0, 1.0).f - 0.2703372).abs() < 1e-7);
        assert!((Franke::F2.jet(0.3, 0.3).f - 1.0 / 9.0).abs() < 1e-15);
        assert!((Franke::F3.jet(1.0 / 3.0, 0.0).f - 2.25 / 6.0).abs() < 1e-15);
        assert!((Franke::F4.jet(0.5, 0.5).f - 1.0 / 3.0).abs() < 1e-15);
        assert!((Franke::F5.jet(0.5, 0.5).f - 1.0 / 3.0).abs() < 1e-15);
        assert!((Franke::F6.jet(0.5, 0.5).f - (8.0 / 9.0 - 0.5)).abs() < 1e-15);
    }

    #[test]
    fn the_closest_point_lies_along_the_normal_and_f6_is_a_sphere() {
        let s = FrankeSurface {
            function: Franke::F1,
        };
        for (x, y) in [(0.2, 0.3), (0.6, 0.7), (0.45, 0.15)] {
            let jet = Franke::F1.jet(x, y);
            let (d, _) = graph_data(x, y, &jet);
            let q = d.p + d.n * 0.01;
            let c = s.closest(&q);
            assert!((c.data.p - d.p).norm() < 1e-10);
            assert!((c.signed_distance - 0.01).abs() < 1e-10);
            assert!(d.shape * d.n == Vector3::zeros() || (d.shape * d.n).norm() < 1e-12);
        }
        // F6 is the sphere of radius 8/9 about (½, ½, −½): κ = −9/8 both ways (bending away
        // from the upward normal), K = 81/64.
        let (_, k) = graph_data(0.3, 0.6, &Franke::F6.jet(0.3, 0.6));
        assert!((k[0] + 9.0 / 8.0).abs() < 1e-12 && (k[1] + 9.0 / 8.0).abs() < 1e-12);
    }
}

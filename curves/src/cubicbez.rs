//! Cubic Bézier curves in the plane and in space, and their degree elevation to quartics.
//!
//! `f(t) = Σ_{i=0}^{3} B_i^3(t) P_i` with Bernstein polynomials `B_i^3`. Derivatives
//! (Farin, *Curves and Surfaces for CAGD*, ch. 5):
//! `f'(t) = 3 Σ B_i^2(t) ΔP_i`, `f''(t) = 6 Σ B_i^1(t) Δ²P_i`, `f''' = 6 Δ³P_0`.
//! Signed curvature of a plane curve `κ = (f' × f'')/|f'|³` (2D cross product
//! `a × b = a_x b_y − a_y b_x`; positive when the curve turns left), its arc-length derivative
//! `dκ/ds = [(f' × f''')|f'|² − 3 (f' × f'')(f' · f'')] / |f'|⁶`, and the curvature vector of a
//! space curve `k = (f' × f'') × f' / |f'|⁴`.

use nalgebra::{Point, SVector, Vector2, Vector3};

use crate::quadrature;

/// Relative accuracy requested from the adaptive quadratures of arc length and curvature
/// variation: far below anything a plot or a table shows, well above rounding.
pub const QUADRATURE_TOL: f64 = 1e-10;

/// A cubic Bézier curve in `D` dimensions, given by its four control points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubicBez<const D: usize> {
    /// Control points `P0..P3`; the curve interpolates `P0` and `P3`.
    pub points: [Point<f64, D>; 4],
}

/// A planar cubic Bézier curve.
pub type CubicBez2 = CubicBez<2>;
/// A cubic Bézier curve in space.
pub type CubicBez3 = CubicBez<3>;

/// A quartic Bézier curve (the degree-elevated form of a cubic used by quartic patches).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuarticBez<const D: usize> {
    /// Control points `Q0..Q4`.
    pub points: [Point<f64, D>; 5],
}

/// One sample of a plane curve's curvature, for curvature plots.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurvatureSample {
    /// Curve parameter in `[0, 1]`.
    pub t: f64,
    /// Arc length from `t = 0`.
    pub s: f64,
    /// Signed curvature.
    pub kappa: f64,
}

fn lerp<const D: usize>(a: &Point<f64, D>, b: &Point<f64, D>, t: f64) -> Point<f64, D> {
    // Affine combination (1 − t) a + t b, written as a point plus a vector.
    a + (b - a) * t
}

impl<const D: usize> CubicBez<D> {
    /// A curve from its control points.
    pub fn new(points: [Point<f64, D>; 4]) -> Self {
        CubicBez { points }
    }

    /// Position at `t` (de Casteljau's algorithm, the numerically stable evaluation).
    pub fn eval(&self, t: f64) -> Point<f64, D> {
        let p = &self.points;
        let a = lerp(&p[0], &p[1], t);
        let b = lerp(&p[1], &p[2], t);
        let c = lerp(&p[2], &p[3], t);
        let d = lerp(&a, &b, t);
        let e = lerp(&b, &c, t);
        lerp(&d, &e, t)
    }

    /// First derivative `f'(t)`.
    pub fn deriv(&self, t: f64) -> SVector<f64, D> {
        let p = &self.points;
        let (d0, d1, d2) = (p[1] - p[0], p[2] - p[1], p[3] - p[2]);
        let s = 1.0 - t;
        (d0 * (s * s) + d1 * (2.0 * s * t) + d2 * (t * t)) * 3.0
    }

    /// Second derivative `f''(t)`.
    pub fn deriv2(&self, t: f64) -> SVector<f64, D> {
        let p = &self.points;
        let a = (p[2] - p[1]) - (p[1] - p[0]);
        let b = (p[3] - p[2]) - (p[2] - p[1]);
        (a * (1.0 - t) + b * t) * 6.0
    }

    /// Third derivative (constant for a cubic).
    pub fn deriv3(&self) -> SVector<f64, D> {
        let p = &self.points;
        ((p[3] - p[2]) - (p[2] - p[1]) * 2.0 + (p[1] - p[0])) * 6.0
    }

    /// The same curve traversed from `P3` to `P0`.
    pub fn reversed(&self) -> Self {
        let p = &self.points;
        CubicBez::new([p[3], p[2], p[1], p[0]])
    }

    /// Degree elevation: `Q_i = (i/4) P_{i−1} + (1 − i/4) P_i` (Farin §5.1), the same curve as a
    /// quartic.
    pub fn elevate(&self) -> QuarticBez<D> {
        let p = &self.points;
        QuarticBez {
            points: [
                p[0],
                lerp(&p[1], &p[0], 0.25),
                lerp(&p[2], &p[1], 0.5),
                lerp(&p[3], &p[2], 0.75),
                p[3],
            ],
        }
    }

    /// Arc length `∫₀¹ |f'(t)| dt` by adaptive Gauss–Legendre quadrature to relative accuracy
    /// [`QUADRATURE_TOL`].
    pub fn arc_length(&self) -> f64 {
        self.arc_length_to(1.0)
    }

    /// Arc length from `t = 0` to `t`.
    pub fn arc_length_to(&self, t: f64) -> f64 {
        quadrature::integrate(|u| self.deriv(u).norm(), 0.0, t, QUADRATURE_TOL)
    }
}

impl<const D: usize> QuarticBez<D> {
    /// Position at `t` (de Casteljau).
    pub fn eval(&self, t: f64) -> Point<f64, D> {
        let mut q = self.points;
        for level in (1..5).rev() {
            for i in 0..level {
                q[i] = lerp(&q[i], &q[i + 1], t);
            }
        }
        q[0]
    }
}

/// The 2D cross product `a × b = a_x b_y − a_y b_x`.
pub fn cross2(a: &Vector2<f64>, b: &Vector2<f64>) -> f64 {
    a.x * b.y - a.y * b.x
}

impl CubicBez<2> {
    /// Signed curvature `κ(t) = (f' × f'')/|f'|³`; positive where the curve turns left
    /// (counter-clockwise). Infinite or NaN where `f'(t) = 0` (a cusp), as the mathematics says.
    pub fn curvature(&self, t: f64) -> f64 {
        let d1 = self.deriv(t);
        let d2 = self.deriv2(t);
        cross2(&d1, &d2) / d1.norm().powi(3)
    }

    /// `dκ/ds`, the derivative of curvature with respect to arc length.
    pub fn curvature_derivative(&self, t: f64) -> f64 {
        let d1 = self.deriv(t);
        let d2 = self.deriv2(t);
        let d3 = self.deriv3();
        let n2 = d1.norm_squared();
        (cross2(&d1, &d3) * n2 - 3.0 * cross2(&d1, &d2) * d1.dot(&d2)) / (n2 * n2 * n2)
    }

    /// Curvature variation `∫ (dκ/ds)² ds = ∫₀¹ (dκ/ds)² |f'| dt` (the fairness measure of docs/conventions.md
    /// for boundary curves), by adaptive quadrature.
    pub fn curvature_variation(&self) -> f64 {
        quadrature::integrate(
            |t| {
                let k = self.curvature_derivative(t);
                k * k * self.deriv(t).norm()
            },
            0.0,
            1.0,
            QUADRATURE_TOL,
        )
    }

    /// `n ≥ 2` curvature samples at equally spaced parameters, with the arc length of each.
    pub fn curvature_samples(&self, n: usize) -> Vec<CurvatureSample> {
        let n = n.max(2);
        let mut out = Vec::with_capacity(n);
        let mut s = 0.0;
        let mut prev_t = 0.0;
        for i in 0..n {
            let t = i as f64 / (n - 1) as f64;
            if i > 0 {
                s += quadrature::integrate(|u| self.deriv(u).norm(), prev_t, t, QUADRATURE_TOL);
            }
            out.push(CurvatureSample {
                t,
                s,
                kappa: self.curvature(t),
            });
            prev_t = t;
        }
        out
    }
}

impl CubicBez<3> {
    /// `dκ/ds`, the arc-length derivative of the unsigned curvature `κ = |c|/|f'|³` with
    /// `c = f' × f''`. As `c' = f' × f'''` (`f'' × f''` vanishes),
    /// `dκ/dt = (c·c')/(|c| |f'|³) − 3 |c| (f'·f'')/|f'|⁵`, and `dκ/ds = (dκ/dt)/|f'|`. Where
    /// `c = 0` (an inflection, a straight curve) the first term's one-sided limits are
    /// `±|c'|/|f'|³`; the `+` one is taken (its square is what
    /// [`CubicBez3::curvature_variation`] reads). On a planar curve this is the signed
    /// curvature's derivative ([`CubicBez2::curvature_derivative`]) up to sign.
    pub fn curvature_derivative(&self, t: f64) -> f64 {
        let d1 = self.deriv(t);
        let d2 = self.deriv2(t);
        let c = d1.cross(&d2);
        let dc = d1.cross(&self.deriv3());
        let n = d1.norm();
        let cn = c.norm();
        let first = if cn > 0.0 { c.dot(&dc) / cn } else { dc.norm() };
        (first / n.powi(3) - 3.0 * cn * d1.dot(&d2) / n.powi(5)) / n
    }

    /// Curvature variation `∫ (dκ/ds)² ds = ∫₀¹ (dκ/ds)² |f'| dt` of the space curve (the
    /// same number as [`CubicBez2::curvature_variation`] of a planar curve's plane image), by
    /// adaptive quadrature.
    pub fn curvature_variation(&self) -> f64 {
        quadrature::integrate(
            |t| {
                let k = self.curvature_derivative(t);
                k * k * self.deriv(t).norm()
            },
            0.0,
            1.0,
            QUADRATURE_TOL,
        )
    }

    /// Curvature vector `k(t) = (f' × f'') × f' / |f'|⁴`, pointing to the centre of the
    /// osculating circle with length `1/radius`.
    pub fn curvature_vector(&self, t: f64) -> Vector3<f64> {
        let d1 = self.deriv(t);
        let d2 = self.deriv2(t);
        d1.cross(&d2).cross(&d1) / d1.norm_squared().powi(2)
    }

    /// Unsigned curvature `|f' × f''|/|f'|³`.
    pub fn curvature(&self, t: f64) -> f64 {
        let d1 = self.deriv(t);
        d1.cross(&self.deriv2(t)).norm() / d1.norm().powi(3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Point2, Point3};

    /// Exact identities evaluated in floating point agree to this absolute tolerance on
    /// coordinates of order one.
    const EXACT: f64 = 1e-13;
    /// Finite-difference step for checking analytic derivatives; central differences then carry
    /// an error of order `h² · |f'''|` ≈ 1e-10 on these curves.
    const FD_STEP: f64 = 1e-5;
    /// Agreement expected between central differences and analytic derivatives.
    const FD_TOL: f64 = 1e-7;

    fn sample() -> CubicBez2 {
        CubicBez::new([
            Point2::new(0.0, 0.0),
            Point2::new(0.3, 0.5),
            Point2::new(0.9, -0.2),
            Point2::new(1.0, 0.0),
        ])
    }

    #[test]
    fn endpoints_and_end_derivatives() {
        let c = sample();
        let p = c.points;
        assert!((c.eval(0.0) - p[0]).norm() < EXACT);
        assert!((c.eval(1.0) - p[3]).norm() < EXACT);
        assert!((c.deriv(0.0) - (p[1] - p[0]) * 3.0).norm() < EXACT);
        assert!((c.deriv(1.0) - (p[3] - p[2]) * 3.0).norm() < EXACT);
        assert!((c.deriv2(0.0) - ((p[2] - p[1]) - (p[1] - p[0])) * 6.0).norm() < EXACT);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let c = sample();
        for i in 1..10 {
            let t = i as f64 / 10.0;
            let fd1 = (c.eval(t + FD_STEP) - c.eval(t - FD_STEP)) / (2.0 * FD_STEP);
            assert!((fd1 - c.deriv(t)).norm() < FD_TOL);
            let fd2 = (c.deriv(t + FD_STEP) - c.deriv(t - FD_STEP)) / (2.0 * FD_STEP);
            assert!((fd2 - c.deriv2(t)).norm() < FD_TOL);
            let fd3 = (c.deriv2(t + FD_STEP) - c.deriv2(t - FD_STEP)) / (2.0 * FD_STEP);
            assert!((fd3 - c.deriv3()).norm() < FD_TOL);
            let fdk = (c.curvature(t + FD_STEP) - c.curvature(t - FD_STEP)) / (2.0 * FD_STEP);
            let dsdt = c.deriv(t).norm();
            assert!((fdk / dsdt - c.curvature_derivative(t)).abs() < 1e-5 * fdk.abs().max(1.0));
        }
    }

    #[test]
    fn elevation_keeps_the_curve() {
        let c = sample();
        let q = c.elevate();
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            assert!((q.eval(t) - c.eval(t)).norm() < EXACT);
        }
    }

    #[test]
    fn straight_evenly_spaced_cubic_has_chord_length_and_zero_curvature() {
        let c = CubicBez::new([
            Point3::new(1.0, 2.0, 3.0),
            Point3::new(2.0, 4.0, 5.0),
            Point3::new(3.0, 6.0, 7.0),
            Point3::new(4.0, 8.0, 9.0),
        ]);
        assert!((c.arc_length() - 9.0).abs() < 1e-12);
        assert!(c.curvature(0.3) < EXACT);
        assert!(c.curvature_vector(0.7).norm() < EXACT);
    }

    /// A twisted cubic (not planar): [`CubicBez3::curvature_derivative`] against central
    /// differences of the curvature over arc length, and the variation of a planar curve
    /// lifted into space (rotated out of every coordinate plane) equal to the plane's.
    #[test]
    fn space_curvature_derivative_and_variation() {
        let twisted = CubicBez::new([
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(0.3, 0.4, 0.1),
            Point3::new(0.8, -0.1, 0.4),
            Point3::new(1.0, 0.2, -0.1),
        ]);
        for i in 1..10 {
            let t = i as f64 / 10.0;
            let fdk =
                (twisted.curvature(t + FD_STEP) - twisted.curvature(t - FD_STEP)) / (2.0 * FD_STEP);
            let got = twisted.curvature_derivative(t);
            let want = fdk / twisted.deriv(t).norm();
            assert!(
                (got - want).abs() < 1e-5 * want.abs().max(1.0),
                "t {t}: {got} vs {want}"
            );
        }
        let c2 = sample();
        let rot = nalgebra::Rotation3::from_euler_angles(0.3, -0.7, 1.1);
        let lift = |p: Point2<f64>| rot * Point3::new(p.x, p.y, 0.0) + Vector3::new(0.2, -1.0, 3.0);
        let c3 = CubicBez::new(c2.points.map(lift));
        let (v2, v3) = (c2.curvature_variation(), c3.curvature_variation());
        assert!((v2 - v3).abs() < 1e-8 * v2, "{v2} vs {v3}");
    }

    #[test]
    fn space_curvature_agrees_with_planar_curvature() {
        let c2 = sample();
        let lift = |p: Point2<f64>| Point3::new(p.x, 0.0, p.y);
        let c3 = CubicBez::new(c2.points.map(lift));
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((c3.curvature(t) - c2.curvature(t).abs()).abs() < 1e-12);
            // The curvature vector is perpendicular to the tangent and has length |κ|.
            let k = c3.curvature_vector(t);
            assert!(k.dot(&c3.deriv(t)).abs() < 1e-12);
            assert!((k.norm() - c3.curvature(t)).abs() < 1e-12);
        }
    }

    #[test]
    fn reversal_flips_curvature_sign() {
        let c = sample();
        let r = c.reversed();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((r.eval(1.0 - t) - c.eval(t)).norm() < EXACT);
            assert!((r.curvature(1.0 - t) + c.curvature(t)).abs() < 1e-10);
        }
    }

    #[test]
    fn samples_are_monotone_in_arc_length() {
        let s = sample().curvature_samples(50);
        assert_eq!(s.len(), 50);
        assert!(s.windows(2).all(|w| w[1].s > w[0].s));
        assert!((s[49].s - sample().arc_length()).abs() < 1e-10);
    }
}

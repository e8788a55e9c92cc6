//! The original testbed's `tweak` and `quadric` boundary curves (the original testbed's
//! fitters, UW 1990): inner control points a fraction `t` of the way from each end to the
//! intersection `X` of the two end tangent lines.
//!
//! # The rule, on the planar problem
//!
//! The source takes Furth's tangent directions (unnormalised) — the tangents of the plane
//! through both ends containing `n_a + n_b`, which are the tangents of [`BoundaryProblem`] (the
//! original testbed's Furth rule is the [`crate::Chord`] construction, `α = 1`: see there; no
//! `furth` copy exists). Both tangent lines lie in that plane, so they meet (if at all) in it,
//! and `E(a→b) = V_a + t (X − V_a)`, `E(b→a) = V_b + t (X − V_b)` lie in it too: the curve is
//! planar, and the rule is a choice of `(α0, α1)` on the unit problem.
//!
//! On the unit chord `D = (1, 0)` with unit tangents `t0` (leaving `(0, 0)`) and `t1`
//! (arriving at `(1, 0)`), `X = s t0 = D − r t1` for the `s, r` with `s t0 + r t1 = D`.
//! Crossing with `t1` and with `t0` (`a × b` the 2D cross product):
//!
//! `s = (D × t1)/(t0 × t1) = t1.y/(t0 × t1)`, `r = (t0 × D)/(t0 × t1) = −t0.y/(t0 × t1)`,
//!
//! and `E(a→b) = t s t0 = (α0/3) t0`, `E(b→a) = D − t r t1 = D − (α1/3) t1`, so
//!
//! `α0 = 3 t s`, `α1 = 3 t r`.
//!
//! A circle arc of angle `ψ` (tangents at `ψ/2` to the chord, `t0 × t1 = −sin ψ`) gives
//! `s = r = 1/(2 cos(ψ/2))`, `α = 3t/(2 cos(ψ/2))`.
//!
//! # `quadric`: `t = 2/3`
//!
//! The quadratic `[V_a, X, V_b]` raised to degree three is `[V_a, V_a + (2/3)(X − V_a),
//! V_b + (2/3)(X − V_b), V_b]`: `tweak` at `t = 2/3` is that parabola exactly (tested). For a
//! circle arc the cubic that matches the arc's midpoint has `t = (4/3) tan(ψ/4)/tan(ψ/2) =
//! (2/3)(1 − tan²(ψ/4))`, which tends to 2/3 for short arcs; the source's default `t = 0.5858`
//! (≈ 2 − √2; the source gives no reason) is that value at `ψ ≈ 77°` (an observation, not the
//! source's).
//!
//! # The parameter
//!
//! `t ∈ (0, 1]` ([`check_t`]): at `t ≤ 0` the inner points sit on or behind the ends (no
//! tangent), and past 1 each inner point lies beyond `X` on its line, so the control polygon
//! `V_a, E(a→b), E(b→a), V_b` crosses itself at `X`. A [`Tweak`] built with a `t` outside the
//! range (by a struct literal) returns the chord choice as a fallback.
//!
//! # Fallbacks
//!
//! * The tangents are parallel (`|t0 × t1| ≤` [`DEGENERATE_SINE`]) and both along the chord
//!   (`|t_i.y| ≤ DEGENERATE_SINE`): the lines coincide with the chord, every cubic with these
//!   ends and tangents is the segment, and the source's "straight line" is taken, `α = (1, 1)`
//!   (the segment at thirds) — not reported as a fallback: nothing the rule asks for is lost.
//! * Parallel otherwise (an S-shaped edge: the lines never meet), or meeting behind or at an
//!   end (`s ≤ 0` or `r ≤ 0`): the source falls back to Furth, which is `chord`, `α = (1, 1)`,
//!   reported as a fallback.
//!
//! Lines that meet far in front give long tangents; in a fit they are bounded like any
//! construction's ([`UnitProblem::bounded_alpha`]). On scans both happen often: through the
//! Shirman–Séquin fit (hybrid estimates), with the lower bound [`MIN_TWEAK_ALPHA`], the bunny's
//! curves fall back on 1663 of 5511 edges and 53 of its 3674 faces fold (43 for `quadric`; 0
//! for `chord`), `dragon_res4`'s on 6013 of 16522 with 398 folded faces (358; 142 for
//! `chord`); on the ring and the sphere no curve falls back and no face is refused. The tangents are the planar problem's, so
//! its clamp ([`crate::problem::MAX_TANGENT_ANGLE`]) applies as for `chord`. Curvature is not
//! read.

use crate::cubicbez::cross2;
use crate::method::{CurveChoice, CurveMethod};
use crate::problem::{UnitProblem, DEGENERATE_SINE};

#[cfg(doc)]
use crate::problem::BoundaryProblem;

/// The source's default `t` of `tweak`.
pub const DEFAULT_TWEAK_T: f64 = 0.5858;

/// `t` of `quadric`: the degree-raised quadratic through `X`.
pub const QUADRIC_T: f64 = 2.0 / 3.0;

/// A `t` outside `(0, 1]`.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "tweak parameter t = {0} is outside (0, 1]: at t ≤ 0 the inner control points leave the \
     tangent lines' front, past 1 the control polygon crosses itself at the tangents' intersection"
)]
pub struct BadTweakT(pub f64);

/// `t` if it is a usable `tweak` parameter: finite and in `(0, 1]` (module docs).
pub fn check_t(t: f64) -> Result<f64, BadTweakT> {
    if t.is_finite() && t > 0.0 && t <= 1.0 {
        Ok(t)
    } else {
        Err(BadTweakT(t))
    }
}

/// The tweak construction with its parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tweak {
    /// The fraction of the way to the tangents' intersection, in `(0, 1]`.
    pub t: f64,
}

impl Tweak {
    /// The construction for `t`, refused outside `(0, 1]`.
    pub fn new(t: f64) -> Result<Self, BadTweakT> {
        check_t(t).map(|t| Tweak { t })
    }
}

impl Default for Tweak {
    fn default() -> Self {
        Tweak { t: DEFAULT_TWEAK_T }
    }
}

/// Where the end tangent lines of a unit problem meet: `Some([s, r])` with `X = s t0 =
/// (1, 0) − r t1`, `None` when they are parallel (module docs).
pub fn tangent_intersection(problem: &UnitProblem) -> Option<[f64; 2]> {
    let cross = cross2(&problem.t0, &problem.t1);
    (cross.abs() > DEGENERATE_SINE).then(|| [problem.t1.y / cross, -problem.t0.y / cross])
}

/// The shortest end derivative the rule keeps, in chord choices (`α`): the `optimized`
/// construction's lower bound ([`crate::optimized::DEFAULT_ALPHA_MIN`], a twentieth). Where the
/// tangent lines meet close to one end (one tangent along the chord, the other steep), `α`
/// there tends to 0: the curve leaves the vertex with a vanishing derivative, the patches'
/// tangent plane at the corner degenerates (their normals are undefined there) and G1 across
/// the edges at that corner is lost (measured before this bound on the teapot: 1.3e-2 rad on a
/// regular edge, with `chord` 6.7e-13). Such a curve falls back to Furth's (`chord`) and is
/// counted as a fallback. The original testbed's sources state no such bound; it is ours.
pub const MIN_TWEAK_ALPHA: f64 = crate::optimized::DEFAULT_ALPHA_MIN;

/// The rule for fraction `t` (assumed checked).
fn tweak_choice(t: f64, problem: &UnitProblem) -> CurveChoice {
    let fallback = CurveChoice {
        fallback: true,
        ..CurveChoice::plain([1.0, 1.0])
    };
    match tangent_intersection(problem) {
        Some([s, r]) if s > 0.0 && r > 0.0 => {
            let alpha = [3.0 * t * s, 3.0 * t * r];
            if alpha[0].min(alpha[1]) < MIN_TWEAK_ALPHA {
                fallback
            } else {
                CurveChoice::plain(alpha)
            }
        }
        Some(_) => fallback,
        None if problem.t0.y.abs() <= DEGENERATE_SINE && problem.t1.y.abs() <= DEGENERATE_SINE => {
            CurveChoice::plain([1.0, 1.0])
        }
        None => fallback,
    }
}

impl CurveMethod for Tweak {
    fn name(&self) -> &'static str {
        "tweak"
    }

    /// `α = 3t (s, r)` (module docs), or the chord choice where the lines do not meet in front
    /// (a fallback) or `t` is outside `(0, 1]` (a fallback).
    fn construct(&self, problem: &UnitProblem) -> CurveChoice {
        match check_t(self.t) {
            Ok(t) => tweak_choice(t, problem),
            Err(_) => CurveChoice {
                fallback: true,
                ..CurveChoice::plain([1.0, 1.0])
            },
        }
    }

    fn needs_curvature(&self) -> bool {
        false
    }
}

/// `tweak` at `t = 2/3`: the degree-raised quadratic through the tangents' intersection.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Quadric;

impl CurveMethod for Quadric {
    fn name(&self) -> &'static str {
        "quadric"
    }

    /// [`Tweak::construct`] at [`QUADRIC_T`].
    fn construct(&self, problem: &UnitProblem) -> CurveChoice {
        tweak_choice(QUADRIC_T, problem)
    }

    fn needs_curvature(&self) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    /// Closed forms in double precision: a few roundings.
    const ROUNDING: f64 = 1e-14;

    #[test]
    fn the_parameter_range_is_enforced() {
        for bad in [0.0, -0.5, 1.0 + 1e-12, f64::NAN, f64::INFINITY] {
            let e = Tweak::new(bad).expect_err("out of range");
            assert!(e.to_string().contains("outside (0, 1]"), "{e}");
        }
        for good in [1e-9, DEFAULT_TWEAK_T, 1.0] {
            assert_eq!(Tweak::new(good), Ok(Tweak { t: good }));
        }
        let u = UnitProblem::new(Vector2::new(0.8, 0.6), Vector2::new(0.8, -0.6), 0.0, 0.0)
            .expect("valid");
        let c = Tweak { t: -1.0 }.construct(&u);
        assert!(c.fallback);
        assert_eq!(c.alpha, [1.0, 1.0]);
    }

    /// Lines meeting just in front of an end (t1 a hair off the chord, t0 steep) give an end
    /// derivative below [`MIN_TWEAK_ALPHA`]: the curve falls back to the chord choice; a bit
    /// farther off the chord it is kept.
    #[test]
    fn a_vanishing_end_derivative_falls_back() {
        let steep = Vector2::new(0.6, 0.8);
        let near =
            UnitProblem::new(steep, Vector2::new(1.0, -1e-4).normalize(), 0.0, 0.0).expect("valid");
        let [s, _] = tangent_intersection(&near).expect("meet");
        assert!(
            s > 0.0 && 3.0 * DEFAULT_TWEAK_T * s < MIN_TWEAK_ALPHA,
            "s {s}"
        );
        let c = Tweak::default().construct(&near);
        assert!(c.fallback);
        assert_eq!(c.alpha, [1.0, 1.0]);
        let off =
            UnitProblem::new(steep, Vector2::new(1.0, -0.2).normalize(), 0.0, 0.0).expect("valid");
        let c = Tweak::default().construct(&off);
        assert!(
            !c.fallback && c.alpha[0].min(c.alpha[1]) >= MIN_TWEAK_ALPHA,
            "{c:?}"
        );
    }

    #[test]
    fn lines_meeting_at_an_end_fall_back_and_an_arch_meets_at_its_apex() {
        // t1 along the chord: its line is the chord, which t0's line meets at the origin (s = 0).
        let u = UnitProblem::new(Vector2::new(0.6, 0.8), Vector2::x(), 0.0, 0.0).expect("valid");
        assert_eq!(tangent_intersection(&u).map(|[s, _]| s), Some(0.0));
        assert!(Tweak::default().construct(&u).fallback);
        // t0 = (0.6, 0.8), t1 = (0.6, −0.8): X = (½, ⅔), s = r = |X| = 5/6.
        let u = UnitProblem::new(Vector2::new(0.6, 0.8), Vector2::new(0.6, -0.8), 0.0, 0.0)
            .expect("valid");
        let [s, r] = tangent_intersection(&u).expect("meet");
        assert!((s - 5.0 / 6.0).abs() < ROUNDING && (r - 5.0 / 6.0).abs() < ROUNDING);
        let c = Quadric.construct(&u);
        assert!((c.alpha[0] - 5.0 / 3.0).abs() < ROUNDING);
    }
}

//! The original testbed's projection family of boundary tangents (the original testbed's
//! fitters, UW 1990): `projection` (the default of its modified Shirman–Séquin fitter),
//! `projection-scaled` and `piper`, each at the chord's third or, as a parameter ([`Reach`]),
//! at its five ninths (the "four-ninths" variants).
//!
//! # The rules
//!
//! For the edge from `V_a` to `V_b`, chord `d = V_b − V_a`, unit chord `x̂ = d/|d|`, unit normal
//! `n_a` and the projection onto the tangent plane at `V_a`, `P_a(v) = v − (v·n_a) n_a`:
//!
//! | rule | `E(a→b)` |
//! |---|---|
//! | `projection` | `V_a + P_a(f d)` |
//! | `projection-scaled` | `V_a + f |d| · P_a(d)/|P_a(d)|` |
//! | `piper` | `V_a + (10/9) P_a(f d)` |
//!
//! with the reach `f = 1/3` ([`Reach::Third`]) or `f = 5/9` ([`Reach::FourNinths`]), and
//! `E(b→a)` the same from `V_b` with `−d` and `n_b`. As `P` is linear, `P_a(f d) = f|d| P_a(x̂)`:
//! every rule points along `u_a = P_a(x̂)/|P_a(x̂)|` and differs only in the length, which in
//! the unit-chord form `α = 3|E − V|/|d|` of the rest of the crate is
//!
//! `α = 3f · g(p)`, with `p = |P(x̂)|` and `g(p) = p` (projection), `1` (rescaled),
//! `(10/9) p` (Piper).
//!
//! `p = sin ∠(x̂, n)` is the cosine of the angle `θ` between the tangent `u` and the chord: `u`
//! is the direction of the tangent plane closest to the chord (`P(x̂)` minimizes `|x̂ − v|` over
//! the plane), so the projection's tangents are the least steep any tangent in the tangent
//! plane can be, and the control polygon's chord components are `α_i (u_i · x̂) = 3f g(p_i) p_i
//! ≤ 3f (10/9)`: at the third the polygon is always monotone along the chord
//! ([`crate::problem::monotone_bound`] never shortens), at five ninths it may be shortened like
//! any construction's. The tangents are never clamped ([`crate::problem::MAX_TANGENT_ANGLE`]):
//! they stay in the tangent plane, so no G1 scheme refuses a face for them. Measured through
//! the Shirman–Séquin fit on `dragon_res4` (hybrid estimates): `chord` clamps 54 tangents and
//! has 316 fallback faces and 142 folded ones; `projection` clamps none, 286 fallback faces and
//! 26 folded (`projection-scaled` 286 / 27, `piper` 286 / 30). On the bunny: 0 / 0 for chord
//! and projection-scaled, 0 / 1 for projection and piper.
//!
//! # Not planar, and not Furth
//!
//! `P_a(d)` lies in the plane of `d` and `n_a`. The curve plane of [`BoundaryProblem`] (through
//! both ends, containing `m = n_a + n_b`, normal `w`) has the tangent `±(w × n_a)/|w × n_a|` at
//! `V_a`, which is the original testbed's **Furth** direction (`unit(n_a × w)` signed towards
//! `V_b`); the two agree only when `n_a` lies in the plane of `d` and `m` (or `d ⊥ n_a`). In
//! general the projection's tangent leaves the curve plane, both ends' tangents do so
//! differently, and the cubic is a space curve: it cannot be written as `(α0, α1)` on the
//! planar problem. This module therefore builds it in space
//! ([`crate::CurveMethod::space_curve`]) from the problem's end positions and normals
//! ([`BoundaryProblem::normals`]). Furth's rule itself — those plane tangents scaled to `|d|`,
//! `E = V_a + |d| t_a/3` — is `α = 1` on the planar problem: it *is* the [`crate::Chord`]
//! construction (up to the workbench's tangent clamp), so it has no copy here.
//!
//! # On a planar unit problem
//!
//! A unit problem ([`UnitProblem`], the `curve` experiment) is a curve in the plane: the
//! "tangent plane" at an end is the line along `t_i`, its normal the in-plane perpendicular of
//! `t_i`, and `P(v) = (v · t_i) t_i`, so `p_i = c_i = t_i · (1, 0) = cos θ_i`:
//! `α = 3f cos θ` (projection: `cos θ` at the third), `3f` (rescaled: `1`, the chord choice, at
//! the third), `(10/9) 3f cos θ` (Piper) — the space construction on planar data (both normals
//! in the curve plane) gives the same curve ([`Projection::construct`]; tested). A tangent with
//! `c_i ≤` [`DEGENERATE_SINE`] (across or against the chord: its projected chord has no length,
//! or points back) takes `α_i = 1` there and is reported as a fallback.
//!
//! # The four-ninths variants: how the source is read
//!
//! The source's statement is "⅓ d replaced by (5/9) d from the point (4/9) V_a + (5/9) V_b".
//! That point is `V_a + (5/9) d`: the vector `(5/9) d` *is* the one from `V_a` to it, so the
//! rule projects that point into the tangent plane at `V_a`, `E(a→b) = V_a + P_a((5/9) d)`, in
//! place of the point `V_a + ⅓ d`. At the other end the statement, read with the same single
//! point, would give `V_b + P_b(−(4/9) d)`: a rule whose curve depends on which way the edge is
//! traversed, which no shared boundary curve may (each mesh edge's curve is built once, along
//! the mesh's edge order, and must be the same curve as the reversed edge's). It is read
//! symmetrically instead: at each end the point with weight 4/9 on that end's own vertex —
//! `(4/9) V_a + (5/9) V_b` for `a`, `(5/9) V_a + (4/9) V_b` for `b` — which is what names the
//! variant "four-ninths". So `f = 5/9` at both ends, and "any of the above" carries over: the
//! rescaled length becomes `(5/9)|d|` (`α = 5/3`), Piper's `(10/9) P((5/9) d)`. The source
//! gives no reason for 5/9; on a circle the tangents come out 5/3 times the projection's, longer
//! than the circle's own (`α → 1` for short arcs), which the fit's monotone-polygon bound
//! shortens on nearly straight edges (`α0 c0 + α1 c1` up to 10/3 > 3): measured through the
//! Shirman–Séquin fit, it shortens 224 of the `ring`'s 384 curves for `projection` and all of
//! them for the other two, and every one of the `sphere`'s for each.
//!
//! # Linear precision
//!
//! On planar data (`n_a = n_b ⊥ d`) `P(d) = d`: `projection` and `projection-scaled` at the
//! third give the edge at thirds, so the Shirman–Séquin patch is the linear one, but Piper's
//! curve is the segment with its inner points at `10/27` and `17/27` of it, parametrized
//! unevenly, and its patch is not linear (the surface crate's linear-precision test measures
//! this exception).
//!
//! # Crease ends
//!
//! Where the edge runs along a crease ([`crate::crease`]), the surface's tangent space at that
//! end, seen from the edge, is the crease line `ℓ` (the curve must lie in both sectors'
//! tangent planes), so `P(v) = (v · ℓ) ℓ` there: `u = ℓ`, `p = ℓ · x̂` (at least
//! [`crate::crease::MIN_TANGENT_COSINE`], as the fit gives `ℓ` only then). A crease end whose
//! line could not be used has the bisector data ([`crate::CreaseEnd`]) and is projected onto
//! the bisector plane.
//!
//! # Degenerate ends
//!
//! `p ≤` [`DEGENERATE_SINE`]: the normal lies along the chord and `P(x̂)` has no direction. The
//! end then takes the planar problem's tangent at `α = 1` (Furth, i.e. `chord`), and the curve
//! is reported as a fallback. (A [`BoundaryProblem`] is not built when the normal is within
//! `DEGENERATE_SINE` of the chord — its plane tangent `t` has `t · x̂ ≤ |P(x̂)|` — so on a mesh
//! this only guards against rounding.)
//!
//! Curvature is not read ([`CurveMethod::needs_curvature`] is false).

use nalgebra::Vector3;

use crate::cubicbez::CubicBez3;
use crate::method::{CurveChoice, CurveMethod, SpaceCurve};
use crate::problem::{monotone_bound, BoundaryProblem, UnitProblem, DEGENERATE_SINE};

/// Piper's lengthening of the projected point: one ninth.
pub const PIPER_FACTOR: f64 = 10.0 / 9.0;

/// How far along the chord the projected point is taken (module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Reach {
    /// `f = 1/3`: the point `V_a + ⅓ d`.
    #[default]
    Third,
    /// `f = 5/9`: the point `(4/9) V_a + (5/9) V_b` (module docs: how the source is read).
    FourNinths,
}

impl Reach {
    /// The fraction `f` of the chord.
    pub fn fraction(self) -> f64 {
        match self {
            Reach::Third => 1.0 / 3.0,
            Reach::FourNinths => 5.0 / 9.0,
        }
    }
}

/// How the projected point's length is set: the member of the family.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scaling {
    /// `E = V + P(f d)`: `g(p) = p`.
    Projected,
    /// `E = V + f|d| unit(P(d))`: `g(p) = 1`.
    Rescaled,
    /// `E = V + (10/9) P(f d)`: `g(p) = (10/9) p`.
    Piper,
}

impl Scaling {
    /// `g(p)`: the end-derivative length in units of `f|d|`, for `p = |P(x̂)|`.
    pub fn length(self, p: f64) -> f64 {
        match self {
            Scaling::Projected => p,
            Scaling::Rescaled => 1.0,
            Scaling::Piper => PIPER_FACTOR * p,
        }
    }
}

/// A member of the projection family (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Projection {
    /// Which member.
    pub scaling: Scaling,
    /// The third or five ninths of the chord.
    pub reach: Reach,
}

impl Projection {
    /// `α` for an end whose projected unit chord has length `p` (`None` when `p` is at most
    /// [`DEGENERATE_SINE`] or not finite: no direction).
    pub fn alpha(&self, p: f64) -> Option<f64> {
        (p > DEGENERATE_SINE && p.is_finite())
            .then(|| 3.0 * self.reach.fraction() * self.scaling.length(p))
    }
}

/// The projection of the unit chord `x` at an end: the unit tangent along the direction of
/// travel and `p = |P(x)|`, onto the crease line `line` where given (a unit vector along the
/// direction of travel), else onto the plane `⊥ n`. `None` when `p ≤` [`DEGENERATE_SINE`].
pub fn projected_chord(
    x: &Vector3<f64>,
    n: &Vector3<f64>,
    line: Option<Vector3<f64>>,
) -> Option<(Vector3<f64>, f64)> {
    let (u, p) = match line {
        Some(l) => (l, l.dot(x)),
        None => {
            let v = x - n * x.dot(n);
            let p = v.norm();
            (v / p, p)
        }
    };
    (p > DEGENERATE_SINE && p.is_finite()).then_some((u, p))
}

impl CurveMethod for Projection {
    /// The tangent is the chord projected into the tangent plane: the rule of the source.
    fn keeps_own_tangents(&self) -> bool {
        true
    }

    fn name(&self) -> &'static str {
        match self.scaling {
            Scaling::Projected => "projection",
            Scaling::Rescaled => "projection-scaled",
            Scaling::Piper => "piper",
        }
    }

    /// The rule on the planar problem: `p_i = t_i · (1, 0)` (module docs, "On a planar unit
    /// problem"); an end with `p_i ≤` [`DEGENERATE_SINE`] takes `α_i = 1` and the choice is a
    /// fallback.
    fn construct(&self, problem: &UnitProblem) -> CurveChoice {
        let ends = [problem.t0.x, problem.t1.x].map(|c| self.alpha(c));
        CurveChoice {
            fallback: ends.iter().any(Option::is_none),
            ..CurveChoice::plain(ends.map(|a| a.unwrap_or(1.0)))
        }
    }

    fn needs_curvature(&self) -> bool {
        false
    }

    /// The rule in space (module docs): `u_i`, `p_i` from the end's normal (or crease line),
    /// `E(a→b) = V_a + α_0 |d|/3 u_0`, `E(b→a) = V_b − α_1 |d|/3 u_1`, the lengths bounded by
    /// [`monotone_bound`]. A degenerate end takes the planar problem's tangent at `α = 1` (and
    /// its clamp flag).
    fn space_curve(
        &self,
        problem: &BoundaryProblem,
        lines: [Option<Vector3<f64>>; 2],
    ) -> SpaceCurve {
        let x = problem.frame.x;
        let mut alpha = [1.0; 2];
        let mut tangents = problem.tangents;
        let mut clamped = [false; 2];
        let mut fallback = false;
        for i in 0..2 {
            match projected_chord(&x, &problem.normals[i], lines[i])
                .and_then(|(u, p)| Some((u, self.alpha(p)?)))
            {
                Some((u, a)) => {
                    tangents[i] = u;
                    alpha[i] = a;
                }
                None => {
                    fallback = true;
                    clamped[i] = problem.clamped[i];
                    if let Some(l) = lines[i] {
                        tangents[i] = l;
                    }
                }
            }
        }
        let chosen = alpha;
        let (alpha, shortened) = monotone_bound(alpha, tangents.map(|t| t.dot(&x)));
        let [pa, pb] = problem.ends();
        let s = problem.frame.scale / 3.0;
        SpaceCurve {
            curve: CubicBez3::new([
                pa,
                pa + tangents[0] * (alpha[0] * s),
                pb - tangents[1] * (alpha[1] * s),
                pb,
            ]),
            alpha,
            choice: CurveChoice {
                fallback,
                ..CurveChoice::plain(chosen)
            },
            shortened,
            clamped,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    /// Closed forms in double precision: a few roundings.
    const ROUNDING: f64 = 1e-14;

    fn all() -> Vec<Projection> {
        let mut out = Vec::new();
        for scaling in [Scaling::Projected, Scaling::Rescaled, Scaling::Piper] {
            for reach in [Reach::Third, Reach::FourNinths] {
                out.push(Projection { scaling, reach });
            }
        }
        out
    }

    #[test]
    fn lengths_on_a_tangent_at_sixty_degrees() {
        // cos 60° = ½: α = 3f g(½).
        let u = UnitProblem::new(
            Vector2::new(0.5, 0.75f64.sqrt()),
            Vector2::new(0.5, -(0.75f64.sqrt())),
            0.0,
            0.0,
        )
        .expect("valid");
        let want = |m: &Projection| match (m.scaling, m.reach) {
            (Scaling::Projected, Reach::Third) => 0.5,
            (Scaling::Rescaled, Reach::Third) => 1.0,
            (Scaling::Piper, Reach::Third) => 5.0 / 9.0,
            (Scaling::Projected, Reach::FourNinths) => 5.0 / 6.0,
            (Scaling::Rescaled, Reach::FourNinths) => 5.0 / 3.0,
            (Scaling::Piper, Reach::FourNinths) => 25.0 / 27.0,
        };
        for m in all() {
            let c = m.construct(&u);
            assert!(!c.fallback);
            for a in c.alpha {
                assert!((a - want(&m)).abs() < ROUNDING, "{m:?}: {a}");
            }
        }
    }

    #[test]
    fn a_tangent_across_or_against_the_chord_falls_back_at_that_end() {
        let u = UnitProblem::new(Vector2::new(0.0, 1.0), Vector2::new(-0.6, 0.8), 0.0, 0.0)
            .expect("valid");
        for m in all() {
            let c = m.construct(&u);
            assert!(c.fallback, "{m:?}");
            assert_eq!(c.alpha, [1.0, 1.0], "{m:?}");
        }
        // The space helper: a normal along the chord has no projected chord.
        assert!(projected_chord(&Vector3::x(), &Vector3::x(), None).is_none());
    }

    #[test]
    fn a_crease_line_is_the_tangent_space() {
        let x = Vector3::new(0.8, 0.6, 0.0);
        let (u, p) = projected_chord(&x, &Vector3::z(), Some(Vector3::x())).expect("along");
        assert_eq!(u, Vector3::x());
        assert!((p - 0.8).abs() < ROUNDING);
    }

    #[test]
    fn no_member_reads_curvature_and_names_are_the_registry_s() {
        for m in all() {
            assert!(!m.needs_curvature());
            assert!(["projection", "projection-scaled", "piper"].contains(&m.name()));
        }
    }
}

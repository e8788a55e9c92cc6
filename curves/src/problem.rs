//! The planar boundary-curve problem: from the data at the two ends of a mesh edge to a
//! unit-chord problem in the plane, and from a unit-chord solution back to a cubic in space.
//!
//! # Construction (docs/conventions.md, "Geometry")
//!
//! For the edge from vertex `a` to vertex `b` with positions `p`, unit normals `n` and shape
//! tensors `S` (normal curvature `κn(d) = dᵀ S d` for unit tangent `d`; `κn > 0` where the
//! surface bends towards `n`):
//!
//! * chord `d = p_b − p_a`; the curve lies in the plane through both points containing the
//!   average normal, with unit normal `w = (d × (n_a + n_b)) / |d × (n_a + n_b)|`;
//! * in-plane frame `x = d/|d|`, `y = w × x` (so `x × y = w`, and the 2D cross product in the
//!   frame is the 3D one read along `w`);
//! * end tangents `t = ±(w × n)/|w × n|`, the sign chosen so that `t · d > 0`. The tangent lies
//!   in the curve plane (it is ⊥ `w`) and in the tangent plane (⊥ `n`). When the sign has to be
//!   flipped from the natural `n × w` the vertex normal leans past the chord (it has turned more
//!   than 90° from where a surface through both points would put it): the problem is still
//!   built, and [`BoundaryProblem::flipped`] says so for reports to count;
//! * target curvature by Meusnier's theorem: a plane curve with signed curvature `κ` (about `w`)
//!   has curvature vector `κ (w × t)`, whose normal component is the normal curvature
//!   `κn(t) = κ ⟨w × t, n⟩`; hence `κ = κn(t) / ⟨w × t, n⟩`. With `t = s (w × n)/|w × n|`,
//!   `⟨w × t, n⟩ = s((w·n)² − 1)/|w × n| = −s |w × n|`, so the denominator vanishes exactly when
//!   the tangent is undefined (`n ∥ w`): one degeneracy, not two. And it is the opposite-normal
//!   degeneracy in disguise: `w ⊥ m̂` for `m = n_a + n_b`, and `n_a · m̂ = |m|/2`, so
//!   `|w × n_a| ≥ |m|/2`; once `|m|` is checked the tangents exist;
//! * **tangent clamp**: where the tangent so found makes more than [`MAX_TANGENT_ANGLE`] with the
//!   chord it is turned, in the curve plane, towards the chord until it makes exactly that angle
//!   ([`BoundaryProblem::clamped`] says so; derivation and choice of the angle there). The target
//!   curvature stays the one of the data's tangent;
//! * unit-chord scaling (techreport §3, "unit problem"): positions `(q − p_a)/|d|` in the frame,
//!   tangents are directions and stay unit, curvatures multiply by `|d|`. A unit solution
//!   `(α0, α1)` maps back to `P1 = p_a + α0 |d| t_a / 3`, `P2 = p_b − α1 |d| t_b / 3`.

use nalgebra::{Matrix3, Point2, Point3, Vector2, Vector3};

use crate::cubicbez::{cross2, CubicBez2, CubicBez3};
pub use mesh::VertexData;

/// Sine of an angle below which a construction step is treated as degenerate: below
/// `√ε ≈ 1.5e-8` a normalized cross product of two unit vectors has lost half its digits, and the
/// Meusnier quotient amplifies curvature by more than 10⁸.
pub const DEGENERATE_SINE: f64 = 1e-8;

/// How far from unit length a tangent of a unit problem may be before it is rejected rather than
/// normalized: a hand-typed `[0.7071, 0.7071]` passes, a vector that is not meant to be a
/// direction does not.
pub const UNIT_TANGENT_TOLERANCE: f64 = 1e-4;

/// The largest angle an end tangent may make with the chord: 80°.
///
/// # Why a bound, and why 80°
///
/// On the unit chord let a cubic have end tangents at angles `θ0, θ1 ≤ θ` to the chord and a
/// control polygon monotone along the chord ([`UnitProblem::bounded_alpha`]): its inner
/// control points sit at chord coordinates `x1 = α0 cos θ0 / 3` and `1 − x2 = α1 cos θ1 / 3`
/// with `x1 + (1 − x2) ≤ 1`, at heights `h1 = x1 tan θ0`, `h2 = (1 − x2) tan θ1`, so
/// `|h1| + |h2| ≤ tan θ`. The curve's height `y(t) = 3t(1−t)[(1−t) h1 + t h2]` is linear in
/// `(h1, h2)`, so its largest value is at a vertex of that set: `max_t 3t(1−t)² tan θ =
/// (4/9) tan θ`. The curve stays within `(4/9)|d| tan θ` of its chord (2.5 `|d|` at 80°).
/// Without a bound, a vertex normal leaning along the chord by `90° − θ` makes the tangent,
/// which must be perpendicular to it, climb steeply: as `θ → 90°` the height grows without
/// bound, and seen from a face on the edge the curve's end tangents swing across the face's
/// other edges — the face then folds whatever patch is put on it.
///
/// The bound must leave smooth data alone: a circle sampled by chords of arc angle `ψ` has
/// tangents at `ψ/2` to each chord, so `θ = 80°` leaves untouched every circle sampled by more
/// than 2.25 chords per turn (`ψ ≤ 160°`), and with it every analytic data set (`octa`, `sphere`
/// at level 0 and `capsule` at 4 reach 45°, the default `ring` 22.5°, `ring` at 8 47.6°, at 6
/// 72° and at 4 76°). A tighter bound trades folds for fallback faces (C0 kinks) on scans: a
/// clamped tangent leaves the tangent plane, and the G1 schemes refuse such faces. Measured with
/// optimized curves, folded / fallback faces: `dragon_res4` 171 / 296 unclamped, 165 / 316 at
/// 80°, 152 / 368 at 70°, 140 / 458 at 60°; the bunny's fallback faces 0 at 80°, 4 at 70°, 17
/// at 60°. 80° keeps the scans' smooth edges smooth and still cuts off the near-vertical
/// tangents of normals leaning along the chord.
pub const MAX_TANGENT_ANGLE: f64 = 80.0 * std::f64::consts::PI / 180.0;

/// `cos` [`MAX_TANGENT_ANGLE`] (correctly rounded, checked by a test).
const MAX_TANGENT_COS: f64 = 0.173_648_177_666_930_4;

/// `sin` [`MAX_TANGENT_ANGLE`] (correctly rounded, checked by a test).
const MAX_TANGENT_SIN: f64 = 0.984_807_753_012_208;

/// The sum `α0 cos θ0 + α1 cos θ1` at and below which a unit-chord cubic's control polygon is
/// monotone along the chord ([`UnitProblem::bounded_alpha`]).
pub const MONOTONE_POLYGON: f64 = 3.0;

/// [`UnitProblem::bounded_alpha`] for end tangents whose components along the unit chord are
/// `c = [c0, c1]`: `alpha` scaled by `3/(α0 c0 + α1 c1)` when both `c_i > 0` and the sum
/// exceeds [`MONOTONE_POLYGON`], and whether it was. The derivation there holds for a cubic in
/// space too: it reads only the control polygon's components along the chord, so the space
/// constructions (`crate::projection`) bound their lengths with it as well.
pub fn monotone_bound(alpha: [f64; 2], c: [f64; 2]) -> ([f64; 2], bool) {
    let along = alpha[0] * c[0] + alpha[1] * c[1];
    if c[0] > 0.0 && c[1] > 0.0 && along > MONOTONE_POLYGON {
        let k = MONOTONE_POLYGON / along;
        ([alpha[0] * k, alpha[1] * k], true)
    } else {
        (alpha, false)
    }
}

/// Which end of an edge a degeneracy concerns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum End {
    /// The start vertex `a`.
    Start,
    /// The end vertex `b`.
    End,
}

impl std::fmt::Display for End {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            End::Start => "start vertex",
            End::End => "end vertex",
        })
    }
}

/// Why a boundary-curve problem cannot be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Degeneracy {
    /// A coordinate of a position, normal or shape tensor is NaN or infinite.
    #[error("non-finite {what} at the {end}")]
    NonFinite {
        /// `"position"`, `"normal"` or `"shape tensor"`.
        what: &'static str,
        /// Which end.
        end: End,
    },
    /// A normal of zero length.
    #[error("zero normal at the {0}")]
    ZeroNormal(End),
    /// Both ends at the same position.
    #[error("the two vertices coincide")]
    CoincidentPoints,
    /// `n_a + n_b ≈ 0`: the normals are opposite and no average normal exists.
    #[error("opposite normals: no average normal defines the curve plane")]
    OppositeNormals,
    /// The chord is parallel to the average normal, so the plane is not determined.
    #[error("chord parallel to the average normal: the curve plane is not determined")]
    ChordAlongNormal,
    /// The end tangent is perpendicular to the chord: the normal lies along the chord.
    #[error("tangent at the {0} is perpendicular to the chord (normal along the chord)")]
    TangentAcrossChord(End),
}

/// A boundary-curve problem could not be built for an edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("edge {}–{}: {kind}", edge.0, edge.1)]
pub struct EdgeError {
    /// The edge, as the caller's vertex indices `(a, b)`.
    pub edge: (usize, usize),
    /// What is wrong.
    pub kind: Degeneracy,
}

/// A unit problem's input is unusable.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum UnitProblemError {
    /// A value is NaN or infinite.
    #[error("non-finite {0}")]
    NonFinite(&'static str),
    /// A tangent is not of unit length (within [`UNIT_TANGENT_TOLERANCE`]).
    #[error("{name} has length {length}, expected a unit vector")]
    NotUnit {
        /// `"t0"` or `"t1"`.
        name: &'static str,
        /// Its length.
        length: f64,
    },
}

/// The planar problem on the unit chord from `(0, 0)` to `(1, 0)`: unit end tangents `t0, t1`
/// (both pointing along the direction of travel) and target signed curvatures `k0, k1`.
///
/// With `D = P3 − P0 = (1, 0)` and `f'(0) = α0 t0`, `f'(1) = α1 t1` the cubic has control points
/// `P1 = α0 t0/3`, `P2 = D − α1 t1/3`, and (derived in [`UnitProblem::end_curvatures`])
/// `κ(0) = 2(3 t0×D − α1 t0×t1)/α0²`, `κ(1) = 2(3 t1×(−D) + α0 t1×t0)/α1²`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitProblem {
    /// Unit tangent at `(0, 0)`.
    pub t0: Vector2<f64>,
    /// Unit tangent at `(1, 0)`.
    pub t1: Vector2<f64>,
    /// Target signed curvature at `(0, 0)`.
    pub k0: f64,
    /// Target signed curvature at `(1, 0)`.
    pub k1: f64,
}

impl UnitProblem {
    /// Validates and normalizes the tangents.
    pub fn new(
        t0: Vector2<f64>,
        t1: Vector2<f64>,
        k0: f64,
        k1: f64,
    ) -> Result<Self, UnitProblemError> {
        let finite = |v: &Vector2<f64>| v.iter().all(|c| c.is_finite());
        if !finite(&t0) {
            return Err(UnitProblemError::NonFinite("t0"));
        }
        if !finite(&t1) {
            return Err(UnitProblemError::NonFinite("t1"));
        }
        if !k0.is_finite() {
            return Err(UnitProblemError::NonFinite("k0"));
        }
        if !k1.is_finite() {
            return Err(UnitProblemError::NonFinite("k1"));
        }
        for (name, t) in [("t0", &t0), ("t1", &t1)] {
            let length = t.norm();
            if (length - 1.0).abs() > UNIT_TANGENT_TOLERANCE {
                return Err(UnitProblemError::NotUnit { name, length });
            }
        }
        Ok(UnitProblem {
            t0: t0.normalize(),
            t1: t1.normalize(),
            k0,
            k1,
        })
    }

    /// The cubic for end-derivative lengths `alpha = [α0, α1]`.
    pub fn curve(&self, alpha: [f64; 2]) -> CubicBez2 {
        let p0 = Point2::origin();
        let p3 = Point2::new(1.0, 0.0);
        CubicBez2::new([
            p0,
            p0 + self.t0 * (alpha[0] / 3.0),
            p3 - self.t1 * (alpha[1] / 3.0),
            p3,
        ])
    }

    /// `alpha` shortened, if need be, so that the control polygon of [`UnitProblem::curve`] is
    /// monotone along the chord, and whether it was shortened.
    ///
    /// With `c_i = t_i · D` (`D = (1, 0)`; both positive for the problems of
    /// [`BoundaryProblem`]), the legs of the control polygon have the chord components
    /// `α0 c0/3`, `1 − (α0 c0 + α1 c1)/3` and `α1 c1/3`, and `f'(t) · D` is the quadratic with
    /// these Bernstein coefficients (times 3). When `α0 c0 + α1 c1 ≤ 3` (=
    /// [`MONOTONE_POLYGON`]) every coefficient is `≥ 0` and the end ones positive, so
    /// `f'(t) · D ≥ 3 l0 l2 / (l0 + l2) > 0` with `l0, l2` the end legs: the curve never runs
    /// back along its chord, stays within `0 ≤ x ≤ 1`, and within `(4/9) tan θ` of the chord
    /// for tangents at `θ` ([`MAX_TANGENT_ANGLE`]). Beyond it the
    /// middle leg runs backwards and, once `u² − uv + v² ≥ 3` (`u² = α0 c0`, `v² = α1 c1`: the
    /// minimum of the quadratic reaches zero), so does the curve: the overshoot seen from the
    /// faces on the edge as a loop across them.
    ///
    /// A longer `alpha` is scaled by `3/(α0 c0 + α1 c1)`: both lengths by the same factor, so
    /// the ratio a construction chose is kept. The chord choice `α = (1, 1)` is never touched
    /// (`c0 + c1 ≤ 2`), nor is any circle arc's `α = 2 tan(ψ/4)/sin(ψ/2)` (`α c ≤ 1` for every
    /// arc angle `ψ < 180°`). Tangents with `c_i ≤ 0` (not produced by [`BoundaryProblem`])
    /// leave `alpha` as it is: the bound is about running along the chord.
    pub fn bounded_alpha(&self, alpha: [f64; 2]) -> ([f64; 2], bool) {
        monotone_bound(alpha, [self.t0.x, self.t1.x])
    }

    /// End curvatures `[κ(0), κ(1)]` of [`UnitProblem::curve`] in closed form.
    ///
    /// Derivation (techreport §3, with its `α2` typo in `f''(1)` read as `α1`):
    /// `f''(0) = 6(P2 − 2P1 + P0) = 6D − 2α1 t1 − 4α0 t0`, so
    /// `f'(0) × f''(0) = α0 t0 × (6D − 2α1 t1) = 2α0(3 t0×D − α1 t0×t1)` and dividing by
    /// `|f'(0)|³ = α0³` gives `κ(0)`. Likewise `f''(1) = 6(P3 − 2P2 + P1) = −6D + 4α1 t1 + 2α0 t0`,
    /// `f'(1) × f''(1) = 2α1(3 t1×(−D) + α0 t1×t0)`, divided by `α1³`.
    pub fn end_curvatures(&self, alpha: [f64; 2]) -> [f64; 2] {
        // t × D with D = (1, 0) is −t.y.
        cost::boundary_curve::end_curvatures(
            -self.t0.y,
            -self.t1.y,
            cross2(&self.t0, &self.t1),
            alpha,
        )
    }

    /// The same problem traversed from `(1, 0)` to `(0, 0)` and turned by 180° about
    /// `(½, 0)` so that it is again on the unit chord: tangents swap, and curvatures swap and
    /// change sign (reversal flips the sign of signed curvature, a rotation keeps it). A
    /// solution `[α0, α1]` of this problem is `[α1, α0]` of the reversed one.
    pub fn reversed(&self) -> UnitProblem {
        UnitProblem {
            t0: self.t1,
            t1: self.t0,
            k0: -self.k1,
            k1: -self.k0,
        }
    }
}

/// The plane and frame of a boundary curve, and the map between world and unit coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneFrame {
    /// World position of the unit problem's `(0, 0)`.
    pub origin: Point3<f64>,
    /// Unit chord direction, the unit problem's x axis.
    pub x: Vector3<f64>,
    /// `w × x`, the unit problem's y axis.
    pub y: Vector3<f64>,
    /// Unit normal of the curve plane.
    pub w: Vector3<f64>,
    /// Chord length `|d|`: world lengths are unit lengths times this.
    pub scale: f64,
}

impl PlaneFrame {
    /// Unit-problem coordinates of a world point (its projection onto the plane).
    pub fn to_unit(&self, q: &Point3<f64>) -> Point2<f64> {
        let v = q - self.origin;
        Point2::new(v.dot(&self.x), v.dot(&self.y)) / self.scale
    }

    /// World position of a unit-problem point.
    pub fn to_world(&self, q: &Point2<f64>) -> Point3<f64> {
        self.origin + (self.x * q.x + self.y * q.y) * self.scale
    }

    /// Unit-problem components of a world direction (no scaling).
    pub fn direction_to_unit(&self, v: &Vector3<f64>) -> Vector2<f64> {
        Vector2::new(v.dot(&self.x), v.dot(&self.y))
    }
}

/// The boundary-curve problem of one mesh edge, in world and unit coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryProblem {
    /// The edge `(a, b)` as the caller's vertex indices, for messages.
    pub edge: (usize, usize),
    /// The curve plane and the unit-chord map.
    pub frame: PlaneFrame,
    /// World unit tangents at `a` and `b`, both along the direction of travel.
    pub tangents: [Vector3<f64>; 2],
    /// Target signed curvatures (about `w`) at `a` and `b` in world units.
    pub curvatures: [f64; 2],
    /// True at an end whose tangent had to be flipped to point along the chord (the normal there
    /// leans past the chord); counted by reports.
    pub flipped: [bool; 2],
    /// True at an end whose tangent made more than [`MAX_TANGENT_ANGLE`] with the chord and was
    /// turned back to it (module docs). The tangent is then no longer perpendicular to the
    /// vertex normal: no G1 surface through the vertex interpolates that normal along this
    /// edge, and the split-domain construction refuses the faces on it
    /// (`surface::shirman_sequin`); counted by reports like `flipped`.
    pub clamped: [bool; 2],
    /// The scaled problem on the unit chord.
    pub unit: UnitProblem,
    /// The unit normals at `a` and `b` the problem was built from (at a crease end the
    /// bisector normal, [`crate::crease`]): what the constructions that build their curve in
    /// space read ([`crate::CurveMethod::space_curve`], [`crate::projection`]).
    pub normals: [Vector3<f64>; 2],
    /// The shape tensors at `a` and `b` the target curvatures were read from (`κn(d) = dᵀ S d`),
    /// for measures of curves whose tangents are not the plane's (`surface::curve_stats`).
    pub shapes: [Matrix3<f64>; 2],
}

impl BoundaryProblem {
    /// Builds the problem for the edge from `a` to `b`; `edge` names it in errors.
    pub fn new(edge: (usize, usize), a: &VertexData, b: &VertexData) -> Result<Self, EdgeError> {
        let fail = |kind| EdgeError { edge, kind };
        for (v, end) in [(a, End::Start), (b, End::End)] {
            if !v.p.iter().all(|c| c.is_finite()) {
                return Err(fail(Degeneracy::NonFinite {
                    what: "position",
                    end,
                }));
            }
            if !v.n.iter().all(|c| c.is_finite()) {
                return Err(fail(Degeneracy::NonFinite {
                    what: "normal",
                    end,
                }));
            }
            if !v.shape.iter().all(|c| c.is_finite()) {
                return Err(fail(Degeneracy::NonFinite {
                    what: "shape tensor",
                    end,
                }));
            }
            if v.n.norm() == 0.0 {
                return Err(fail(Degeneracy::ZeroNormal(end)));
            }
        }
        let na = a.n.normalize();
        let nb = b.n.normalize();
        let d = b.p - a.p;
        let len = d.norm();
        if len == 0.0 || !len.is_finite() {
            return Err(fail(Degeneracy::CoincidentPoints));
        }
        let x = d / len;
        let m = na + nb;
        if m.norm() <= 2.0 * DEGENERATE_SINE {
            return Err(fail(Degeneracy::OppositeNormals));
        }
        let wv = x.cross(&m.normalize());
        if wv.norm() <= DEGENERATE_SINE {
            return Err(fail(Degeneracy::ChordAlongNormal));
        }
        let w = wv.normalize();
        let y = w.cross(&x);
        let frame = PlaneFrame {
            origin: a.p,
            x,
            y,
            w,
            scale: len,
        };

        let mut tangents = [Vector3::zeros(); 2];
        let mut curvatures = [0.0; 2];
        let mut flipped = [false; 2];
        let mut clamped = [false; 2];
        for (i, (v, n, end)) in [(a, na, End::Start), (b, nb, End::End)]
            .into_iter()
            .enumerate()
        {
            let natural = n.cross(&w);
            let sine = natural.norm();
            if sine <= DEGENERATE_SINE {
                // |w × n| ≥ |n_a + n_b|/2 (module docs): only nearly opposite normals get here.
                return Err(fail(Degeneracy::OppositeNormals));
            }
            let mut t = natural / sine;
            let along = t.dot(&x);
            if along.abs() <= DEGENERATE_SINE {
                return Err(fail(Degeneracy::TangentAcrossChord(end)));
            }
            if along < 0.0 {
                t = -t;
                flipped[i] = true;
            }
            // Meusnier: κ = κn(t) / ⟨w × t, n⟩.
            let denom = w.cross(&t).dot(&n);
            curvatures[i] = v.normal_curvature(&t) / denom;
            // The clamp (MAX_TANGENT_ANGLE): t lies in the curve plane, t = x cos θ + y sin θ;
            // beyond the bound it becomes x cos θ_max ± y sin θ_max, on the same side.
            if t.dot(&x) < MAX_TANGENT_COS {
                let side = if t.dot(&y) < 0.0 { -1.0 } else { 1.0 };
                t = x * MAX_TANGENT_COS + y * (side * MAX_TANGENT_SIN);
                clamped[i] = true;
            }
            tangents[i] = t;
        }
        let unit = UnitProblem {
            t0: frame.direction_to_unit(&tangents[0]).normalize(),
            t1: frame.direction_to_unit(&tangents[1]).normalize(),
            k0: curvatures[0] * len,
            k1: curvatures[1] * len,
        };
        Ok(BoundaryProblem {
            edge,
            frame,
            tangents,
            curvatures,
            flipped,
            clamped,
            unit,
            normals: [na, nb],
            shapes: [a.shape, b.shape],
        })
    }

    /// The world positions of `a` and `b` as every curve of this problem ends there: `a` the
    /// frame's origin, `b` the unit problem's `(1, 0)` mapped back (equal to the data's
    /// position up to rounding; the same bits for every construction, so curves of one edge
    /// built by different constructions share their end points).
    pub fn ends(&self) -> [Point3<f64>; 2] {
        [
            self.frame.origin,
            self.frame.to_world(&Point2::new(1.0, 0.0)),
        ]
    }

    /// The world cubic for a unit solution `alpha = [α0, α1]`:
    /// `P1 = p_a + α0 |d| t_a / 3`, `P2 = p_b − α1 |d| t_b / 3`.
    pub fn curve(&self, alpha: [f64; 2]) -> CubicBez3 {
        let s = self.frame.scale / 3.0;
        let [pa, pb] = self.ends();
        CubicBez3::new([
            pa,
            pa + self.tangents[0] * (alpha[0] * s),
            pb - self.tangents[1] * (alpha[1] * s),
            pb,
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Matrix3;

    /// Round trips between frames are exact up to a few roundings.
    const ROUND_TRIP: f64 = 1e-12;

    fn flat(p: [f64; 3]) -> VertexData {
        VertexData::new(Point3::from(p), Vector3::z(), Matrix3::zeros())
    }

    #[test]
    fn end_curvature_formula_matches_the_curve() {
        let u = UnitProblem::new(Vector2::new(0.8, 0.6), Vector2::new(0.6, -0.8), 0.0, 0.0)
            .expect("valid");
        for alpha in [[1.0, 1.0], [0.3, 2.0], [1.7, 0.4]] {
            let c = u.curve(alpha);
            let [k0, k1] = u.end_curvatures(alpha);
            assert!((k0 - c.curvature(0.0)).abs() < 1e-12 * k0.abs().max(1.0));
            assert!((k1 - c.curvature(1.0)).abs() < 1e-12 * k1.abs().max(1.0));
        }
    }

    #[test]
    fn reversed_problem_has_swapped_solution() {
        let u = UnitProblem::new(Vector2::new(0.8, 0.6), Vector2::new(0.6, 0.8), 1.5, -0.5)
            .expect("valid");
        let r = u.reversed();
        let [k0, k1] = u.end_curvatures([0.7, 1.3]);
        let [r0, r1] = r.end_curvatures([1.3, 0.7]);
        assert!((k0 + r1).abs() < ROUND_TRIP && (k1 + r0).abs() < ROUND_TRIP);
    }

    #[test]
    fn unit_problem_rejects_bad_tangents() {
        assert!(matches!(
            UnitProblem::new(Vector2::new(2.0, 0.0), Vector2::x(), 0.0, 0.0),
            Err(UnitProblemError::NotUnit { name: "t0", .. })
        ));
        assert!(matches!(
            UnitProblem::new(Vector2::x(), Vector2::new(f64::NAN, 0.0), 0.0, 0.0),
            Err(UnitProblemError::NonFinite("t1"))
        ));
        assert!(matches!(
            UnitProblem::new(Vector2::x(), Vector2::x(), f64::INFINITY, 0.0),
            Err(UnitProblemError::NonFinite("k0"))
        ));
    }

    #[test]
    fn flat_edge_maps_to_a_straight_unit_problem() {
        let p = BoundaryProblem::new((3, 4), &flat([1.0, 2.0, 0.0]), &flat([4.0, 6.0, 0.0]))
            .expect("valid");
        assert!((p.frame.scale - 5.0).abs() < ROUND_TRIP);
        assert!((p.unit.t0 - Vector2::x()).norm() < ROUND_TRIP);
        assert!((p.unit.t1 - Vector2::x()).norm() < ROUND_TRIP);
        assert_eq!((p.unit.k0, p.unit.k1), (0.0, 0.0));
        let c = p.curve([1.0, 1.0]);
        assert!((c.points[1] - Point3::new(2.0, 10.0 / 3.0, 0.0)).norm() < ROUND_TRIP);
        assert_eq!(p.flipped, [false, false]);
    }

    #[test]
    fn degenerate_edges_are_named() {
        let a = flat([0.0, 0.0, 0.0]);
        let err = |b: VertexData| BoundaryProblem::new((7, 9), &a, &b).expect_err("degenerate");
        assert_eq!(
            err(flat([0.0, 0.0, 0.0])).kind,
            Degeneracy::CoincidentPoints
        );
        assert_eq!(
            err(flat([0.0, 0.0, 1.0])).kind,
            Degeneracy::ChordAlongNormal
        );
        let mut b = flat([1.0, 0.0, 0.0]);
        b.n = -Vector3::z();
        assert_eq!(err(b).kind, Degeneracy::OppositeNormals);
        b.n = Vector3::zeros();
        assert_eq!(err(b).kind, Degeneracy::ZeroNormal(End::End));
        b.n = Vector3::new(f64::NAN, 0.0, 1.0);
        assert!(matches!(
            err(b).kind,
            Degeneracy::NonFinite { what: "normal", .. }
        ));
        let mut b = flat([1.0, 0.0, 0.0]);
        b.shape[(0, 1)] = f64::INFINITY;
        assert!(matches!(
            err(b).kind,
            Degeneracy::NonFinite {
                what: "shape tensor",
                ..
            }
        ));
        let mut b = flat([1.0, 0.0, 0.0]);
        b.p.x = f64::NAN;
        assert!(matches!(
            err(b).kind,
            Degeneracy::NonFinite {
                what: "position",
                ..
            }
        ));
        // Normal along the chord at b: its tangent is perpendicular to the chord.
        let mut b = flat([1.0, 0.0, 0.0]);
        b.n = Vector3::x();
        assert_eq!(err(b).kind, Degeneracy::TangentAcrossChord(End::End));
        let e = err(flat([0.0, 0.0, 0.0]));
        assert_eq!(e.to_string(), "edge 7–9: the two vertices coincide");
    }

    /// The edge from the origin to `(1, 0, 0)` with the normal at `a` turned about `y` so that
    /// its tangent climbs at `theta` from the chord (`n_a = (−sin θ, 0, cos θ)`, tangent
    /// `(cos θ, 0, sin θ)`); `n_b = z`, tangent along the chord. Both normals lie in the
    /// `xz`-plane, which is the curve plane.
    fn climbing(theta: f64) -> BoundaryProblem {
        let a = VertexData::new(
            Point3::origin(),
            Vector3::new(-theta.sin(), 0.0, theta.cos()),
            Matrix3::zeros(),
        );
        BoundaryProblem::new((0, 1), &a, &flat([1.0, 0.0, 0.0])).expect("valid")
    }

    #[test]
    fn a_tangent_beyond_the_bound_is_clamped_to_it() {
        assert!((MAX_TANGENT_COS - MAX_TANGENT_ANGLE.cos()).abs() <= f64::EPSILON);
        assert!((MAX_TANGENT_SIN - MAX_TANGENT_ANGLE.sin()).abs() <= f64::EPSILON);
        let p = climbing(85f64.to_radians());
        assert_eq!(p.clamped, [true, false]);
        // Turned in the curve plane to exactly 80° from the chord, on the side it climbed.
        let want = Vector3::new(MAX_TANGENT_COS, 0.0, MAX_TANGENT_SIN);
        assert!(
            (p.tangents[0] - want).norm() < ROUND_TRIP,
            "{:?}",
            p.tangents[0]
        );
        assert!((p.tangents[0].dot(&p.frame.x) - MAX_TANGENT_COS).abs() < ROUND_TRIP);
        assert!((p.unit.t0.x - MAX_TANGENT_COS).abs() < ROUND_TRIP);
        // No longer perpendicular to the vertex normal: t · n = cos 80° (−sin 85°) + sin 80° cos 85°
        // = −sin 5°, the 5° it was turned by …
        let n = Vector3::new(-(85f64.to_radians()).sin(), 0.0, (85f64.to_radians()).cos());
        assert!((p.tangents[0].dot(&n) + 5f64.to_radians().sin()).abs() < ROUND_TRIP);
        // … and the other end, along the chord, is untouched.
        assert!((p.tangents[1] - Vector3::x()).norm() < ROUND_TRIP);
        assert_eq!(p.flipped, [false, false]);
    }

    #[test]
    fn a_tangent_under_the_bound_is_untouched_bit_for_bit() {
        let p = climbing(79f64.to_radians());
        assert_eq!(p.clamped, [false, false]);
        // Exactly the tangent of the construction without the clamp: w × n normalized, turned
        // to run along the chord.
        let n = Vector3::new(-(79f64.to_radians()).sin(), 0.0, (79f64.to_radians()).cos());
        let natural = n.cross(&p.frame.w);
        let t = natural / natural.norm();
        let t = if t.dot(&p.frame.x) < 0.0 { -t } else { t };
        assert_eq!(p.tangents[0], t);
        assert!((p.tangents[0].dot(&p.frame.x) - 79f64.to_radians().cos()).abs() < ROUND_TRIP);
    }

    #[test]
    fn a_long_alpha_is_shortened_to_a_monotone_polygon() {
        // Tangents at 60° (the α bound does not depend on the clamp angle).
        let s = 3f64.sqrt() / 2.0;
        // Tangents at 60° on the same side (an arch): c0 = c1 = ½.
        let u =
            UnitProblem::new(Vector2::new(0.5, s), Vector2::new(0.5, -s), 0.0, 0.0).expect("valid");
        let (alpha, shortened) = u.bounded_alpha([4.0, 8.0]);
        // α0 c0 + α1 c1 = 6 → both scaled by ½.
        assert!(shortened);
        assert!((alpha[0] - 2.0).abs() < ROUND_TRIP && (alpha[1] - 4.0).abs() < ROUND_TRIP);
        let c = u.curve(alpha);
        // The middle leg has no length along the chord: the polygon is monotone, just.
        assert!((c.points[2].x - c.points[1].x).abs() < ROUND_TRIP);
        // The curve never runs back and stays within (4/9) tan θ of its chord.
        for k in 0..=1000 {
            let t = f64::from(k) / 1000.0;
            let d = c.deriv(t);
            assert!(d.x > 0.0, "t {t}: {d:?}");
            assert!(c.eval(t).y.abs() <= 4.0 / 9.0 * 3f64.sqrt());
        }
        // Unbounded, the same α runs back along the chord: u² − uv + v² = 6 − 2√2 ≥ 3.
        let back = u.curve([4.0, 8.0]);
        assert!((0..=100).any(|k| back.deriv(f64::from(k) / 100.0).x < 0.0));
    }

    #[test]
    fn short_and_circular_alphas_are_untouched_bit_for_bit() {
        let u = UnitProblem::new(Vector2::new(0.8, 0.6), Vector2::new(0.8, -0.6), 0.0, 0.0)
            .expect("valid");
        for alpha in [[1.0, 1.0], [0.3, 2.0], [1.7, 1.7], [1e-3, 3.0]] {
            assert_eq!(u.bounded_alpha(alpha), (alpha, false));
        }
        // The circle arc of angle ψ through both ends: tangents at ψ/2, α = 2 tan(ψ/4)/sin(ψ/2).
        for psi in [0.1f64, 1.0, 2.0, 3.0] {
            let (sn, cs) = (psi / 2.0).sin_cos();
            let arc = UnitProblem::new(Vector2::new(cs, sn), Vector2::new(cs, -sn), 0.0, 0.0)
                .expect("valid");
            let a = 2.0 * (psi / 4.0).tan() / sn;
            assert_eq!(arc.bounded_alpha([a, a]), ([a, a], false), "ψ {psi}");
        }
    }

    #[test]
    fn the_height_bound_is_reached_in_the_limit() {
        // θ0 = θ1 = 60°, α0 c0 → 3 and α1 → 0 (α0 c0 + α1 c1 = 3 − 3ε): the curve's height tends
        // to (4/9) tan 60°.
        // Tangents at 60° (the α bound does not depend on the clamp angle).
        let s = 3f64.sqrt() / 2.0;
        let u =
            UnitProblem::new(Vector2::new(0.5, s), Vector2::new(0.5, -s), 0.0, 0.0).expect("valid");
        let eps = 1e-6;
        let (alpha, shortened) = u.bounded_alpha([6.0 * (1.0 - 2.0 * eps), 6.0 * eps]);
        assert!(!shortened);
        let c = u.curve(alpha);
        let top = (0..=3000)
            .map(|k| c.eval(f64::from(k) / 3000.0).y)
            .fold(0.0, f64::max);
        let bound = 4.0 / 9.0 * 3f64.sqrt();
        assert!(
            top <= bound && top > bound * (1.0 - 1e-4),
            "{top} vs {bound}"
        );
    }

    #[test]
    fn leaning_normal_is_flipped_and_flagged() {
        // At b the normal has turned more than 90° from the normal at a.
        let a = flat([0.0, 0.0, 0.0]);
        let b = VertexData::new(
            Point3::new(1.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, -0.2),
            Matrix3::zeros(),
        );
        let p = BoundaryProblem::new((0, 1), &a, &b).expect("valid");
        assert_eq!(p.flipped, [false, true]);
        assert!(p.tangents[1].dot(&p.frame.x) > 0.0);
    }
}

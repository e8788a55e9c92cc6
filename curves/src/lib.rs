//! Cubic boundary curves for triangular surface interpolants.
//!
//! The curve layer of the workbench: cubic Bézier curves in the plane and in space
//! ([`CubicBez`]), the planar boundary-curve problem of a mesh edge ([`BoundaryProblem`], scaled
//! to the unit chord as [`UnitProblem`]), and the constructions that choose the end-derivative
//! lengths `(α0, α1)`, each behind the [`CurveMethod`] trait and registered by name in
//! [`REGISTRY`]:
//!
//! * [`chord`] — the Shirman–Séquin default, `α = (1, 1)`: one third of the chord;
//! * [`dbhs`] — de Boor–Höllig–Sabin, matching end curvatures, with every positive solution
//!   enumerated and one chosen by a named [`DbhsPick`] policy;
//! * [`dbhs_guarded`] — dBHS where its solution keeps within half to twice the chord choice,
//!   [`optimized`] elsewhere;
//! * [`optimized`] — Mann's trade-off between tangent length and end curvature, minimized by any
//!   adapter of the `solver` crate (objective in the `cost` crate);
//! * [`projection`] — the original testbed's projection rules (`projection`,
//!   `projection-scaled`, `piper`, each at a third or five ninths of the chord): the chord
//!   projected into the tangent plane, a space curve ([`CurveMethod::space_curve`]);
//! * [`tweak`] — the original testbed's `tweak` and `quadric`: inner points part of the way to
//!   the end tangents' intersection.
//!
//! The original testbed's Furth rule is [`chord`] (see there).
//!
//! A crease edge's curve runs along the crease, in both sectors' tangent planes ([`crease`]).
//!
//! Conventions are those of `docs/conventions.md`: signed curvature is positive where a
//! plane curve turns left (about the plane normal `w`), normal curvature `κn(d) = dᵀ S d` is
//! positive where the surface bends towards its normal, `α = 1` is one third of the chord.

pub mod chord;
pub mod crease;
pub mod cubicbez;
pub mod dbhs;
pub mod dbhs_guarded;
pub mod jsonl;
pub mod method;
pub mod optimized;
pub mod poly;
pub mod problem;
pub mod projection;
pub mod quadrature;
pub mod tweak;

pub use chord::Chord;
pub use crease::{apply_tangents, crease_end, CreaseEnd};
pub use cubicbez::{cross2, CubicBez, CubicBez2, CubicBez3, CurvatureSample, QuarticBez};
pub use dbhs::{Dbhs, DbhsPick, DbhsSolution, DbhsSolutions};
pub use dbhs_guarded::DbhsGuarded;
pub use method::{
    method_by_name, planar_space_curve, takes_solver, Candidates, CurveChoice, CurveMethod,
    MethodEntry, MethodOptions, SpaceCurve, TangentRule, UnknownMethod, REGISTRY,
};
pub use optimized::Optimized;
pub use problem::{
    BoundaryProblem, Degeneracy, EdgeError, End, PlaneFrame, UnitProblem, UnitProblemError,
    VertexData, DEGENERATE_SINE,
};
pub use projection::{Projection, Reach, Scaling};
pub use tweak::{BadTweakT, Quadric, Tweak};

//! The Shirman–Séquin default boundary curve (techreport Appendix A; Shirman & Séquin 1987):
//! inner control points at one third of the chord along the end tangents, i.e. `α0 = α1 = 1` on
//! the unit chord.
//!
//! # The original testbed's Furth rule is this construction
//!
//! The original testbed's fitters (UW 1990) offer, as the default of their original
//! Shirman–Séquin fitter, Furth's tangents: `u = d/|d|`, `w = unit(u × (n_a + n_b))`, the
//! direction `t_a = unit(n_a × w)` signed to point towards `V_b`, scaled to `|d|`, and
//! `E(a→b) = V_a + |d| t_a/3`. The [`crate::BoundaryProblem`]'s plane has the same normal
//! `w = (d × (n_a + n_b))/|d × (n_a + n_b)|`, its tangent is `±(w × n_a)/|w × n_a| =
//! ∓ unit(n_a × w)`, signed so that `t · d > 0` — Furth's direction — and `α = 1` puts the
//! inner point at `V_a + |d| t_a/3`: Furth's point. The two differ only where the workbench
//! clamps a tangent steeper than [`crate::problem::MAX_TANGENT_ANGLE`] to the chord, which
//! Furth does not; so there is no separate `furth` construction. (The testbed's projection
//! rules are not this one: [`crate::projection`].)

use crate::method::{CurveChoice, CurveMethod};
use crate::problem::UnitProblem;

/// End derivatives of one third of the chord: `α = (1, 1)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Chord;

impl CurveMethod for Chord {
    fn name(&self) -> &'static str {
        "chord"
    }

    fn construct(&self, _problem: &UnitProblem) -> CurveChoice {
        CurveChoice::plain([1.0, 1.0])
    }

    fn needs_curvature(&self) -> bool {
        false
    }
}

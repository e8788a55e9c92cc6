//! The Shirman–Séquin default boundary curve (techreport Appendix A; Shirman & Séquin 1987):
//! inner control points at one third of the chord along the end tangents, i.e. `α0 = α1 = 1` on
//! the unit chord.

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

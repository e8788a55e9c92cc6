//! Solver selection by name: `exact-penalty`, `lbfgs`, `lm`.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// The solver adapters, selectable by name (`FromStr`/`Display` round-trip): the family's
/// registry is this closed enum and [`SolverKind::ALL`], because `solve` dispatches to each
/// adapter's fast paths monomorphized for the problem's sizes (const generics), which a `dyn`
/// trait object cannot carry. A new adapter is one file, one variant, one entry in `ALL` and
/// its name here; every `--solver` option, report and agreement test then takes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SolverKind {
    /// `exact-penalty`: the projected structured quasi-Newton exact-penalty method
    /// ([`crate::exact_penalty`]), after Mahdavi-Amiri & Bartels (1989).
    ExactPenalty,
    /// `lbfgs`: argmin's L-BFGS with a Moré–Thuente line search ([`crate::lbfgs`]).
    Lbfgs,
    /// `lm`: the `levenberg-marquardt` crate's MINPACK-style trust region ([`crate::lm`]).
    Lm,
}

impl SolverKind {
    /// Every adapter, in a fixed order.
    pub const ALL: [SolverKind; 3] = [Self::ExactPenalty, Self::Lbfgs, Self::Lm];

    /// The name used on command lines and in reports.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::ExactPenalty => "exact-penalty",
            Self::Lbfgs => "lbfgs",
            Self::Lm => "lm",
        }
    }
}

impl fmt::Display for SolverKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A solver name that is not one of [`SolverKind::ALL`] (the message lists them, from the
/// registry).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown solver `{name}`; expected one of: {known}", name = .0, known = SolverKind::ALL.map(SolverKind::name).join(", "))]
pub struct UnknownSolver(
    /// The name that was given.
    pub String,
);

impl FromStr for SolverKind {
    type Err = UnknownSolver;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| UnknownSolver(s.to_owned()))
    }
}

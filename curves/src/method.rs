//! The boundary-curve construction trait and the registry of constructions by name.
//!
//! A construction turns a [`UnitProblem`] into end-derivative lengths `(α0, α1)`; the world
//! curve follows from [`crate::BoundaryProblem::curve`]. Adding a construction means one file
//! implementing [`CurveMethod`] and one line in [`REGISTRY`].

use crate::{chord::Chord, dbhs::Dbhs, dbhs::DbhsPick, optimized::Optimized, problem::UnitProblem};
use cost::Weights;
use solver::{SolveOptions, SolveReport, SolverKind};

/// Alternative solutions a construction found, at most four (the dBHS quartic has at most four
/// real roots). Fixed size: constructions run once per mesh edge and should not allocate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Candidates {
    items: [[f64; 2]; 4],
    len: usize,
}

impl Candidates {
    /// The candidates, each `[α0, α1]`.
    pub fn as_slice(&self) -> &[[f64; 2]] {
        &self.items[..self.len]
    }

    /// Appends; a fifth candidate is ignored (it cannot occur for a quartic).
    pub fn push(&mut self, alpha: [f64; 2]) {
        if self.len < self.items.len() {
            self.items[self.len] = alpha;
            self.len += 1;
        }
    }

    /// Number of candidates.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True if there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// What a construction chose for one problem.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveChoice {
    /// End-derivative lengths `[α0, α1]` on the unit chord (`α = 1`: one third of the chord).
    pub alpha: [f64; 2],
    /// True when the construction could not do what it is for and fell back to `chord`
    /// (for dbhs: no positive solution exists).
    pub fallback: bool,
    /// Every solution the construction found, for constructions that enumerate them
    /// ([`CurveMethod::enumerates_solutions`]); empty otherwise.
    pub candidates: Candidates,
    /// Index into `candidates` of the chosen one, if one was chosen.
    pub chosen: Option<usize>,
    /// The solver's report, for constructions that solve an optimization problem.
    pub report: Option<SolveReport>,
}

impl CurveChoice {
    /// A choice with nothing to report beyond `alpha`.
    pub fn plain(alpha: [f64; 2]) -> Self {
        CurveChoice {
            alpha,
            fallback: false,
            candidates: Candidates::default(),
            chosen: None,
            report: None,
        }
    }
}

/// A way to build the cubic boundary curve of an edge.
pub trait CurveMethod: Send + Sync {
    /// The registered name (`"chord"`, `"dbhs"`, …).
    fn name(&self) -> &'static str;

    /// Chooses `(α0, α1)` for a unit problem. Infallible: a construction that cannot do its job
    /// falls back (and says so in [`CurveChoice::fallback`]).
    fn construct(&self, problem: &UnitProblem) -> CurveChoice;

    /// True if it reads the end curvatures of its problems, so that a mesh must carry shape
    /// tensors (estimated or given) before it is fitted with it; false for a construction of
    /// tangents alone (`chord`).
    fn needs_curvature(&self) -> bool {
        true
    }

    /// True if [`CurveChoice::candidates`] lists all solutions (then outputs show them even
    /// when there are none).
    fn enumerates_solutions(&self) -> bool {
        false
    }
}

/// Settings the registered constructions read; each ignores what it does not use.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MethodOptions {
    /// Which dBHS solution to take when there are several.
    pub dbhs_pick: DbhsPick,
    /// The solver of the `optimized` construction (default: exact penalty, the seeds' choice).
    pub solver: SolverKind,
    /// Weights of the `optimized` objective (default 1, 1).
    pub weights: Weights,
    /// Lower bound on α for `optimized`.
    pub alpha_min: f64,
    /// Solver settings for `optimized`.
    pub solve_options: SolveOptions,
}

impl Default for MethodOptions {
    fn default() -> Self {
        MethodOptions {
            dbhs_pick: DbhsPick::default(),
            solver: SolverKind::ExactPenalty,
            weights: Weights::default(),
            alpha_min: crate::optimized::DEFAULT_ALPHA_MIN,
            solve_options: SolveOptions {
                record_history: false,
                ..SolveOptions::default()
            },
        }
    }
}

/// A name that is not in the registry.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown boundary-curve method `{name}` (known: {known})")]
pub struct UnknownMethod {
    /// The name asked for.
    pub name: String,
    /// The registered names, comma-separated.
    pub known: String,
}

/// A registry entry.
pub struct MethodEntry {
    /// Name used on the command line and in reports.
    pub name: &'static str,
    /// One line for `--help`.
    pub summary: &'static str,
    /// Builds the construction from the options.
    pub build: fn(&MethodOptions) -> Box<dyn CurveMethod>,
}

/// Every registered construction.
pub const REGISTRY: &[MethodEntry] = &[
    MethodEntry {
        name: "chord",
        summary: "Shirman–Séquin default: end derivatives of one third of the chord (α = 1)",
        build: |_| Box::new(Chord),
    },
    MethodEntry {
        name: "dbhs",
        summary: "de Boor–Höllig–Sabin: matches end tangents and curvatures; chord if impossible",
        build: |o| Box::new(Dbhs { pick: o.dbhs_pick }),
    },
    MethodEntry {
        name: "optimized",
        summary: "Mann: minimizes tangent-length and end-curvature errors with a chosen solver",
        build: |o| {
            Box::new(Optimized {
                solver: o.solver,
                weights: o.weights,
                alpha_min: o.alpha_min,
                solve_options: o.solve_options,
            })
        },
    },
];

/// Looks a construction up by name.
pub fn method_by_name(
    name: &str,
    options: &MethodOptions,
) -> Result<Box<dyn CurveMethod>, UnknownMethod> {
    REGISTRY
        .iter()
        .find(|e| e.name == name)
        .map(|e| (e.build)(options))
        .ok_or_else(|| UnknownMethod {
            name: name.to_string(),
            known: REGISTRY
                .iter()
                .map(|e| e.name)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_names_are_unique_and_resolve() {
        for e in REGISTRY {
            let m = method_by_name(e.name, &MethodOptions::default()).expect("registered");
            assert_eq!(m.name(), e.name);
            assert_eq!(REGISTRY.iter().filter(|f| f.name == e.name).count(), 1);
        }
        let err = method_by_name("bogus", &MethodOptions::default())
            .err()
            .expect("unknown");
        assert!(err.to_string().contains("chord, dbhs, optimized"));
    }
}

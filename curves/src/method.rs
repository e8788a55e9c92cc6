//! The boundary-curve construction trait and the registry of constructions by name.
//!
//! A construction turns a [`UnitProblem`] into end-derivative lengths `(α0, α1)`; the world
//! curve follows from [`crate::BoundaryProblem::curve`] — or, for the constructions whose curve
//! is not planar (the original testbed's projection rules, [`crate::projection`]), from
//! [`CurveMethod::space_curve`], which every fit calls and which by default is the planar
//! curve of [`CurveMethod::construct`]'s `α`. Adding a construction means one file implementing
//! [`CurveMethod`] and one line in [`REGISTRY`].

use nalgebra::Vector3;

use crate::crease::apply_tangents;
use crate::cubicbez::CubicBez3;
use crate::projection::{Projection, Reach, Scaling};
use crate::tweak::{Quadric, Tweak, DEFAULT_TWEAK_T};
use crate::{
    chord::Chord, dbhs::Dbhs, dbhs::DbhsPick, dbhs_guarded::DbhsGuarded, optimized::Optimized,
    problem::BoundaryProblem, problem::UnitProblem,
};
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

/// The world cubic a construction built for a [`BoundaryProblem`], with what a fit reports
/// about it ([`CurveMethod::space_curve`]).
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceCurve {
    /// The cubic from `a` to `b`, ending at [`BoundaryProblem::ends`].
    pub curve: CubicBez3,
    /// Its end-derivative lengths in unit-chord form, `α0 = 3|P1 − P0|/|d|`,
    /// `α1 = 3|P3 − P2|/|d|`, after the monotone-polygon bound.
    pub alpha: [f64; 2],
    /// The construction's choice (fallback, candidates, solver report), its `alpha` before the
    /// bound.
    pub choice: CurveChoice,
    /// True if the lengths were shortened so the control polygon does not run back along the
    /// chord ([`UnitProblem::bounded_alpha`]).
    pub shortened: bool,
    /// True at an end whose tangent is the planar problem's clamped one
    /// ([`BoundaryProblem::clamped`]), off the vertex's tangent plane.
    pub clamped: [bool; 2],
}

/// The default [`CurveMethod::space_curve`]: the planar problem's curve for `choice.alpha`
/// bounded by [`UnitProblem::bounded_alpha`], with its end tangents turned to `lines` where
/// given ([`apply_tangents`]: a crease end's tangent, keeping the length).
pub fn planar_space_curve(
    problem: &BoundaryProblem,
    choice: CurveChoice,
    lines: [Option<Vector3<f64>>; 2],
) -> SpaceCurve {
    let (alpha, shortened) = problem.unit.bounded_alpha(choice.alpha);
    SpaceCurve {
        curve: apply_tangents(&problem.curve(alpha), lines),
        alpha,
        choice,
        shortened,
        clamped: problem.clamped,
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

    /// True if the construction's end tangents are fixed by its source (the original testbed's
    /// projection rules, [`crate::projection`]): a fit then keeps them as they are, and only
    /// counts the face corners they leave non-convex, instead of choosing a vertex's tangents
    /// together from its star (`surface::fit::fan`). False for the constructions on the planar
    /// problem, whose tangents are the problem's.
    fn keeps_own_tangents(&self) -> bool {
        false
    }

    /// True if [`CurveChoice::candidates`] lists all solutions (then outputs show them even
    /// when there are none).
    fn enumerates_solutions(&self) -> bool {
        false
    }

    /// True if it solves an optimization problem with [`MethodOptions::solver`] (its choice then
    /// depends on the solver: sweeps run it once per solver); false for a closed-form rule.
    fn takes_solver(&self) -> bool {
        false
    }

    /// The world cubic of an edge: what a surface fit calls for every edge curve. `lines` are
    /// the tangents the curve must take at its ends where the mesh fixes them (a crease end's
    /// line, unit, along the direction of travel: leaving `a`, arriving at `b`).
    ///
    /// The default is planar, via α: [`CurveMethod::construct`] on the problem's unit problem,
    /// bounded and mapped back ([`planar_space_curve`]). A construction whose curve leaves the
    /// problem's plane (its end tangents are not the plane's: [`crate::projection`]) overrides
    /// it and builds the cubic from the problem's end positions and normals; its
    /// [`CurveMethod::construct`] then gives the same rule's meaning on a planar problem.
    fn space_curve(
        &self,
        problem: &BoundaryProblem,
        lines: [Option<Vector3<f64>>; 2],
    ) -> SpaceCurve {
        planar_space_curve(problem, self.construct(&problem.unit), lines)
    }
}

/// How a fit chooses the directions in which a vertex's boundary curves leave it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TangentRule {
    /// Each edge's own end tangents, except in a sector where they leave a face corner that is
    /// not convex: there the sector's tangents are chosen together from its whole star
    /// (`surface::fit::fan`). The default.
    #[default]
    Star,
    /// Each edge's end tangents from its own two end normals alone, as the seeds build them
    /// (the corners they leave non-convex are only counted).
    PerEdge,
}

impl TangentRule {
    /// Every rule, in the order `--help` lists them.
    pub const ALL: [TangentRule; 2] = [TangentRule::Star, TangentRule::PerEdge];

    /// The name on the command line: `star` or `per-edge`.
    pub fn name(&self) -> &'static str {
        match self {
            TangentRule::Star => "star",
            TangentRule::PerEdge => "per-edge",
        }
    }
}

impl std::fmt::Display for TangentRule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for TangentRule {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        TangentRule::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or_else(|| format!("unknown tangent rule `{s}` (known: star, per-edge)"))
    }
}

/// A construction with its tangents kept as it builds them ([`TangentRule::PerEdge`]): every
/// method delegates to the construction it wraps, and [`CurveMethod::keeps_own_tangents`] is
/// true.
struct PerEdgeTangents(Box<dyn CurveMethod>);

impl CurveMethod for PerEdgeTangents {
    fn name(&self) -> &'static str {
        self.0.name()
    }
    fn construct(&self, problem: &UnitProblem) -> CurveChoice {
        self.0.construct(problem)
    }
    fn needs_curvature(&self) -> bool {
        self.0.needs_curvature()
    }
    fn keeps_own_tangents(&self) -> bool {
        true
    }
    fn enumerates_solutions(&self) -> bool {
        self.0.enumerates_solutions()
    }
    fn takes_solver(&self) -> bool {
        self.0.takes_solver()
    }
    fn space_curve(
        &self,
        problem: &BoundaryProblem,
        lines: [Option<Vector3<f64>>; 2],
    ) -> SpaceCurve {
        self.0.space_curve(problem, lines)
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
    /// The parameter `t` of `tweak`, in `(0, 1]` ([`crate::tweak::check_t`]; default 0.5858).
    pub tweak_t: f64,
    /// Where the projection family takes its point: the chord's third, or five ninths (the
    /// "four-ninths" variants, [`crate::projection`]).
    pub reach: Reach,
    /// How a fit chooses the end tangents at a vertex ([`TangentRule`]; default: from the
    /// star where the per-edge tangents leave a corner that is not convex).
    pub tangents: TangentRule,
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
            tweak_t: DEFAULT_TWEAK_T,
            reach: Reach::Third,
            tangents: TangentRule::Star,
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
    MethodEntry {
        name: "dbhs-guarded",
        summary: "de Boor–Höllig–Sabin where its lengths keep within half to twice the chord choice, optimized elsewhere (G2 ends without the lumps)",
        build: |o| {
            Box::new(DbhsGuarded {
                pick: o.dbhs_pick,
                optimized: Optimized {
                    solver: o.solver,
                    weights: o.weights,
                    alpha_min: o.alpha_min,
                    solve_options: o.solve_options,
                },
            })
        },
    },
    MethodEntry {
        name: "projection",
        summary: "original testbed: the chord's third (or five ninths) projected into the tangent plane",
        build: |o| {
            Box::new(Projection {
                scaling: Scaling::Projected,
                reach: o.reach,
            })
        },
    },
    MethodEntry {
        name: "projection-scaled",
        summary: "original testbed: the projected chord's direction at a third (or five ninths) of its length",
        build: |o| {
            Box::new(Projection {
                scaling: Scaling::Rescaled,
                reach: o.reach,
            })
        },
    },
    MethodEntry {
        name: "piper",
        summary: "original testbed's Piper boundaries: the projected point lengthened by a ninth",
        build: |o| {
            Box::new(Projection {
                scaling: Scaling::Piper,
                reach: o.reach,
            })
        },
    },
    MethodEntry {
        name: "tweak",
        summary: "original testbed: inner points a fraction t of the way to the tangents' intersection",
        build: |o| Box::new(Tweak { t: o.tweak_t }),
    },
    MethodEntry {
        name: "quadric",
        summary: "original testbed: the degree-raised quadratic through the tangents' intersection",
        build: |_| Box::new(Quadric),
    },
];

/// True if the registered construction `name` takes a solver ([`CurveMethod::takes_solver`]);
/// false for an unknown name.
pub fn takes_solver(name: &str) -> bool {
    method_by_name(name, &MethodOptions::default()).is_ok_and(|m| m.takes_solver())
}

/// Looks a construction up by name.
pub fn method_by_name(
    name: &str,
    options: &MethodOptions,
) -> Result<Box<dyn CurveMethod>, UnknownMethod> {
    REGISTRY
        .iter()
        .find(|e| e.name == name)
        .map(|e| {
            let built = (e.build)(options);
            match options.tangents {
                TangentRule::Star => built,
                TangentRule::PerEdge => Box::new(PerEdgeTangents(built)) as Box<dyn CurveMethod>,
            }
        })
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
        assert!(err.to_string().contains(
            "chord, dbhs, optimized, dbhs-guarded, projection, projection-scaled, piper, tweak, quadric"
        ));
    }
}

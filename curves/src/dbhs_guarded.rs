//! `dbhs-guarded`: de Boor–Höllig–Sabin where its curve keeps to its chord, Mann's optimized
//! curve elsewhere.
//!
//! dBHS matches the end tangents and curvatures exactly (G2 Hermite), which is what a surface
//! whose curvature should converge at second order needs from its boundary curves: on the
//! sphere every scheme on dBHS curves converges in K RMS at order 2.0, on optimized curves at
//! 1.45 (`results/interior/`). But on coarse data its solutions can have a leg of a few
//! hundredths of the chord choice (α = 0.028 on the 16 × 8 ring): the seeds' lumps. On smooth
//! data the solution nearest the chord choice tends to `α = (1, 1)` as the edges shorten (the
//! cubic of the chord choice already matches the end curvatures to first order), so a bound on
//! `α` separates the two cases: the dBHS solution picked ([`crate::DbhsPick`], nearest
//! `(1, 1)` by default) is taken where both its lengths lie in [`GUARD`], and the
//! [`crate::Optimized`] construction (the same solver, weights and bound as `optimized`) is
//! used where none does.

use crate::dbhs::{self, DbhsPick};
use crate::method::{Candidates, CurveChoice, CurveMethod};
use crate::optimized::Optimized;
use crate::problem::UnitProblem;

/// The end-derivative lengths (in chord choices) within which a dBHS solution is taken: half
/// to twice the chord choice, the range outside which a leg bulges its curve (the surface
/// layer's fold test uses the same range, `surface::scheme::shirman_sequin::FOLD_TEST_ALPHA`).
pub const GUARD: (f64, f64) = (0.5, 2.0);

/// dBHS where its picked solution lies in [`GUARD`], optimized elsewhere (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DbhsGuarded {
    /// How to choose among several dBHS solutions.
    pub pick: DbhsPick,
    /// The construction used where dBHS leaves the guard.
    pub optimized: Optimized,
}

impl CurveMethod for DbhsGuarded {
    fn name(&self) -> &'static str {
        "dbhs-guarded"
    }

    /// Its optimized branch takes one.
    fn takes_solver(&self) -> bool {
        true
    }

    /// The picked dBHS solution inside [`GUARD`] with every solution as candidates, else the
    /// optimized construction's choice (its solver report, no candidates).
    fn construct(&self, problem: &UnitProblem) -> CurveChoice {
        let all = dbhs::solve(problem);
        let chosen = self.pick.pick(&all);
        let inside = |a: [f64; 2]| a.iter().all(|&x| (GUARD.0..=GUARD.1).contains(&x));
        match chosen.and_then(|i| all.get(i)) {
            Some(s) if inside(s.alpha) => {
                let mut candidates = Candidates::default();
                for s in all.iter() {
                    candidates.push(s.alpha);
                }
                CurveChoice {
                    alpha: s.alpha,
                    fallback: false,
                    candidates,
                    chosen,
                    report: None,
                }
            }
            _ => self.optimized.construct(problem),
        }
    }
}

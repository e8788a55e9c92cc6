//! The de Boor–Höllig–Sabin construction: the cubic that matches position, tangent direction and
//! signed curvature at both ends (de Boor, Höllig & Sabin, "High accuracy geometric Hermite
//! interpolation", CAGD 4(4), 1987).
//!
//! # The equations
//!
//! On the unit chord, with `c = t0 × t1`, `d0 = t0 × D`, `d1 = t1 × D` (`D = (1, 0)`), setting the
//! end curvatures of [`UnitProblem::end_curvatures`] to the targets gives two quadratics:
//!
//! ```text
//! E0:  k0 α0² − 6 d0 + 2c α1 = 0
//! E1:  k1 α1² + 6 d1 + 2c α0 = 0
//! ```
//!
//! a pair of parabolas in the `(α0, α1)` plane. Wanted: every intersection with `α0, α1 > 0`.
//!
//! * `c ≠ 0`: `E0` gives `α1 = (6 d0 − k0 α0²)/(2c)`; substituting into `E1` and multiplying by
//!   `4c²` gives the quartic
//!   `k1 k0² α0⁴ − 12 k1 k0 d0 α0² + 8c³ α0 + 36 k1 d0² + 24 c² d1 = 0`,
//!   whose degree drops by itself when `k0` or `k1` vanish (then the system is linear in one
//!   unknown). Each real positive root `α0` gives exactly one `α1`; it is computed both from `E0`
//!   (well conditioned for large `|c|`) and from `E1` (well conditioned for small `|c|`), the
//!   better of the two is polished by Newton's method on `(E0, E1)`, and the pair is kept if it
//!   satisfies both equations to [`RESIDUAL_TOL`] relative to the size of their terms.
//! * `c = 0` (parallel end tangents): the equations decouple, `k0 α0² = 6 d0` and
//!   `k1 α1² = −6 d1`. With `k = 0` and `d = 0` (a straight end) that length is free; it is
//!   set to `1` (the chord choice) and flagged in [`DbhsSolution::free`].
//!
//! Curvatures below [`FLAT_CURVATURE`] are treated as zero, and the sines `c, d0, d1` below
//! [`PARALLEL_SINE`] as zero: otherwise rounding noise in the data creates solutions that no
//! real data asks for. Example: an edge along the top circle of a torus has both tangents along
//! the chord (`c = d0 = d1 = 0` up to 10⁻¹⁷) but non-zero curvature; no cubic does that
//! (`k0 α0² = 0`), yet the noise alone yields "solutions" with `α0 ≈ 10⁻⁸`.
//!
//! There may be no solution (about one edge in twelve on a 16×8 torus), one, or several
//! (most torus edges have three). The seeds' "lumps" come from choosing a solution with a short
//! end tangent, so the choice is a named policy, [`DbhsPick`].

use crate::cubicbez::cross2;
use crate::method::{Candidates, CurveChoice, CurveMethod};
use crate::poly::{cauchy_bound, Poly};
use crate::problem::UnitProblem;

/// Unit-chord curvature treated as zero: a circle of radius 10¹² chords deviates from its chord
/// by 10⁻¹³, below the resolution of positions of order one.
pub const FLAT_CURVATURE: f64 = 1e-12;

/// `|t0 × t1|` treated as zero. Tangents are unit vectors carrying rounding of order 10⁻¹⁶;
/// below 10⁻¹² the coupling terms `2c α` are below that noise for every `α` up to 10⁴.
pub const PARALLEL_SINE: f64 = 1e-12;

/// A candidate is a solution when both equations hold to this fraction of the sum of the
/// magnitudes of their terms: a few hundred rounding errors after Newton polishing.
pub const RESIDUAL_TOL: f64 = 1e-10;

/// Two candidates closer than this (relative) are the same solution (a double root found both
/// as a bracketed root and at a critical point).
const SAME_SOLUTION: f64 = 1e-8;

/// Newton steps used to polish a candidate; convergence is quadratic from the root finder's
/// accuracy, so three or four suffice and the rest guard against slow starts.
const NEWTON_STEPS: usize = 8;

/// One positive solution of the dBHS equations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DbhsSolution {
    /// `[α0, α1]`.
    pub alpha: [f64; 2],
    /// Which lengths the equations leave free (straight ends between parallel tangents); a free
    /// length is set to `1`.
    pub free: [bool; 2],
}

/// All positive solutions, ordered by increasing `α0`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DbhsSolutions {
    items: [Option<DbhsSolution>; 4],
    len: usize,
}

impl DbhsSolutions {
    /// Number of solutions.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when no positive solution exists.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The `i`-th solution in order of increasing `α0`.
    pub fn get(&self, i: usize) -> Option<DbhsSolution> {
        self.items.get(i).copied().flatten()
    }

    /// Iterates over the solutions in order.
    pub fn iter(&self) -> impl Iterator<Item = DbhsSolution> + '_ {
        self.items[..self.len].iter().flatten().copied()
    }

    fn insert(&mut self, s: DbhsSolution) {
        let dup = self.iter().any(|o| {
            (0..2).all(|i| {
                (o.alpha[i] - s.alpha[i]).abs() <= SAME_SOLUTION * o.alpha[i].abs().max(1.0)
            })
        });
        if dup || self.len == self.items.len() {
            return;
        }
        let mut pos = self.len;
        while pos > 0 && self.get(pos - 1).is_some_and(|o| o.alpha[0] > s.alpha[0]) {
            self.items[pos] = self.items[pos - 1];
            pos -= 1;
        }
        self.items[pos] = Some(s);
        self.len += 1;
    }
}

struct Coefficients {
    k0: f64,
    k1: f64,
    c: f64,
    d0: f64,
    d1: f64,
}

impl Coefficients {
    fn new(p: &UnitProblem) -> Self {
        let snap = |x: f64, tol: f64| if x.abs() <= tol { 0.0 } else { x };
        Coefficients {
            k0: snap(p.k0, FLAT_CURVATURE),
            k1: snap(p.k1, FLAT_CURVATURE),
            c: snap(cross2(&p.t0, &p.t1), PARALLEL_SINE),
            d0: snap(-p.t0.y, PARALLEL_SINE),
            d1: snap(-p.t1.y, PARALLEL_SINE),
        }
    }

    /// `(E0, E1)` and the magnitudes of their terms.
    fn residuals(&self, a: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        let Coefficients { k0, k1, c, d0, d1 } = *self;
        (
            [
                k0 * a[0] * a[0] - 6.0 * d0 + 2.0 * c * a[1],
                k1 * a[1] * a[1] + 6.0 * d1 + 2.0 * c * a[0],
            ],
            [
                (k0 * a[0] * a[0]).abs() + (6.0 * d0).abs() + (2.0 * c * a[1]).abs(),
                (k1 * a[1] * a[1]).abs() + (6.0 * d1).abs() + (2.0 * c * a[0]).abs(),
            ],
        )
    }

    fn misfit(&self, a: [f64; 2]) -> f64 {
        let (r, s) = self.residuals(a);
        (r[0].abs() / s[0].max(f64::MIN_POSITIVE)).max(r[1].abs() / s[1].max(f64::MIN_POSITIVE))
    }

    fn polish(&self, mut a: [f64; 2]) -> [f64; 2] {
        let Coefficients { k0, k1, c, .. } = *self;
        for _ in 0..NEWTON_STEPS {
            let (r, _) = self.residuals(a);
            // J = [[2 k0 α0, 2c], [2c, 2 k1 α1]]
            let (j00, j01, j10, j11) = (2.0 * k0 * a[0], 2.0 * c, 2.0 * c, 2.0 * k1 * a[1]);
            let det = j00 * j11 - j01 * j10;
            if det == 0.0 || !det.is_finite() {
                break;
            }
            let next = [
                a[0] - (j11 * r[0] - j01 * r[1]) / det,
                a[1] - (-j10 * r[0] + j00 * r[1]) / det,
            ];
            if !(next[0].is_finite() && next[1].is_finite()) || self.misfit(next) > self.misfit(a) {
                break;
            }
            if next == a {
                break;
            }
            a = next;
        }
        a
    }
}

/// Positive length `α` with `k α² = r`, or free (`k = 0 = r`), or none.
fn decoupled(k: f64, r: f64) -> Option<(f64, bool)> {
    if k == 0.0 {
        return (r == 0.0).then_some((1.0, true));
    }
    let q = r / k;
    (q > 0.0).then(|| (q.sqrt(), false))
}

/// Every positive solution `(α0, α1)` of the dBHS equations for a unit problem.
pub fn solve(problem: &UnitProblem) -> DbhsSolutions {
    let co = Coefficients::new(problem);
    let mut out = DbhsSolutions::default();
    let Coefficients { k0, k1, c, d0, d1 } = co;
    if c == 0.0 {
        if let (Some((a0, f0)), Some((a1, f1))) =
            (decoupled(k0, 6.0 * d0), decoupled(k1, -6.0 * d1))
        {
            out.insert(DbhsSolution {
                alpha: [a0, a1],
                free: [f0, f1],
            });
        }
        return out;
    }
    let quartic = [
        36.0 * k1 * d0 * d0 + 24.0 * c * c * d1,
        8.0 * c * c * c,
        -12.0 * k1 * k0 * d0,
        0.0,
        k1 * k0 * k0,
    ];
    let Some(poly) = Poly::new(&quartic) else {
        return out;
    };
    let hi = cauchy_bound(&poly);
    for &a0 in poly.roots_in(0.0, hi).as_slice() {
        if a0 <= 0.0 {
            continue;
        }
        // α1 from E0, and from E1 (both signs); keep the best and polish it.
        let mut best = [a0, (6.0 * d0 - k0 * a0 * a0) / (2.0 * c)];
        if k1 != 0.0 {
            let q = -(6.0 * d1 + 2.0 * c * a0) / k1;
            if q >= 0.0 {
                for a1 in [q.sqrt(), -q.sqrt()] {
                    if co.misfit([a0, a1]) < co.misfit(best) {
                        best = [a0, a1];
                    }
                }
            }
        }
        let a = co.polish(best);
        if a[0] > 0.0 && a[1] > 0.0 && co.misfit(a) <= RESIDUAL_TOL {
            out.insert(DbhsSolution {
                alpha: a,
                free: [false, false],
            });
        }
    }
    out
}

/// Which dBHS solution to use when there are several.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DbhsPick {
    /// The solution closest to the chord choice `(1, 1)` in the Euclidean norm (default).
    #[default]
    Closest,
    /// The solution whose shorter end derivative is longest (`max min(α0, α1)`): the one least
    /// prone to the seeds' lumps.
    LongestShort,
    /// The `i`-th solution in order of increasing `α0`; if there are fewer, the chord fallback.
    Index(usize),
}

impl std::str::FromStr for DbhsPick {
    type Err = String;

    /// `closest`, `longest-short`, or a solution index `0, 1, …`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "closest" => Ok(DbhsPick::Closest),
            "longest-short" => Ok(DbhsPick::LongestShort),
            _ => s.parse::<usize>().map(DbhsPick::Index).map_err(|_| {
                format!("unknown dBHS pick `{s}` (expected closest, longest-short or an index)")
            }),
        }
    }
}

impl std::fmt::Display for DbhsPick {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DbhsPick::Closest => f.write_str("closest"),
            DbhsPick::LongestShort => f.write_str("longest-short"),
            DbhsPick::Index(i) => write!(f, "{i}"),
        }
    }
}

impl DbhsPick {
    /// Index of the picked solution, or `None` when there is none to pick.
    pub fn pick(&self, solutions: &DbhsSolutions) -> Option<usize> {
        let key = |s: &DbhsSolution| match self {
            DbhsPick::Closest => (s.alpha[0] - 1.0).powi(2) + (s.alpha[1] - 1.0).powi(2),
            DbhsPick::LongestShort => -s.alpha[0].min(s.alpha[1]),
            DbhsPick::Index(_) => 0.0,
        };
        match self {
            DbhsPick::Index(i) => (*i < solutions.len()).then_some(*i),
            _ => solutions
                .iter()
                .enumerate()
                .min_by(|a, b| key(&a.1).total_cmp(&key(&b.1)))
                .map(|(i, _)| i),
        }
    }
}

/// The de Boor–Höllig–Sabin construction with a solution-picking policy; falls back to the chord
/// choice `α = (1, 1)` when no positive solution exists (or the index asked for does not).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dbhs {
    /// How to choose among several solutions.
    pub pick: DbhsPick,
}

impl CurveMethod for Dbhs {
    fn name(&self) -> &'static str {
        "dbhs"
    }

    fn construct(&self, problem: &UnitProblem) -> CurveChoice {
        let all = solve(problem);
        let mut candidates = Candidates::default();
        for s in all.iter() {
            candidates.push(s.alpha);
        }
        let chosen = self.pick.pick(&all);
        let (alpha, fallback) = match chosen.and_then(|i| all.get(i)) {
            Some(s) => (s.alpha, false),
            None => ([1.0, 1.0], true),
        };
        CurveChoice {
            alpha,
            fallback,
            candidates,
            chosen,
            report: None,
        }
    }

    fn enumerates_solutions(&self) -> bool {
        true
    }
}

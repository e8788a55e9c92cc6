//! Bounded work on any unit-chord problem: a few thousand random problems, a third of them
//! extreme (curvatures from 10⁻³⁰ to 10³⁰ and zero; tangents parallel, antiparallel and along
//! the chord), each answered by every construction with the curvature variation of every curve
//! it reports. Every answer comes back (the quadrature's rule budget bounds the work; the time is
//! measured in `benches/worst_case.rs`, never here), and no measure is NaN.

use curves::{method_by_name, MethodOptions, UnitProblem, REGISTRY};
use nalgebra::Vector2;

/// Problems in the test suite (the benchmark runs 10⁶).
const PROBLEMS: usize = 3000;

use fixtures::SplitMix64 as Rng;

#[test]
fn every_extreme_problem_is_answered_without_nan() {
    let options = MethodOptions::default();
    let methods: Vec<_> = REGISTRY
        .iter()
        .filter_map(|e| method_by_name(e.name, &options).ok())
        .collect();
    assert_eq!(methods.len(), REGISTRY.len());
    let mut rng = Rng::new(7);
    let mut answered = 0;
    for _ in 0..PROBLEMS {
        let mut curvature = || match (rng.next_f64() * 6.0) as usize {
            0 => 0.0,
            1 => 10f64.powf(60.0 * rng.next_f64() - 30.0),
            _ => 20.0 * rng.next_f64() - 10.0,
        };
        let (k0, k1) = (curvature(), -curvature());
        let a = (rng.next_f64() - 0.5) * 3.0;
        let t0 = Vector2::new(a.cos(), a.sin());
        let t1 = match (rng.next_f64() * 4.0) as usize {
            0 => t0,
            1 => -t0,
            2 => Vector2::x(),
            _ => {
                let b = (rng.next_f64() - 0.5) * 3.0;
                Vector2::new(b.cos(), b.sin())
            }
        };
        let Ok(p) = UnitProblem::new(t0, t1, k0, k1) else {
            continue;
        };
        for m in &methods {
            let c = m.construct(&p);
            assert!(c.alpha.iter().all(|a| !a.is_nan()), "{}: {p:?}", m.name());
            for a in std::iter::once(&c.alpha).chain(c.candidates.as_slice()) {
                let v = p.curve(*a).curvature_variation();
                assert!(!v.is_nan(), "{}: {p:?} α {a:?}", m.name());
            }
        }
        answered += 1;
    }
    assert!(answered > PROBLEMS / 2, "{answered}");
}

//! Criterion benchmark: each adapter on the representative 2-unknown / 4-residual end-curvature
//! problem (α ≥ 0.05), from the Shirman–Séquin start α = (1, 1), history off: `solve`'s fast
//! paths (`exact-penalty`, `lbfgs`, `lm`) and the reference paths through the backends.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector2;
use solver::{solve, SolveOptions, SolverKind};
use std::hint::black_box;

/// The representative end-curvature problem, shared with the tests.
#[path = "../tests/suite/common/mod.rs"]
mod common;
use common::EndCurvature;

fn adapters(c: &mut Criterion) {
    let p = EndCurvature::representative();
    let options = SolveOptions {
        record_history: false,
        ..SolveOptions::default()
    };
    for kind in SolverKind::ALL {
        c.bench_function(kind.name(), |b| {
            b.iter(|| {
                solve(
                    kind,
                    black_box(&p),
                    black_box(Vector2::new(1.0, 1.0)),
                    &options,
                )
            })
        });
    }
    // The reference paths on the same problem (the backends themselves; same results as the
    // fast paths `solve` runs): the levenberg-marquardt crate on fixed-size and on dynamic
    // matrices, argmin's executor.
    c.bench_function("lm-crate", |b| {
        b.iter(|| {
            solver::solve_lm_crate(black_box(&p), black_box(Vector2::new(1.0, 1.0)), &options)
        })
    });
    c.bench_function("lm-any-size", |b| {
        b.iter(|| solver::solve_lm_any(black_box(&p), black_box(Vector2::new(1.0, 1.0)), &options))
    });
    c.bench_function("lbfgs-argmin", |b| {
        b.iter(|| {
            solver::solve_lbfgs_argmin(black_box(&p), black_box(Vector2::new(1.0, 1.0)), &options)
        })
    });
}

criterion_group!(benches, adapters);
criterion_main!(benches);

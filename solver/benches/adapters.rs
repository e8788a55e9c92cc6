//! Criterion benchmark: each adapter on the representative 2-unknown / 4-residual end-curvature
//! problem (α ≥ 0.05), from the Shirman–Séquin start α = (1, 1), history off: `solve`'s fast
//! paths (`exact-penalty`, `lbfgs`, `lm`) and the reference paths through the backends.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{SMatrix, SVector, Vector2};
use solver::{solve, LeastSquaresProblem, SolveOptions, SolverKind};
use std::hint::black_box;

struct EndCurvature {
    c: f64,
    d0: f64,
    d1: f64,
    k0: f64,
    k1: f64,
}

impl LeastSquaresProblem<2, 4> for EndCurvature {
    fn residuals(&self, a: &SVector<f64, 2>) -> SVector<f64, 4> {
        let k0 = 2.0 * (3.0 * self.d0 - a[1] * self.c) / (a[0] * a[0]);
        let k1 = 2.0 * (-3.0 * self.d1 - a[0] * self.c) / (a[1] * a[1]);
        SVector::<f64, 4>::new(a[0] - 1.0, a[1] - 1.0, k0 - self.k0, k1 - self.k1)
    }
    fn jacobian(&self, a: &SVector<f64, 2>) -> SMatrix<f64, 4, 2> {
        let (a0, a1) = (a[0], a[1]);
        let n0 = 2.0 * (3.0 * self.d0 - a1 * self.c);
        let n1 = 2.0 * (-3.0 * self.d1 - a0 * self.c);
        SMatrix::<f64, 4, 2>::new(
            1.0,
            0.0,
            0.0,
            1.0,
            -2.0 * n0 / (a0 * a0 * a0),
            -2.0 * self.c / (a0 * a0),
            -2.0 * self.c / (a1 * a1),
            -2.0 * n1 / (a1 * a1 * a1),
        )
    }
    fn lower_bounds(&self) -> SVector<f64, 2> {
        SVector::from_element(0.05)
    }
}

fn adapters(c: &mut Criterion) {
    let t0 = (0.3f64.cos(), 0.3f64.sin());
    let t1 = (0.2f64.cos(), -(0.2f64.sin()));
    let p = EndCurvature {
        c: t0.0 * t1.1 - t0.1 * t1.0,
        d0: -t0.1,
        d1: -t1.1,
        k0: -0.5,
        k1: -0.3,
    };
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

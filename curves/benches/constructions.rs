//! Boundary-curve constructions per edge problem: building the unit problem from vertex data and
//! choosing `(α0, α1)` with `chord`, `dbhs` and `optimized` (once per solver adapter, default
//! options, no cost history), on the 384 edges of the 16×8 ring (torus R = 1, r = 0.4). Divide
//! the reported time by 384 for the time per edge.

use criterion::{criterion_group, criterion_main, Criterion};
use curves::{BoundaryProblem, CurveMethod, UnitProblem};
use mesh::analytic::{torus_grid_edges, torus_point};
use std::hint::black_box;

fn torus_problems() -> Vec<(curves::VertexData, curves::VertexData)> {
    torus_grid_edges(16, 8)
        .into_iter()
        .map(|((ua, va), (ub, vb))| (torus_point(ua, va, 1.0, 0.4), torus_point(ub, vb, 1.0, 0.4)))
        .collect()
}

fn optimized_defaults() -> curves::Optimized {
    let o = curves::MethodOptions::default();
    curves::Optimized {
        solver: o.solver,
        weights: o.weights,
        alpha_min: o.alpha_min,
        solve_options: o.solve_options,
    }
}

fn bench(c: &mut Criterion) {
    let verts = torus_problems();
    let units: Vec<UnitProblem> = verts
        .iter()
        .filter_map(|(a, b)| BoundaryProblem::new((0, 1), a, b).ok())
        .map(|p| p.unit)
        .collect();
    let mut g = c.benchmark_group("torus16x8_384_edges");
    g.bench_function("boundary_problem", |b| {
        b.iter(|| {
            for (x, y) in &verts {
                black_box(BoundaryProblem::new((0, 1), black_box(x), black_box(y)).ok());
            }
        })
    });
    for m in [&curves::Chord as &dyn CurveMethod, &curves::Dbhs::default()] {
        g.bench_function(m.name(), |b| {
            b.iter(|| {
                for u in &units {
                    black_box(m.construct(black_box(u)));
                }
            })
        });
    }
    for kind in solver::SolverKind::ALL {
        let m = curves::Optimized {
            solver: kind,
            ..optimized_defaults()
        };
        g.bench_function(format!("optimized_{kind}"), |b| {
            b.iter(|| {
                for u in &units {
                    black_box(m.construct(black_box(u)));
                }
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

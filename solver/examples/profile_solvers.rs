//! A profiling loop: one adapter solving the benchmark's end-curvature problem many times, for
//! `perf stat` / `perf record` (criterion's own machinery would dominate a profile).
//!
//! ```sh
//! cargo build --release -p solver --example profile_solvers
//! perf stat -e cycles:u,instructions:u target/release/examples/profile_solvers lm 1000000
//! ```
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use nalgebra::{SMatrix, SVector, Vector2};
use solver::{LeastSquaresProblem, SolveOptions, SolverKind};
use std::hint::black_box;

/// The benchmark's problem (`benches/adapters.rs`).
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

fn main() {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "exact-penalty".into());
    let count: usize = args
        .next()
        .map_or(1_000_000, |s| s.parse().expect("a count"));
    let any = name.ends_with("-any");
    let kind: SolverKind = name
        .trim_end_matches("-any")
        .parse()
        .expect("a solver name");
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
    let start = std::time::Instant::now();
    for _ in 0..count {
        let s = if any {
            solver::solve_any(
                kind,
                black_box(&p),
                black_box(Vector2::new(1.0, 1.0)),
                &options,
            )
        } else {
            solver::solve(
                kind,
                black_box(&p),
                black_box(Vector2::new(1.0, 1.0)),
                &options,
            )
        };
        black_box(s.unwrap());
    }
    if std::env::var_os("SHOW").is_some() {
        let s = solver::solve(kind, &p, Vector2::new(1.0, 1.0), &options).unwrap();
        eprintln!("{}", s.report.table());
    }
    let per = start.elapsed().as_secs_f64() / count as f64;
    eprintln!("{name}: {:.3} µs per solve", per * 1e6);
}

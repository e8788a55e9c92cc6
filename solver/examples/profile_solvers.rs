//! A profiling loop: one adapter solving the benchmark's end-curvature problem many times, for
//! `perf stat` / `perf record` (criterion's own machinery would dominate a profile).
//!
//! ```sh
//! cargo build --release -p solver --example profile_solvers
//! perf stat -e cycles:u,instructions:u target/release/examples/profile_solvers lm 1000000
//! ```
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use nalgebra::Vector2;
use solver::{SolveOptions, SolverKind};
use std::hint::black_box;

/// The representative end-curvature problem, shared with the tests.
#[path = "../tests/suite/common/mod.rs"]
mod common;
use common::EndCurvature;

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
    let p = EndCurvature::representative();
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

//! The worst case of one `curve` line: 10⁶ random unit-chord problems, a third of them extreme
//! (curvatures from 10⁻³⁰ to 10³⁰ and exactly zero, tangents parallel, antiparallel and along
//! the chord), each answered as `experiments -- curve` answers a line — every registered
//! construction, and the curvature variation of every curve it reports (dBHS: every solution).
//! Prints the percentiles of the time per problem; the target is the 100th under 10 ms.
//!
//! `cargo bench -p curves --bench worst_case [-- N]` (N problems, default 10⁶).

use std::time::Instant;

use curves::{method_by_name, MethodOptions, UnitProblem, REGISTRY};
use nalgebra::Vector2;

use fixtures::SplitMix64 as Rng;

fn curvature(rng: &mut Rng) -> f64 {
    match (rng.next_f64() * 6.0) as usize {
        0 => 0.0,
        1 => {
            10f64.powf(60.0 * rng.next_f64() - 30.0) * if rng.next_f64() < 0.5 { -1.0 } else { 1.0 }
        }
        _ => 20.0 * rng.next_f64() - 10.0,
    }
}

fn tangent(rng: &mut Rng, other: Option<Vector2<f64>>) -> Vector2<f64> {
    let special = rng.next_f64();
    match (special, other) {
        (s, Some(t)) if s < 0.1 => t,      // parallel
        (s, Some(t)) if s < 0.2 => -t,     // antiparallel
        (s, _) if s < 0.3 => Vector2::x(), // along the chord
        _ => {
            let a = (rng.next_f64() - 0.5) * std::f64::consts::PI * 1.9;
            Vector2::new(a.cos(), a.sin())
        }
    }
}

fn main() {
    let n: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let options = MethodOptions::default();
    let methods: Vec<_> = REGISTRY
        .iter()
        .filter_map(|e| method_by_name(e.name, &options).ok())
        .collect();
    let mut rng = Rng::new(20_261_129);
    let mut times = Vec::with_capacity(n);
    let mut worst: Option<(f64, [f64; 6])> = None;
    for _ in 0..n {
        let t0 = tangent(&mut rng, None);
        let t1 = tangent(&mut rng, Some(t0));
        let (k0, k1) = (curvature(&mut rng), curvature(&mut rng));
        let start = Instant::now();
        if let Ok(p) = UnitProblem::new(t0, t1, k0, k1) {
            for m in &methods {
                let c = m.construct(&p);
                std::hint::black_box(p.curve(c.alpha).curvature_variation());
                for a in c.candidates.as_slice() {
                    std::hint::black_box(p.curve(*a).curvature_variation());
                }
            }
        }
        let dt = start.elapsed().as_secs_f64();
        if worst.is_none_or(|(w, _)| dt > w) {
            worst = Some((dt, [t0.x, t0.y, t1.x, t1.y, k0, k1]));
        }
        times.push(dt);
    }
    times.sort_by(f64::total_cmp);
    let pct = |q: f64| times[((times.len() - 1) as f64 * q) as usize] * 1e3;
    println!(
        "{n} problems: p50 {:.4} ms, p99 {:.4} ms, p99.99 {:.3} ms, p100 {:.3} ms",
        pct(0.5),
        pct(0.99),
        pct(0.9999),
        pct(1.0)
    );
    if let Some((w, [a, b, c, d, k0, k1])) = worst {
        println!(
            "slowest ({:.3} ms): {{\"t0\":[{a},{b}],\"t1\":[{c},{d}],\"k0\":{k0},\"k1\":{k1}}}",
            w * 1e3
        );
    }
}

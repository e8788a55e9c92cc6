//! Repeats `tessellate_fit` on a ring fit for profiling (`perf record`, `perf stat`), where a
//! criterion run on a shared machine cannot tell the stages apart:
//! `cargo run --release -p surface --example profile_tessellate -- FACES S REPEATS`
//! (FACES one of 10000, 102400, 1000000; defaults 1000000 1 5).

// A profiling driver on fixed valid data: a failed step should stop it loudly.
#![allow(clippy::expect_used)]

use std::time::Instant;

use curves::{method_by_name, MethodOptions};
use surface::{fit_scheme, scheme_by_name, tessellate_fit, SchemeOptions};

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number"))
        .collect();
    let faces = args.first().copied().unwrap_or(1_000_000);
    let s = args.get(1).copied().unwrap_or(1);
    let repeats = args.get(2).copied().unwrap_or(5);
    let (nu, nv) = match faces {
        10_000 => (100, 50),
        102_400 => (320, 160),
        _ => (1000, 500),
    };
    let chord = method_by_name("chord", &MethodOptions::default()).expect("registered");
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).expect("registered");
    let data = surface::datasets::ring(nu, nv).expect("valid resolution");
    let fit = fit_scheme(&data.mesh, scheme.as_ref(), chord.as_ref()).expect("fits");
    let triangles = data.mesh.num_faces() * 3 * s * s;
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let t = Instant::now();
        let tess = tessellate_fit(&data.mesh, &fit, s).expect("tessellates");
        let dt = t.elapsed().as_secs_f64();
        best = best.min(dt);
        std::hint::black_box(tess);
    }
    println!(
        "{} faces, s = {s}: best of {repeats} {:.2} ms, {:.2} M triangles/s",
        data.mesh.num_faces(),
        best * 1e3,
        triangles as f64 / best / 1e6
    );
}

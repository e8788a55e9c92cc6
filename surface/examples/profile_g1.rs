//! Profiling driver for the G1 measurement: `cargo run --release -p surface --example
//! profile_g1 -- [faces] [repeats]` measures a Shirman–Séquin fit of the ring (chord curves)
//! at 9 samples per boundary `repeats` times and prints the time per face (set
//! `RAYON_NUM_THREADS=1` for one thread; run under `perf record` to see where it goes).

#![allow(clippy::expect_used)] // a profiling driver on fixed valid data

use curves::{method_by_name, MethodOptions};
use surface::{fit_scheme, measure_g1, scheme_by_name, SchemeOptions};

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a number"))
        .collect();
    let faces = args.first().copied().unwrap_or(102_400);
    let repeats = args.get(1).copied().unwrap_or(20);
    // ring(nu, nv) has 2·nu·nv triangles; nu = 2 nv.
    let nv = ((faces as f64 / 4.0).sqrt().round() as usize).max(2);
    let data = surface::datasets::ring(2 * nv, nv).expect("valid resolution");
    let chord = method_by_name("chord", &MethodOptions::default()).expect("registered");
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).expect("registered");
    let fit = fit_scheme(&data.mesh, scheme.as_ref(), chord.as_ref()).expect("fits");
    let n = data.mesh.num_faces();
    let mut best = f64::INFINITY;
    let mut report = None;
    for _ in 0..repeats {
        let t = std::time::Instant::now();
        report = Some(measure_g1(&data.mesh, &fit, 9));
        best = best.min(t.elapsed().as_secs_f64());
    }
    println!(
        "{n} faces: best {:.1} ns a face ({:.3} M faces/s); {:?}",
        best * 1e9 / n as f64,
        n as f64 / best / 1e6,
        report.map(|r| (r.interior_max, r.exterior_max))
    );
}

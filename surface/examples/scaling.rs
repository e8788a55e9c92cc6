//! How the speed of each stage scales from 10³ to 10⁶ faces, and what a user gets per second at
//! each: `cargo run --release -p surface --example scaling [--features mimalloc] [MAX_FACES]`
//! (default 10⁶).
//!
//! The meshes are the irregular noisy tori of `fixtures --example big_mesh`
//! (`fixtures::large::noisy_torus`: jittered, random diagonals, noise a tenth of an edge) with
//! `2·nu·nv` triangles for `(nu, nv)` = (32, 16),
//! (100, 50), (320, 160), (1000, 500). Each stage runs on the previous stage's output; its time
//! is the best of several runs (more at the small sizes, where one run is short). Printed: the
//! cost per face in nanoseconds at each size, the spread (largest over smallest) from 10⁴ up and
//! from 10³ up, and the rate at the largest size. The scaling study of
//! docs/performance.md is this table.
//!
//! The last two rows are references without arithmetic: the nets' bytes copied between reused
//! buffers, and written into a fresh allocation. Their spreads are what the memory hierarchy
//! and the allocator alone impose on a stage that moves that many bytes a face.

// A measurement driver on fixed valid data: a failed step should stop it loudly.
#![allow(clippy::expect_used)]

use std::time::Instant;

/// With `--features mimalloc`: an allocator that keeps freed memory for the next allocation,
/// where glibc's malloc (the default) returns a freed block above its mmap threshold (32 MB at
/// most) to the system, so that each run of a large stage faults its output in afresh.
#[cfg(feature = "mimalloc")]
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

use curves::{method_by_name, MethodOptions};
use estimate::{estimator_by_name, prepare, EstimateChoice, DEFAULT_ESTIMATOR};
use rayon::prelude::*;
use surface::patch_io::{write_binary, write_jsonl};
use surface::{
    fit_scheme, fit_scheme_into, measure_g1, scheme_by_name, tessellate_fit, Fit, SchemeOptions,
};

/// Bytes of a face's nets (three quartic Bézier triangles of 15 points): the memory references'
/// unit.
const NET_BYTES: usize = 3 * 15 * 3 * 8;

/// Words per parallel chunk of the memory references (256 kB).
const CHUNK: usize = 1 << 15;

/// Runs of a stage at `faces` faces: about 2·10⁶ face-runs in all, at least 3, at most 200.
fn runs(faces: usize) -> usize {
    (2_000_000 / faces).clamp(3, 200)
}

/// Best wall time (seconds) of `runs` calls of `f`.
fn best<T>(runs: usize, mut f: impl FnMut() -> T) -> f64 {
    (0..runs)
        .map(|_| {
            let t = Instant::now();
            std::hint::black_box(f());
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

/// One stage: its name, the unit its rate counts, and per size (faces, seconds, units).
struct Stage {
    name: &'static str,
    unit: &'static str,
    rows: Vec<(usize, f64, f64)>,
}

/// Largest over smallest of `xs`.
fn spread(xs: &[f64]) -> f64 {
    let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
    hi / lo
}

fn main() {
    let max_faces: usize = std::env::args()
        .nth(1)
        .map_or(1_000_000, |a| a.parse().expect("MAX_FACES, a number"));
    // (nu, nv) of each torus; a size within 10 % of MAX_FACES counts as that size.
    let grids: Vec<(usize, usize)> = [(32usize, 16usize), (100, 50), (320, 160), (1000, 500)]
        .into_iter()
        .filter(|(nu, nv)| 2 * nu * nv <= max_faces + max_faces / 10)
        .collect();
    let sizes: Vec<usize> = grids.iter().map(|(nu, nv)| 2 * nu * nv).collect();
    let est = EstimateChoice::With(estimator_by_name(DEFAULT_ESTIMATOR).expect("registered"));
    let chord = method_by_name("chord", &MethodOptions::default()).expect("registered");
    let optimized = method_by_name("optimized", &MethodOptions::default()).expect("registered");
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).expect("registered");
    let identity = |p: &nalgebra::Point3<f64>| *p;
    let mut stages: Vec<Stage> = [
        ("repair + estimate (hybrid)", "faces"),
        ("fit, chord curves", "faces"),
        ("fit, optimized curves", "faces"),
        ("fit, optimized curves, into a reused Fit", "faces"),
        ("G1 measurement (9 samples an edge)", "faces"),
        ("tessellate s = 1", "output triangles"),
        ("tessellate s = 4", "output triangles"),
        ("patches as JSON Lines (to a sink)", "MB"),
        ("patches as binary .bzp (to a sink)", "MB"),
        ("reference: copy 1080 B a face, reused buffers", "MB"),
        ("reference: first touch of 1080 B a face, fresh", "MB"),
    ]
    .into_iter()
    .map(|(name, unit)| Stage {
        name,
        unit,
        rows: Vec::new(),
    })
    .collect();
    for &(nu, nv) in &grids {
        let faces = 2 * nu * nv;
        let raw = fixtures::large::noisy_torus(nu, nv);
        let n = runs(faces);
        eprintln!("{faces} faces, best of {n}");
        let mut record = |stage: usize, seconds: f64, units: f64| {
            stages[stage].rows.push((faces, seconds, units));
        };
        let t = best(n.min(20), || prepare(&raw, est, false).expect("prepares"));
        record(0, t, faces as f64);
        let mesh = prepare(&raw, est, false).expect("prepares").mesh;
        let t = best(n, || {
            fit_scheme(&mesh, scheme.as_ref(), chord.as_ref()).expect("fits")
        });
        record(1, t, faces as f64);
        let t = best(n, || {
            fit_scheme(&mesh, scheme.as_ref(), optimized.as_ref()).expect("fits")
        });
        record(2, t, faces as f64);
        let mut fit = Fit::default();
        let t = best(n, || {
            fit_scheme_into(&mesh, scheme.as_ref(), optimized.as_ref(), &mut fit).expect("fits")
        });
        record(3, t, faces as f64);
        let t = best(n, || measure_g1(&mesh, &fit, 9));
        record(4, t, faces as f64);
        let t = best(n, || tessellate_fit(&mesh, &fit, 1).expect("tessellates"));
        record(5, t, (3 * faces) as f64);
        if faces <= 200_000 {
            let t = best(n, || tessellate_fit(&mesh, &fit, 4).expect("tessellates"));
            record(6, t, (3 * 16 * faces) as f64);
        }
        let mut bytes = Vec::new();
        write_jsonl(&fit, &identity, &mut bytes).expect("writes");
        let t = best(n.min(20), || {
            write_jsonl(&fit, &identity, &mut std::io::sink()).expect("writes")
        });
        record(7, t, bytes.len() as f64 / 1e6);
        bytes = Vec::new();
        write_binary(&fit, &identity, &mut bytes).expect("writes");
        let t = best(n.min(20), || {
            write_binary(&fit, &identity, &mut std::io::sink()).expect("writes")
        });
        record(8, t, bytes.len() as f64 / 1e6);
        // What the memory gives at this size, without any arithmetic: the nets' bytes (three
        // quartics, 1080 B a face) copied between two buffers that are reused (a cache-resident
        // size against one that streams from memory), and written into a fresh allocation
        // (glibc maps a block above 32 MB anew, so every run pays its page faults). Both on all
        // threads in chunks, as the stages above run.
        let words = faces * NET_BYTES / 8;
        let src = vec![1.0f64; words];
        let mut dst = vec![0.0f64; words];
        let t = best(n, || {
            dst.par_chunks_mut(CHUNK)
                .zip(src.par_chunks(CHUNK))
                .for_each(|(d, s)| d.copy_from_slice(s));
        });
        record(9, t, (faces * NET_BYTES) as f64 / 1e6);
        let t = best(n.min(20), || {
            let mut fresh = vec![0.0f64; words];
            fresh.par_chunks_mut(CHUNK).for_each(|d| d.fill(2.0));
            fresh
        });
        record(10, t, (faces * NET_BYTES) as f64 / 1e6);
    }
    print!("| stage |");
    for faces in &sizes {
        print!(" ns a face at {faces} |");
    }
    println!(" spread from 10⁴ / from 10³ | per second at the largest size |");
    print!("|---|");
    for _ in &sizes {
        print!("---:|");
    }
    println!("---:|---:|");
    for s in &stages {
        print!("| {} |", s.name);
        let per_face: Vec<f64> = s.rows.iter().map(|r| r.1 / r.0 as f64 * 1e9).collect();
        for &faces in &sizes {
            match s.rows.iter().position(|r| r.0 == faces) {
                Some(i) => print!(" {:.0} |", per_face[i]),
                None => print!(" – |"),
            }
        }
        let from_1e4: Vec<f64> = s
            .rows
            .iter()
            .zip(&per_face)
            .filter(|(r, _)| r.0 >= 10_000)
            .map(|(_, x)| *x)
            .collect();
        let rate = s.rows.last().map_or(0.0, |r| r.2 / r.1);
        println!(
            " {:.2} / {:.2} | {:.3e} {} |",
            spread(&from_1e4),
            spread(&per_face),
            rate,
            s.unit
        );
    }
}

//! Reads a mesh file and repairs it several times, for profiling the way from a file to a
//! validated mesh (`perf record`, `perf stat`): prints the read time, each repair's
//! wall and CPU time (the process's user + system time, all threads), and the time of building
//! the repaired mesh again with `Mesh::new_allowing_degenerate` (the validation part):
//! `cargo run --release -p surface --example profile_repair -- FILE [REPEATS]` (default 5).

// A profiling driver on fixed valid data: a failed step should stop it loudly.
#![allow(clippy::expect_used)]

use std::time::Instant;

use mesh::repair::{repair, RepairOptions};
use mesh::Mesh;

/// CPU time of the process so far (user + system, all threads), seconds, from
/// `/proc/self/stat` (clock ticks of 1/100 s); 0 where that file cannot be read.
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // Fields after the command name (which ends with ')'): utime and stime are the
            // 12th and 13th.
            let rest = s.rsplit_once(')')?.1;
            let f: Vec<&str> = rest.split_whitespace().collect();
            let ticks: f64 = f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?;
            Some(ticks / 100.0)
        })
        .unwrap_or(0.0)
}

/// The median (NaN for none).
fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs.get(xs.len() / 2).copied().unwrap_or(f64::NAN)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("usage: profile_repair FILE [REPEATS]");
    let repeats: usize = args.next().map_or(5, |s| s.parse().expect("a number"));
    let (t, c) = (Instant::now(), cpu_seconds());
    let raw = meshio::read_file(&path).expect("read");
    println!(
        "{path}: {} vertices, {} faces; read {:.3} s wall, {:.2} s CPU",
        raw.positions.len(),
        raw.polygons.len(),
        t.elapsed().as_secs_f64(),
        cpu_seconds() - c
    );
    let (mut walls, mut cpus, mut builds) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..repeats {
        let (t, c) = (Instant::now(), cpu_seconds());
        let r = repair(&raw, &RepairOptions::default()).expect("repairs");
        walls.push(t.elapsed().as_secs_f64());
        cpus.push(cpu_seconds() - c);
        let (vertices, faces) = (r.mesh.vertices().to_vec(), r.mesh.faces().to_vec());
        drop(r);
        let t = Instant::now();
        let m = Mesh::new_allowing_degenerate(vertices, faces).expect("valid");
        builds.push(t.elapsed().as_secs_f64());
        std::hint::black_box(m);
    }
    let show = |xs: &[f64]| {
        xs.iter()
            .take(10)
            .map(|x| format!("{x:.4}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    println!(
        "repair wall: median {:.4} s [{}]",
        median(walls.clone()),
        show(&walls)
    );
    println!(
        "repair CPU:  median {:.2} s, mean {:.4} s [{}]",
        median(cpus.clone()),
        cpus.iter().sum::<f64>() / cpus.len().max(1) as f64,
        show(&cpus)
    );
    println!(
        "Mesh::new_allowing_degenerate alone: median {:.4} s [{}]",
        median(builds.clone()),
        show(&builds)
    );
}

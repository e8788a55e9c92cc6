//! A profiling and regression driver for the estimators.
//!
//! * `cargo run --release -p estimate --example estimator_speed -- time NAME [RUNS] [MESH]`
//!   prepares one mesh (the working frame and repair of `estimate::prepare`, no estimation) and
//!   runs the estimator `NAME` (or `none`, for the set-up cost alone) `RUNS` times (default 1),
//!   printing the wall and CPU (user + system, all threads) seconds of each run. `MESH` is a
//!   mesh file, or `torus:NU:NV` for `fixtures::large::noisy_torus(NU, NV)` (default
//!   `torus:1000:500`, 10⁶ faces, the mesh of `fixtures --example big_mesh`). Under
//!   `perf stat` or `perf record` with `none` as the baseline it isolates an estimator's cost.
//!   Each run also prints how far the peak resident memory rose above the prepared mesh's.
//! * `… -- hash` prints one 64-bit FNV-1a hash per (mesh, estimator, given normals or not) of
//!   the bits of every normal, every shape tensor and every fallback, over the small zoo of
//!   hostile meshes (`fixtures::zoo`), the corpus meshes and the noisy tori at 10⁴ and 10⁶
//!   faces: two builds that print the same lines estimate the same values, bit for bit. The
//!   given-normals runs pass the Area-weighted vertex normals with every 97th one spoiled
//!   (zero, NaN, missing past the end) so that the kept-normal and invalid-normal paths count.

// A measurement driver on fixed valid data: a failed step should stop it loudly.
#![allow(clippy::expect_used)]

use std::time::Instant;

use estimate::{estimator_by_name, vertex_normals, Estimate, NormalWeighting, ESTIMATORS};
use mesh::repair::{repair, RepairOptions};
use mesh::Mesh;
use meshio::RawMesh;
use nalgebra::Vector3;

/// The mesh of `spec`: a file, or `torus:NU:NV`.
fn raw_mesh(spec: &str) -> RawMesh {
    match spec.strip_prefix("torus:") {
        Some(rest) => {
            let mut it = rest.split(':').map(|x| x.parse().expect("torus:NU:NV"));
            let nu = it.next().expect("NU");
            let nv = it.next().expect("NV");
            fixtures::large::noisy_torus(nu, nv)
        }
        None => meshio::read_file(spec).expect("readable mesh"),
    }
}

/// What `estimate::prepare_owned` does before estimating: the working frame, then the repair.
fn prepared(mut raw: RawMesh) -> Mesh {
    let frame = mesh::Frame::of_points(&raw.positions).expect("finite extent");
    for p in &mut raw.positions {
        *p = frame.to_work(p);
    }
    repair(&raw, &RepairOptions::default())
        .expect("repairable")
        .mesh
}

/// User plus system CPU seconds of this process (all threads), from `/proc/self/stat`.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let after = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let fields: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|x| x.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    // Field 14 is index 11 after the state (field 3 is index 0); clock ticks of 1/100 s.
    (ticks(11) + ticks(12)) / 100.0
}

/// A `kB` line of `/proc/self/status` in MB (`VmHWM`: the peak resident memory, `VmRSS`: the
/// current one).
fn status_mb(key: &str) -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with(key))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1000.0)
}

/// Resets the peak resident memory to the current one (writing `5` to `/proc/self/clear_refs`,
/// Linux 4.0 on) and returns the current one, MB.
fn reset_peak_mb() -> f64 {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
    status_mb("VmRSS:")
}

/// FNV-1a over 64-bit words.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn word(&mut self, w: u64) {
        for b in w.to_le_bytes() {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// The hash of every bit of an estimate.
fn hash(e: &Estimate) -> u64 {
    let mut h = Fnv::new();
    h.word(e.normals.len() as u64);
    for n in &e.normals {
        n.iter().for_each(|c| h.word(c.to_bits()));
    }
    for s in &e.shapes {
        s.iter().for_each(|c| h.word(c.to_bits()));
    }
    for f in &e.fallbacks {
        h.word(f.vertex as u64);
        for b in format!("{:?}", f.kind).bytes() {
            h.word(u64::from(b));
        }
    }
    h.0
}

/// Area-weighted normals with every 97th spoiled, one in three of those left off the end.
fn spoiled_normals(mesh: &Mesh) -> Vec<Vector3<f64>> {
    let mut given = vertex_normals(mesh, NormalWeighting::Area).normals;
    for (i, n) in given.iter_mut().enumerate().filter(|(i, _)| i % 97 == 5) {
        *n = if i % 2 == 0 {
            Vector3::zeros()
        } else {
            Vector3::new(f64::NAN, 0.0, 1.0)
        };
    }
    let keep = given.len().saturating_sub(given.len() / 300);
    given.truncate(keep);
    given
}

fn hash_all() {
    let mut meshes: Vec<(String, RawMesh)> = fixtures::zoo()
        .into_iter()
        .map(|(n, m)| (n.to_string(), m))
        .collect();
    for path in fixtures::corpus::corpus_files() {
        let name = path
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().into());
        meshes.push((name, meshio::read_file(&path).expect("corpus mesh")));
    }
    meshes.push(("torus_1e4".into(), fixtures::large::noisy_torus(100, 50)));
    meshes.push(("torus_1e6".into(), fixtures::large::noisy_torus(1000, 500)));
    for (name, raw) in meshes {
        let Ok(rep) = repair(&raw, &RepairOptions::default()) else {
            println!("{name}: not repairable");
            continue;
        };
        let mesh = rep.mesh;
        let given = spoiled_normals(&mesh);
        for est in ESTIMATORS {
            let free = hash(&est.estimate(&mesh, None));
            let kept = hash(&est.estimate(&mesh, Some(&given)));
            println!("{name} {} {free:016x} {kept:016x}", est.name());
        }
    }
}

fn time(name: &str, runs: usize, spec: &str) {
    let mesh = prepared(raw_mesh(spec));
    println!(
        "{spec}: {} vertices, {} faces",
        mesh.num_vertices(),
        mesh.num_faces()
    );
    if name == "none" {
        return;
    }
    let est = estimator_by_name(name).expect("registered estimator");
    for _ in 0..runs {
        let before = reset_peak_mb();
        let (c, t) = (cpu_seconds(), Instant::now());
        let e = std::hint::black_box(est.estimate(&mesh, None));
        let wall = t.elapsed().as_secs_f64();
        let cpu = cpu_seconds() - c;
        let peak = status_mb("VmHWM:") - before;
        println!(
            "{name}: wall {wall:.3} s, cpu {cpu:.2} s, peak +{peak:.0} MB, hash {:016x}",
            hash(&e)
        );
        drop(e);
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("hash") => hash_all(),
        Some("time") => {
            let name = args.get(1).expect("estimator name");
            let runs = args.get(2).map_or(1, |r| r.parse().expect("RUNS"));
            let spec = args.get(3).map_or("torus:1000:500", String::as_str);
            time(name, runs, spec);
        }
        _ => eprintln!("usage: estimator_speed hash | time NAME [RUNS] [MESH]"),
    }
}

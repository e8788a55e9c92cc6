//! What crease detection and per-sector estimation add to the default estimation at 10⁶
//! triangles (target: at most 25 %): the default estimator (`hybrid`) on the mesh as it is
//! (one normal per vertex, what `--no-creases` does) against [`estimate::attach_creases`] by
//! the default rule followed by the same estimation per sector (the mesh cut along its
//! creases, [`mesh::Sectors::split_mesh`]).
//!
//! Two meshes: a box meshed 289 × 289 cells a side (1 002 252 triangles, 12 crease lines of 289
//! edges each, 8 corners: every vertex on them split into two or three sectors), and the ring
//! at 1000 × 500 (10⁶ triangles, smooth: the detection finds nothing, its cost alone).
//! Measured numbers are in docs/performance.md.

#![allow(clippy::expect_used)] // a benchmark on fixed valid data
#![allow(missing_docs)] // criterion's macros generate undocumented items

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, Throughput};
use mesh::features::CreaseRule;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("creases_1e6");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(8));
    let est = estimate::estimator_by_name(estimate::DEFAULT_ESTIMATOR).expect("the default");
    let boxed = mesh::repair::repair(
        &fixtures::creases::box_mesh(289, [1.0, 0.8, 0.6]),
        &mesh::repair::RepairOptions::default(),
    )
    .expect("a valid box")
    .mesh;
    let ring = mesh::datasets::ring(1000, 500).expect("valid").mesh;
    for (name, m) in [("box", &boxed), ("ring", &ring)] {
        g.throughput(Throughput::Elements(m.num_faces() as u64));
        g.bench_with_input(BenchmarkId::new("per_vertex", name), m, |b, m| {
            b.iter_batched(
                || m.clone(),
                |mut m| {
                    let summary = estimate::apply(&mut m, est, false);
                    // Returned, so the mesh is dropped outside the timing.
                    (m, summary)
                },
                BatchSize::LargeInput,
            )
        });
        g.bench_with_input(BenchmarkId::new("creases_and_sectors", name), m, |b, m| {
            b.iter_batched(
                || m.clone(),
                |mut m| {
                    let found = estimate::attach_creases(&mut m, CreaseRule::Auto, &[]);
                    let summary = estimate::apply(&mut m, est, false);
                    (m, found, summary)
                },
                BatchSize::LargeInput,
            )
        });
        g.bench_with_input(BenchmarkId::new("detection_only", name), m, |b, m| {
            b.iter_batched(
                || m.clone(),
                |mut m| {
                    let found = estimate::attach_creases(&mut m, CreaseRule::Auto, &[]);
                    (m, found)
                },
                BatchSize::LargeInput,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

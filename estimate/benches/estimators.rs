//! Estimation speed: every registered estimator on rings of about 10⁵ and 10⁶ triangles
//! (`mesh::datasets::ring(nu, nv)` has `2 nu nv` triangles), all cores (rayon over vertices).
//! Throughput is reported in triangles per second.
//!
//! Measured 2026-11-29 on the 2-core build machine, shared with other builds (load 2–3, so
//! expect ±30 %): ring 316×158 (99 856 triangles, 49 928 vertices) / ring 1000×500 (10⁶
//! triangles, 5·10⁵ vertices):
//!
//! | estimator | 10⁵ | 10⁶ |
//! |---|---|---|
//! | jet (= jet2) | 53 ms | 0.35 s (0.55 s under heavier load) |
//! | jet3 | 117 ms | 0.68 s |
//! | jet4 | 175 ms | 1.0 s |
//! | quadric | 50 ms | 0.29–0.34 s |
//! | rusinkiewicz | 50 ms | 0.30 s |
//!
//! Stages at 10⁶: adjacency ([`estimate::Topology`]) 53 ms (sequential), angle-weighted
//! normals 53 ms; one vertex on one thread: 2-ring gathering 90 ns, degree-2 fit 0.75 µs.

#![allow(clippy::expect_used)] // a benchmark on fixed valid data
#![allow(missing_docs)] // criterion's macros generate undocumented items

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use estimate::ESTIMATORS;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("estimate_ring");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(3));
    for (nu, nv) in [(316usize, 158usize), (1000, 500)] {
        let data = mesh::datasets::ring(nu, nv).expect("valid resolution");
        let faces = data.mesh.num_faces();
        g.throughput(Throughput::Elements(faces as u64));
        for est in ESTIMATORS {
            // `jet` is `jet2` under its recommended name: timed once.
            if est.name() == "jet2" {
                continue;
            }
            g.bench_with_input(
                BenchmarkId::new(est.name(), faces),
                &data.mesh,
                |b, mesh| b.iter(|| est.estimate(mesh, None)),
            );
        }
    }
    g.finish();
}

/// The shared stages on the 10⁶-triangle ring: adjacency and first normals.
fn stages(c: &mut Criterion) {
    let mut g = c.benchmark_group("stages_ring");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(2));
    let data = mesh::datasets::ring(1000, 500).expect("valid resolution");
    let faces = data.mesh.num_faces();
    g.throughput(Throughput::Elements(faces as u64));
    g.bench_function(BenchmarkId::new("topology", faces), |b| {
        b.iter(|| estimate::Topology::new(&data.mesh))
    });
    let topo = estimate::Topology::new(&data.mesh);
    g.bench_function(BenchmarkId::new("angle_normals", faces), |b| {
        b.iter(|| {
            estimate::normals::vertex_normals_with(
                &data.mesh,
                &topo,
                estimate::NormalWeighting::Angle,
                None,
            )
        })
    });
    // One vertex, one thread: the parts of the jet's hot loop.
    let spec = estimate::fit::FitSpec {
        degree: 2,
        constant: true,
        rule: estimate::fit::RingRule {
            min_points: 12,
            max_rings: 5,
            max_points: 200,
        },
    };
    let mut ws = estimate::fit::Workspace::default();
    let n0 = data.mesh.vertices()[1234].data.n;
    g.throughput(Throughput::Elements(1));
    g.bench_function("rings_into_one_vertex", |b| {
        b.iter(|| topo.rings_into(1234, 12, 5, 200, &mut ws.ring))
    });
    g.bench_function("jet2_one_vertex", |b| {
        b.iter(|| estimate::fit::fit_vertex(&data.mesh, &topo, 1234, &n0, &spec, &mut ws))
    });
    let _ = estimate::fit::fit_vertex(&data.mesh, &topo, 1234, &n0, &spec, &mut ws);
    g.bench_function("fit_height_one_vertex", |b| {
        b.iter(|| estimate::fit::fit_height(&mut ws, 2, true))
    });
    g.finish();
}

criterion_group!(benches, bench, stages);
criterion_main!(benches);

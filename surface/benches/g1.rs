//! G1 measurement speed (`surface::measure_g1`, 9 samples per boundary, as `fit` runs it) on
//! rings of 10⁴ to 10⁶ triangles, for the Shirman–Séquin layout (three quartics per face, 3
//! interior boundaries) and one-patch schemes, all cores. Throughput in faces per second
//! (the target: at least 10⁶ faces/s; docs/performance.md).

#![allow(clippy::expect_used)] // a benchmark on fixed valid data

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use curves::{method_by_name, MethodOptions};
use surface::{fit_scheme, measure_g1, scheme_by_name, SchemeOptions};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("g1_ring");
    g.sample_size(10);
    let chord = method_by_name("chord", &MethodOptions::default()).expect("registered");
    // ring(nu, nv) has 2·nu·nv triangles.
    for (nu, nv) in [(100usize, 50usize), (320, 160), (1000, 500)] {
        let data = surface::datasets::ring(nu, nv).expect("valid resolution");
        let faces = data.mesh.num_faces();
        g.throughput(Throughput::Elements(faces as u64));
        for name in ["shirman-sequin", "pn-triangles"] {
            let scheme = scheme_by_name(name, &SchemeOptions::default()).expect("registered");
            let fit = fit_scheme(&data.mesh, scheme.as_ref(), chord.as_ref()).expect("fits");
            g.bench_with_input(BenchmarkId::new(name, faces), &data.mesh, |b, mesh| {
                b.iter(|| measure_g1(mesh, &fit, 9))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

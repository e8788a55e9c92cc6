//! Tessellation speed in output triangles per second (positions, normals, K, H, shape
//! tensors): the positional weld (`tessellate`) and the topological one (`tessellate_fit`) on
//! ring fits of 10⁴ and 10⁵ faces (Shirman–Séquin, three quartics per face) at s = 1, 4, 8,
//! and 10⁶ faces at s = 1 (the target: at least 10⁷ output triangles per second).

#![allow(clippy::expect_used)] // a benchmark on fixed valid data

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use curves::{method_by_name, MethodOptions};
use surface::{fit_scheme, scheme_by_name, tessellate, tessellate_fit, SchemeOptions};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("tessellate_ring");
    g.sample_size(10);
    let chord = method_by_name("chord", &MethodOptions::default()).expect("registered");
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).expect("registered");
    for (nu, nv, densities) in [
        (100usize, 50usize, &[1usize, 4, 8][..]),
        (320, 160, &[1, 4][..]),
        (1000, 500, &[1][..]),
    ] {
        let data = surface::datasets::ring(nu, nv).expect("valid resolution");
        let fit = fit_scheme(&data.mesh, scheme.as_ref(), chord.as_ref()).expect("fits");
        let faces = data.mesh.num_faces();
        for &s in densities {
            let triangles = (faces * 3 * s * s) as u64;
            g.throughput(Throughput::Elements(triangles));
            let id = format!("{faces}f/s{s}");
            g.bench_with_input(BenchmarkId::new("topological", &id), &s, |b, &s| {
                b.iter(|| tessellate_fit(&data.mesh, &fit, s).expect("tessellates"))
            });
            if faces <= 102_400 {
                let patches = fit.bezier_patches();
                g.bench_with_input(BenchmarkId::new("positional", &id), &s, |b, &s| {
                    b.iter(|| tessellate(&patches, s).expect("tessellates"))
                });
            }
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

//! Fitting speed: the modified Shirman–Séquin scheme on rings of 10³ to 10⁶ triangles with
//! `chord` and `optimized` (exact-penalty) curves, all cores (rayon), buffers reused as in a
//! sweep. Throughput is reported in triangles per second. `fit_ring` builds every face at the
//! given parameters (`ShirmanSequin::per_face`, as sweeps and optimizers do); `fit_ring_scheme`
//! is the registered scheme `fit` and the pipeline use (its crease lines read per face).

#![allow(clippy::expect_used)] // a benchmark on fixed valid data

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use curves::{method_by_name, MethodOptions};
use surface::fit::fit_scheme_into;
use surface::{fit_into, scheme_by_name, Fit, InteriorParameters, SchemeOptions};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("fit_ring");
    g.sample_size(10);
    // ring(nu, nv) has 2·nu·nv triangles.
    for (nu, nv) in [(32usize, 16usize), (100, 50), (320, 160), (1000, 500)] {
        let data = surface::datasets::ring(nu, nv).expect("valid resolution");
        let faces = data.mesh.num_faces();
        g.throughput(Throughput::Elements(faces as u64));
        for name in ["chord", "optimized"] {
            let m = method_by_name(name, &MethodOptions::default()).expect("registered");
            // Buffers are reused across iterations, as in a sweep (`fit_into`).
            let mut out = Fit::default();
            g.bench_with_input(BenchmarkId::new(name, faces), &data.mesh, |b, mesh| {
                b.iter(|| {
                    fit_into(
                        mesh,
                        m.as_ref(),
                        &|_| InteriorParameters::default(),
                        &mut out,
                    )
                    .expect("fits")
                })
            });
        }
    }
    g.finish();
    let mut g = c.benchmark_group("fit_ring_scheme");
    g.sample_size(10);
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).expect("registered");
    for (nu, nv) in [(100usize, 50usize), (1000, 500)] {
        let data = surface::datasets::ring(nu, nv).expect("valid resolution");
        let faces = data.mesh.num_faces();
        g.throughput(Throughput::Elements(faces as u64));
        for name in ["chord", "optimized"] {
            let m = method_by_name(name, &MethodOptions::default()).expect("registered");
            let mut out = Fit::default();
            g.bench_with_input(BenchmarkId::new(name, faces), &data.mesh, |b, mesh| {
                b.iter(|| {
                    fit_scheme_into(mesh, scheme.as_ref(), m.as_ref(), &mut out).expect("fits")
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

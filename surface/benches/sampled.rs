//! Speed of the sampled (non-Bézier) schemes through the patch abstraction: Nielson's
//! side-vertex interpolant and its discrete counterpart, tessellated at s = 8 with positions,
//! normals, K, H and shape tensors, on ring fits of 10⁴ and 10⁵ faces (the target: at least 10⁵
//! faces per second), beside PN triangles (a Bézier cubic per face) at the same s.

#![allow(clippy::expect_used)] // a benchmark on fixed valid data

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use curves::{method_by_name, MethodOptions};
use surface::{fit_scheme, scheme_by_name, tessellate_fit, SchemeOptions};

/// Segments per face edge, the sampling of the target (the testbed's `Tess -s 8`).
const S: usize = 8;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("sampled_s8");
    g.sample_size(10);
    let chord = method_by_name("chord", &MethodOptions::default()).expect("registered");
    for (nu, nv) in [(100usize, 50usize), (320, 160)] {
        let data = surface::datasets::ring(nu, nv).expect("valid resolution");
        let faces = data.mesh.num_faces();
        for name in ["nielson", "discrete-side-vertex", "pn-triangles"] {
            let scheme = scheme_by_name(name, &SchemeOptions::default()).expect("registered");
            let fit = fit_scheme(&data.mesh, scheme.as_ref(), chord.as_ref()).expect("fits");
            g.throughput(Throughput::Elements(faces as u64));
            g.bench_with_input(BenchmarkId::new(name, faces), &S, |b, &s| {
                b.iter(|| tessellate_fit(&data.mesh, &fit, s).expect("tessellates"))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

//! Fitting speed: the modified Shirman–Séquin scheme on rings of 10³ to 10⁶ triangles with
//! `chord` and `optimized` (exact-penalty) curves, all cores (rayon), buffers reused as in a
//! sweep. Throughput is reported in triangles per second. `fit_ring` builds every face at the
//! given parameters (`ShirmanSequin::per_face`, as sweeps and optimizers do); `fit_ring_scheme`
//! is the registered scheme `fit` and the pipeline use (its crease lines read per face);
//! `fit_ring_curvature` the `shirman-sequin-curvature` variant (the shape tensors in the
//! cross-boundary field).

#![allow(clippy::expect_used)] // a benchmark on fixed valid data

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use curves::{method_by_name, CurveMethod, MethodOptions};
use surface::fit::fit_scheme_into;
use surface::{fit_into, scheme_by_name, Fit, InteriorParameters, Mesh, SchemeOptions};

/// One group: `fit` (mesh, method, reused buffers) on rings of `sizes` with `chord` and
/// `optimized` curves.
fn group(
    c: &mut Criterion,
    name: &str,
    sizes: &[(usize, usize)],
    fit: &dyn Fn(&Mesh, &dyn CurveMethod, &mut Fit),
) {
    let mut g = c.benchmark_group(name);
    g.sample_size(10);
    // ring(nu, nv) has 2·nu·nv triangles.
    for &(nu, nv) in sizes {
        let data = surface::datasets::ring(nu, nv).expect("valid resolution");
        let faces = data.mesh.num_faces();
        g.throughput(Throughput::Elements(faces as u64));
        for curves in ["chord", "optimized"] {
            let m = method_by_name(curves, &MethodOptions::default()).expect("registered");
            // Buffers are reused across iterations, as in a sweep.
            let mut out = Fit::default();
            g.bench_with_input(BenchmarkId::new(curves, faces), &data.mesh, |b, mesh| {
                b.iter(|| fit(mesh, m.as_ref(), &mut out))
            });
        }
    }
    g.finish();
}

fn bench(c: &mut Criterion) {
    let sizes = [(32, 16), (100, 50), (320, 160), (1000, 500)];
    group(c, "fit_ring", &sizes, &|mesh, m, out| {
        fit_into(mesh, m, &|_| InteriorParameters::default(), out).expect("fits")
    });
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).expect("registered");
    group(
        c,
        "fit_ring_scheme",
        &[sizes[1], sizes[3]],
        &|mesh, m, out| fit_scheme_into(mesh, scheme.as_ref(), m, out).expect("fits"),
    );
    let curvature =
        scheme_by_name("shirman-sequin-curvature", &SchemeOptions::default()).expect("registered");
    group(
        c,
        "fit_ring_curvature",
        &[sizes[1], sizes[3]],
        &|mesh, m, out| fit_scheme_into(mesh, curvature.as_ref(), m, out).expect("fits"),
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);

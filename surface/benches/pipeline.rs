//! The whole input path at scale: a positions-only binary PLY of a regular torus grid (10⁵ and
//! 10⁶ triangles) read, repaired, completed by the default estimator, fitted with optimized
//! curves (exact penalty), tessellated at `s = 1` (the three sub-triangles of each macro-patch,
//! with the patch normals) and written as glTF binary. Each stage is timed on its own, then the
//! whole path end to end; the real-mesh target is < 3 s at 10⁶ triangles on 2 cores
//! (docs/performance.md).

#![allow(clippy::expect_used, clippy::unwrap_used)] // benchmark fixtures fail loudly by design

use criterion::{criterion_group, criterion_main, Criterion};
use curves::{method_by_name, MethodOptions};
use estimate::{estimator_by_name, prepare, EstimateChoice, DEFAULT_ESTIMATOR};
use meshio::{format_by_name, WriteOptions};
use std::path::Path;
use surface::{fit, tessellate, InteriorParameters};

fn glb(tess: &surface::Tessellation) -> Vec<u8> {
    format_by_name("glb")
        .unwrap()
        .write(&tess.to_raw(), &WriteOptions::new())
        .unwrap()
}

fn pipeline(c: &mut Criterion) {
    let ply = format_by_name("ply").unwrap();
    let method = method_by_name("optimized", &MethodOptions::default()).unwrap();
    let est = EstimateChoice::With(estimator_by_name(DEFAULT_ESTIMATOR).unwrap());
    let params = |_| InteriorParameters::default();
    for (nu, nv) in [(317usize, 158usize), (1000, 500)] {
        let bytes = ply
            .write(&fixtures::large::ring_grid(nu, nv), &WriteOptions::new())
            .unwrap();
        let label = format!("{}k triangles", 2 * nu * nv / 1000);
        let mut g = c.benchmark_group(format!("pipeline/{label}"));
        g.sample_size(10);
        let raw = meshio::read_bytes(Path::new("ring.ply"), &bytes).unwrap();
        let prepared = prepare(&raw, est, false).unwrap();
        let fitted = fit(&prepared.mesh, method.as_ref(), &params).unwrap();
        let tess = tessellate(&fitted.bezier_patches(), 1).unwrap();
        g.bench_function("read", |b| {
            b.iter(|| meshio::read_bytes(Path::new("ring.ply"), &bytes).unwrap())
        });
        g.bench_function("repair", |b| {
            b.iter(|| surface::repair::repair(&raw, &Default::default()).unwrap())
        });
        g.bench_function("repair+estimate", |b| {
            b.iter(|| prepare(&raw, est, false).unwrap())
        });
        g.bench_function("fit optimized", |b| {
            b.iter(|| fit(&prepared.mesh, method.as_ref(), &params).unwrap())
        });
        g.bench_function("tessellate s=1", |b| {
            b.iter(|| tessellate(&fitted.bezier_patches(), 1).unwrap())
        });
        g.bench_function("write glb", |b| b.iter(|| glb(&tess)));
        g.bench_function("end to end", |b| {
            b.iter(|| {
                let raw = meshio::read_bytes(Path::new("ring.ply"), &bytes).unwrap();
                let p = prepare(&raw, est, false).unwrap();
                let f = fit(&p.mesh, method.as_ref(), &params).unwrap();
                glb(&tessellate(&f.bezier_patches(), 1).unwrap())
            })
        });
        g.finish();
    }
}

criterion_group!(benches, pipeline);
criterion_main!(benches);

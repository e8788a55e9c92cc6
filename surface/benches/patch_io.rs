//! Patch output speed in bytes per second, formatting into a sink (no disk): JSON Lines and
//! the binary form of a 10⁵-face ring fit (Shirman–Séquin, 45 control points per face).

#![allow(clippy::expect_used)] // a benchmark on fixed valid data

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use curves::{method_by_name, MethodOptions};
use nalgebra::Point3;
use surface::patch_io::{write_binary, write_jsonl};
use surface::{fit_scheme, scheme_by_name, SchemeOptions};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("patch_io");
    g.sample_size(10);
    let data = surface::datasets::ring(320, 160).expect("valid resolution");
    let chord = method_by_name("chord", &MethodOptions::default()).expect("registered");
    let scheme = scheme_by_name("shirman-sequin", &SchemeOptions::default()).expect("registered");
    let fit = fit_scheme(&data.mesh, scheme.as_ref(), chord.as_ref()).expect("fits");
    let id = |p: &Point3<f64>| *p;
    let mut bytes = Vec::new();
    write_jsonl(&fit, &id, &mut bytes).expect("writes");
    g.throughput(Throughput::Bytes(bytes.len() as u64));
    g.bench_function("jsonl_102400_faces", |b| {
        b.iter(|| write_jsonl(&fit, &id, &mut std::io::sink()).expect("writes"))
    });
    bytes.clear();
    write_binary(&fit, &id, &mut bytes).expect("writes");
    g.throughput(Throughput::Bytes(bytes.len() as u64));
    g.bench_function("binary_102400_faces", |b| {
        b.iter(|| write_binary(&fit, &id, &mut std::io::sink()).expect("writes"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

//! Reading and writing a 10⁶-triangle grid mesh in memory: binary PLY and glTF binary.
#![allow(missing_docs)]
#![allow(clippy::expect_used)] // a benchmark on fixed valid data

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use meshio::{format_by_name, WriteOptions};

#[path = "../tests/suite/common/mod.rs"]
mod common;
use common::grid;

fn bench(c: &mut Criterion) {
    // 708² · 2 ≈ 1.0 · 10⁶ triangles.
    let mesh = grid(708);
    let opts = WriteOptions::new();
    let ply = format_by_name("ply").expect("ply");
    let glb = format_by_name("glb").expect("glb");
    let ply_bytes = ply.write(&mesh, &opts).expect("write ply");
    let glb_bytes = glb.write(&mesh, &opts).expect("write glb");
    let mut g = c.benchmark_group("formats_1M_triangles");
    g.sample_size(10);
    g.throughput(Throughput::Bytes(ply_bytes.len() as u64));
    g.bench_function("ply_binary_read", |b| {
        b.iter(|| ply.read(&ply_bytes).expect("read"))
    });
    g.bench_function("ply_binary_write", |b| {
        b.iter(|| ply.write(&mesh, &opts).expect("write"))
    });
    // The testbed format against OBJ on the same mesh (the target: within 2× in time and memory).
    let obj = format_by_name("obj").expect("obj");
    let testbed = format_by_name("testbed").expect("testbed");
    let obj_bytes = obj.write(&mesh, &opts).expect("write obj");
    let testbed_bytes = testbed.write(&mesh, &opts).expect("write testbed");
    g.throughput(Throughput::Elements(mesh.polygons.len() as u64));
    g.bench_function("obj_read", |b| {
        b.iter(|| obj.read(&obj_bytes).expect("read"))
    });
    g.bench_function("testbed_read", |b| {
        b.iter(|| testbed.read(&testbed_bytes).expect("read"))
    });
    g.throughput(Throughput::Bytes(glb_bytes.len() as u64));
    g.bench_function("glb_write", |b| {
        b.iter(|| glb.write(&mesh, &opts).expect("write"))
    });
    g.finish();
    streaming(c, &mesh);
}

/// Writing a whole file to a sink, for each writable binary and text encoder: the bytes reach
/// an `io::Write` (here `io::sink()`, standing for a file), so what is timed is the encoding
/// plus whatever buffering the writer needs to get the bytes out.
fn streaming(c: &mut Criterion, mesh: &meshio::RawMesh) {
    let mut g = c.benchmark_group("streaming_1M_triangles");
    g.sample_size(10);
    let cases = [
        ("ply", WriteOptions::new()),
        ("glb", WriteOptions::new()),
        ("stl", WriteOptions::new()),
        ("obj", WriteOptions::new()),
    ];
    for (name, opts) in cases {
        let f = format_by_name(name).expect("format");
        let len = f.write(mesh, &opts).expect("write").len();
        g.throughput(Throughput::Bytes(len as u64));
        g.bench_function(format!("{name}_to_sink"), |b| {
            b.iter(|| to_sink(f, mesh, &opts))
        });
    }
    g.finish();
}

/// One file streamed to `io::sink()` ([`meshio::MeshFormat::write_to`]). Before the writers
/// streamed, this was `write` into a `Vec` and then `write_all` of it (docs/performance.md).
fn to_sink(f: &dyn meshio::MeshFormat, mesh: &meshio::RawMesh, opts: &WriteOptions) {
    f.write_to(mesh, opts, &mut std::io::sink()).expect("write");
}

criterion_group!(benches, bench);
criterion_main!(benches);

//! Three levels of Loop and Catmull–Clark on meshes of about 10⁵ faces
//! ([`subdiv::bench_meshes::bench_meshes`]); the C++ side of the comparison is
//! `scripts/golden_subdivision.py --bench`.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use subdiv::{subdivide, CatmullClark, Loop, LoopWeights, Subdivision, DEFAULT_MAX_FACES};

fn three_levels(c: &mut Criterion) {
    let mut group = c.benchmark_group("three-levels");
    group.sample_size(10);
    let schemes: [(&str, Box<dyn Subdivision>); 3] = [
        (
            "loop",
            Box::new(Loop {
                weights: LoopWeights::Loop,
            }),
        ),
        (
            "loop-warren",
            Box::new(Loop {
                weights: LoopWeights::Warren,
            }),
        ),
        ("catmull-clark", Box::new(CatmullClark)),
    ];
    for (name, mesh) in subdiv::bench_meshes::bench_meshes() {
        for (sname, scheme) in &schemes {
            if sname.starts_with("loop") && !mesh.all_triangles() {
                continue;
            }
            group.bench_function(format!("{sname}/{name}"), |b| {
                b.iter(|| {
                    let out = subdivide(scheme.as_ref(), &mesh, 3, DEFAULT_MAX_FACES);
                    black_box(out.map(|m| m.num_faces()).unwrap_or(0))
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, three_levels);
criterion_main!(benches);

//! The ring study's pictures: one 380×285 tile of a torus (R = 1, r = 0.4) of 20 000 triangles
//! (100 × 100 grid), uniformly coloured and coloured by Gaussian curvature, from the study's
//! overview camera; the 45 tiles of one composite; the linear → sRGB conversion of a tile's
//! worth of values; and a 5 × 3 composite written as PNG (as `experiments -- ring` does three
//! times).

use std::f64::consts::TAU;
use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Point3, Vector3};
use render::colors::{diverging, MATERIAL};
use render::shade::to_srgb8;
use render::{
    render, render_many, write_composite, Camera, Legend, LegendKind, RenderMesh, RenderOptions,
    Tile,
};

/// A torus of `nu × nv` quads split in two, coloured uniformly or by Gaussian curvature.
fn torus(nu: usize, nv: usize, by_curvature: bool) -> RenderMesh {
    let (big, small) = (1.0, 0.4);
    let mut m = RenderMesh::default();
    for i in 0..nu {
        for j in 0..nv {
            let (u, v) = (TAU * i as f64 / nu as f64, TAU * j as f64 / nv as f64);
            let n = Vector3::new(v.cos() * u.cos(), v.cos() * u.sin(), v.sin());
            let c = Point3::new(big * u.cos(), big * u.sin(), 0.0);
            m.positions.push(c + n * small);
            m.normals.push(n);
            let k = v.cos() / (small * (big + small * v.cos()));
            m.colors.push(if by_curvature {
                diverging(k, 2.0)
            } else {
                MATERIAL
            });
        }
    }
    for i in 0..nu {
        for j in 0..nv {
            let at = |a: usize, b: usize| (a % nu) * nv + b % nv;
            let (p, q, r, s) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            m.faces.push([p, q, r]);
            m.faces.push([p, r, s]);
        }
    }
    m
}

fn options() -> RenderOptions {
    RenderOptions {
        width: 380,
        height: 285,
        ..RenderOptions::default()
    }
}

fn camera(azimuth: f64, elevation: f64) -> Camera {
    Camera::framing(
        Point3::new(-1.4, -1.4, -0.4),
        Point3::new(1.4, 1.4, 0.4),
        azimuth,
        elevation,
    )
}

fn bench(c: &mut Criterion) {
    let shaded = torus(100, 100, false);
    let kcolor = torus(100, 100, true);
    let o = options();
    let cam = camera(35.0, 35.0);
    let mut g = c.benchmark_group("ring_tile_380x285_20k_triangles");
    g.bench_function("render_uniform", |b| {
        b.iter(|| black_box(render(black_box(&shaded), &cam, &o)))
    });
    g.bench_function("render_kcolor", |b| {
        b.iter(|| black_box(render(black_box(&kcolor), &cam, &o)))
    });
    let values: Vec<f32> = (0..3 * 380 * 285)
        .map(|i| (i % 4099) as f32 / 4098.0)
        .collect();
    g.bench_function("to_srgb8_tile", |b| {
        b.iter(|| {
            black_box(&values)
                .iter()
                .map(|v| u32::from(to_srgb8(*v)))
                .sum::<u32>()
        })
    });
    let views = [(35.0, 35.0), (100.0, 65.0), (200.0, 6.0)];
    let cams: Vec<Camera> = views.iter().map(|&(a, e)| camera(a, e)).collect();
    g.sample_size(10);
    g.bench_function("render_15_tiles_one_by_one", |b| {
        b.iter(|| {
            for cam in &cams {
                for _ in 0..5 {
                    black_box(render(&kcolor, cam, &o).ok());
                }
            }
        })
    });
    let jobs: Vec<(&RenderMesh, &Camera)> = cams
        .iter()
        .flat_map(|cam| std::iter::repeat_n((&kcolor, cam), 5))
        .collect();
    g.bench_function("render_many_15_tiles", |b| {
        b.iter(|| black_box(render_many(&jobs, &o).ok()))
    });
    let tiles: Vec<Tile> = cams
        .iter()
        .flat_map(|cam| {
            let image = render(&kcolor, cam, &o).ok();
            std::iter::repeat_n(image, 5)
        })
        .flatten()
        .enumerate()
        .map(|(k, image)| Tile {
            image,
            label: format!("surface {} — view {}", k % 5, k / 5),
        })
        .collect();
    let legend = Legend {
        title: "Gaussian curvature K".into(),
        kind: LegendKind::Diverging { limit: 2.0 },
    };
    let dir = tempfile::tempdir().ok();
    let path = dir
        .as_ref()
        .map(|d| d.path().join("kcolor.png"))
        .unwrap_or_default();
    g.bench_function("write_composite_5x3", |b| {
        b.iter(|| {
            black_box(write_composite(&tiles, 5, "Gaussian curvature", Some(&legend), &path).ok())
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

//! Prints one digest line per input of `mesh::repair::repair`: a hash of the whole result
//! (`Debug` of the repaired mesh with its private half-edge arrays, face and vertex sources,
//! report; or the error's message), so that a change to the repair can be checked to give the
//! identical result on every input. Inputs: the fixture zoo, the committed corpus, damaged
//! meshes (flipped, duplicated, fin, repeated-vertex, merged-vertex, polygon and dropped
//! faces, bad normals) at several sizes, random face soups, and the mesh files named on the
//! command line:
//! `cargo run --release -p surface --example repair_digest -- [FILE…] > digest.txt`.

#![allow(clippy::expect_used)] // a checking script fails loudly by design

use std::fmt::Write as _;
use std::hash::Hasher;

use fixtures::SplitMix64;
use mesh::repair::{repair, PolygonRule, RepairOptions};
use meshio::{Polygons, RawMesh};
use nalgebra::{Matrix3, Point3, Vector3};

/// A `fmt::Write` that feeds a hasher, so a large `Debug` output is hashed without storing it.
struct HashWriter(std::collections::hash_map::DefaultHasher);

impl std::fmt::Write for HashWriter {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.0.write(s.as_bytes());
        Ok(())
    }
}

fn digest(raw: &RawMesh, options: &RepairOptions) -> String {
    let mut w = HashWriter(Default::default());
    let summary = match repair(raw, options) {
        Ok(r) => {
            write!(w, "{r:?}").expect("hashing");
            format!(
                "ok V={} F={} E={} clean={} dropped={} detached={} split={} degenerate={}",
                r.mesh.num_vertices(),
                r.mesh.num_faces(),
                r.mesh.num_edges(),
                r.report.is_clean(),
                r.report.dropped_faces.len(),
                r.report.detached_edges.len(),
                r.report.split_vertices.len(),
                r.report.degenerate_faces.len()
            )
        }
        Err(e) => {
            write!(w, "{e:?} {e}").expect("hashing");
            format!("err {e}")
        }
    };
    format!("{:016x} {summary}", w.0.finish())
}

/// Faces of a raw mesh as vectors of corners.
fn polys(raw: &RawMesh) -> Vec<Vec<usize>> {
    raw.polygons.iter().map(<[usize]>::to_vec).collect()
}

fn with_polys(raw: &RawMesh, ps: &[Vec<usize>]) -> RawMesh {
    let mut p = Polygons::new();
    for f in ps {
        p.push(f);
    }
    RawMesh {
        polygons: p,
        ..raw.clone()
    }
}

/// A copy of `raw` with `rate` of its faces damaged in every way the rules handle.
fn damaged(raw: &RawMesh, rate: f64, seed: u64) -> RawMesh {
    let mut rng = SplitMix64::new(seed);
    let mut ps = polys(raw);
    let nv = raw.positions.len();
    let mut extra = Vec::new();
    let mut positions = raw.positions.clone();
    for face in &mut ps {
        if !rng.chance(rate) {
            continue;
        }
        match rng.below(9) {
            0 => face.reverse(),
            1 => extra.push(face.clone()),
            2 => {
                let mut r = face.clone();
                r.reverse();
                extra.push(r);
            }
            3 => {
                // A fin on the face's first edge.
                positions.push(Point3::new(rng.next_f64(), rng.next_f64(), rng.next_f64()));
                extra.push(vec![face[0], face[1], positions.len() - 1]);
            }
            4 => {
                let k = face.len();
                face[rng.below(k)] = face[0];
            }
            5 => {
                // Merge a corner with a random vertex (non-manifold vertices, odd edges).
                let k = face.len();
                face[rng.below(k)] = rng.below(nv);
            }
            6 => face.clear(),
            7 => {
                // A quad over this face and a neighbouring index.
                face.push(rng.below(nv));
            }
            _ => {
                // A collinear (zero-area) face on new points.
                let a = Point3::new(rng.next_f64(), 0.0, 0.0);
                positions.push(a);
                positions.push(Point3::new(a.x + 1.0, 0.0, 0.0));
                positions.push(Point3::new(a.x + 2.0, 0.0, 0.0));
                let n = positions.len();
                extra.push(vec![n - 3, n - 2, n - 1]);
                extra.push(vec![face[0], n - 2, n - 1]);
            }
        }
    }
    ps.retain(|f| !f.is_empty());
    ps.extend(extra);
    let mut out = with_polys(raw, &ps);
    out.normals = None;
    out.shapes = None;
    out.vertex_names = None;
    out.properties.clear();
    out.positions = positions;
    out
}

/// Random triangles and polygons over a few random points.
fn soup(rng: &mut SplitMix64) -> RawMesh {
    let n = 3 + rng.below(10);
    let positions: Vec<Point3<f64>> = (0..n)
        .map(|_| {
            Point3::new(
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
                rng.uniform(-1.0, 1.0),
            )
        })
        .collect();
    let faces = 1 + rng.below(30);
    let mut p = Polygons::new();
    for _ in 0..faces {
        let k = if rng.chance(0.1) { 4 + rng.below(2) } else { 3 };
        let f: Vec<usize> = (0..k).map(|_| rng.below(n)).collect();
        p.push(&f);
    }
    let mut raw = RawMesh {
        positions,
        polygons: p,
        ..RawMesh::default()
    };
    if rng.chance(0.2) {
        raw.normals = Some(
            (0..n)
                .map(|_| {
                    Vector3::new(
                        rng.uniform(-1.0, 1.0),
                        rng.uniform(-1.0, 1.0),
                        rng.uniform(-1.0, 1.0),
                    )
                })
                .collect(),
        );
    }
    if rng.chance(0.02) {
        // Not from a reader (they refuse NaN), but a hand-built raw mesh may have it.
        raw.positions[0].x = f64::NAN;
    }
    if rng.chance(0.1) {
        raw.shapes = Some((0..n).map(|i| Matrix3::identity() * i as f64).collect());
        raw.implied_vertex_names = true;
        raw.implied_face_names = true;
    }
    raw
}

/// Patches of a regular grid glued along shared vertices only, several times over (many
/// non-manifold vertices and edges, several components).
fn glued_grids(k: usize) -> RawMesh {
    let n = 6;
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            positions.push(Point3::new(i as f64, j as f64, ((i * j) % 3) as f64 * 0.1));
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut p = Polygons::new();
    for c in 0..k {
        for j in 0..n {
            for i in 0..n {
                if (i + j + c) % (c + 2) == 0 {
                    continue;
                }
                if c % 2 == 0 {
                    p.push(&[id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                    p.push(&[id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
                } else {
                    p.push(&[id(i, j), id(i + 1, j + 1), id(i + 1, j)]);
                    p.push(&[id(i, j), id(i, j + 1), id(i + 1, j + 1)]);
                }
            }
        }
    }
    RawMesh {
        positions,
        polygons: p,
        ..RawMesh::default()
    }
}

fn main() {
    let fan = RepairOptions::default();
    let refuse = RepairOptions {
        polygons: PolygonRule::Refuse,
        ..RepairOptions::default()
    };
    let mut inputs: Vec<(String, RawMesh)> = Vec::new();
    for (name, raw) in fixtures::zoo() {
        inputs.push((format!("zoo/{name}"), raw));
    }
    for path in fixtures::corpus::corpus_files() {
        let raw = meshio::read_file(&path).expect("corpus file");
        inputs.push((format!("corpus/{}", path.display()), raw));
    }
    let zoo = fixtures::zoo();
    for (i, (name, raw)) in zoo.iter().enumerate() {
        for (j, rate) in [0.05, 0.3].iter().enumerate() {
            let seed = (100 * i + j) as u64;
            inputs.push((format!("damaged/{name}/{rate}"), damaged(raw, *rate, seed)));
        }
    }
    let torus = fixtures::large::noisy_torus(100, 50);
    for (j, rate) in [0.001, 0.01, 0.1].iter().enumerate() {
        inputs.push((
            format!("damaged/torus10k/{rate}"),
            damaged(&torus, *rate, 7 + j as u64),
        ));
    }
    inputs.push(("torus10k".into(), torus));
    for k in 1..6 {
        inputs.push((format!("glued_grids/{k}"), glued_grids(k)));
    }
    let mut rng = SplitMix64::new(2024);
    for i in 0..3000 {
        inputs.push((format!("soup/{i}"), soup(&mut rng)));
    }
    for path in std::env::args().skip(1) {
        let raw = meshio::read_file(&path).expect("a mesh file");
        inputs.push((format!("file/{path}"), raw.clone()));
        inputs.push((format!("file/{path}/damaged"), damaged(&raw, 0.001, 99)));
    }
    let mut all = std::collections::hash_map::DefaultHasher::new();
    for (name, raw) in &inputs {
        for (oname, opts) in [("fan", &fan), ("refuse", &refuse)] {
            if oname == "refuse" && raw.polygons.all_triangles() {
                continue;
            }
            let line = format!("{name} {oname} {}", digest(raw, opts));
            all.write(line.as_bytes());
            println!("{line}");
        }
    }
    println!("ALL {:016x}", all.finish());
}

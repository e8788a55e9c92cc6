//! Deterministic meshes for tests, benchmarks and examples: icosahedron and icosphere, torus
//! grids of triangles or quads, planar grids, and irregular valences by splitting faces and
//! edges. All faces counter-clockwise seen from outside (from `+z` for planar grids).

use std::f64::consts::PI;

use meshio::Polygons;
use nalgebra::{Point3, Vector3};
use rng::SplitMix64;

use crate::error::SubdivError;
use crate::mesh::PolyMesh;

/// The regular icosahedron inscribed in the unit sphere (12 vertices of valence 5, 20 faces).
pub fn icosahedron() -> PolyMesh {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let raw = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let positions = raw
        .iter()
        .map(|c| Point3::from(Vector3::from(*c).normalize()))
        .collect();
    let faces = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    known_good(PolyMesh::from_triangles(positions, &faces))
}

/// The icosahedron split `level` times into four (edge midpoints pushed onto the unit
/// sphere): `20·4^level` triangles.
pub fn icosphere(level: u32) -> PolyMesh {
    let mut mesh = icosahedron();
    for _ in 0..level {
        let nv = mesh.num_vertices();
        let mut positions = mesh.positions().to_vec();
        for [a, b] in mesh.edges() {
            let m = (mesh.positions()[a].coords + mesh.positions()[b].coords).normalize();
            positions.push(Point3::from(m));
        }
        let mut faces = Vec::with_capacity(4 * mesh.num_faces());
        let edges = edge_lookup(&mesh);
        for f in mesh.faces() {
            let v = [f[0] as usize, f[1] as usize, f[2] as usize];
            let m = |i: usize| nv + edges(v[i], v[(i + 1) % 3]);
            let (m01, m12, m20) = (m(0), m(1), m(2));
            faces.extend_from_slice(&[
                [v[0], m01, m20],
                [v[1], m12, m01],
                [v[2], m20, m12],
                [m01, m12, m20],
            ]);
        }
        mesh = known_good(PolyMesh::from_triangles(positions, &faces));
    }
    mesh
}

/// A lookup from an unordered vertex pair to its edge index.
fn edge_lookup(mesh: &PolyMesh) -> impl Fn(usize, usize) -> usize {
    let mut map: std::collections::HashMap<(usize, usize), usize> =
        std::collections::HashMap::new();
    for (e, [a, b]) in mesh.edges().into_iter().enumerate() {
        map.insert((a.min(b), a.max(b)), e);
    }
    move |a, b| {
        map.get(&(a.min(b), a.max(b)))
            .copied()
            .unwrap_or(usize::MAX)
    }
}

/// A torus of radii `big` and `small` sampled on a `nu × nv` grid (both ≥ 3), quads.
pub fn torus_quads(nu: usize, nv: usize, big: f64, small: f64) -> PolyMesh {
    let (positions, quads) = torus_grid(nu, nv, big, small);
    let mut polygons = Polygons::with_capacity(quads.len(), 4 * quads.len());
    for q in &quads {
        polygons.push(q);
    }
    known_good(PolyMesh::new(positions, &polygons))
}

/// The torus of [`torus_quads`] with every quad split along the same diagonal: `2·nu·nv`
/// triangles, every vertex of valence 6.
pub fn torus_triangles(nu: usize, nv: usize, big: f64, small: f64) -> PolyMesh {
    let (positions, quads) = torus_grid(nu, nv, big, small);
    let tris: Vec<[usize; 3]> = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    known_good(PolyMesh::from_triangles(positions, &tris))
}

fn torus_grid(nu: usize, nv: usize, big: f64, small: f64) -> (Vec<Point3<f64>>, Vec<[usize; 4]>) {
    let (nu, nv) = (nu.max(3), nv.max(3));
    let mut positions = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let u = 2.0 * PI * i as f64 / nu as f64;
        for j in 0..nv {
            let v = 2.0 * PI * j as f64 / nv as f64;
            let r = big + small * v.cos();
            positions.push(Point3::new(r * u.cos(), r * u.sin(), small * v.sin()));
        }
    }
    let id = |i: usize, j: usize| (i % nu) * nv + (j % nv);
    let mut quads = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            quads.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (positions, quads)
}

/// A planar `nu × nv` grid of unit quads in `z = 0` (open; vertex `(i, j)` at `(i, j, 0)` has
/// index `j·(nu + 1) + i`).
pub fn quad_grid(nu: usize, nv: usize) -> PolyMesh {
    let (positions, quads) = plane_grid(nu, nv);
    let mut polygons = Polygons::with_capacity(quads.len(), 4 * quads.len());
    for q in &quads {
        polygons.push(q);
    }
    known_good(PolyMesh::new(positions, &polygons))
}

/// The regular (three-direction) triangulation of [`quad_grid`]: every quad split along the
/// diagonal from `(i, j)` to `(i + 1, j + 1)`, interior vertices of valence 6.
pub fn triangle_grid(nu: usize, nv: usize) -> PolyMesh {
    let (positions, quads) = plane_grid(nu, nv);
    let tris: Vec<[usize; 3]> = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    known_good(PolyMesh::from_triangles(positions, &tris))
}

fn plane_grid(nu: usize, nv: usize) -> (Vec<Point3<f64>>, Vec<[usize; 4]>) {
    let (nu, nv) = (nu.max(1), nv.max(1));
    let mut positions = Vec::with_capacity((nu + 1) * (nv + 1));
    for j in 0..=nv {
        for i in 0..=nu {
            positions.push(Point3::new(i as f64, j as f64, 0.0));
        }
    }
    let id = |i: usize, j: usize| j * (nu + 1) + i;
    let mut quads = Vec::with_capacity(nu * nv);
    for j in 0..nv {
        for i in 0..nu {
            quads.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (positions, quads)
}

/// A triangle mesh with irregular valences: each face of `mesh` is split 1→3 at its centroid
/// (lifted by `lift` times the face's size along its normal) with probability `fraction`, so
/// new vertices have valence 3 and their corners gain one each; then every position is moved
/// by up to `jitter` times the mean edge length in each coordinate. Non-triangular faces are
/// kept as they are. The draws come from the workbench's one generator, [`SplitMix64`] seeded
/// with `seed`.
pub fn irregular(mesh: &PolyMesh, fraction: f64, lift: f64, jitter: f64, seed: u64) -> PolyMesh {
    let mut rng = SplitMix64::new(seed);
    let mut positions = mesh.positions().to_vec();
    let mut polygons = Polygons::new();
    for face in mesh.faces() {
        let f: Vec<usize> = face.iter().map(|&v| v as usize).collect();
        if f.len() == 3 && rng.next_f64() < fraction {
            let p: Vec<Point3<f64>> = f.iter().map(|&v| mesh.positions()[v]).collect();
            let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
            let size = n.norm().sqrt();
            let c = Point3::from((p[0].coords + p[1].coords + p[2].coords) / 3.0);
            let c = if size > 0.0 {
                c + n / n.norm() * (lift * size)
            } else {
                c
            };
            let m = positions.len();
            positions.push(c);
            polygons.push(&[f[0], f[1], m]);
            polygons.push(&[f[1], f[2], m]);
            polygons.push(&[f[2], f[0], m]);
        } else {
            polygons.push(&f);
        }
    }
    let mean_edge = {
        let edges = mesh.edges();
        let s: f64 = edges
            .iter()
            .map(|&[a, b]| (mesh.positions()[a] - mesh.positions()[b]).norm())
            .sum();
        s / edges.len().max(1) as f64
    };
    for p in &mut positions {
        for c in p.coords.iter_mut() {
            *c += (2.0 * rng.next_f64() - 1.0) * jitter * mean_edge;
        }
    }
    let creases: Vec<[usize; 2]> = mesh.creases();
    known_good(PolyMesh::with_creases(positions, &polygons, &creases))
}

/// A small closed triangle mesh with interior valences 3, 4, 5, 6, 7 and 8: the icosahedron
/// with the three faces at vertex 0 split at their centroids (vertex 0: 5 → 8), one edge split
/// at its midpoint (a valence-4 vertex), and jittered positions.
pub fn irregular_small(seed: u64) -> PolyMesh {
    let ico = icosahedron();
    let mut positions = ico.positions().to_vec();
    let mut tris: Vec<[usize; 3]> = ico
        .faces()
        .map(|f| [f[0] as usize, f[1] as usize, f[2] as usize])
        .collect();
    // Split the edge (3, 9) shared by faces [3, 9, 4] and [3, 8, 9]: a valence-4 vertex.
    let m = positions.len();
    positions.push(Point3::from(
        ((positions[3].coords + positions[9].coords) * 0.5).normalize(),
    ));
    let mut out = Vec::new();
    for t in tris.drain(..) {
        match t {
            [3, 9, 4] => out.extend([[3, m, 4], [m, 9, 4]]),
            [3, 8, 9] => out.extend([[3, 8, m], [m, 8, 9]]),
            _ => out.push(t),
        }
    }
    // Split three of the five faces at vertex 0.
    let mut final_tris = Vec::new();
    for t in out {
        if t[0] == 0 && matches!(t[1], 11 | 5 | 1) {
            let c = positions.len();
            let centre = (positions[t[0]].coords + positions[t[1]].coords + positions[t[2]].coords)
                .normalize();
            positions.push(Point3::from(centre));
            final_tris.extend([[t[0], t[1], c], [t[1], t[2], c], [t[2], t[0], c]]);
        } else {
            final_tris.push(t);
        }
    }
    let mut rng = SplitMix64::new(seed);
    for p in &mut positions {
        for c in p.coords.iter_mut() {
            *c += (2.0 * rng.next_f64() - 1.0) * 0.05;
        }
    }
    known_good(PolyMesh::from_triangles(positions, &final_tris))
}

/// The generators build valid meshes by construction; a failure here is a bug in this file,
/// reported as an empty mesh rather than a panic.
fn known_good(mesh: Result<PolyMesh, SubdivError>) -> PolyMesh {
    mesh.unwrap_or_else(|_| empty())
}

fn empty() -> PolyMesh {
    PolyMesh::empty()
}

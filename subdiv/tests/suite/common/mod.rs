//! Helpers shared by the integration tests.

#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use meshio::Polygons;
use nalgebra::{Point3, Vector3};
use subdiv::{PolyMesh, Subdivision};

/// The faces at `v` cut out as a mesh with `v` as vertex 0. Corners joined to `v` by an edge
/// are shared between faces; other corners (the far corners of polygons) get a copy per face.
/// Crease tags on the edges at `v` are kept. After a step, `v`'s new position and its new
/// one-ring are exactly those the whole mesh would give (the rules at `v` and on the edges at
/// `v` read only the faces at `v`); this is what lets a test run 12 or more levels on one
/// vertex without 4¹² faces.
pub fn one_ring(mesh: &PolyMesh, v: usize) -> PolyMesh {
    let mut local: Vec<(usize, usize)> = vec![(v, 0)];
    let mut positions = vec![mesh.positions()[v]];
    let mut polygons = Polygons::new();
    let creases = mesh.creases();
    let mut tags = Vec::new();
    for face in mesh.faces() {
        let Some(k) = face.iter().position(|&x| x as usize == v) else {
            continue;
        };
        let n = face.len();
        let mut corners = Vec::with_capacity(n);
        for i in 0..n {
            let g = face[(k + i) % n] as usize;
            let l = if i == 0 || i == 1 || i == n - 1 {
                match local.iter().find(|(x, _)| *x == g) {
                    Some(&(_, l)) => l,
                    None => {
                        positions.push(mesh.positions()[g]);
                        local.push((g, positions.len() - 1));
                        positions.len() - 1
                    }
                }
            } else {
                positions.push(mesh.positions()[g]);
                positions.len() - 1
            };
            corners.push(l);
        }
        for &j in &[1, n - 1] {
            let g = face[(k + j) % n] as usize;
            if creases.contains(&[v.min(g), v.max(g)]) {
                tags.push([0, corners[j]]);
            }
        }
        polygons.push(&corners);
    }
    PolyMesh::with_creases(positions, &polygons, &tags).unwrap()
}

/// Positions of vertex `v` after 0, 1, …, `levels` steps, by one-ring patches.
pub fn track(
    scheme: &dyn Subdivision,
    mesh: &PolyMesh,
    v: usize,
    levels: usize,
) -> Vec<Point3<f64>> {
    let mut patch = one_ring(mesh, v);
    let mut out = vec![patch.positions()[0]];
    for _ in 0..levels {
        let fine = scheme.step(&patch).unwrap();
        out.push(fine.positions()[0]);
        patch = one_ring(&fine, 0);
    }
    out
}

/// The one-ring patch of `v` after `levels` steps.
pub fn patch_after(scheme: &dyn Subdivision, mesh: &PolyMesh, v: usize, levels: usize) -> PolyMesh {
    let mut patch = one_ring(mesh, v);
    for _ in 0..levels {
        patch = one_ring(&scheme.step(&patch).unwrap(), 0);
    }
    patch
}

/// Angle between two vectors, radians.
pub fn angle(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

/// A triangle mesh merged into mixed triangles, quads and pentagons: a copy of the mesh with
/// pairs of triangles sharing an edge merged greedily (every third face left alone).
pub fn mixed_polygons(mesh: &PolyMesh) -> PolyMesh {
    let tris: Vec<[usize; 3]> = mesh
        .faces()
        .map(|f| [f[0] as usize, f[1] as usize, f[2] as usize])
        .collect();
    let mut used = vec![false; tris.len()];
    let mut polygons = Polygons::new();
    for i in 0..tris.len() {
        if used[i] {
            continue;
        }
        used[i] = true;
        let t = tris[i];
        let mut merged = None;
        if i % 3 != 2 {
            'outer: for k in 0..3 {
                let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                for (j, u) in tris.iter().enumerate() {
                    if used[j] {
                        continue;
                    }
                    for r in 0..3 {
                        if u[r] == b && u[(r + 1) % 3] == a {
                            used[j] = true;
                            merged = Some(vec![a, u[(r + 2) % 3], b, c]);
                            break 'outer;
                        }
                    }
                }
            }
        }
        polygons.push(&merged.unwrap_or_else(|| t.to_vec()));
    }
    PolyMesh::new(mesh.positions().to_vec(), &polygons).unwrap()
}

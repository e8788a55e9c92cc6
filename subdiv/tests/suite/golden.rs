//! One and two steps against widely used C++ implementations of the same rules
//! (`scripts/golden_subdivision.py` wrote the files in `data/golden/`):
//!
//! - Loop with Warren's β against libigl 2.6.3 (`igl.loop`), closed and open;
//! - Loop with Loop's β against CGAL's `Loop_subdivision` (compas_cgal 0.10.0), closed and open;
//! - Catmull–Clark on mixed triangles, quads and a pentagon against CGAL's
//!   `CatmullClark_subdivision` (compas_cgal 0.10.0), closed and open.
//!
//! Vertex orders differ between implementations, so vertices are matched by nearest
//! neighbour: each reference vertex must have exactly one of ours within [`UNIQUE`] and that
//! one within [`TOLERANCE`]; the matching must be a bijection, and the faces must be the same
//! cyclic vertex sequences (orientation included) under it.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::PathBuf;

use meshio::Polygons;
use nalgebra::Point3;
use serde_json::Value;
use subdiv::{CatmullClark, Loop, LoopWeights, PolyMesh, Subdivision};

/// The task's bar: one step matches to 1e-12 (coordinates are of order 1).
const TOLERANCE: f64 = 1e-12;
/// Distinct vertices of these meshes are at least ~1e-2 apart; 1e-9 separates "the same
/// vertex up to rounding" from "another vertex" with room on both sides.
const UNIQUE: f64 = 1e-9;

fn golden(name: &str) -> Value {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../data/golden")
        .join(format!("subdivision-{name}.json"));
    let text = std::fs::read_to_string(&path).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn mesh_of(v: &Value) -> (Vec<Point3<f64>>, Vec<Vec<usize>>) {
    let positions = v["positions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let c: Vec<f64> = p
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_str().unwrap().parse().unwrap())
                .collect();
            Point3::new(c[0], c[1], c[2])
        })
        .collect();
    let faces = v["faces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            f.as_array()
                .unwrap()
                .iter()
                .map(|i| i.as_u64().unwrap() as usize)
                .collect()
        })
        .collect();
    (positions, faces)
}

fn cyclic(face: &[usize]) -> Vec<usize> {
    let k = (0..face.len()).min_by_key(|&i| face[i]).unwrap();
    face[k..].iter().chain(&face[..k]).copied().collect()
}

/// Compares our mesh with a reference one; returns the largest position difference.
fn compare(ours: &PolyMesh, reference: &Value, what: &str) -> f64 {
    let (pos, faces) = mesh_of(reference);
    assert_eq!(ours.num_vertices(), pos.len(), "{what}: vertex count");
    assert_eq!(ours.num_faces(), faces.len(), "{what}: face count");
    let mut map = vec![usize::MAX; pos.len()];
    let mut taken = vec![false; pos.len()];
    let mut worst = 0.0f64;
    for (i, p) in pos.iter().enumerate() {
        let mut close = ours
            .positions()
            .iter()
            .enumerate()
            .map(|(j, q)| ((p - q).norm(), j))
            .filter(|(d, _)| *d < UNIQUE);
        let (d, j) = close
            .next()
            .unwrap_or_else(|| panic!("{what}: no vertex of ours near {p}"));
        assert!(close.next().is_none(), "{what}: two of ours near {p}");
        assert!(!taken[j], "{what}: vertex {j} matched twice");
        taken[j] = true;
        map[i] = j;
        worst = worst.max(d);
    }
    assert!(
        worst <= TOLERANCE,
        "{what}: largest difference {worst:e} over {TOLERANCE:e}"
    );
    let mut theirs: Vec<Vec<usize>> = faces
        .iter()
        .map(|f| cyclic(&f.iter().map(|&i| map[i]).collect::<Vec<_>>()))
        .collect();
    let mut mine: Vec<Vec<usize>> = ours
        .faces()
        .map(|f| cyclic(&f.iter().map(|&i| i as usize).collect::<Vec<_>>()))
        .collect();
    theirs.sort();
    mine.sort();
    assert_eq!(mine, theirs, "{what}: faces differ");
    worst
}

fn check(file: &str, scheme: &dyn Subdivision) {
    let doc = golden(file);
    for case in doc["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let (pos, faces) = mesh_of(&case["input"]);
        let mut polygons = Polygons::new();
        for f in &faces {
            polygons.push(f);
        }
        let mut mesh = PolyMesh::new(pos, &polygons).unwrap();
        for (level, reference) in case["levels"].as_array().unwrap().iter().enumerate() {
            mesh = scheme.step(&mesh).unwrap();
            let worst = compare(
                &mesh,
                reference,
                &format!("{file} {name} level {}", level + 1),
            );
            eprintln!("{file} {name} level {}: max |Δ| = {worst:e}", level + 1);
        }
    }
}

#[test]
fn loop_warren_matches_libigl() {
    check(
        "loop-warren-libigl",
        &Loop {
            weights: LoopWeights::Warren,
        },
    );
}

#[test]
fn loop_original_matches_cgal() {
    check(
        "loop-cgal",
        &Loop {
            weights: LoopWeights::Loop,
        },
    );
}

#[test]
fn catmull_clark_matches_cgal() {
    check("catmull-clark-cgal", &CatmullClark);
}

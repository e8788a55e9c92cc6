//! `hybrid` takes `jet4` where the sampling resolves the surface and Rusinkiewicz elsewhere,
//! vertex by vertex, by the stated rule (`estimate::hybrid`).

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use estimate::{Estimator, HYBRID, JET4, RUSINKIEWICZ};
use mesh::Mesh;

/// Positions only reach the estimators.
fn positions_only(mut mesh: Mesh) -> Mesh {
    for v in mesh.vertices_mut() {
        v.data.n = nalgebra::Vector3::zeros();
        v.data.shape = nalgebra::Matrix3::zeros();
    }
    mesh
}

/// How many vertices took each estimate: (jet4, rusinkiewicz).
fn split(mesh: &Mesh) -> (usize, usize) {
    let h = HYBRID.estimate(mesh, None);
    let j = JET4.estimate(mesh, None);
    let r = RUSINKIEWICZ.estimate(mesh, None);
    let (mut nj, mut nr) = (0, 0);
    for v in 0..mesh.num_vertices() {
        let from_jet = h.normals[v] == j.normals[v] && h.shapes[v] == j.shapes[v];
        let from_rus = h.normals[v] == r.normals[v] && h.shapes[v] == r.shapes[v];
        assert!(from_jet || from_rus, "vertex {v} is neither estimate");
        if from_jet {
            nj += 1;
        } else {
            nr += 1;
        }
    }
    (nj, nr)
}

#[test]
fn the_coarse_ring_takes_rusinkiewicz_everywhere() {
    // 16 × 8 ring: one edge turns the tube's normal by about 0.4 · 2.5 = 1 rad.
    let mesh = positions_only(mesh::datasets::ring(16, 8).unwrap().mesh);
    assert_eq!(split(&mesh), (0, mesh.num_vertices()));
}

#[test]
fn a_fine_sphere_takes_jet4_everywhere() {
    // Level 5: edges of 0.06 on the unit sphere turn the normal by 0.06 rad.
    let mesh = positions_only(mesh::datasets::sphere(5).unwrap().mesh);
    assert_eq!(split(&mesh), (mesh.num_vertices(), 0));
}

#[test]
fn a_middle_ring_mixes_by_curvature() {
    // 64 × 32: the largest principal curvature is the tube's, 1/r = 2.5, everywhere, but the
    // edges around the axis are 2π(R ∓ r)/64 long, 0.06 inside and 0.14 outside: the inner
    // vertices are resolved (ρ ≈ 0.15–0.2), the outer ones not.
    let mesh = positions_only(mesh::datasets::ring(64, 32).unwrap().mesh);
    let (nj, nr) = split(&mesh);
    assert!(nj > 0 && nr > 0, "jet4 {nj}, rusinkiewicz {nr}");
}

/// The zoo of hostile meshes (`fixtures::zoo`), repaired, positions only.
fn zoo_meshes() -> Vec<(&'static str, Mesh)> {
    fixtures::zoo()
        .into_iter()
        .filter_map(|(name, raw)| {
            let repaired = mesh::repair::repair(&raw, &Default::default()).ok()?;
            Some((name, positions_only(repaired.mesh)))
        })
        .collect()
}

/// The rule of `estimate::hybrid` applied to the full Rusinkiewicz and `jet4` estimates, as the
/// module states it.
fn rule(mesh: &Mesh, given: Option<&[nalgebra::Vector3<f64>]>) -> estimate::Estimate {
    use estimate::FallbackKind;
    // A noisy mesh is the multi-scale jet's, whole.
    if estimate::multiscale::mesh_noise(mesh, given).is_noisy() {
        return estimate::MULTISCALE.estimate(mesh, given);
    }
    let rus = RUSINKIEWICZ.estimate(mesh, given);
    let jet = JET4.estimate(mesh, given);
    let n = mesh.num_vertices();
    let (mut len, mut count) = (vec![0.0f64; n], vec![0usize; n]);
    for e in mesh.edges() {
        let [a, b] = e.vertices;
        let l = (mesh.vertices()[b].data.p - mesh.vertices()[a].data.p).norm();
        for v in [a, b] {
            len[v] += l;
            count[v] += 1;
        }
    }
    let mut fell_back = vec![false; n];
    for f in &jet.fallbacks {
        if matches!(
            f.kind,
            FallbackKind::LowerDegree { .. } | FallbackKind::Planar { .. }
        ) {
            fell_back[f.vertex] = true;
        }
    }
    let mut out = rus.clone();
    for v in 0..n {
        let [k1, k2] = rus.principal(v).unwrap();
        let rho = k1.abs().max(k2.abs()) * len[v] / count[v].max(1) as f64;
        if rho <= estimate::hybrid::RESOLVED && !fell_back[v] && count[v] > 0 {
            out.normals[v] = jet.normals[v];
            out.shapes[v] = jet.shapes[v];
        }
    }
    out
}

#[test]
fn hybrid_is_the_rule_on_the_two_full_estimates_to_the_bit() {
    // `hybrid` fits the jet only where the rule can take it and shares the topology and the
    // normal pass: the result must be the rule applied to the two full estimates, bit for bit
    // (`==` on every float), with and without given normals (some spoiled).
    for (name, mesh) in zoo_meshes() {
        let mut given = estimate::vertex_normals(&mesh, estimate::NormalWeighting::Area).normals;
        for (i, n) in given.iter_mut().enumerate().filter(|(i, _)| i % 7 == 3) {
            *n = if i % 2 == 0 {
                nalgebra::Vector3::zeros()
            } else {
                nalgebra::Vector3::new(f64::NAN, 0.0, 1.0)
            };
        }
        for g in [None, Some(given.as_slice())] {
            assert_eq!(HYBRID.estimate(&mesh, g), rule(&mesh, g), "{name}");
        }
    }
}

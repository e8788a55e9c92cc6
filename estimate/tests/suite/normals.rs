//! Vertex normals: exactness where known, convergence, fallbacks.

use crate::support;

use estimate::normals::{vertex_normals, NormalWeighting};
use estimate::FallbackKind;
use nalgebra::Vector3;
use support::*;

#[test]
fn weightings_on_the_ring_converge() {
    // Observed RMS (°) at 32, 64, 128: angle 0.49, 0.12, 0.031; area about twice that; Max
    // exact (1e-14). Order 2 for angle and area.
    for w in [NormalWeighting::Angle, NormalWeighting::Area] {
        let errs: Vec<f64> = [32, 64, 128]
            .iter()
            .map(|&n| {
                let d = mesh::datasets::ring(n, n / 2).expect("valid");
                let est = vertex_normals(&d.mesh, w);
                let s: f64 = est
                    .normals
                    .iter()
                    .zip(d.mesh.vertices())
                    .map(|(a, v)| angle_deg(a, &v.data.n).powi(2))
                    .sum();
                (s / d.mesh.num_vertices() as f64).sqrt()
            })
            .collect();
        assert_order(&errs, ORDER_2, &format!("{w:?}"));
    }
}

#[test]
fn fallbacks_are_counted() {
    let (mesh, ix) = broken_mesh();
    let n = vertex_normals(&mesh, NormalWeighting::Angle);
    assert_eq!(
        n.fallbacks
            .iter()
            .filter(|f| f.kind == FallbackKind::Isolated)
            .map(|f| f.vertex)
            .collect::<Vec<_>>(),
        vec![ix.isolated]
    );
    assert_eq!(n.normals[ix.isolated], Vector3::z());
    // The valence-3 apex of the tetrahedron corner: straight up.
    /// The apex sits 0.004 off the base's centroid (coordinates rounded to 0.87): ≈ 2e-3.
    const APEX_NORMAL: f64 = 1e-2;
    /// Normalized vectors: rounding only.
    const UNIT: f64 = 1e-14;
    assert!((n.normals[ix.valence3] - Vector3::z()).norm() < APEX_NORMAL);
    assert!(n.normals.iter().all(|v| (v.norm() - 1.0).abs() < UNIT));
}

#[test]
fn several_weightings_in_one_pass_are_each_one_to_the_bit() {
    use estimate::normals::{vertex_normals_many, vertex_normals_with};
    use estimate::Topology;
    let weightings = [
        NormalWeighting::Max,
        NormalWeighting::Angle,
        NormalWeighting::Area,
    ];
    for (name, raw) in fixtures::zoo() {
        let Ok(repaired) = mesh::repair::repair(&raw, &Default::default()) else {
            continue;
        };
        let mesh = repaired.mesh;
        let topo = Topology::new(&mesh);
        let mut given = vertex_normals(&mesh, NormalWeighting::Area).normals;
        for n in given.iter_mut().step_by(5) {
            *n = Vector3::zeros();
        }
        for g in [None, Some(given.as_slice())] {
            let many = vertex_normals_many(&mesh, &topo, weightings, g);
            for (w, normals) in weightings.into_iter().zip(many) {
                assert_eq!(
                    normals,
                    vertex_normals_with(&mesh, &topo, w, g),
                    "{name} {w:?}"
                );
            }
        }
    }
}

//! The topological weld (`surface::tessellate_fit`) against the positional weld
//! (`surface::tessellate`) on every data set, every scheme and every hostile mesh of the
//! fixtures' zoo: the same number of vertices and triangles, and every triangle at the same
//! place. Schemes whose patches are evaluated (not Bézier) have no positional weld to compare
//! with; their tessellations are checked for counts, finiteness and closedness.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions};
use estimate::{prepare, EstimateChoice};

use crate::support::default_estimator;
use surface::scheme::REGISTRY;
use surface::{
    dataset_by_name, fit_scheme, scheme_by_name, tessellate, tessellate_fit, Mesh, SchemeOptions,
};

/// Both paths evaluate the same sample from the same net with the same weights when the same
/// patch owns it; where a neighbour owns a shared sample the two patches agree to rounding
/// (C0), measured against the model size.
const SAME_PLACE: f64 = 1e-9;

/// `same_vertices`: the mesh has no two vertices at one place and no zero-area face, so both
/// welds must give the same vertex count.
fn compare(label: &str, mesh: &Mesh, same_vertices: bool) {
    let chord = method_by_name("chord", &MethodOptions::default()).unwrap();
    for e in REGISTRY {
        let scheme = scheme_by_name(e.name, &SchemeOptions::default()).unwrap();
        let f = fit_scheme(mesh, scheme.as_ref(), chord.as_ref()).unwrap();
        for s in [1, 2, 3, 5] {
            let b = tessellate_fit(mesh, &f, s).unwrap();
            if !f.layout.is_bezier() {
                // No positional weld for evaluated (non-Bézier) patches: the topological one's
                // own invariants, on every mesh of the zoo.
                let what = format!("{label}/{}/s={s}", e.name);
                assert_eq!(b.faces.len(), mesh.num_faces() * s * s, "{what}");
                assert!(
                    b.positions.iter().all(|p| p.iter().all(|c| c.is_finite())),
                    "{what}"
                );
                assert!(
                    b.normals.iter().all(|n| (n.norm() - 1.0).abs() < 1e-9),
                    "{what}"
                );
                assert!(
                    b.gaussian.iter().chain(&b.mean).all(|x| x.is_finite()),
                    "{what}"
                );
                if same_vertices {
                    let m = b.to_mesh().unwrap_or_else(|err| panic!("{what}: {err}"));
                    assert_eq!(m.is_closed(), mesh.is_closed(), "{what}");
                }
                continue;
            }
            let a = tessellate(&f.bezier_patches(), s).unwrap();
            let size = surface::mesh::bounding_size(a.positions.iter()).max(1e-300);
            assert_eq!(
                b.faces.len(),
                a.faces.len() + a.collapsed_faces,
                "{label}/{}/s={s}",
                e.name
            );
            // Distinct samples that land on one point (on a zero-area face, or vertices that
            // repair split apart at a non-manifold spot) are one vertex for the positional weld
            // and stay two for the topological one.
            let what = format!("{label}/{}/s={s}", e.name);
            assert!(b.positions.len() >= a.positions.len(), "{what}");
            if same_vertices {
                assert_eq!(b.positions.len(), a.positions.len(), "{what}");
                assert_eq!(b.welds, a.welds, "{what}");
            }
            if a.collapsed_faces == 0 {
                for (ta, tb) in a.faces.iter().zip(&b.faces) {
                    for k in 0..3 {
                        let d = (a.positions[ta[k]] - b.positions[tb[k]]).norm();
                        assert!(d < SAME_PLACE * size, "{what}: {d}");
                    }
                }
            }
            if same_vertices {
                // A closed, consistently oriented mesh in, a closed manifold out.
                let m = b
                    .to_mesh()
                    .unwrap_or_else(|err| panic!("{label}/{}/s={s}: {err}", e.name));
                assert_eq!(m.is_closed(), mesh.is_closed(), "{label}/{}/s={s}", e.name);
            }
            assert!(b.normals.iter().all(|n| (n.norm() - 1.0).abs() < 1e-9));
            assert!(b.gaussian.iter().chain(&b.mean).all(|x| x.is_finite()));
        }
    }
}

#[test]
fn the_topological_weld_matches_the_positional_one_on_the_data_sets() {
    for name in surface::DATASET_NAMES {
        compare(name, &dataset_by_name(name, None).unwrap().mesh, true);
    }
}

#[test]
fn the_topological_weld_matches_the_positional_one_on_hostile_meshes() {
    for (name, raw) in fixtures::zoo() {
        let mesh = prepare(&raw, EstimateChoice::With(default_estimator()), false)
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .mesh;
        compare(name, &mesh, false);
    }
}

/// Large enough that the faces go to the threads in several tasks (the tessellation evaluates
/// 512 faces a task): an irregular noisy torus and an open torus patch, so a task boundary falls
/// between faces that share vertices and edges owned across it.
#[test]
fn the_topological_weld_matches_the_positional_one_across_parallel_tasks() {
    use fixtures::analytic::{torus, Irregular};
    let opts = Irregular {
        noise: 0.005,
        seed: 7,
        ..Irregular::default()
    };
    let open = Irregular { seed: 8, ..opts };
    for (name, raw) in [
        ("noisy torus", torus(48, 24, 1.0, 0.4, &opts)),
        (
            "open torus patch",
            fixtures::open::torus_patch(40, 20, 0.8, 0.7, &open),
        ),
    ] {
        assert!(raw.polygons.len() > 3 * 512, "{name}: several tasks");
        let mesh = prepare(&raw, EstimateChoice::With(default_estimator()), false)
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .mesh;
        compare(name, &mesh, true);
    }
}

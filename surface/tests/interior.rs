//! Section 4's claim, as a test: the interior boundaries' normal curvature at the data vertices
//! and the normalized corner twists do not change with β or c.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions};
use surface::interior::corner_measures;
use surface::{dataset_by_name, fit, InteriorParameters};

/// The measures are ratios of quantities that scale together with β; what is left is rounding.
const INDEPENDENT: f64 = 1e-9;

#[test]
fn corner_measures_ignore_beta_and_c() {
    for name in ["ring", "capsule"] {
        let data = dataset_by_name(name, None).unwrap();
        let m = method_by_name("optimized", &MethodOptions::default()).unwrap();
        let measures = |p: InteriorParameters| {
            let f = fit(&data.mesh, m.as_ref(), &|_| p).unwrap();
            (0..data.mesh.num_faces())
                .flat_map(|fi| {
                    let face = data.mesh.faces()[fi];
                    let nets = [
                        f.patches[3 * fi],
                        f.patches[3 * fi + 1],
                        f.patches[3 * fi + 2],
                    ];
                    corner_measures(&nets, face.map(|i| &data.mesh.vertices()[i].data))
                })
                .collect::<Vec<_>>()
        };
        let base = measures(InteriorParameters::default());
        for p in [
            InteriorParameters {
                beta: [0.15, 0.6, 0.9],
                c: [1.0; 3],
            },
            InteriorParameters {
                beta: [1.0 / 3.0; 3],
                c: [0.3, 2.5, 4.0],
            },
        ] {
            for (a, b) in base.iter().zip(measures(p)) {
                assert!(
                    (a.boundary_curvature - b.boundary_curvature).abs() < INDEPENDENT,
                    "{name}"
                );
                assert!(
                    (a.twist_start - b.twist_start).abs() < INDEPENDENT,
                    "{name}"
                );
                assert!((a.twist_end - b.twist_end).abs() < INDEPENDENT, "{name}");
            }
        }
    }
}

//! `piper`: the stand-in for Piper's scheme is the modified Shirman–Séquin macro-patch at
//! `β = ⅓`, `c = 1` (module docs derive why), whatever the scheme options say; G1 measured on
//! sphere, ring and capsule with every curve method.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions};
use surface::{
    dataset_by_name, fit_scheme, measure_g1, scheme_by_name, Continuity, InteriorParameters,
    SchemeOptions,
};

/// The bound for a G1 claim: angles of rounding size.
const G1_TOL: f64 = 1e-9;
/// Corner normals equal to the data's to rounding.
const NORMALS: f64 = 1e-12;

#[test]
fn the_nets_are_shirman_sequin_at_its_defaults_whatever_the_options() {
    let other = SchemeOptions {
        interior: InteriorParameters {
            beta: [0.2, 0.5, 0.4],
            c: [0.7, 1.6, 1.1],
        },
        phong_alpha: 0.3,
    };
    let piper = scheme_by_name("piper", &other).unwrap();
    let ss = scheme_by_name("shirman-sequin", &SchemeOptions::default()).unwrap();
    assert_eq!(piper.continuity(), Continuity::G1);
    assert_eq!(piper.layout(), ss.layout());
    assert!(piper.uses_curves());
    for name in ["sphere", "ring", "capsule"] {
        let data = dataset_by_name(name, None).unwrap();
        for method in ["chord", "dbhs", "optimized"] {
            let m = method_by_name(method, &MethodOptions::default()).unwrap();
            let a = fit_scheme(&data.mesh, piper.as_ref(), m.as_ref()).unwrap();
            let b = fit_scheme(&data.mesh, ss.as_ref(), m.as_ref()).unwrap();
            assert_eq!(a.points, b.points, "{name}/{method}");
            assert_eq!(a.face_fallbacks, b.face_fallbacks);
        }
    }
}

#[test]
fn g1_measured_on_the_data_sets() {
    let piper = scheme_by_name("piper", &SchemeOptions::default()).unwrap();
    for name in ["sphere", "ring", "capsule"] {
        let data = dataset_by_name(name, None).unwrap();
        for method in ["chord", "dbhs", "optimized"] {
            let m = method_by_name(method, &MethodOptions::default()).unwrap();
            let f = fit_scheme(&data.mesh, piper.as_ref(), m.as_ref()).unwrap();
            assert!(f.face_fallbacks.is_empty(), "{name}/{method}");
            let g1 = measure_g1(&data.mesh, &f, 9);
            eprintln!(
                "{name}/{method}: piper normal angle {:.3e} rad (exterior), {:.3e} (interior)",
                g1.exterior_max, g1.interior_max
            );
            assert!(g1.max_angle() < G1_TOL, "{name}/{method}: {g1:?}");
            assert!(g1.normal_error < NORMALS, "{name}/{method}");
        }
    }
}

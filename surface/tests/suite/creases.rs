//! Crease-aware fits: data per sector, curves along the creases, every scheme and every curve
//! method on meshes with sharp features (the fixture cube, a cone, the committed CAD corpus),
//! measured by `surface::sharp` (flat regions, creases kept, kinks on smooth edges) and
//! `surface::folds`.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions};
use estimate::{prepare_with, EstimateChoice, ESTIMATORS};
use mesh::features::CreaseRule;
use surface::{fit_scheme, folds, scheme_by_name, sharp, Fit, Mesh, SchemeOptions};

/// Planar faces must be reproduced to rounding (the bound, relative to the bounding-box
/// diagonal): a scheme with linear precision on coplanar data with exact sector normals adds a
/// few ulps per de Casteljau step.
const FLAT_TOL: f64 = 1e-12;

/// A normal estimated on a planar sector is its plane's normal to rounding of the fit's
/// arithmetic (angle-weighted sums and a least-squares solve on exactly coplanar points).
const PLANE_NORMAL_TOL: f64 = 1e-12;

/// The G1 bound of docs/conventions.md.
const G1_TOL: f64 = 1e-9;

fn cube_mesh(rule: CreaseRule, estimator: EstimateChoice) -> Mesh {
    prepare_with(fixtures::creases::cube(4), estimator, false, rule)
        .unwrap()
        .mesh
}

fn default_estimator() -> EstimateChoice {
    EstimateChoice::parse(estimate::DEFAULT_ESTIMATOR).unwrap()
}

fn fit(mesh: &Mesh, scheme: &str, curves: &str) -> Fit {
    let s = scheme_by_name(scheme, &SchemeOptions::default()).unwrap();
    let m = method_by_name(curves, &MethodOptions::default()).unwrap();
    fit_scheme(mesh, s.as_ref(), m.as_ref()).unwrap()
}

/// Every estimator, run per sector on the cube, gives each sector its side's exact normal and
/// a zero shape tensor: the estimate at a crease vertex sees only its own side.
#[test]
fn every_estimator_gives_each_sector_of_the_cube_its_side_plane() {
    for est in ESTIMATORS {
        let mesh = cube_mesh(CreaseRule::Auto, EstimateChoice::With(*est));
        let sectors = mesh.sectors().expect("the cube has creases");
        assert_eq!(sectors.num_creases(), 48, "{}", est.name());
        for f in 0..mesh.num_faces() {
            let n = mesh.face_area_normal(f).unwrap().normalize();
            for c in 0..3 {
                let d = mesh.corner_data(f, c).unwrap();
                let angle = d.n.cross(&n).norm().atan2(d.n.dot(&n));
                assert!(
                    angle <= PLANE_NORMAL_TOL,
                    "{}: face {f} corner {c}: {angle:e}",
                    est.name()
                );
                assert!(d.shape.norm() <= PLANE_NORMAL_TOL, "{}", est.name());
            }
        }
    }
}

/// The cube under every scheme and every curve method: the sides stay flat to rounding, every
/// crease is kept (the patches meet at the data's 90°), no face folds, and the G1 schemes kink
/// no smooth edge. Without creases the same fit bulges (`sharp.rs`).
#[test]
fn every_scheme_and_curve_method_keeps_the_cube_flat_and_sharp() {
    let mesh = cube_mesh(CreaseRule::Auto, default_estimator());
    for scheme in surface::scheme::scheme_names() {
        for curves in curves::REGISTRY.iter().map(|e| e.name) {
            let f = fit(&mesh, scheme, curves);
            let r = sharp::measure(&mesh, &f).unwrap();
            let what = format!("{scheme} on {curves}: {r:?}");
            assert_eq!(r.flat.regions, 6, "{what}");
            assert!(r.flat.deviation <= FLAT_TOL, "{what}");
            assert_eq!(r.creases.kept, r.creases.candidates, "{what}");
            assert_eq!(r.creases.candidates, 48, "{what}");
            assert!(folds::measure(&mesh, &f).folded.is_empty(), "{what}");
            assert_eq!(f.crease_edges, if f.curves.is_empty() { 0 } else { 48 });
            if f.continuity == surface::Continuity::G1 {
                assert_eq!(r.smooth.kinked, 0, "{what}");
            }
        }
    }
}

/// A watertight fit stays watertight along creases: the patches of the Bézier schemes,
/// tessellated and welded by position alone, close up into a mesh without boundary.
#[test]
fn crease_boundaries_are_shared_by_both_faces() {
    let mesh = cube_mesh(CreaseRule::Auto, default_estimator());
    for scheme in surface::scheme::scheme_names() {
        let f = fit(&mesh, scheme, "optimized");
        if !f.layout.is_bezier() {
            continue;
        }
        let t = surface::tessellate::tessellate(&f.bezier_patches(), 3).unwrap();
        let welded = t.to_mesh().unwrap();
        assert!(
            welded.is_closed(),
            "{scheme}: the welded tessellation has a crack"
        );
    }
}

/// A cone's rim (a circle where the flat base meets the slanted side) is a crease line of
/// non-zero curvature: the curves along it take the crease tangents, the surface stays G1 on
/// the smooth edges of both sides, and the rim is kept.
#[test]
fn a_cone_keeps_its_rim_and_stays_g1_elsewhere() {
    let raw = fixtures::creases::cone(24, 6, 1.0);
    let mesh = prepare_with(raw, default_estimator(), false, CreaseRule::Auto)
        .unwrap()
        .mesh;
    let sectors = mesh.sectors().expect("the rim is a crease");
    assert!(sectors.num_creases() >= 24, "{}", sectors.num_creases());
    for curves in ["chord", "optimized"] {
        let f = fit(&mesh, "shirman-sequin", curves);
        let g1 = surface::g1::measure(&mesh, &f, 9);
        let r = sharp::measure(&mesh, &f).unwrap();
        assert_eq!(r.creases.kept, r.creases.candidates, "{curves}: {r:?}");
        assert_eq!(g1.crease_edges, sectors.num_creases());
        // Faces beside the apex may fall back (a pole); the rest is G1.
        assert!(g1.exterior_max <= G1_TOL, "{curves}: {g1:?}");
        assert!(g1.interior_max <= G1_TOL, "{curves}: {g1:?}");
    }
}

/// A scan keeps one normal per vertex by default (no component of the bunny is a tessellated
/// model), and gets sectors when a crease angle is asked for.
#[test]
fn scans_stay_smooth_unless_a_crease_angle_is_asked_for() {
    let path = fixtures::corpus::corpus_dir().join("bunny.ply");
    let raw = meshio::read_file(&path).unwrap();
    let auto = prepare_with(raw.clone(), default_estimator(), false, CreaseRule::Auto).unwrap();
    assert!(auto.mesh.sectors().is_none());
    assert_eq!(auto.creases.creases, 0);
    let asked = prepare_with(raw, default_estimator(), false, CreaseRule::Angle(40.0)).unwrap();
    assert!(asked.mesh.sectors().is_some());
    assert!(asked.creases.creases > 0, "{:?}", asked.creases);
}

/// The crease-aware tessellation gives each side of a crease its own vertices (its own normals)
/// at bit-identical positions, so a file in single precision still closes up when a reader
/// merges coincident vertices: the CAD gear's tessellation (curved creases round its teeth and
/// bore), positions rounded to `f32` and merged by equality alone, has every edge on exactly two
/// triangles. (At 4 segments a patch edge, copies evaluated each from its own patch differed
/// beyond single precision: the merge left cracks.)
#[test]
fn crease_copies_of_a_tessellation_vertex_share_their_position_bit_for_bit() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/cad/gear.ply");
    let raw = meshio::read_file(&path).unwrap();
    let mesh = prepare_with(raw, default_estimator(), false, CreaseRule::Auto)
        .unwrap()
        .mesh;
    let f = fit(&mesh, "shirman-sequin", "optimized");
    let t = surface::tessellate_fit(&mesh, &f, 4).unwrap();
    let mut ids = std::collections::HashMap::new();
    let merged: Vec<usize> = t
        .positions
        .iter()
        .map(|p| {
            let key = [p.x as f32, p.y as f32, p.z as f32].map(f32::to_bits);
            let next = ids.len();
            *ids.entry(key).or_insert(next)
        })
        .collect();
    assert!(ids.len() < t.positions.len(), "the creases split vertices");
    let mut edges = std::collections::HashMap::new();
    for tri in &t.faces {
        for k in 0..3 {
            let (a, b) = (merged[tri[k]], merged[tri[(k + 1) % 3]]);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    assert!(edges.values().all(|&n| n == 2), "a crack after merging");
}

//! One bad face never sinks a mesh: faces the split-domain construction cannot fit get the C0
//! fallback patch, degenerate edges the straight cubic, and the rest of the mesh is fitted and
//! measured as usual.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions, REGISTRY};
use meshio::RawMesh;
use nalgebra::{Point3, Rotation3, Vector3};
use surface::repair::{repair, RepairOptions};
use surface::scheme::shirman_sequin::{ShirmanSequin, Unfold};
use surface::{
    dataset_by_name, fit, fit_scheme, measure_g1, FaceFallbackReason, InteriorParameters, Mesh,
};

/// G1 is exact by construction on regular faces; measured angles are rounding noise.
const G1_TOL: f64 = 1e-9;
/// Fallback patches share the boundary curves: corners and edges agree to rounding.
const C0_TOL: f64 = 1e-12;

fn defaults(_: usize) -> InteriorParameters {
    InteriorParameters::default()
}

/// The largest gap between the two faces' patches along every shared edge, at 9 samples.
fn max_edge_gap(mesh: &Mesh, f: &surface::Fit) -> f64 {
    let mut worst: f64 = 0.0;
    for e in mesh.edges() {
        let (Some((g, lg)), (h, lh)) = (e.second, e.first) else {
            continue;
        };
        let ph = f.patch(3 * h + lh).unwrap();
        let pg = f.patch(3 * g + lg).unwrap();
        for s in 0..9 {
            let t = s as f64 / 8.0;
            let a = ph.eval(1.0 - t, t, 0.0);
            let b = pg.eval(t, 1.0 - t, 0.0);
            worst = worst.max((a - b).norm());
        }
    }
    worst
}

#[test]
fn a_normal_against_the_winding_gives_fallback_faces_only_there() {
    let mut data = dataset_by_name("sphere", None).unwrap();
    // Turn one vertex normal by 2.8 rad (160°) about a tangent axis: some of its corner cross
    // vectors fold over the edges (smaller turns of this vertex still fit: measured, 1.6 rad is
    // the first turn about this axis that folds a corner).
    let v = 5;
    let n = data.mesh.vertices()[v].data.n;
    let axis = n.cross(&Vector3::new(0.3, 0.2, 0.9)).normalize();
    data.mesh.vertices_mut()[v].data.n = Rotation3::new(axis * 2.8) * n;
    let around = data.mesh.faces_around_vertex(v);
    for entry in REGISTRY.iter().filter(|e| e.name == "chord") {
        let m = method_by_name(entry.name, &MethodOptions::default()).unwrap();
        let fitted = fit(&data.mesh, m.as_ref(), &defaults).unwrap();
        assert!(!fitted.face_fallbacks.is_empty());
        for fb in &fitted.face_fallbacks {
            assert!(
                around.contains(&fb.face),
                "face {} is not around vertex {v}",
                fb.face
            );
            assert!(matches!(fb.reason, FaceFallbackReason::Scheme(_)));
        }
        let r = measure_g1(&data.mesh, &fitted, 9);
        assert!(r.interior_max < G1_TOL, "{r:?}");
        assert!(r.exterior_max < G1_TOL, "{r:?}");
        assert!(r.fallback_edges > 0);
        assert!(r.position_error < C0_TOL);
        assert!(max_edge_gap(&data.mesh, &fitted) < C0_TOL);
    }
}

#[test]
fn zero_area_faces_and_coincident_vertices_are_fitted() {
    // A flat square fan with a collinear triangle and a duplicated position.
    let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    let pos = vec![
        p(0.0, 0.0),
        p(1.0, 0.0),
        p(1.0, 1.0),
        p(0.0, 1.0),
        p(2.0, 0.0),
        p(1.0, 1.0), // same position as vertex 2
        p(2.0, 1.0),
    ];
    let tris = [[0, 1, 2], [0, 2, 3], [0, 4, 1], [1, 4, 6], [1, 6, 5]];
    let mut raw = RawMesh::from_triangles(pos, &tris);
    raw.normals = Some(vec![Vector3::z(); 7]);
    let r = repair(&raw, &RepairOptions::default()).unwrap();
    assert_eq!(r.report.degenerate_faces, vec![2]);
    let m = method_by_name("chord", &MethodOptions::default()).unwrap();
    let fitted = fit(&r.mesh, m.as_ref(), &defaults).unwrap();
    let reasons: Vec<(usize, FaceFallbackReason)> = fitted
        .face_fallbacks
        .iter()
        .map(|fb| (fb.face, fb.reason))
        .collect();
    assert!(
        reasons.contains(&(2, FaceFallbackReason::ZeroArea)),
        "{reasons:?}"
    );
    // Vertices 1–5 lie on no common face, so no edge joins them: no degenerate edge here, but
    // every control point is finite and the flat data gives a flat surface.
    for net in fitted.nets() {
        for q in net {
            assert!(q.z.abs() < C0_TOL && q.x.is_finite() && q.y.is_finite());
        }
    }
}

#[test]
fn a_degenerate_edge_gets_the_straight_cubic() {
    // Two triangles sharing an edge whose end normals are opposite.
    let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    let pos = vec![p(0.0, 0.0), p(1.0, 0.0), p(0.5, 1.0), p(0.5, -1.0)];
    let mut raw = RawMesh::from_triangles(pos, &[[0, 1, 2], [1, 0, 3]]);
    raw.normals = Some(vec![
        Vector3::z(),
        -Vector3::z(),
        Vector3::z(),
        Vector3::z(),
    ]);
    // Opposite normals make the file's winding ambiguous: keep the faces as given.
    let r = repair(&raw, &RepairOptions::default()).unwrap();
    let m = method_by_name("chord", &MethodOptions::default()).unwrap();
    let fitted = fit(&r.mesh, m.as_ref(), &defaults).unwrap();
    assert!(!fitted.degenerate_edges.is_empty());
    let e = fitted.degenerate_edges[0];
    let c = fitted.curves[e.edge];
    let d = c.points[3] - c.points[0];
    assert!((c.points[1] - (c.points[0] + d / 3.0)).norm() < C0_TOL);
    assert!(
        e.error.to_string().contains("opposite normals"),
        "{}",
        e.error
    );
    assert!(fitted
        .points
        .iter()
        .all(|q| q.iter().all(|x| x.is_finite())));
}

#[test]
fn the_ring_on_dbhs_curves_unfolds_by_its_interior_parameters() {
    // dBHS's short end derivatives on the 16 × 8 ring fold 64 of its 256 regular patches over
    // their faces (the seeds' "lumps") at the default β and c. The registered scheme
    // (`Unfold::Interior`) rebuilds each with the first interior parameters that do not fold:
    // every one unfolds, no face falls back, and G1 and C0 hold as for any β, c > 0.
    let data = dataset_by_name("ring", None).unwrap();
    let m = method_by_name("dbhs", &MethodOptions::default()).unwrap();
    let kept = fit(&data.mesh, m.as_ref(), &defaults).unwrap();
    assert!(kept.face_fallbacks.is_empty());
    let folded = surface::folds::measure(&data.mesh, &kept).folded;
    assert_eq!(folded.len(), 64);
    for rule in [Unfold::Interior, Unfold::Fallback] {
        let unfolding =
            ShirmanSequin::uniform(InteriorParameters::default()).with_unfold_rule(rule);
        let fitted = fit_scheme(&data.mesh, &unfolding, m.as_ref()).unwrap();
        assert!(fitted.face_fallbacks.is_empty(), "{rule:?}");
        let folds = surface::folds::measure(&data.mesh, &fitted);
        assert!(folds.folded.is_empty(), "{rule:?}: {:?}", folds.folded);
        let r = measure_g1(&data.mesh, &fitted, 9);
        assert!(r.interior_max < G1_TOL && r.exterior_max < G1_TOL, "{r:?}");
        assert!(max_edge_gap(&data.mesh, &fitted) < C0_TOL);
        // Exactly the folded faces were rebuilt; every other face is bit for bit as asked.
        let per_face = 45;
        for face in 0..data.mesh.num_faces() {
            let range = per_face * face..per_face * (face + 1);
            let same = fitted.points[range.clone()] == kept.points[range];
            assert_eq!(same, !folded.contains(&face), "face {face}");
        }
    }
}

//! The streamed fit (`surface::stream`, what `fit --out` runs when nothing needs the whole fit)
//! against the path that holds every net: on every hostile mesh of the fixtures' zoo (irregular,
//! noisy, open, needles, zero-area faces, creases, non-manifold spots…) and a larger irregular
//! noisy torus, with every registered scheme, chord and optimized curves, windows from one face
//! (every exterior edge crosses a border: its other face is built again) to the default, the
//! fit's bookkeeping, the G1 report and the written bytes are **identical** — not close: the
//! same bits, the same maxima at the same places (ties included), the same file — and the
//! tessellation from the streamed fit (nets built again per face) is the whole fit's.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use curves::{method_by_name, MethodOptions};
use estimate::{prepare, EstimateChoice};

use crate::support::default_estimator;
use meshio::RawMesh;
use nalgebra::Point3;
use surface::patch_io::{write_patches, PatchFormat};
use surface::stream::{fit_streamed_with, Output, WINDOW_FACES};
use surface::tessellate_fit::Keep;
use surface::{
    fit_scheme, measure_g1, scheme_by_name, tessellate_fit, tessellate_fit_rebuilt,
    tessellate_fit_rebuilt_taking, tessellate_fit_rebuilt_with, welds_by_topology, Fit, Mesh,
    SchemeOptions,
};

/// G1 is measured at 9 samples per boundary, as `fit` does.
const SAMPLES: usize = 9;

fn prepared(label: &str, raw: &RawMesh) -> Mesh {
    prepare(raw, EstimateChoice::With(default_estimator()), false)
        .unwrap_or_else(|e| panic!("{label}: {e}"))
        .mesh
}

/// A map to world coordinates that is not the identity, so the writers' mapping is exercised.
fn to_world(p: &Point3<f64>) -> Point3<f64> {
    Point3::new(2.0 * p.x + 0.25, p.y - 1.0, 0.5 * p.z)
}

fn same_fit(label: &str, streamed: &Fit, whole: &Fit) {
    assert_eq!(streamed.scheme, whole.scheme, "{label}");
    assert_eq!(streamed.layout, whole.layout, "{label}");
    assert_eq!(streamed.curves, whole.curves, "{label}: curves");
    assert_eq!(streamed.alphas, whole.alphas, "{label}: alphas");
    assert_eq!(streamed.fallbacks, whole.fallbacks, "{label}");
    assert_eq!(streamed.unconverged, whole.unconverged, "{label}");
    assert_eq!(streamed.flipped_tangents, whole.flipped_tangents, "{label}");
    assert_eq!(streamed.degenerate_edges, whole.degenerate_edges, "{label}");
    assert_eq!(streamed.face_fallbacks, whole.face_fallbacks, "{label}");
    assert!(streamed.points.is_empty(), "{label}: the nets are not kept");
}

/// Streams `mesh` with every window in `windows` and both formats, and compares everything with
/// the non-streamed fit, measurement and writer. Returns the number of fallback faces.
fn check(label: &str, mesh: &Mesh, scheme: &str, curves: &str, windows: &[usize]) -> usize {
    let scheme = scheme_by_name(scheme, &SchemeOptions::default()).unwrap();
    let method = method_by_name(curves, &MethodOptions::default()).unwrap();
    let whole = fit_scheme(mesh, scheme.as_ref(), method.as_ref())
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    let g1 = measure_g1(mesh, &whole, SAMPLES);
    for format in [PatchFormat::JsonLines, PatchFormat::Binary] {
        let mut expected = Vec::new();
        write_patches(&whole, format, &to_world, &mut expected).unwrap();
        for &window in windows {
            let label = format!(
                "{label}/{}/{curves}/{format:?}/window {window}",
                whole.scheme
            );
            let mut bytes = Vec::new();
            let s = fit_streamed_with(
                mesh,
                scheme.as_ref(),
                method.as_ref(),
                SAMPLES,
                Some(Output {
                    format,
                    to_world: &to_world,
                    out: &mut bytes,
                }),
                window,
            )
            .unwrap_or_else(|e| panic!("{label}: {e}"));
            same_fit(&label, &s.fit, &whole);
            assert_eq!(s.g1, g1, "{label}: G1 report");
            assert!(bytes == expected, "{label}: the bytes differ");
        }
    }
    // Without output: the same report.
    let s = fit_streamed_with(mesh, scheme.as_ref(), method.as_ref(), SAMPLES, None, 5).unwrap();
    assert_eq!(s.g1, g1, "{label}: G1 without output");
    // The tessellation from the streamed fit, each face's nets built again where its samples
    // are evaluated, is the whole fit's (what `fit --mesh-out` writes without holding the nets).
    assert!(
        whole.scheme != "shirman-sequin" || welds_by_topology(&whole.layout, 1),
        "{label}: the split-domain layout is welded by topology"
    );
    for density in [1, 3] {
        if !welds_by_topology(&whole.layout, density) {
            continue;
        }
        let expected = tessellate_fit(mesh, &whole, density).unwrap();
        let rebuilt = tessellate_fit_rebuilt(mesh, &s.fit, scheme.as_ref(), density)
            .unwrap_or_else(|e| panic!("{label}: {e}"));
        assert!(
            rebuilt == expected,
            "{label}/{}: the tessellation at s = {density} differs",
            whole.scheme
        );
        // What a file needs (`fit --mesh-output`): the principal directions instead of the
        // shape tensors, no patches. The same tessellation but for those, and directions that
        // are the tensors' once mapped to world coordinates, bit for bit.
        let scale = 0.37;
        let keep = Keep {
            shapes: false,
            directions: Some(scale),
            patches: false,
        };
        let lean = tessellate_fit_rebuilt_with(mesh, &s.fit, scheme.as_ref(), density, keep)
            .unwrap_or_else(|e| panic!("{label}: {e}"));
        assert!(
            lean.shapes.is_empty() && lean.patch_of_face.is_empty(),
            "{label}"
        );
        // The same with the curves taken from the fit (freed before the triangles).
        let mut taken = s.fit.clone();
        let owned = tessellate_fit_rebuilt_taking(mesh, &mut taken, scheme.as_ref(), density, keep)
            .unwrap_or_else(|e| panic!("{label}: {e}"));
        assert!(
            taken.curves.is_empty(),
            "{label}: the curves were not taken"
        );
        assert!(
            owned == lean,
            "{label}: taking the curves changed the tessellation"
        );
        let mut expected_lean = expected.clone();
        expected_lean.shapes.clear();
        expected_lean.patch_of_face.clear();
        let mut lean_rest = lean.clone();
        let directions = std::mem::take(&mut lean_rest.directions);
        assert!(
            lean_rest == expected_lean,
            "{label}/{}: the lean tessellation at s = {density} differs",
            whole.scheme
        );
        assert_eq!(directions.len(), expected.positions.len(), "{label}");
        for ((d, shape), n) in directions
            .iter()
            .zip(&expected.shapes)
            .zip(&expected.normals)
        {
            let p = estimate::principal_frame(&(shape / scale), n);
            for (a, b) in [p.d1, p.d2]
                .iter()
                .flat_map(|v| v.iter())
                .zip(d.iter().flat_map(|v| v.iter()))
            {
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "{label}: a principal direction differs"
                );
            }
        }
    }
    whole.face_fallbacks.len()
}

#[test]
fn every_zoo_mesh_and_scheme_streams_to_the_same_report_and_bytes() {
    let mut fallbacks = 0;
    let mut meshes = 0;
    for (label, raw) in fixtures::zoo() {
        let Ok(p) = prepare(&raw, EstimateChoice::With(default_estimator()), false) else {
            continue; // meshes the input path refuses are tested elsewhere
        };
        meshes += 1;
        for entry in surface::scheme::REGISTRY {
            fallbacks += check(label, &p.mesh, entry.name, "chord", &[1, 7, WINDOW_FACES]);
        }
        fallbacks += check(label, &p.mesh, "shirman-sequin", "optimized", &[1, 13]);
    }
    assert!(meshes >= 25, "only {meshes} zoo meshes were prepared");
    // The zoo's hostile meshes do send faces to the fallback: the fallback paths (C0 faces,
    // fallback edges measured apart, a rebuilt outside face that is itself a fallback) are
    // exercised, not just the regular ones.
    assert!(fallbacks > 0);
}

#[test]
fn a_larger_noisy_torus_streams_to_the_same_report_and_bytes() {
    let opts = fixtures::Irregular {
        noise: 0.002,
        seed: 11,
        ..fixtures::Irregular::default()
    };
    let raw = fixtures::analytic::torus(120, 60, 1.0, 0.35, &opts);
    let mesh = prepared("torus 14400", &raw);
    assert_eq!(mesh.num_faces(), 14_400);
    for scheme in ["shirman-sequin", "pn-triangles", "nielson"] {
        check("torus 14400", &mesh, scheme, "optimized", &[97, 4096]);
    }
}

/// Ties of the largest exterior defect are resolved as the sequential scan does (smallest
/// edge, then smallest parameter), whatever order the windows measure edges in: on a flat
/// grid every normal is the same, every defect is 0, and the report must name the first edge.
#[test]
fn ties_name_the_first_edge_as_the_sequential_scan_does() {
    let (nx, ny) = (12, 9);
    let positions = (0..ny)
        .flat_map(|j| (0..nx).map(move |i| Point3::new(i as f64, j as f64, 0.0)))
        .collect();
    let mut tris = Vec::new();
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let a = j * nx + i;
            tris.push([a, a + 1, a + nx + 1]);
            tris.push([a, a + nx + 1, a + nx]);
        }
    }
    let mesh = prepared("flat grid", &RawMesh::from_triangles(positions, &tris));
    check(
        "flat grid",
        &mesh,
        "shirman-sequin",
        "chord",
        &[1, 2, 3, 50],
    );
    let scheme = scheme_by_name("flat", &SchemeOptions::default()).unwrap();
    let method = method_by_name("chord", &MethodOptions::default()).unwrap();
    let s = fit_streamed_with(&mesh, scheme.as_ref(), method.as_ref(), SAMPLES, None, 3).unwrap();
    assert_eq!(s.g1.exterior_max, 0.0);
    let first_inner = mesh.edges().position(|e| e.second.is_some());
    assert_eq!(
        s.g1.exterior_at,
        first_inner.map(|edge| (surface::Boundary::Exterior { edge }, 0.0))
    );
}

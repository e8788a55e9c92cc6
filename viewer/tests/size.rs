//! The page's size against the same surface as `.glb` (positions, normals, K and H as `f32`,
//! `u32` indices): the embedded data is at most twice the glb at any size, and so is the whole
//! page once the mesh outweighs the vendored three.js (a constant ≈ 0.54 MB).

#![allow(clippy::expect_used)] // test fixtures fail loudly by design

mod common;

use nalgebra::{Point3, Vector3};
use viewer::{Page, View};

/// The bound the page is held to, relative to the glb.
const MAX_RATIO: f64 = 2.0;

/// The view's surface as glb bytes, with the same per-vertex data glTF can carry.
fn glb_of(view: &View) -> Vec<u8> {
    let scalar = |name: &str| -> Vec<f64> {
        view.scalars
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.iter().map(|&x| f64::from(x)).collect())
            .unwrap_or_default()
    };
    let positions = view
        .mesh
        .positions
        .iter()
        .map(|p| Point3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2])))
        .collect();
    let tris: Vec<[usize; 3]> = view
        .mesh
        .indices
        .iter()
        .map(|t| [t[0] as usize, t[1] as usize, t[2] as usize])
        .collect();
    let mut raw = meshio::RawMesh::from_triangles(positions, &tris);
    raw.normals = Some(
        view.mesh
            .normals
            .iter()
            .map(|n| Vector3::new(f64::from(n[0]), f64::from(n[1]), f64::from(n[2])))
            .collect(),
    );
    // K and H only, as the page's data: the principal directions a fit's glb also carries
    // would make the glb larger and the comparison easier.
    raw.curvature = Some(meshio::Curvature::from_exported(scalar("K"), scalar("H")));
    meshio::write_bytes(&raw, &meshio::glb::Glb, &meshio::WriteOptions::new()).expect("a glb")
}

#[test]
fn the_page_is_at_most_twice_the_glb() {
    for (nu, nv) in [(48, 24), (192, 96), (512, 256)] {
        let full = common::torus("torus", nu, nv, 2.0, 0.75, 8);
        let mut view = full.clone();
        // The page carries what the glb cannot (k1, k2, boundaries, data mesh): the bound is for
        // the same surface, so only the glb's data are kept.
        view.scalars.retain(|(n, _)| n == "K" || n == "H");
        view.boundaries = None;
        view.data_mesh = None;
        let glb = glb_of(&view).len() as f64;
        let mut page = Page::new("size");
        page.add_view(view).expect("a valid torus");
        let (data, html) = (page.data_json().len() as f64, page.to_html().len() as f64);
        eprintln!(
            "{} vertices: glb {glb} bytes, data {data} ({:.2}×), page {html} ({:.2}×)",
            nu * nv,
            data / glb,
            html / glb
        );
        assert!(
            data <= MAX_RATIO * glb,
            "data {data} > {MAX_RATIO} × glb {glb}"
        );
        // With κ1 and κ2 as well (what `view_from_tessellation` gives), still within the bound.
        let mut with_principal = Page::new("size");
        let mut four = full;
        four.boundaries = None;
        four.data_mesh = None;
        with_principal.add_view(four).expect("a valid torus");
        let data4 = with_principal.data_json().len() as f64;
        eprintln!("  with κ1, κ2: data {data4} ({:.2}×)", data4 / glb);
        assert!(
            data4 <= MAX_RATIO * glb,
            "data with κ1, κ2 {data4} > {MAX_RATIO} × glb {glb}"
        );
        if nu * nv >= 100_000 {
            assert!(
                html <= MAX_RATIO * glb,
                "page {html} > {MAX_RATIO} × glb {glb}"
            );
        }
    }
}

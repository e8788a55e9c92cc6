//! The CAD corpus (`data/cad/`, made by `data/cad/generate.py`): parts with sharp features made
//! by CSG and remeshed badly on purpose (needles, caps, fans, anisotropic strips). Every file is
//! read and prepared the way `fit` prepares a file (`meshio` → `estimate::prepare`), must be
//! used as given (no face skipped, reversed, split or dropped: the corpus promises consistent
//! outward winding and no zero-area face), and must agree with `data/cad/README.md`'s table:
//! faces, vertices, boundary edges, components and the number of edges whose dihedral angle is
//! over 40° as `mesh::features::Features::detect` finds them.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use std::path::PathBuf;

use estimate::{prepare, EstimateChoice};
use mesh::features::Features;

use crate::support::default_estimator;

/// The crease threshold of the README's "dihedral > 40°" column (the workbench's default,
/// `mesh::features::DEFAULT_CREASE_ANGLE_DEG`).
const CREASE_DEG: f64 = 40.0;

/// Per mesh: faces, vertices, edges over [`CREASE_DEG`], boundary edges, components — as the
/// generator measured them (README table).
struct Expected {
    name: &'static str,
    faces: usize,
    vertices: usize,
    creases: usize,
    boundary_edges: usize,
    components: usize,
}

const fn row(
    name: &'static str,
    faces: usize,
    vertices: usize,
    creases: usize,
    boundary_edges: usize,
    components: usize,
) -> Expected {
    Expected {
        name,
        faces,
        vertices,
        creases,
        boundary_edges,
        components,
    }
}

const EXPECTED: &[Expected] = &[
    row("box", 850, 427, 152, 0, 1),
    row("box_fillet", 4196, 2100, 62, 0, 1),
    row("cylinder_chamfer", 6124, 3064, 216, 0, 1),
    row("plate_holes", 8036, 4008, 480, 0, 1),
    row("boss", 7836, 3918, 188, 0, 1),
    row("gear", 7084, 3542, 932, 0, 1),
    row("swiss_cheese", 3282, 1643, 416, 0, 1),
    row("pipe_joint", 8092, 4044, 376, 0, 1),
    row("open_bracket", 2339, 1204, 174, 75, 1),
    row("two_parts", 1504, 752, 374, 0, 2),
];

/// Two coordinates of a file's vertices this close (absolute; the parts are 10–60 units
/// across) are meant to be one: the generator snaps a vertex onto its part's plane when it is
/// within 1e-9 of it, and its smallest features are 0.05 across.
const SAME_COORDINATE: f64 = 1e-9;

fn cad_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("data")
        .join("cad")
}

#[test]
fn the_directory_holds_exactly_the_tabled_meshes() {
    let mut found: Vec<String> = std::fs::read_dir(cad_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter_map(|n| n.strip_suffix(".ply").map(str::to_owned))
        .collect();
    found.sort();
    let mut tabled: Vec<String> = EXPECTED.iter().map(|e| e.name.to_owned()).collect();
    tabled.sort();
    assert_eq!(found, tabled);
}

#[test]
fn every_cad_mesh_prepares_as_given_with_the_readme_counts_and_creases() {
    for e in EXPECTED {
        let path = cad_dir().join(format!("{}.ply", e.name));
        let raw = meshio::read_file(&path).unwrap_or_else(|err| panic!("{}: {err}", e.name));
        assert_eq!(raw.polygons.len(), e.faces, "{}: faces in the file", e.name);
        assert!(
            raw.polygons.all_triangles(),
            "{}: a face is not a triangle",
            e.name
        );
        assert_eq!(raw.positions.len(), e.vertices, "{}: vertices", e.name);
        let p = prepare(&raw, EstimateChoice::With(default_estimator()), false)
            .unwrap_or_else(|err| panic!("{}: {err}", e.name));
        let r = &p.report;
        assert!(r.is_clean(), "{}: {:?}", e.name, r.summary_lines());
        assert!(
            r.degenerate_faces.is_empty(),
            "{}: zero-area faces {:?}",
            e.name,
            r.degenerate_faces
        );
        assert_eq!(r.unused_vertices, 0, "{}", e.name);
        assert_eq!(r.components, e.components, "{}: components", e.name);
        assert_eq!(r.boundary_edges, e.boundary_edges, "{}: boundary", e.name);
        assert_eq!(
            p.mesh.num_faces(),
            e.faces,
            "{}: faces after repair",
            e.name
        );
        let creases = Features::detect(&p.mesh, CREASE_DEG).num_creases();
        assert!(creases > 0, "{}: no crease over {CREASE_DEG}°", e.name);
        assert_eq!(creases, e.creases, "{}: creases over {CREASE_DEG}°", e.name);
    }
}

#[test]
fn the_readme_table_is_the_tested_one() {
    let readme = std::fs::read_to_string(cad_dir().join("README.md")).unwrap();
    for e in EXPECTED {
        let start = format!("| `{}.ply` |", e.name);
        let line = readme
            .lines()
            .find(|l| l.starts_with(&start))
            .unwrap_or_else(|| panic!("README.md has no row for {}", e.name));
        // Columns: mesh, faces, vertices, edges, dihedral > 40°, …, boundary edges, closed,
        // components (the generator's `readme_section`).
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let num = |i: usize| -> usize { cells[i].parse().unwrap() };
        assert_eq!(num(2), e.faces, "{}: faces", e.name);
        assert_eq!(num(3), e.vertices, "{}: vertices", e.name);
        assert_eq!(num(5), e.creases, "{}: dihedral > 40°", e.name);
        assert_eq!(num(13), e.boundary_edges, "{}: boundary edges", e.name);
        assert_eq!(num(15), e.components, "{}: components", e.name);
    }
}

#[test]
fn axis_flat_faces_are_exactly_flat_in_the_file() {
    // A face whose three corners agree in one coordinate to SAME_COORDINATE lies on an
    // axis-aligned plane of its part and must agree exactly: the file's float64 positions put
    // every vertex of a planar face exactly on its plane. At least one face of every mesh is
    // such a face (each part has an axis-aligned planar face).
    for e in EXPECTED {
        let raw = meshio::read_file(cad_dir().join(format!("{}.ply", e.name))).unwrap();
        let mut exact = 0;
        for (fi, face) in raw.polygons.iter().enumerate() {
            let [a, b, c] = [face[0], face[1], face[2]].map(|v| raw.positions[v]);
            for axis in 0..3 {
                let (lo, hi) = [a[axis], b[axis], c[axis]]
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                        (lo.min(x), hi.max(x))
                    });
                if hi - lo <= SAME_COORDINATE {
                    assert_eq!(
                        lo, hi,
                        "{}: face {fi} is off its plane (axis {axis})",
                        e.name
                    );
                    exact += 1;
                }
            }
        }
        assert!(exact > 0, "{}: no axis-aligned flat face", e.name);
    }
}

/// G1 on the CAD parts' smooth edges and inside their faces: exact by construction, measured to
/// rounding grown by the parts' scale (10–60 units; plate_holes measured 1.3e-9, the largest).
const G1_CAD: f64 = 1e-8;

/// Every CAD part is fitted with the default curves and no C0 fallback face: the caps between
/// two crease edges on a curved crease line (a straight crease corner, whose tangents are
/// opposite) are built by the scheme's straight-corner form, G1 inside and across their smooth
/// edge. Measured: straight corners box_fillet 12, pipe_joint 6, two_parts 6, boss 2, gear 2,
/// the faces that fell back before.
#[test]
fn every_cad_part_fits_without_a_fallback_face() {
    let m = curves::method_by_name("optimized", &curves::MethodOptions::default()).unwrap();
    let mut straight = 0;
    for e in EXPECTED {
        let path = cad_dir().join(format!("{}.ply", e.name));
        let raw = meshio::read_file(&path).unwrap();
        let mesh = prepare(&raw, EstimateChoice::With(default_estimator()), false)
            .unwrap()
            .mesh;
        let f = surface::fit(&mesh, m.as_ref(), &|_| {
            surface::InteriorParameters::default()
        })
        .unwrap();
        assert!(
            f.face_fallbacks.is_empty(),
            "{}: {:?}",
            e.name,
            f.face_fallbacks
        );
        let g1 = surface::measure_g1(&mesh, &f, 5);
        assert!(
            g1.interior_max < G1_CAD && g1.exterior_max < G1_CAD,
            "{}: {g1:?}",
            e.name
        );
        assert_eq!(f.fan.sectors_unfannable, 0, "{}: {:?}", e.name, f.fan);
        straight += f.fan.sectors_straight;
    }
    // The premise: the corpus has straight crease corners, and they were built.
    assert_eq!(straight, 28);
}

/// Positions interpolated by construction, to rounding at the parts' scale (10–60 units).
const INTERPOLATION_CAD: f64 = 1e-9;

/// The registered scheme rebuilds a face whose patch folds with other interior parameters
/// (`surface::scheme::shirman_sequin::Unfold::Interior`): on swiss_cheese (needles round its
/// holes) the folded faces drop from 60 to 20 (measured), G1 holds as before, and every face
/// that did not fold keeps its nets bit for bit; the fallback rule then gives the C0 fallback
/// to faces no candidate unfolds.
#[test]
fn folded_faces_are_rebuilt_with_interior_parameters_that_do_not_fold() {
    use surface::scheme::shirman_sequin::{ShirmanSequin, Unfold};
    let raw = meshio::read_file(cad_dir().join("swiss_cheese.ply")).unwrap();
    let mesh = prepare(&raw, EstimateChoice::With(default_estimator()), false)
        .unwrap()
        .mesh;
    let m = curves::method_by_name("optimized", &curves::MethodOptions::default()).unwrap();
    let fit_with = |rule: Unfold| {
        let scheme =
            ShirmanSequin::uniform(surface::InteriorParameters::default()).with_unfold_rule(rule);
        surface::fit_scheme(&mesh, &scheme, m.as_ref()).unwrap()
    };
    let (off, on) = (fit_with(Unfold::Off), fit_with(Unfold::Interior));
    let folded_off = surface::folds::measure(&mesh, &off).folded;
    let folded_on = surface::folds::measure(&mesh, &on).folded;
    assert!(
        folded_on.len() * 2 < folded_off.len(),
        "{} → {}",
        folded_off.len(),
        folded_on.len()
    );
    assert!(on.face_fallbacks.is_empty() && off.face_fallbacks.is_empty());
    for f in [&off, &on] {
        let g1 = surface::measure_g1(&mesh, f, 5);
        assert!(
            g1.interior_max < G1_CAD && g1.exterior_max < G1_CAD,
            "{g1:?}"
        );
        assert!(g1.position_error < INTERPOLATION_CAD, "{g1:?}");
    }
    // Where no candidate unfolds a face, `Unfold::Fallback` gives it the C0 fallback when
    // that does not fold (measured: 4 of the 20, leaving 16 folded), and only there.
    let fallback = fit_with(Unfold::Fallback);
    let folded_fallback = surface::folds::measure(&mesh, &fallback).folded;
    assert!(!fallback.face_fallbacks.is_empty());
    assert_eq!(
        fallback.face_fallbacks.len() + folded_fallback.len(),
        folded_on.len()
    );
    for fb in &fallback.face_fallbacks {
        assert_eq!(
            fb.reason,
            surface::FaceFallbackReason::Scheme(surface::SchemeError::FoldsOverFace)
        );
        assert!(folded_on.contains(&fb.face), "face {}", fb.face);
    }
    // Only faces that folded were rebuilt (three quartic nets of 15 points a face).
    let per_face = 3 * 15;
    for face in 0..mesh.num_faces() {
        let same = off.points[per_face * face..per_face * (face + 1)]
            == on.points[per_face * face..per_face * (face + 1)];
        assert!(same || folded_off.contains(&face), "face {face} changed");
    }
}

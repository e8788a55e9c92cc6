//! Hostile and unusual input: boundaries, several components, isolated vertices, valence-2
//! boundary corners, creases and corners, and every refusal with the element it names.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use fixtures::analytic::Irregular;
use meshio::{Polygons, RawMesh};
use nalgebra::Point3;
use subdiv::shapes::{icosahedron, quad_grid};
use subdiv::{
    scheme_by_name, subdivide, CatmullClark, Loop, PolyMesh, SubdivError, Subdivision,
    DEFAULT_MAX_FACES, SCHEMES,
};

fn euler(m: &PolyMesh) -> i64 {
    let used = {
        let mut u = vec![false; m.num_vertices()];
        for f in m.faces() {
            for &v in f {
                u[v as usize] = true;
            }
        }
        u.iter().filter(|&&x| x).count() as i64
    };
    used - m.num_edges() as i64 + m.num_faces() as i64
}

fn all_schemes() -> Vec<Box<dyn Subdivision>> {
    SCHEMES.iter().map(|e| (e.build)()).collect()
}

#[test]
fn open_meshes_components_and_isolated_vertices_subdivide() {
    let meshes: Vec<(&str, RawMesh)> = vec![
        (
            "hemisphere",
            fixtures::open::hemisphere(8, 5, &Irregular::default()),
        ),
        (
            "spheres",
            fixtures::components::disjoint_spheres(3, 6, 4, 0.5, &Irregular::default()),
        ),
        (
            "isolated",
            fixtures::nonmanifold::isolated_vertices(6, 4, 5, 9),
        ),
    ];
    for (name, raw) in meshes {
        let mesh = PolyMesh::from_raw(&raw).unwrap();
        for scheme in all_schemes() {
            let out = subdivide(scheme.as_ref(), &mesh, 2, DEFAULT_MAX_FACES).unwrap();
            assert_eq!(
                out.num_faces() as u64,
                scheme.faces_after(&mesh, 2).unwrap(),
                "{name} {}",
                scheme.name()
            );
            assert_eq!(euler(&out), euler(&mesh), "{name} {}", scheme.name());
            let lim = scheme.limit_positions(&mesh).unwrap();
            let nrm = scheme.limit_normals(&mesh).unwrap();
            assert!(lim.iter().all(|p| p.coords.iter().all(|c| c.is_finite())));
            if name == "isolated" {
                let n = mesh.num_vertices();
                for v in n - 5..n {
                    assert_eq!(out.positions()[v], mesh.positions()[v]);
                    assert_eq!(lim[v], mesh.positions()[v]);
                    assert_eq!(nrm[v].norm(), 0.0);
                }
            }
        }
    }
}

/// A single triangle and a single quad: every corner is a valence-2 boundary corner and
/// follows the boundary rule (1/8, 3/4, 1/8), as libigl and CGAL do.
#[test]
fn valence_two_boundary_corners_follow_the_boundary_rule() {
    let tri = PolyMesh::from_triangles(
        vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.0, 1.0, 0.0),
        ],
        &[[0, 1, 2]],
    )
    .unwrap();
    let out = Loop::default().step(&tri).unwrap();
    assert_eq!(out.positions()[0], Point3::new(0.125, 0.125, 0.0));
    assert_eq!(out.positions()[1], Point3::new(0.75, 0.125, 0.0));
    let quad = quad_grid(1, 1);
    let out = CatmullClark.step(&quad).unwrap();
    assert_eq!(out.positions()[0], Point3::new(0.125, 0.125, 0.0));
    assert_eq!(out.num_faces(), 4);
    // Limit: the cubic B-spline of the boundary polygon at its vertex.
    let lim = CatmullClark.limit_positions(&quad).unwrap();
    assert!((lim[0] - Point3::new(1.0 / 6.0, 1.0 / 6.0, 0.0)).norm() < 1e-15);
}

/// The cube with every edge creased: every vertex is a corner (three creases) and stays; edge
/// points stay on the cube's edges, so the crease lines are straight.
#[test]
fn creases_and_corners() {
    let mut positions = Vec::new();
    for i in 0..8 {
        positions.push(Point3::new(
            (i & 1) as f64,
            ((i >> 1) & 1) as f64,
            ((i >> 2) & 1) as f64,
        ));
    }
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut polygons = Polygons::new();
    for q in &quads {
        polygons.push(q);
    }
    let plain = PolyMesh::new(positions.clone(), &polygons).unwrap();
    let creases = plain.edges();
    let cube = PolyMesh::with_creases(positions, &polygons, &creases).unwrap();
    let out = subdivide(&CatmullClark, &cube, 3, DEFAULT_MAX_FACES).unwrap();
    for v in 0..8 {
        assert_eq!(out.positions()[v], cube.positions()[v], "corner {v} moved");
    }
    for [a, b] in out.creases() {
        for v in [a, b] {
            let p = out.positions()[v];
            let on_faces = p.coords.iter().filter(|c| **c == 0.0 || **c == 1.0).count();
            assert!(
                on_faces >= 2,
                "crease vertex {v} at {p} is off the cube's edges"
            );
        }
    }
    assert_eq!(out.creases().len(), 12 * 8);
    // Loop on the octahedron with a crease around the equator: the crease stays in z = 0.
    let oct = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ]
    .map(|c| Point3::new(c[0], c[1], c[2]));
    let faces = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    let equator = [[0, 2], [2, 1], [1, 3], [3, 0]];
    let m =
        PolyMesh::with_creases(oct.to_vec(), &Polygons::from_triangles(&faces), &equator).unwrap();
    let out = subdivide(&Loop::default(), &m, 3, DEFAULT_MAX_FACES).unwrap();
    for [a, b] in out.creases() {
        assert!(out.positions()[a].z.abs() < 1e-15 && out.positions()[b].z.abs() < 1e-15);
    }
    let lim = Loop::default().limit_positions(&out).unwrap();
    for [a, _] in out.creases() {
        assert!(lim[a].z.abs() < 1e-15);
    }
}

#[test]
fn refusals_name_the_element() {
    let p = |n: usize| {
        (0..n)
            .map(|i| Point3::new(i as f64, (i * i) as f64, 0.0))
            .collect::<Vec<_>>()
    };
    let mut polys = Polygons::new();
    polys.push(&[0, 1, 2]);
    polys.push(&[2, 1, 3, 1]);
    assert_eq!(
        PolyMesh::new(p(4), &polys).unwrap_err(),
        SubdivError::RepeatedVertex { face: 1, vertex: 1 }
    );
    let mut polys = Polygons::new();
    polys.push(&[0, 1]);
    assert_eq!(
        PolyMesh::new(p(4), &polys).unwrap_err(),
        SubdivError::FaceTooSmall {
            face: 0,
            corners: 2
        }
    );
    assert_eq!(
        PolyMesh::from_triangles(p(3), &[[0, 1, 7]]).unwrap_err(),
        SubdivError::IndexOutOfRange {
            face: 0,
            index: 7,
            vertices: 3
        }
    );
    let mut bad = p(3);
    bad[1].y = f64::NAN;
    assert_eq!(
        PolyMesh::from_triangles(bad, &[[0, 1, 2]]).unwrap_err(),
        SubdivError::NonFinitePosition { vertex: 1 }
    );
    // The fin: edge (a, b) of the cube's top face has a third triangle (the last face).
    let fin = fixtures::nonmanifold::fin(2);
    let last = fin.polygons.get(fin.polygons.len() - 1).to_vec();
    match PolyMesh::from_raw(&fin).unwrap_err() {
        SubdivError::NonManifoldEdge { a, b, faces } => {
            assert_eq!(faces, 3);
            assert!(last.contains(&a) && last.contains(&b));
        }
        e => panic!("fin: {e}"),
    }
    match PolyMesh::from_raw(&fixtures::nonmanifold::book(4)).unwrap_err() {
        SubdivError::NonManifoldEdge { a, b, faces } => {
            assert_eq!(([a, b], faces), ([0, 1], 4))
        }
        e => panic!("book: {e}"),
    }
    assert_eq!(
        PolyMesh::from_raw(&fixtures::nonmanifold::bowtie(5)).unwrap_err(),
        SubdivError::NonManifoldVertex { vertex: 0 }
    );
    assert!(matches!(
        PolyMesh::from_raw(&fixtures::nonmanifold::flipped_face(8, 5)).unwrap_err(),
        SubdivError::InconsistentOrientation { .. }
    ));
    assert!(matches!(
        PolyMesh::from_raw(&fixtures::nonmanifold::duplicate_face(8, 5)).unwrap_err(),
        SubdivError::NonManifoldEdge { faces: 3, .. }
    ));
    let ico = icosahedron();
    assert_eq!(
        PolyMesh::with_creases(ico.positions().to_vec(), &ico.to_raw().polygons, &[[0, 3]])
            .unwrap_err(),
        SubdivError::CreaseNotAnEdge { a: 0, b: 3 }
    );
    let mut polys = Polygons::new();
    polys.push(&[0, 1, 2]);
    polys.push(&[0, 2, 3, 4]);
    let mixed = PolyMesh::new(p(5), &polys).unwrap();
    assert_eq!(
        Loop::default().step(&mixed).unwrap_err(),
        SubdivError::NotTriangular {
            scheme: "loop",
            face: 1,
            corners: 4
        }
    );
    assert!(CatmullClark.step(&mixed).is_ok());
    assert!(matches!(
        scheme_by_name("butterfly").err(),
        Some(SubdivError::UnknownScheme { .. })
    ));
    assert_eq!(
        scheme_by_name("catmull-clark").unwrap().name(),
        "catmull-clark"
    );
}

/// Faces grow 4× per level: 20 faces, 11 levels = 20·4¹¹ ≈ 8.4·10⁷ > 2²⁴ (Catmull–Clark:
/// 60 corners·4¹⁰ ≈ 6.3·10⁷); refused before any work, and absurd level counts do not
/// overflow.
#[test]
fn output_size_is_bounded() {
    let ico = icosahedron();
    for scheme in all_schemes() {
        match subdivide(scheme.as_ref(), &ico, 11, DEFAULT_MAX_FACES).err() {
            Some(SubdivError::TooLarge {
                levels,
                faces,
                limit,
            }) => {
                assert_eq!((levels, limit), (11, DEFAULT_MAX_FACES));
                assert!(faces > limit);
            }
            e => panic!("{e:?}"),
        }
        assert!(matches!(
            subdivide(scheme.as_ref(), &ico, 200, DEFAULT_MAX_FACES).err(),
            Some(SubdivError::TooLarge {
                faces: u64::MAX,
                ..
            })
        ));
        assert!(subdivide(scheme.as_ref(), &ico, 2, 320).is_ok());
        assert!(
            subdivide(scheme.as_ref(), &ico, 2, 319).is_err() || scheme.name() == "catmull-clark"
        );
    }
}

//! The testbed format: octa.m, fields, names, round trips, errors with their lines.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use meshio::{format_by_name, Location, MeshFormat, RawMesh, ReadError, WriteOptions};
use nalgebra::Matrix3;

fn testbed() -> &'static dyn MeshFormat {
    format_by_name("testbed").expect("testbed")
}

fn read(text: &str) -> Result<RawMesh, ReadError> {
    testbed().read(text.as_bytes())
}

fn err(text: &str) -> ReadError {
    read(text).expect_err("should fail")
}

const OCTA: &str = include_str!("../../../data/octa.m");

#[test]
fn octa_reads_as_is() {
    let m = read(OCTA).expect("octa");
    assert_eq!(m.num_vertices(), 6);
    assert_eq!(m.num_faces(), 8);
    assert!(m.polygons.all_triangles());
    let names = m.vertex_names.as_ref().expect("names");
    assert_eq!(names[0], "px");
    assert_eq!(m.face_names.as_ref().map(|f| f[1].as_str()), Some("PMP"));
    assert_eq!(m.polygons.get(1), &[2, 4, 0]);
    assert_eq!(m.normals.as_ref().map(|n| n[3].x), Some(-1.0));
    assert!(m.shapes.is_none());
}

const FIELDS: &str = "% fields\n\
    a = (Point . (pos . [0,0,0]) (norm . [0,0,2]) (shape . [[1,0,0],[0,2,0],[0,0,0]]) (k . 1) (uv . [[1,2],[3,4]]));\n\
    b = (Point . (pos . [1,0,0]) (norm . [0,0,1]) (shape . [1,1e-12,0, 0,2,0, 0,0,0]) (k . [2]) (uv . [5,6,7,8]));\n\
    c = (Point . (pos . [0,1,0]) (norm . [0,0,1]) (shape . [1,0,0,0,2,0,0,0,0]) (uv . [0,0,0,0]) (k . 3));\n\
    d = (Point . (pos . [1,1,0]) (norm . [0,0,1]) (shape . [1,0,0,0,2,0,0,0,0]) (k . 4) (uv . [0,0,0,0]));\n\
    Q = [a, b, d, c];\n\
    T = [a, b, d];\n\
    scale = 2.5;\n\
    mesh = {Q};\n\
    bounds = [[0, 1], [0, 1]];\n";

#[test]
fn fields_shapes_properties_polygons() {
    let m = read(FIELDS).expect("read");
    assert_eq!(common::polys(&m), vec![vec![0, 1, 3, 2]]);
    assert_eq!(m.normals.as_ref().map(|n| n[0].z), Some(1.0));
    let s = m.shapes.as_ref().expect("shapes");
    assert_eq!(
        s[0],
        Matrix3::new(1.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0)
    );
    assert_eq!(s[1], s[1].transpose());
    assert_eq!(m.properties.get("k"), Some(&vec![1.0, 2.0, 3.0, 4.0]));
    assert_eq!(m.properties.get("uv[3]"), Some(&vec![4.0, 8.0, 0.0, 0.0]));
    assert_eq!(m.mesh_fields.get("scale"), Some(&vec![2.5]));
    assert_eq!(m.mesh_fields.get("bounds"), Some(&vec![0.0, 1.0, 0.0, 1.0]));
    assert!(common::has_note(&m, "1 faces are defined but not listed"));
}

#[test]
fn roundtrip_is_exact() {
    let m = read(FIELDS).expect("read");
    let back = read(
        std::str::from_utf8(&testbed().write(&m, &WriteOptions::new()).expect("w")).expect("utf8"),
    )
    .expect("r");
    assert_eq!(back.positions, m.positions);
    assert_eq!(back.normals, m.normals);
    assert_eq!(back.shapes, m.shapes);
    assert_eq!(back.properties, m.properties);
    assert_eq!(back.vertex_names, m.vertex_names);
    assert_eq!(back.face_names, m.face_names);
    assert_eq!(back.mesh_fields, m.mesh_fields);
    assert_eq!(common::polys(&back), common::polys(&m));
    // Generated names, unit normals.
    let mut cube = common::cube();
    cube.colors = None;
    for n in cube.normals.iter_mut().flatten() {
        *n = n.normalize();
    }
    let back = testbed()
        .read(&testbed().write(&cube, &WriteOptions::new()).expect("w"))
        .expect("r");
    assert_eq!(back.positions, cube.positions);
    assert_eq!(back.normals, cube.normals);
    assert_eq!(back.properties, cube.properties);
    assert_eq!(back.vertex_name(7).as_deref(), Some("v7"));
    assert_eq!(back.face_name(5).as_deref(), Some("f5"));
    assert_eq!(common::polys(&back), common::polys(&cube));
}

/// Names the writer would generate (`v<i>`, `f<k>` by position) are implied, not stored — a
/// million points cost no million strings — and the round trip is still exact: the same
/// names through the accessors, the same bytes written back. One name off the pattern (or
/// out of place, or with a leading zero) and every name of that kind is stored as read.
#[test]
fn positional_names_are_implied_and_round_trip_exactly() {
    let mut cube = common::cube();
    cube.colors = None;
    cube.normals = None;
    let text = testbed().write(&cube, &WriteOptions::new()).expect("w");
    let back = testbed().read(&text).expect("r");
    assert!(back.vertex_names.is_none() && back.implied_vertex_names);
    assert!(back.face_names.is_none() && back.implied_face_names);
    assert!(back.has_vertex_names() && back.has_face_names());
    assert_eq!(back.vertex_name(0).as_deref(), Some("v0"));
    assert_eq!(back.vertex_name(8), None, "the cube has 8 vertices");
    assert_eq!(back.face_name(5).as_deref(), Some("f5"));
    assert_eq!(
        testbed().write(&back, &WriteOptions::new()).expect("w"),
        text,
        "written back byte for byte"
    );
    let text = String::from_utf8(text).expect("utf8");
    for (from, to, vertex) in [
        ("v7 =", "w7 =", true),
        ("v3 =", "v03 =", true),
        ("f2 =", "g2 =", false),
    ] {
        let from_ref = from.trim_end_matches(" =");
        let to_ref = to.trim_end_matches(" =");
        let renamed = text
            .replace(from, to)
            .replace(&format!("{from_ref},"), &format!("{to_ref},"));
        let renamed = renamed
            .replace(&format!("{from_ref}]"), &format!("{to_ref}]"))
            .replace(&format!("{from_ref}}}"), &format!("{to_ref}}}"));
        let m = read(&renamed).unwrap_or_else(|e| panic!("{to}: {e}"));
        if vertex {
            assert!(!m.implied_vertex_names && m.implied_face_names, "{to}");
            let names = m.vertex_names.as_ref().expect("stored");
            assert_eq!(names.len(), 8);
            assert!(names.iter().any(|n| n == to_ref));
        } else {
            assert!(m.implied_vertex_names && !m.implied_face_names, "{to}");
            assert_eq!(m.face_name(2).as_deref(), Some(to_ref));
        }
        assert_eq!(
            testbed().write(&m, &WriteOptions::new()).expect("w"),
            renamed.as_bytes(),
            "{to}: written back byte for byte"
        );
    }
}

#[test]
fn writer_refuses_bad_names() {
    let mut m = common::bare_cube();
    m.vertex_names = Some(
        (0..8)
            .map(|i| {
                if i == 3 {
                    "not a name".into()
                } else {
                    format!("p{i}")
                }
            })
            .collect(),
    );
    assert!(testbed().write(&m, &WriteOptions::new()).is_err());
    m.vertex_names = Some((0..8).map(|_| "p".into()).collect());
    assert!(testbed().write(&m, &WriteOptions::new()).is_err());
}

#[test]
fn errors_name_the_line() {
    let tri = "a = (Point . (pos . [0,0,0]));\nb = (Point . (pos . [1,0,0]));\nc = (Point . (pos . [0,1,0]));\n";
    let at = |text: &str| err(text).location;
    assert_eq!(
        at(&format!("{tri}F = [a, b];\nmesh = {{F}};\n")),
        Location::Line(4)
    );
    assert_eq!(
        at(&format!("{tri}F = [a, b, x];\nmesh = {{F}};\n")),
        Location::Line(4)
    );
    assert!(err(&format!("{tri}F = [a, b, x];\nmesh = {{F}};\n"))
        .message
        .contains("unknown vertex `x`"));
    assert_eq!(
        at(&format!("{tri}F = [a, b, c];\nmesh = {{G}};\n")),
        Location::Line(5)
    );
    assert_eq!(
        at(&format!("{tri}\na = (Point . (pos . [0,0,0]));\n")),
        Location::Line(5)
    );
    assert_eq!(
        at("a = (Point . (pos . [0,0,0]) (norm . [0,0,0]));\n"),
        Location::Line(1)
    );
    assert!(err("a = (Point . (pos . [0,0,0]) (norm . [0,0,0]));\n")
        .message
        .contains("zero normal"));
    assert!(
        err("a = (Point . (pos . [0,0,0]) (shape . [1,2,0,0,1,0,0,0,1]));\n")
            .message
            .contains("not symmetric")
    );
    assert!(err("a = (Point . (pos . [0,0]));\n")
        .message
        .contains("expected 3"));
    assert!(err("a = (Point . (pos . [0,0,0]) (name . \"x\"));\n")
        .message
        .contains("string"));
    assert!(err("\n\na = (Point . (pos . [0,1e999,0]));\n")
        .message
        .contains("not a finite number"));
    assert_eq!(
        at("\n\na = (Point . (pos . [0,1e999,0]));\n"),
        Location::Line(3)
    );
    assert!(err(&format!("{tri}F = [a, b, c];\n"))
        .message
        .contains("no `mesh"));
    assert!(err("a = (Point . (pos . [0,0,0])) b")
        .message
        .contains("`;`"));
    // Partial fields name the point.
    let e = err(
        "a = (Point . (pos . [0,0,0]) (k . 1));\n\nb = (Point . (pos . [1,0,0]));\nmesh = {};\n",
    );
    assert_eq!(e.location, Location::Line(3));
    assert!(e.message.contains("`b`"), "{e}");
    let e = err("a = (Point . (pos . [0,0,0]) (k . 1));\nb = (Point . (pos . [1,0,0]) (k . [1,2]));\nmesh = {};\n");
    assert_eq!(e.location, Location::Line(2));
    let e = err("a = (Point . (pos . [0,0,0]) (norm . [0,0,1]));\nb = (Point . (pos . [1,0,0]));\nmesh = {};\n");
    assert!(e.message.contains("`b` has no `norm`"), "{e}");
    // Nesting is capped.
    let deep = format!(
        "a = (Point . (pos . [0,0,0]) (k . {}1{}));\n",
        "[".repeat(100_000),
        "]".repeat(100_000)
    );
    assert!(err(&deep).message.contains("nested deeper"));
}

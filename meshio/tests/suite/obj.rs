//! OBJ: round trips, corner forms, normals per corner, errors with their lines.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use meshio::{format_by_name, Location, MeshFormat, RawMesh, ReadError, WriteOptions};

fn obj() -> &'static dyn MeshFormat {
    format_by_name("obj").expect("obj")
}

fn read(text: &str) -> Result<RawMesh, ReadError> {
    obj().read(text.as_bytes())
}

fn err(text: &str) -> ReadError {
    read(text).expect_err("should fail")
}

#[test]
fn roundtrip_is_exact() {
    let mut cube = common::cube();
    cube.positions[1].x = 0.1 + 1e-15;
    let bytes = obj().write(&cube, &WriteOptions::new()).expect("write");
    let back = obj().read(&bytes).expect("read");
    assert_eq!(back.positions, cube.positions);
    assert_eq!(back.normals, cube.normals);
    assert!(common::colors_close(
        back.colors.as_deref(),
        cube.colors.as_deref(),
        common::COLOR_FLOAT_ROUND_TRIP
    ));
    assert_eq!(common::polys(&back), common::polys(&cube));
    let bare = common::bare_cube();
    let back = obj()
        .read(&obj().write(&bare, &WriteOptions::new()).expect("w"))
        .expect("r");
    assert_eq!(back.normals, None);
    assert_eq!(common::polys(&back), common::polys(&bare));
}

const SQUARE: &str = "# a square\nmtllib a.mtl\no sq\nv 0 0 0\nv 1 0 0\nv 1 1 0 1.0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ng g1\ns off\nusemtl m\n";

#[test]
fn corner_forms_and_negative_indices() {
    for face in [
        "f 1 2 3 4",
        "f 1/1 2/1 3/1 4/1",
        "f -4 -3 -2 -1",
        "f 1/1/1 2/1/1 3//1 4//-1",
    ] {
        let m = read(&format!("{SQUARE}{face}\n")).expect(face);
        assert_eq!(common::polys(&m), vec![vec![0, 1, 2, 3]], "{face}");
        assert!(
            common::has_note(&m, "ignored 5 statements"),
            "{:?}",
            m.notes
        );
        assert!(common::has_note(&m, "usemtl ×1"), "{:?}", m.notes);
    }
    let m = read(&format!("{SQUARE}f 1//1 2//1 3//1 4//1\n")).expect("normals");
    assert_eq!(m.normals.as_ref().map(|n| n[2].z), Some(1.0));
}

#[test]
fn vertex_colours() {
    let m = read("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n").expect("read");
    assert_eq!(m.colors.as_ref().map(|c| c[1]), Some([0.0, 1.0, 0.0]));
    let m = read("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("read");
    assert_eq!(m.colors, None);
    assert!(common::has_note(&m, "colours given for 1 of 3"));
}

#[test]
fn creases_get_the_normalized_sum() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvn 0 1 0\nf 1//1 2//1 3//1\nf 1//2 4//2 2//2\n";
    let m = read(text).expect("read");
    let n = m.normals.expect("normals");
    let s = std::f64::consts::FRAC_1_SQRT_2;
    assert!((n[0] - nalgebra::Vector3::new(0.0, s, s)).norm() < 1e-15);
    assert_eq!(n[2], nalgebra::Vector3::new(0.0, 0.0, 1.0));
    assert!(
        common::has_note_vec(&m.notes, "2 vertices have corners with different normals"),
        "{:?}",
        m.notes
    );
}

#[test]
fn partial_normals_are_dropped_with_a_note() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 4 2\n";
    let m = read(text).expect("read");
    assert_eq!(m.normals, None);
    assert!(
        common::has_note(&m, "normals given for 1 of 4 vertices: ignored"),
        "{:?}",
        m.notes
    );
}

#[test]
fn errors_name_the_line() {
    let e = err("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    assert_eq!(e.location, Location::Line(4));
    assert!(
        e.message
            .contains("vertex index 4 is out of range (3 vertices read so far)"),
        "{e}"
    );
    assert_eq!(err("v 0 0 0\nv 1 0 0\nf 1 2\n").location, Location::Line(3));
    assert!(err("v 0 0 0\nv 1 0 0\nf 1 2\n")
        .message
        .contains("2 corners"));
    assert_eq!(err("v 0 0 0\nf 0 1 1\n").location, Location::Line(2));
    assert_eq!(err("v 0 0 0\nf -2 1 1\n").location, Location::Line(2));
    assert_eq!(err("\n\nv 0 nan 0\n").location, Location::Line(3));
    assert!(err("v 0 inf 0\n").message.contains("not a finite number"));
    assert!(err("v 0 0\n").message.contains("2 values"));
    assert!(err("vn 0 0 1 1\n").message.contains("expected 3"));
    assert!(err("v 0 0 0\nvn 0 0 1\nf 1//2 1 1\n")
        .message
        .contains("normal index 2"));
    assert!(err("v 0 0 0\nf 1/1/1/1 1 1\n")
        .message
        .contains("more than 3 parts"));
    assert!(err("v 0 0 0\nf a 1 1\n")
        .message
        .contains("not a vertex index"));
}

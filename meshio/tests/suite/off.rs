//! OFF: header variants, colours, round trips, errors with their lines.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use meshio::{format_by_name, Location, MeshFormat, RawMesh, ReadError, WriteOptions};

fn off() -> &'static dyn MeshFormat {
    format_by_name("off").expect("off")
}

fn read(text: &str) -> Result<RawMesh, ReadError> {
    off().read(text.as_bytes())
}

fn err(text: &str) -> ReadError {
    read(text).expect_err("should fail")
}

#[test]
fn roundtrips() {
    // Colours and normals: COFF with sRGB bytes, the normals left out (no reader takes both).
    let cube = common::cube();
    let bytes = off().write(&cube, &WriteOptions::new()).expect("w");
    assert!(bytes.starts_with(b"COFF\n"));
    let back = off().read(&bytes).expect("r");
    assert_eq!(back.positions, cube.positions);
    assert_eq!(back.normals, None);
    assert!(common::colors_close(
        back.colors.as_deref(),
        cube.colors.as_deref(),
        common::COLOR_QUANTUM
    ));
    assert_eq!(common::polys(&back), common::polys(&cube));
    // Normals alone: NOFF.
    let mut normals_only = common::cube();
    normals_only.colors = None;
    let bytes = off().write(&normals_only, &WriteOptions::new()).expect("w");
    assert!(bytes.starts_with(b"NOFF\n"));
    assert_eq!(off().read(&bytes).expect("r").normals, normals_only.normals);
    let bare = common::bare_cube();
    let bytes = off().write(&bare, &WriteOptions::new()).expect("w");
    assert!(bytes.starts_with(b"OFF\n"));
    let back = off().read(&bytes).expect("r");
    assert_eq!(back.positions, bare.positions);
    assert_eq!(back.normals, None);
}

#[test]
fn header_variants() {
    // Counts on the header line, comments, blank lines, a quad, a face colour.
    let m = read("# square\nOFF 4 1 0\n\n0 0 0\n1 0 0 # corner\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n")
        .expect("OFF");
    assert_eq!(common::polys(&m), vec![vec![0, 1, 2, 3]]);
    assert!(common::has_note(&m, "colours of 1 faces ignored"));
    let m = read("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n").expect("NOFF");
    assert_eq!(m.normals.as_ref().map(|n| n[1].z), Some(1.0));
    // Integer colours are 0–255, with alpha.
    let m = read("COFF\n3 1 0\n0 0 0 255 0 51 255\n1 0 0 0 0 0 255\n0 1 0 0 0 0 255\n3 0 1 2\n")
        .expect("COFF");
    // sRGB bytes, decoded to linear.
    let want = [255u8, 0, 51].map(meshio::srgb::decode_byte);
    assert_eq!(m.colors.as_ref().map(|c| c[0]), Some(want));
    assert!(common::has_note(&m, "alpha of 3"));
    // Float colours are 0–1.
    let m = read(
        "CNOFF\n3 1 0\n0 0 0 0 0 1 1.0 0.5 0.25\n1 0 0 0 0 1 0 0 0.\n0 1 0 0 0 1 0 0 0.\n3 0 1 2\n",
    )
    .expect("CNOFF");
    let want = [1.0f32, 0.5, 0.25].map(meshio::srgb::decode);
    assert_eq!(m.colors.as_ref().map(|c| c[0]), Some(want));
    assert_eq!(m.normals.as_ref().map(|n| n[0].z), Some(1.0));
}

#[test]
fn errors_name_the_line() {
    let e = err("STOFF\n");
    assert_eq!(e.location, Location::Line(1));
    let e = err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
    assert_eq!(e.location, Location::Line(6));
    assert!(
        e.message.contains("face 0: vertex index 3 is out of range"),
        "{e}"
    );
    let e = err("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
    assert!(e.message.contains("2 corners"));
    let e = err("OFF\n3 1 0\n0 0 0\n1 0\n");
    assert_eq!(e.location, Location::Line(4));
    let e = err("OFF\n3 1 0\n0 0 0\n1 0 nan\n");
    assert_eq!(e.location, Location::Line(4));
    assert!(e.message.contains("not a finite number"));
    let e = err("OFF\n3 1 0\n0 0 0\n");
    assert!(e.message.contains("1 of 3 vertices"), "{e}");
    let e = err("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    assert!(e.message.contains("1 of 2 faces"), "{e}");
    let e = err("OFF\n3\n");
    assert_eq!(e.location, Location::Line(2));
    // A huge count with a small file: an error, not an allocation of the count.
    let e = err("OFF\n4000000000 4000000000 0\n0 0 0\n");
    assert!(e.message.contains("end of file"));
}

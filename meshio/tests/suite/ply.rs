//! PLY: round trips, header variants, both byte orders, errors with their locations.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use meshio::{format_by_name, Location, MeshFormat, RawMesh, ReadError, WriteOptions};

fn ply() -> &'static dyn MeshFormat {
    format_by_name("ply").expect("ply")
}

fn read(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    ply().read(bytes)
}

fn roundtrip(mesh: &RawMesh, opts: WriteOptions) -> RawMesh {
    let bytes = ply().write(mesh, &opts).expect("write");
    read(&bytes).expect("read back")
}

fn check_cube(back: &RawMesh) {
    let cube = common::cube();
    assert_eq!(back.positions, cube.positions);
    assert_eq!(back.normals, cube.normals);
    assert_eq!(common::polys(back), common::polys(&cube));
    assert_eq!(back.properties, cube.properties);
    let (c0, c1) = (
        back.colors.as_ref().expect("colours"),
        cube.colors.as_ref().expect("c"),
    );
    for (a, b) in c0.iter().zip(c1) {
        for k in 0..3 {
            assert!(
                (a[k] - b[k]).abs() <= common::COLOR_FLOAT_ROUND_TRIP,
                "{a:?} {b:?}"
            );
        }
    }
}

#[test]
fn binary_roundtrip_keeps_everything_and_quads() {
    check_cube(&roundtrip(&common::cube(), WriteOptions::new()));
}

#[test]
fn ascii_roundtrip() {
    check_cube(&roundtrip(&common::cube(), WriteOptions::new().ascii()));
}

#[test]
fn double_precision_roundtrip_is_exact() {
    let mut m = common::grid(5);
    m.positions[3].x = 0.1 + 1e-12;
    let back = roundtrip(&m, WriteOptions::new().double_precision());
    assert_eq!(back.positions, m.positions);
    let back = roundtrip(&m, WriteOptions::new().double_precision().ascii());
    assert_eq!(back.positions, m.positions);
}

#[test]
fn float_positions_round_to_f32() {
    let m = common::grid(5);
    let back = roundtrip(&m, WriteOptions::new());
    for (a, b) in back.positions.iter().zip(&m.positions) {
        assert_eq!(a.map(|x| x as f32), b.map(|x| x as f32));
    }
}

/// A binary file built by hand in the given byte order, with comments, obj_info, an int8
/// property, a list property on vertices, float colours, `vertex_index`, an extra face property
/// and an `edge` element with a list of ends and a crease value (5: sharp).
fn handmade(big: bool) -> Vec<u8> {
    let order = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let header = format!(
        "ply\r\nformat {order} 1.0\r\ncomment made by hand\r\nobj_info nothing\r\n\
         element vertex 4\r\nproperty float32 x\r\nproperty double y\r\nproperty int16 z\r\n\
         property char flag\r\nproperty list uint8 float tex\r\nproperty float red\r\n\
         property float green\r\nproperty float blue\r\n\
         element face 2\r\nproperty uchar material\r\nproperty list ushort uint vertex_index\r\n\
         element edge 1\r\nproperty list uchar int ends\r\nproperty int crease\r\nend_header\r\n"
    );
    let mut b = header.into_bytes();
    let put =
        |b: &mut Vec<u8>, le: &[u8], be: &[u8]| b.extend_from_slice(if big { be } else { le });
    for i in 0..4u8 {
        let x = i as f32 * 0.5;
        put(&mut b, &x.to_le_bytes(), &x.to_be_bytes());
        let y = -(i as f64);
        put(&mut b, &y.to_le_bytes(), &y.to_be_bytes());
        let z = 100i16 * i as i16;
        put(&mut b, &z.to_le_bytes(), &z.to_be_bytes());
        b.push((-(i as i8)) as u8);
        b.push(2); // two tex floats
        for t in [1.0f32, 2.0] {
            put(&mut b, &t.to_le_bytes(), &t.to_be_bytes());
        }
        for c in [0.25f32, 0.5, 1.0] {
            put(&mut b, &c.to_le_bytes(), &c.to_be_bytes());
        }
    }
    for (mat, face) in [(7u8, vec![0u32, 1, 2, 3]), (9, vec![3, 2, 1])] {
        b.push(mat);
        let n = face.len() as u16;
        put(&mut b, &n.to_le_bytes(), &n.to_be_bytes());
        for i in face {
            put(&mut b, &i.to_le_bytes(), &i.to_be_bytes());
        }
    }
    b.push(2);
    for e in [0i32, 1, 5] {
        // 2 ends, then crease
        put(&mut b, &e.to_le_bytes(), &e.to_be_bytes());
    }
    b
}

fn check_handmade(m: &RawMesh) {
    assert_eq!(m.num_vertices(), 4);
    assert_eq!(m.positions[3].coords.as_slice(), &[1.5, -3.0, 300.0]);
    assert_eq!(m.properties.get("flag"), Some(&vec![0.0, -1.0, -2.0, -3.0]));
    // Colours are sRGB-encoded in a PLY: decoded to linear.
    let want = [0.25f32, 0.5, 1.0].map(meshio::srgb::decode);
    assert_eq!(m.colors.as_ref().map(|c| c[0]), Some(want));
    assert_eq!(common::polys(m), vec![vec![0, 1, 2, 3], vec![3, 2, 1]]);
    // The edge 0–1 with crease 5 is read, not skipped.
    assert_eq!(m.crease_edges, vec![[0, 1]]);
    assert!(
        common::has_note(
            m,
            "1 of 1 edges marked sharp (element edge, property crease)"
        ),
        "{:?}",
        m.notes
    );
    assert!(!common::has_note(m, "skipped elements"), "{:?}", m.notes);
    assert!(common::has_note(m, "tex"), "{:?}", m.notes);
}

#[test]
fn handmade_little_endian() {
    check_handmade(&read(&handmade(false)).expect("read"));
}

#[test]
fn handmade_big_endian() {
    check_handmade(&read(&handmade(true)).expect("read"));
}

#[test]
fn ascii_header_variants_and_uchar_colours() {
    let text = "ply\nformat ascii 1.0\ncomment c\nelement vertex 3\nproperty float x\n\
                property float y\nproperty float z\nproperty uchar red\nproperty uchar green\n\
                property uchar blue\nproperty uchar alpha\nproperty float nx\nproperty float ny\n\
                property float nz\nelement face 1\nproperty list uchar int vertex_indices\n\
                end_header\n0 0 0 255 0 51 128 0 0 1\n1 0 0 0 0 0 0 0 0 1\n0 1 0 0 0 0 0 0 0 1\n\
                3 0 1 2\n";
    let m = read(text.as_bytes()).expect("read");
    // Bytes 255, 0, 51 are sRGB 1, 0, 0.2: decoded to linear.
    let want = [255u8, 0, 51].map(meshio::srgb::decode_byte);
    assert_eq!(m.colors.as_ref().map(|c| c[0]), Some(want));
    assert_eq!(m.properties.get("alpha"), Some(&vec![128.0, 0.0, 0.0]));
    assert_eq!(m.normals.as_ref().map(|n| n[2].z), Some(1.0));
    assert_eq!(m.num_faces(), 1);
}

#[test]
fn point_cloud_without_faces() {
    let text = "ply\nformat ascii 1.0\nelement vertex 1\nproperty double x\nproperty double y\nproperty double z\nend_header\n1 2 3\n";
    let m = read(text.as_bytes()).expect("read");
    assert_eq!(m.num_vertices(), 1);
    assert_eq!(m.num_faces(), 0);
}

fn err(bytes: &[u8]) -> ReadError {
    read(bytes).expect_err("should fail")
}

fn at(element: &str, index: usize, property: Option<&str>) -> Location {
    Location::Element {
        element: element.into(),
        index,
        property: property.map(Into::into),
    }
}

#[test]
fn truncated_binary_names_element_and_index() {
    let bytes = ply()
        .write(&common::cube(), &WriteOptions::new())
        .expect("write");
    // Cut inside the faces: each face is 1 + 4·4 = 17 bytes.
    let e = err(&bytes[..bytes.len() - 17 - 3]);
    assert_eq!(e.location, at("face", 4, Some("vertex_indices")));
    assert!(e.message.contains("unexpected end of file"));
    // Cut inside the vertices.
    let header_len = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .expect("header")
        + 11;
    let e = err(&bytes[..header_len + 5]);
    assert_eq!(e.location, at("vertex", 0, Some("y")));
    // A big count in the header with few bytes: an error, not a huge allocation.
    let text =
        String::from_utf8_lossy(&bytes[..header_len]).replace("vertex 8", "vertex 4000000000");
    let mut huge = text.into_bytes();
    huge.extend_from_slice(&bytes[header_len..]);
    assert!(matches!(err(&huge).location, Location::Element { .. }));
}

#[test]
fn header_errors() {
    assert_eq!(
        err(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty flot x\nend_header\n").location,
        Location::Header
    );
    assert!(
        err(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty flot x\nend_header\n")
            .message
            .contains("line 4: unknown type `flot`")
    );
    assert!(err(b"ply\nformat ascii 1.0\n")
        .message
        .contains("end_header"));
    assert!(err(b"ply\nformat ebcdic 1.0\nend_header\n")
        .message
        .contains("ebcdic"));
    assert!(err(b"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n").message.contains("no `vertex` element"));
    assert!(
        err(b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n")
            .message
            .contains("x, y and z")
    );
}

const TRI_HEADER: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

#[test]
fn body_errors_name_the_record() {
    let e = err(format!("{TRI_HEADER}0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n").as_bytes());
    assert_eq!(e.location, at("vertex", 1, Some("z")));
    assert!(e.message.contains("not finite"), "{e}");
    let e = err(format!("{TRI_HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n").as_bytes());
    assert_eq!(e.location, at("face", 0, Some("vertex_indices")));
    assert!(e.message.contains("out of range"), "{e}");
    let e = err(format!("{TRI_HEADER}0 0 0\n1 0 0\n0 1 0\n2 0 1\n").as_bytes());
    assert!(e.message.contains("2 corners"), "{e}");
    let e = err(format!("{TRI_HEADER}0 0 0\n1 0 zero\n").as_bytes());
    assert_eq!(e.location, at("vertex", 1, Some("z")));
    assert!(e.message.contains("not a number"), "{e}");
}

#[test]
fn binary_nan_is_refused() {
    let mut m = common::bare_cube();
    let mut bytes = ply().write(&m, &WriteOptions::new()).expect("write");
    let header_len = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .expect("h")
        + 11;
    bytes[header_len + 12 * 2 + 4..header_len + 12 * 2 + 8]
        .copy_from_slice(&f32::NAN.to_le_bytes());
    let e = err(&bytes);
    assert_eq!(e.location, at("vertex", 2, Some("y")));
    m.positions[0].x = f64::NAN;
    assert!(ply().write(&m, &WriteOptions::new()).is_err());
}

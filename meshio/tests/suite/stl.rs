//! STL: ASCII and binary, welding, the `solid` header on binary files, errors.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use meshio::{format_by_name, Location, MeshFormat, RawMesh, ReadError, WriteOptions};

fn stl() -> &'static dyn MeshFormat {
    format_by_name("stl").expect("stl")
}

fn read(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    stl().read(bytes)
}

#[test]
fn binary_and_ascii_roundtrips_weld_back_to_the_cube() {
    let cube = common::bare_cube();
    for opts in [WriteOptions::new(), WriteOptions::new().ascii()] {
        let bytes = stl().write(&cube, &opts).expect("write");
        let m = read(&bytes).expect("read");
        // 6 quads → 12 triangles, 36 corners welded into the 8 vertices in first-seen order.
        assert_eq!(m.num_faces(), 12);
        assert_eq!(m.num_vertices(), 8);
        assert!(m.polygons.all_triangles());
        assert!(
            common::has_note(&m, "welded 36 corners into 8 vertices (28 corners merged"),
            "{:?}",
            m.notes
        );
        assert!(common::has_note(&m, "facet normals ignored"));
        // Same geometry: every triangle of the fan maps to the same positions.
        let mut fans = Vec::new();
        for p in cube.polygons.iter() {
            for k in 1..p.len() - 1 {
                fans.push([p[0], p[k], p[k + 1]].map(|i| cube.positions[i]));
            }
        }
        let got: Vec<_> = m
            .polygons
            .iter()
            .map(|t| [t[0], t[1], t[2]].map(|i| m.positions[i]))
            .collect();
        assert_eq!(got, fans);
    }
}

#[test]
fn binary_starting_with_solid_is_binary() {
    let mut bytes = stl()
        .write(&common::bare_cube(), &WriteOptions::new())
        .expect("write");
    bytes[..5].copy_from_slice(b"solid");
    let m = read(&bytes).expect("read");
    assert_eq!(m.num_faces(), 12);
    assert!(stl().sniff(&bytes));
}

#[test]
fn negative_zero_is_welded_with_zero() {
    let text = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n\
                facet normal 0 0 1\nouter loop\nvertex -0.0 0 0\nvertex 0 1 0\nvertex -1 0 -0\nendloop\nendfacet\nendsolid t\n";
    let m = read(text.as_bytes()).expect("read");
    assert_eq!(m.num_vertices(), 4);
    assert_eq!(common::polys(&m), vec![vec![0, 1, 2], vec![0, 2, 3]]);
    assert!(m.positions[3].z.is_sign_positive());
}

#[test]
fn ascii_polygon_loops_are_kept() {
    let text = "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n";
    let m = read(text.as_bytes()).expect("read");
    assert_eq!(common::polys(&m), vec![vec![0, 1, 2, 3]]);
}

#[test]
fn errors() {
    let bytes = stl()
        .write(&common::bare_cube(), &WriteOptions::new())
        .expect("write");
    // Truncated binary: names the first incomplete facet.
    let e = read(&bytes[..84 + 50 * 5 + 20]).expect_err("truncated");
    assert_eq!(
        e.location,
        Location::Element {
            element: "facet".into(),
            index: 5,
            property: None
        }
    );
    // Too short for a header.
    assert_eq!(
        read(b"\0\0\0").expect_err("short").location,
        Location::Header
    );
    // NaN in binary.
    let mut nan = bytes.clone();
    nan[84 + 50 * 2 + 12 + 4..84 + 50 * 2 + 12 + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    let e = read(&nan).expect_err("nan");
    assert_eq!(
        e.location,
        Location::Element {
            element: "facet".into(),
            index: 2,
            property: None
        }
    );
    // Trailing bytes: read, with a note.
    let mut long = bytes.clone();
    long.extend_from_slice(&[1, 2, 3]);
    assert!(common::has_note(
        &read(&long).expect("long"),
        "3 bytes after the last facet"
    ));
    // ASCII errors name the line.
    let e =
        read(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n").expect_err("short vertex");
    assert_eq!(e.location, Location::Line(4));
    let e = read(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nendloop\n")
        .expect_err("2 corners");
    assert_eq!(e.location, Location::Line(6));
    let e = read(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 inf\n").expect_err("inf");
    assert!(e.message.contains("not a finite number"));
    let e = read(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n").expect_err("eof");
    assert!(e.message.contains("end of file"));
}

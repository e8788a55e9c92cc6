//! PLY: crease edges in an `edge` element, read and written.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use meshio::{format_by_name, Location, MeshFormat, RawMesh, ReadError, WriteOptions};

fn ply() -> &'static dyn MeshFormat {
    format_by_name("ply").expect("ply")
}

fn read(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    ply().read(bytes)
}

/// The cube's 12 edges (vertex `i` at `(i & 1, i >> 1 & 1, i >> 2 & 1)`): the pairs that differ
/// in one bit.
fn cube_edges() -> Vec<[usize; 2]> {
    let mut e = Vec::new();
    for a in 0..8usize {
        for b in a + 1..8 {
            if (a ^ b).count_ones() == 1 {
                e.push([a, b]);
            }
        }
    }
    e
}

fn creased_cube() -> RawMesh {
    let mut m = common::cube();
    m.crease_edges = cube_edges();
    m
}

/// The bytes after `end_header\n`.
fn body(bytes: &[u8]) -> &[u8] {
    let at = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .expect("header")
        + 11;
    &bytes[at..]
}

#[test]
fn crease_edges_round_trip_in_every_encoding() {
    let m = creased_cube();
    for opts in [
        WriteOptions::new(),
        WriteOptions::new().ascii(),
        WriteOptions::new().double_precision(),
    ] {
        let bytes = ply().write(&m, &opts).expect("write");
        let back = read(&bytes).expect("read back");
        assert_eq!(back.crease_edges, m.crease_edges, "{opts:?}");
        assert_eq!(back.positions, m.positions);
        assert_eq!(common::polys(&back), common::polys(&m));
        assert!(
            common::has_note(
                &back,
                "12 of 12 edges marked sharp (element edge, property crease)"
            ),
            "{:?}",
            back.notes
        );
    }
}

#[test]
fn creases_add_an_edge_element_and_change_nothing_else() {
    let with = creased_cube();
    let without = common::cube();
    for opts in [WriteOptions::new(), WriteOptions::new().ascii()] {
        let a = ply().write(&with, &opts).expect("write");
        let b = ply().write(&without, &opts).expect("write");
        let header_a = String::from_utf8_lossy(&a[..a.len() - body(&a).len()]).into_owned();
        let header_b = String::from_utf8_lossy(&b[..b.len() - body(&b).len()]).into_owned();
        assert!(!header_b.contains("element edge"), "{header_b}");
        // The header gains the element after the faces, and nothing else.
        assert_eq!(
            header_a,
            header_b.replace(
                "end_header\n",
                "element edge 12\nproperty int vertex1\nproperty int vertex2\n\
                 property uchar crease\nend_header\n"
            )
        );
        // The body gains the twelve records after the faces.
        let (body_a, body_b) = (body(&a), body(&b));
        assert_eq!(&body_a[..body_b.len()], body_b);
        let records = &body_a[body_b.len()..];
        if opts.ascii {
            let text = String::from_utf8_lossy(records);
            let lines: Vec<&str> = text.lines().collect();
            assert_eq!(lines.len(), 12);
            assert_eq!(lines[0], "0 1 1");
            assert_eq!(lines[11], "6 7 1");
        } else {
            // int, int, uchar: 9 bytes a record.
            assert_eq!(records.len(), 9 * 12);
            assert_eq!(&records[..9], &[0, 0, 0, 0, 1, 0, 0, 0, 1]);
        }
    }
}

#[test]
fn obj_creases_survive_a_ply_round_trip() {
    // The cube with one normal per face: its 12 edges are sharp (the OBJ reader), and written
    // to PLY and read back they still are.
    let mut text = String::new();
    for i in 0..8 {
        text.push_str(&format!("v {} {} {}\n", i & 1, (i >> 1) & 1, (i >> 2) & 1));
    }
    text.push_str("vn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 0 1 0\nvn -1 0 0\nvn 1 0 0\n");
    for (k, q) in [
        [1, 3, 4, 2],
        [5, 6, 8, 7],
        [1, 2, 6, 5],
        [3, 7, 8, 4],
        [1, 5, 7, 3],
        [2, 4, 8, 6],
    ]
    .iter()
    .enumerate()
    {
        let n = k + 1;
        text.push_str(&format!(
            "f {}//{n} {}//{n} {}//{n} {}//{n}\n",
            q[0], q[1], q[2], q[3]
        ));
    }
    let obj = format_by_name("obj").expect("obj");
    let m = obj.read(text.as_bytes()).expect("obj");
    assert_eq!(m.crease_edges, cube_edges());
    let back = read(&ply().write(&m, &WriteOptions::new()).expect("write")).expect("read");
    assert_eq!(back.crease_edges, cube_edges());
}

const HEADER: &str =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                      property float z\nelement face 2\nproperty list uchar int vertex_indices\n";
const BODY: &str = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

fn with_edges(edge_header: &str, records: &str) -> Vec<u8> {
    format!("{HEADER}{edge_header}end_header\n{BODY}{records}").into_bytes()
}

#[test]
fn scalar_ends_and_a_sharp_flag_are_read_sorted_and_deduplicated() {
    let bytes = with_edges(
        "element edge 5\nproperty uchar flags\nproperty uint vertex2\nproperty short vertex1\n\
         property float sharp\n",
        // flags, vertex2, vertex1, sharp: 2–0 sharp, 3–2 not, 0–2 again, 1–2 sharp (0.5).
        "7 0 2 1\n7 2 3 0\n7 2 0 1\n7 2 1 0.5\n7 3 0 -1\n",
    );
    let m = read(&bytes).expect("read");
    assert_eq!(m.crease_edges, vec![[0, 2], [0, 3], [1, 2]]);
    assert!(
        common::has_note(
            &m,
            "3 of 5 edges marked sharp (element edge, property sharp)"
        ),
        "{:?}",
        m.notes
    );
}

#[test]
fn an_edge_element_without_a_crease_property_is_skipped() {
    let bytes = with_edges(
        "element edge 1\nproperty int vertex1\nproperty int vertex2\n",
        "0 2\n",
    );
    let m = read(&bytes).expect("read");
    assert!(m.crease_edges.is_empty());
    assert!(
        common::has_note(&m, "skipped elements: edge (1)"),
        "{:?}",
        m.notes
    );
}

#[test]
fn bad_edges_name_the_record() {
    let at = |index: usize, property: Option<&str>| Location::Element {
        element: "edge".into(),
        index,
        property: property.map(Into::into),
    };
    let scalar =
        "element edge 2\nproperty int vertex1\nproperty int vertex2\nproperty uchar crease\n";
    let e = read(&with_edges(scalar, "0 1 1\n0 4 1\n")).expect_err("range");
    assert_eq!(e.location, at(1, Some("vertex2")));
    assert!(
        e.message
            .contains("vertex index 4 is out of range (4 vertices)"),
        "{e}"
    );
    let e = read(&with_edges(scalar, "0 1 1\n2 2 0\n")).expect_err("loop");
    assert_eq!(e.location, at(1, None));
    assert!(e.message.contains("edge joins vertex 2 to itself"), "{e}");
    let e = read(&with_edges(scalar, "0 1 nan\n")).expect_err("nan");
    assert_eq!(e.location, at(0, Some("crease")));
    let list = "element edge 1\nproperty list uchar int ends\nproperty uchar crease\n";
    let e = read(&with_edges(list, "3 0 1 2 1\n")).expect_err("three ends");
    assert_eq!(e.location, at(0, Some("ends")));
    assert!(e.message.contains("edge has 3 ends, 2 needed"), "{e}");
    let float =
        "element edge 1\nproperty float vertex1\nproperty float vertex2\nproperty uchar crease\n";
    let e = read(&with_edges(float, "0 1 1\n")).expect_err("float");
    assert_eq!(e.location, Location::Header);
    assert!(e.message.contains("float index type"), "{e}");
    // Truncated: the second record is missing.
    let e = read(&with_edges(scalar, "0 1 1\n")).expect_err("eof");
    assert_eq!(e.location, at(1, Some("vertex1")));
}

#[test]
fn the_writer_refuses_a_crease_that_is_no_pair_of_vertices() {
    for bad in [[0, 8], [3, 3]] {
        let mut m = common::cube();
        m.crease_edges = vec![[0, 1], bad];
        let e = ply()
            .write(&m, &WriteOptions::new())
            .expect_err("bad crease");
        assert!(e.to_string().contains("crease edge 1"), "{e}");
    }
}

//! OBJ: sharp edges from per-corner normals and smoothing groups.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use std::fmt::Write as _;

use crate::common;

use meshio::obj::NORMAL_AGREEMENT;
use meshio::{format_by_name, Location, MeshFormat, RawMesh, ReadError, WriteOptions};

fn obj() -> &'static dyn MeshFormat {
    format_by_name("obj").expect("obj")
}

fn read(text: &str) -> RawMesh {
    obj().read(text.as_bytes()).expect(text)
}

fn err(text: &str) -> ReadError {
    obj().read(text.as_bytes()).expect_err(text)
}

/// The unit cube's quads (vertex `i` at `(i & 1, i >> 1 & 1, i >> 2 & 1)`), outward.
const QUADS: [[usize; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

/// The outward normal of each quad.
const FACE_NORMALS: [[i32; 3]; 6] = [
    [0, 0, -1],
    [0, 0, 1],
    [0, -1, 0],
    [0, 1, 0],
    [-1, 0, 0],
    [1, 0, 0],
];

/// The cube as OBJ: 8 positions, the 6 face normals and `f a//n b//n c//n d//n` quads when
/// `face_normals`, plain `f a b c d` otherwise; `s_lines[k]` is written before quad `k`.
fn cube(face_normals: bool, s_lines: [Option<&str>; 6]) -> String {
    let mut t = String::new();
    for i in 0..8 {
        let _ = writeln!(t, "v {} {} {}", i & 1, (i >> 1) & 1, (i >> 2) & 1);
    }
    if face_normals {
        for [x, y, z] in FACE_NORMALS {
            let _ = writeln!(t, "vn {x} {y} {z}");
        }
    }
    for (k, q) in QUADS.iter().enumerate() {
        if let Some(s) = s_lines[k] {
            let _ = writeln!(t, "s {s}");
        }
        t.push('f');
        for &v in q {
            if face_normals {
                let _ = write!(t, " {}//{}", v + 1, k + 1);
            } else {
                let _ = write!(t, " {}", v + 1);
            }
        }
        t.push('\n');
    }
    t
}

/// The cube's 12 edges: the vertex pairs differing in one coordinate (one bit); none of the
/// quads' diagonals (two bits).
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

#[test]
fn face_normals_mark_the_twelve_cube_edges_and_no_diagonal() {
    let m = read(&cube(true, [None; 6]));
    assert_eq!(m.crease_edges.len(), 12);
    assert_eq!(m.crease_edges, cube_edges());
    assert!(
        common::has_note(
            &m,
            "12 edges marked sharp by per-corner normals, 0 by smoothing groups (12 in all)"
        ),
        "{:?}",
        m.notes
    );
    // The polygons stay quads: a diagonal such as 0–3 is no side of one.
    assert!(!m.crease_edges.contains(&[0, 3]));
    assert_eq!(m.polygons.len(), 6);
}

#[test]
fn one_smoothing_group_marks_nothing() {
    let m = read(&cube(false, [Some("1"), None, None, None, None, None]));
    assert_eq!(m.crease_edges, Vec::<[usize; 2]>::new());
    assert!(!common::has_note(&m, "marked sharp"), "{:?}", m.notes);
    // `s` is read, not ignored.
    assert!(!common::has_note(&m, "ignored"), "{:?}", m.notes);
}

#[test]
fn a_group_per_face_marks_the_twelve() {
    let m = read(&cube(
        false,
        [
            Some("1"),
            Some("2"),
            Some("3"),
            Some("4"),
            Some("5"),
            Some("4294967295"),
        ],
    ));
    assert_eq!(m.crease_edges, cube_edges());
    assert!(
        common::has_note(
            &m,
            "0 edges marked sharp by per-corner normals, 12 by smoothing groups (12 in all)"
        ),
        "{:?}",
        m.notes
    );
}

#[test]
fn no_group_marks_every_shared_side() {
    for off in ["off", "0", "OFF"] {
        let m = read(&cube(false, [Some(off), None, None, None, None, None]));
        assert_eq!(m.crease_edges, cube_edges(), "s {off}");
    }
    // Group 1 then `s off` for the last quad: the quad's four sides only.
    let m = read(&cube(
        false,
        [Some("1"), None, None, None, None, Some("off")],
    ));
    assert_eq!(m.crease_edges, vec![[1, 3], [1, 5], [3, 7], [5, 7]]);
}

#[test]
fn polygons_before_the_first_s_line_are_in_no_group() {
    let m = read(&cube(false, [None, Some("1"), None, None, None, None]));
    // Quad 0 (0 2 3 1) is in no group: its four sides, and nothing else.
    assert_eq!(m.crease_edges, vec![[0, 1], [0, 2], [1, 3], [2, 3]]);
}

#[test]
fn a_file_without_s_lines_or_normals_says_nothing() {
    let m = read(&cube(false, [None; 6]));
    assert!(m.crease_edges.is_empty());
}

/// Two unit squares side by side sharing the side 2–5 (file numbering 1-based: `v 2`, `v 5`),
/// the left one with normal `vn 1`, the right one with `vn 2`.
fn two_squares(n1: [f64; 3], n2: [f64; 3]) -> String {
    format!(
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n\
         vn {:?} {:?} {:?}\nvn {:?} {:?} {:?}\n\
         f 1//1 2//1 5//1 4//1\nf 2//2 3//2 6//2 5//2\n",
        n1[0], n1[1], n1[2], n2[0], n2[1], n2[2]
    )
}

#[test]
fn normals_within_the_agreement_angle_are_not_creases() {
    // 1e-6 rad apart (an exporter's rounding), in different `vn` lines: the same surface.
    let t = 1e-6f64;
    let m = read(&two_squares([0.0, 0.0, 1.0], [t.sin(), 0.0, t.cos()]));
    assert!(m.crease_edges.is_empty(), "{:?}", m.crease_edges);
    // The same direction at another length agrees too.
    let m = read(&two_squares([0.0, 0.0, 1.0], [0.0, 0.0, 2.5]));
    assert!(m.crease_edges.is_empty());
    // Twice the agreement angle apart: the shared side (file vertices 2 and 5) is a crease,
    // the six boundary sides are not.
    let t = 2.0 * NORMAL_AGREEMENT;
    let m = read(&two_squares([0.0, 0.0, 1.0], [t.sin(), 0.0, t.cos()]));
    assert_eq!(m.crease_edges, vec![[1, 4]]);
    assert!(
        common::has_note(&m, "1 edges marked sharp by per-corner normals"),
        "{:?}",
        m.notes
    );
}

#[test]
fn a_disagreement_at_one_end_is_enough() {
    // The squares share normal 1 at vertex 2 and differ (1 against 2) at vertex 5.
    let text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n\
                vn 0 0 1\nvn 0 0.6 0.8\n\
                f 1//1 2//1 5//1 4//1\nf 2//1 3//2 6//2 5//2\n";
    assert_eq!(read(text).crease_edges, vec![[1, 4]]);
}

#[test]
fn a_corner_without_a_normal_says_nothing_there() {
    // The right square has no normal at vertex 5, and the same normal as the left at vertex 2.
    let text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\n\
                vn 0 0 1\nvn 0 0.6 0.8\n\
                f 1//1 2//1 5//1 4//1\nf 2//1 3//2 6//2 5\n";
    let m = read(text);
    assert!(m.crease_edges.is_empty(), "{:?}", m.crease_edges);
}

#[test]
fn normals_and_groups_combine_by_union() {
    // A strip of four unit squares, bottom vertices 1–5, top 6–10; square k (0-based) is
    // k+1, k+2, k+7, k+6. Shared sides: A = 2–7, B = 3–8, C = 4–9 (1-based).
    // Normals: squares 0 and 3 use vn 1, squares 1 and 2 use vn 2 (36.87° apart): A and C.
    // Groups: 1, 1, 2, 3: B and C. The union: A, B, C.
    let mut t = String::new();
    for y in 0..2 {
        for x in 0..5 {
            let _ = writeln!(t, "v {x} {y} 0");
        }
    }
    t.push_str("vn 0 0 1\nvn 0 0.6 0.8\n");
    for (k, (n, s)) in [(1, "1"), (2, "1"), (2, "2"), (1, "3")].iter().enumerate() {
        let _ = writeln!(t, "s {s}");
        let _ = writeln!(
            t,
            "f {a}//{n} {b}//{n} {c}//{n} {d}//{n}",
            a = k + 1,
            b = k + 2,
            c = k + 7,
            d = k + 6
        );
    }
    let m = read(&t);
    assert_eq!(m.crease_edges, vec![[1, 6], [2, 7], [3, 8]]);
    assert!(
        common::has_note(
            &m,
            "2 edges marked sharp by per-corner normals, 2 by smoothing groups (3 in all)"
        ),
        "{:?}",
        m.notes
    );
}

#[test]
fn bad_s_lines_name_the_line() {
    let cube = cube(false, [None; 6]);
    for (bad, what) in [
        ("s", "one argument"),
        ("s 1 2", "one argument"),
        ("s x", "`s x`"),
        ("s -1", "`s -1`"),
        ("s 4294967296", "32 bits"),
    ] {
        let e = err(&format!("{cube}{bad}\n"));
        assert_eq!(e.location, Location::Line(15), "{bad}");
        assert!(e.message.contains(what), "{bad}: {e}");
    }
}

#[test]
fn the_obj_writer_does_not_write_creases() {
    let m = read(&cube(true, [None; 6]));
    assert_eq!(m.crease_edges.len(), 12);
    let mut bare = m.clone();
    bare.crease_edges.clear();
    let opts = WriteOptions::new();
    assert_eq!(
        obj().write(&m, &opts).expect("write"),
        obj().write(&bare, &opts).expect("write")
    );
}

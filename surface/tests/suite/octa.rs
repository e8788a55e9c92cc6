//! The octahedron of the testbed's Figure 2 (`data/octa.m`), read as is.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use surface::{read_testbed, read_testbed_file, write_testbed_file, Mesh, TestbedError};

const OCTA_PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m");

fn octa() -> Mesh {
    read_testbed_file(OCTA_PATH).expect("data/octa.m reads")
}

#[test]
fn octa_has_the_octahedrons_counts() {
    let m = octa();
    assert_eq!(m.num_vertices(), 6);
    assert_eq!(m.num_faces(), 8);
    assert_eq!(m.num_edges(), 12);
    assert_eq!(m.euler_characteristic(), 2);
    assert!(m.is_closed());
    assert!(m.boundary_edges().is_empty());
    // Every vertex has four faces around it, and four neighbours.
    for v in 0..6 {
        assert_eq!(m.faces_around_vertex(v).len(), 4);
        assert_eq!(m.vertex_ring(v).len(), 4);
    }
    // Names and order as in the file.
    let names: Vec<&str> = m.vertices().iter().map(|v| v.name().unwrap()).collect();
    assert_eq!(names, ["px", "py", "pz", "mx", "my", "mz"]);
    assert_eq!(m.face_name(1), Some("PMP"));
    assert_eq!(m.faces()[1], [2, 4, 0]); // PMP = [pz, my, px]
                                         // No curvature in Figure 2: flagged, zero tensors.
    assert!(m.vertices().iter().all(|v| !v.curvature_known));
}

#[test]
fn octa_is_consistently_oriented_outward() {
    let m = octa();
    for f in 0..m.num_faces() {
        let geometric = m.face_area_normal(f).unwrap();
        let [a, b, c] = m.face_data(f).unwrap();
        let average = a.n + b.n + c.n;
        // For the octahedron both are along (±1, ±1, ±1): the cosine is exactly 1.
        let cosine = geometric.dot(&average) / (geometric.norm() * average.norm());
        assert!((cosine - 1.0).abs() < 1e-15, "face {f}: cosine {cosine}");
    }
}

#[test]
fn walking_around_the_north_pole_returns() {
    let m = octa();
    // pz is vertex 2. From each face around it, cross the local edge that ends at pz: that
    // leads to the next face counter-clockwise, the order of `faces_around_vertex`.
    let fan = m.faces_around_vertex(2);
    let mut f = fan[0];
    let mut visited = vec![f];
    for _ in 0..4 {
        let face = m.face(f).unwrap();
        let c = face.iter().position(|&v| v == 2).unwrap();
        f = m.walk(f, &[(c + 2) % 3]).unwrap()[1];
        visited.push(f);
    }
    assert_eq!(visited[4], visited[0]);
    assert_eq!(&visited[..4], fan.as_slice());
}

#[test]
fn round_trip_through_a_file() {
    let m = octa();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("octa.m");
    write_testbed_file(&m, &path).unwrap();
    let again = read_testbed_file(&path).unwrap();
    assert_eq!(again, m);
}

#[test]
fn malformed_octa_variants_report_lines() {
    let text = std::fs::read_to_string(OCTA_PATH).unwrap();
    let line_of = |t: &str| match read_testbed(t) {
        Err(TestbedError::Syntax { line, message }) => (line, message),
        other => panic!("expected a syntax error, got {other:?}"),
    };
    // Line 10 is `PMP = [pz, my, px];`. A four-vertex face parses (meshio keeps polygons) and
    // the strict reader refuses it by name.
    match read_testbed(&text.replace("[pz, my, px]", "[pz, my, px, mx]")) {
        Err(e @ TestbedError::NotTriangle { corners: 4, .. }) => {
            assert!(e.to_string().contains("face `PMP` has 4 vertices"), "{e}");
        }
        other => panic!("expected a refused polygon, got {other:?}"),
    }
    let (line, msg) = line_of(&text.replace("[pz, my, px]", "[pz, my, qx]"));
    assert_eq!(line, 10);
    assert!(msg.contains("unknown vertex `qx`"), "{msg}");
    // Line 7 is mz's definition.
    let (line, msg) = line_of(&text.replace("(pos . [0,0,-1])", "(pos . [0,0,-1,5])"));
    assert_eq!(line, 7);
    assert!(
        msg.contains("`pos` of `mz` has 4 numbers, expected 3"),
        "{msg}"
    );
    let (line, msg) = line_of(&text.replace("mesh = {PPP,PMP,MPP,MMP,PPM,PMM,MPM,MMM};", ""));
    assert_eq!(
        line,
        text.lines().count() + usize::from(text.ends_with('\n'))
    );
    assert!(msg.contains("no `mesh"), "{msg}");
    let missing = std::path::Path::new(OCTA_PATH).with_file_name("no-such-file.m");
    let err = read_testbed_file(&missing).unwrap_err();
    assert!(err.to_string().contains("no-such-file.m"));
}

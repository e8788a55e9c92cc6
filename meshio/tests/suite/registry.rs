//! The format registry: lookup by name and path, sniffing, the lying extension, errors.
#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use std::path::Path;

use meshio::{
    format_by_name, format_for_path, read_bytes, read_file, write_bytes, Location, MeshIoError,
    WriteOptions, FORMATS,
};

#[test]
fn names_are_unique_and_found() {
    for f in FORMATS {
        let g = format_by_name(f.name()).map(|g| g.name());
        assert_eq!(g, Some(f.name()));
        assert_eq!(FORMATS.iter().filter(|g| g.name() == f.name()).count(), 1);
    }
    assert!(format_by_name("PLY").is_some());
    assert!(format_by_name("dxf").is_none());
}

#[test]
fn extension_is_case_insensitive() {
    let name = |p: &str| format_for_path(Path::new(p)).map(|f| f.name());
    assert_eq!(name("a/b/bunny.OBJ"), Some("obj"));
    assert_eq!(name("x.Ply"), Some("ply"));
    assert_eq!(name("x.stl"), Some("stl"));
    assert_eq!(name("x.off"), Some("off"));
    assert_eq!(name("octa.m"), Some("testbed"));
    assert_eq!(name("x.glb"), Some("glb"));
    assert_eq!(name("x.dxf"), None);
    assert_eq!(name("noext"), None);
}

#[test]
fn every_written_file_is_sniffed_as_its_format() {
    let mesh = common::cube();
    for f in FORMATS {
        for opts in [WriteOptions::new(), WriteOptions::new().ascii()] {
            let bytes = write_bytes(&mesh, *f, &opts).expect("write");
            assert!(
                f.sniff(&bytes),
                "{} does not sniff its own output",
                f.name()
            );
            let first = meshio::sniff_format(&bytes).map(|g| g.name());
            if f.can_read() {
                assert_eq!(first, Some(f.name()));
            }
        }
    }
}

#[test]
fn lying_extension_reads_the_content_format_with_a_note() {
    let ply = write_bytes(
        &common::cube(),
        format_by_name("ply").expect("ply"),
        &WriteOptions::new(),
    )
    .expect("write");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let path = dir.join("meshio_lying_extension.obj");
    std::fs::write(&path, &ply).expect("write temp file");
    let mesh = read_file(&path).expect("read");
    std::fs::remove_file(&path).ok();
    assert_eq!(mesh.num_vertices(), 8);
    assert_eq!(mesh.num_faces(), 6);
    assert!(
        common::has_note(&mesh, "content is ply"),
        "{:?}",
        mesh.notes
    );
}

#[test]
fn unknown_extension_goes_by_content() {
    let off = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let mesh = read_bytes(Path::new("thing.mesh"), off).expect("read");
    assert_eq!(mesh.num_faces(), 1);
    assert!(common::has_note(&mesh, "the content is off"));
}

#[test]
fn unknown_extension_and_content_is_unsupported() {
    let err = read_bytes(Path::new("drawing.dxf"), b"\x00\x01binary junk").expect_err("junk");
    assert!(matches!(err, MeshIoError::Unsupported { .. }));
    let text = err.to_string();
    assert!(
        text.starts_with("drawing.dxf: unsupported format"),
        "{text}"
    );
    for ext in [".ply", ".obj", ".stl", ".off", ".m", ".glb"] {
        assert!(text.contains(ext), "{text}");
    }
}

#[test]
fn errors_display_path_location_message() {
    // A binary PLY cut inside vertex 17's y.
    let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 20\nproperty float x\nproperty float y\nproperty float z\nend_header\n".to_vec();
    bytes.extend(std::iter::repeat_n(0u8, 17 * 12 + 4 + 2));
    let err = read_bytes(Path::new("bunny.ply"), &bytes).expect_err("truncated");
    assert_eq!(
        err.to_string(),
        "bunny.ply: element vertex 17, property y: unexpected end of file"
    );
    let MeshIoError::Read { source, .. } = err else {
        panic!("not a read error")
    };
    assert_eq!(source.format, "ply");
    assert_eq!(
        source.location,
        Location::Element {
            element: "vertex".into(),
            index: 17,
            property: Some("y".into()),
        }
    );
}

#[test]
fn missing_file_is_an_io_error() {
    let err = read_file(Path::new(env!("CARGO_TARGET_TMPDIR")).join("no_such_mesh.ply"))
        .expect_err("missing");
    assert!(matches!(err, MeshIoError::Io { .. }));
}

#[test]
fn glb_reads_back_by_extension() {
    let glb = format_by_name("glb").expect("glb");
    assert!(glb.can_read());
    let cube = common::cube();
    let bytes = write_bytes(&cube, glb, &WriteOptions::new()).expect("write");
    let back = read_bytes(Path::new("x.glb"), &bytes).expect("glb reads");
    assert_eq!(back.num_vertices(), 8);
    // Six quads as twelve triangles.
    assert_eq!(back.num_faces(), 12);
}

#[test]
fn octa_reads_from_the_repository() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/octa.m");
    let mesh = read_file(&path).expect("octa.m");
    assert_eq!(mesh.num_vertices(), 6);
    assert_eq!(mesh.num_faces(), 8);
    assert!(mesh.polygons.all_triangles());
    assert_eq!(mesh.normals.as_ref().map(Vec::len), Some(6));
}

/// The writable extensions are exactly those of the formats that write: glTF binary is among
/// them (write-only), and every one names a format that can write.
#[test]
fn writable_extensions_are_the_writers() {
    let ext = meshio::writable_extensions();
    for e in ["obj", "ply", "stl", "off", "m", "glb"] {
        assert!(ext.contains(&e), "{e} missing from {ext:?}");
    }
    for e in &ext {
        let f = meshio::format_for_path(std::path::Path::new(&format!("x.{e}"))).unwrap();
        assert!(f.can_write(), "{e}");
    }
}

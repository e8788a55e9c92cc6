//! The seed's Examples 1–5 (`examples/example*.sh`) run with the test binary into a temporary
//! directory; every picture must exist, have the examples' size and not be blank.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use std::path::Path;
use std::process::Command;

/// The examples' picture size (`testbed render`'s default).
const SIZE: (u32, u32) = (400, 300);

/// A picture is "not blank" when at least this many pixels differ from the background
/// (top-left pixel): the octahedron covers tens of thousands at 400×300, a stray pixel or a
/// one-line artefact a few hundred.
const MIN_DRAWN_PIXELS: usize = 1000;

fn check_png(path: &Path) {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let decoder = png::Decoder::new(std::io::BufReader::new(file));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("a frame");
    assert_eq!((info.width, info.height), SIZE, "{}", path.display());
    let bytes = &buf[..info.buffer_size()];
    let px = info.color_type.samples();
    let background = &bytes[..px];
    let drawn = bytes.chunks(px).filter(|p| *p != background).count();
    assert!(
        drawn >= MIN_DRAWN_PIXELS,
        "{}: only {drawn} pixels differ from the background",
        path.display()
    );
}

fn run_example(n: usize, outputs: &[&str]) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let dir = tempfile::tempdir().expect("temp dir");
    let status = Command::new("bash")
        .arg(root.join(format!("examples/example{n}.sh")))
        .arg(dir.path())
        .env("TESTBED", env!("CARGO_BIN_EXE_testbed"))
        .status()
        .expect("bash runs");
    assert!(status.success(), "example {n} failed");
    for o in outputs {
        check_png(&dir.path().join(o));
    }
}

#[test]
fn example1_shaded() {
    run_example(1, &["example1.png"]);
}

#[test]
fn example2_wire_frame() {
    run_example(2, &["example2.png"]);
}

#[test]
fn example3_gaussian_curvature() {
    run_example(3, &["example3.png"]);
}

#[test]
fn example4_one_file_read_twice() {
    run_example(4, &["example4-kg.png", "example4-simple.png"]);
}

#[test]
fn example5_sampling_fitter() {
    run_example(5, &["example5.png"]);
}

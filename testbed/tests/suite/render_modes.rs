//! `render --mode`: the interrogation pictures through the binary, and their options' usage
//! errors (exit status 2, naming the option).
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use crate::support::{ok, testbed};

/// The octahedron's Shirman–Séquin patches tessellated with normals.
fn triangles() -> Vec<u8> {
    let octa =
        std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/octa.m")).expect("octa.m");
    let patches = ok(&["fit", "--scheme", "shirman-sequin"], &octa);
    ok(&["tess", "-s", "8", "--mesh"], &patches)
}

/// The RGB bytes of a PNG.
fn decode(png_bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let mut reader = png::Decoder::new(std::io::Cursor::new(png_bytes))
        .read_info()
        .expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("a frame");
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

#[test]
fn every_mode_draws_two_tone_stripes_and_shaded_stays_lit() {
    let tris = triangles();
    // sRGB bytes of render::interrogation's DARK (0.02) and LIGHT (0.8), and the background.
    let (dark, light, white) = (39u8, 231u8, 255u8);
    let (_, _, shaded) = decode(&ok(&["render", "--size", "160x120"], &tris));
    let tones = |rgb: &[u8]| {
        let mut seen: Vec<u8> = rgb.to_vec();
        seen.sort_unstable();
        seen.dedup();
        seen
    };
    assert!(tones(&shaded).len() > 20, "the lit picture has shades");
    for mode in [
        &["--mode", "reflection"][..],
        &["--mode", "isophotes", "--stripes", "6"],
        &[
            "--mode",
            "highlight",
            "--direction",
            "1,0,0",
            "--width",
            "0.3",
        ],
        &[
            "--mode",
            "reflection",
            "--direction",
            "0,0,1",
            "--stripes",
            "24",
        ],
    ] {
        let mut args = vec!["render", "--size", "160x120"];
        args.extend_from_slice(mode);
        let (w, h, rgb) = decode(&ok(&args, &tris));
        assert_eq!((w, h), (160, 120));
        assert_eq!(tones(&rgb), [dark, light, white], "{mode:?}");
        let count = |b: u8| rgb.chunks(3).filter(|p| p[0] == b).count();
        let (d, l) = (count(dark), count(light));
        // The octahedron's surface covers a good part of the frame, both tones on it.
        assert!(d > 500 && l > 500, "{mode:?}: {d} dark, {l} light pixels");
    }
}

#[test]
fn bad_mode_options_exit_2_naming_the_option() {
    let tris = triangles();
    for (args, expect) in [
        (&["render", "--mode", "zebra"][..], "--mode zebra"),
        (&["render", "--stripes", "8"], "--stripes needs --mode"),
        (
            &["render", "--mode", "reflection", "--stripes", "0"],
            "--stripes 0",
        ),
        (
            &["render", "--mode", "isophotes", "--width", "2"],
            "--width 2",
        ),
        (
            &["render", "--mode", "highlight", "--direction", "0,0,0"],
            "zero vector",
        ),
        (
            &["render", "--mode", "highlight", "--direction", "x,y,z"],
            "--direction x,y,z",
        ),
        // The lights along the view direction (from azimuth 0, elevation 0: along x).
        (
            &[
                "render",
                "--mode",
                "highlight",
                "--view",
                "0,0",
                "--direction",
                "1,0,0",
            ],
            "along the view axis",
        ),
    ] {
        let out = testbed(args, &tris);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(expect), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}: nothing written");
    }
}

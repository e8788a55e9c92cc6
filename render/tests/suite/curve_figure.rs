//! End-to-end tests of `write_curve_figure`: files written, PNG size, SVG text, degenerate input.

use std::fs;
use std::path::{Path, PathBuf};

use curves::CubicBez2;
use nalgebra::{Point2, Vector2};
use render::{figure_size, write_curve_figure, CurveFigure, CurvePanel, RenderError};

/// The eight-byte PNG file signature.
const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a];

/// Unit-chord cubic from (0,0) to (1,0) with end tangents at `angle` above and below the chord
/// and end-derivative lengths `alpha` (α = 1 is one third of the chord).
fn unit_chord(angle: f64, alpha: [f64; 2]) -> CubicBez2 {
    let t0 = Vector2::new(angle.cos(), angle.sin());
    let t1 = Vector2::new(angle.cos(), -angle.sin());
    let p0 = Point2::new(0.0, 0.0);
    let p3 = Point2::new(1.0, 0.0);
    CubicBez2::new([
        p0,
        p0 + t0 * (alpha[0] / 3.0),
        p3 - t1 * (alpha[1] / 3.0),
        p3,
    ])
}

fn panel(title: &str, alpha: [f64; 2]) -> CurvePanel {
    CurvePanel {
        title: title.to_string(),
        curve: unit_chord(0.4, alpha),
        targets: [-0.8, -0.8],
        notes: vec![format!("α = ({}, {})", alpha[0], alpha[1])],
    }
}

fn sample_figure() -> CurveFigure {
    CurveFigure {
        title: "Boundary curves, tangent angle 0.4, target κ = -0.8".to_string(),
        rows: vec![
            vec![
                panel("chord", [1.0, 1.0]),
                panel("dbhs", [0.15, 1.8]),
                panel("optimized", [0.83, 1.21]),
            ],
            vec![
                CurvePanel {
                    title: "chord".to_string(),
                    curve: unit_chord(-0.3, [1.0, 1.0]),
                    targets: [0.5, 1.5],
                    notes: vec![],
                },
                CurvePanel {
                    title: "dbhs".to_string(),
                    curve: unit_chord(-0.3, [1.6, 0.05]),
                    targets: [0.5, 1.5],
                    notes: vec!["a long note that has to be wrapped because it does not fit into one column of the figure".to_string()],
                },
            ],
        ],
    }
}

/// Width and height from a PNG's IHDR chunk, which the format requires to come first.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], &PNG_SIGNATURE);
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
    (be(&bytes[16..20]), be(&bytes[20..24]))
}

fn outputs(dir: &Path, stem: &str) -> (PathBuf, PathBuf) {
    (
        dir.join(format!("{stem}.png")),
        dir.join(format!("{stem}.svg")),
    )
}

#[test]
fn writes_png_and_svg_of_the_expected_size() {
    let dir = tempfile::tempdir().unwrap();
    let (png, svg) = outputs(dir.path(), "fig2");
    let fig = sample_figure();
    write_curve_figure(&fig, &png, &svg).unwrap();

    let (w, h) = figure_size(&fig);
    // 420 px per column, three columns.
    assert_eq!(w, 3 * 420);
    assert!((1000..1800).contains(&h), "height {h}");
    assert_eq!(png_size(&fs::read(&png).unwrap()), (w, h));

    let svg_text = fs::read_to_string(&svg).unwrap();
    assert!(svg_text.contains(&format!("width=\"{w}\"")));
    for title in ["chord", "dbhs", "optimized"] {
        assert!(svg_text.contains(&format!("{title}\n</text>")), "{title}");
    }
    assert!(svg_text.contains("α = (0.15, 1.8)"));
    assert!(svg_text.contains("font-family=\"DejaVu Sans\""));
    // Only the two outputs, no temporary files.
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 2);
}

#[test]
fn short_tangent_spike_is_clipped_and_reported() {
    let dir = tempfile::tempdir().unwrap();
    let (png, svg) = outputs(dir.path(), "spike");
    let fig = CurveFigure {
        title: "spike".to_string(),
        rows: vec![vec![panel("dbhs", [0.15, 1.8])]],
    };
    write_curve_figure(&fig, &png, &svg).unwrap();
    let svg_text = fs::read_to_string(&svg).unwrap();
    assert!(svg_text.contains("(clipped in plot)"));
    // The spike's true height, κ(0) = (2/3)(d0 × d1)/|d0|³ with d0 = P1 − P0 = 0.05 t0 and
    // d1 = P2 − P1, is more than ten times the target and is printed both in the caption and at
    // the clip marker (four significant digits).
    let c = unit_chord(0.4, [0.15, 1.8]);
    let k0 = c.curvature(0.0);
    assert!((10.0..100.0).contains(&k0), "{k0}");
    for shown in [format!("κ(0) = {k0:.2}"), format!("max {k0:.2}")] {
        assert!(svg_text.contains(&shown), "{shown}");
    }
}

#[test]
fn degenerate_curves_do_not_panic() {
    let dir = tempfile::tempdir().unwrap();
    let (png, svg) = outputs(dir.path(), "degenerate");
    let p = Point2::new(0.5, 0.5);
    let q = Point2::new(1.0, 0.0);
    let fig = CurveFigure {
        title: "degenerate".to_string(),
        rows: vec![vec![
            // A point: zero length, κ NaN everywhere.
            CurvePanel {
                title: "point".to_string(),
                curve: CubicBez2::new([p, p, p, p]),
                targets: [0.0, 0.0],
                notes: vec![],
            },
            // Vanishing end derivatives: κ NaN at both ends only.
            CurvePanel {
                title: "cusps".to_string(),
                curve: CubicBez2::new([Point2::origin(), Point2::origin(), q, q]),
                targets: [f64::NAN, f64::INFINITY],
                notes: vec![],
            },
            // Coordinates and targets near the end of the f64 range.
            CurvePanel {
                title: "huge".to_string(),
                curve: CubicBez2::new([
                    Point2::new(-1e300, 0.0),
                    Point2::new(0.0, 1e300),
                    q,
                    Point2::new(1e300, 0.0),
                ]),
                targets: [-1e300, 1e300],
                notes: vec![],
            },
            // Non-finite control points.
            CurvePanel {
                title: "nan".to_string(),
                curve: CubicBez2::new([Point2::new(f64::NAN, 0.0), p, q, q]),
                targets: [1.0, 1.0],
                notes: vec![],
            },
        ]],
    };
    write_curve_figure(&fig, &png, &svg).unwrap();
    let svg_text = fs::read_to_string(&svg).unwrap();
    assert!(svg_text.contains("2 non-finite κ samples skipped"));
    assert!(svg_text.contains("κ plotted against t"));
    assert_eq!(png_size(&fs::read(&png).unwrap()), figure_size(&fig));
}

#[test]
fn empty_figure_is_an_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let (png, svg) = outputs(dir.path(), "empty");
    for rows in [vec![], vec![vec![], vec![]]] {
        let fig = CurveFigure {
            title: "empty".to_string(),
            rows,
        };
        let err = write_curve_figure(&fig, &png, &svg).unwrap_err();
        assert!(matches!(err, RenderError::EmptyFigure { .. }));
        assert!(err.to_string().contains("empty.png"));
    }
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn single_column_figure_wraps_its_title_and_legend() {
    let dir = tempfile::tempdir().unwrap();
    let (png, svg) = outputs(dir.path(), "narrow");
    let mut long = panel(
        "a method name far too long for one column of the figure",
        [1.0, 1.0],
    );
    long.targets = [f64::NAN, -0.8];
    let fig = CurveFigure {
        title: "A figure title far too long for a single column of 420 pixels".to_string(),
        rows: vec![vec![long]],
    };
    write_curve_figure(&fig, &png, &svg).unwrap();
    let (w, h) = figure_size(&fig);
    assert_eq!(w, 420);
    assert_eq!(png_size(&fs::read(&png).unwrap()), (w, h));
    let svg_text = fs::read_to_string(&svg).unwrap();
    // The title is split into lines at spaces; every word is still there.
    assert!(!svg_text.contains(&fig.title));
    assert!(svg_text.contains("A figure title"));
    assert!(svg_text.contains("pixels\n</text>"));
}

#[test]
fn existing_outputs_are_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let (png, svg) = outputs(dir.path(), "replace");
    fs::write(&png, b"old").unwrap();
    fs::write(&svg, b"old").unwrap();
    let fig = CurveFigure {
        title: "replace".to_string(),
        rows: vec![vec![panel("chord", [1.0, 1.0])]],
    };
    write_curve_figure(&fig, &png, &svg).unwrap();
    assert_eq!(png_size(&fs::read(&png).unwrap()), figure_size(&fig));
    assert!(fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 2);
}

/// Writes the sample figure to `std::env::temp_dir()/render-sample-fig2.{png,svg}` for looking
/// at: `cargo test -p render --test curve_figure -- --ignored`.
#[test]
#[ignore = "writes a sample figure for visual inspection"]
fn write_sample_figure_for_inspection() {
    let (png, svg) = outputs(&std::env::temp_dir(), "render-sample-fig2");
    write_curve_figure(&sample_figure(), &png, &svg).unwrap();
    println!("{}\n{}", png.display(), svg.display());
    let fig = CurveFigure {
        title: "A one-column figure whose title is too long for one line".to_string(),
        rows: vec![vec![panel(
            "a method name far too long for one column",
            [0.05, 1.0],
        )]],
    };
    let (png, svg) = outputs(&std::env::temp_dir(), "render-sample-narrow");
    write_curve_figure(&fig, &png, &svg).unwrap();
}

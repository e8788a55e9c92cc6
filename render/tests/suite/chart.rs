//! Line charts and histograms are written as readable PNG and SVG files, and bad input is an
//! error, not a panic.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use render::{write_histogram, write_line_charts, Histogram, LineChart, RenderError, Series};

fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let be = |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    (be(16), be(20))
}

#[test]
fn line_chart_grid_with_log_axis_and_zeros() {
    let dir = tempfile::tempdir().unwrap();
    let chart = |t: &str| LineChart {
        title: t.into(),
        x_label: "iteration".into(),
        y_label: "cost".into(),
        series: vec![
            Series {
                label: "exact-penalty".into(),
                points: vec![(0.0, 1e-2), (1.0, 1e-8), (2.0, 0.0)],
            },
            Series {
                label: "lm".into(),
                points: vec![(0.0, 1e-2), (1.0, 1e-5), (2.0, f64::NAN), (3.0, 1e-12)],
            },
        ],
        log_y: true,
    };
    let (png, svg) = (dir.path().join("c.png"), dir.path().join("c.svg"));
    write_line_charts(
        &[chart("first"), chart("second"), chart("third")],
        2,
        "Costs",
        &png,
        &svg,
    )
    .unwrap();
    // Two columns, two rows of 560 × 420 cells under a 44-pixel title band.
    assert_eq!(png_size(&std::fs::read(&png).unwrap()), (1120, 884));
    let text = std::fs::read_to_string(&svg).unwrap();
    for needle in ["Costs", "first", "third", "exact-penalty", "not drawn"] {
        assert!(text.contains(needle), "SVG lacks {needle}");
    }
    let empty = write_line_charts(&[], 2, "none", &png, &svg).unwrap_err();
    assert!(matches!(empty, RenderError::EmptyFigure { .. }));
}

#[test]
fn histogram_draws_groups_with_a_legend() {
    let dir = tempfile::tempdir().unwrap();
    let h = Histogram {
        title: "Iterations".into(),
        x_label: "iterations".into(),
        y_label: "problems".into(),
        categories: (0..6).map(|i| i.to_string()).collect(),
        groups: vec![
            ("a".into(), vec![0.0, 3.0, 10.0, 4.0, 0.0, 1.0]),
            ("b".into(), vec![1.0, 1.0, 2.0, 9.0, 5.0, 0.0]),
        ],
    };
    let (png, svg) = (dir.path().join("h.png"), dir.path().join("h.svg"));
    write_histogram(&h, &png, &svg).unwrap();
    assert_eq!(png_size(&std::fs::read(&png).unwrap()), (900, 560));
    let text = std::fs::read_to_string(&svg).unwrap();
    // One rectangle per positive bar (4 + 5) plus the two legend swatches, at least.
    assert!(text.matches("<rect").count() >= 11);
    assert!(text.contains("Iterations"));
}

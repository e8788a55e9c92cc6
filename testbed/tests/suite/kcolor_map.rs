//! `kcolor --map`: the original testbed's hue ramp beside the default diverging map, through
//! the command line, on a Triangle whose vertices carry the curvatures −4, 0 and 4.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use serde_json::Value;

use crate::support::{json_records, ok};

/// The stream writes colours with four decimals: half the last digit.
const COLOUR_TOL: f64 = 5e-5;

/// One Triangle with kg = −4, 0, 4 at its three vertices.
fn triangle() -> Vec<u8> {
    let v = |x: f64, k: f64| serde_json::json!({"pos": [x, 0.0, 1.0 + x * x], "norm": [0.0, 0.0, 1.0], "kg": k});
    let t = serde_json::json!({"type": "Triangle", "vertex1": v(0.0, -4.0),
        "vertex2": v(1.0, 0.0), "vertex3": v(2.0, 4.0)});
    format!("{t}\n").into_bytes()
}

fn colours(out: &[u8]) -> Vec<[f64; 3]> {
    let recs = json_records(out);
    let t: &Value = recs.iter().find(|r| r["type"] == "Triangle").unwrap();
    ["vertex1", "vertex2", "vertex3"]
        .iter()
        .map(|k| {
            let c = t[k]["color"].as_array().unwrap();
            std::array::from_fn(|i| c[i].as_f64().unwrap())
        })
        .collect()
}

/// sRGB to linear (IEC 61966-2-1), written out here rather than taken from `render`.
fn linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[test]
fn the_testbed_map_is_blue_green_red_at_minus_four_zero_four() {
    // HLS at L = 0.5, S = 0.9: m₂ = 0.95, m₁ = 0.05; hue 240°, 120°, 0°.
    let (hi, lo) = (linear(0.95), linear(0.05));
    let want = [[lo, lo, hi], [lo, hi, lo], [hi, lo, lo]];
    for args in [
        &["kcolor", "--map", "testbed"][..],
        &["kcolor", "--map", "testbed", "--range", "-4:4"],
    ] {
        let got = colours(&ok(args, &triangle()));
        for (g, w) in got.iter().zip(&want) {
            for c in 0..3 {
                assert!((g[c] - w[c]).abs() < COLOUR_TOL, "{args:?}: {got:?}");
            }
        }
    }
    // A range of its own rescales the ramp: over -8:8, k = 4 is k' = −½, hue 120(1 − ½^0.625).
    let got = colours(&ok(
        &["kcolor", "--map", "testbed", "--range", "-8:8"],
        &triangle(),
    ));
    let hue = 120.0 * (1.0 - 0.5_f64.powf(0.625));
    let srgb = render::colors::hls_to_rgb(hue, 0.5, 0.9);
    for c in 0..3 {
        assert!((got[2][c] - linear(srgb[c])).abs() < COLOUR_TOL, "{got:?}");
    }
}

#[test]
fn the_diverging_map_stays_the_default() {
    let plain = colours(&ok(&["kcolor", "--range", "-4:4"], &triangle()));
    let named = colours(&ok(
        &["kcolor", "--map", "diverging", "--range", "-4:4"],
        &triangle(),
    ));
    assert_eq!(plain, named);
    for (k, got) in [-4.0, 0.0, 4.0].iter().zip(&plain) {
        let want = render::colors::diverging(*k, 4.0);
        for c in 0..3 {
            assert!(
                (got[c] - f64::from(want[c])).abs() < COLOUR_TOL,
                "{plain:?}"
            );
        }
    }
}

//! Colour maps for surface pictures, returning linear RGB for shading.
//!
//! * [`diverging`]: blue – light grey – red, Moreland's "cool to warm" end points (Moreland,
//!   *Diverging Color Maps for Scientific Visualization*, 2009), centred on zero: Gaussian
//!   curvature (the testbed's KColor);
//! * [`sequential`]: five control points of matplotlib's viridis, perceptually ordered:
//!   distances (the testbed's Radial);
//! * [`testbed_kcolor`]: the original testbed's KColor hue ramp (red – green – blue through
//!   HLS), kept for comparison with its pictures.
//!
//! Control points are sRGB; interpolation is done in sRGB and the result converted to linear.

/// Quantile of `|value|` taken as the data's robust maximum for colour ranges: curvature
/// spikes at a few singular samples (collapsed edges, seams of fallback faces) would
/// otherwise wash the picture out; 95% keeps the bulk of the surface in the scale.
pub const ROBUST_QUANTILE: f64 = 0.95;

/// The [`ROBUST_QUANTILE`] of `|values|` by nearest rank (1 when it is zero or not finite, or
/// there are no values); `values` is reordered in place (absolute values, sorted).
pub fn robust_max(values: &mut [f64]) -> f64 {
    for v in values.iter_mut() {
        *v = v.abs();
    }
    values.sort_by(f64::total_cmp);
    let k = ((values.len().saturating_sub(1)) as f64 * ROBUST_QUANTILE).round() as usize;
    values
        .get(k)
        .copied()
        .filter(|m| *m > 0.0 && m.is_finite())
        .unwrap_or(1.0)
}

/// The uniform material colour of shaded pictures (linear RGB of sRGB (0.72, 0.75, 0.80)).
pub const MATERIAL: [f32; 3] = [0.4793, 0.5225, 0.6038];

fn to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn interpolate(stops: &[(f64, [f32; 3])], t: f64) -> [f32; 3] {
    let t = if t.is_finite() {
        t.clamp(stops[0].0, stops[stops.len() - 1].0)
    } else {
        stops[0].0
    };
    for w in stops.windows(2) {
        let ((a, ca), (b, cb)) = (w[0], w[1]);
        if t <= b {
            let s = ((t - a) / (b - a)) as f32;
            return std::array::from_fn(|k| to_linear(ca[k] + (cb[k] - ca[k]) * s));
        }
    }
    stops[stops.len() - 1].1.map(to_linear)
}

/// Diverging colour of `value` saturating at `±limit` (white-ish grey at zero).
pub fn diverging(value: f64, limit: f64) -> [f32; 3] {
    const STOPS: [(f64, [f32; 3]); 3] = [
        (-1.0, [0.230, 0.299, 0.754]),
        (0.0, [0.865, 0.865, 0.865]),
        (1.0, [0.706, 0.016, 0.150]),
    ];
    interpolate(&STOPS, value / limit.abs().max(f64::MIN_POSITIVE))
}

/// Sequential colour of `value` between `lo` (dark purple) and `hi` (yellow).
pub fn sequential(value: f64, lo: f64, hi: f64) -> [f32; 3] {
    const STOPS: [(f64, [f32; 3]); 5] = [
        (0.0, [0.267, 0.005, 0.329]),
        (0.25, [0.229, 0.322, 0.546]),
        (0.5, [0.128, 0.567, 0.551]),
        (0.75, [0.369, 0.789, 0.383]),
        (1.0, [0.993, 0.906, 0.144]),
    ];
    let span = (hi - lo).abs().max(f64::MIN_POSITIVE);
    interpolate(&STOPS, (value - lo) / span)
}

/// The original testbed's KColor range, `[k_min, k_max] = [−4, 4]` (the original testbed's
/// fitters, UW 1990): curvature beyond it is clamped.
pub const TESTBED_KCOLOR_RANGE: (f64, f64) = (-4.0, 4.0);
/// The exponent of the testbed's hue ramp: `|k'|^γ` with `γ < 1` spends more hue on small
/// curvature than a linear ramp.
pub const TESTBED_KCOLOR_GAMMA: f64 = 0.625;
/// Lightness and saturation of the testbed's KColor (HLS).
pub const TESTBED_KCOLOR_LS: (f64, f64) = (0.5, 0.9);

/// The testbed's KColor hue in degrees of curvature `k` over `[k_min, k_max]` (clamped):
/// with `k' = 2(k_max − k)/(k_max − k_min) − 1 ∈ [−1, 1]` (−1 at `k_max`, 1 at `k_min`), the hue
/// is `120(1 − |k'|^γ)` for `k' < 0` and `120(1 + k'^γ)` otherwise: red (0°) at `k_max`, green
/// (120°) at the range's middle, blue (240°) at `k_min`. A NaN curvature gets the middle.
pub fn testbed_kcolor_hue(k: f64, (k_min, k_max): (f64, f64), gamma: f64) -> f64 {
    let span = (k_max - k_min).max(f64::MIN_POSITIVE);
    let mid = 0.5 * (k_min + k_max);
    let k = if k.is_nan() {
        mid
    } else {
        k.clamp(k_min, k_max)
    };
    let kp = (2.0 * (k_max - k) / span - 1.0).clamp(-1.0, 1.0);
    if kp < 0.0 {
        120.0 * (1.0 - (-kp).powf(gamma))
    } else {
        120.0 * (1.0 + kp.powf(gamma))
    }
}

/// HLS to RGB (hue in degrees, lightness and saturation in `[0, 1]`), the double-hexcone
/// model: `m₂ = L(1 + S)` for `L ≤ ½`, else `L + S − LS`; `m₁ = 2L − m₂`; each channel is
/// `m₁` on the far half of the hue circle, `m₂` on the near third, and linear between over
/// sixths, the red channel centred on hue 0°, green on 120°, blue on 240°.
pub fn hls_to_rgb(hue_degrees: f64, l: f64, s: f64) -> [f64; 3] {
    if s == 0.0 {
        return [l; 3];
    }
    let m2 = if l <= 0.5 {
        l * (1.0 + s)
    } else {
        l + s - l * s
    };
    let m1 = 2.0 * l - m2;
    let channel = |h: f64| {
        let h = h.rem_euclid(1.0);
        if h < 1.0 / 6.0 {
            m1 + (m2 - m1) * h * 6.0
        } else if h < 0.5 {
            m2
        } else if h < 2.0 / 3.0 {
            m1 + (m2 - m1) * (2.0 / 3.0 - h) * 6.0
        } else {
            m1
        }
    };
    let h = hue_degrees / 360.0;
    [channel(h + 1.0 / 3.0), channel(h), channel(h - 1.0 / 3.0)]
}

/// The testbed's KColor of curvature `k` over `range` as sRGB: [`testbed_kcolor_hue`] with
/// [`TESTBED_KCOLOR_GAMMA`], then [`hls_to_rgb`] at [`TESTBED_KCOLOR_LS`].
pub fn testbed_kcolor_srgb(k: f64, range: (f64, f64)) -> [f64; 3] {
    let (l, s) = TESTBED_KCOLOR_LS;
    hls_to_rgb(testbed_kcolor_hue(k, range, TESTBED_KCOLOR_GAMMA), l, s)
}

/// [`testbed_kcolor_srgb`] in linear RGB, for shading like the other maps.
pub fn testbed_kcolor(k: f64, range: (f64, f64)) -> [f32; 3] {
    testbed_kcolor_srgb(k, range).map(|c| to_linear(c as f32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn robust_max_ignores_the_top_five_percent() {
        // 100 values 1..=100 with a spike: the 95% nearest-rank quantile of |v| is 95.
        let mut v: Vec<f64> = (1..=100).map(|i| -(i as f64)).collect();
        v[99] = -1e9;
        assert_eq!(robust_max(&mut v), 95.0);
        assert_eq!(robust_max(&mut []), 1.0);
        assert_eq!(robust_max(&mut [0.0, 0.0]), 1.0);
        assert_eq!(robust_max(&mut [f64::NAN]), 1.0);
    }

    fn luminance(c: [f32; 3]) -> f32 {
        0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
    }

    #[test]
    fn diverging_is_symmetric_about_a_light_centre() {
        let z = diverging(0.0, 2.0);
        assert!(z.iter().all(|c| *c > 0.7));
        let (lo, hi) = (diverging(-2.0, 2.0), diverging(2.0, 2.0));
        assert!(lo[2] > lo[0] && hi[0] > hi[2]);
        assert!((luminance(diverging(-1.0, 2.0)) - luminance(diverging(1.0, 2.0))).abs() < 0.08);
        assert_eq!(diverging(5.0, 2.0), diverging(2.0, 2.0));
        assert_eq!(diverging(f64::NAN, 1.0), diverging(-1.0, 1.0));
    }

    #[test]
    fn sequential_is_monotone_in_luminance() {
        let l: Vec<f32> = (0..=20)
            .map(|i| luminance(sequential(i as f64 / 20.0, 0.0, 1.0)))
            .collect();
        assert!(l.windows(2).all(|w| w[1] > w[0]), "{l:?}");
    }

    /// HLS → RGB and the testbed's map are exact arithmetic on sixths and tenths: rounding.
    const HLS_TOL: f64 = 1e-12;

    #[test]
    fn hls_to_rgb_matches_the_closed_form() {
        // Python's colorsys.hls_to_rgb(h/360, 0.5, 0.9), by hand: m₂ = 0.95, m₁ = 0.05.
        let cases = [
            (0.0, [0.95, 0.05, 0.05]),
            (30.0, [0.95, 0.5, 0.05]),
            (60.0, [0.95, 0.95, 0.05]),
            (120.0, [0.05, 0.95, 0.05]),
            (200.0, [0.05, 0.65, 0.95]),
            (240.0, [0.05, 0.05, 0.95]),
            (300.0, [0.95, 0.05, 0.95]),
        ];
        for (h, want) in cases {
            let got = hls_to_rgb(h, 0.5, 0.9);
            for c in 0..3 {
                assert!((got[c] - want[c]).abs() < HLS_TOL, "hue {h}: {got:?}");
            }
        }
        // Light side (L > ½): m₂ = L + S − LS = 0.85, m₁ = 0.55 at L = 0.7, S = 0.5.
        let got = hls_to_rgb(90.0, 0.7, 0.5);
        let want = [0.55 + 0.3 * 0.5, 0.85, 0.55];
        for c in 0..3 {
            assert!((got[c] - want[c]).abs() < HLS_TOL, "{got:?}");
        }
        assert_eq!(hls_to_rgb(77.0, 0.3, 0.0), [0.3; 3]);
    }

    #[test]
    fn testbed_kcolor_is_blue_green_red_at_minus_four_zero_four() {
        let r = TESTBED_KCOLOR_RANGE;
        let cases = [
            (-4.0, [0.05, 0.05, 0.95]),
            (0.0, [0.05, 0.95, 0.05]),
            (4.0, [0.95, 0.05, 0.05]),
            (-9.0, [0.05, 0.05, 0.95]),
            (9.0, [0.95, 0.05, 0.05]),
        ];
        for (k, want) in cases {
            let got = testbed_kcolor_srgb(k, r);
            for c in 0..3 {
                assert!((got[c] - want[c]).abs() < HLS_TOL, "k = {k}: {got:?}");
            }
        }
        // The linear-RGB form is the sRGB one decoded.
        let lin = testbed_kcolor(0.0, r);
        assert!((f64::from(lin[1]) - f64::from(to_linear(0.95))).abs() < 1e-7);
    }

    #[test]
    fn testbed_kcolor_hue_follows_the_power_gamma() {
        let r = TESTBED_KCOLOR_RANGE;
        let g = TESTBED_KCOLOR_GAMMA;
        // k = 2 is k' = −½: hue 120(1 − ½^γ) = 42.19…°; k = −2 is k' = ½: 120(1 + ½^γ).
        let half = 0.5_f64.powf(g);
        assert!((testbed_kcolor_hue(2.0, r, g) - 120.0 * (1.0 - half)).abs() < HLS_TOL);
        assert!((testbed_kcolor_hue(-2.0, r, g) - 120.0 * (1.0 + half)).abs() < HLS_TOL);
        assert!((half - 0.648_419_777_325_504_8).abs() < HLS_TOL);
        // The exponent read back from two curvatures: |hue − 120| = 120 |k'|^γ.
        let dev = |k: f64| (testbed_kcolor_hue(k, r, g) - 120.0).abs();
        let measured = (dev(0.4) / dev(0.1)).ln() / 4.0_f64.ln();
        assert!((measured - g).abs() < HLS_TOL, "{measured}");
        // γ < 1 spends more hue near zero than the linear ramp (γ = 1).
        assert!(dev(0.4) > (testbed_kcolor_hue(0.4, r, 1.0) - 120.0).abs());
        // Monotone: hue falls as curvature rises.
        let hues: Vec<f64> = (-40..=40)
            .map(|i| testbed_kcolor_hue(f64::from(i) / 10.0, r, g))
            .collect();
        assert!(hues.windows(2).all(|w| w[1] < w[0]));
        assert_eq!(testbed_kcolor_hue(f64::NAN, r, g), 120.0);
    }
}

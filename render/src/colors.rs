//! Colour maps for surface pictures, returning linear RGB for shading.
//!
//! * [`diverging`]: blue – light grey – red, Moreland's "cool to warm" end points (Moreland,
//!   *Diverging Color Maps for Scientific Visualization*, 2009), centred on zero: Gaussian
//!   curvature (the testbed's KColor);
//! * [`sequential`]: five control points of matplotlib's viridis, perceptually ordered:
//!   distances (the testbed's Radial).
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
}

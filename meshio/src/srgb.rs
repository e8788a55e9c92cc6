//! The sRGB transfer function (IEC 61966-2-1): how PLY, OBJ and OFF store colours, the way every
//! viewer of those formats reads them. [`crate::RawMesh::colors`] are linear; writers encode,
//! readers decode.
//!
//! Encoding a linear value `c ∈ [0, 1]`: `12.92 c` for `c ≤ 0.0031308`, else
//! `1.055 c^(1/2.4) − 0.055`. Decoding `s ∈ [0, 1]`: `s / 12.92` for `s ≤ 0.04045`, else
//! `((s + 0.055) / 1.055)^2.4`. The two pieces meet (to 4 digits) at the thresholds, which are
//! each other's image. Values outside `[0, 1]` are clamped; NaN becomes 0.

/// Linear value → sRGB-encoded value, both in `[0, 1]` (module docs).
pub fn encode(c: f32) -> f32 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// sRGB-encoded value → linear value, both in `[0, 1]` (module docs).
pub fn decode(s: f32) -> f32 {
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
    if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear value → sRGB byte (the encoding of [`encode`], times 255, rounded).
pub fn encode_byte(c: f32) -> u8 {
    (encode(c) * 255.0).round() as u8
}

/// sRGB byte → linear value.
pub fn decode_byte(b: u8) -> f32 {
    decode(f32::from(b) / 255.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The published values below have 4 to 5 significant digits.
    const PUBLISHED: f32 = 5e-5;

    /// A round trip through `powf` twice in `f32`: a few ulps of values ≤ 1.
    const ROUND_TRIP: f32 = 4.0 * f32::EPSILON;

    #[test]
    fn known_values() {
        assert_eq!(encode(0.0), 0.0);
        assert!((encode(1.0) - 1.0).abs() < ROUND_TRIP);
        assert_eq!(decode(0.0), 0.0);
        assert!((decode(1.0) - 1.0).abs() < ROUND_TRIP);
        // Linear 0.5 is sRGB 0.7354 (byte 188); linear 0.18 ("middle grey") is sRGB 0.4614.
        assert!((encode(0.5) - 0.735_36).abs() < PUBLISHED);
        assert_eq!(encode_byte(0.5), 188);
        assert!((encode(0.18) - 0.461_35).abs() < PUBLISHED);
        // sRGB 0.5 (byte 128 ≈ 0.502) is linear 0.2140.
        assert!((decode(0.5) - 0.214_04).abs() < PUBLISHED);
        // The linear segment: 0.002 → 0.02584.
        assert!((encode(0.002) - 0.025_84).abs() < PUBLISHED);
        // Clamping and NaN.
        assert_eq!(encode(-1.0), 0.0);
        assert_eq!(encode(2.0), encode(1.0));
        assert_eq!(encode(f32::NAN), 0.0);
    }

    #[test]
    fn the_curvature_red_is_stored_as_its_srgb_bytes() {
        // The diverging map's red end is sRGB (0.706, 0.016, 0.150), about the bytes
        // (180, 4, 38); its linear value stored without encoding was (116, 0, 5).
        let linear = [0.706f32, 0.016, 0.150].map(decode);
        assert_eq!(linear.map(|c| (c * 255.0).round() as u8), [116, 0, 5]);
        assert_eq!(linear.map(encode_byte), [180, 4, 38]);
    }

    #[test]
    fn every_byte_round_trips() {
        for b in 0..=255u8 {
            assert_eq!(encode_byte(decode_byte(b)), b, "byte {b}");
        }
        for i in 0..=1000 {
            let c = i as f32 / 1000.0;
            assert!((decode(encode(c)) - c).abs() < ROUND_TRIP, "{c}");
        }
    }
}

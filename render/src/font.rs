//! The bundled text font and its one-time registration with plotters.
//!
//! Plotters is built without its default features (which need fontconfig), so no system font is
//! looked up: text is drawn with DejaVu Sans, embedded from the workspace's `assets/fonts`
//! (licence beside it) and registered under [`FONT_FAMILY`].

use std::sync::OnceLock;

use plotters::style::FontStyle;

/// The family name under which the bundled font is registered; use it in every text style.
/// It is also the `font-family` SVG output names, so viewers with DejaVu Sans installed show the
/// same glyphs.
pub const FONT_FAMILY: &str = "DejaVu Sans";

/// DejaVu Sans, regular (Bitstream Vera derived licence, see `assets/fonts`).
static FONT_BYTES: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

static REGISTERED: OnceLock<bool> = OnceLock::new();

/// Register the bundled font under [`FONT_FAMILY`] (once per process; later calls only report
/// the first outcome). Returns whether the font is available.
pub fn ensure_registered() -> bool {
    *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, FONT_BYTES).is_ok()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bundled_font_registers() {
        assert!(ensure_registered());
        assert!(ensure_registered());
    }
}

//! Surface interrogation: reflection lines, isophotes and highlight lines, the shading modes
//! of [`crate::shade`] that show a surface's continuity.
//!
//! Each mode maps a pixel's **interpolated unit normal** `n` (and, for reflection lines, the
//! pixel's view ray) to a stripe parameter, and paints the pixel [`DARK`] on a stripe and
//! [`LIGHT`] between stripes. The parameter is computed per pixel from the perspective-correct
//! interpolation of the vertex normals and positions (never per vertex and then interpolated:
//! bands interpolated across a triangle come out as jagged polygons, the triangles' edges, not
//! the surface's).
//!
//! What the stripes show: a parameter that depends on `n` is as smooth as `n`. Across a
//! G1-discontinuity (a crease, a C0 joint) `n` jumps, so the stripes break (they are
//! *discontinuous*); across a G1 but not G2 joint `n`'s derivative jumps, so the stripes
//! *kink*; a G2 surface has smooth stripes (Klass 1980; Poeschl 1984; Beier and Chen 1994; see
//! docs/references.md).
//!
//! * **Reflection lines** ([`Shading::Reflection`], Klass 1980). The surface is a mirror in a
//!   "light cylinder": infinitely far away, around an axis `a`, a family of parallel light
//!   tubes along `a`, equally spaced in angle. A pixel sees, in the mirror, the environment in
//!   the reflected direction `r = d − 2 (d·n) n` of its unit view ray `d` (eye to surface
//!   point; per pixel, from the interpolated camera-space position, so perspective is exact).
//!   Environment at infinity depends on the direction only, and a stripe along `a` on the
//!   cylinder is a half-plane of directions bounded by `a`: the stripe is fixed by the angle of
//!   `r` around `a`, `θ = atan2(r·e₂, r·e₁) ∈ (−π, π]` for an orthonormal `e₁, e₂ ⊥ a` (`e₁`
//!   the direction back to the viewer, made perpendicular to `a`; `e₂ = a × e₁`). The stripe
//!   parameter is `s = stripes · θ / 2π`, so `stripes` stripes go round the full circle (`s`
//!   jumps by the whole number `stripes` at `θ = ±π`, invisible to the stripes); pixels with
//!   `s` within `width/2` of a whole number are dark (`width` the dark fraction of a period).
//!   `r` does not change when `n` is reversed, so two-sided surfaces need no care. A normal
//!   jump by an angle `α` turns `r` by `2α` (mirror reflection doubles angles): reflection
//!   lines magnify a crease twice.
//! * **Isophotes** ([`Shading::Isophotes`], Poeschl 1984). Curves of constant `n·L` for a
//!   light direction `L` (parallel light: what a Lambertian surface's brightness depends on).
//!   With `n` turned to face the viewer, `c = n·L ∈ [−1, 1]`; the band index is
//!   `⌊bands · (c + 1)/2⌋`, `bands` bands over the full range, and the stripe parameter `s =
//!   bands · (c + 1)/2` is dark within `width/2` of a whole number: thin dark lines on the
//!   band borders for a small `width`, alternating bands for `width = 1/2`.
//! * **Highlight lines** ([`Shading::Highlight`], Beier and Chen 1994). Linear light sources
//!   `Aₖ + μE` (`μ ∈ ℝ`) with a common unit direction `E`, in a plane with unit normal `M`
//!   (`E ⊥ M`), spaced `h` apart along `T = M × E`: `Aₖ = A₀ + k h T`. A surface point `P`
//!   with unit normal `N` lies on the highlight line of light `k` where its normal line `P +
//!   λN` meets that light; the highlight parameter is the distance between the two lines. For
//!   skew lines with directions `N` and `E` the distance is the length of the projection of
//!   any joining vector on their common perpendicular `w = N × E`:
//!   `dₖ = (Aₖ − P)·w / |w|`. Since `T·(N × E) = N·(E × T)` and `E × T = E × (M × E) = M(E·E)
//!   − E(E·M) = M`, `dₖ = d₀ + k δ` with `d₀ = (A₀ − P)·w/|w|` and `δ = h (N·M)/|w|`: the
//!   distances to the lights are an arithmetic sequence in `k`, the nearest light is the whole
//!   number nearest `t = −d₀/δ` and its distance is `|δ| · dist(t, ℤ)`. A pixel is dark where
//!   that distance is below `width · h / 2` (on a plate facing the lights, `N = M`, `|w| = 1`,
//!   `δ = h`: a dark fraction `width`; elsewhere the bands narrow and widen with `N` as Beier
//!   and Chen's do). Where the normal line is parallel to the light plane (`N·M = 0`, `δ = 0`)
//!   every light is `|d₀|` away; where it is parallel to the lights (`|w| = 0`) the distance is
//!   that of parallel lines, `√(dist_h((A₀ − P)·T)² + ((A₀ − P)·M)²)` with `dist_h` the
//!   distance to the nearest multiple of `h`. The highlight parameter does not change when
//!   `N` is reversed. [`crate::shade::render`] puts the lights in the plane facing the viewer
//!   (`M` towards the eye) touching the object's bounding sphere (centre `C`, radius `ρ`) on
//!   the viewer's side, `A₀ = C + ρM`, `h = 2ρ / lines`: `lines` lines across the object's
//!   bounding diameter on a plate facing the viewer. A normal tilted by `γ` from `M` meets the
//!   plane about `ρ tan γ` from its foot, so the lines crowd towards the silhouette; the
//!   nearest plane outside the sphere crowds them least (at `2ρ` they came twice as dense).

use nalgebra::Vector3;

/// Dark colour of a stripe (linear RGB): near black, so the stripes read in print.
pub const DARK: [f32; 3] = [0.02, 0.02, 0.02];

/// Light colour between stripes (linear RGB; sRGB 231): not white, so the object stays apart
/// from [`crate::shade::RenderOptions`]'s default white background.
pub const LIGHT: [f32; 3] = [0.8, 0.8, 0.8];

/// Default number of stripes (reflection lines round the circle, isophote bands over `n·L ∈
/// [−1, 1]`, highlight lines across the object).
pub const DEFAULT_STRIPES: u32 = 16;

/// Default dark fraction of a stripe period.
pub const DEFAULT_WIDTH: f64 = 0.5;

/// Most stripes accepted: beyond this a stripe period is far below a pixel on any picture
/// the testbed draws (a 8192-pixel side seeing a full circle of reflected directions).
pub const MAX_STRIPES: u32 = 100_000;

/// How [`crate::shade::render`] colours a visible pixel.
///
/// Directions are in world coordinates and need not be unit (they are normalized); `None`
/// takes the camera's default named at each mode.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Shading {
    /// Blinn–Phong with the vertex colours and the camera-fixed lights (the default).
    #[default]
    Lit,
    /// Reflection lines (Klass 1980): a mirror in a light cylinder around `direction`.
    Reflection {
        /// Stripes round the full circle of directions about the axis (≥ 1).
        stripes: u32,
        /// Axis of the light cylinder; `None`: the camera's up direction (stripes of a surface
        /// of revolution about the vertical run vertically).
        direction: Option<Vector3<f64>>,
        /// Dark fraction of a stripe period, in `[0, 1]`.
        width: f64,
    },
    /// Isophotes (Poeschl 1984): bands of constant `n·L`.
    Isophotes {
        /// Bands over `n·L ∈ [−1, 1]` (≥ 1).
        bands: u32,
        /// Light direction `L` (towards the light); `None`: towards the eye along the view
        /// axis (a headlight).
        light: Option<Vector3<f64>>,
        /// Dark fraction of a band, centred on the band borders, in `[0, 1]`.
        width: f64,
    },
    /// Highlight lines (Beier and Chen 1994): parallel linear lights in a plane facing the
    /// viewer.
    Highlight {
        /// Lights across the object's bounding diameter (≥ 1).
        lines: u32,
        /// Direction of the lights (its part along the view axis is dropped); `None`: the
        /// camera's up direction.
        direction: Option<Vector3<f64>>,
        /// Dark band: normal lines closer to a light than `width / 2` light spacings.
        width: f64,
    },
}

impl Shading {
    /// Reflection lines with [`DEFAULT_STRIPES`], the camera's up axis and [`DEFAULT_WIDTH`].
    pub const REFLECTION: Shading = Shading::Reflection {
        stripes: DEFAULT_STRIPES,
        direction: None,
        width: DEFAULT_WIDTH,
    };

    /// Isophotes with [`DEFAULT_STRIPES`] bands, a headlight and thin lines (width 0.15).
    pub const ISOPHOTES: Shading = Shading::Isophotes {
        bands: DEFAULT_STRIPES,
        light: None,
        width: 0.15,
    };

    /// Highlight lines with [`DEFAULT_STRIPES`] lights, vertical, [`DEFAULT_WIDTH`].
    pub const HIGHLIGHT: Shading = Shading::Highlight {
        lines: DEFAULT_STRIPES,
        direction: None,
        width: DEFAULT_WIDTH,
    };

    /// The mode's name as the testbed spells it: `shaded`, `reflection`, `isophotes`,
    /// `highlight`.
    pub fn name(&self) -> &'static str {
        match self {
            Shading::Lit => "shaded",
            Shading::Reflection { .. } => "reflection",
            Shading::Isophotes { .. } => "isophotes",
            Shading::Highlight { .. } => "highlight",
        }
    }

    /// Checks the numbers: a stripe count from 1 to [`MAX_STRIPES`], a width in `[0, 1]`, a
    /// direction finite and not zero. The message names the field.
    pub fn validate(&self) -> Result<(), String> {
        let (count, direction, width) = match *self {
            Shading::Lit => return Ok(()),
            Shading::Reflection {
                stripes,
                direction,
                width,
            } => (stripes, direction, width),
            Shading::Isophotes {
                bands,
                light,
                width,
            } => (bands, light, width),
            Shading::Highlight {
                lines,
                direction,
                width,
            } => (lines, direction, width),
        };
        if !(1..=MAX_STRIPES).contains(&count) {
            return Err(format!("stripes {count}: from 1 to {MAX_STRIPES}"));
        }
        if !(0.0..=1.0).contains(&width) {
            return Err(format!("width {width}: a fraction from 0 to 1"));
        }
        if let Some(d) = direction {
            if !d.iter().all(|x| x.is_finite()) || d.norm() == 0.0 {
                return Err(format!(
                    "direction {},{},{}: finite and not zero",
                    d.x, d.y, d.z
                ));
            }
        }
        Ok(())
    }
}

/// Distance from `s` to the nearest whole number, in `[0, 1/2]`.
#[inline]
pub fn frac_distance(s: f64) -> f64 {
    (s - s.round()).abs()
}

/// The reflection-line angle `θ ∈ (−π, π]` of a unit view ray `d` reflected in a unit
/// normal `n`, around the axis of the orthonormal frame `(e1, e2, axis)`.
#[inline]
pub fn reflection_angle(
    d: &Vector3<f64>,
    n: &Vector3<f64>,
    e1: &Vector3<f64>,
    e2: &Vector3<f64>,
) -> f64 {
    let r = d - n * (2.0 * d.dot(n));
    r.dot(e2).atan2(r.dot(e1))
}

/// Parallel linear lights (camera or world space, all vectors unit and `e ⊥ m`, `t = m × e`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightLines {
    /// A point of light 0.
    pub a0: Vector3<f64>,
    /// Direction of every light.
    pub e: Vector3<f64>,
    /// Unit normal of the lights' plane.
    pub m: Vector3<f64>,
    /// Direction across the lights in their plane, `m × e`.
    pub t: Vector3<f64>,
    /// Spacing of the lights along `t`.
    pub spacing: f64,
}

/// Below this `|N × E|` the normal line is taken as parallel to the lights: the skew-line
/// formula divides by it, and at 10⁻⁹ its rounding error (about 10⁻¹⁶ / 10⁻⁹ relative) is still
/// far below a pixel's worth of change.
const PARALLEL_SINE: f64 = 1e-9;

impl LightLines {
    /// The highlight parameter of point `p` with unit normal `n`: the continuous light index
    /// `t` whose nearest whole number is the nearest light (NaN where the normal line is
    /// parallel to the light plane), and the distance from the normal line to the nearest
    /// light (module documentation).
    pub fn distance(&self, p: &Vector3<f64>, n: &Vector3<f64>) -> (f64, f64) {
        let q = self.a0 - p;
        let w = n.cross(&self.e);
        let sine = w.norm();
        if sine < PARALLEL_SINE {
            let along = q.dot(&self.t) / self.spacing;
            let across = self.spacing * frac_distance(along);
            return (-along, across.hypot(q.dot(&self.m)));
        }
        let d0 = q.dot(&w) / sine;
        let delta = self.spacing * n.dot(&self.m) / sine;
        if delta.abs() <= f64::MIN_POSITIVE * d0.abs().max(1.0) {
            return (f64::NAN, d0.abs());
        }
        let t = -d0 / delta;
        (t, delta.abs() * frac_distance(t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance between the lines `p + λ n` and `a + μ e` by minimizing over a fine grid of
    /// `λ` with `μ` solved exactly: an independent check of the closed form.
    fn brute_line_distance(
        p: &Vector3<f64>,
        n: &Vector3<f64>,
        a: &Vector3<f64>,
        e: &Vector3<f64>,
    ) -> f64 {
        let mut best = f64::INFINITY;
        for i in -200_000..=200_000 {
            let x = p + n * (f64::from(i) * 1e-4);
            let v = x - a;
            let perp = v - e * v.dot(e);
            best = best.min(perp.norm());
        }
        best
    }

    #[test]
    fn highlight_distance_is_the_distance_to_the_nearest_light_line() {
        let lights = LightLines {
            a0: Vector3::new(0.0, 0.0, 3.0),
            e: Vector3::y(),
            m: Vector3::z(),
            t: Vector3::z().cross(&Vector3::y()),
            spacing: 0.5,
        };
        for (p, n) in [
            (
                Vector3::new(0.1, 0.2, 0.0),
                Vector3::new(0.3, 0.1, 1.0).normalize(),
            ),
            (
                Vector3::new(-0.7, 0.0, 0.4),
                Vector3::new(-0.5, 0.4, 0.7).normalize(),
            ),
            (Vector3::new(0.0, 0.0, 0.0), Vector3::z()),
        ] {
            let (t, d) = lights.distance(&p, &n);
            let k = t.round();
            let a = lights.a0 + lights.t * (k * lights.spacing);
            let brute = (-3..=3)
                .map(|j| {
                    let a = lights.a0 + lights.t * ((k + f64::from(j)) * lights.spacing);
                    brute_line_distance(&p, &n, &a, &lights.e)
                })
                .fold(f64::INFINITY, f64::min);
            // The grid step 10⁻⁴ along the normal line bounds the brute force's excess.
            assert!(
                (d - brute).abs() < 1e-4,
                "{d} vs {brute} (light {k}, {a:?})"
            );
        }
        // A point right under light 2, normal facing the plane: on the highlight line.
        let p = Vector3::new(0.0, 0.0, 0.0) - lights.t * 1.0;
        let (t, d) = lights.distance(&p, &Vector3::z());
        assert!((t - -2.0).abs() < 1e-12 && d < 1e-12, "{t} {d}");
    }

    #[test]
    fn validation_names_the_field() {
        assert!(Shading::REFLECTION.validate().is_ok());
        let bad = Shading::Reflection {
            stripes: 0,
            direction: None,
            width: 0.5,
        };
        assert!(bad.validate().unwrap_err().contains("stripes 0"));
        let bad = Shading::Isophotes {
            bands: 4,
            light: Some(Vector3::zeros()),
            width: 0.5,
        };
        assert!(bad.validate().unwrap_err().contains("direction"));
        let bad = Shading::Highlight {
            lines: 4,
            direction: None,
            width: 1.5,
        };
        assert!(bad.validate().unwrap_err().contains("width 1.5"));
    }
}

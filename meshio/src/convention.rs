//! The conventions written mesh files follow, so that other tools read them as their users
//! expect (`docs/conventions.md`, "Mesh files"):
//!
//! * **Curvature** ([`Curvature`], [`CURVATURE_CONVENTION`]): libigl's, trimesh's and MeshLab's.
//!   The mean curvature `H = (κ1 + κ2)/2` is positive where the surface bends **away from** its
//!   normal: the unit sphere with outward normals has `H = +1`, `K = κ1 κ2 = +1`, and the
//!   principal curvatures are ordered `κ1 ≥ κ2`. The workbench computes internally with the
//!   opposite sign of `H` (`docs/conventions.md`, "Geometry": `κn > 0` where the surface bends
//!   towards `n`, `H = −1` on that sphere); [`Curvature::from_internal`] is the one place the
//!   sign changes. `K` is the same in both (it is a product of two principal curvatures, and
//!   both change sign).
//! * **Colours**: [`crate::RawMesh::colors`] are linear RGB; PLY, OBJ and OFF store them
//!   sRGB-encoded ([`crate::srgb`]), the way every viewer reads those formats; glTF stores
//!   them linear, as its specification says `COLOR_0` is.
//! * **Up axis** ([`UpAxis`]): the workbench's data have `z` up; glTF is `y` up, so its writer
//!   turns the data's `z` into glTF's `y` unless told the data are `y` up already.
//! * **Provenance**: every written file names its generator ([`GENERATOR`]) and, where it holds
//!   curvature or colours by curvature, the curvature convention, in the format's own place
//!   for it (PLY `comment`, OBJ and OFF `#` lines, glTF `asset.generator` and `extras`).

use std::fmt;
use std::str::FromStr;

/// The `generator` of every file written: the workbench's name and version, not the crate's
/// (`meshio` is also a well-known Python library's name).
pub const GENERATOR: &str = concat!("surface-workbench ", env!("CARGO_PKG_VERSION"));

/// The curvature convention as one line, written into every file that holds curvature.
pub const CURVATURE_CONVENTION: &str = "curvature convention: libigl/trimesh/MeshLab, H = (k1 + k2)/2 > 0 where the surface bends away from its normal (unit sphere with outward normals: K = +1, H = +1), k1 >= k2";

/// The colour encoding of PLY, OBJ and OFF files, as one line.
pub const SRGB_COLOURS: &str = "vertex colours: sRGB-encoded";

/// Per-vertex curvature in the exported convention (module docs): one value per vertex each.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Curvature {
    /// Gaussian curvature `K = κ1 κ2`.
    pub gaussian: Vec<f64>,
    /// Mean curvature `H = (κ1 + κ2)/2`, positive on a sphere with outward normals.
    pub mean: Vec<f64>,
    /// The unit principal directions `[d1, d2]` of `κ1 ≥ κ2` at each vertex, when known
    /// (`d2 = n × d1`; at an umbilic any orthonormal pair). Written by PLY as `pd1x pd1y pd1z
    /// pd2x pd2y pd2z` (libigl's `PD1`, `PD2`) and by glTF as `_PRINCIPAL_DIRECTION_1`,
    /// `_PRINCIPAL_DIRECTION_2`.
    pub directions: Option<Vec<[nalgebra::Vector3<f64>; 2]>>,
}

impl Curvature {
    /// From the workbench's internal values (`docs/conventions.md`, "Geometry": `H = −1` on the
    /// unit sphere with outward normals): `K` kept, `H` negated.
    pub fn from_internal(gaussian: Vec<f64>, mut mean: Vec<f64>) -> Self {
        for h in &mut mean {
            *h = -*h;
        }
        Curvature {
            gaussian,
            mean,
            directions: None,
        }
    }

    /// From values already in the exported convention, without directions.
    pub fn from_exported(gaussian: Vec<f64>, mean: Vec<f64>) -> Self {
        Curvature {
            gaussian,
            mean,
            directions: None,
        }
    }

    /// These values with the principal directions `directions` (one pair per vertex).
    pub fn with_directions(mut self, directions: Vec<[nalgebra::Vector3<f64>; 2]>) -> Self {
        self.directions = Some(directions);
        self
    }

    /// Number of vertices.
    pub fn len(&self) -> usize {
        self.gaussian.len()
    }

    /// True when there are no vertices.
    pub fn is_empty(&self) -> bool {
        self.gaussian.is_empty()
    }

    /// The principal curvatures `[κ1, κ2]`, `κ1 ≥ κ2`, of vertex `i`: the roots of
    /// `κ² − 2Hκ + K = 0`, `κ = H ± √(H² − K)`. `H² − K = ((κ1 − κ2)/2)² ≥ 0` for exact values;
    /// rounding can make it slightly negative at an umbilic, where both are `H`. `None` when
    /// `i` is out of range.
    pub fn principal(&self, i: usize) -> Option<[f64; 2]> {
        let (k, h) = (*self.gaussian.get(i)?, *self.mean.get(i)?);
        let d = (h * h - k).max(0.0).sqrt();
        Some([h + d, h - d])
    }
}

/// How far a model's curvatures may lie from `1/size` (mean) and `1/size²` (Gaussian) for the
/// scale check [`curvature_scale_fits_f32`]: features a thousandth of the model's size have
/// a Gaussian curvature a million times the model's, and the check leaves that much room on
/// both sides of the 32-bit float range.
pub const CURVATURE_HEADROOM: f64 = 1e6;

/// Whether the curvature of a model of `size` (its largest bounding-box side) can be stored as
/// 32-bit floats (PLY `float`, glTF `FLOAT`): its Gaussian curvature is about `1/size²` and must
/// lie, with [`CURVATURE_HEADROOM`] on both sides, within the positive normal `f32` range.
/// Known before a fit, so that a run whose curvature could not be written is refused before
/// its work; the error says why and what to do. A size of zero (a single point) passes: its
/// curvature is zero.
pub fn curvature_scale_fits_f32(size: f64) -> Result<(), String> {
    if size == 0.0 {
        return Ok(());
    }
    let k = 1.0 / (size * size);
    let (lo, hi) = (
        f64::from(f32::MIN_POSITIVE) * CURVATURE_HEADROOM,
        f64::from(f32::MAX) / CURVATURE_HEADROOM,
    );
    if k.is_finite() && (lo..=hi).contains(&k) {
        return Ok(());
    }
    Err(format!(
        "the model's size is {size:.3e}, so its Gaussian curvature is about 1/size² = {k:.3e}, outside what this format's 32-bit floats store with room for its features ({lo:.1e} to {hi:.1e}: sizes {:.1e} to {:.1e}); write a format without curvature (.obj, .off, .stl) or rescale the model",
        1.0 / hi.sqrt(),
        1.0 / lo.sqrt()
    ))
}

/// What the vertex colours show: a colour map of a per-vertex quantity over a range, recorded
/// in the file (glTF `extras`, PLY/OBJ/OFF comments) so a reader can tell colour from value.
#[derive(Clone, Debug, PartialEq)]
pub struct ColorMap {
    /// The quantity mapped (`"gaussian_curvature"`).
    pub quantity: String,
    /// The map's name (`"diverging"`: blue–grey–red, Moreland's cool to warm).
    pub map: String,
    /// The value shown by the map's first colour (values below it get that colour).
    pub min: f64,
    /// The value shown by the map's last colour (values above it get that colour).
    pub max: f64,
}

impl ColorMap {
    /// The map as one line for a comment.
    pub fn describe(&self) -> String {
        format!(
            "colour map: {} of {} over [{:e}, {:e}] (saturating outside)",
            self.map, self.quantity, self.min, self.max
        )
    }
}

/// The data's up axis, for formats that fix one (glTF is `y` up).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum UpAxis {
    /// `z` is up (the workbench's data): glTF's writer turns it into glTF's `y`.
    #[default]
    Z,
    /// `y` is up already: written unchanged.
    Y,
}

impl UpAxis {
    /// Every value, for messages and `--help`.
    pub const ALL: [UpAxis; 2] = [UpAxis::Z, UpAxis::Y];

    /// `"z"` or `"y"`.
    pub fn name(self) -> &'static str {
        match self {
            UpAxis::Z => "z",
            UpAxis::Y => "y",
        }
    }

    /// The data's point `(x, y, z)` in glTF's `y`-up frame: unchanged for [`UpAxis::Y`]; for
    /// [`UpAxis::Z`] the rotation by −90° about `x`, `(x, y, z) ↦ (x, z, −y)` (data `z` becomes
    /// glTF `y`, data `y` becomes glTF `−z`; a rotation, so normals turn the same way and
    /// orientation is kept).
    pub fn to_gltf(self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        match self {
            UpAxis::Y => [x, y, z],
            UpAxis::Z => [x, z, -y],
        }
    }

    /// The inverse of [`UpAxis::to_gltf`]: a glTF point in the data's frame.
    pub fn from_gltf(self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        match self {
            UpAxis::Y => [x, y, z],
            UpAxis::Z => [x, -z, y],
        }
    }
}

impl fmt::Display for UpAxis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for UpAxis {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "z" | "Z" => Ok(UpAxis::Z),
            "y" | "Y" => Ok(UpAxis::Y),
            other => Err(format!("`{other}` is not an up axis (y or z)")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rounding of one square root and a few products of values near 1.
    const PRINCIPAL_TOLERANCE: f64 = 1e-12;

    #[test]
    fn the_unit_sphere_exports_positive_mean_curvature() {
        // Internally H = −1 on the unit sphere with outward normals.
        let c = Curvature::from_internal(vec![1.0], vec![-1.0]);
        assert_eq!(c.gaussian, vec![1.0]);
        assert_eq!(c.mean, vec![1.0]);
        let [k1, k2] = c.principal(0).unwrap_or([f64::NAN; 2]);
        assert!((k1 - 1.0).abs() < PRINCIPAL_TOLERANCE && (k2 - 1.0).abs() < PRINCIPAL_TOLERANCE);
    }

    #[test]
    fn principal_curvatures_are_ordered_and_reproduce_k_and_h() {
        // A saddle κ = (3, −2) and a cylinder of radius 1/2 (κ = (2, 0)), exported.
        for (a, b) in [(3.0, -2.0), (2.0, 0.0), (-0.5, -4.0)] {
            let c = Curvature {
                gaussian: vec![a * b],
                mean: vec![0.5 * (a + b)],
                directions: None,
            };
            let [k1, k2] = c.principal(0).unwrap_or([f64::NAN; 2]);
            assert!(k1 >= k2);
            assert!(
                (k1 - f64::max(a, b)).abs() < PRINCIPAL_TOLERANCE,
                "{k1} vs {a}, {b}"
            );
            assert!(
                (k2 - f64::min(a, b)).abs() < PRINCIPAL_TOLERANCE,
                "{k2} vs {a}, {b}"
            );
        }
        assert_eq!(Curvature::default().principal(0), None);
    }

    #[test]
    fn the_scale_check_refuses_curvature_no_float_holds() {
        assert!(curvature_scale_fits_f32(1.0).is_ok());
        assert!(curvature_scale_fits_f32(1e-12).is_ok());
        assert!(curvature_scale_fits_f32(1e12).is_ok());
        assert!(curvature_scale_fits_f32(0.0).is_ok());
        // The case that used to fail after the whole fit: K ~ 1e308.
        let e = curvature_scale_fits_f32(1e-154).err().unwrap_or_default();
        assert!(e.contains("1.000e-154") && e.contains(".obj"), "{e}");
        assert!(curvature_scale_fits_f32(1e100).is_err());
    }

    #[test]
    fn z_up_turns_into_gltf_y_up_and_back() {
        assert_eq!(UpAxis::Z.to_gltf([0.0, 0.0, 1.0]), [0.0, 1.0, 0.0]);
        assert_eq!(UpAxis::Z.to_gltf([0.0, 1.0, 0.0]), [0.0, 0.0, -1.0]);
        assert_eq!(UpAxis::Z.to_gltf([1.0, 0.0, 0.0]), [1.0, 0.0, 0.0]);
        let p = [0.25, -2.0, 7.5];
        assert_eq!(UpAxis::Z.from_gltf(UpAxis::Z.to_gltf(p)), p);
        assert_eq!(UpAxis::Y.to_gltf(p), p);
        assert_eq!("y".parse::<UpAxis>(), Ok(UpAxis::Y));
        assert!("x".parse::<UpAxis>().is_err());
    }
}

//! The seed's Examples 1–5 (`examples/example*.sh`) run with the test binary into a temporary
//! directory; every picture must have the examples' size and show what its script says it
//! draws:
//!
//! * Example 1, the Shirman–Séquin surface over the octahedron shaded in the uniform material
//!   (`mat0`): one hue, the material's, under a continuum of shades;
//! * Example 2, the mesh in wire frame: line pixels of the wire colour with background between
//!   them, nothing else;
//! * Example 3, the same surface coloured by its Gaussian curvature (`kcolor`): the same
//!   silhouette as Example 1, every pixel a colour of the diverging map, spread over its range;
//! * Example 4, the triangles of Example 3 written once and read twice: the two pictures are
//!   Examples 3 and 1, byte for byte;
//! * Example 5, Nielson's interpolant sampled by `fit` itself, shaded: the material under
//!   shades, Example 1's silhouette (both interpolate the same vertices and normals) but not
//!   Example 1's picture.
//!
//! Colours are compared in linear RGB (the pictures are sRGB): shading multiplies a colour by a
//! light factor and adds a white specular term, which leaves its hue as it is, so a shaded pixel
//! shows the hue of its colour (up to the 8-bit rounding), and its saturation
//! `(max − min) / max` as it is or, under a highlight, less.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use std::collections::BTreeSet;
use std::path::Path;
use std::process::Command;

/// The examples' picture size (`testbed render`'s default).
const SIZE: (u32, u32) = (400, 300);

/// The background of both `render` (linear white) and `wire` (a white canvas).
const BACKGROUND: [u8; 3] = [255, 255, 255];

/// The pixels the fitted octahedron covers in Examples 1, 3 and 5 (the camera as near as keeps
/// every vertex in the middle 90% of the width and the height, `render::Camera::framing_points`):
/// measured 52 457 (Examples 1 and 3) and 52 555 (Example 5), 44% of the picture (32 018 and
/// 31 721 when the camera was set back by the bounding box's sphere); ±12% lets the framing or
/// the surface move a little, not the object go missing or fill the frame.
const OBJECT_PIXELS: std::ops::RangeInclusive<usize> = 46_000..=59_000;

/// Pixels whose linear chroma `max − min` is below this have no hue worth reading: near the
/// shadows an 8-bit step is a tenth of their chroma and turns their hue by several degrees.
/// Above it, the hues measured stay within 3.9° of their colour's (the material in Examples 1
/// and 5) and 2.5° of the map's (Example 3).
const MIN_CHROMA: f64 = 0.02;

/// A pixel of chroma at least [`MIN_CHROMA`] has its colour's hue within this many degrees:
/// 8-bit rounding measured at most 3.9° (above). It keeps the material's hues (219.2° ± 6°)
/// apart from the diverging map's blue half (232.2°–236.4°, less 6°) and far from its red half
/// (348.5°–357.6°).
const HUE_TOL: f64 = 6.0;

/// How far beyond the red half's hues (348.4°–357.6°) a dark pixel of its saturated end may
/// read (see `check_curvature_colours`): 340.1° and 0.0° measured, so 8.3° and 2.4° beyond;
/// 12.5° leaves room for rounding and stays far from every other hue of the picture.
const DARK_END_HUE_TOL: f64 = 12.5;

/// At least this fraction of a shaded object's pixels have a hue to check (chroma ≥
/// [`MIN_CHROMA`]): measured 99.4% in Examples 1 and 5; a check of the hues of a few pixels
/// would say nothing.
const MIN_CHROMATIC: f64 = 0.95;

/// The same for Example 3's curvature colours: Piper's tangent rule (Examples 1, 3 and 4 since
/// they run it) leaves the middle of each octant nearly flat, K ≈ 0, which the diverging map
/// draws grey (no hue): measured 78.1% (100% with the `chord` curves they ran before).
const MIN_CHROMATIC_K: f64 = 0.7;

/// A shaded picture has at least this many distinct object colours: a curved surface under two
/// lights and a highlight shades continuously (measured 812 in Example 1, 805 in Example 5,
/// 13 741 in Example 3); an unlit, uniformly coloured object would have one.
const MIN_SHADES: usize = 100;

/// The wire frame's line pixels: the octahedron's 12 edges, each drawn as a one-pixel line as
/// long as its projection (about 130 pixels each at this size): measured 1 591 with the
/// camera fitted to the vertices (1 179 when it was set back by the bounding box's sphere);
/// ±15%.
const WIRE_PIXELS: std::ops::RangeInclusive<usize> = 1_350..=1_830;

/// A wire frame covers at most this fraction of its lines' bounding box (measured 3.5%); a
/// filled picture covers most of its box (Example 1: 76%).
const WIRE_FILL_MAX: f64 = 0.10;

/// The middle row of the wire frame crosses at least this many separate lines, with background
/// between them: the silhouette twice and the interior edges (measured 5).
const WIRE_CROSSINGS: usize = 4;

/// The curvature colours spread over the map: the 5th percentile of the pixels' map coordinate
/// (read from their saturation, below) is below [`SPREAD_LOW`] and the 95th above
/// [`SPREAD_HIGH`]. Measured 0.006 and 0.736 with Piper's tangent rule (0.164 and 0.934 with
/// `chord` curves): the colour range is the 95% quantile of |K|
/// (`render::colors::ROBUST_QUANTILE`), so the most curved parts reach the saturated end while
/// the flatter face centres stay pale; Piper's curvature sits in narrow bands along the edges,
/// so fewer pixels are saturated.
const SPREAD_LOW: f64 = 0.3;
/// See [`SPREAD_LOW`].
const SPREAD_HIGH: f64 = 0.65;

/// Example 5's silhouette against Example 1's, intersection over union: both surfaces
/// interpolate the octahedron's vertices and normals with G1 surfaces, so they overlap closely;
/// a different object or framing would not. Measured 0.991 when Example 1 ran `chord` curves,
/// 0.883 with Piper's tangent rule, whose curves a ninth longer than the projection's round
/// the octants differently from Nielson's.
const SILHOUETTE_IOU: f64 = 0.85;

/// At least this fraction of Example 5's object pixels differ from Example 1's: another surface,
/// not Example 1 again (measured 66%).
const MIN_DIFFERENT: f64 = 0.10;

/// A decoded picture.
struct Picture {
    name: String,
    width: usize,
    rgb: Vec<[u8; 3]>,
}

impl Picture {
    fn read(path: &Path) -> Picture {
        let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let decoder = png::Decoder::new(std::io::BufReader::new(file));
        let mut reader = decoder.read_info().expect("a PNG");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("a frame");
        assert_eq!((info.width, info.height), SIZE, "{}", path.display());
        assert_eq!(
            (info.color_type, info.bit_depth),
            (png::ColorType::Rgb, png::BitDepth::Eight),
            "{}",
            path.display()
        );
        let rgb: Vec<[u8; 3]> = buf[..info.buffer_size()]
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        assert_eq!(rgb[0], BACKGROUND, "{name}: the corner is background");
        Picture {
            name,
            width: info.width as usize,
            rgb,
        }
    }

    /// True where the picture is not background.
    fn mask(&self) -> Vec<bool> {
        self.rgb.iter().map(|p| *p != BACKGROUND).collect()
    }

    fn object(&self) -> impl Iterator<Item = [u8; 3]> + '_ {
        self.rgb.iter().copied().filter(|p| *p != BACKGROUND)
    }
}

/// sRGB byte to linear.
fn linear(c: u8) -> f64 {
    let c = f64::from(c) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Hue (degrees), chroma `max − min` and saturation `(max − min) / max` of a linear colour.
fn hcs(l: [f64; 3]) -> (f64, f64, f64) {
    let max = l[0].max(l[1]).max(l[2]);
    let min = l[0].min(l[1]).min(l[2]);
    let c = max - min;
    if c <= 0.0 {
        return (f64::NAN, 0.0, 0.0);
    }
    let h = if max == l[0] {
        ((l[1] - l[2]) / c).rem_euclid(6.0)
    } else if max == l[1] {
        (l[2] - l[0]) / c + 2.0
    } else {
        (l[0] - l[1]) / c + 4.0
    };
    (h * 60.0, c, c / max)
}

fn pixel_hcs(p: [u8; 3]) -> (f64, f64, f64) {
    hcs(p.map(linear))
}

fn colour_hcs(c: [f32; 3]) -> (f64, f64, f64) {
    hcs(c.map(f64::from))
}

/// The hue of pixels whose chroma is at least [`MIN_CHROMA`], after checking that at least
/// `min_fraction` of the object's pixels have one.
fn hues(pic: &Picture, min_fraction: f64) -> Vec<f64> {
    let object = pic.object().count();
    let hues: Vec<f64> = pic
        .object()
        .map(pixel_hcs)
        .filter(|(_, c, _)| *c >= MIN_CHROMA)
        .map(|(h, _, _)| h)
        .collect();
    assert!(
        hues.len() as f64 >= min_fraction * object as f64,
        "{}: only {} of {object} object pixels have a hue",
        pic.name,
        hues.len()
    );
    hues
}

/// Distance between two hues on the circle.
fn hue_distance(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    d.min(360.0 - d)
}

/// `q` quantile by nearest rank of `values` (sorted here).
fn quantile(values: &mut [f64], q: f64) -> f64 {
    values.sort_by(f64::total_cmp);
    values[((values.len() - 1) as f64 * q).round() as usize]
}

fn check_object_size(pic: &Picture) {
    let n = pic.object().count();
    assert!(
        OBJECT_PIXELS.contains(&n),
        "{}: {n} object pixels, expected {OBJECT_PIXELS:?}",
        pic.name
    );
}

/// Example 1's content: the surface in the uniform material, shaded.
fn check_material_shading(pic: &Picture) {
    check_object_size(pic);
    let want = colour_hcs(render::colors::MATERIAL).0;
    for h in hues(pic, MIN_CHROMATIC) {
        assert!(
            hue_distance(h, want) <= HUE_TOL,
            "{}: hue {h:.1}° is not the material's {want:.1}°",
            pic.name
        );
    }
    let shades: BTreeSet<[u8; 3]> = pic.object().collect();
    assert!(
        shades.len() >= MIN_SHADES,
        "{}: {} shades",
        pic.name,
        shades.len()
    );
}

/// The diverging map's hue and saturation at `t` in `[-1, 1]` (the kcolor filter's coordinate).
fn map_at(t: f64) -> (f64, f64) {
    let (h, _, s) = colour_hcs(render::colors::diverging(t, 1.0));
    (h, s)
}

/// The hue range of the map's half from `t` to `±1` (hue is monotone along each half).
fn half_hues(from: f64, to: f64) -> (f64, f64) {
    let (a, b) = (map_at(from).0, map_at(to).0);
    (a.min(b), a.max(b))
}

/// The map coordinate `t ∈ [0, 1]` on the red half whose saturation is `s` (saturation grows
/// with `t` there), by bisection.
fn red_coordinate(s: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if map_at(mid).1 < s {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Example 3's content: the curvature colours of the diverging map, spread over it.
fn check_curvature_colours(pic: &Picture) {
    check_object_size(pic);
    // The map's two halves, from just off its grey centre (whose hue is undefined) to the ends.
    let near_zero = 0.02;
    let red = half_hues(near_zero, 1.0);
    let blue = half_hues(-near_zero, -1.0);
    let on = |h: f64, (lo, hi): (f64, f64)| h >= lo - HUE_TOL && h <= hi + HUE_TOL;
    let material = colour_hcs(render::colors::MATERIAL).0;
    let (mut reds, mut blues) = (0, 0);
    let mut off = Vec::new();
    for h in hues(pic, MIN_CHROMATIC_K) {
        assert!(
            hue_distance(h, material) > HUE_TOL,
            "{}: hue {h:.1}° is the uniform material's",
            pic.name
        );
        if on(h, red) {
            reds += 1;
        } else if on(h, blue) {
            blues += 1;
        } else {
            off.push(h);
        }
    }
    // The map's saturated red end shaded dark: its small green and blue parts round in 8 bits
    // and turn the hue by up to 12° either way (measured 340.1°–0.0° on 2 039 of 36 258 pixels
    // of Piper's octahedron, whose curvature reaches the clamp along the edges); nothing else
    // may be off the map.
    let centre = 0.5 * (red.0 + red.1);
    let dark_end = |h: f64| hue_distance(h, centre) <= 0.5 * (red.1 - red.0) + DARK_END_HUE_TOL;
    let stray: Vec<f64> = off.iter().copied().filter(|h| !dark_end(*h)).collect();
    eprintln!(
        "{}: {} pixels at the map's dark red end, {} off the map",
        pic.name,
        off.len() - stray.len(),
        stray.len()
    );
    assert!(
        stray.is_empty(),
        "{}: {} hues off the diverging map ({red:?}, {blue:?}), e.g. {:?}",
        pic.name,
        stray.len(),
        stray.first()
    );
    // The surface over the octahedron is convex: K > 0, the red half only (measured: no
    // pixel of the blue half).
    assert_eq!(blues, 0, "{}: {reds} red, {blues} blue", pic.name);
    // Spread: the pixels' map coordinates from their saturation (a highlight only lowers it,
    // so a high coordinate is never overstated).
    let mut t: Vec<f64> = pic
        .object()
        .map(|p| red_coordinate(pixel_hcs(p).2))
        .collect();
    let (low, high) = (quantile(&mut t, 0.05), quantile(&mut t, 0.95));
    eprintln!(
        "{}: map coordinate 5% {low:.3}, 95% {high:.3}; {reds} pixels on the red half",
        pic.name
    );
    assert!(
        low < SPREAD_LOW && high > SPREAD_HIGH,
        "{}: the curvature colours span only {low:.3}..{high:.3} of the map",
        pic.name
    );
}

/// Runs the examples `which` into one temporary directory (they write different files).
fn run_examples(which: &[usize]) -> tempfile::TempDir {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let dir = tempfile::tempdir().expect("temp dir");
    for n in which {
        let status = Command::new("bash")
            .arg(root.join(format!("examples/example{n}.sh")))
            .arg(dir.path())
            .env("TESTBED", env!("CARGO_BIN_EXE_testbed"))
            .status()
            .expect("bash runs");
        assert!(status.success(), "example {n} failed");
    }
    dir
}

fn picture(dir: &tempfile::TempDir, name: &str) -> Picture {
    Picture::read(&dir.path().join(name))
}

#[test]
fn example1_shaded() {
    let dir = run_examples(&[1]);
    check_material_shading(&picture(&dir, "example1.png"));
}

#[test]
fn example2_wire_frame() {
    let dir = run_examples(&[2]);
    let pic = picture(&dir, "example2.png");
    let wire = render::shade::WIRE_COLOUR;
    let colours: BTreeSet<[u8; 3]> = pic.rgb.iter().copied().collect();
    assert_eq!(
        colours,
        BTreeSet::from([wire, BACKGROUND]),
        "lines and background only"
    );
    let lines: Vec<usize> = (0..pic.rgb.len()).filter(|&i| pic.rgb[i] == wire).collect();
    assert!(
        WIRE_PIXELS.contains(&lines.len()),
        "{} line pixels, expected {WIRE_PIXELS:?}",
        lines.len()
    );
    let w = pic.width;
    let (xs, ys): (Vec<usize>, Vec<usize>) = lines.iter().map(|i| (i % w, i / w)).unzip();
    let bx = xs.iter().max().unwrap() - xs.iter().min().unwrap() + 1;
    let by = ys.iter().max().unwrap() - ys.iter().min().unwrap() + 1;
    let fill = lines.len() as f64 / (bx * by) as f64;
    assert!(fill <= WIRE_FILL_MAX, "lines fill {fill:.3} of their box");
    // The middle row: separate lines with background between them.
    let row = &pic.rgb[(SIZE.1 as usize / 2) * w..(SIZE.1 as usize / 2 + 1) * w];
    let crossings = row
        .windows(2)
        .filter(|p| p[0] == BACKGROUND && p[1] == wire)
        .count()
        + usize::from(row[0] == wire);
    assert!(
        crossings >= WIRE_CROSSINGS,
        "the middle row crosses {crossings} lines"
    );
}

#[test]
fn example3_gaussian_curvature() {
    let dir = run_examples(&[1, 3]);
    let (shaded, kg) = (picture(&dir, "example1.png"), picture(&dir, "example3.png"));
    check_curvature_colours(&kg);
    // The same surface and tessellation as Example 1, only coloured otherwise: the same
    // silhouette, and every pixel of it different from the uniform material's.
    assert!(kg.mask() == shaded.mask(), "the silhouettes differ");
    let same = kg
        .rgb
        .iter()
        .zip(&shaded.rgb)
        .filter(|(a, b)| **a != BACKGROUND && a == b)
        .count();
    assert_eq!(same, 0, "{same} object pixels are Example 1's");
}

#[test]
fn example4_one_file_read_twice() {
    let dir = run_examples(&[1, 3, 4]);
    let (kg, simple) = (
        picture(&dir, "example4-kg.png"),
        picture(&dir, "example4-simple.png"),
    );
    check_curvature_colours(&kg);
    check_material_shading(&simple);
    // The dstruct file keeps the triangles exactly: the pictures drawn from it are those the
    // pipes draw (Examples 3 and 1), byte for byte; and the file is removed after use.
    assert!(
        kg.rgb == picture(&dir, "example3.png").rgb,
        "the kcolor picture is not Example 3's"
    );
    assert!(
        simple.rgb == picture(&dir, "example1.png").rgb,
        "the mat0 picture is not Example 1's"
    );
    assert!(
        !dir.path().join("octa.out").exists(),
        "octa.out left behind"
    );
}

#[test]
fn example5_sampling_fitter() {
    let dir = run_examples(&[1, 5]);
    let (nielson, shaded) = (picture(&dir, "example5.png"), picture(&dir, "example1.png"));
    check_material_shading(&nielson);
    let (a, b) = (nielson.mask(), shaded.mask());
    let both = a.iter().zip(&b).filter(|(x, y)| **x && **y).count();
    let either = a.iter().zip(&b).filter(|(x, y)| **x || **y).count();
    let iou = both as f64 / either as f64;
    assert!(iou >= SILHOUETTE_IOU, "silhouettes overlap {iou:.4}");
    let different = nielson
        .rgb
        .iter()
        .zip(&shaded.rgb)
        .filter(|(x, y)| **x != BACKGROUND && x != y)
        .count();
    let object = nielson.object().count();
    assert!(
        different as f64 >= MIN_DIFFERENT * object as f64,
        "only {different} of {object} pixels differ from Example 1"
    );
}

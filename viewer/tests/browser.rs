//! The page in headless Chromium: no script error in any mode, the object framed with a margin,
//! both diverging hues of K on a torus, stripes in the reflection-line and isophote modes, the
//! line toggles drawn, and linked cameras (a drag over one view turns both, as the hash's turn
//! does). Skipped with a printed reason when Chromium is missing, unless
//! `VIEWER_REQUIRE_BROWSER=1` (then failed).

#![allow(clippy::expect_used)] // test fixtures fail loudly by design

mod common;

use std::path::{Path, PathBuf};

use common::{browser_or_skip, shoot, sphere, torus, Shot};
use viewer::Page;

/// Screenshot size: small enough to be quick in SwiftShader, large enough for 16 stripes.
const SIZE: (usize, usize) = (480, 360);
/// A pixel is background when every channel is at least this (the page is white; antialiased
/// edges and shading are well below).
const BACKGROUND_MIN: u8 = 245;
/// The object's bounding box must stay this many pixels off every edge of the image.
const EDGE_MARGIN_PX: usize = 4;
/// ... and span at least this fraction of the image's smaller side (fitted, not lost).
const MIN_SPAN: f64 = 0.5;
/// Luminance below this is a dark stripe, above [`BRIGHT`] a bright one (stripes are drawn at
/// 0.06 and 0.97 of full scale; shading between them is neither).
const DARK: f64 = 70.0;
/// See [`DARK`].
const BRIGHT: f64 = 190.0;

fn write_page(dir: &Path, name: &str, page: &Page) -> PathBuf {
    let path = dir.join(format!("{name}.html"));
    std::fs::write(&path, page.to_html()).expect("write the page");
    if let Some(keep) = std::env::var_os("VIEWER_SCREENSHOTS") {
        let _ = std::fs::create_dir_all(&keep);
        let _ = std::fs::copy(&path, Path::new(&keep).join(format!("{name}.html")));
    }
    path
}

fn torus_page() -> Page {
    let mut page = Page::new("torus");
    page.add_view(torus("torus R=2 r=0.75", 96, 48, 2.0, 0.75, 8))
        .expect("a valid torus");
    page
}

fn luminance(p: [u8; 3]) -> f64 {
    0.2126 * f64::from(p[0]) + 0.7152 * f64::from(p[1]) + 0.0722 * f64::from(p[2])
}

fn background(p: [u8; 3]) -> bool {
    p.iter().all(|&c| c >= BACKGROUND_MIN)
}

/// The bounding box `(x0, y0, x1, y1)` of the non-background pixels, and their count.
fn object_box(s: &Shot) -> ((usize, usize, usize, usize), usize) {
    let (mut x0, mut y0, mut x1, mut y1, mut n) = (usize::MAX, usize::MAX, 0, 0, 0);
    for y in 0..s.height {
        for x in 0..s.width {
            if !background(s.at(x, y)) {
                x0 = x0.min(x);
                y0 = y0.min(y);
                x1 = x1.max(x);
                y1 = y1.max(y);
                n += 1;
            }
        }
    }
    ((x0, y0, x1, y1), n)
}

/// Dark/bright alternations along row `y` (hysteresis between [`DARK`] and [`BRIGHT`]).
fn transitions(s: &Shot, y: usize) -> usize {
    let mut last: Option<bool> = None;
    let mut count = 0;
    for x in 0..s.width {
        let p = s.at(x, y);
        if background(p) {
            continue;
        }
        let l = luminance(p);
        let now = if l < DARK {
            Some(false)
        } else if l > BRIGHT {
            Some(true)
        } else {
            None
        };
        if let (Some(a), Some(b)) = (last, now) {
            if a != b {
                count += 1;
            }
        }
        if now.is_some() {
            last = now;
        }
    }
    count
}

/// The most transitions along the rows through the middle third of the object.
fn stripes(s: &Shot) -> usize {
    let ((_, y0, _, y1), _) = object_box(s);
    let third = (y1 - y0) / 3;
    (y0 + third..=y1 - third)
        .map(|y| transitions(s, y))
        .max()
        .unwrap_or(0)
}

/// Mean absolute difference per channel between two equal-sized regions `[x, x + w)`.
fn region_difference(a: &Shot, ax: usize, b: &Shot, bx: usize, w: usize) -> f64 {
    let mut sum = 0.0;
    for y in 0..a.height {
        for x in 0..w {
            let (p, q) = (a.at(ax + x, y), b.at(bx + x, y));
            sum += (0..3)
                .map(|c| (f64::from(p[c]) - f64::from(q[c])).abs())
                .sum::<f64>();
        }
    }
    sum / (3 * w * a.height) as f64
}

#[test]
fn every_mode_draws_without_script_errors_and_fits_the_frame() {
    let Some(browser) =
        browser_or_skip("every_mode_draws_without_script_errors_and_fits_the_frame")
    else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let mut page = Page::new("modes");
    page.add_view(sphere("sphere", 64, 32))
        .expect("a valid sphere");
    let path = write_page(dir.path(), "modes", &page);
    for mode in [
        "shaded",
        "K",
        "H",
        "k1",
        "k2",
        "zebra",
        "isophotes",
        "distance",
    ] {
        let shot = shoot(
            &browser,
            &path,
            &format!("mode={mode}&ui=0"),
            SIZE,
            &format!("sphere-{mode}"),
        );
        assert_eq!(shot.status, format!("ready:{mode}"), "mode {mode}");
        let ((x0, y0, x1, y1), n) = object_box(&shot);
        assert!(n > 0, "mode {mode}: nothing drawn");
        assert!(
            x0 >= EDGE_MARGIN_PX
                && y0 >= EDGE_MARGIN_PX
                && x1 + EDGE_MARGIN_PX < shot.width
                && y1 + EDGE_MARGIN_PX < shot.height,
            "mode {mode}: object box {:?} touches the {}×{} frame",
            (x0, y0, x1, y1),
            shot.width,
            shot.height
        );
        let span = (x1 - x0).max(y1 - y0) as f64 / shot.width.min(shot.height) as f64;
        assert!(
            span >= MIN_SPAN,
            "mode {mode}: object spans only {span:.2} of the frame"
        );
    }
    // An unknown mode is reported as an error, not drawn as something else.
    let shot = shoot(&browser, &path, "mode=nonsense", SIZE, "sphere-nonsense");
    assert!(shot.status.starts_with("error:"), "status {}", shot.status);
}

#[test]
fn the_torus_fits_the_frame_from_any_side() {
    let Some(browser) = browser_or_skip("the_torus_fits_the_frame_from_any_side") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write_page(dir.path(), "torus", &torus_page());
    for (k, hash) in ["turn=0", "turn=90&tilt=60", "tilt=-110", "turn=45&tilt=-20"]
        .iter()
        .enumerate()
    {
        let shot = shoot(
            &browser,
            &path,
            &format!("{hash}&ui=0"),
            SIZE,
            &format!("torus-fit-{k}"),
        );
        assert_eq!(shot.status, "ready:shaded", "{hash}");
        let ((x0, y0, x1, y1), _) = object_box(&shot);
        assert!(
            x0 >= EDGE_MARGIN_PX
                && y0 >= EDGE_MARGIN_PX
                && x1 + EDGE_MARGIN_PX < shot.width
                && y1 + EDGE_MARGIN_PX < shot.height,
            "{hash}: object box {:?} touches the frame",
            (x0, y0, x1, y1)
        );
        let span = (x1 - x0).max(y1 - y0) as f64 / shot.width.min(shot.height) as f64;
        assert!(
            span >= MIN_SPAN,
            "{hash}: object spans only {span:.2} of the frame"
        );
    }
}

#[test]
fn gaussian_curvature_on_a_torus_shows_both_diverging_hues() {
    let Some(browser) = browser_or_skip("gaussian_curvature_on_a_torus_shows_both_diverging_hues")
    else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write_page(dir.path(), "torus", &torus_page());
    let shot = shoot(&browser, &path, "mode=K", SIZE, "torus-K");
    assert_eq!(shot.status, "ready:K");
    let ((x0, y0, x1, y1), object) = object_box(&shot);
    let (mut red, mut blue) = (0, 0);
    for y in y0..=y1 {
        for x in x0..=x1 {
            let [r, g, b] = shot.at(x, y).map(i32::from);
            // Hue by channel dominance: the map's ends are (180, 4, 38) and (59, 76, 192).
            if r > b + 50 && r > g + 50 {
                red += 1;
            } else if b > r + 50 && b > g + 30 {
                blue += 1;
            }
        }
    }
    // K > 0 on the outer half of the torus, K < 0 on the inner: each hue covers a good part.
    let (fr, fb) = (red as f64 / object as f64, blue as f64 / object as f64);
    assert!(
        fr > 0.05 && fb > 0.05,
        "reddish {fr:.3}, bluish {fb:.3} of {object} object pixels"
    );
    // The colour bar (bottom right) is shown with its labels.
    let bar = (shot.width - 200..shot.width - 20)
        .filter(|&x| {
            let [r, _, b] = shot.at(x, shot.height - 40);
            r > 150 && b < 100
        })
        .count();
    assert!(bar > 0, "no red end of the colour bar found");
}

#[test]
fn reflection_lines_and_isophotes_show_stripes_shading_does_not() {
    let Some(browser) =
        browser_or_skip("reflection_lines_and_isophotes_show_stripes_shading_does_not")
    else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write_page(dir.path(), "torus", &torus_page());
    let zebra = shoot(
        &browser,
        &path,
        "mode=zebra&boundaries=0&ui=0",
        SIZE,
        "torus-zebra",
    );
    assert_eq!(zebra.status, "ready:zebra");
    let iso = shoot(
        &browser,
        &path,
        "mode=isophotes&boundaries=0&ui=0",
        SIZE,
        "torus-isophotes",
    );
    assert_eq!(iso.status, "ready:isophotes");
    let shaded = shoot(
        &browser,
        &path,
        "mode=shaded&boundaries=0&ui=0",
        SIZE,
        "torus-shaded",
    );
    let (z, i, s) = (stripes(&zebra), stripes(&iso), stripes(&shaded));
    eprintln!("dark/bright transitions along a row: zebra {z}, isophotes {i}, shaded {s}");
    assert!(z >= 10, "reflection lines: only {z} transitions");
    assert!(i >= 6, "isophotes: only {i} transitions");
    assert!(
        s <= 2,
        "shaded: {s} transitions (the row test would not tell stripes)"
    );
}

#[test]
fn line_toggles_draw_boundaries_and_the_data_mesh() {
    let Some(browser) = browser_or_skip("line_toggles_draw_boundaries_and_the_data_mesh") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write_page(dir.path(), "torus", &torus_page());
    let count = |s: &Shot, f: &dyn Fn([u8; 3]) -> bool| {
        (0..s.height)
            .flat_map(|y| (0..s.width).map(move |x| (x, y)))
            .filter(|&(x, y)| f(s.at(x, y)))
            .count()
    };
    let dark = |p: [u8; 3]| luminance(p) < 50.0;
    let blue = |p: [u8; 3]| i32::from(p[2]) > i32::from(p[0]) + 80;
    let none = shoot(&browser, &path, "boundaries=0&ui=0", SIZE, "torus-no-lines");
    let bounds = shoot(
        &browser,
        &path,
        "boundaries=1&ui=0",
        SIZE,
        "torus-boundaries",
    );
    let mesh = shoot(
        &browser,
        &path,
        "boundaries=0&mesh=1&ui=0",
        SIZE,
        "torus-data-mesh",
    );
    let (d0, d1) = (count(&none, &dark), count(&bounds, &dark));
    let (b0, b1) = (count(&none, &blue), count(&mesh, &blue));
    eprintln!("dark pixels {d0} → {d1} with boundaries; blue {b0} → {b1} with the data mesh");
    assert!(d1 > d0 + 500, "boundaries: dark pixels {d0} → {d1}");
    assert!(b1 > b0 + 500, "data mesh: blue pixels {b0} → {b1}");
}

#[test]
fn linked_views_turn_together_by_drag_and_by_hash() {
    let Some(browser) = browser_or_skip("linked_views_turn_together_by_drag_and_by_hash") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let mut page = Page::new("two");
    for title in ["left", "right"] {
        page.add_view(torus(title, 96, 48, 2.0, 0.75, 8))
            .expect("a valid torus");
    }
    let path = write_page(dir.path(), "two", &page);
    let size = (720, 320);
    let half = size.0 / 2;
    let before = shoot(&browser, &path, "ui=0", size, "two-before");
    // 120 px right and 60 down over the left view turns by −60° and tilts by 30° (0.5° a
    // pixel) ...
    let dragged_left = shoot(&browser, &path, "ui=0&drag=0:120:60", size, "two-drag-left");
    // ... as it does over the right view, and as the hash's turn does.
    let dragged_right = shoot(
        &browser,
        &path,
        "ui=0&drag=1:120:60",
        size,
        "two-drag-right",
    );
    let turned = shoot(&browser, &path, "ui=0&turn=-60&tilt=30", size, "two-turn");
    for s in [&before, &dragged_left, &dragged_right, &turned] {
        assert_eq!(s.status, "ready:shaded");
    }
    let halves = |s: &Shot| region_difference(s, 0, s, half, half);
    let moved = region_difference(&before, 0, &dragged_left, 0, half);
    eprintln!(
        "halves differ by {:.3}, {:.3}, {:.3}; the turn changed the left half by {moved:.3}; \
         drag vs hash {:.3}",
        halves(&before),
        halves(&dragged_left),
        halves(&dragged_right),
        region_difference(&dragged_left, 0, &turned, 0, size.0),
    );
    // Same mesh, same camera: the two halves agree to rounding, before and after the turn.
    for s in [&before, &dragged_left, &dragged_right] {
        assert!(halves(s) < 0.5, "halves differ by {:.3}", halves(s));
    }
    // The turn and tilt really changed the picture, and both drags and the hash agree.
    assert!(
        moved > 1.0,
        "the drag changed the left half by only {moved:.3}"
    );
    assert!(region_difference(&dragged_left, 0, &dragged_right, 0, size.0) < 0.5);
    assert!(region_difference(&dragged_left, 0, &turned, 0, size.0) < 0.5);
}

/// The bounding box `(x0, y0, x1, y1)` of the non-background pixels in columns `xs`.
fn box_in(s: &Shot, xs: std::ops::Range<usize>) -> (usize, usize, usize, usize) {
    let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
    for y in 0..s.height {
        for x in xs.clone() {
            if !background(s.at(x, y)) {
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
        }
    }
    (x0, y0, x1, y1)
}

/// The wheel's zoom factor for `delta_y`: `exp(−delta_y · 0.0015)` (page.js's `ZOOM_PER_WHEEL`).
fn wheel_zoom(delta_y: f64) -> f64 {
    (-delta_y * 0.0015).exp()
}

/// Pixels two silhouettes' edges may differ by and still be the same shape moved (rounding of
/// the rasterized edge, one pixel each side).
const EDGE_PX: usize = 2;

/// The wheel zooms every view exactly as the hash's `zoom` does; a shift-drag over one view
/// moves both objects right, rigidly (a translation: no turn, no zoom).
///
/// The pan's size per dragged pixel depends on the view's height when the drag happens, and
/// headless Chromium runs the page's script in a smaller viewport (181 px for a 320 px window)
/// than it takes the screenshot in, so the drag is checked as a rigid move to the right rather
/// than against a hash `pan` of a computed size.
#[test]
fn the_wheel_zooms_and_a_shift_drag_pans_every_view() {
    let Some(browser) = browser_or_skip("the_wheel_zooms_and_a_shift_drag_pans_every_view") else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let mut page = Page::new("two");
    for title in ["left", "right"] {
        page.add_view(torus(title, 96, 48, 2.0, 0.75, 8))
            .expect("a valid torus");
    }
    let path = write_page(dir.path(), "two", &page);
    let size = (720, 320);
    let half = size.0 / 2;
    let before = shoot(&browser, &path, "ui=0", size, "two-before-zoom");
    // Wheel steps of −300 over the right view zoom every view in by exp(0.45).
    let wheeled = shoot(&browser, &path, "ui=0&wheel=1:-300", size, "two-wheel");
    let zoomed = shoot(
        &browser,
        &path,
        &format!("ui=0&zoom={}", wheel_zoom(-300.0)),
        size,
        "two-zoom",
    );
    let dragged = shoot(
        &browser,
        &path,
        "ui=0&drag=0:20:0:pan",
        size,
        "two-pan-drag",
    );
    for s in [&before, &wheeled, &zoomed, &dragged] {
        assert_eq!(s.status, "ready:shaded");
    }
    let halves = |s: &Shot| region_difference(s, 0, s, half, half);
    let zoom_moved = region_difference(&before, 0, &wheeled, 0, size.0);
    let (b, d) = (box_in(&before, 0..half), box_in(&dragged, 0..half));
    let (br, dr) = (
        box_in(&before, half..size.0),
        box_in(&dragged, half..size.0),
    );
    eprintln!(
        "wheel changed the picture by {zoom_moved:.3}, wheel vs hash {:.3}; halves {:.3}, {:.3}; \
         left view {b:?} → {d:?}, right view {br:?} → {dr:?}",
        region_difference(&wheeled, 0, &zoomed, 0, size.0),
        halves(&wheeled),
        halves(&dragged),
    );
    assert!(
        zoom_moved > 1.0,
        "the wheel changed the picture by only {zoom_moved:.3}"
    );
    assert!(region_difference(&wheeled, 0, &zoomed, 0, size.0) < 0.5);
    // Both views follow either gesture.
    for s in [&wheeled, &dragged] {
        assert!(halves(s) < 0.5, "halves differ by {:.3}", halves(s));
    }
    // The pan: both edges move right by the same amount, the rows stay.
    let shift = d.0 as i64 - b.0 as i64;
    assert!(shift > 10, "the pan moved the object by {shift} px");
    assert!((d.2 as i64 - b.2 as i64 - shift).unsigned_abs() as usize <= EDGE_PX);
    assert!(b.1.abs_diff(d.1) <= EDGE_PX && b.3.abs_diff(d.3) <= EDGE_PX);
}

/// The octahedron's eight faces as flat cubic patches, through [`viewer::view_from_patches`]
/// (the path `experiments view` takes for patch files).
fn octahedron_page() -> Page {
    let v = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces = [
        [0, 1, 4],
        [1, 2, 4],
        [2, 3, 4],
        [3, 0, 4],
        [1, 0, 5],
        [2, 1, 5],
        [3, 2, 5],
        [0, 3, 5],
    ];
    let patches: Vec<surface::BezierTriangle> = faces
        .iter()
        .map(|f| {
            surface::BezierTriangle::from_fn(3, |i, j, k| {
                let w = [i as f64 / 3.0, j as f64 / 3.0, k as f64 / 3.0];
                let c = |a: usize| (0..3).map(|m| w[m] * v[f[m]][a]).sum::<f64>();
                nalgebra::Point3::new(c(0), c(1), c(2))
            })
        })
        .collect();
    let mut page = Page::new("octahedron");
    page.add_view(viewer::view_from_patches("octahedron", &patches, 6).expect("tessellates"))
        .expect("a valid view");
    page
}

#[test]
fn patch_views_draw_their_control_nets_and_turn_about_either_up_axis() {
    let Some(browser) =
        browser_or_skip("patch_views_draw_their_control_nets_and_turn_about_either_up_axis")
    else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let path = write_page(dir.path(), "octahedron", &octahedron_page());
    // The nets' colour, 0xd06000, drawn at opacity 0.55 over the grey-blue surface.
    let orange = |p: [u8; 3]| i32::from(p[0]) > i32::from(p[2]) + 60;
    let count = |s: &Shot| {
        (0..s.height)
            .flat_map(|y| (0..s.width).map(move |x| (x, y)))
            .filter(|&(x, y)| orange(s.at(x, y)))
            .count()
    };
    let without = shoot(&browser, &path, "ui=0", SIZE, "octahedron");
    let with = shoot(&browser, &path, "ui=0&nets=1", SIZE, "octahedron-nets");
    assert_eq!(with.status, "ready:shaded");
    let (a, b) = (count(&without), count(&with));
    eprintln!("orange pixels {a} → {b} with the control nets");
    assert!(b > a + 500, "nets: orange pixels {a} → {b}");
    // Either up axis frames the object; a wrong one is an error.
    let y_up = shoot(
        &browser,
        &path,
        "ui=0&up=y&mode=zebra",
        SIZE,
        "octahedron-y-up",
    );
    assert_eq!(y_up.status, "ready:zebra");
    let ((x0, y0, x1, y1), n) = object_box(&y_up);
    assert!(n > 0 && x0 >= EDGE_MARGIN_PX && y0 >= EDGE_MARGIN_PX);
    assert!(x1 + EDGE_MARGIN_PX < y_up.width && y1 + EDGE_MARGIN_PX < y_up.height);
    let bad = shoot(&browser, &path, "up=w", SIZE, "octahedron-bad-up");
    assert!(bad.status.starts_with("error:"), "status {}", bad.status);
}

/// A mesh named `<!--<script>.obj` (issue 43): before, the page's data block kept the `<!--`
/// and `<script`, the HTML parser took the rest of the page as script, and it came up empty.
/// Now the page draws, with the name as its title.
#[test]
fn a_file_named_like_a_comment_and_a_script_does_not_blank_the_page() {
    let Some(browser) =
        browser_or_skip("a_file_named_like_a_comment_and_a_script_does_not_blank_the_page")
    else {
        return;
    };
    let dir = tempfile::tempdir().expect("tempdir");
    let name = "<!--<script>.obj";
    let mut page = Page::new(name);
    page.add_view(sphere(name, 32, 16)).expect("a valid sphere");
    let path = write_page(dir.path(), "hostile", &page);
    let shot = shoot(&browser, &path, "mode=shaded&ui=0", SIZE, "hostile-name");
    assert_eq!(shot.status, "ready:shaded");
    let (_, n) = object_box(&shot);
    assert!(n > 0, "nothing drawn");
}

//! Reflection lines, isophotes and the framing camera against their geometry: stripe counts on
//! a cylinder and rings on a sphere predicted in closed form, the stripe break of a crease
//! against a smooth bend, and every vertex of a disk, a tall cylinder and a sphere inside the
//! framed picture with its margin.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use std::f64::consts::{PI, TAU};

use nalgebra::{Point3, Vector3};
use render::interrogation::{frac_distance, DARK, LIGHT};
use render::shade::FRAME_FILL;
use render::{interrogation_field, render, Camera, Image, RenderMesh, RenderOptions, Shading};

/// A grid mesh of `nu × nv` quads over `[0, 1]²` (two triangles each), point and normal given
/// by `f(u, v)`.
fn grid(nu: usize, nv: usize, f: impl Fn(f64, f64) -> (Point3<f64>, Vector3<f64>)) -> RenderMesh {
    let mut m = RenderMesh::default();
    for i in 0..=nu {
        for j in 0..=nv {
            let (p, n) = f(i as f64 / nu as f64, j as f64 / nv as f64);
            m.positions.push(p);
            m.normals.push(n);
            m.colors.push([0.8; 3]);
        }
    }
    let at = |i: usize, j: usize| i * (nv + 1) + j;
    for i in 0..nu {
        for j in 0..nv {
            m.faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            m.faces.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    m
}

/// The open cylinder `x² + y² = r²`, `|z| ≤ half_height`, its analytic normals, `around`
/// segments round.
fn cylinder(r: f64, half_height: f64, around: usize) -> RenderMesh {
    grid(around, 8, |u, v| {
        let phi = TAU * u;
        let n = Vector3::new(phi.cos(), phi.sin(), 0.0);
        (
            Point3::new(r * phi.cos(), r * phi.sin(), half_height * (2.0 * v - 1.0)),
            n,
        )
    })
}

/// The unit sphere, its analytic normals.
fn sphere(nu: usize, nv: usize) -> RenderMesh {
    grid(nu, nv, |u, v| {
        let (phi, th) = (TAU * u, PI * v);
        let n = Vector3::new(th.sin() * phi.cos(), th.sin() * phi.sin(), th.cos());
        (Point3::from(n), n)
    })
}

/// A flat disk of radius 1 in the xy plane.
fn disk() -> RenderMesh {
    grid(64, 8, |u, v| {
        let phi = TAU * u;
        (Point3::new(v * phi.cos(), v * phi.sin(), 0.0), Vector3::z())
    })
}

/// The camera at `(distance, 0, 0)` looking at the origin, z up: picture columns run along
/// world y, rows along world z.
fn side_camera(distance: f64) -> Camera {
    Camera {
        eye: Point3::new(distance, 0.0, 0.0),
        target: Point3::origin(),
        up: Vector3::z(),
        fov_y_degrees: 30.0,
    }
}

/// Pixels per unit of `tan` off axis for a picture `h` pixels tall and a 30° field.
fn focal(h: u32) -> f64 {
    f64::from(h) * 0.5 / 15f64.to_radians().tan()
}

fn options(w: u32, h: u32, shading: Shading) -> RenderOptions {
    RenderOptions {
        width: w,
        height: h,
        shading,
        ..RenderOptions::default()
    }
}

fn pixel(img: &Image, x: u32, y: u32) -> [u8; 3] {
    let i = 3 * (y * img.width + x) as usize;
    [img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]]
}

/// The sRGB bytes of the light and dark stripe colours (the white background is 255).
fn stripe_bytes() -> (u8, u8) {
    (
        render::shade::to_srgb8(LIGHT[0]),
        render::shade::to_srgb8(DARK[0]),
    )
}

/// Dark (`Some(true)`), light (`Some(false)`) or background (`None`) at a pixel of an
/// interrogation picture.
fn stripe(img: &Image, x: u32, y: u32) -> Option<bool> {
    let (light, dark) = stripe_bytes();
    match pixel(img, x, y)[0] {
        255 => None,
        b if b == light => Some(false),
        b if b == dark => Some(true),
        b => panic!("pixel ({x}, {y}) is neither stripe colour: {b}"),
    }
}

/// Changes between dark and light along a run of stripe values (background skipped).
fn transitions(run: impl Iterator<Item = Option<bool>>) -> usize {
    let seen: Vec<bool> = run.flatten().collect();
    seen.windows(2).filter(|p| p[0] != p[1]).count()
}

/// How many of the stripe borders `k ± width/2` lie strictly between `lo` and `hi`.
fn borders_between(lo: f64, hi: f64, width: f64) -> usize {
    let mut count = 0;
    for k in (lo.floor() as i64 - 1)..=(hi.ceil() as i64 + 1) {
        for b in [k as f64 - width / 2.0, k as f64 + width / 2.0] {
            if b > lo && b < hi {
                count += 1;
            }
        }
    }
    count
}

/// Reflection-line angle on the cylinder of radius `r` seen from `(d, 0, 0)` at the point of
/// polar angle `phi` (z = 0): the mirror image of the direction back to the eye, `−d`, of
/// polar angle `β`, in the normal of polar angle `φ` has polar angle `θ = 2φ − β`, measured
/// from the direction back to the viewer (world x).
fn cylinder_theta(r: f64, d: f64, phi: f64) -> f64 {
    let beta = (-r * phi.sin()).atan2(d - r * phi.cos());
    2.0 * phi - beta
}

/// Polar angle of the point where the ray through column `x` of the middle row of a picture
/// `w × h` from [`side_camera`]`(d)` meets the cylinder of radius `r` (`None`: it misses).
fn cylinder_hit(r: f64, d: f64, w: u32, h: u32, x: u32) -> Option<f64> {
    let t_off = (f64::from(x) + 0.5 - f64::from(w) * 0.5) / focal(h);
    // From (d, 0) along (−1, t_off): (d − t)² + (t_off t)² = r².
    let a = 1.0 + t_off * t_off;
    let disc = d * d - a * (d * d - r * r);
    if disc < 0.0 {
        return None;
    }
    let t = (d - disc.sqrt()) / a;
    Some((t_off * t).atan2(d - t))
}

#[test]
fn reflection_stripes_on_a_cylinder_match_the_mirror_geometry() {
    let (r, d, stripes, width) = (1.0, 6.0, 8u32, 0.5);
    let (w, h) = (400u32, 400u32);
    let mesh = cylinder(r, 2.0, 1440);
    let shading = Shading::Reflection {
        stripes,
        direction: Some(Vector3::z()),
        width,
    };
    let img = render(&mesh, &side_camera(d), &options(w, h, shading)).unwrap();
    std::fs::write("/tmp/interro-cylinder-reflection.png", png(&img)).ok();
    let s_of = |phi: f64| f64::from(stripes) * cylinder_theta(r, d, phi) / TAU;

    // Across the middle row: where the normal is within 60° of the view, the stripes crossed
    // are the borders between s(−60°) and s(60°).
    let limit = 60f64.to_radians();
    let window: Vec<u32> = (0..w)
        .filter(|&x| cylinder_hit(r, d, w, h, x).is_some_and(|phi| phi.abs() <= limit))
        .collect();
    let predicted = borders_between(s_of(-limit), s_of(limit), width);
    let row = h / 2;
    let seen = transitions(window.iter().map(|&x| stripe(&img, x, row)));
    assert_eq!(seen, predicted, "central window, {} columns", window.len());
    assert_eq!(predicted, 12);

    // The whole row: s runs over (−s_max, s_max), θ_max = φ_s + π/2 at the silhouette
    // cos φ_s = r/d. Stripes there are compressed below a pixel, so the count is compared
    // with the per-pixel prediction (the analytic ray hit), which may miss the same ones.
    let phi_s = (r / d).acos();
    let s_max = f64::from(stripes) * (phi_s + PI / 2.0) / TAU;
    let closed = borders_between(-s_max, s_max, width);
    let per_pixel =
        transitions((0..w).map(|x| {
            cylinder_hit(r, d, w, h, x).map(|phi| frac_distance(s_of(phi)) < width / 2.0)
        }));
    let full = transitions((0..w).map(|x| stripe(&img, x, row)));
    eprintln!("cylinder: window {seen} = {predicted}; row {full}, per-pixel {per_pixel}, closed form {closed}");
    assert!(full.abs_diff(per_pixel) <= 2, "{full} vs {per_pixel}");
    assert!(
        per_pixel <= closed && closed - per_pixel <= 4,
        "{per_pixel} vs {closed}"
    );

    // Along the axis (a column): the normal is constant and the view ray's horizontal part
    // too, so θ is constant: no transitions, and the field is flat.
    let field = interrogation_field(&mesh, &side_camera(d), &options(w, h, shading)).unwrap();
    for &x in &[
        window[0],
        window[window.len() / 3],
        w / 2,
        window[window.len() - 1],
    ] {
        let col: Vec<f64> = (0..h)
            .map(|y| field.at(x, y))
            .filter(|v| !v.is_nan())
            .collect();
        assert!(col.len() > 100, "column {x} covered");
        assert_eq!(
            transitions((0..h).map(|y| stripe(&img, x, y))),
            0,
            "column {x}"
        );
        let spread = col.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
            - col.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        // Interpolating the normals of the 8 rows of vertices along z is exact (they are
        // equal); what is left is rounding.
        assert!(spread < 1e-9, "column {x}: s spreads {spread}");
        let phi = cylinder_hit(r, d, w, h, x).unwrap();
        // Against the analytic s at the column's hit: the 1440-gon's facets and the
        // interpolated normal differ from the circle's by under 10⁻³ in s.
        assert!(
            (col[0] - s_of(phi)).abs() < 1e-3,
            "column {x}: {} vs {}",
            col[0],
            s_of(phi)
        );
    }
}

#[test]
fn isophotes_on_a_sphere_are_concentric_rings_at_the_predicted_radii() {
    let (d, bands, width) = (4.0, 8u32, 0.5);
    let (w, h) = (401u32, 401u32);
    let mesh = sphere(720, 360);
    let shading = Shading::Isophotes {
        bands,
        light: None,
        width,
    };
    let img = render(&mesh, &side_camera(d), &options(w, h, shading)).unwrap();
    std::fs::write("/tmp/interro-sphere-isophotes.png", png(&img)).ok();
    // Lit along the view: n·L = cos of the angle at the centre between the point and the eye
    // direction, from 1 at the middle to r/d at the silhouette; s = bands (c + 1)/2.
    let s = |c: f64| f64::from(bands) * (c + 1.0) / 2.0;
    let borders = borders_between(s(1.0 / d), s(1.0), width);
    let (cx, cy) = (w / 2, h / 2);
    let across = transitions((0..w).map(|x| stripe(&img, x, cy)));
    let down = transitions((0..h).map(|y| stripe(&img, cx, y)));
    assert_eq!(borders, 6);

    // Radii: the border n·L = c lies at the sphere point n = (c, √(1 − c²), 0), seen
    // focal · n_y / (d − n_x) pixels off the centre.
    let mut predicted: Vec<f64> = Vec::new();
    for k in 0..=bands {
        for b in [f64::from(k) - width / 2.0, f64::from(k) + width / 2.0] {
            let c = 2.0 * b / f64::from(bands) - 1.0;
            if c > 1.0 / d && c < 1.0 {
                predicted.push(focal(h) * (1.0 - c * c).sqrt() / (d - c));
            }
        }
    }
    predicted.sort_by(f64::total_cmp);
    let radii = |values: Vec<Option<bool>>| -> Vec<f64> {
        let mut out = Vec::new();
        for i in 1..values.len() {
            if let (Some(a), Some(b)) = (values[i - 1], values[i]) {
                if a != b && i as f64 > values.len() as f64 / 2.0 {
                    // The border lies between pixel centres i − 1/2 and i + 1/2.
                    out.push(i as f64 - values.len() as f64 / 2.0);
                }
            }
        }
        out
    };
    let right = radii((0..w).map(|x| stripe(&img, x, cy)).collect());
    let below = radii((0..h).map(|y| stripe(&img, cx, y)).collect());
    let diag: Vec<Option<bool>> = (0..w).map(|i| stripe(&img, i, i)).collect();
    let diagonal: Vec<f64> = radii(diag).iter().map(|r| r * 2f64.sqrt()).collect();
    eprintln!("isophote radii: predicted {predicted:.2?}\n right {right:?}\n below {below:?}\n diagonal {diagonal:.2?}");
    // The silhouette, where the view ray grazes the sphere (sin = 1/d), is the largest
    // radius: there ρ(c) is flat in c and the outer rings crowd within a pixel of it. A ring
    // less than a pixel inside the silhouette may fall between pixel centres.
    let silhouette = focal(h) * (1.0 / d).asin().tan();
    /// How far inside the silhouette a ring is sure to be sampled: a pixel (a diagonal's √2).
    const RESOLVED: f64 = 1.5;
    let resolved = predicted
        .iter()
        .filter(|&&r| r < silhouette - RESOLVED)
        .count();
    assert_eq!(resolved, 5, "silhouette {silhouette}");
    assert_eq!(
        across,
        2 * right.len(),
        "the rings are symmetric across the diameter"
    );
    assert_eq!(down, 2 * below.len());
    /// A border is found between two pixel centres: half a pixel, and the diagonal's √2.
    const RADIUS_TOLERANCE: f64 = 1.0;
    for found in [&right, &below, &diagonal] {
        assert!(
            (resolved..=predicted.len()).contains(&found.len()),
            "{found:?}"
        );
        for (f, p) in found.iter().zip(&predicted) {
            assert!((f - p).abs() <= RADIUS_TOLERANCE, "{f} vs {p}");
        }
    }
}

/// A roof `x = −k |y| − c y²` (ridge along z; `c` bends the two sides so that stripes run
/// across them), `|y|, |z| ≤ 1`, the two sides meeting at a crease (`smooth: None`), or the
/// smooth bend `x = −k √(y² + ε²) − c y²`, with their analytic normals.
fn roof(k: f64, c: f64, smooth: Option<f64>) -> RenderMesh {
    let strip = |lo: f64, hi: f64| {
        grid(200, 4, move |u, v| {
            let y = lo + (hi - lo) * u;
            let (x, slope) = match smooth {
                Some(e) => (
                    -k * (y * y + e * e).sqrt() - c * y * y,
                    -k * y / (y * y + e * e).sqrt() - 2.0 * c * y,
                ),
                // The strip's own side: its slope from its side of the ridge, also at y = 0.
                None => (
                    -k * y.abs() - c * y * y,
                    -k * (lo + hi).signum() - 2.0 * c * y,
                ),
            };
            // The surface x = g(y) has the normal ∇(x − g(y)) = (1, −g′(y), 0).
            (
                Point3::new(x, y, 2.0 * v - 1.0),
                Vector3::new(1.0, -slope, 0.0),
            )
        })
    };
    if smooth.is_some() {
        return strip(-1.0, 1.0);
    }
    // Two strips, unwelded along the ridge, each with its facet's normal.
    let (mut a, b) = (strip(-1.0, 0.0), strip(0.0, 1.0));
    let base = a.positions.len();
    a.positions.extend(&b.positions);
    a.normals.extend(&b.normals);
    a.colors.extend(&b.colors);
    a.faces.extend(b.faces.iter().map(|f| f.map(|i| i + base)));
    a
}

/// Largest jump of the reflection parameter between neighbouring covered pixels of row `y`,
/// wrapped to the nearest equivalent (s is defined modulo `stripes`), and its column.
fn largest_jump(field: &render::Field, y: u32, stripes: f64) -> (f64, u32) {
    let mut best = (0.0, 0);
    for x in 1..field.width {
        let (a, b) = (field.at(x - 1, y), field.at(x, y));
        if a.is_nan() || b.is_nan() {
            continue;
        }
        let jump = b - a;
        let jump = (jump - stripes * (jump / stripes).round()).abs();
        if jump > best.0 {
            best = (jump, x);
        }
    }
    best
}

#[test]
fn a_crease_breaks_the_reflection_lines_and_a_smooth_bend_does_not() {
    let (d, stripes) = (5.0, 8u32);
    let (w, h) = (400u32, 300u32);
    let slope = 10f64.to_radians().tan();
    let shading = Shading::Reflection {
        stripes,
        direction: Some(Vector3::z()),
        width: 0.5,
    };
    let o = options(w, h, shading);
    let cam = side_camera(d);
    let crease = roof(slope, 0.25, None);
    let bend = roof(slope, 0.25, Some(0.2));
    // Pictures to look at: the axis along the ridge, and tilted so the stripes cross it
    // (where a crease offsets them and a smooth bend bends them).
    let tilted = options(
        w,
        h,
        Shading::Reflection {
            stripes: 16,
            direction: Some(Vector3::new(0.0, 1.0, 1.0)),
            width: 0.5,
        },
    );
    for (name, m) in [("crease", &crease), ("bend", &bend)] {
        let img = render(m, &cam, &o).unwrap();
        std::fs::write(format!("/tmp/interro-roof-{name}.png"), png(&img)).ok();
        let img = render(m, &cam, &tilted).unwrap();
        std::fs::write(format!("/tmp/interro-roof-{name}-tilted.png"), png(&img)).ok();
    }
    let fc = interrogation_field(&crease, &cam, &o).unwrap();
    let fb = interrogation_field(&bend, &cam, &o).unwrap();
    // At the ridge the view ray is (−1, 0, 0) and the facet normals (1, ±k, 0)/√(1 + k²), at
    // polar angles ±atan k: θ = 2φ − 0 jumps by 4 atan k, s by stripes · 4 atan k / 2π.
    let predicted = f64::from(stripes) * 4.0 * slope.atan() / TAU;
    let mut smooth_worst: f64 = 0.0;
    for y in (h / 2 - 60..=h / 2 + 60).step_by(20) {
        let (jc, xc) = largest_jump(&fc, y, f64::from(stripes));
        let (jb, _) = largest_jump(&fb, y, f64::from(stripes));
        smooth_worst = smooth_worst.max(jb);
        // The ridge projects on the middle column: the jump is between columns w/2 − 1, w/2.
        assert_eq!(xc, w / 2, "row {y}: the break is on the ridge");
        // The two pixels either side are half a pixel off the ridge: on top of the ridge's
        // jump, s moves by a pixel's worth of the sides' own turn, the step between
        // neighbouring pixels beside the ridge (and the 200-strip tessellation's 10⁻³).
        let step = |x: u32| (fc.at(x, y) - fc.at(x - 1, y)).abs();
        let drift = step(xc - 1).max(step(xc + 1));
        assert!(
            (jc - predicted).abs() <= drift + 1e-3,
            "row {y}: jump {jc} vs {predicted}, drift {drift}"
        );
        eprintln!("row {y}: crease jump {jc:.4} (predicted {predicted:.4}, drift {drift:.4}), bend {jb:.4}");
    }
    // The bend turns the normal through the same 20° over about 120 pixels: its largest step
    // is a small fraction of the crease's single jump.
    assert!(smooth_worst < 0.05 * predicted, "bend steps {smooth_worst}");
}

/// The camera frame (right, up, forward) as the renderer builds it, recomputed here.
fn project(cam: &Camera, w: u32, h: u32, p: &Point3<f64>) -> (f64, f64) {
    let f = (cam.target - cam.eye).normalize();
    let r = f.cross(&cam.up).normalize();
    let u = r.cross(&f);
    let q = p - cam.eye;
    let fpx = f64::from(h) * 0.5 / (cam.fov_y_degrees.to_radians() * 0.5).tan();
    let z = q.dot(&f);
    assert!(z > 0.0, "{p:?} behind the eye");
    (
        f64::from(w) * 0.5 + fpx * q.dot(&r) / z,
        f64::from(h) * 0.5 - fpx * q.dot(&u) / z,
    )
}

#[test]
fn framing_fits_every_vertex_with_its_margin() {
    let tall = cylinder(0.05, 2.0, 32);
    let meshes = [
        ("disk", disk()),
        ("tall cylinder", tall),
        ("sphere", sphere(48, 24)),
    ];
    let views = [
        (0.0, 0.0),
        (35.0, 25.0),
        (90.0, 0.0),
        (10.0, 89.0),
        (0.0, 90.0),
        (200.0, -60.0),
        (45.0, 5.0),
    ];
    let margin = (1.0 - FRAME_FILL) / 2.0;
    /// Rounding of the projection against the margin's edge.
    const EDGE: f64 = 1e-9;
    for (name, m) in &meshes {
        let b = meshio::BoundingBox::of_finite(&m.positions);
        for &(w, h) in &[(400u32, 300u32), (300, 400), (200, 200), (640, 120)] {
            let aspect = f64::from(w) / f64::from(h);
            for &(az, el) in &views {
                for tight in [false, true] {
                    let cam = if tight {
                        Camera::framing_points(&m.positions, az, el, aspect)
                    } else {
                        Camera::framing_aspect(b.min, b.max, az, el, aspect)
                    };
                    let (mut lo, mut hi) = ((f64::INFINITY, f64::INFINITY), (0.0f64, 0.0f64));
                    for p in &m.positions {
                        let (x, y) = project(&cam, w, h, p);
                        lo = (lo.0.min(x), lo.1.min(y));
                        hi = (hi.0.max(x), hi.1.max(y));
                    }
                    // Fitted to the points, one of them touches the margin (unless the distance
                    // floor, 1.25 half-diagonals, holds the eye back).
                    let (mw, mh) = (margin * f64::from(w), margin * f64::from(h));
                    let touch = (lo.0 - mw)
                        .min(lo.1 - mh)
                        .min(f64::from(w) - mw - hi.0)
                        .min(f64::from(h) - mh - hi.1);
                    let floor = (cam.eye - cam.target).norm()
                        <= 1.25 * (b.max - b.min).norm() * 0.5 * (1.0 + 1e-12);
                    if tight && !floor {
                        assert!(
                            touch.abs() < 1e-6,
                            "{name} {w}x{h} from {az},{el}: {touch} px spare"
                        );
                    }
                    let inside = lo.0 >= mw - EDGE
                        && lo.1 >= mh - EDGE
                        && hi.0 <= f64::from(w) - mw + EDGE
                        && hi.1 <= f64::from(h) - mh + EDGE;
                    assert!(inside, "{name} {w}x{h} from {az},{el}: x {lo:?}..{hi:?}");
                    // And the object is not lost in the frame: it spans at least a third of the
                    // width or of the height (the box's corners, not the object, touch the margin).
                    let span = ((hi.0 - lo.0) / f64::from(w)).max((hi.1 - lo.1) / f64::from(h));
                    assert!(
                        span > 1.0 / 3.0,
                        "{name} {w}x{h} from {az},{el}: spans {span}"
                    );
                }
            }
        }
        // `framing` is the square case: inside any landscape picture.
        let cam = Camera::framing(b.min, b.max, 35.0, 25.0);
        let img = render(m, &cam, &options(400, 300, Shading::Lit)).unwrap();
        for x in 0..400 {
            for y in 0..300 {
                let border = !(20..380).contains(&x) || !(15..285).contains(&y);
                if border {
                    assert_eq!(pixel(&img, x, y), [255; 3], "{name}: drawn at ({x}, {y})");
                }
            }
        }
    }
}

fn png(img: &Image) -> Vec<u8> {
    let mut out = Vec::new();
    render::write_png(img, &mut out).expect("encodes");
    out
}

#[test]
fn highlight_lines_on_a_plate_facing_the_lights_are_evenly_spaced() {
    // The plate z = 0, |x|, |y| ≤ 1, seen from (0, 0, d): its normal is the lights' plane
    // normal M, so every normal line meets the lights' plane straight in front of its point
    // and the light index is t = x / h (up to sign) with h = 2ρ / lines, ρ = √2 the bounding
    // radius: dark where |t − round t| < width / 2.
    let (d, lines, width) = (4.0, 8u32, 0.5);
    let (w, h) = (400u32, 400u32);
    let plate = grid(64, 64, |u, v| {
        (Point3::new(2.0 * u - 1.0, 2.0 * v - 1.0, 0.0), Vector3::z())
    });
    let cam = Camera {
        eye: Point3::new(0.0, 0.0, d),
        target: Point3::origin(),
        up: Vector3::y(),
        fov_y_degrees: 30.0,
    };
    let shading = Shading::Highlight {
        lines,
        direction: None,
        width,
    };
    let img = render(&plate, &cam, &options(w, h, shading)).unwrap();
    std::fs::write("/tmp/interro-plate-highlight.png", png(&img)).ok();
    let spacing = 2.0 * 2f64.sqrt() / f64::from(lines);
    let predicted = borders_between(-1.0 / spacing, 1.0 / spacing, width);
    assert_eq!(predicted, 12);
    let row = transitions((0..w).map(|x| stripe(&img, x, h / 2)));
    let column = transitions((0..h).map(|y| stripe(&img, w / 2 + 3, y)));
    assert_eq!((row, column), (predicted, 0));
    // Where the borders are: x = (k ± width/2) h on the plate, focal · x / d pixels off the
    // centre.
    let mut found = Vec::new();
    for x in 1..w {
        let (a, b) = (stripe(&img, x - 1, h / 2), stripe(&img, x, h / 2));
        if a.is_some() && b.is_some() && a != b {
            found.push(f64::from(x) - f64::from(w) / 2.0);
        }
    }
    let mut expect = Vec::new();
    for k in -3i32..=3 {
        for b in [f64::from(k) - width / 2.0, f64::from(k) + width / 2.0] {
            if (b * spacing).abs() < 1.0 {
                expect.push(focal(h) * b * spacing / d);
            }
        }
    }
    expect.sort_by(f64::total_cmp);
    eprintln!("highlight borders: found {found:?}\n expected {expect:.2?}");
    for (f, e) in found.iter().zip(&expect) {
        // A border found between two pixel centres: half a pixel.
        assert!((f - e).abs() <= 0.5 + 1e-9, "{f} vs {e}");
    }
}

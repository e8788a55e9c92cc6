//! A small CPU rasterizer for shaded triangle meshes (no GPU, no crate that fits: docs/conventions.md).
//!
//! Perspective camera, z-buffer, clipping against the near plane (Sutherland–Hodgman on one
//! plane), perspective-correct interpolation of normals, colours and positions (weights
//! `λᵢ/zᵢ`, renormalized), per-pixel Blinn–Phong shading with two-sided lighting, lights fixed
//! to the camera (a key light above left, a fill light right) so every view is lit alike, and
//! sRGB output. Bad triangles (non-finite vertices) are skipped, never a panic.

use nalgebra::{Point3, Vector3};

use crate::error::RenderError;

/// A triangle mesh to draw: per-vertex positions, normals and linear RGB colours in `[0, 1]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderMesh {
    /// Vertex positions.
    pub positions: Vec<Point3<f64>>,
    /// Vertex normals (any length; normalized per pixel).
    pub normals: Vec<Vector3<f64>>,
    /// Vertex colours, linear RGB.
    pub colors: Vec<[f32; 3]>,
    /// Triangles.
    pub faces: Vec<[usize; 3]>,
}

/// A perspective camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Eye position.
    pub eye: Point3<f64>,
    /// Point looked at (image centre).
    pub target: Point3<f64>,
    /// Up direction (need not be perpendicular to the view direction).
    pub up: Vector3<f64>,
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
}

impl Camera {
    /// A camera looking at the box `[lo, hi]` from azimuth and elevation (degrees, about the z
    /// axis and above the xy plane), far enough that the box's bounding sphere fits the view.
    pub fn framing(lo: Point3<f64>, hi: Point3<f64>, azimuth: f64, elevation: f64) -> Camera {
        let centre = nalgebra::center(&lo, &hi);
        let radius = ((hi - lo).norm() * 0.5).max(f64::MIN_POSITIVE);
        let (az, el) = (azimuth.to_radians(), elevation.to_radians());
        let dir = Vector3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let fov = 30.0f64;
        // The bounding sphere of a box overstates most objects' silhouettes; 0.8 of the
        // sphere-fitting distance keeps flat and elongated shapes (a ring) inside the frame.
        let distance = radius / (fov.to_radians() * 0.5).sin() * 0.8;
        let up = if el.cos() < 1e-3 {
            Vector3::y()
        } else {
            Vector3::z()
        };
        Camera {
            eye: centre + dir * distance,
            target: centre,
            up,
            fov_y_degrees: fov,
        }
    }
}

/// Rendering settings.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Ambient term.
    pub ambient: f64,
    /// Key light intensity (above left of the camera).
    pub key: f64,
    /// Fill light intensity (right of the camera).
    pub fill: f64,
    /// Specular strength.
    pub specular: f64,
    /// Blinn–Phong exponent.
    pub shininess: f64,
    /// Background colour, linear RGB.
    pub background: [f32; 3],
    /// Colour of a triangle-edge overlay (the testbed's XRender view), drawn with the depth
    /// test; `None` draws no edges.
    pub wireframe: Option<[f32; 3]>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 480,
            height: 360,
            ambient: 0.12,
            key: 0.85,
            fill: 0.3,
            specular: 0.35,
            shininess: 40.0,
            background: [1.0, 1.0, 1.0],
            wireframe: None,
        }
    }
}

/// An 8-bit sRGB image, rows top to bottom.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `3 · width · height` bytes.
    pub rgb: Vec<u8>,
}

pub use crate::srgb::{to_srgb8, to_srgb8_exact};

/// A vertex in camera space with its attributes.
#[derive(Clone, Copy)]
struct Cv {
    c: Vector3<f64>,
    n: Vector3<f64>,
    col: [f32; 3],
}

fn lerp_cv(a: &Cv, b: &Cv, t: f64) -> Cv {
    let tf = t as f32;
    Cv {
        c: a.c + (b.c - a.c) * t,
        n: a.n + (b.n - a.n) * t,
        col: std::array::from_fn(|k| a.col[k] + (b.col[k] - a.col[k]) * tf),
    }
}

/// Renders `mesh` seen by `camera`.
pub fn render(
    mesh: &RenderMesh,
    camera: &Camera,
    options: &RenderOptions,
) -> Result<Image, RenderError> {
    let (w, h) = (
        options.width.max(1) as usize,
        options.height.max(1) as usize,
    );
    let f = (camera.target - camera.eye).normalize();
    let r = f.cross(&camera.up).normalize();
    let u = r.cross(&f);
    let fpx = (h as f64 * 0.5) / (camera.fov_y_degrees.to_radians() * 0.5).tan();
    let near = 1e-3 * (camera.target - camera.eye).norm().max(f64::MIN_POSITIVE);
    // Lights in camera space (x right, y up, z forward), pointing towards the light.
    let key = Vector3::new(-0.45, 0.65, -0.6).normalize();
    let fill = Vector3::new(0.7, -0.1, -0.7).normalize();

    let mut depth = vec![f64::INFINITY; w * h];
    let mut colour = vec![options.background; w * h];
    let to_cam = |p: &Point3<f64>| {
        let d = p - camera.eye;
        Vector3::new(d.dot(&r), d.dot(&u), d.dot(&f))
    };
    for face in &mesh.faces {
        if face.iter().any(|&i| i >= mesh.positions.len()) {
            continue;
        }
        let tri: [Cv; 3] = face.map(|i| {
            let n = mesh.normals.get(i).copied().unwrap_or_else(Vector3::zeros);
            Cv {
                c: to_cam(&mesh.positions[i]),
                n: Vector3::new(n.dot(&r), n.dot(&u), n.dot(&f)),
                col: mesh.colors.get(i).copied().unwrap_or([0.8, 0.8, 0.8]),
            }
        });
        if tri.iter().any(|v| !v.c.iter().all(|x| x.is_finite())) {
            continue;
        }
        // Clip against z ≥ near.
        let mut poly: Vec<Cv> = Vec::with_capacity(4);
        for k in 0..3 {
            let (a, b) = (&tri[k], &tri[(k + 1) % 3]);
            let (ina, inb) = (a.c.z >= near, b.c.z >= near);
            if ina {
                poly.push(*a);
            }
            if ina != inb {
                let t = (near - a.c.z) / (b.c.z - a.c.z);
                poly.push(lerp_cv(a, b, t));
            }
        }
        for k in 1..poly.len().saturating_sub(1) {
            raster(
                [&poly[0], &poly[k], &poly[k + 1]],
                (w, h),
                fpx,
                &mut depth,
                &mut colour,
                &|n, col, pos| shade(n, col, pos, &key, &fill, options),
            );
        }
    }
    if let Some(wire) = options.wireframe {
        for face in &mesh.faces {
            if face.iter().any(|&i| i >= mesh.positions.len()) {
                continue;
            }
            let c = face.map(|i| to_cam(&mesh.positions[i]));
            for k in 0..3 {
                draw_edge(
                    &c[k],
                    &c[(k + 1) % 3],
                    (w, h),
                    fpx,
                    near,
                    &depth,
                    &mut colour,
                    wire,
                );
            }
        }
    }
    let mut rgb = Vec::with_capacity(3 * w * h);
    for c in &colour {
        rgb.extend(c.iter().map(|x| to_srgb8(*x)));
    }
    Ok(Image {
        width: w as u32,
        height: h as u32,
        rgb,
    })
}

/// Relative depth tolerance of the wireframe against the filled surface it lies on.
const WIRE_DEPTH_BIAS: f64 = 2e-3;

/// Draws one camera-space edge as a 1-pixel line where it is not hidden.
#[allow(clippy::too_many_arguments)]
fn draw_edge(
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    (w, h): (usize, usize),
    fpx: f64,
    near: f64,
    depth: &[f64],
    colour: &mut [[f32; 3]],
    wire: [f32; 3],
) {
    if !(a.iter().chain(b.iter()).all(|x| x.is_finite())) || a.z < near || b.z < near {
        return;
    }
    let sx = |v: &Vector3<f64>| {
        (
            w as f64 * 0.5 + v.x / v.z * fpx,
            h as f64 * 0.5 - v.y / v.z * fpx,
        )
    };
    let (p, q) = (sx(a), sx(b));
    let steps = ((q.0 - p.0).abs().max((q.1 - p.1).abs()).ceil() as usize).clamp(1, 4 * (w + h));
    for i in 0..=steps {
        let t = i as f64 / steps as f64;
        let (x, y) = (p.0 + (q.0 - p.0) * t, p.1 + (q.1 - p.1) * t);
        if x < 0.0 || y < 0.0 || x >= w as f64 || y >= h as f64 {
            continue;
        }
        // 1/z is linear in screen space.
        let z = 1.0 / ((1.0 - t) / a.z + t / b.z);
        let idx = y as usize * w + x as usize;
        if z <= depth[idx] * (1.0 + WIRE_DEPTH_BIAS) {
            colour[idx] = wire;
        }
    }
}

fn shade(
    n: Vector3<f64>,
    col: [f32; 3],
    pos: Vector3<f64>,
    key: &Vector3<f64>,
    fill: &Vector3<f64>,
    o: &RenderOptions,
) -> [f32; 3] {
    let view = -pos.normalize();
    let mut n = if n.norm() > 0.0 { n.normalize() } else { view };
    if n.dot(&view) < 0.0 {
        n = -n;
    }
    let mut diffuse = o.ambient;
    let mut spec = 0.0;
    for (l, i) in [(key, o.key), (fill, o.fill)] {
        let d = n.dot(l).max(0.0);
        diffuse += i * d;
        if d > 0.0 {
            let hv = (l + view).normalize();
            spec += i * n.dot(&hv).max(0.0).powf(o.shininess);
        }
    }
    col.map(|c| (f64::from(c) * diffuse + o.specular * spec) as f32)
}

/// Rasterizes one camera-space triangle (all z ≥ near).
fn raster(
    t: [&Cv; 3],
    (w, h): (usize, usize),
    fpx: f64,
    depth: &mut [f64],
    colour: &mut [[f32; 3]],
    shade: &dyn Fn(Vector3<f64>, [f32; 3], Vector3<f64>) -> [f32; 3],
) {
    let s: [(f64, f64); 3] = t.map(|v| {
        (
            w as f64 * 0.5 + v.c.x / v.c.z * fpx,
            h as f64 * 0.5 - v.c.y / v.c.z * fpx,
        )
    });
    let area = (s[1].0 - s[0].0) * (s[2].1 - s[0].1) - (s[2].0 - s[0].0) * (s[1].1 - s[0].1);
    if !area.is_finite() || area.abs() < 1e-12 {
        return;
    }
    let minx = s
        .iter()
        .map(|p| p.0)
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0) as usize;
    let maxx = s
        .iter()
        .map(|p| p.0)
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min(w as f64 - 1.0);
    let miny = s
        .iter()
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(0.0) as usize;
    let maxy = s
        .iter()
        .map(|p| p.1)
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min(h as f64 - 1.0);
    if maxx < 0.0 || maxy < 0.0 {
        return;
    }
    let (maxx, maxy) = (maxx as usize, maxy as usize);
    let inv_z = t.map(|v| 1.0 / v.c.z);
    for py in miny..=maxy {
        for px in minx..=maxx {
            let (x, y) = (px as f64 + 0.5, py as f64 + 0.5);
            let e =
                |a: (f64, f64), b: (f64, f64)| (b.0 - a.0) * (y - a.1) - (b.1 - a.1) * (x - a.0);
            let l0 = e(s[1], s[2]) / area;
            let l1 = e(s[2], s[0]) / area;
            let l2 = e(s[0], s[1]) / area;
            if l0 < 0.0 || l1 < 0.0 || l2 < 0.0 {
                continue;
            }
            // Perspective-correct weights.
            let (w0, w1, w2) = (l0 * inv_z[0], l1 * inv_z[1], l2 * inv_z[2]);
            let sum = w0 + w1 + w2;
            let z = 1.0 / sum;
            let idx = py * w + px;
            if z >= depth[idx] {
                continue;
            }
            depth[idx] = z;
            let (a, b, c) = (w0 / sum, w1 / sum, w2 / sum);
            let n = t[0].n * a + t[1].n * b + t[2].n * c;
            let pos = t[0].c * a + t[1].c * b + t[2].c * c;
            let (af, bf, cf) = (a as f32, b as f32, c as f32);
            let col =
                std::array::from_fn(|k| t[0].col[k] * af + t[1].col[k] * bf + t[2].col[k] * cf);
            colour[idx] = shade(n, col, pos);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(z: f64, col: [f32; 3]) -> RenderMesh {
        RenderMesh {
            positions: vec![
                Point3::new(-1.0, -1.0, z),
                Point3::new(1.0, -1.0, z),
                Point3::new(1.0, 1.0, z),
                Point3::new(-1.0, 1.0, z),
            ],
            normals: vec![Vector3::z(); 4],
            colors: vec![col; 4],
            faces: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    fn top_camera() -> Camera {
        Camera {
            eye: Point3::new(0.0, 0.0, 5.0),
            target: Point3::origin(),
            up: Vector3::y(),
            fov_y_degrees: 60.0,
        }
    }

    fn pixel(img: &Image, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y * img.width + x) as usize;
        [img.rgb[i], img.rgb[i + 1], img.rgb[i + 2]]
    }

    #[test]
    fn square_covers_the_expected_fraction() {
        let o = RenderOptions {
            width: 200,
            height: 200,
            background: [0.0; 3],
            ..RenderOptions::default()
        };
        let img = render(&quad(0.0, [1.0, 1.0, 1.0]), &top_camera(), &o).unwrap();
        let lit = img
            .rgb
            .chunks(3)
            .filter(|p| p.iter().any(|c| *c > 0))
            .count();
        // Half-width 1 at distance 5 with a 60° field: 2/(2·5·tan 30°) of the width, squared.
        let side = 2.0 / (2.0 * 5.0 * 30f64.to_radians().tan());
        let expect = side * side * 40_000.0;
        assert!(
            (lit as f64 - expect).abs() < 0.03 * expect,
            "{lit} vs {expect}"
        );
    }

    #[test]
    fn nearer_triangles_hide_farther_ones() {
        let mut m = quad(0.0, [1.0, 0.0, 0.0]);
        let near = quad(1.0, [0.0, 0.0, 1.0]);
        let off = m.positions.len();
        m.positions.extend(&near.positions);
        m.normals.extend(&near.normals);
        m.colors.extend(&near.colors);
        m.faces
            .extend(near.faces.iter().map(|f| f.map(|i| i + off)));
        let img = render(&m, &top_camera(), &RenderOptions::default()).unwrap();
        let p = pixel(&img, 240, 180);
        assert!(p[2] > p[0], "{p:?}");
    }

    #[test]
    fn triangles_through_the_near_plane_are_clipped_not_dropped() {
        let m = RenderMesh {
            positions: vec![
                Point3::new(-1.0, -1.0, 0.0),
                Point3::new(1.0, -1.0, 0.0),
                Point3::new(0.0, 0.0, 10.0),
            ],
            normals: vec![Vector3::z(); 3],
            colors: vec![[1.0; 3]; 3],
            faces: vec![[0, 1, 2]],
        };
        let img = render(&m, &top_camera(), &RenderOptions::default()).unwrap();
        assert_eq!(img.rgb.len(), 3 * 480 * 360);
        let nan = RenderMesh {
            positions: vec![Point3::new(f64::NAN, 0.0, 0.0); 3],
            ..m
        };
        assert!(render(&nan, &top_camera(), &RenderOptions::default()).is_ok());
    }

    #[test]
    fn wireframe_draws_visible_edges_only() {
        let o = RenderOptions {
            wireframe: Some([0.0, 0.0, 0.0]),
            ..RenderOptions::default()
        };
        let img = render(&quad(0.0, [1.0, 1.0, 1.0]), &top_camera(), &o).unwrap();
        let dark = img
            .rgb
            .chunks(3)
            .filter(|p| p.iter().all(|c| *c == 0))
            .count();
        // Four sides and a diagonal of a square about 139 px wide: roughly 5 × 139 pixels.
        assert!(dark > 500 && dark < 900, "{dark}");
    }

    #[test]
    fn srgb_encoding_endpoints() {
        assert_eq!(to_srgb8(0.0), 0);
        assert_eq!(to_srgb8(1.0), 255);
        assert_eq!(to_srgb8(0.2159), 128); // sRGB 0.502
    }
}

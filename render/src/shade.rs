//! A small CPU rasterizer for shaded triangle meshes (no GPU, no crate that fits: docs/conventions.md).
//!
//! Perspective camera, z-buffer, clipping against the near plane (Sutherland–Hodgman on one
//! plane), perspective-correct interpolation of normals, colours and positions (weights
//! `λᵢ/zᵢ`, renormalized), per-pixel Blinn–Phong shading with two-sided lighting, lights fixed
//! to the camera (a key light above left, a fill light right) so every view is lit alike, and
//! sRGB output; or, instead of the lighting, reflection lines, isophotes or highlight lines computed
//! per pixel from the interpolated normal ([`Shading`], [`crate::interrogation`]). Bad triangles (non-finite vertices) are skipped, never a panic.
//!
//! Speed: vertices are transformed once, triangles set up in parallel chunks, and
//! the picture drawn in bands of rows in parallel (rayon) with deferred shading (a depth pass
//! keeps each pixel's nearest triangle, then every visible pixel is shaded once); the sRGB
//! conversion is a table equal to the formula ([`crate::srgb`]) and the specular power of a
//! whole exponent is raised by squaring ([`spec_power`]). The bytes are those of the serial
//! per-triangle shader this replaced (same operations per pixel, same triangle order per
//! pixel), the same on every run and for any number of threads. [`render_many`] draws many
//! pictures in parallel.
//!
//! [`render`] needs the whole mesh at once. [`crate::canvas::Canvas`] draws the same pictures
//! from triangles given in parts (a stream's), in bounded memory, by forward shading with the
//! pieces here (the triangle set-up `setup_chunk`, the colouring `Painter`), and
//! [`draw_wire_frame`] draws [`wire_frame`]'s lines part by part; the camera of
//! [`Camera::framing_points`] is framed on points visited twice by
//! [`Camera::framing_passes`].

use nalgebra::{Point3, Vector3};
use rayon::prelude::*;

use crate::error::RenderError;
use crate::interrogation::{frac_distance, reflection_angle, LightLines, DARK, LIGHT};
use crate::srgb::Srgb8Table;

pub use crate::interrogation::Shading;

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

pub use crate::camera::{Camera, FrameBox, FRAME_FILL, FRAME_FOV_DEGREES, MIN_FRAME_DISTANCE};

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
    /// How visible pixels are coloured: lit (the default), or one of the interrogation modes
    /// (reflection lines, isophotes, highlight lines; [`crate::interrogation`]), which ignore
    /// the lights, material and vertex colours above.
    pub shading: Shading,
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
            shading: Shading::Lit,
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

/// Rows of one band of the parallel rasterization. Each band draws the triangles that reach it
/// in mesh order, so a pixel sees the same triangles in the same order as a serial pass: the
/// picture does not depend on the band height or on the number of threads.
pub(crate) const BAND_ROWS: usize = 16;

/// Faces per task of the parallel triangle setup.
pub(crate) const SETUP_CHUNK: usize = 4096;

/// Largest integer Blinn–Phong exponent raised by repeated squaring (more multiplications
/// than that would lose more than the 2⁻⁴⁶ relative accuracy stated in [`spec_power`]).
const MAX_INTEGER_SHININESS: f64 = 1024.0;

/// A vertex in camera space with its attributes.
#[derive(Clone, Copy)]
pub(crate) struct Cv {
    pub(crate) c: Vector3<f64>,
    n: Vector3<f64>,
    col: [f32; 3],
}

/// Vertex `i` of `mesh` (at `p`) in camera space with its attributes: a normal of zero and a
/// light grey where the mesh has none for it.
#[inline]
pub(crate) fn camera_vertex(mesh: &RenderMesh, view: &View, i: usize, p: &Point3<f64>) -> Cv {
    let n = mesh.normals.get(i).copied().unwrap_or_else(Vector3::zeros);
    Cv {
        c: view.to_cam(p),
        n: view.dir_to_cam(&n),
        col: mesh.colors.get(i).copied().unwrap_or([0.8, 0.8, 0.8]),
    }
}

fn lerp_cv(a: &Cv, b: &Cv, t: f64) -> Cv {
    let tf = t as f32;
    Cv {
        c: a.c + (b.c - a.c) * t,
        n: a.n + (b.n - a.n) * t,
        col: std::array::from_fn(|k| a.col[k] + (b.col[k] - a.col[k]) * tf),
    }
}

/// The camera frame and screen mapping of one picture.
pub(crate) struct View {
    eye: Point3<f64>,
    r: Vector3<f64>,
    u: Vector3<f64>,
    f: Vector3<f64>,
    fpx: f64,
    near: f64,
    pub(crate) w: usize,
    pub(crate) h: usize,
}

impl View {
    pub(crate) fn new(camera: &Camera, (w, h): (usize, usize)) -> View {
        let f = (camera.target - camera.eye).normalize();
        let r = f.cross(&camera.up).normalize();
        let u = r.cross(&f);
        View {
            eye: camera.eye,
            r,
            u,
            f,
            fpx: (h as f64 * 0.5) / (camera.fov_y_degrees.to_radians() * 0.5).tan(),
            near: 1e-3 * (camera.target - camera.eye).norm().max(f64::MIN_POSITIVE),
            w,
            h,
        }
    }

    pub(crate) fn to_cam(&self, p: &Point3<f64>) -> Vector3<f64> {
        let d = p - self.eye;
        Vector3::new(d.dot(&self.r), d.dot(&self.u), d.dot(&self.f))
    }

    fn dir_to_cam(&self, n: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(n.dot(&self.r), n.dot(&self.u), n.dot(&self.f))
    }

    fn screen(&self, c: &Vector3<f64>) -> (f64, f64) {
        (
            self.w as f64 * 0.5 + c.x / c.z * self.fpx,
            self.h as f64 * 0.5 - c.y / c.z * self.fpx,
        )
    }
}

/// One edge function of a triangle, `e(x, y) = dx (y − ay) − dy (x − ax)` for the edge from
/// `(ax, ay)` to `(ax + dx, ay + dy)`.
#[derive(Clone, Copy)]
struct Edge {
    ax: f64,
    ay: f64,
    dx: f64,
    dy: f64,
}

impl Edge {
    fn new(a: (f64, f64), b: (f64, f64)) -> Edge {
        Edge {
            ax: a.0,
            ay: a.1,
            dx: b.0 - a.0,
            dy: b.1 - a.1,
        }
    }
}

/// A camera-space triangle (all z ≥ near) set up for rasterization: its edge functions, twice
/// its signed screen area, inverse depths, the pixel box it may cover (inclusive, inside the
/// picture) and its vertices (indices into the vertex list of the picture).
#[derive(Clone, Copy)]
pub(crate) struct Tri {
    edges: [Edge; 3],
    area: f64,
    inv_z: [f64; 3],
    pub(crate) x: (usize, usize),
    pub(crate) y: (usize, usize),
    v: [usize; 3],
}

impl Tri {
    /// Sets up triangle `v` of `verts`; `None` when it is degenerate or off the picture.
    fn new(verts: &[Cv], v: [usize; 3], view: &View) -> Option<Tri> {
        let t = v.map(|i| &verts[i]);
        let s = t.map(|p| view.screen(&p.c));
        let area = (s[1].0 - s[0].0) * (s[2].1 - s[0].1) - (s[2].0 - s[0].0) * (s[1].1 - s[0].1);
        if !area.is_finite() || area.abs() < 1e-12 {
            return None;
        }
        let lo = |k: fn(&(f64, f64)) -> f64| s.iter().map(k).fold(f64::INFINITY, f64::min);
        let hi = |k: fn(&(f64, f64)) -> f64| s.iter().map(k).fold(f64::NEG_INFINITY, f64::max);
        let minx = lo(|p| p.0).floor().max(0.0) as usize;
        let maxx = hi(|p| p.0).ceil().min(view.w as f64 - 1.0);
        let miny = lo(|p| p.1).floor().max(0.0) as usize;
        let maxy = hi(|p| p.1).ceil().min(view.h as f64 - 1.0);
        if maxx < 0.0 || maxy < 0.0 {
            return None;
        }
        let (maxx, maxy) = (maxx as usize, maxy as usize);
        if minx > maxx || miny > maxy {
            return None;
        }
        Some(Tri {
            edges: [
                Edge::new(s[1], s[2]),
                Edge::new(s[2], s[0]),
                Edge::new(s[0], s[1]),
            ],
            area,
            inv_z: t.map(|p| 1.0 / p.c.z),
            x: (minx, maxx),
            y: (miny, maxy),
            v,
        })
    }

    /// The row parts `dx (y − ay)` of the edge functions at the centres of pixel row `py`.
    #[inline]
    pub(crate) fn row(&self, py: usize) -> [f64; 3] {
        let y = py as f64 + 0.5;
        self.edges.map(|e| e.dx * (y - e.ay))
    }

    /// The edge functions at the centre of pixel `px` of the row whose parts are `row` (the
    /// same operations, in the same order, as `(b.x − a.x)(y − a.y) − (b.y − a.y)(x − a.x)`).
    #[inline]
    pub(crate) fn at(&self, row: &[f64; 3], px: usize) -> [f64; 3] {
        let x = px as f64 + 0.5;
        std::array::from_fn(|k| row[k] - self.edges[k].dy * (x - self.edges[k].ax))
    }

    /// Calls `pixel(idx, e)` for every pixel of rows `r0..r1` (a band of width `w`, `idx`
    /// counted from the band's first row) whose centre is inside the triangle, with the edge
    /// functions `e` there, rows top to bottom and pixels left to right: each row's pixels
    /// inside are one run ([`Tri::inside`]), so a row stops at the first pixel after it. The
    /// rasterization both the deferred depth pass and the canvas's forward one use.
    #[inline]
    pub(crate) fn for_each_pixel(
        &self,
        (r0, r1): (usize, usize),
        w: usize,
        mut pixel: impl FnMut(usize, &[f64; 3]),
    ) {
        for py in self.y.0.max(r0)..=self.y.1.min(r1 - 1) {
            let (row, at) = ((py - r0) * w, self.row(py));
            let mut entered = false;
            for px in self.x.0..=self.x.1 {
                let e = self.at(&at, px);
                if !self.inside(&e) {
                    if entered {
                        break;
                    }
                    continue;
                }
                entered = true;
                pixel(row + px, &e);
            }
        }
    }

    /// Whether edge function values `e` put the pixel centre inside the triangle.
    ///
    /// The test looks at the sign of each edge function against the sign of the area, which is
    /// the sign of the barycentric `e/area` the test was first written with, except where
    /// `e/area` underflows to zero (|e| below 10⁻³⁰⁸ |area|; screen coordinates never get
    /// there). Along a row each edge function is a monotone function of `px` even after
    /// rounding (a rounded difference and a rounded product by a constant are monotone), so
    /// the pixels inside form one run: the rasterizer stops a row at the first pixel after it.
    #[inline]
    pub(crate) fn inside(&self, e: &[f64; 3]) -> bool {
        if self.area > 0.0 {
            e[0] >= 0.0 && e[1] >= 0.0 && e[2] >= 0.0
        } else {
            e[0] <= 0.0 && e[1] <= 0.0 && e[2] <= 0.0
        }
    }

    /// The perspective-correct weights `λᵢ/zᵢ` for edge functions `e` and their sum `1/z`.
    #[inline]
    pub(crate) fn weights(&self, e: &[f64; 3]) -> ([f64; 3], f64) {
        let l = e.map(|e| e / self.area);
        let w = [
            l[0] * self.inv_z[0],
            l[1] * self.inv_z[1],
            l[2] * self.inv_z[2],
        ];
        let sum = w[0] + w[1] + w[2];
        (w, sum)
    }
}

/// Camera-space vertices and set-up triangles of a mesh, in chunks of [`SETUP_CHUNK`] faces
/// (kept apart, not concatenated): each chunk's triangles in face order and the vertices its
/// clipping made. A triangle's vertex `i` is the mesh's vertex `i` below `verts.len()` and the
/// chunk's own vertex `i − verts.len()` above.
pub(crate) struct Scene {
    pub(crate) verts: Vec<Cv>,
    pub(crate) chunks: Vec<(Vec<Tri>, Vec<Cv>)>,
}

/// A triangle's id: its chunk in the high half, its place in the chunk in the low half.
pub(crate) type TriId = u64;

/// One band of the depth pass: its number, its depths and nearest triangles, its triangles.
type DepthBand<'a> = (usize, ((&'a mut [f64], &'a mut [TriId]), &'a Vec<TriId>));

/// Id of "no triangle" in the per-pixel triangle buffer.
const NO_TRIANGLE: TriId = TriId::MAX;

/// Clips the faces of one chunk against the near plane and sets up their triangles. Vertices
/// made by clipping are numbered from `verts.len()` in the chunk's own list.
pub(crate) fn setup_chunk(faces: &[[usize; 3]], verts: &[Cv], view: &View) -> (Vec<Tri>, Vec<Cv>) {
    let (mut tris, mut extra) = (Vec::with_capacity(faces.len()), Vec::new());
    let n = verts.len();
    for face in faces {
        if face.iter().any(|&i| i >= n) {
            continue;
        }
        let tri = face.map(|i| verts[i]);
        if tri.iter().any(|v| !v.c.iter().all(|x| x.is_finite())) {
            continue;
        }
        if tri.iter().all(|v| v.c.z >= view.near) {
            tris.extend(Tri::new(verts, *face, view));
            continue;
        }
        // Clip against z ≥ near (Sutherland–Hodgman): at most four corners.
        let (mut poly, mut len) = ([0usize; 4], 0);
        for k in 0..3 {
            let (a, b) = (&tri[k], &tri[(k + 1) % 3]);
            let (ina, inb) = (a.c.z >= view.near, b.c.z >= view.near);
            if ina {
                poly[len] = face[k];
                len += 1;
            }
            if ina != inb {
                let t = (view.near - a.c.z) / (b.c.z - a.c.z);
                extra.push(lerp_cv(a, b, t));
                poly[len] = n + extra.len() - 1;
                len += 1;
            }
        }
        for k in 1..len.saturating_sub(1) {
            let v = [poly[0], poly[k], poly[k + 1]];
            let lookup = |i: usize| if i < n { verts[i] } else { extra[i - n] };
            let local = v.map(lookup);
            if let Some(mut t) = Tri::new(&local, [0, 1, 2], view) {
                t.v = v;
                tris.push(t);
            }
        }
    }
    (tris, extra)
}

impl Scene {
    pub(crate) fn new(mesh: &RenderMesh, view: &View, parallel: bool) -> Scene {
        let vertex = |(i, p): (usize, &Point3<f64>)| camera_vertex(mesh, view, i, p);
        let verts: Vec<Cv> = if parallel {
            mesh.positions.par_iter().enumerate().map(vertex).collect()
        } else {
            mesh.positions.iter().enumerate().map(vertex).collect()
        };
        let setup = |faces: &[[usize; 3]]| setup_chunk(faces, &verts, view);
        let chunks = if parallel {
            mesh.faces.par_chunks(SETUP_CHUNK).map(setup).collect()
        } else {
            mesh.faces.chunks(SETUP_CHUNK).map(setup).collect()
        };
        Scene { verts, chunks }
    }

    /// Every triangle with its id, in mesh order.
    pub(crate) fn tris(&self) -> impl Iterator<Item = (TriId, &Tri)> {
        self.chunks.iter().enumerate().flat_map(|(c, (tris, _))| {
            tris.iter()
                .enumerate()
                .map(move |(k, t)| (((c as TriId) << 32) | k as TriId, t))
        })
    }

    /// The triangle `id` and its three vertices.
    pub(crate) fn tri(&self, id: TriId) -> Option<(&Tri, [&Cv; 3])> {
        let (tris, extra) = self.chunks.get((id >> 32) as usize)?;
        let t = tris.get((id & 0xffff_ffff) as usize)?;
        let n = self.verts.len();
        let v =
            t.v.map(|i| if i < n { &self.verts[i] } else { &extra[i - n] });
        Some((t, v))
    }
}

/// The lights (camera space, pointing towards the light) and material of a picture.
pub(crate) struct Lighting {
    key: Vector3<f64>,
    fill: Vector3<f64>,
    exponent: Exponent,
    ambient: f64,
    key_intensity: f64,
    fill_intensity: f64,
    specular: f64,
}

impl Lighting {
    /// The lights fixed to the camera and the material of `o`.
    pub(crate) fn new(o: &RenderOptions) -> Lighting {
        Lighting {
            key: Vector3::new(-0.45, 0.65, -0.6).normalize(),
            fill: Vector3::new(0.7, -0.1, -0.7).normalize(),
            exponent: Exponent::new(o.shininess),
            ambient: o.ambient,
            key_intensity: o.key,
            fill_intensity: o.fill,
            specular: o.specular,
        }
    }
}

/// A Blinn–Phong exponent: a small whole number is raised by repeated squaring.
#[derive(Clone, Copy)]
enum Exponent {
    Integer(u32),
    Real(f64),
}

impl Exponent {
    fn new(shininess: f64) -> Exponent {
        if shininess.fract() == 0.0 && (0.0..=MAX_INTEGER_SHININESS).contains(&shininess) {
            Exponent::Integer(shininess as u32)
        } else {
            Exponent::Real(shininess)
        }
    }
}

/// `x^e` for the specular term. A whole exponent `e ≤ 1024` is raised by binary
/// exponentiation (squarings, and a multiplication per set bit, in a fixed order): each
/// rounding adds half an ulp and a squaring doubles the relative error so far, so the result
/// is within `2·e` ulps of `x^e` (2⁻⁴⁶ relative at `e` = 1024; about 1.8·10⁻¹⁴ relative and
/// in practice a few ulps at the default 40), where `powf` is within one ulp. The specular term
/// enters the pixel as `f32` and then as a byte, so such a difference changes a byte only if
/// the exact value lies within 10⁻¹⁴ of a rounding boundary of the `f32` cast and that
/// rounding then crosses a byte boundary: the 45 pictures of the ring study (exponent 40) are
/// byte-identical to those drawn with `powf`.
pub fn spec_power(x: f64, shininess: f64) -> f64 {
    pow_exponent(x, Exponent::new(shininess))
}

#[inline]
fn pow_exponent(x: f64, e: Exponent) -> f64 {
    match e {
        Exponent::Integer(mut n) => {
            let (mut result, mut base) = (1.0, x);
            while n > 0 {
                if n & 1 == 1 {
                    result *= base;
                }
                n >>= 1;
                if n > 0 {
                    base *= base;
                }
            }
            result
        }
        Exponent::Real(s) => x.powf(s),
    }
}

impl Lighting {
    fn shade(&self, n: Vector3<f64>, col: [f32; 3], pos: Vector3<f64>) -> [f32; 3] {
        let view = -pos.normalize();
        let mut n = if n.norm() > 0.0 { n.normalize() } else { view };
        if n.dot(&view) < 0.0 {
            n = -n;
        }
        let mut diffuse = self.ambient;
        let mut spec = 0.0;
        for (l, i) in [
            (&self.key, self.key_intensity),
            (&self.fill, self.fill_intensity),
        ] {
            let d = n.dot(l).max(0.0);
            diffuse += i * d;
            if d > 0.0 {
                let hv = (l + view).normalize();
                spec += i * pow_exponent(n.dot(&hv).max(0.0), self.exponent);
            }
        }
        col.map(|c| (f64::from(c) * diffuse + self.specular * spec) as f32)
    }
}

/// An interrogation mode set up for one picture, in camera space (the eye at the origin, `x`
/// right, `y` up, `z` along the view).
#[derive(Clone, Copy)]
pub(crate) enum Probe {
    /// Reflection lines: the frame `(e1, e2)` perpendicular to the axis, stripes per radian.
    Reflection {
        e1: Vector3<f64>,
        e2: Vector3<f64>,
        per_radian: f64,
        half_width: f64,
    },
    /// Isophotes: the unit light direction.
    Isophotes {
        light: Vector3<f64>,
        bands: f64,
        half_width: f64,
    },
    /// Highlight lines: the lights and the dark distance.
    Highlight {
        lights: LightLines,
        dark_within: f64,
    },
}

/// A unit vector perpendicular to the unit vector `a`, the part of `v` perpendicular to `a`
/// when that is not (nearly) zero, else that of `fallback`, else of the x axis.
fn perpendicular(a: &Vector3<f64>, v: Vector3<f64>, fallback: Vector3<f64>) -> Vector3<f64> {
    /// Below this length the perpendicular part is dominated by rounding.
    const TINY: f64 = 1e-9;
    for c in [v, fallback, Vector3::x(), Vector3::y()] {
        let p = c - a * a.dot(&c);
        if p.norm() > TINY {
            return p.normalize();
        }
    }
    Vector3::z()
}

impl Probe {
    /// Sets up `shading` for the picture `view`; `None` for [`Shading::Lit`]. The highlight
    /// lines are spaced across the scene's bounding sphere, asked of `sphere` (camera space:
    /// [`CamBox::sphere`]) only then.
    pub(crate) fn new(
        shading: &Shading,
        view: &View,
        sphere: impl FnOnce() -> (Vector3<f64>, f64),
    ) -> Result<Option<Probe>, RenderError> {
        let mode = shading.name();
        shading
            .validate()
            .map_err(|message| RenderError::Shading { mode, message })?;
        let cam = |d: &Option<Vector3<f64>>, default: Vector3<f64>| {
            d.map_or(default, |d| view.dir_to_cam(&d.normalize()).normalize())
        };
        let (up, to_eye) = (Vector3::y(), -Vector3::z());
        Ok(Some(match *shading {
            Shading::Lit => return Ok(None),
            Shading::Reflection {
                stripes,
                direction,
                width,
            } => {
                let axis = cam(&direction, up);
                let e1 = perpendicular(&axis, to_eye, up);
                Probe::Reflection {
                    e1,
                    // Camera coordinates (x right, y up, z away from the eye) are left-handed:
                    // the world's `a × e₁` is `e₁ × a` here.
                    e2: e1.cross(&axis),
                    per_radian: f64::from(stripes) / std::f64::consts::TAU,
                    half_width: width * 0.5,
                }
            }
            Shading::Isophotes {
                bands,
                light,
                width,
            } => Probe::Isophotes {
                light: cam(&light, to_eye),
                bands: f64::from(bands),
                half_width: width * 0.5,
            },
            Shading::Highlight {
                lines,
                direction,
                width,
            } => {
                let along = cam(&direction, up);
                let e = along - to_eye * to_eye.dot(&along);
                /// Below this the lights' direction is the view axis: no lines to see.
                const ALONG_VIEW: f64 = 1e-6;
                if e.norm() < ALONG_VIEW {
                    return Err(RenderError::Shading {
                        mode,
                        message: "direction along the view axis: the lights would be seen end on"
                            .into(),
                    });
                }
                let e = e.normalize();
                let (centre, radius) = sphere();
                let radius = if radius > 0.0 { radius } else { 1.0 };
                let spacing = 2.0 * radius / f64::from(lines);
                Probe::Highlight {
                    lights: LightLines {
                        a0: centre + to_eye * radius,
                        e,
                        m: to_eye,
                        t: to_eye.cross(&e),
                        spacing,
                    },
                    dark_within: width * spacing * 0.5,
                }
            }
        }))
    }

    /// The unit normal at a pixel from its interpolated normal `n` and camera-space position
    /// `pos` (the view direction where `n` is zero), and the unit view ray.
    #[inline]
    fn unit(n: Vector3<f64>, pos: Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let d = pos.normalize();
        let n = if n.norm() > 0.0 { n.normalize() } else { -d };
        (n, d)
    }

    /// The stripe parameter at a pixel ([`crate::interrogation`]): reflection `s = stripes ·
    /// θ/2π`, isophote `s = bands · (n·L + 1)/2`, highlight the light index `t`.
    #[inline]
    fn parameter(&self, n: Vector3<f64>, pos: Vector3<f64>) -> f64 {
        let (n, d) = Probe::unit(n, pos);
        match self {
            Probe::Reflection {
                e1, e2, per_radian, ..
            } => per_radian * reflection_angle(&d, &n, e1, e2),
            Probe::Isophotes { light, bands, .. } => {
                let n = if n.dot(&d) > 0.0 { -n } else { n };
                bands * (n.dot(light) + 1.0) * 0.5
            }
            Probe::Highlight { lights, .. } => lights.distance(&pos, &n).0,
        }
    }

    /// Whether a pixel is on a dark stripe.
    #[inline]
    fn dark(&self, n: Vector3<f64>, pos: Vector3<f64>) -> bool {
        match self {
            Probe::Reflection { half_width, .. } | Probe::Isophotes { half_width, .. } => {
                frac_distance(self.parameter(n, pos)) < *half_width
            }
            Probe::Highlight {
                lights,
                dark_within,
            } => {
                let (n, _) = Probe::unit(n, pos);
                lights.distance(&pos, &n).1 < *dark_within
            }
        }
    }
}

/// The bounding box of the finite camera-space vertices added so far (the highlight lines'
/// scale). The box is a minimum and a maximum, so it does not depend on the order the
/// vertices come in or on how they are split: a scene drawn in chunks gets the same box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CamBox {
    lo: Vector3<f64>,
    hi: Vector3<f64>,
}

impl Default for CamBox {
    fn default() -> Self {
        CamBox {
            lo: Vector3::repeat(f64::INFINITY),
            hi: Vector3::repeat(f64::NEG_INFINITY),
        }
    }
}

impl CamBox {
    /// Adds a camera-space vertex (left out when not finite).
    #[inline]
    pub(crate) fn add(&mut self, c: &Vector3<f64>) {
        if c.iter().all(|x| x.is_finite()) {
            self.lo = self.lo.inf(c);
            self.hi = self.hi.sup(c);
        }
    }

    /// Centre and radius of the box's bounding sphere (the origin and 0 when empty).
    pub(crate) fn sphere(&self) -> (Vector3<f64>, f64) {
        let (lo, hi) = (self.lo, self.hi);
        if lo.x > hi.x {
            return (Vector3::zeros(), 0.0);
        }
        ((lo + hi) * 0.5, (hi - lo).norm() * 0.5)
    }
}

impl Scene {
    /// Centre and radius of the bounding sphere of the finite vertices' bounding box
    /// (camera space; the origin and 0 when there are none).
    fn bounding_sphere(&self) -> (Vector3<f64>, f64) {
        let mut b = CamBox::default();
        for v in &self.verts {
            b.add(&v.c);
        }
        b.sphere()
    }
}

/// How a covered pixel is coloured, straight to sRGB bytes: lit, or dark and light stripes of
/// an interrogation mode. [`render`]'s shading pass and [`crate::canvas::Canvas`] both colour
/// with it, so a pixel shaded by either from the same triangle and weights has the same bytes.
pub(crate) struct Painter {
    lighting: Lighting,
    probe: Option<Probe>,
    srgb: &'static Srgb8Table,
    dark: [u8; 3],
    light: [u8; 3],
}

impl Painter {
    /// The painter of `probe` (`None`: lit with `lighting`).
    pub(crate) fn new(lighting: Lighting, probe: Option<Probe>) -> Painter {
        let srgb = Srgb8Table::get();
        Painter {
            lighting,
            probe,
            srgb,
            dark: srgb.encode3(DARK),
            light: srgb.encode3(LIGHT),
        }
    }

    /// The bytes of a pixel of the triangle with vertices `v` at the perspective-correct
    /// barycentric weights `a, b, c`.
    #[inline]
    pub(crate) fn paint(&self, v: [&Cv; 3], a: f64, b: f64, c: f64) -> [u8; 3] {
        let (n, pos) = normal_position(v, a, b, c);
        match &self.probe {
            None => {
                let (af, bf, cf) = (a as f32, b as f32, c as f32);
                let col =
                    std::array::from_fn(|k| v[0].col[k] * af + v[1].col[k] * bf + v[2].col[k] * cf);
                self.srgb.encode3(self.lighting.shade(n, col, pos))
            }
            Some(p) => {
                if p.dark(n, pos) {
                    self.dark
                } else {
                    self.light
                }
            }
        }
    }
}

/// The depth pass's result, ready for the shading pass.
struct Frame<'a> {
    scene: &'a Scene,
    nearest: &'a [TriId],
    w: usize,
    parallel: bool,
    /// The wireframe's pixels (empty without a wireframe).
    wire_mask: Vec<bool>,
}

impl Frame<'_> {
    /// Colours every pixel of `out` (`K` elements a pixel, rows top to bottom): a wireframe
    /// pixel `wire` (where `mask` says), a pixel without a triangle `background`, a covered
    /// pixel `f(vertices, a, b, c)` of its triangle's perspective-correct barycentric weights.
    fn shade<E, const K: usize, F>(
        &self,
        out: &mut [E],
        background: [E; K],
        wire: Option<([E; K], &[bool])>,
        f: F,
    ) where
        E: Copy + Send + Sync,
        F: Fn([&Cv; 3], f64, f64, f64) -> [E; K] + Sync,
    {
        let (w, scene, nearest) = (self.w, self.scene, self.nearest);
        let shade_band = |(b, out): (usize, &mut [E])| {
            let r0 = b * BAND_ROWS;
            for (i, px) in out.chunks_exact_mut(K).enumerate() {
                let idx = r0 * w + i;
                let colour = match wire {
                    Some((c, mask)) if mask.get(idx) == Some(&true) => c,
                    _ => match scene.tri(nearest[idx]) {
                        None => background,
                        Some((t, v)) => {
                            let (x, y) = (idx % w, idx / w);
                            let e = t.at(&t.row(y), x);
                            match t.inside(&e) {
                                true => {
                                    let (wt, sum) = t.weights(&e);
                                    f(v, wt[0] / sum, wt[1] / sum, wt[2] / sum)
                                }
                                false => background,
                            }
                        }
                    },
                };
                px.copy_from_slice(&colour);
            }
        };
        if self.parallel {
            out.par_chunks_mut(K * BAND_ROWS * w)
                .enumerate()
                .for_each(shade_band);
        } else {
            out.chunks_mut(K * BAND_ROWS * w)
                .enumerate()
                .for_each(shade_band);
        }
    }
}

/// The interpolated normal and camera-space position of a pixel.
#[inline]
pub(crate) fn normal_position(v: [&Cv; 3], a: f64, b: f64, c: f64) -> (Vector3<f64>, Vector3<f64>) {
    (
        v[0].n * a + v[1].n * b + v[2].n * c,
        v[0].c * a + v[1].c * b + v[2].c * c,
    )
}

/// Renders `mesh` seen by `camera`.
///
/// Parallel inside (rayon): the vertices are transformed and the triangles set up in chunks,
/// then horizontal bands of 16 rows are rasterized and shaded on their own. Shading
/// is deferred: the depth pass keeps, per pixel, the nearest triangle (the first of equally
/// near ones, as before), and each visible pixel is shaded once. The bytes are the same on
/// every run and for any number of threads. To draw many pictures, [`render_many`] also runs
/// the pictures in parallel. An interrogation mode ([`RenderOptions::shading`]) with numbers
/// out of range is an error ([`Shading::validate`]).
pub fn render(
    mesh: &RenderMesh,
    camera: &Camera,
    options: &RenderOptions,
) -> Result<Image, RenderError> {
    render_with(mesh, camera, options, true)
}

/// Per-pixel values of a picture, rows top to bottom; NaN where no triangle is seen.
#[derive(Clone, Debug, PartialEq)]
pub struct Field {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width · height` values.
    pub values: Vec<f64>,
}

impl Field {
    /// The value at pixel `(x, y)` (NaN outside the picture).
    pub fn at(&self, x: u32, y: u32) -> f64 {
        if x >= self.width || y >= self.height {
            return f64::NAN;
        }
        self.values[(y * self.width + x) as usize]
    }
}

/// The stripe parameter of [`RenderOptions::shading`] at every pixel [`render`] would draw
/// (same camera, same nearest triangle, same interpolation; the wireframe is not drawn):
/// reflection lines `s = stripes · θ/2π` (dark within `width/2` of a whole number; it jumps
/// by `stripes` where `θ` passes ±π), isophotes `s = bands · (n·L + 1)/2`, highlight lines
/// the continuous light index `t` (NaN where the normal line is parallel to the lights'
/// plane), and for [`Shading::Lit`] the key light's `n·l` (two-sided). For measuring what the
/// stripes show: a jump of `s` between neighbouring pixels is a break of the stripes.
pub fn interrogation_field(
    mesh: &RenderMesh,
    camera: &Camera,
    options: &RenderOptions,
) -> Result<Field, RenderError> {
    let o = RenderOptions {
        wireframe: None,
        ..options.clone()
    };
    let mut values = Vec::new();
    let (w, h) = draw(mesh, camera, &o, true, |frame, view, lighting| {
        values = vec![0.0f64; frame.w * view.h];
        match Probe::new(&o.shading, view, || frame.scene.bounding_sphere())? {
            None => frame.shade(&mut values, [f64::NAN], None, |v, a, b, c| {
                let (n, pos) = normal_position(v, a, b, c);
                let (mut n, d) = Probe::unit(n, pos);
                if n.dot(&d) > 0.0 {
                    n = -n;
                }
                [n.dot(&lighting.key)]
            }),
            Some(p) => frame.shade(&mut values, [f64::NAN], None, |v, a, b, c| {
                let (n, pos) = normal_position(v, a, b, c);
                [p.parameter(n, pos)]
            }),
        }
        Ok(())
    })?;
    Ok(Field {
        width: w as u32,
        height: h as u32,
        values,
    })
}

/// [`render`], parallel inside or not (the bytes are the same either way).
fn render_with(
    mesh: &RenderMesh,
    camera: &Camera,
    options: &RenderOptions,
    parallel: bool,
) -> Result<Image, RenderError> {
    let mut rgb = Vec::new();
    let (w, h) = draw(mesh, camera, options, parallel, |frame, view, lighting| {
        // Shading pass: every visible pixel once, straight to sRGB bytes.
        let srgb = Srgb8Table::get();
        let background = srgb.encode3(options.background);
        let wire = options
            .wireframe
            .map(|c| (srgb.encode3(c), &frame.wire_mask[..]));
        rgb = vec![0u8; 3 * frame.w * view.h];
        let probe = Probe::new(&options.shading, view, || frame.scene.bounding_sphere())?;
        let painter = Painter::new(lighting, probe);
        frame.shade(&mut rgb, background, wire, |v, a, b, c| {
            painter.paint(v, a, b, c)
        });
        Ok(())
    })?;
    Ok(Image {
        width: w as u32,
        height: h as u32,
        rgb,
    })
}

/// The set-up, depth pass and wireframe mask of a picture, then `shade` with them; the
/// picture's size.
fn draw<S>(
    mesh: &RenderMesh,
    camera: &Camera,
    options: &RenderOptions,
    parallel: bool,
    shade: S,
) -> Result<(usize, usize), RenderError>
where
    S: FnOnce(&Frame<'_>, &View, Lighting) -> Result<(), RenderError>,
{
    // Refused before any drawing (`Probe::new` sets the mode up after the depth pass).
    options
        .shading
        .validate()
        .map_err(|message| RenderError::Shading {
            mode: options.shading.name(),
            message,
        })?;
    let (w, h) = (
        options.width.max(1) as usize,
        options.height.max(1) as usize,
    );
    let view = View::new(camera, (w, h));
    let lighting = Lighting::new(options);
    let scene = Scene::new(mesh, &view, parallel);

    // The triangles reaching each band, in mesh order.
    let bands = h.div_ceil(BAND_ROWS);
    let mut per_band: Vec<Vec<TriId>> = vec![Vec::new(); bands];
    for (k, t) in scene.tris() {
        for list in &mut per_band[t.y.0 / BAND_ROWS..=t.y.1 / BAND_ROWS] {
            list.push(k);
        }
    }

    // Depth pass: the nearest triangle of every pixel.
    let mut depth = vec![f64::INFINITY; w * h];
    let mut nearest = vec![NO_TRIANGLE; w * h];
    let depth_band = |(b, ((depth, nearest), list)): DepthBand<'_>| {
        let (r0, r1) = (b * BAND_ROWS, (b * BAND_ROWS + depth.len() / w).min(h));
        for &k in list {
            let Some((t, _)) = scene.tri(k) else {
                continue;
            };
            t.for_each_pixel((r0, r1), w, |idx, e| {
                let z = 1.0 / t.weights(e).1;
                if z >= depth[idx] {
                    return;
                }
                depth[idx] = z;
                nearest[idx] = k;
            });
        }
    };
    if parallel {
        depth
            .par_chunks_mut(BAND_ROWS * w)
            .zip(nearest.par_chunks_mut(BAND_ROWS * w))
            .zip(per_band.par_iter())
            .enumerate()
            .for_each(depth_band);
    } else {
        depth
            .chunks_mut(BAND_ROWS * w)
            .zip(nearest.chunks_mut(BAND_ROWS * w))
            .zip(per_band.iter())
            .enumerate()
            .for_each(depth_band);
    }

    let mut wire_mask = Vec::new();
    if options.wireframe.is_some() {
        wire_mask = vec![false; w * h];
        for face in &mesh.faces {
            if face.iter().any(|&i| i >= mesh.positions.len()) {
                continue;
            }
            let c = face.map(|i| scene.verts[i].c);
            for k in 0..3 {
                draw_edge(&c[k], &c[(k + 1) % 3], &view, &depth, &mut wire_mask);
            }
        }
    }

    let frame = Frame {
        scene: &scene,
        nearest: &nearest,
        w,
        parallel,
        wire_mask,
    };
    shade(&frame, &view, lighting)?;
    Ok((w, h))
}

/// Renders every `(mesh, camera)` pair with the same options, in parallel over the pictures
/// (each picture drawn by one thread: with many pictures that keeps every core busy without
/// the hand-offs of [`render`]'s bands); the images come back in the order of `jobs`, byte for
/// byte what [`render`] gives for each. The first failing job's error (in `jobs` order) is
/// returned.
pub fn render_many(
    jobs: &[(&RenderMesh, &Camera)],
    options: &RenderOptions,
) -> Result<Vec<Image>, RenderError> {
    let images: Vec<Result<Image, RenderError>> = jobs
        .par_iter()
        .map(|(mesh, camera)| render_with(mesh, camera, options, false))
        .collect();
    images.into_iter().collect()
}

/// Relative depth tolerance of the wireframe against the filled surface it lies on.
const WIRE_DEPTH_BIAS: f64 = 2e-3;

/// Marks the pixels of one camera-space edge, drawn as a 1-pixel line, where it is not hidden.
fn draw_edge(a: &Vector3<f64>, b: &Vector3<f64>, view: &View, depth: &[f64], mask: &mut [bool]) {
    let (w, h) = (view.w, view.h);
    if !(a.iter().chain(b.iter()).all(|x| x.is_finite())) || a.z < view.near || b.z < view.near {
        return;
    }
    let (p, q) = (view.screen(a), view.screen(b));
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
            mask[idx] = true;
        }
    }
}

/// The colour of [`wire_frame`]'s lines (dark blue, sRGB bytes).
pub const WIRE_COLOUR: [u8; 3] = [20, 20, 60];

/// Every triangle edge of `mesh` as a one-pixel [`WIRE_COLOUR`] line on white, seen by
/// `camera` as [`render`] projects (the testbed's XRender: no hidden lines removed). Points
/// behind the eye are skipped with their edges; an edge is drawn with at most 10⁵ steps.
pub fn wire_frame(mesh: &RenderMesh, camera: &Camera, w: u32, h: u32) -> Image {
    let mut img = blank_wire_frame(w, h);
    draw_wire_frame(&mut img, mesh, camera);
    img
}

/// The white picture [`wire_frame`] draws its lines on.
pub fn blank_wire_frame(w: u32, h: u32) -> Image {
    Image {
        width: w,
        height: h,
        rgb: vec![255u8; 3 * w as usize * h as usize],
    }
}

/// Draws the edges of `mesh` onto `img` as [`wire_frame`] does: a picture drawn from a mesh in
/// parts, one call a part onto the same [`blank_wire_frame`], is the picture of the whole
/// (every line is drawn in one colour, without a depth test, so neither the order nor the
/// split changes a byte).
pub fn draw_wire_frame(img: &mut Image, mesh: &RenderMesh, camera: &Camera) {
    /// Most steps one edge is drawn with: a far longer edge is clipped by the picture anyway.
    const MAX_STEPS: f64 = 1e5;
    let (w, h) = (img.width, img.height);
    let f = (camera.target - camera.eye).normalize();
    let r = f.cross(&camera.up).normalize();
    let u = r.cross(&f);
    let fpx = (f64::from(h) * 0.5) / (camera.fov_y_degrees.to_radians() * 0.5).tan();
    let project = |p: &Point3<f64>| -> Option<(f64, f64)> {
        let d = p - camera.eye;
        let z = d.dot(&f);
        (z > 0.0 && z.is_finite()).then(|| {
            (
                f64::from(w) * 0.5 + fpx * d.dot(&r) / z,
                f64::from(h) * 0.5 - fpx * d.dot(&u) / z,
            )
        })
    };
    for face in &mesh.faces {
        for k in 0..3 {
            let (Some(a), Some(b)) = (
                mesh.positions.get(face[k]).and_then(project),
                mesh.positions.get(face[(k + 1) % 3]).and_then(project),
            ) else {
                continue;
            };
            let steps = (b.0 - a.0)
                .abs()
                .max((b.1 - a.1).abs())
                .ceil()
                .min(MAX_STEPS) as usize
                + 1;
            for i in 0..=steps {
                let t = i as f64 / steps as f64;
                let (x, y) = (a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t);
                if x >= 0.0 && y >= 0.0 && x < f64::from(w) && y < f64::from(h) {
                    let at = 3 * (y as usize * w as usize + x as usize);
                    if let Some(px) = img.rgb.get_mut(at..at + 3) {
                        px.copy_from_slice(&WIRE_COLOUR);
                    }
                }
            }
        }
    }
}

/// Encodes `rgb` (`3 · w · h` bytes) as an 8-bit RGB PNG into `out`.
pub fn write_rgb_png(
    rgb: &[u8],
    w: u32,
    h: u32,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    let mut enc = png::Encoder::new(out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    writer
        .write_image_data(rgb)
        .map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}

/// Encodes an image as PNG into `out` (a pipe, a buffer; files go through
/// `meshio::outfile::write_atomic_with`).
pub fn write_png(image: &Image, out: &mut dyn std::io::Write) -> std::io::Result<()> {
    write_rgb_png(&image.rgb, image.width, image.height, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wire_frame_draws_every_edge_and_the_png_reads_back() {
        let mesh = RenderMesh {
            positions: vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
            ],
            normals: vec![Vector3::z(); 3],
            colors: vec![[0.5; 3]; 3],
            faces: vec![[0, 1, 2]],
        };
        let camera = Camera::framing(
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 1.0, 0.0),
            0.0,
            90.0,
        );
        let img = wire_frame(&mesh, &camera, 64, 48);
        let lines = img.rgb.chunks(3).filter(|p| *p == WIRE_COLOUR).count();
        // Three edges across a 64×48 picture: well over a hundred pixels, far from all.
        assert!(lines > 100 && lines < 64 * 48 / 2, "{lines}");
        let mut bytes = Vec::new();
        write_png(&img, &mut bytes).expect("encodes");
        let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .expect("a PNG");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("a frame");
        assert_eq!((info.width, info.height), (64, 48));
        assert_eq!(&buf[..info.buffer_size()], &img.rgb[..]);
    }

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

    /// A torus of `nu × nv` quads (two triangles each), coloured by position, with a few
    /// triangles through the near plane of [`top_camera`] and one bad face.
    fn busy_mesh(nu: usize, nv: usize) -> RenderMesh {
        let mut m = RenderMesh::default();
        for i in 0..nu {
            for j in 0..nv {
                let tau = std::f64::consts::TAU;
                let (u, v) = (tau * i as f64 / nu as f64, tau * j as f64 / nv as f64);
                let n = Vector3::new(v.cos() * u.cos(), v.cos() * u.sin(), v.sin());
                m.positions
                    .push(Point3::new(u.cos(), u.sin(), 0.0) * 2.0 + n * 0.8);
                m.normals.push(n);
                m.colors.push([(u / tau) as f32, (v / tau) as f32, 0.5]);
                let at = |a: usize, b: usize| (a % nu) * nv + b % nv;
                m.faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                m.faces.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        // Through the near plane (the eye is at z = 5) and an out-of-range index.
        let base = m.positions.len();
        m.positions.extend([
            Point3::new(-1.0, -1.0, 0.0),
            Point3::new(1.0, -1.0, 0.0),
            Point3::new(0.0, 0.3, 9.0),
        ]);
        m.normals.extend([Vector3::z(); 3]);
        m.colors.extend([[0.9, 0.2, 0.1]; 3]);
        m.faces.push([base, base + 1, base + 2]);
        m.faces.push([0, 1, base + 7]);
        m
    }

    #[test]
    fn rendering_is_deterministic_for_any_thread_count() {
        // More faces than one setup chunk, so chunks and bands both split the work.
        let m = busy_mesh(120, 40);
        assert!(m.faces.len() > 2 * SETUP_CHUNK);
        let cam = Camera {
            eye: Point3::new(0.5, -6.0, 3.0),
            ..top_camera()
        };
        for wireframe in [None, Some([0.1, 0.1, 0.1])] {
            let o = RenderOptions {
                width: 301,
                height: 203,
                wireframe,
                ..RenderOptions::default()
            };
            let first = render(&m, &cam, &o).unwrap();
            assert!(first.rgb.iter().any(|c| *c < 200), "something drawn");
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let again = pool.install(|| render(&m, &cam, &o)).unwrap();
                assert!(again == first, "{threads} threads");
            }
            let serial = render_with(&m, &cam, &o, false).unwrap();
            assert!(serial == first);
            let cams = [cam, top_camera(), cam];
            let jobs: Vec<(&RenderMesh, &Camera)> = cams.iter().map(|c| (&m, c)).collect();
            let many = render_many(&jobs, &o).unwrap();
            assert_eq!(many.len(), 3);
            assert!(many[0] == first && many[2] == first);
            assert!(many[1] == render(&m, &top_camera(), &o).unwrap());
        }
        assert!(render_many(&[], &RenderOptions::default())
            .unwrap()
            .is_empty());
    }

    #[test]
    fn interrogation_modes_are_deterministic_and_refuse_bad_numbers() {
        let m = busy_mesh(120, 40);
        let cam = Camera {
            eye: Point3::new(0.5, -6.0, 3.0),
            ..top_camera()
        };
        for shading in [Shading::REFLECTION, Shading::ISOPHOTES, Shading::HIGHLIGHT] {
            let o = RenderOptions {
                width: 301,
                height: 203,
                shading,
                ..RenderOptions::default()
            };
            let first = render(&m, &cam, &o).unwrap();
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(3)
                .build()
                .unwrap();
            assert!(pool.install(|| render(&m, &cam, &o)).unwrap() == first);
            assert!(render_with(&m, &cam, &o, false).unwrap() == first);
            // Two tones and the background only.
            let mut tones: Vec<u8> = first.rgb.clone();
            tones.sort_unstable();
            tones.dedup();
            assert_eq!(tones.len(), 3, "{shading:?}: {tones:?}");
        }
        let bad = RenderOptions {
            shading: Shading::Isophotes {
                bands: 0,
                light: None,
                width: 0.5,
            },
            ..RenderOptions::default()
        };
        let err = render(&m, &cam, &bad).unwrap_err().to_string();
        assert!(
            err.contains("isophotes") && err.contains("stripes 0"),
            "{err}"
        );
    }

    /// Relative accuracy promised by [`spec_power`] for whole exponents `e`: `2·e` ulps.
    fn spec_bound(e: u32) -> f64 {
        2.0 * f64::from(e) * f64::EPSILON
    }

    #[test]
    fn specular_power_matches_powf() {
        for e in [0u32, 1, 2, 3, 5, 17, 40, 64, 255, 1024] {
            for i in 0..=2000 {
                let x = f64::from(i) / 2000.0;
                let (fast, exact) = (spec_power(x, f64::from(e)), x.powf(f64::from(e)));
                assert!(
                    (fast - exact).abs() <= spec_bound(e) * exact,
                    "{x}^{e}: {fast} vs {exact}"
                );
            }
        }
        // Fractional, negative and large exponents go through powf.
        for e in [40.5, -2.0, 2000.0, f64::NAN] {
            assert!(spec_power(0.7f64, e).to_bits() == 0.7f64.powf(e).to_bits());
        }
    }

    #[test]
    fn srgb_encoding_endpoints() {
        assert_eq!(to_srgb8(0.0), 0);
        assert_eq!(to_srgb8(1.0), 255);
        assert_eq!(to_srgb8(0.2159), 128); // sRGB 0.502
    }
}

//! A picture drawn from triangles as they come, in bounded memory: [`Canvas`].
//!
//! [`crate::render`] holds the whole mesh: a depth pass keeps, per pixel, the nearest
//! triangle's id, and a shading pass then colours each visible pixel once from that triangle,
//! so every triangle must stay alive until the end. A canvas instead keeps per pixel only a
//! depth (`f64`) and the RGB bytes, and is fed the triangles in parts ([`Canvas::draw`]); each
//! part can be dropped once drawn, so the memory is the pixel buffers plus one part, whatever
//! the whole holds.
//!
//! Forward shading gives the same bytes as the deferred pass. Both visit a pixel's fragments
//! in mesh order (the parts in the order given, each part's faces in order; a band draws the
//! triangles that reach it in that order) and keep a fragment only if it is strictly nearer
//! than the depth so far (`z < depth`; the first of equally near ones stays). So the fragment
//! that last passes the test at a pixel is the one the depth pass leaves as its nearest
//! triangle. The canvas colours each fragment that passes, at once, by the same function
//! (`shade::Painter`) of the same values — the triangle set up by the same code
//! (`shade::setup_chunk`), the edge functions at the pixel centre (`Tri::at`) and the
//! perspective-correct weights (`Tri::weights`) — so the last colour written is the colour
//! the shading pass gives that triangle there. Overdrawn fragments are shaded in vain (the
//! price of not keeping the triangles), never wrongly.
//!
//! Two things need the whole scene before the first pixel is drawn, and are given to the
//! canvas up front: the camera (the caller's; `Camera::framing_passes` frames points visited
//! twice), and for highlight lines the scene's camera-space bounding box ([`SceneBounds`],
//! one pass over the points before drawing). The wireframe overlay
//! ([`RenderOptions::wireframe`]) needs the finished depth buffer to hide its lines, so a
//! canvas refuses it ([`RenderError::Unsupported`]); [`crate::render`] draws it.

use nalgebra::Point3;
use rayon::prelude::*;

use crate::error::RenderError;
use crate::shade::{
    CamBox, Camera, Image, Lighting, Painter, Probe, RenderMesh, RenderOptions, Scene, Shading,
    TriId, View, BAND_ROWS,
};
use crate::srgb::Srgb8Table;

/// The camera-space bounding box of a scene's finite vertices, gathered over its parts before
/// drawing: the highlight lines are spaced across its bounding sphere, as [`crate::render`]
/// spaces them across the whole mesh's. Other modes do not use it
/// ([`SceneBounds::needed`]).
pub struct SceneBounds {
    view: View,
    cam: CamBox,
}

impl SceneBounds {
    /// No points yet, seen by `camera`.
    pub fn new(camera: &Camera) -> SceneBounds {
        SceneBounds {
            // The camera frame does not depend on the picture's size.
            view: View::new(camera, (1, 1)),
            cam: CamBox::default(),
        }
    }

    /// Whether `shading` uses the bounds (highlight lines); for other modes a [`Canvas`] may
    /// be given empty bounds.
    pub fn needed(shading: &Shading) -> bool {
        matches!(shading, Shading::Highlight { .. })
    }

    /// Adds the vertices of a part of the scene (every position, as [`crate::render`] takes
    /// every position of its mesh, whether a face uses it or not; those not finite are left
    /// out).
    pub fn add(&mut self, points: &[Point3<f64>]) {
        for p in points {
            self.cam.add(&self.view.to_cam(p));
        }
    }
}

/// One band of a part's drawing: its number, its depths and RGB bytes, the ids of the
/// triangles reaching it.
type Band<'a> = (usize, ((&'a mut [f64], &'a mut [u8]), &'a Vec<TriId>));

/// A picture being drawn part by part (module docs): per pixel its depth and RGB bytes.
pub struct Canvas {
    view: View,
    painter: Painter,
    depth: Vec<f64>,
    rgb: Vec<u8>,
}

impl Canvas {
    /// A canvas of `options`' size and shading seen by `camera`, every pixel the background.
    /// `bounds` holds the whole scene's vertices when the shading needs them
    /// ([`SceneBounds::needed`]). Errors: a shading mode out of range or seen end on
    /// ([`RenderError::Shading`], as [`crate::render`]), a wireframe
    /// ([`RenderError::Unsupported`]).
    pub fn new(
        camera: &Camera,
        options: &RenderOptions,
        bounds: &SceneBounds,
    ) -> Result<Canvas, RenderError> {
        if options.wireframe.is_some() {
            return Err(RenderError::Unsupported(
                "the wireframe overlay needs the whole depth buffer before its lines are drawn: \
                 draw it with render::render"
                    .into(),
            ));
        }
        let (w, h) = (
            options.width.max(1) as usize,
            options.height.max(1) as usize,
        );
        let view = View::new(camera, (w, h));
        let probe = Probe::new(&options.shading, &view, || bounds.cam.sphere())?;
        let background = Srgb8Table::get().encode3(options.background);
        Ok(Canvas {
            view,
            painter: Painter::new(Lighting::new(options), probe),
            depth: vec![f64::INFINITY; w * h],
            rgb: background.repeat(w * h),
        })
    }

    /// Draws the triangles of `mesh` over what is drawn so far (module docs: the picture of
    /// parts drawn in turn is that of their concatenation). Parallel over bands of rows; the
    /// bytes do not depend on the number of threads.
    pub fn draw(&mut self, mesh: &RenderMesh) {
        if mesh.faces.is_empty() {
            return;
        }
        let view = &self.view;
        let (w, h) = (view.w, view.h);
        let scene = Scene::new(mesh, view, true);
        let mut per_band = vec![Vec::new(); h.div_ceil(BAND_ROWS)];
        for (k, t) in scene.tris() {
            for list in &mut per_band[t.y.0 / BAND_ROWS..=t.y.1 / BAND_ROWS] {
                list.push(k);
            }
        }
        let painter = &self.painter;
        let band = |(b, ((depth, rgb), list)): Band<'_>| {
            let (r0, r1) = (b * BAND_ROWS, (b * BAND_ROWS + depth.len() / w).min(h));
            for &k in list {
                let Some((t, v)) = scene.tri(k) else {
                    continue;
                };
                t.for_each_pixel((r0, r1), w, |idx, e| {
                    let (wt, sum) = t.weights(e);
                    let z = 1.0 / sum;
                    if z >= depth[idx] {
                        return;
                    }
                    depth[idx] = z;
                    rgb[3 * idx..3 * idx + 3].copy_from_slice(&painter.paint(
                        v,
                        wt[0] / sum,
                        wt[1] / sum,
                        wt[2] / sum,
                    ));
                });
            }
        };
        self.depth
            .par_chunks_mut(BAND_ROWS * w)
            .zip(self.rgb.par_chunks_mut(3 * BAND_ROWS * w))
            .zip(per_band.par_iter())
            .enumerate()
            .for_each(band);
    }

    /// The picture drawn.
    pub fn finish(self) -> Image {
        Image {
            width: self.view.w as u32,
            height: self.view.h as u32,
            rgb: self.rgb,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::{blank_wire_frame, draw_wire_frame, render, wire_frame};
    use nalgebra::Vector3;
    use proptest::prelude::*;

    /// Picture size of the comparisons: small enough for many cases, several bands tall.
    const W: u32 = 61;
    /// See [`W`].
    const H: u32 = 53;

    /// Looks down the z axis from z = 5: world points above z ≈ 4.995 are behind its near
    /// plane (`1e-3` of the distance to the target), those above 5 behind the eye.
    fn camera() -> Camera {
        Camera {
            eye: Point3::new(0.3, -0.2, 5.0),
            target: Point3::new(0.0, 0.1, 0.0),
            up: Vector3::y(),
            fov_y_degrees: 60.0,
        }
    }

    fn modes() -> [Shading; 4] {
        [
            Shading::Lit,
            Shading::REFLECTION,
            Shading::ISOPHOTES,
            Shading::HIGHLIGHT,
        ]
    }

    /// A triangle of the random meshes: three corners, a colour, what to do with it.
    #[derive(Clone, Debug)]
    struct Spec {
        corners: [[f64; 3]; 3],
        normals: Option<[[f64; 3]; 3]>,
        color: [f32; 3],
        kind: u8,
    }

    fn spec() -> impl Strategy<Value = Spec> {
        let coord = || -2.5f64..2.5;
        let depth = -1.0f64..7.0;
        let corner = move || (coord(), coord(), depth.clone()).prop_map(|(x, y, z)| [x, y, z]);
        let normal = || (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0).prop_map(|(x, y, z)| [x, y, z]);
        (
            [corner(), corner(), corner()],
            proptest::option::of([normal(), normal(), normal()]),
            [0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0],
            0u8..10,
        )
            .prop_map(|(corners, normals, color, kind)| Spec {
                corners,
                normals,
                color,
                kind,
            })
    }

    /// An unwelded mesh (three vertices a face, as the testbed draws a stream): mostly plain
    /// triangles, some crossing the near plane or behind the eye (the random depths), some
    /// degenerate (a corner repeated: kind 0), not finite (kind 1), or the previous triangle
    /// again in another colour at exactly the same depth (kind 2).
    fn mesh_of(specs: &[Spec]) -> RenderMesh {
        let mut m = RenderMesh::default();
        let mut last: Option<[[f64; 3]; 3]> = None;
        for s in specs {
            let mut c = s.corners;
            match s.kind {
                0 => c[2] = c[0],
                1 => c[1][0] = f64::NAN,
                2 => c = last.unwrap_or(c),
                _ => {}
            }
            last = Some(c);
            let p: Vec<Point3<f64>> = c.iter().map(|c| Point3::new(c[0], c[1], c[2])).collect();
            let geometric = (p[1] - p[0]).cross(&(p[2] - p[0]));
            let base = m.positions.len();
            for (k, q) in p.into_iter().enumerate() {
                m.positions.push(q);
                m.normals
                    .push(s.normals.map_or(geometric, |n| Vector3::from(n[k])));
                m.colors.push(s.color);
            }
            m.faces.push([base, base + 1, base + 2]);
        }
        m
    }

    /// Faces `from..to` of an unwelded mesh with their own vertices, numbered from 0.
    fn part(m: &RenderMesh, from: usize, to: usize) -> RenderMesh {
        RenderMesh {
            positions: m.positions[3 * from..3 * to].to_vec(),
            normals: m.normals[3 * from..3 * to].to_vec(),
            colors: m.colors[3 * from..3 * to].to_vec(),
            faces: m.faces[from..to]
                .iter()
                .map(|f| f.map(|i| i - 3 * from))
                .collect(),
        }
    }

    /// The picture of `parts` drawn in turn on a canvas (the bounds from every part first).
    fn canvas_picture(
        parts: &[RenderMesh],
        camera: &Camera,
        o: &RenderOptions,
    ) -> Result<Image, RenderError> {
        let mut bounds = SceneBounds::new(camera);
        for p in parts {
            bounds.add(&p.positions);
        }
        let mut canvas = Canvas::new(camera, o, &bounds)?;
        for p in parts {
            canvas.draw(p);
        }
        Ok(canvas.finish())
    }

    fn options(shading: Shading) -> RenderOptions {
        RenderOptions {
            width: W,
            height: H,
            shading,
            ..RenderOptions::default()
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// The canvas fed the mesh in parts of random sizes draws `render`'s picture, byte for
        /// byte, in every shading mode.
        #[test]
        fn canvas_in_random_parts_draws_renders_picture(
            specs in proptest::collection::vec(spec(), 1..60),
            cuts in proptest::collection::vec(0usize..60, 0..6),
        ) {
            let m = mesh_of(&specs);
            let n = m.faces.len();
            let mut cuts: Vec<usize> = cuts.into_iter().map(|c| c % (n + 1)).collect();
            cuts.extend([0, n]);
            cuts.sort_unstable();
            let parts: Vec<RenderMesh> = cuts.windows(2).map(|c| part(&m, c[0], c[1])).collect();
            for shading in modes() {
                let o = options(shading);
                let whole = render(&m, &camera(), &o).unwrap();
                let drawn = canvas_picture(&parts, &camera(), &o).unwrap();
                prop_assert!(drawn == whole, "{:?}", shading);
            }
        }

        /// `framing_passes` over the points in slices of random lengths gives
        /// `framing_points`' camera bit for bit (non-finite points among them).
        #[test]
        fn two_pass_framing_is_framing_points(
            pts in proptest::collection::vec((-1e3f64..1e3, -1e3f64..1e3, -1e3f64..1e3, 0u8..12), 0..40),
            cuts in proptest::collection::vec(0usize..40, 0..5),
            az in -360.0f64..360.0,
            el in -90.0f64..90.0,
            aspect in 0.2f64..5.0,
        ) {
            let points: Vec<Point3<f64>> = pts
                .iter()
                .map(|&(x, y, z, k)| match k {
                    0 => Point3::new(f64::NAN, y, z),
                    1 => Point3::new(x, f64::INFINITY, z),
                    _ => Point3::new(x, y, z),
                })
                .collect();
            let n = points.len();
            let mut cuts: Vec<usize> = cuts.into_iter().map(|c| c % (n + 1)).collect();
            cuts.extend([0, n]);
            cuts.sort_unstable();
            let mut passes = 0;
            let two = Camera::framing_passes(
                |visit| {
                    passes += 1;
                    for c in cuts.windows(2) {
                        visit(&points[c[0]..c[1]]);
                    }
                    Ok::<(), ()>(())
                },
                az,
                el,
                aspect,
            )
            .unwrap();
            let one = Camera::framing_points(&points, az, el, aspect);
            let bits = |c: &Camera| {
                [c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y, c.up.z, c.fov_y_degrees]
                    .map(f64::to_bits)
            };
            prop_assert_eq!(bits(&two), bits(&one));
            prop_assert!(passes <= 2);
            // The box gathered as the points come, then one pass.
            let mut bounds = crate::shade::FrameBox::default();
            for c in cuts.windows(2) {
                bounds.add(&points[c[0]..c[1]]);
            }
            let boxed = Camera::framing_box(
                &bounds,
                |visit| {
                    visit(&points);
                    Ok::<(), ()>(())
                },
                az,
                el,
                aspect,
            )
            .unwrap();
            prop_assert_eq!(bits(&boxed), bits(&one));
        }
    }

    /// A torus of shared vertices, over several setup chunks, with a face out of range:
    /// drawn whole in parts that share the vertex lists, with 1 and 3 threads.
    #[test]
    fn canvas_draws_a_busy_shared_mesh_like_render_for_any_thread_count() {
        let (nu, nv) = (90, 50);
        let mut m = RenderMesh::default();
        let tau = std::f64::consts::TAU;
        for i in 0..nu {
            for j in 0..nv {
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
        m.faces.push([0, 1, m.positions.len() + 3]);
        let cam = Camera {
            eye: Point3::new(0.5, -6.0, 3.0),
            target: Point3::origin(),
            up: Vector3::z(),
            fov_y_degrees: 40.0,
        };
        let parts: Vec<RenderMesh> = m
            .faces
            .chunks(2500)
            .map(|f| RenderMesh {
                faces: f.to_vec(),
                ..m.clone()
            })
            .collect();
        for shading in modes() {
            let o = RenderOptions {
                width: 301,
                height: 203,
                shading,
                ..RenderOptions::default()
            };
            let whole = render(&m, &cam, &o).unwrap();
            assert!(whole.rgb.iter().any(|&c| c < 200), "something drawn");
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let drawn = pool.install(|| canvas_picture(&parts, &cam, &o)).unwrap();
                assert!(drawn == whole, "{shading:?}, {threads} threads");
            }
        }
    }

    #[test]
    fn canvas_refuses_a_wireframe_and_bad_modes_as_render_does() {
        let bounds = SceneBounds::new(&camera());
        let wire = RenderOptions {
            wireframe: Some([0.0; 3]),
            ..RenderOptions::default()
        };
        let err = Canvas::new(&camera(), &wire, &bounds).err().unwrap();
        assert!(matches!(err, RenderError::Unsupported(_)), "{err}");
        assert!(err.to_string().contains("wireframe"), "{err}");
        let bad = options(Shading::Isophotes {
            bands: 0,
            light: None,
            width: 0.5,
        });
        let canvas = Canvas::new(&camera(), &bad, &bounds).err().unwrap();
        let whole = render(&RenderMesh::default(), &camera(), &bad).unwrap_err();
        assert_eq!(canvas.to_string(), whole.to_string());
        // Nothing drawn: the background, as `render` of an empty mesh.
        let o = options(Shading::Lit);
        let empty = Canvas::new(&camera(), &o, &bounds).unwrap().finish();
        assert!(empty == render(&RenderMesh::default(), &camera(), &o).unwrap());
        assert!(SceneBounds::needed(&Shading::HIGHLIGHT) && !SceneBounds::needed(&Shading::Lit));
    }

    #[test]
    fn wire_frame_drawn_in_parts_is_the_whole() {
        let specs: Vec<Spec> = (0..30)
            .map(|i| {
                let t = f64::from(i) * 0.37;
                Spec {
                    corners: [
                        [t.cos(), t.sin(), 0.1 * t],
                        [2.0 * t.sin(), -t.cos(), 1.0],
                        [-1.0, 0.5 * t.cos(), 6.0 * t.sin()],
                    ],
                    normals: None,
                    color: [0.5; 3],
                    kind: (i % 10) as u8,
                }
            })
            .collect();
        let m = mesh_of(&specs);
        let whole = wire_frame(&m, &camera(), W, H);
        let mut img = blank_wire_frame(W, H);
        for (a, b) in [(0, 7), (7, 8), (8, 30)] {
            draw_wire_frame(&mut img, &part(&m, a, b), &camera());
        }
        assert!(img == whole);
        assert!(whole.rgb.iter().any(|&c| c < 255));
    }
}

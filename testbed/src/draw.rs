//! The ends of the pipeline: reading the triangles of a stream (`render`, `wire`, `to-mesh`),
//! and the pictures of `render` (the seed's Sgp | Render) and `wire` (Sgp | XRender): their
//! options ([`PictureArgs`]), drawing, PNG.
//!
//! The triangles are drawn as they come, unwelded (each Triangle record's three vertices; a
//! TriangleMesh's vertices shared as in the record), with their normals (the geometric normal
//! where a vertex has none) and colours (the uniform material where a vertex has none). The
//! camera looks at the centre of the triangles' bounding box from the given azimuth and
//! elevation, as near as keeps every vertex in the middle 90% of the width and the height.
//!
//! In bounded memory: the filters keep the stream's triangles in a [`TriangleStore`] (in
//! memory up to [`STORE_BYTES`], the rest in a temporary file), frame the camera on them
//! (their bounding box gathered as they are read, then one replay for the distance:
//! `render::Camera::framing_box`, the camera of `framing_points` bit for bit), and draw them
//! chunk by chunk onto a `render::Canvas` (one replay more before it for the highlight lines'
//! bounds). The picture is byte for byte the one `render::render` draws from the whole mesh.

use std::io::Write;

use render::{Camera, Canvas, Image, RenderMesh, RenderOptions, SceneBounds, Shading};

use crate::error::FilterError;
use crate::options::pair;
use crate::pipe::{Pipe, StreamOptions};
use crate::record::{self, Vertex};
use crate::stream::Record;
use crate::triangle_mesh::{self, TriangleMesh};
use crate::triangle_store::{TriangleStore, STORE_BYTES};

/// Default view: azimuth and elevation in degrees (the octahedron's three front faces).
pub const DEFAULT_VIEW: (f64, f64) = (35.0, 25.0);

/// Default picture size (the examples' size).
pub const DEFAULT_SIZE: (u32, u32) = (400, 300);

/// Largest picture side accepted: an 8192 × 8192 picture takes about 1 GB while it is drawn
/// and encoded ([`RENDER_BYTES_PER_PIXEL`] and [`PICTURE_FIXED_BYTES`]: 1.07 GB estimated,
/// 0.80 GB measured; 1.25 GB with the deferred renderer this replaced, which kept a triangle
/// id a pixel more; a 16384 × 16384 one took 5.0 GB), the most a shared machine should be asked for; every size is also
/// checked against the memory available before anything is drawn ([`check_picture_memory`]).
pub const MAX_SIDE: u32 = 8192;

/// Bytes a pixel of a shaded picture takes while drawn and encoded: its depth (8), its RGB
/// bytes (3) and, at most, the PNG's compressed copy of them (3) (`render::Canvas`; the
/// deferred renderer before it also kept the nearest triangle's id, 8 more, and measured 18.6
/// bytes a pixel at 8192 × 8192 against the 22 then estimated: docs/hostile-input.md).
pub const RENDER_BYTES_PER_PIXEL: u128 = 14;

/// Bytes a pixel of a wire-frame picture takes: its RGB bytes and at most the PNG's
/// compressed copy (measured: 3.1 bytes a pixel at 8192 × 8192).
pub const WIRE_BYTES_PER_PIXEL: u128 = 6;

/// Bytes a picture takes besides its pixels, whatever the stream holds: the triangles kept in
/// memory ([`STORE_BYTES`], 64 MiB) and the work of one chunk of [`crate::triangle_store::CHUNK_TRIANGLES`]: the
/// chunk being filled and one read back (unwelded at worst, 204 bytes a triangle each) and
/// the canvas's set-up of it (64 bytes a camera-space vertex, 184 a set-up triangle), under
/// 48 MiB; 64 MiB is allowed.
pub const PICTURE_FIXED_BYTES: u128 = STORE_BYTES as u128 + (64 << 20);

/// Reads every Triangle, and every triangle of every TriangleMesh, as three vertices; other
/// records are ignored.
pub fn collect_triangles(pipe: &mut Pipe) -> Result<Vec<[Vertex; 3]>, FilterError> {
    let mut tris = Vec::new();
    let mut mesh = TriangleMesh::default();
    let mut rec = Record::default();
    while pipe.next_good(&mut rec)? {
        match rec.kind() {
            "Triangle" => match record::triangle(&rec.tape) {
                Ok(t) => tris.push(t),
                Err(e) => pipe.bad_field(&rec, e)?,
            },
            triangle_mesh::KIND => match mesh.read(&rec.tape) {
                Ok(()) => tris.extend((0..mesh.triangles.len()).map(|k| mesh.triangle(k))),
                Err(e) => pipe.bad_field(&rec, e)?,
            },
            _ => {}
        }
    }
    pipe.report_skipped();
    Ok(tris)
}

/// Reads every Triangle (unwelded) and every TriangleMesh (its vertices shared, as in the
/// record) straight into a render mesh, the uniform material where a vertex has no colour;
/// other records are ignored. The pictures' reader: no triangle list is held beside the mesh.
pub fn collect_mesh(pipe: &mut Pipe) -> Result<RenderMesh, FilterError> {
    collect_mesh_seen(pipe, &mut Seen::default())
}

/// [`collect_mesh`], counting the records read in `seen`.
pub fn collect_mesh_seen(pipe: &mut Pipe, seen: &mut Seen) -> Result<RenderMesh, FilterError> {
    let mut m = RenderMesh {
        positions: Vec::new(),
        normals: Vec::new(),
        colors: Vec::new(),
        faces: Vec::new(),
    };
    read_triangles(pipe, seen, &mut |t| {
        match t {
            Triangles::One(t) => push_triangle(&mut m, t, render::colors::MATERIAL),
            Triangles::Mesh(mesh) => push_triangle_mesh(&mut m, mesh, render::colors::MATERIAL),
        }
        Ok(())
    })?;
    Ok(m)
}

/// The triangles of one record, as [`read_triangles`] gives them.
pub enum Triangles<'a> {
    /// A `Triangle` record's three vertices.
    One(&'a [Vertex; 3]),
    /// A `TriangleMesh` record.
    Mesh(&'a TriangleMesh),
}

/// Reads the stream, giving `take` the triangles of every Triangle and TriangleMesh record in
/// order and counting the records read in `seen` (other records are ignored; a record that is
/// not well formed goes as the pipe's `--keep-going` policy says) — the one reader of the
/// pictures and of `collect_mesh_seen`.
pub fn read_triangles(
    pipe: &mut Pipe,
    seen: &mut Seen,
    take: &mut dyn FnMut(Triangles<'_>) -> Result<(), FilterError>,
) -> Result<(), FilterError> {
    let mut mesh = TriangleMesh::default();
    let mut rec = Record::default();
    while pipe.next_good(&mut rec)? {
        seen.records += 1;
        match rec.kind() {
            "BezierTriangle" => seen.patches += 1,
            "Triangle" => match record::triangle(&rec.tape) {
                Ok(t) => take(Triangles::One(&t))?,
                Err(e) => pipe.bad_field(&rec, e)?,
            },
            triangle_mesh::KIND => match mesh.read(&rec.tape) {
                Ok(()) => take(Triangles::Mesh(&mesh))?,
                Err(e) => pipe.bad_field(&rec, e)?,
            },
            _ => {}
        }
    }
    pipe.report_skipped();
    Ok(())
}

/// Appends a TriangleMesh record's triangles to a render mesh: with its vertices shared when
/// it has normals; without, each triangle on its own with its geometric normal (as a
/// Triangle without normals is drawn). Colours: `default_color` where the record has none.
pub fn push_triangle_mesh(m: &mut RenderMesh, mesh: &TriangleMesh, default_color: [f32; 3]) {
    if mesh.norm.is_empty() && !mesh.pos.is_empty() {
        for k in 0..mesh.triangles.len() {
            push_triangle(m, &mesh.triangle(k), default_color);
        }
        return;
    }
    let base = m.positions.len();
    m.positions.extend_from_slice(&mesh.pos);
    m.normals.extend_from_slice(&mesh.norm);
    if mesh.color.is_empty() {
        m.colors
            .extend(std::iter::repeat_n(default_color, mesh.pos.len()));
    } else {
        m.colors.extend_from_slice(&mesh.color);
    }
    m.faces
        .extend(mesh.triangles.iter().map(|t| t.map(|i| base + i as usize)));
}

/// Appends one triangle to a render mesh: its normals (the geometric normal where a vertex
/// has none) and colours (`default_color` where a vertex has none).
pub fn push_triangle(m: &mut RenderMesh, t: &[Vertex; 3], default_color: [f32; 3]) {
    let geometric = (t[1].pos - t[0].pos).cross(&(t[2].pos - t[0].pos));
    let base = m.positions.len();
    for v in t {
        m.positions.push(v.pos);
        m.normals.push(v.norm.unwrap_or(geometric));
        m.colors.push(v.color.unwrap_or(default_color));
    }
    m.faces.push([base, base + 1, base + 2]);
}

/// Triangles to a render mesh.
pub fn render_mesh(tris: &[[Vertex; 3]], default_color: [f32; 3]) -> RenderMesh {
    let mut m = RenderMesh {
        positions: Vec::with_capacity(tris.len() * 3),
        normals: Vec::with_capacity(tris.len() * 3),
        colors: Vec::with_capacity(tris.len() * 3),
        faces: Vec::with_capacity(tris.len()),
    };
    for t in tris {
        push_triangle(&mut m, t, default_color);
    }
    m
}

/// Picture options (`render`, `wire`).
#[derive(clap::Args, Debug, Clone, Default, PartialEq, Eq)]
pub struct PictureArgs {
    /// View direction `AZ,EL` in degrees.
    #[arg(long, allow_hyphen_values = true)]
    pub view: Option<String>,
    /// Size `WxH` in pixels, each side from 1 to 8192 (and within memory: 14 bytes a pixel
    /// shaded, 6 wire-frame, and 128 MiB for the triangles).
    #[arg(long)]
    pub size: Option<String>,
}

impl PictureArgs {
    /// The view they ask for (the defaults where not given), shaded or `wire`-frame: `--view`
    /// two finite angles, `--size` two whole numbers (their range is checked when drawing,
    /// [`draw_mesh`]).
    pub fn view(&self, wire: bool) -> Result<View, FilterError> {
        let view = match &self.view {
            Some(v) => pair::<f64>(v, ',', "--view")?,
            None => DEFAULT_VIEW,
        };
        if !(view.0.is_finite() && view.1.is_finite()) {
            return Err(FilterError::Usage("--view: finite angles".into()));
        }
        let size = match &self.size {
            Some(s) => pair::<u32>(&s.to_ascii_lowercase(), 'x', "--size")?,
            None => DEFAULT_SIZE,
        };
        Ok(View { view, size, wire })
    }
}

/// The records a picture's stream held, by kind, for the message of a blank picture.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Seen {
    /// Records read.
    pub records: usize,
    /// `BezierTriangle` records among them (patches not yet tessellated).
    pub patches: usize,
}

/// Refuses a picture of `view`'s size whose drawing would exceed the memory available
/// ([`RENDER_BYTES_PER_PIXEL`] or [`WIRE_BYTES_PER_PIXEL`] a pixel, and
/// [`PICTURE_FIXED_BYTES`]; [`surface::limits::check_memory`]), before anything is drawn.
pub fn check_picture_memory(view: &View) -> Result<(), FilterError> {
    let (w, h) = view.size;
    let per_pixel = if view.wire {
        WIRE_BYTES_PER_PIXEL
    } else {
        RENDER_BYTES_PER_PIXEL
    };
    Ok(surface::limits::check_memory(
        &format!("--size {w}x{h}"),
        (u128::from(w) * u128::from(h))
            .saturating_mul(per_pixel)
            .saturating_add(PICTURE_FIXED_BYTES),
    )?)
}

/// Why a picture of `triangles` triangles from a stream holding `seen` is blank (an error,
/// never a blank PNG), or `None` when the image shows something (`blank`: every pixel is the
/// background).
pub fn blank_reason(name: &str, triangles: usize, seen: &Seen, blank: bool) -> Option<String> {
    if triangles == 0 {
        let hint = if seen.patches > 0 {
            format!(
                " ({} BezierTriangle records: put `tess` before `{name}`)",
                seen.patches
            )
        } else if seen.records == 0 {
            " (the stream is empty)".to_string()
        } else {
            " (no Triangle or TriangleMesh records: put `tess` before it, or `fit -s N`)"
                .to_string()
        };
        return Some(format!(
            "no triangles in the stream, {} records read{hint}: the picture would be blank",
            seen.records
        ));
    }
    blank.then(|| {
        format!(
            "the picture is blank: {triangles} triangles read, none of them visible (every pixel the background: degenerate or not finite triangles, or seen from behind the camera)"
        )
    })
}

/// Runs a picture filter named `name`: the triangles kept in a store ([`collect_store_seen`]),
/// drawn with `view` chunk by chunk ([`draw_store`]), PNG out. A picture with nothing drawn on
/// it is an error naming the cause ([`blank_reason`]), and a size whose drawing would not fit
/// in memory is refused before the stream is read ([`check_picture_memory`]).
pub fn picture(name: &'static str, stream: &StreamOptions, view: &View) -> Result<(), FilterError> {
    picture_with(name, stream, view, Shading::Lit)
}

/// [`picture`] with a shading mode (`render --mode`; ignored by a wire frame).
pub fn picture_with(
    name: &'static str,
    stream: &StreamOptions,
    view: &View,
    shading: Shading,
) -> Result<(), FilterError> {
    check_side(view)?;
    check_picture_memory(view)?;
    let mut seen = Seen::default();
    let mut store = stream.read(name, &mut |p| collect_store_seen(p, name, &mut seen))?;
    if let Some(why) = blank_reason(name, store.triangles(), &seen, false) {
        return Err(FilterError::Blank(why));
    }
    let image = draw_store(&mut store, view, shading)?;
    // Both pictures are drawn on white (`render`'s default background, `wire_frame`'s).
    let blank = image.rgb.iter().all(|&b| b == u8::MAX);
    if let Some(why) = blank_reason(name, store.triangles(), &seen, blank) {
        return Err(FilterError::Blank(why));
    }
    drop(store);
    stream.with_output(&mut |out| write_png(&image, out))
}

/// Reads every Triangle (unwelded) and every TriangleMesh (its vertices shared, as in the
/// record) into a [`TriangleStore`] as [`collect_mesh_seen`] reads them into a render mesh
/// (the uniform material where a vertex has no colour), counting the records read in `seen`;
/// other records are ignored. The store is finished (ready to replay).
pub fn collect_store_seen(
    pipe: &mut Pipe,
    name: &'static str,
    seen: &mut Seen,
) -> Result<TriangleStore, FilterError> {
    let mut store = TriangleStore::new(STORE_BYTES, name);
    read_triangles(pipe, seen, &mut |t| match t {
        Triangles::One(t) => store.push_triangle(t, render::colors::MATERIAL),
        Triangles::Mesh(mesh) => store.push_triangle_mesh(mesh, render::colors::MATERIAL),
    })?;
    store.finish()?;
    Ok(store)
}

/// The renderer's options for a picture of `view` with `shading`, and its aspect (width over
/// height), once its size is checked: each side in range ([`check_side`]) and its drawing
/// within memory ([`check_picture_memory`]).
fn picture_options(view: &View, shading: Shading) -> Result<(RenderOptions, f64), FilterError> {
    check_side(view)?;
    check_picture_memory(view)?;
    let (w, h) = view.size;
    let options = RenderOptions {
        width: w,
        height: h,
        shading,
        ..RenderOptions::default()
    };
    Ok((options, f64::from(w) / f64::from(h)))
}

/// Draws the stored triangles with a shading mode (ignored by a wire frame): the picture
/// [`draw_mesh_with`] draws of their whole mesh, byte for byte, from replays of the store
/// (the camera's distance; for highlight lines their bounds; the drawing), one chunk in
/// memory at a time besides the store's budget.
pub fn draw_store(
    store: &mut TriangleStore,
    view: &View,
    shading: Shading,
) -> Result<Image, FilterError> {
    let (options, aspect) = picture_options(view, shading)?;
    let (w, h) = view.size;
    let bounds = *store.bounds();
    let camera = Camera::framing_box(
        &bounds,
        |visit| {
            store.replay(&mut |m| {
                visit(&m.positions);
                Ok(())
            })
        },
        view.view.0,
        view.view.1,
        aspect,
    )?;
    if view.wire {
        let mut image = render::blank_wire_frame(w, h);
        store.replay(&mut |m| {
            render::draw_wire_frame(&mut image, m, &camera);
            Ok(())
        })?;
        return Ok(image);
    }
    let mut scene = SceneBounds::new(&camera);
    if SceneBounds::needed(&shading) {
        store.replay(&mut |m| {
            scene.add(&m.positions);
            Ok(())
        })?;
    }
    let mut canvas = Canvas::new(&camera, &options, &scene).map_err(|e| shading_usage(e, view))?;
    store.replay(&mut |m| {
        canvas.draw(m);
        Ok(())
    })?;
    Ok(canvas.finish())
}

/// A mode the renderer refuses (the highlight lights seen end on: `--direction` along
/// `--view`) as a usage error naming the view; other errors as they are.
fn shading_usage(e: render::RenderError, view: &View) -> FilterError {
    match e {
        render::RenderError::Shading { mode, message } => FilterError::Usage(format!(
            "--mode {mode}: {message} (--view {},{})",
            view.view.0, view.view.1
        )),
        other => other.into(),
    }
}

/// How a picture is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Azimuth and elevation, degrees.
    pub view: (f64, f64),
    /// Width and height, pixels.
    pub size: (u32, u32),
    /// Wire-frame (XRender) instead of shaded.
    pub wire: bool,
}

/// Draws triangles.
pub fn draw(tris: &[[Vertex; 3]], view: &View) -> Result<Image, FilterError> {
    draw_mesh(&render_mesh(tris, render::colors::MATERIAL), view)
}

/// Refuses a picture side outside `1..=MAX_SIDE` (a usage error naming the range).
fn check_side(view: &View) -> Result<(), FilterError> {
    let (w, h) = view.size;
    if w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE {
        return Err(FilterError::Usage(format!(
            "--size {w}x{h}: each side from 1 to {MAX_SIDE}"
        )));
    }
    Ok(())
}

/// Draws a render mesh (unwelded triangles).
pub fn draw_mesh(mesh: &RenderMesh, view: &View) -> Result<Image, FilterError> {
    draw_mesh_with(mesh, view, Shading::Lit)
}

/// Draws a render mesh with a shading mode (ignored by a wire frame). The camera looks at the
/// centre of the mesh's bounding box from the view's angles, as near as keeps every vertex in
/// the middle 90% of the width and of the height (`render::Camera::framing_points`, for the
/// picture's aspect): the object fills 90% of one of them. A mode the renderer refuses (the
/// highlight lights seen end on: `--direction` along `--view`) is a usage error.
pub fn draw_mesh_with(
    mesh: &RenderMesh,
    view: &View,
    shading: Shading,
) -> Result<Image, FilterError> {
    let (options, aspect) = picture_options(view, shading)?;
    let (w, h) = view.size;
    let camera = Camera::framing_points(&mesh.positions, view.view.0, view.view.1, aspect);
    if view.wire {
        return Ok(render::wire_frame(mesh, &camera, w, h));
    }
    render::render(mesh, &camera, &options).map_err(|e| shading_usage(e, view))
}

/// Encodes an image as PNG (`render::write_png`).
pub fn write_png(image: &Image, out: &mut dyn Write) -> Result<(), FilterError> {
    render::write_png(image, out).map_err(|e| FilterError::Png(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::triangle_store::CHUNK_TRIANGLES;
    use nalgebra::{Point3, Vector3};

    /// A stream's worth of triangles: single Triangles (some without normals or colours, one
    /// corner not finite now and then) and TriangleMesh strips with and without normals,
    /// into a store of `budget` bytes and into one mesh as [`collect_mesh`] builds it.
    fn stored(budget: usize) -> (TriangleStore, RenderMesh) {
        let mut store = TriangleStore::new(budget, "test");
        let mut whole = RenderMesh::default();
        let colour = render::colors::MATERIAL;
        for r in 0..60 {
            let t = f64::from(r) * 0.41;
            if r % 3 == 0 {
                let mut m = TriangleMesh::default();
                // One strip longer than a chunk: the store closes chunks before and after it.
                let n = if r == 30 { CHUNK_TRIANGLES + 100 } else { 38 };
                for k in 0..n as u32 + 2 {
                    let a = t + f64::from(k) * 0.15;
                    m.pos.push(Point3::new(
                        a.cos(),
                        a.sin(),
                        0.3 * f64::from(k % 2) + 0.1 * t,
                    ));
                    if r % 2 == 0 {
                        m.norm.push(Vector3::new(a.cos(), a.sin(), 0.4));
                        m.color.push([0.2, (k % 5) as f32 / 5.0, 0.7]);
                    }
                }
                m.triangles = (0..n as u32).map(|k| [k, k + 1, k + 2]).collect();
                store.push_triangle_mesh(&m, colour).unwrap();
                push_triangle_mesh(&mut whole, &m, colour);
            } else {
                let at = |k: f64| Point3::new(t.sin() + 0.5 * k, t.cos() - 0.3 * k, 0.2 * k);
                let v = |pos, norm, color| Vertex {
                    pos,
                    norm,
                    kg: None,
                    km: None,
                    color,
                };
                let tri = [
                    v(
                        at(0.0),
                        Some(Vector3::new(0.0, 0.3, 1.0)),
                        Some([0.9, 0.1, 0.2]),
                    ),
                    v(
                        if r % 11 == 4 {
                            Point3::new(f64::NAN, 0.0, 0.0)
                        } else {
                            at(1.0)
                        },
                        None,
                        None,
                    ),
                    v(at(1.7) + Vector3::new(0.0, 0.9, 0.0), None, None),
                ];
                store.push_triangle(&tri, colour).unwrap();
                push_triangle(&mut whole, &tri, colour);
            }
        }
        store.finish().unwrap();
        (store, whole)
    }

    /// The store's pictures, in memory and spilled, are `draw_mesh_with`'s of the whole mesh
    /// byte for byte: shaded in every mode, and the wire frame.
    #[test]
    fn stored_pictures_are_the_whole_meshs_pictures() {
        /// No memory for chunks: all three go to the file.
        const TINY: usize = 0;
        let modes = [
            Shading::Lit,
            Shading::REFLECTION,
            Shading::ISOPHOTES,
            Shading::HIGHLIGHT,
        ];
        for budget in [STORE_BYTES, TINY] {
            let (mut store, whole) = stored(budget);
            assert_eq!(store.triangles(), whole.faces.len());
            assert_eq!(store.spilled(), if budget == TINY { 3 } else { 0 });
            for (wire, size) in [(false, (97, 71)), (true, (64, 80))] {
                let view = View {
                    view: (20.0, 35.0),
                    size,
                    wire,
                };
                for &shading in if wire { &modes[..1] } else { &modes[..] } {
                    let a = draw_store(&mut store, &view, shading).unwrap();
                    let b = draw_mesh_with(&whole, &view, shading).unwrap();
                    assert!(a.rgb.iter().any(|&c| c < 200), "{shading:?}: drawn");
                    assert!(a == b, "budget {budget}, {shading:?}, wire {wire}");
                }
            }
        }
    }

    /// A highlight seen end on is the same usage error from the store as from the mesh.
    #[test]
    fn a_refused_mode_is_the_same_usage_error() {
        let (mut store, whole) = stored(STORE_BYTES);
        let view = View {
            view: (0.0, 90.0),
            size: (40, 30),
            wire: false,
        };
        let end_on = Shading::Highlight {
            lines: 8,
            direction: Some(Vector3::z()),
            width: 0.5,
        };
        let a = draw_store(&mut store, &view, end_on).unwrap_err();
        let b = draw_mesh_with(&whole, &view, end_on).unwrap_err();
        assert!(matches!(a, FilterError::Usage(_)), "{a}");
        assert_eq!(a.to_string(), b.to_string());
    }
}

//! One self-contained interactive HTML page for fitted surfaces.
//!
//! [`Page::to_html`] writes a single file that works offline, from `file://`: the vendored
//! three.js (`vendor/three.min.js`, MIT, bundled from the npm package by `vendor/fetch.sh`)
//! and the page's own script (`src/page.js`) are inlined, and every view's data is embedded in
//! binary form — base64 of little-endian `Float32` positions, normals, per-vertex scalars,
//! line segments and `Uint32` triangle indices.
//!
//! The page shows its views side by side in a grid, each with its own title, with linked
//! cameras (one orbit state for all: turning, zooming or panning one view does the same to
//! every view, each relative to its own object's bounding sphere). Modes: shaded, one colour
//! map per scalar (diverging, symmetric about 0, with a colour bar), reflection lines (zebra),
//! isophotes, and the distance to the true surface when a view has it. Toggles: patch
//! boundaries, control nets and the data mesh, where a view gives them as line segments.
//!
//! The URL hash selects the state, so a headless browser can take one screenshot a state:
//! `#mode=K&turn=30&tilt=10&zoom=1.5&pan=0.1,0&boundaries=1&nets=0&mesh=1&up=y&ui=0`
//! (`drag=0:120:0` replays a mouse drag of 120 px right over view 0, through the same
//! handlers a person's drag goes through; `ui=0` hides the toolbar, titles and colour bar).
//! Once drawn, the page's `#status` element reads `ready:<mode>`; any script error sets
//! `error:<message>` there and in `document.title` (README.md).

use std::collections::{BTreeMap, HashMap};

use surface::{BezierTriangle, Tessellation};

pub mod patch_file;
pub use patch_file::{is_patch_file, read_patch_file, PatchFileError};

/// The vendored three.js bundle (a classic script defining the global `THREE`).
const THREE_JS: &str = include_str!("../vendor/three.min.js");
/// The page's script: decodes the data, builds the views, handles input and the hash.
const PAGE_JS: &str = include_str!("page.js");
/// The page's markup and style, with the placeholders [`PLACEHOLDERS`] filled in order.
const PAGE_HTML: &str = include_str!("page.html");
/// The placeholders of [`PAGE_HTML`], in the order they appear.
const PLACEHOLDERS: [&str; 4] = ["{{TITLE}}", "{{THREE_JS}}", "{{DATA}}", "{{PAGE_JS}}"];

/// The colour range of a scalar is this quantile of its absolute values over all views: a few
/// spikes (singular patch corners of a fitted surface reach curvatures 10²–10⁴ times the rest)
/// would otherwise wash the map out to white; values beyond are shown at full colour and the
/// colour bar states the clipping and the true maximum.
pub const RANGE_QUANTILE: f64 = 0.99;

/// Mode names of the page other than the scalars' own; a scalar may not take one of them.
pub const RESERVED_NAMES: [&str; 4] = ["shaded", "zebra", "isophotes", "distance"];

/// A point in the page's data (single precision: what WebGL draws with).
pub type Point = [f32; 3];
/// A line segment (patch boundary, control-net edge, data-mesh edge).
pub type Segment = [Point; 2];

/// A triangle mesh with per-vertex unit normals.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleMesh {
    /// Vertex positions.
    pub positions: Vec<Point>,
    /// Per-vertex normals (normalized by the page; zero is refused).
    pub normals: Vec<Point>,
    /// Triangles as vertex indices, counter-clockwise seen from the normals' side.
    pub indices: Vec<[u32; 3]>,
}

/// One surface of the page: its mesh, what is coloured on it and what is drawn over it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct View {
    /// Shown above the view.
    pub title: String,
    /// The surface.
    pub mesh: TriangleMesh,
    /// Named per-vertex scalars, one value per vertex, each a colour-map mode of the page
    /// (`K`, `H`, `k1`, `k2` from [`view_from_tessellation`]; any other name is a mode too).
    pub scalars: Vec<(String, Vec<f32>)>,
    /// Patch boundaries.
    pub boundaries: Option<Vec<Segment>>,
    /// Control nets.
    pub nets: Option<Vec<Segment>>,
    /// The data mesh's edges ([`wireframe`] makes them from its triangles).
    pub data_mesh: Option<Vec<Segment>>,
    /// Distance of each vertex to the true surface (the `distance` mode).
    pub distance: Option<Vec<f32>>,
}

impl View {
    /// A view of `mesh` with nothing on it yet.
    pub fn new(title: impl Into<String>, mesh: TriangleMesh) -> Self {
        View {
            title: title.into(),
            mesh,
            ..View::default()
        }
    }
}

/// Why a view cannot be put on a page.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ViewError {
    /// The mesh has no triangle.
    #[error("view `{view}`: the mesh has no triangle")]
    Empty {
        /// The view's title.
        view: String,
    },
    /// An array has a different length than the vertices.
    #[error("view `{view}`: {what} has {got} values for {vertices} vertices")]
    Length {
        /// The view's title.
        view: String,
        /// Which array.
        what: String,
        /// Its length.
        got: usize,
        /// The number of vertices.
        vertices: usize,
    },
    /// A triangle names a vertex that does not exist.
    #[error("view `{view}`: triangle {triangle} has vertex {index}, but there are {vertices}")]
    Index {
        /// The view's title.
        view: String,
        /// The triangle's position.
        triangle: usize,
        /// The index out of range.
        index: u32,
        /// The number of vertices.
        vertices: usize,
    },
    /// A number is NaN or infinite.
    #[error("view `{view}`: {what} value {at} is not finite")]
    NotFinite {
        /// The view's title.
        view: String,
        /// Which array.
        what: String,
        /// The position of the value (vertex, segment) in it.
        at: usize,
    },
    /// A normal is zero.
    #[error("view `{view}`: the normal of vertex {vertex} is zero")]
    ZeroNormal {
        /// The view's title.
        view: String,
        /// The vertex.
        vertex: usize,
    },
    /// A scalar's name is empty, repeated, or the name of another mode.
    #[error("view `{view}`: the scalar name `{name}` is empty, repeated or reserved ({RESERVED_NAMES:?})")]
    Name {
        /// The view's title.
        view: String,
        /// The name.
        name: String,
    },
}

/// A page of views side by side.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Page {
    title: String,
    views: Vec<View>,
    up: meshio::UpAxis,
}

impl Page {
    /// An empty page with a title (the browser tab's and the page's heading).
    pub fn new(title: impl Into<String>) -> Self {
        Page {
            title: title.into(),
            views: Vec::new(),
            up: meshio::UpAxis::Z,
        }
    }

    /// The axis the camera keeps up and the reflection lines turn about: `z` (the default,
    /// the workbench's data) or `y` (most scanned models, glTF). The hash's `up=` overrides it.
    pub fn set_up(&mut self, up: meshio::UpAxis) -> &mut Self {
        self.up = up;
        self
    }

    /// Adds a view after checking it: lengths, indices, finite numbers, non-zero normals and
    /// scalar names ([`ViewError`]).
    pub fn add_view(&mut self, view: View) -> Result<&mut Self, ViewError> {
        check(&view)?;
        self.views.push(view);
        Ok(self)
    }

    /// The views, in order.
    pub fn views(&self) -> &[View] {
        &self.views
    }

    /// The embedded data block: JSON with the base64 arrays, every `<` written `\u003c` (the
    /// same string to JSON; `<` occurs only inside strings), so no name can close its
    /// `<script>` element (`</script>`) or put the HTML parser into a script's escaped states
    /// (`<!--` followed by `<script`, which swallowed the rest of the page).
    pub fn data_json(&self) -> String {
        let ranges = ranges(&self.views);
        let views: Vec<serde_json::Value> = self.views.iter().map(view_json).collect();
        let doc = serde_json::json!({
            "title": self.title,
            "up": self.up.name(),
            "ranges": ranges,
            "views": views,
        });
        doc.to_string().replace('<', "\\u003c")
    }

    /// The whole page.
    pub fn to_html(&self) -> String {
        let title = html_escape(&self.title);
        let data = self.data_json();
        let fills = [title.as_str(), THREE_JS, data.as_str(), PAGE_JS];
        let mut out = String::with_capacity(PAGE_HTML.len() + THREE_JS.len() + data.len());
        let mut rest = PAGE_HTML;
        for (marker, fill) in PLACEHOLDERS.iter().zip(fills) {
            // The template is ours and has every marker once (tested); a missing one would
            // leave the marker's fill out rather than fail.
            if let Some((before, after)) = rest.split_once(marker) {
                out.push_str(before);
                out.push_str(fill);
                rest = after;
            }
        }
        out.push_str(rest);
        out
    }
}

/// Checks one view ([`Page::add_view`]).
fn check(view: &View) -> Result<(), ViewError> {
    let name = || view.title.clone();
    let n = view.mesh.positions.len();
    if view.mesh.indices.is_empty() || n == 0 {
        return Err(ViewError::Empty { view: name() });
    }
    let length = |what: &str, got: usize| {
        if got == n {
            Ok(())
        } else {
            Err(ViewError::Length {
                view: name(),
                what: what.into(),
                got,
                vertices: n,
            })
        }
    };
    length("normals", view.mesh.normals.len())?;
    for (t, tri) in view.mesh.indices.iter().enumerate() {
        if let Some(&index) = tri.iter().find(|&&i| i as usize >= n) {
            return Err(ViewError::Index {
                view: name(),
                triangle: t,
                index,
                vertices: n,
            });
        }
    }
    let finite = |what: &str, values: &mut dyn Iterator<Item = f32>| match Iterator::position(
        &mut &mut *values,
        |x| !x.is_finite(),
    ) {
        None => Ok(()),
        Some(at) => Err(ViewError::NotFinite {
            view: name(),
            what: what.into(),
            at,
        }),
    };
    finite(
        "positions",
        &mut view.mesh.positions.iter().map(|p| p[0] + p[1] + p[2]),
    )?;
    finite(
        "normals",
        &mut view.mesh.normals.iter().map(|p| p[0] + p[1] + p[2]),
    )?;
    if let Some(vertex) = view.mesh.normals.iter().position(|m| m == &[0.0; 3]) {
        return Err(ViewError::ZeroNormal {
            view: name(),
            vertex,
        });
    }
    let mut seen = Vec::new();
    for (scalar, values) in &view.scalars {
        if scalar.is_empty()
            || RESERVED_NAMES.contains(&scalar.as_str())
            || seen.contains(&scalar.as_str())
        {
            return Err(ViewError::Name {
                view: name(),
                name: scalar.clone(),
            });
        }
        seen.push(scalar.as_str());
        length(&format!("scalar `{scalar}`"), values.len())?;
        finite(&format!("scalar `{scalar}`"), &mut values.iter().copied())?;
    }
    if let Some(d) = &view.distance {
        length("distance", d.len())?;
        finite("distance", &mut d.iter().copied())?;
    }
    for (what, segments) in [
        ("boundaries", &view.boundaries),
        ("nets", &view.nets),
        ("data mesh", &view.data_mesh),
    ] {
        if let Some(s) = segments {
            finite(
                what,
                &mut s
                    .iter()
                    .map(|[a, b]| a[0] + a[1] + a[2] + b[0] + b[1] + b[2]),
            )?;
        }
    }
    Ok(())
}

/// The colour range of every scalar name (and `distance`) over all views: each view's
/// [`RANGE_QUANTILE`] of its absolute values, and of those the median over the views (the
/// lower one of an even count), so that one view with lumps (dBHS curves on the ring reach
/// |K| ≈ 8 000 where the others stay below 5) does not wash out the others, which share the
/// scale; the largest value where that is zero, 1 where everything is zero; and the true
/// largest absolute value over all views.
fn ranges(views: &[View]) -> serde_json::Value {
    let mut all: BTreeMap<&str, Vec<Vec<f32>>> = BTreeMap::new();
    for v in views {
        for (name, values) in &v.scalars {
            all.entry(name)
                .or_default()
                .push(values.iter().map(|x| x.abs()).collect());
        }
        if let Some(d) = &v.distance {
            all.entry("distance")
                .or_default()
                .push(d.iter().map(|x| x.abs()).collect());
        }
    }
    let mut out = serde_json::Map::new();
    for (name, per_view) in all {
        let mut max = 0.0f32;
        let mut quantiles: Vec<f32> = per_view
            .into_iter()
            .map(|mut values| {
                values.sort_by(f32::total_cmp);
                max = max.max(values.last().copied().unwrap_or(0.0));
                let at =
                    ((values.len().saturating_sub(1)) as f64 * RANGE_QUANTILE).round() as usize;
                values.get(at).copied().unwrap_or(0.0)
            })
            .collect();
        quantiles.sort_by(f32::total_cmp);
        let q = quantiles
            .get(quantiles.len().saturating_sub(1) / 2)
            .copied()
            .unwrap_or(0.0);
        let range = if q > 0.0 {
            q
        } else if max > 0.0 {
            max
        } else {
            1.0
        };
        out.insert(
            name.to_string(),
            serde_json::json!({ "range": range, "max": max, "quantile": RANGE_QUANTILE }),
        );
    }
    serde_json::Value::Object(out)
}

/// One view's JSON: counts, title and base64 arrays.
fn view_json(v: &View) -> serde_json::Value {
    let points = |p: &[Point]| base64_f32(p.iter().flatten().copied());
    let segments = |s: &Option<Vec<Segment>>| {
        s.as_ref()
            .map(|s| base64_f32(s.iter().flatten().flatten().copied()))
    };
    let scalars: Vec<serde_json::Value> = v
        .scalars
        .iter()
        .map(|(name, values)| {
            serde_json::json!({ "name": name, "values": base64_f32(values.iter().copied()) })
        })
        .collect();
    serde_json::json!({
        "title": v.title,
        "vertices": v.mesh.positions.len(),
        "triangles": v.mesh.indices.len(),
        "positions": points(&v.mesh.positions),
        "normals": points(&v.mesh.normals),
        "indices": base64_u32(v.mesh.indices.iter().flatten().copied()),
        "scalars": scalars,
        "distance": v.distance.as_ref().map(|d| base64_f32(d.iter().copied())),
        "boundaries": segments(&v.boundaries),
        "nets": segments(&v.nets),
        "data_mesh": segments(&v.data_mesh),
    })
}

fn base64_f32(values: impl Iterator<Item = f32>) -> String {
    base64(&values.flat_map(f32::to_le_bytes).collect::<Vec<u8>>())
}

fn base64_u32(values: impl Iterator<Item = u32>) -> String {
    base64(&values.flat_map(u32::to_le_bytes).collect::<Vec<u8>>())
}

/// Standard base64 (RFC 4648, with `=` padding), what the browser's `atob` reads.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for (k, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> shift) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

fn html_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
    out
}

/// The edges of a triangle mesh, each once (the data-mesh wireframe).
pub fn wireframe(positions: &[Point], triangles: &[[u32; 3]]) -> Vec<Segment> {
    let mut seen = std::collections::HashSet::new();
    let mut out = Vec::new();
    for t in triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = (a.min(b), a.max(b));
            if let (true, Some(&p), Some(&q)) = (
                seen.insert(key),
                positions.get(a as usize),
                positions.get(b as usize),
            ) {
                out.push([p, q]);
            }
        }
    }
    out
}

/// The control nets of triangular Bézier patches: each patch's net of `(n+1)(n+2)/2` points
/// joined as the edges of its `n(n+1)/2` upward small triangles, which hold every edge of the
/// net once: `3n(n+1)/2` segments a patch.
pub fn control_nets(patches: &[BezierTriangle]) -> Vec<Segment> {
    let mut out = Vec::new();
    for patch in patches {
        let n = patch.degree();
        let p = |i, j, k| patch.point(i, j, k).map(to_f32);
        // The "upward" triangles (i+1, j, k), (i, j+1, k), (i, j, k+1) with i + j + k = n − 1
        // hold every edge of the net exactly once.
        for i in 0..n {
            for j in 0..n - i {
                let k = n - 1 - i - j;
                if let (Some(a), Some(b), Some(c)) =
                    (p(i + 1, j, k), p(i, j + 1, k), p(i, j, k + 1))
                {
                    out.extend([[a, b], [b, c], [c, a]]);
                }
            }
        }
    }
    out
}

fn to_f32(p: nalgebra::Point3<f64>) -> Point {
    [p.x as f32, p.y as f32, p.z as f32]
}

/// A view of a tessellation: its mesh; the scalars `K`, `H` (the exported convention: `H > 0`
/// on a sphere with outward normals, `meshio::convention`), and the principal curvatures
/// `k1 ≥ k2` (`H ± √(H² − K)`, the root clamped at 0 where rounding makes `H² < K`); and the
/// patch boundaries (the edges between triangles of different patches, and the mesh's border).
pub fn view_from_tessellation(title: impl Into<String>, t: &Tessellation) -> View {
    let positions: Vec<Point> = t.positions.iter().map(|&p| to_f32(p)).collect();
    let normals: Vec<Point> = t
        .normals
        .iter()
        .map(|n| [n.x as f32, n.y as f32, n.z as f32])
        .collect();
    let indices: Vec<[u32; 3]> = t
        .faces
        .iter()
        .map(|f| [f[0] as u32, f[1] as u32, f[2] as u32])
        .collect();
    let k: Vec<f64> = t.gaussian.clone();
    // Internally H = −1 on the unit sphere with outward normals; the page shows the exported sign.
    let h: Vec<f64> = t.mean.iter().map(|h| -h).collect();
    let root = |k: f64, h: f64| (h * h - k).max(0.0).sqrt();
    let k1: Vec<f32> = k
        .iter()
        .zip(&h)
        .map(|(&k, &h)| (h + root(k, h)) as f32)
        .collect();
    let k2: Vec<f32> = k
        .iter()
        .zip(&h)
        .map(|(&k, &h)| (h - root(k, h)) as f32)
        .collect();
    // Edge → (patch of the first face, faces seen).
    let mut edges: HashMap<(usize, usize), (usize, bool, u8)> = HashMap::new();
    for (f, tri) in t.faces.iter().enumerate() {
        let patch = t.patch_of_face.get(f).copied().unwrap_or(0);
        for c in 0..3 {
            let (a, b) = (tri[c], tri[(c + 1) % 3]);
            let e = edges
                .entry((a.min(b), a.max(b)))
                .or_insert((patch, false, 0));
            e.2 = e.2.saturating_add(1);
            if e.0 != patch {
                e.1 = true;
            }
        }
    }
    let mut boundaries: Vec<Segment> = edges
        .iter()
        .filter(|(_, &(_, between, count))| between || count == 1)
        .filter_map(|(&(a, b), _)| Some([*positions.get(a)?, *positions.get(b)?]))
        .collect();
    // HashMap order is not deterministic; the page should be.
    boundaries.sort_by(|x, y| {
        x.iter()
            .flatten()
            .zip(y.iter().flatten())
            .map(|(a, b)| a.total_cmp(b))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    View {
        title: title.into(),
        mesh: TriangleMesh {
            positions,
            normals,
            indices,
        },
        scalars: vec![
            ("K".into(), k.iter().map(|&x| x as f32).collect()),
            ("H".into(), h.iter().map(|&x| x as f32).collect()),
            ("k1".into(), k1),
            ("k2".into(), k2),
        ],
        boundaries: Some(boundaries),
        ..View::default()
    }
}

/// A view of triangular Bézier patches: their tessellation at `density` segments per patch
/// edge ([`surface::tessellate()`]) as [`view_from_tessellation`] gives it, with the control nets
/// ([`control_nets`]).
pub fn view_from_patches(
    title: impl Into<String>,
    patches: &[BezierTriangle],
    density: usize,
) -> Result<View, surface::TessError> {
    let t = surface::tessellate(patches, density)?;
    let mut view = view_from_tessellation(title, &t);
    view.nets = Some(control_nets(patches));
    Ok(view)
}

/// A view of a mesh as a file gave it ([`meshio::RawMesh`]): polygons fan-triangulated around
/// their first corner; the file's normals, or else area-weighted face normals summed at the
/// vertices (`+z` at a vertex no face with area touches); `K`, `H`, `k1`, `k2` when the file
/// carries curvature ([`meshio::RawMesh::curvature`], the exported convention); the polygons'
/// edges as the data mesh.
pub fn view_from_raw(title: impl Into<String>, raw: &meshio::RawMesh) -> Result<View, ViewError> {
    let title = title.into();
    let positions: Vec<Point> = raw.positions.iter().map(|&p| to_f32(p)).collect();
    let mut indices = Vec::new();
    let mut edges = Vec::new();
    for poly in raw.polygons.iter() {
        for k in 2..poly.len() {
            indices.push([poly[0] as u32, poly[k - 1] as u32, poly[k] as u32]);
        }
        for k in 0..poly.len() {
            edges.push([poly[k] as u32, poly[(k + 1) % poly.len()] as u32]);
        }
    }
    let normals: Vec<Point> = match &raw.normals {
        Some(n) if n.iter().all(|v| v.norm() > 0.0) => n
            .iter()
            .map(|v| [v.x as f32, v.y as f32, v.z as f32])
            .collect(),
        _ => {
            let mut sum = vec![nalgebra::Vector3::<f64>::zeros(); raw.positions.len()];
            for t in &indices {
                let [a, b, c] = t.map(|i| raw.positions.get(i as usize).copied());
                if let (Some(a), Some(b), Some(c)) = (a, b, c) {
                    // Twice the area times the unit normal: large faces weigh more.
                    let n = (b - a).cross(&(c - a));
                    for &i in t {
                        if let Some(s) = sum.get_mut(i as usize) {
                            *s += n;
                        }
                    }
                }
            }
            sum.iter()
                .map(|s| {
                    let n = s.try_normalize(0.0).unwrap_or_else(nalgebra::Vector3::z);
                    [n.x as f32, n.y as f32, n.z as f32]
                })
                .collect()
        }
    };
    let mut scalars = Vec::new();
    if let Some(c) = &raw.curvature {
        if c.gaussian.len() == positions.len() && c.mean.len() == positions.len() {
            let root = |k: f64, h: f64| (h * h - k).max(0.0).sqrt();
            let f = |v: &[f64]| v.iter().map(|&x| x as f32).collect::<Vec<f32>>();
            let k1: Vec<f64> = c
                .gaussian
                .iter()
                .zip(&c.mean)
                .map(|(&k, &h)| h + root(k, h))
                .collect();
            let k2: Vec<f64> = c
                .gaussian
                .iter()
                .zip(&c.mean)
                .map(|(&k, &h)| h - root(k, h))
                .collect();
            scalars = vec![
                ("K".to_string(), f(&c.gaussian)),
                ("H".to_string(), f(&c.mean)),
                ("k1".to_string(), f(&k1)),
                ("k2".to_string(), f(&k2)),
            ];
        }
    }
    let mut seen = std::collections::HashSet::new();
    let data_mesh = edges
        .iter()
        .filter(|[a, b]| seen.insert((*a.min(b), *a.max(b))))
        .filter_map(|[a, b]| Some([*positions.get(*a as usize)?, *positions.get(*b as usize)?]))
        .collect();
    let view = View {
        title,
        mesh: TriangleMesh {
            positions,
            normals,
            indices,
        },
        scalars,
        data_mesh: Some(data_mesh),
        ..View::default()
    };
    check(&view)?;
    Ok(view)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        // RFC 4648 §10.
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, coded) in cases {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
    }

    #[test]
    fn template_has_every_placeholder_once_in_order() {
        let mut at = 0;
        for m in PLACEHOLDERS {
            assert_eq!(PAGE_HTML.matches(m).count(), 1, "{m}");
            let pos = PAGE_HTML.find(m).unwrap_or(0);
            assert!(pos >= at, "{m} out of order");
            at = pos;
        }
        // Inlined scripts must not close their element early.
        assert!(!THREE_JS.contains("</script"));
        assert!(!PAGE_JS.contains("</script"));
    }

    fn one_triangle() -> View {
        View::new(
            "t",
            TriangleMesh {
                positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
                normals: vec![[0.0, 0.0, 1.0]; 3],
                indices: vec![[0, 1, 2]],
            },
        )
    }

    #[test]
    fn bad_views_are_refused_with_the_reason() {
        let mut page = Page::new("p");
        let mut v = one_triangle();
        v.mesh.indices[0][2] = 3;
        assert!(matches!(
            page.add_view(v),
            Err(ViewError::Index { index: 3, .. })
        ));
        let mut v = one_triangle();
        v.scalars.push(("K".into(), vec![0.0; 2]));
        assert!(matches!(
            page.add_view(v),
            Err(ViewError::Length { got: 2, .. })
        ));
        let mut v = one_triangle();
        v.scalars.push(("zebra".into(), vec![0.0; 3]));
        assert!(matches!(page.add_view(v), Err(ViewError::Name { .. })));
        let mut v = one_triangle();
        v.mesh.positions[1][2] = f32::NAN;
        assert!(matches!(
            page.add_view(v),
            Err(ViewError::NotFinite { at: 1, .. })
        ));
        let mut v = one_triangle();
        v.mesh.normals[2] = [0.0; 3];
        assert!(matches!(
            page.add_view(v),
            Err(ViewError::ZeroNormal { vertex: 2, .. })
        ));
        assert!(page.add_view(one_triangle()).is_ok());
        assert_eq!(page.views().len(), 1);
    }

    #[test]
    fn the_page_loads_nothing_from_outside() {
        let mut page = Page::new("p");
        assert!(page.add_view(one_triangle()).is_ok());
        let html = page.to_html().to_ascii_lowercase();
        // No external script, style, image or frame: everything is inline.
        for needle in [
            "<script src",
            "<link",
            "<img",
            "<iframe",
            "import(",
            "@import",
        ] {
            assert!(!html.contains(needle), "the page has {needle}");
        }
        assert!(!PAGE_JS.contains("fetch(") && !PAGE_JS.contains("http"));
    }

    #[test]
    fn titles_cannot_break_out_of_the_page() {
        let mut page = Page::new("<b>a</script>");
        let mut v = one_triangle();
        v.title = "</script><script>alert(1)</script>".into();
        assert!(page.add_view(v).is_ok());
        let html = page.to_html();
        assert!(html.contains("<title>&lt;b&gt;a&lt;/script&gt;</title>"));
        assert!(!page.data_json().contains("</script"));
        // A file named `<!--<script>.obj` (issue 43): no `<` at all in the data block, and
        // the JSON still reads back the same names.
        let mut page = Page::new("<!--<script>.obj");
        let mut v = one_triangle();
        v.title = "<!--<script>.obj".into();
        assert!(page.add_view(v).is_ok());
        let data = page.data_json();
        assert!(!data.contains('<'));
        let back: serde_json::Value = serde_json::from_str(&data).unwrap();
        assert_eq!(back["title"], "<!--<script>.obj");
    }

    #[test]
    fn range_is_the_quantile_of_absolute_values() {
        let mut page = Page::new("p");
        let mut v = one_triangle();
        v.scalars.push(("K".into(), vec![-2.0, 1.0, 0.5]));
        v.distance = Some(vec![0.0; 3]);
        assert!(page.add_view(v).is_ok());
        let r = ranges(page.views());
        // Three values: the 0.99 quantile rounds to the largest, |−2| = 2.
        assert_eq!(r["K"]["range"], 2.0);
        assert_eq!(r["K"]["max"], 2.0);
        // All zero: the range falls back to 1 so the map is defined.
        assert_eq!(r["distance"]["range"], 1.0);
    }

    #[test]
    fn one_view_with_lumps_does_not_set_the_others_scale() {
        let mut page = Page::new("p");
        for k in [[1.0, -2.0, 0.5], [3.0, 1.0, -1.5], [8000.0, -6000.0, 2.0]] {
            let mut v = one_triangle();
            v.scalars.push(("K".into(), k.to_vec()));
            assert!(page.add_view(v).is_ok());
        }
        let r = ranges(page.views());
        // The views' own ranges are 2, 3 and 8 000: the median, 3, is the page's.
        assert_eq!(r["K"]["range"], 3.0);
        assert_eq!(r["K"]["max"], 8000.0);
    }

    #[test]
    fn wireframe_lists_each_edge_once() {
        let p = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
        let w = wireframe(&p, &[[0, 1, 2], [1, 3, 2]]);
        assert_eq!(w.len(), 5);
    }

    #[test]
    fn a_flat_cubic_patch_gives_its_net_boundary_and_zero_curvature() {
        // The cubic net of the triangle (0,0,0), (1,0,0), (0,1,0): points at (j, k)/3.
        let patch = BezierTriangle::from_fn(3, |_i, j, k| {
            nalgebra::Point3::new(j as f64 / 3.0, k as f64 / 3.0, 0.0)
        });
        let s = 4;
        let view = view_from_patches("flat", &[patch], s).unwrap_or_default();
        // (s+1)(s+2)/2 samples, s² triangles; the net's n(n+1)/2 = 6 upward triangles hold
        // its 18 edges; the border has 3s edges and no edge lies between two patches.
        assert_eq!(view.mesh.positions.len(), 15);
        assert_eq!(view.mesh.indices.len(), 16);
        assert_eq!(view.nets.as_ref().map(Vec::len), Some(18));
        assert_eq!(view.boundaries.as_ref().map(Vec::len), Some(3 * s));
        for (name, values) in &view.scalars {
            assert!(values.iter().all(|v| v.abs() < 1e-12), "{name} on a plane");
        }
    }

    #[test]
    fn a_raw_quad_is_fanned_with_area_normals_and_its_edges_as_data_mesh() {
        let p = [
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let mut raw = meshio::RawMesh::from_triangles(
            p.iter()
                .map(|q| nalgebra::Point3::new(q[0], q[1], q[2]))
                .collect(),
            &[],
        );
        raw.polygons.push(&[0, 1, 2, 3]);
        let view = view_from_raw("quad", &raw).unwrap_or_default();
        assert_eq!(view.mesh.indices, vec![[0, 1, 2], [0, 2, 3]]);
        assert!(view.mesh.normals.iter().all(|n| n == &[0.0, 0.0, 1.0]));
        // Four sides, not the fan's diagonal; no curvature in the file, no scalar modes.
        assert_eq!(view.data_mesh.as_ref().map(Vec::len), Some(4));
        assert!(view.scalars.is_empty());
    }
}
